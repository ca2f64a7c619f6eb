//! The web app: an axum server over the library (SPEC §4), same JSON as `close analyze --json`.
//!
//! Routes: `GET /` (the app in `web/`, embedded), `GET /healthz`, `POST /api/analyze`,
//! `GET /api/samples`, `GET /api/samples/{id}`, `GET /api/images/{key}/{picture}.png`,
//! `POST /api/interpolate`, `POST /api/disk` (the dGLI disk PNG of any border state),
//! `POST /api/plan`, `GET /api/samples/{id}/recording.rrd` (a Rerun recording; with the
//! `rerun` feature, else a 404 saying so). Every error is a 4xx (or, for a server fault,
//! 5xx) with `{"error": "..."}`. Analyses and renders run on blocking threads, at most one
//! per core at a time, and are cached by content: an analysis under the hash of the request
//! body and frame range (a built-in sample under its id), a PNG under (analysis, picture,
//! size); both caches are bounded.
//!
//! ```no_run
//! // Tests drive the router without a socket:
//! let app = close::server::app(close::server::AppState::new());
//! ```

mod assets;
pub mod cache;
mod datasets;
mod error;
mod routes;

use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::Duration;

use axum::body::Bytes;
use axum::extract::DefaultBodyLimit;
use axum::http::{header, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::Router;
use tokio::sync::Semaphore;
use tower::ServiceBuilder;
use tower_http::compression::CompressionLayer;
use tower_http::limit::RequestBodyLimitLayer;
use tower_http::timeout::TimeoutLayer;
use tower_http::trace::TraceLayer;

pub use error::ApiError;
pub use routes::Analyzed;

use cache::Lru;
use crate::dataset::Dataset;

/// Limits and sizes of a server.
#[derive(Debug, Clone)]
pub struct Config {
    /// Largest request body, in bytes.
    pub body_limit: usize,
    /// Longest a request may take.
    pub timeout: Duration,
    /// Analyses kept in memory, and their largest total size in bytes.
    pub cached_analyses: usize,
    pub analysis_cache_bytes: usize,
    /// PNGs and recordings kept in memory, and their largest total size in bytes.
    pub cached_images: usize,
    pub image_cache_bytes: usize,
    /// Analyses and renders running at once.
    pub workers: usize,
    /// The user's own datasets (`--dataset`): folders of samples or VR-Folding stores.
    pub datasets: Vec<PathBuf>,
}

impl Default for Config {
    fn default() -> Self {
        Config {
            body_limit: 64 * 1024 * 1024,
            timeout: Duration::from_secs(30),
            cached_analyses: 256,
            analysis_cache_bytes: 256 * 1024 * 1024,
            cached_images: 512,
            image_cache_bytes: 64 * 1024 * 1024,
            workers: std::thread::available_parallelism().map_or(2, |n| n.get()),
            datasets: Vec::new(),
        }
    }
}

struct Inner {
    config: Config,
    analyses: Mutex<Lru<Arc<Analyzed>>>,
    images: Mutex<Lru<Bytes>>,
    cpu: Arc<Semaphore>,
    dataset: Dataset,
    /// The user's datasets, listed at start.
    catalog: Arc<crate::catalog::Catalog>,
}

/// What every request shares: the configuration, the caches and the worker permits.
#[derive(Clone)]
pub struct AppState(Arc<Inner>);

/// A poisoned lock only means a worker panicked mid-insert; the map itself is still valid.
fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

impl AppState {
    /// A server with the default limits and the built-in dataset.
    pub fn new() -> Self {
        Self::with_config(Config::default())
    }

    pub fn with_config(config: Config) -> Self {
        let catalog = Arc::new(crate::catalog::Catalog::open(&config.datasets));
        AppState(Arc::new(Inner {
            dataset: Dataset::builtin(),
            catalog,
            analyses: Mutex::new(Lru::new(config.cached_analyses, config.analysis_cache_bytes)),
            images: Mutex::new(Lru::new(config.cached_images, config.image_cache_bytes)),
            cpu: Arc::new(Semaphore::new(config.workers.max(1))),
            config,
        }))
    }

    pub fn config(&self) -> &Config {
        &self.0.config
    }

    /// The built-in samples.
    pub fn dataset(&self) -> &Dataset {
        &self.0.dataset
    }

    /// The user's datasets.
    pub fn catalog(&self) -> &Arc<crate::catalog::Catalog> {
        &self.0.catalog
    }

    /// Run CPU-heavy `work` on a blocking thread once a worker permit is free.
    async fn run_cpu<T: Send + 'static>(&self, work: impl FnOnce() -> Result<T, ApiError> + Send + 'static) -> Result<T, ApiError> {
        let permit = self.0.cpu.clone().acquire_owned().await.map_err(|_| ApiError::Internal("the worker pool is closed".into()))?;
        tokio::task::spawn_blocking(move || {
            let _permit = permit;
            work()
        })
        .await
        .map_err(|e| ApiError::Internal(format!("the analysis stopped unexpectedly: {e}")))?
    }

    /// The cached analysis under `key`, or `compute` it (off the runtime) and cache it.
    async fn analysis(
        &self,
        key: String,
        compute: impl FnOnce(String) -> Result<Analyzed, ApiError> + Send + 'static,
    ) -> Result<Arc<Analyzed>, ApiError> {
        if let Some(hit) = lock(&self.0.analyses).get(&key) {
            return Ok(hit);
        }
        let analyzed = Arc::new(self.run_cpu(move || compute(key)).await?);
        lock(&self.0.analyses).insert(analyzed.key.clone(), analyzed.clone(), analyzed.bytes());
        Ok(analyzed)
    }

    fn cached_analysis(&self, key: &str) -> Option<Arc<Analyzed>> {
        lock(&self.0.analyses).get(key)
    }

    /// The cached file (a PNG, a recording) under `key`, or `render` it (off the runtime)
    /// and cache it.
    async fn cached_bytes(&self, key: String, render: impl FnOnce() -> Result<Vec<u8>, ApiError> + Send + 'static) -> Result<Bytes, ApiError> {
        if let Some(hit) = lock(&self.0.images).get(&key) {
            return Ok(hit);
        }
        let png = Bytes::from(self.run_cpu(render).await?);
        lock(&self.0.images).insert(key, png.clone(), png.len());
        Ok(png)
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
    let is_json = response.headers().get(header::CONTENT_TYPE).is_some_and(|t| t.as_bytes().starts_with(b"application/json"));
    if !(status.is_client_error() || status.is_server_error()) || is_json {
        return response.map(axum::body::Body::new);
    }
    let body = axum::body::to_bytes(axum::body::Body::new(response.into_body()), 4096).await.unwrap_or_default();
    let text = String::from_utf8_lossy(&body).trim().to_string();
    let reason = status.canonical_reason().unwrap_or("request failed").to_lowercase();
    let message = match status {
        StatusCode::PAYLOAD_TOO_LARGE => format!("request body too large: {}", if text.is_empty() { reason } else { text }),
        _ if text.is_empty() => reason,
        _ => text,
    };
    ApiError::Rejected(status, message).into_response()
}

/// The router of the web app.
pub fn app(state: AppState) -> Router {
    let config = state.config().clone();
    Router::new()
        .route("/", get(assets::index))
        .route("/assets/{file}", get(assets::asset))
        .route("/healthz", get(routes::healthz))
        .route("/api/analyze", post(routes::analyze))
        .route("/api/samples", get(datasets::samples))
        .route("/api/samples/{id}", get(datasets::sample))
        .route("/api/samples/{id}/recording.rrd", get(routes::recording))
        .route("/api/images/{key}/{file}", get(routes::image))
        .route("/api/interpolate", post(routes::interpolate))
        .route("/api/disk", post(routes::disk))
        .route("/api/plan", post(routes::plan))
        .fallback(routes::not_found)
        .layer(DefaultBodyLimit::max(config.body_limit))
        .layer(
            ServiceBuilder::new()
                .layer(TraceLayer::new_for_http())
                .layer(CompressionLayer::new())
                .layer(axum::middleware::map_response(json_errors))
                .layer(TimeoutLayer::with_status_code(StatusCode::REQUEST_TIMEOUT, config.timeout))
                .layer(RequestBodyLimitLayer::new(config.body_limit)),
        )
        .with_state(state)
}

/// Serve the app on `addr` until Ctrl-C.
pub async fn serve(addr: SocketAddr, state: AppState) -> std::io::Result<()> {
    let listener = tokio::net::TcpListener::bind(addr).await?;
    println!("CloSE web app: http://{}/  (Ctrl-C to stop)", listener.local_addr()?);
    axum::serve(listener, app(state))
        .with_graceful_shutdown(async {
            // If the signal cannot be listened to, run until killed.
            if tokio::signal::ctrl_c().await.is_err() {
                std::future::pending::<()>().await;
            }
        })
        .await
}

/// `close serve`: log to stderr (`RUST_LOG` overrides), start a runtime, serve.
pub fn run(addr: &str) -> Result<(), String> {
    run_with(addr, Config::default())
}

/// `close serve` with a configuration (e.g. `--dataset` folders).
pub fn run_with(addr: &str, config: Config) -> Result<(), String> {
    let addr: SocketAddr = addr.parse().map_err(|e| format!("--addr {addr}: {e} (expected e.g. 127.0.0.1:8080)"))?;
    let filter = tracing_subscriber::EnvFilter::try_from_default_env().unwrap_or_else(|_| "close=info,tower_http=info".into());
    // Already initialised (e.g. by an embedding program) is fine.
    let _ = tracing_subscriber::fmt().with_env_filter(filter).with_writer(std::io::stderr).try_init();
    let runtime = tokio::runtime::Builder::new_multi_thread().enable_all().build().map_err(|e| e.to_string())?;
    runtime.block_on(serve(addr, AppState::with_config(config))).map_err(|e| format!("cannot serve on {addr}: {e}"))
}
