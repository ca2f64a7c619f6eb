//! The web app: an axum server over the library, same JSON as `close analyze --json`.
//!
//! Routes: `GET /` (the app in `web/`, embedded), `GET /healthz`, `POST /api/analyze`,
//! `GET /api/samples` (one typed row per built-in or dataset sample), `GET /api/samples/{id}`
//! (either kind), `GET /api/images/{key}/{picture}.png` (`?format=svg`: the same drawing as SVG),
//! `POST /api/interpolate`, `POST /api/disk` (the dGLI disk PNG of any border state; `?format=svg`: SVG),
//! `POST /api/disk/cells`, `GET /api/readout/{key}` and `GET /api/cells.png` (a disk's
//! values and which cell each pixel of its picture shows, for reading values off the
//! pictures: [`close_render::readout`]),
//! `POST /api/plan`, `GET /api/samples/{id}/recording.rrd` (a Rerun recording; with the
//! `rerun` feature, else a 404 saying so). Every error is a 4xx (or, for a server fault,
//! 5xx) with `{"error": "..."}`. Analyses, renders and large answers run on CPU workers
//! (one light worker per core, a heavy lane of one fewer for jobs of many dGLI cells), never
//! on the async threads. Results are cached by content: an analysis under the hash of the
//! request body and frame range (a built-in sample under its id), a PNG under (analysis,
//! picture, clamped size); both caches are bounded. An analysis's drawing (the analysis
//! without its JSON answer) is kept in a third, longer cache, so an answer's image URLs
//! still draw once the analysis cache has let the analysis go.
//!
//! Bounded work: each CPU job is estimated first (a [`close_core::budget::Budget`]: analysed frames × N² dGLI
//! cells, interpolated points; 413 over the limit) and carries a [`close_core::budget::Deadline`] that is
//! cancelled when its request is dropped (the 408 of the time-out, a closed connection), so
//! its loops stop and its worker permit is freed. Bodies in flight share one byte budget;
//! connections are capped and closed when their headers do not arrive in time (which also
//! closes idle keep-alive connections); `Host` and `Origin` are checked ([`guard`]).
//!
//! ```no_run
//! // Tests drive the router without a socket:
//! let app = close_server::app(close_server::AppState::new());
//! ```

pub mod answer;
mod assets;
mod datasets;
mod error;
mod extract;
pub mod guard;
mod listing;
mod routes;
mod socket;
mod state;
mod uploads;
mod workers;

use std::future::Future;
use std::net::SocketAddr;
use std::sync::Arc;
use std::time::Duration;

