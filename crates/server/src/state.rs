//! What every request shares: the server's configuration ([`Config`]) and its state
//! ([`AppState`]): the built-in dataset and the user's, the caches of analyses, drawings and
//! pictures, the CPU workers and the memory and connection budgets. The routes
//! ([`crate::routes`]) read and fill it; nothing here knows HTTP.

use std::sync::{Arc, Mutex, OnceLock};
use std::time::Duration;

use axum::body::Bytes;
use tokio::sync::Semaphore;

use crate::error::ApiError;
use crate::guard::UploadBudget;
use crate::uploads::{Stored, Uploads};
use crate::workers::{lock, Workers};
use close_core::analysis::Analysis;
use close_core::budget::{Budget, Deadline};
use close_io::cache::Lru;
use close_io::dataset::{BuiltinSample, Dataset};
use close_render::mesh_picture::MeshView;

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

/// What an analysis's pictures and plans need: the analysis and the sample's known folds,
/// without the JSON answer. It outlives its [`Analyzed`] in the server's drawings cache, so
/// the image URLs of an answer stay reachable after the analysis cache let it go.
pub struct Drawing {
    pub analysis: Analysis,
    /// The sample's known folds (empty when it carries none), drawn beside the found ones.
    pub truth: close_render::truth::Truth,
    /// A mesh sample's mesh at the analysed frames, for its mesh picture.
    pub mesh: Option<MeshView>,
    /// Roughly the memory it holds (`Drawing::weigh`), counted once when it is made.
    pub bytes: usize,
}

impl Drawing {
    pub(crate) fn new(
        analysis: Analysis,
        truth: close_render::truth::Truth,
        mesh: Option<MeshView>,
    ) -> Drawing {
        let bytes = Self::weigh(&analysis, &truth) + mesh.as_ref().map_or(0, MeshView::bytes);
        Drawing { analysis, truth, mesh, bytes }
    }

    /// The heap and inline bytes of an analysis and its truth: its frames and predicted end
    /// (O(frames·N), the bulk), its index and angle lists, its steps with their arcs and
    /// curves, and its texts.
    fn weigh(a: &Analysis, truth: &close_render::truth::Truth) -> usize {
        use std::mem::{size_of, size_of_val};
        let frames: usize = a.frames.iter().map(|f| size_of_val(f.as_slice())).sum();
        let steps: usize = a
            .steps
            .iter()
            .map(|s| {
                size_of_val(s)
                    + size_of_val(s.detection.arcs.as_slice())
                    + size_of_val(s.detection.curves.as_slice())
            })
            .sum();
        let lists = size_of_val(a.corners.as_slice())
            + size_of_val(a.corner_vertices.as_slice())
            + size_of_val(a.border_indices.as_slice())
            + size_of_val(a.folds.as_slice())
            + size_of_val(a.predicted_end.as_slice())
            + size_of_val(truth.folds.as_slice())
            + truth.folded.iter().flatten().map(|f| size_of_val(f.as_slice())).sum::<usize>();
        let texts = a.border_source.len() + a.warnings.iter().map(String::len).sum::<usize>();
        size_of::<Drawing>() + frames + steps + lists + texts
    }
}

/// An analysis, with the response JSON already written (a cache hit costs a copy).
pub struct Analyzed {
    pub key: String,
    pub drawing: Arc<Drawing>,
    pub response: Bytes,
}

impl Analyzed {
    /// Roughly the memory it holds: the drawing and the response.
    pub fn bytes(&self) -> usize {
        self.drawing.bytes + self.response.len()
    }
}

