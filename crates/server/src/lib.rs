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
//! Bounded work: each CPU job is estimated first (a [`Budget`]: analysed frames × N² dGLI
//! cells, interpolated points; 413 over the limit) and carries a [`Deadline`] that is
//! cancelled when its request is dropped (the 408 of the time-out, a closed connection), so
//! its loops stop and its worker permit is freed. Bodies in flight share one byte budget;
//! connections are capped and closed when their headers do not arrive in time (which also
//! closes idle keep-alive connections); `Host` and `Origin` are checked ([`guard`]).
//!
//! ```no_run
//! // Tests drive the router without a socket:
//! let app = close_server::app(close_server::AppState::new());
//! ```

mod assets;
mod datasets;
mod error;
mod extract;
pub mod guard;
mod routes;
mod socket;
mod uploads;
mod workers;

use std::future::Future;
use std::net::SocketAddr;
use std::sync::{Arc, Mutex, MutexGuard, OnceLock};
use std::time::Duration;

use axum::body::Bytes;
use axum::extract::DefaultBodyLimit;
use axum::http::{header, HeaderValue, Method, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::Router;
use hyper_util::rt::{TokioIo, TokioTimer};
use tokio::net::TcpListener;
use tokio::sync::Semaphore;
use tower::{ServiceBuilder, ServiceExt};
use tower_http::compression::predicate::{DefaultPredicate, Predicate};
use tower_http::compression::CompressionLayer;
use tower_http::cors::{AllowOrigin, CorsLayer};
use tower_http::limit::RequestBodyLimitLayer;
use tower_http::timeout::TimeoutLayer;
use tower_http::trace::TraceLayer;

pub use error::ApiError;
pub use extract::{AppJson, AppPath, AppQuery};
pub use routes::{Analyzed, Drawing};

use close_core::budget::{Budget, Deadline};
use close_io::cache::Lru;
use close_io::dataset::{BuiltinSample, Dataset};
use guard::{AnswerWatch, Doors, ServedAt, UploadBudget};
use socket::Socket;
use workers::Workers;

/// Limits and sizes of a server.
#[derive(Debug, Clone)]
pub struct Config {
    /// Largest request body, in bytes (uploads to `/api/analyze`).
    pub body_limit: usize,
    /// Largest JSON body of the other POST routes (a border, a fold, a goal).
    pub json_body_limit: usize,
    /// Bytes of request bodies and unwritten answers held at once, across all requests.
    pub upload_budget: usize,
    /// Longest a request may take; its CPU job is stopped then too.
    pub timeout: Duration,
    /// Longest a connection may take to send a request's headers, and may stay idle
    /// between requests.
    pub header_timeout: Duration,
    /// Longest an answer's writing may make no progress (its client reads nothing) before
    /// the connection is dropped.
    pub write_timeout: Duration,
    /// Connections open at once; more wait to be accepted.
    pub max_connections: usize,
    /// What one analysis or interpolation may cost.
    pub budget: Budget,
    /// Analyses kept in memory, and their largest total size in bytes.
    pub cached_analyses: usize,
    pub analysis_cache_bytes: usize,
    /// Drawings (an analysis without its JSON answer: what its pictures and plans need)
    /// kept in memory, and their largest total size in bytes. They outlive the analyses
    /// cache, so an answer's image URLs stay reachable under a flood of new analyses.
    pub cached_drawings: usize,
    pub drawing_cache_bytes: usize,
    /// PNGs and recordings kept in memory, and their largest total size in bytes.
    pub cached_images: usize,
    pub image_cache_bytes: usize,
    /// Analyses and renders running at once.
    pub workers: usize,
    /// Host names served besides loopback names and the address listened on.
    pub allowed_hosts: Vec<String>,
    /// Origins whose pages may call the API (CORS); none by default.
    pub cors_origins: Vec<String>,
    /// The user's own datasets (`--dataset`): folders of samples or VR-Folding stores.
    pub datasets: Vec<std::path::PathBuf>,
    /// Where uploads are kept on disk (`--data-dir`), so their links outlive a restart;
    /// none: uploads live in the caches alone.
    pub data_dir: Option<std::path::PathBuf>,
    /// Uploads kept in the data folder at most, and their largest total size in bytes; past
    /// either, the oldest go first.
    pub kept_uploads: usize,
    pub kept_upload_bytes: u64,
}

impl Default for Config {
    fn default() -> Self {
        Config {
            body_limit: 64 * 1024 * 1024,
            json_body_limit: 8 * 1024 * 1024,
            upload_budget: 256 * 1024 * 1024,
            timeout: Duration::from_secs(30),
            header_timeout: Duration::from_secs(10),
            write_timeout: Duration::from_secs(30),
            max_connections: 256,
            budget: Budget::SERVER,
            cached_analyses: 256,
            analysis_cache_bytes: 256 * 1024 * 1024,
            cached_drawings: 4096,
            drawing_cache_bytes: 64 * 1024 * 1024,
            cached_images: 512,
            image_cache_bytes: 64 * 1024 * 1024,
            workers: std::thread::available_parallelism().map_or(2, |n| n.get()),
            allowed_hosts: Vec::new(),
            cors_origins: Vec::new(),
            datasets: Vec::new(),
            data_dir: None,
            kept_uploads: 1000,
            kept_upload_bytes: 1 << 30,
        }
    }
}

struct Inner {
    config: Config,
    analyses: Mutex<Lru<Arc<Analyzed>>>,
    drawings: Mutex<Lru<Arc<Drawing>>>,
    images: Mutex<Lru<Bytes>>,
    /// Light jobs: one worker per core, each on one thread.
    light: Workers,
    /// Heavy jobs: one fewer than the cores (at least one), so light jobs always find a
    /// worker; each on as many threads as cores (the OS shares them with light jobs).
    heavy: Workers,
    dataset: Dataset,
    /// Bytes of bodies and answers in flight ([`guard::upload_budget`]).
    memory: Arc<UploadBudget>,
    /// The rows of `GET /api/samples`, built once: the datasets never change.
    sample_list: OnceLock<Arc<datasets::Listing>>,
    /// The user's datasets, listed at start.
    catalog: Arc<close_io::catalog::Catalog>,
    /// The uploads kept on disk, with `--data-dir`.
    uploads: Option<uploads::Uploads>,
    /// Connection slots: [`Config::max_connections`] permits, one held by each open
    /// connection ([`serve_with`]); their crowding shortens a body's grace ([`guard::BodyRate`]).
    connections: Arc<Semaphore>,
}

/// What every request shares: the configuration, the dataset, the caches and the worker
/// permits.
#[derive(Clone)]
pub struct AppState(Arc<Inner>);

/// Jobs of more dGLI cells than this (e.g. two frames of 1400 vertices) are heavy.
const HEAVY_CELLS: u64 = 4_000_000;

/// Which permits a CPU job takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Lane {
    Light,
    Heavy,
}