use axum::body::Bytes;
use axum::extract::DefaultBodyLimit;
use axum::http::{header, HeaderValue, Method, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::Router;
use hyper_util::rt::{TokioIo, TokioTimer};
use tokio::net::TcpListener;
use tower::{ServiceBuilder, ServiceExt};
use tower_http::compression::predicate::{DefaultPredicate, Predicate};
use tower_http::compression::CompressionLayer;
use tower_http::cors::{AllowOrigin, CorsLayer};
use tower_http::limit::RequestBodyLimitLayer;
use tower_http::timeout::TimeoutLayer;
use tower_http::trace::TraceLayer;

pub use error::ApiError;
pub use extract::{AppJson, AppPath, AppQuery};
pub use state::{Analyzed, AppState, Config, Drawing};

use guard::{AnswerWatch, Doors, ServedAt};
use socket::Socket;

/// Give every error response that is not JSON yet (a layer's or axum's own: 405, 408, 413…)
/// the `{"error": "..."}` body.
async fn json_errors<B>(response: Response<B>) -> Response
where
    B: axum::body::HttpBody<Data = Bytes> + Send + 'static,
    B::Error: Into<axum::BoxError>,
{
    let status = response.status();
    let is_json = response
        .headers()
        .get(header::CONTENT_TYPE)
        .is_some_and(|t| t.as_bytes().starts_with(b"application/json"));
    if !(status.is_client_error() || status.is_server_error()) || is_json {
        return response.map(axum::body::Body::new);
    }
    let body = axum::body::to_bytes(axum::body::Body::new(response.into_body()), 4096)
        .await
        .unwrap_or_default();
    let text = String::from_utf8_lossy(&body).trim().to_string();
    let reason = status.canonical_reason().unwrap_or("request failed").to_lowercase();
    let message = match status {
        StatusCode::PAYLOAD_TOO_LARGE => {
            format!("request body too large: {}", if text.is_empty() { reason } else { text })
        }
        _ if text.is_empty() => reason,
        _ => text,
    };
    ApiError::Rejected(status, message).into_response()
}

/// Largest answer that is gzipped. The compression layer runs on the async threads, where a
/// 90 MB interpolation took seconds and stalled every other request (`/healthz` too); an
/// answer up to 1 MiB takes milliseconds. Larger answers, which only the interpolation and
/// a huge analysis give, are sent as they are.
const COMPRESS_AT_MOST: u64 = 1 << 20;

/// Compress an answer whose size is known and at most [`COMPRESS_AT_MOST`].
#[derive(Debug, Clone, Copy)]
struct SmallAnswers;

impl Predicate for SmallAnswers {
    fn should_compress<B: axum::body::HttpBody>(&self, response: &Response<B>) -> bool {
        response.body().size_hint().exact().is_some_and(|bytes| bytes <= COMPRESS_AT_MOST)
    }
}

/// CORS for the `--cors` origins only; none (the browser's same-origin rule) by default.
fn cors(origins: &[String]) -> Option<CorsLayer> {
    let origins: Vec<HeaderValue> = origins
        .iter()
        .filter_map(|o| HeaderValue::from_str(o.trim_end_matches('/')).ok())
        .collect();
    (!origins.is_empty()).then(|| {
        CorsLayer::new()
            .allow_origin(AllowOrigin::list(origins))
            .allow_methods([Method::GET, Method::POST])
            .allow_headers([header::CONTENT_TYPE])
    })
}

/// The router of the web app.
pub fn app(state: AppState) -> Router {
    let config = state.config().clone();
    let doors = Arc::new(Doors {
        hosts: config.allowed_hosts.clone(),
        origins: config.cors_origins.clone(),
    });
    let uploads = state.0.memory.clone();
    let body_rate = guard::BodyRate {
        grace: config.header_timeout,
        connections: state.0.connections.clone(),
        max_connections: config.max_connections.max(1),
        timeout: config.timeout,
    };
    let small_bodies = DefaultBodyLimit::max(config.json_body_limit);
    Router::new()
        .route("/", get(assets::index))
        .route("/assets/{file}", get(assets::asset))
        .route("/healthz", get(routes::healthz))
        .route("/api/analyze", post(routes::analyze))
        .route("/api/analyses/{key}", get(routes::analysis_by_key))
        .route("/api/samples", get(datasets::samples))
        .route("/api/samples/{id}", get(routes::sample))
        .route("/api/samples/{id}/recording.rrd", get(routes::recording))
        .route("/api/images/{key}/{file}", get(routes::image))
        .route("/api/interpolate", post(routes::interpolate).layer(small_bodies))
        .route("/api/disk", post(routes::disk).layer(small_bodies))
        .route("/api/disk/cells", post(routes::disk_cells).layer(small_bodies))
        .route("/api/readout/{key}", get(routes::readout))
        .route("/api/cells.png", get(routes::cell_picture))
        .route("/api/plan", post(routes::plan).layer(small_bodies))
        .route("/api/verify", post(routes::verify).layer(small_bodies))
        .route("/api/distance", post(routes::distance).layer(small_bodies))
        .fallback(routes::not_found)
        .layer(DefaultBodyLimit::max(config.body_limit))
        .layer(
            ServiceBuilder::new()
                .layer(TraceLayer::new_for_http())
                .option_layer(cors(&config.cors_origins))
                .layer(
                    CompressionLayer::new()
                        .compress_when(DefaultPredicate::new().and(SmallAnswers)),
                )
                .layer(axum::middleware::map_response(json_errors))
                .layer(axum::middleware::from_fn_with_state(doors, guard::doors))
                .layer(TimeoutLayer::with_status_code(StatusCode::REQUEST_TIMEOUT, config.timeout))
                .layer(axum::middleware::from_fn_with_state(uploads, guard::upload_budget))
                .layer(axum::middleware::from_fn_with_state(body_rate, guard::body_rate))
                .layer(RequestBodyLimitLayer::new(config.body_limit)),
        )
        .with_state(state)
}

/// Serve the app on `addr` until Ctrl-C.
pub async fn serve(addr: SocketAddr, state: AppState) -> std::io::Result<()> {
    let listener = TcpListener::bind(addr).await?;
    println!("CloSE web app: http://{}/  (Ctrl-C to stop)", listener.local_addr()?);
    serve_with(listener, state, async {
        // If the signal cannot be listened to, run until killed.
        if tokio::signal::ctrl_c().await.is_err() {
            std::future::pending::<()>().await;
        }
    })
    .await
}

/// Serve the app on `listener` until `shutdown` completes, then let open requests finish.
///
/// At most [`Config::max_connections`] connections are served at once (the others wait in
/// the listen queue); a connection that does not send a request's headers within
/// [`Config::header_timeout`], first or between keep-alive requests, is closed; one whose
/// answer is not read for [`Config::write_timeout`] is dropped (for
/// [`guard::CROWDED_GRACE`] when others wait for the memory the answer holds). hyper's own
/// answers to heads it cannot read get the JSON error body too (the server's socket module).
pub async fn serve_with(
    listener: TcpListener,
    state: AppState,
    shutdown: impl Future<Output = ()>,
) -> std::io::Result<()> {
    let config = state.config().clone();
    let slots = state.0.connections.clone();
    let app = app(state);
    let mut http = hyper::server::conn::http1::Builder::new();
    http.timer(TokioTimer::new())
        .header_read_timeout(config.header_timeout)
        .max_buf_size(socket::MAX_HEAD)
        .max_headers(socket::MAX_HEADERS);
    let graceful = hyper_util::server::graceful::GracefulShutdown::new();
    tokio::pin!(shutdown);
    loop {
        let slot = tokio::select! {
            slot = slots.clone().acquire_owned() => slot.map_err(std::io::Error::other)?,
            () = &mut shutdown => break,
        };
        let stream = tokio::select! {
            accepted = listener.accept() => match accepted {
                Ok((stream, _)) => stream,
                Err(e) => {
                    // Out of descriptors and the like: wait for connections to close.
                    tracing::warn!(error = %e, "accept failed");
                    tokio::time::sleep(Duration::from_millis(50)).await;
                    continue;
                }
            },
            () = &mut shutdown => break,
        };
        let served_at = stream.local_addr().ok().map(ServedAt);
        // Answers are small and written at once: do not wait for more to send.
        let _ = stream.set_nodelay(true);
        // What the connection's answer holds of the budget, for its socket to see.
        let watch = AnswerWatch::default();
        let answers = watch.clone();
        let service = app.clone().map_request(
            move |mut request: axum::http::Request<hyper::body::Incoming>| {
                if let Some(at) = served_at {
                    request.extensions_mut().insert(at);
                }
                request.extensions_mut().insert(answers.clone());
                request
            },
        );
        let connection = graceful.watch(http.serve_connection(
            TokioIo::new(Socket::new(stream, config.write_timeout, watch)),
            hyper_util::service::TowerToHyperService::new(service),
        ));
        tokio::spawn(async move {
            let _slot = slot;
            if let Err(e) = connection.await {
                tracing::debug!(error = %e, "connection closed");
            }
        });
    }
    // Open requests may finish, within one request time-out.
    let _ = tokio::time::timeout(config.timeout, graceful.shutdown()).await;
    Ok(())
}

/// Why [`run`] could not serve.
#[derive(Debug, thiserror::Error)]
pub enum ServeError {
    /// The address is not a socket address: the caller's mistake.
    #[error("--addr {addr}: {source} (expected e.g. 127.0.0.1:8080)")]
    Address { addr: String, source: std::net::AddrParseError },
    /// The runtime could not start.
    #[error("cannot start the server: {0}")]
    Runtime(std::io::Error),
    /// The address could not be bound (in use, not ours), or accepting failed.
    #[error("cannot serve on {addr}: {source}")]
    Serve { addr: SocketAddr, source: std::io::Error },
}

/// `close serve`: log to stderr (`RUST_LOG` overrides), start a runtime, serve.
pub fn run(addr: &str, config: Config) -> Result<(), ServeError> {
    let addr: SocketAddr =
        addr.parse().map_err(|source| ServeError::Address { addr: addr.to_string(), source })?;
    let filter = tracing_subscriber::EnvFilter::try_from_default_env()
        .unwrap_or_else(|_| "close=info,tower_http=info".into());
    // Already initialised (e.g. by an embedding program) is fine.
    let _ =
        tracing_subscriber::fmt().with_env_filter(filter).with_writer(std::io::stderr).try_init();
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .map_err(ServeError::Runtime)?;
    runtime
        .block_on(serve(addr, AppState::with_config(config)))
        .map_err(|source| ServeError::Serve { addr, source })
}