pub(crate) struct Inner {
    pub(crate) config: Config,
    pub(crate) analyses: Mutex<Lru<Arc<Analyzed>>>,
    pub(crate) drawings: Mutex<Lru<Arc<Drawing>>>,
    pub(crate) images: Mutex<Lru<Bytes>>,
    /// Light jobs: one worker per core, each on one thread.
    pub(crate) light: Workers,
    /// Heavy jobs: one fewer than the cores (at least one), so light jobs always find a
    /// worker; each on as many threads as cores (the OS shares them with light jobs).
    pub(crate) heavy: Workers,
    pub(crate) dataset: Dataset,
    /// Bytes of bodies and answers in flight ([`guard::upload_budget`]).
    pub(crate) memory: Arc<UploadBudget>,
    /// The rows of `GET /api/samples`, built once: the datasets never change.
    pub(crate) sample_list: OnceLock<Arc<crate::listing::Listing>>,
    /// The user's datasets, listed at start.
    pub(crate) catalog: Arc<close_io::catalog::Catalog>,
    /// The uploads kept on disk, with `--data-dir`.
    pub(crate) uploads: Option<Uploads>,
    /// Connection slots: [`Config::max_connections`] permits, one held by each open
    /// connection ([`serve_with`]); their crowding shortens a body's grace ([`guard::BodyRate`]).
    pub(crate) connections: Arc<Semaphore>,
}

/// What every request shares: the configuration, the dataset, the caches and the worker
/// permits.
#[derive(Clone)]
pub struct AppState(pub(crate) Arc<Inner>);

/// Jobs of more dGLI cells than this (e.g. two frames of 1400 vertices) are heavy.
const HEAVY_CELLS: u64 = 4_000_000;

/// Which permits a CPU job takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Lane {
    Light,
    Heavy,
}

impl Lane {
    /// The lane of a job that computes `cells` dGLI cells.
    pub(crate) fn of(cells: u64) -> Lane {
        if cells > HEAVY_CELLS {
            Lane::Heavy
        } else {
            Lane::Light
        }
    }
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
            uploads: config
                .data_dir
                .as_deref()
                .map(|dir| Uploads::new(dir, config.kept_uploads, config.kept_upload_bytes)),
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
    pub(crate) fn entries(&self) -> &[BuiltinSample] {
        self.0.dataset.entries()
    }

    /// The built-in sample `id`.
    pub(crate) fn entry(&self, id: &str) -> Option<&BuiltinSample> {
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
    pub(crate) async fn run_cpu<T: Send + 'static>(
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
    pub(crate) fn uploads(&self) -> Option<&Uploads> {
        self.0.uploads.as_ref()
    }

    /// Keep upload `key` (its `sample`, the `frames` analysed) on disk, with `--data-dir`.
    /// An upload that cannot be kept is still analysed: the failure is logged.
    pub(crate) fn keep_upload(
        &self,
        key: &str,
        frames: close_core::FrameRange,
        sample: close_io::formats::Sample,
    ) {
        if let Some(uploads) = self.uploads() {
            let stored = Stored { start: frames.start, end: frames.end, sample };
            if let Err(e) = uploads.save(key, &stored) {
                tracing::warn!("could not keep upload {key} in {}: {e}", uploads.dir().display());
            }
        }
    }

    /// Pictures (and recordings) in the cache now.
    pub fn cached_pictures(&self) -> usize {
        lock(&self.0.images).len()
    }

    pub(crate) fn cached_analysis(&self, key: &str) -> Option<Arc<Analyzed>> {
        lock(&self.0.analyses).get(key)
    }

    /// What the pictures of analysis `key` are drawn from: its cached analysis, or, once
    /// that was evicted, the drawing kept after it.
    pub(crate) fn drawing(&self, key: &str) -> Option<Arc<Drawing>> {
        match self.cached_analysis(key) {
            Some(hit) => Some(hit.drawing.clone()),
            None => lock(&self.0.drawings).get(key),
        }
    }

    /// The cached file (a PNG, a recording) under `key`, or `render` it (off the runtime,
    /// in the lane of `cells` dGLI cells) and cache it.
    pub(crate) async fn cached_bytes(
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
    pub(crate) fn cache_analysis(&self, analyzed: &Arc<Analyzed>) {
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