impl Lane {
    /// The lane of a job that computes `cells` dGLI cells.
    fn of(cells: u64) -> Lane {
        if cells > HEAVY_CELLS {
            Lane::Heavy
        } else {
            Lane::Light
        }
    }
}

/// A poisoned lock only means a worker panicked mid-insert; the map itself is still valid.
fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

/// Cancels a job's deadline when the request that waits for it is dropped (or done).
struct CancelOnDrop(Deadline);

impl Drop for CancelOnDrop {
    fn drop(&mut self) {
        self.0.cancel();
    }
}

impl AppState {
    /// A server with the default limits and the built-in dataset.
    pub fn new() -> Self {
        Self::with_config(Config::default())
    }

    pub fn with_config(config: Config) -> Self {
        AppState(Arc::new(Inner {
            dataset: Dataset::builtin(),
            analyses: Mutex::new(Lru::new(config.cached_analyses, config.analysis_cache_bytes)),
            drawings: Mutex::new(Lru::new(config.cached_drawings, config.drawing_cache_bytes)),
            images: Mutex::new(Lru::new(config.cached_images, config.image_cache_bytes)),
            light: Workers::new("light", config.workers, 1),
            heavy: Workers::new("heavy", config.workers.saturating_sub(1), config.workers),
            sample_list: OnceLock::new(),
            memory: Arc::new(UploadBudget::new(
                config.upload_budget,
                config.body_limit,
                config.json_body_limit,
            )),
            catalog: Arc::new(close_io::catalog::Catalog::open(&config.datasets)),
            connections: Arc::new(Semaphore::new(config.max_connections.max(1))),
            uploads: config.data_dir.as_deref().map(|dir| {
                uploads::Uploads::new(dir, config.kept_uploads, config.kept_upload_bytes)
            }),
            config,
        }))
    }

    pub fn config(&self) -> &Config {
        &self.0.config
    }

    /// The user's datasets.
    pub fn catalog(&self) -> &Arc<close_io::catalog::Catalog> {
        &self.0.catalog
    }

    /// The built-in dataset.
    pub fn dataset(&self) -> &Dataset {
        &self.0.dataset
    }

    /// The built-in samples.
    fn entries(&self) -> &[BuiltinSample] {
        self.0.dataset.entries()
    }

    /// The built-in sample `id`.
    fn entry(&self, id: &str) -> Option<&BuiltinSample> {
        self.0.dataset.get(id)
    }

    /// Bytes of the memory budget not held by a request body or an unwritten answer now.
    pub fn free_budget(&self) -> usize {
        self.0.memory.available()
    }

    /// Workers free now, light and heavy (all of them when no job runs).
    pub fn idle_workers(&self) -> usize {
        self.0.light.idle() + self.0.heavy.idle()
    }

    /// Workers of this server, light and heavy.
    pub fn workers(&self) -> usize {
        self.0.light.count() + self.0.heavy.count()
    }

    /// Connections open now (each holds a connection slot).
    pub fn open_connections(&self) -> usize {
        self.config().max_connections.max(1) - self.0.connections.available_permits()
    }

    /// CPU jobs given to a worker so far, light and heavy.
    pub fn worker_jobs(&self) -> usize {
        self.0.light.started() + self.0.heavy.started()
    }

    /// CPU jobs that stopped at their deadline (a time-out, a request gone away) so far.
    pub fn cancelled_jobs(&self) -> usize {
        self.0.light.cancelled() + self.0.heavy.cancelled()
    }

    /// Run CPU-heavy `work` on a worker of `lane` once one is free. The work gets a deadline
    /// of the request time-out, cancelled as soon as this future is dropped, so a request
    /// that timed out or went away stops its work and frees the worker.
    async fn run_cpu<T: Send + 'static>(
        &self,
        lane: Lane,
        work: impl FnOnce(&Deadline) -> Result<T, ApiError> + Send + 'static,
    ) -> Result<T, ApiError> {
        let deadline = Deadline::after(self.config().timeout);
        let _cancel = CancelOnDrop(deadline.clone());
        let workers = match lane {
            Lane::Light => &self.0.light,
            Lane::Heavy => &self.0.heavy,
        };
        workers.run(deadline, work).await
    }

    /// The uploads kept on disk, with `--data-dir`.
    fn uploads(&self) -> Option<&uploads::Uploads> {
        self.0.uploads.as_ref()
    }

    /// Keep upload `key` (its `sample`, the `frames` analysed) on disk, with `--data-dir`.
    /// An upload that cannot be kept is still analysed: the failure is logged.
    fn keep_upload(
        &self,
        key: &str,
        frames: close_core::FrameRange,
        sample: close_io::formats::Sample,
    ) {
        if let Some(uploads) = self.uploads() {
            let stored = uploads::Stored { start: frames.start, end: frames.end, sample };
            if let Err(e) = uploads.save(key, &stored) {
                tracing::warn!("could not keep upload {key} in {}: {e}", uploads.dir().display());
            }
        }
    }

    /// Pictures (and recordings) in the cache now.
    pub fn cached_pictures(&self) -> usize {
        lock(&self.0.images).len()
    }

    fn cached_analysis(&self, key: &str) -> Option<Arc<Analyzed>> {
        lock(&self.0.analyses).get(key)
    }

    /// What the pictures of analysis `key` are drawn from: its cached analysis, or, once
    /// that was evicted, the drawing kept after it.
    fn drawing(&self, key: &str) -> Option<Arc<Drawing>> {
        match self.cached_analysis(key) {
            Some(hit) => Some(hit.drawing.clone()),
            None => lock(&self.0.drawings).get(key),
        }
    }

    /// The cached file (a PNG, a recording) under `key`, or `render` it (off the runtime,
    /// in the lane of `cells` dGLI cells) and cache it.
    async fn cached_bytes(
        &self,
        key: String,
        cells: u64,
        render: impl FnOnce(&Deadline) -> Result<Vec<u8>, ApiError> + Send + 'static,
    ) -> Result<Bytes, ApiError> {
        if let Some(hit) = lock(&self.0.images).get(&key) {
            return Ok(hit);
        }
        let png = Bytes::from(self.run_cpu(Lane::of(cells), render).await?);
        lock(&self.0.images).insert(key, png.clone(), png.len());
        Ok(png)
    }

    /// Cache `analyzed`, and its drawing apart: the drawing is shared, not copied, while
    /// both hold it, and each cache counts its full weight (an over-count, never an under-).
    fn cache_analysis(&self, analyzed: &Arc<Analyzed>) {
        lock(&self.0.analyses).insert(analyzed.key.clone(), analyzed.clone(), analyzed.bytes());
        lock(&self.0.drawings).insert(
            analyzed.key.clone(),
            analyzed.drawing.clone(),
            analyzed.drawing.bytes,
        );
    }
}

impl Default for AppState {
    fn default() -> Self {
        Self::new()
    }
}

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
/// [`guard::CROWDED_GRACE`] when others wait for the memory the answer holds). hyper's own answers to heads
/// it cannot read get the JSON error body too ([`socket`]).
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
