//! The handlers of the HTTP API: each reads a typed request, runs the library on a blocking
//! worker (with the request's deadline and the server's budget), and writes a typed response
//! there too, so the async threads only move bytes.

use std::sync::Arc;

use axum::body::Bytes;
use axum::extract::{FromRequest, Multipart, Request, State};
use axum::http::{header, Uri};
use axum::response::{IntoResponse, Response};
use axum::Json;
use serde::{Deserialize, Serialize};
use serde_json::value::RawValue;

use super::answer::{AnalyzeAnswer, ListedFields, PlanAnswer, SampleRow};
use super::{ApiError, AppJson, AppPath, AppQuery};
use crate::state::{Analyzed, AppState, Drawing, Lane};
use close_core::analysis::{analyze_with, Analysis, FrameRange, Options};
use close_core::border::{to_xyz, BorderFrames};
use close_core::budget::{Budget, Deadline};
use close_core::error::{Error, Result};
use close_core::geometry::{Fold, Line};
use close_io::cache::content_key;
use close_io::formats::{json::parse_sample, read_files, Sample, Truth};
use close_render::colour::Scale;
use close_render::mesh_picture::MeshView;
use close_render::{
    render, render_disk, Format, Known, Output, Picture, View, DEFAULT_SIZE, MAX_SIZE, MIN_SIZE,
};

/// Thumbnail size in the sample list.
const THUMBNAIL_SIZE: u32 = 160;
/// Cache keys of built-in samples start with this; uploads are hex digests.
const SAMPLE_KEY: &str = "sample:";

/// A JSON answer already serialised (on a worker, not on the async runtime).
pub struct JsonBytes(pub(super) Bytes);

impl IntoResponse for JsonBytes {
    fn into_response(self) -> Response {
        ([(header::CONTENT_TYPE, "application/json")], self.0).into_response()
    }
}

pub(super) fn to_json<T: Serialize>(value: &T) -> Result<Bytes, ApiError> {
    serde_json::to_vec(value)
        .map(Bytes::from)
        .map_err(|e| ApiError::Internal(format!("could not write the answer: {e}")))
}

/// A sample that `GET /api/samples` lists, by id: built-in, or from one of the user's
/// datasets (`--dataset`). Both are answered, pictured and planned alike.
pub(super) enum Listed {
    Builtin(String),
    Dataset { id: String, sample: Arc<Sample> },
}

/// Where a sample comes from, as rows and analyses name it: `"builtin"`, the dataset
/// folder or store, or `"upload"`.
pub(super) const BUILTIN: &str = "builtin";
const UPLOAD: &str = "upload";

/// A sample read and validated, ready to be analysed.
pub(super) struct Loaded {
    key: String,
    name: String,
    category: String,
    frames: usize,
    border: BorderFrames,
    range: FrameRange,
    /// Most folds one step may hold ([`Options::max_folds`]).
    max_folds: usize,
    source: String,
    truth: Option<Truth>,
    /// A listed sample, whose answer includes the sample.
    listed: Option<Listed>,
    /// A mesh sample's mesh at the frames the range asks (the analysis's by default).
    mesh: Option<MeshView>,
}

impl Loaded {
    /// Validate `sample`, refused over the cell budget before its border is prepared when
    /// that is known ([`Sample::check_budget`]).
    pub(super) fn of(
        key: String,
        sample: &Sample,
        range: FrameRange,
        source: &str,
        listed: Option<Listed>,
        budget: &Budget,
    ) -> Result<Loaded, ApiError> {
        sample.check_budget(range, budget)?;
        Ok(Loaded {
            key,
            name: sample.name.clone(),
            category: sample.category.clone(),
            frames: frame_count(sample),
            border: sample.border_frames()?,
            range,
            max_folds: close_core::DEFAULT_MAX_FOLDS,
            source: source.to_string(),
            truth: sample.truth.clone(),
            listed,
            mesh: sample.mesh.as_ref().and_then(|m| {
                MeshView::new(
                    m,
                    (
                        range.start.unwrap_or(0),
                        range.end.unwrap_or(m.frames.len().saturating_sub(1)),
                    ),
                )
            }),
        })
    }

    /// dGLI cells of every frame: at least what the analysis of any range costs.
    fn cells(&self) -> u64 {
        let n = self.border.len() as u64;
        (self.border.frames.len() as u64).saturating_mul(n * n)
    }

    /// Analyse, with the server's budget and the job's deadline, and write the response.
    fn analyze(self, state: &AppState, deadline: &Deadline) -> Result<Analyzed, ApiError> {
        let options = Options {
            frames: self.range,
            max_folds: self.max_folds,
            budget: state.config().budget,
            deadline: deadline.clone(),
            ..Options::default()
        };
        let analysis = analyze_with(&self.border, options)?;
        let key = self.key;
        // The view of other frames than the analysis's is no view of it.
        let mesh = self.mesh.filter(|m| m.frames == (analysis.start_frame, analysis.end_frame));
        let listed_pictures =
            Picture::ALL.into_iter().chain(mesh.is_some().then_some(Picture::Mesh));
        let images = listed_pictures
            .map(|p| (p.name(), format!("/api/images/{key}/{}.png?size={DEFAULT_SIZE}", p.name())))
            .collect();
        let listed = match &self.listed {
            Some(Listed::Builtin(id)) => state.entry(id).map(|entry| ListedFields {
                id: &entry.id,
                sample: &entry.sample,
                recording: cfg!(feature = "rerun")
                    .then(|| format!("/api/samples/{}/recording.rrd", entry.id)),
            }),
            Some(Listed::Dataset { id, sample }) => {
                Some(ListedFields { id, sample, recording: None })
            }
            None => None,
        };
        let response = to_json(&AnalyzeAnswer {
            key: &key,
            name: &self.name,
            category: &self.category,
            frames: self.frames,
            analysis: &analysis,
            start_border: analysis.start_border().iter().map(to_xyz).collect(),
            end_border: analysis.end_border().iter().map(to_xyz).collect(),
            images,
            source: &self.source,
            truth: self.truth.as_ref(),
            listed,
        })?;
        let truth = self.truth.as_ref().map(close_render::truth::Truth::of).unwrap_or_default();
        Ok(Analyzed { key, drawing: Arc::new(Drawing::new(analysis, truth, mesh)), response })
    }
}

/// The cached analysis under `key`, or `load` the sample (within the job's deadline) and
/// analyse it. Both run on a worker: a light analysis in the same job as its loading, a heavy one (over
/// [`Lane::of`]'s threshold) in the heavy lane, so it never holds the light workers.
pub(super) async fn analysis(
    state: &AppState,
    key: String,
    load: impl FnOnce(String, &Deadline) -> Result<Loaded, ApiError> + Send + 'static,
) -> Result<Arc<Analyzed>, ApiError> {
    if let Some(hit) = state.cached_analysis(&key) {
        return Ok(hit);
    }
    let job = state.clone();
    let loaded = state
        .run_cpu(Lane::Light, move |deadline| {
            let loaded = load(key, deadline)?;
            // A request gone while its sample was read hands nothing on to the heavy lane.
            deadline.check()?;
            match Lane::of(loaded.cells()) {
                Lane::Light => loaded.analyze(&job, deadline).map(Ok),
                Lane::Heavy => Ok(Err(loaded)),
            }
        })
        .await?;
    let analyzed = match loaded {
        Ok(done) => done,
        Err(heavy) => {
            let job = state.clone();
            state.run_cpu(Lane::Heavy, move |deadline| heavy.analyze(&job, deadline)).await?
        }
    };
    let analyzed = Arc::new(analyzed);
    state.cache_analysis(&analyzed);
    Ok(analyzed)
}

#[derive(Serialize)]
pub struct Health {
    status: &'static str,
}

pub async fn healthz() -> Json<Health> {
    Json(Health { status: "ok" })
}

pub async fn not_found(uri: Uri) -> ApiError {
    ApiError::NotFound(format!("no route {}", uri.path()))
}

/// Optional frame range of `POST /api/analyze`, and the most folds one step may hold
/// (`max_folds`, 1 to 4, default 3: `close analyze --max-folds`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RangeQuery {
    start: Option<usize>,
    end: Option<usize>,
    max_folds: Option<usize>,
}

/// What an analyze request brought: a Sample JSON body, or named files.
enum Upload {
    Json(Bytes),
    Files(Vec<(String, Vec<u8>)>),
}

impl Upload {
    async fn from_request(request: Request, state: &AppState) -> Result<Upload, ApiError> {
        let content_type = request
            .headers()
            .get(header::CONTENT_TYPE)
            .and_then(|t| t.to_str().ok())
            .unwrap_or("")
            .to_ascii_lowercase();
        let essence = content_type.split(';').next().unwrap_or("").trim();
        if essence == "application/json" || essence.ends_with("+json") {
            return Ok(Upload::Json(Bytes::from_request(request, state).await?));
        }
        if essence == "multipart/form-data" {
            return Self::files(Multipart::from_request(request, state).await?).await;
        }
        Err(ApiError::UnsupportedMediaType(format!(
            "content type {:?} is not accepted: send a Sample JSON as application/json, or files as multipart/form-data",
            if essence.is_empty() { "(none)" } else { essence }
        )))
    }

    /// Form files `sample` (one or more: one per frame), or one `start` and at most one `end`.
    async fn files(mut form: Multipart) -> Result<Upload, ApiError> {
        let (mut samples, mut start, mut end) = (Vec::new(), None, None);
        while let Some(field) = form.next_field().await? {
            let name = field.name().unwrap_or_default().to_string();
            let (slot, default_name) = match name.as_str() {
                "sample" => (None, "sample.json"),
                "start" => (Some(&mut start), "start.txt"),
                "end" => (Some(&mut end), "end.txt"),
                other => return Err(ApiError::BadRequest(format!("unknown form field {other:?}: send files named \"sample\", or \"start\" and \"end\""))),
            };
            // A second part of the same name would silently replace the first.
            if slot.as_ref().is_some_and(|s| s.is_some()) {
                return Err(ApiError::BadRequest(format!(
                    "the form holds two {name:?} files: send one"
                )));
            }
            let file =
                field.file_name().filter(|f| !f.is_empty()).unwrap_or(default_name).to_string();
            let bytes = field.bytes().await?.to_vec();
            match slot {
                Some(slot) => *slot = Some((file, bytes)),
                None => samples.push((file, bytes)),
            }
        }
        let files = match (samples.is_empty(), start, end) {
            (false, None, None) => samples,
            (false, _, _) => {
                return Err(ApiError::BadRequest(
                    "send either \"sample\" or \"start\"/\"end\" files, not both".into(),
                ))
            }
            (true, Some(s), e) => std::iter::once(s).chain(e).collect(),
            (true, None, Some(_)) => {
                return Err(ApiError::BadRequest("an \"end\" file needs a \"start\" file".into()))
            }
            (true, None, None) => {
                return Err(Error::Empty {
                    what: "the form holds no file: send \"sample\", or \"start\" and \"end\"",
                }
                .into())
            }
        };
        Ok(Upload::Files(files))
    }

    /// Content key of the upload and the frame range.
    fn key(&self, range: &RangeQuery) -> String {
        let range = format!("{:?}-{:?}-{:?}", range.start, range.end, range.max_folds);
        match self {
            Upload::Json(bytes) => content_key(&[b"json", bytes, range.as_bytes()]),
            Upload::Files(files) => {
                let mut parts: Vec<&[u8]> = vec![b"files", range.as_bytes()];
                parts.extend(
                    files.iter().flat_map(|(name, bytes)| [name.as_bytes(), bytes.as_slice()]),
                );
                content_key(&parts)
            }
        }
    }

    fn sample(&self) -> close_io::error::Result<Sample> {
        match self {
            Upload::Json(bytes) => parse_sample(bytes),
            Upload::Files(files) => read_files(files),
        }
    }
}

pub async fn analyze(
    State(state): State<AppState>,
    AppQuery(range): AppQuery<RangeQuery>,
    request: Request,
) -> Result<JsonBytes, ApiError> {
    let upload = Upload::from_request(request, &state).await?;
    let key = upload.key(&range);
    let frames = FrameRange { start: range.start, end: range.end };
    let max_folds = range.max_folds.unwrap_or(close_core::DEFAULT_MAX_FOLDS);
    let budget = state.config().budget;
    let job = state.clone();
    let done = analysis(&state, key, move |key, _| {
        let sample = upload.sample()?;
        let loaded = Loaded::of(key, &sample, frames, UPLOAD, None, &budget)?;
        job.keep_upload(&loaded.key, frames, sample);
        Ok(Loaded { max_folds, ..loaded })
    })
    .await?;
    Ok(JsonBytes(done.response.clone()))
}

/// Why upload `key` cannot be found: the server keeps uploads in memory only, or its data
/// folder no longer holds this one.
fn upload_gone(state: &AppState, key: &str) -> ApiError {
    ApiError::NotFound(match state.uploads() {
        Some(uploads) => {
            let (files, bytes) = uploads.bounds();
            format!(
                "the upload {key:?} is gone: this server keeps its {files} most recent uploads (at most {} MB) in {}, and newer ones took its place. Upload the sample again.",
                bytes >> 20,
                uploads.dir().display()
            )
        }
        None => format!(
            "no analysis {key:?}: this server keeps uploads in memory only, and no longer has this one (it restarted, or newer analyses took its place; `close serve --data-dir DIR` keeps uploads on disk). Upload the sample again."
        ),
    })
}

/// The analysis of upload `key`: cached, or analysed again from the data folder.
async fn kept_analysis(state: &AppState, key: &str) -> Result<Arc<Analyzed>, ApiError> {
    if let Some(hit) = state.cached_analysis(key) {
        return Ok(hit);
    }
    if state.uploads().is_none() {
        return Err(upload_gone(state, key));
    }
    let job = state.clone();
    analysis(state, key.to_string(), move |key, _| {
        let stored = match job.uploads().map(|u| u.load(&key)) {
            Some(Ok(Some(stored))) => stored,
            Some(Err(why)) => {
                return Err(ApiError::NotFound(format!(
                    "the upload {key:?} cannot be read from the data folder: {why}"
                )))
            }
            Some(Ok(None)) | None => return Err(upload_gone(&job, &key)),
        };
        let frames = FrameRange { start: stored.start, end: stored.end };
        Loaded::of(key, &stored.sample, frames, UPLOAD, None, &job.config().budget)
    })
    .await
}

/// `GET /api/analyses/{key}`: an analysis still kept, by the `key` its answer gave (an
/// upload's, so that a link to it outlives the page that uploaded it).
pub async fn analysis_by_key(
    State(state): State<AppState>,
    AppPath(key): AppPath<String>,
) -> Result<JsonBytes, ApiError> {
    if let Some(id) = key.strip_prefix(SAMPLE_KEY) {
        return Ok(JsonBytes(sample_analysis(&state, id).await?.response.clone()));
    }
    Ok(JsonBytes(kept_analysis(&state, &key).await?.response.clone()))
}

/// dGLI cells of the pictures of `analysis` (two disks at most).
fn cells(analysis: &Analysis) -> u64 {
    2 * (analysis.n as u64).pow(2)
}

/// Frames of a border or mesh sample.
fn frame_count(sample: &Sample) -> usize {
    sample.mesh.as_ref().map_or(sample.frames.len(), |m| m.frames.len())
}

impl SampleRow {
    pub(super) fn builtin(e: &close_io::dataset::BuiltinSample) -> SampleRow {
        let border = e.sample.border_frames();
        SampleRow::dataset(&close_io::catalog::Entry {
            id: e.id.clone(),
            name: e.sample.name.clone(),
            category: e.sample.category.clone(),
            n: border.as_ref().ok().map(BorderFrames::len),
            frames: frame_count(&e.sample),
            mesh: e.sample.mesh.is_some(),
            source: BUILTIN.into(),
            error: border.err().map(|e| e.to_string()),
        })
    }

    pub(super) fn dataset(e: &close_io::catalog::Entry) -> SampleRow {
        SampleRow { entry: e.clone(), thumbnail: thumbnail(&e.id) }
    }
}

/// The thumbnail URL of listed sample `id`: its analysis is cached under `sample:{id}`.
fn thumbnail(id: &str) -> String {
    format!("/api/images/{SAMPLE_KEY}{id}/thumbnail.png?size={THUMBNAIL_SIZE}")
}

fn unknown_sample(id: &str) -> ApiError {
    ApiError::NotFound(format!("no sample {id:?}; GET /api/samples lists them"))
}

/// The analysis of listed sample `id` (built-in or from a dataset), cached under
/// `sample:{id}`, so its pictures, plan and thumbnail are found alike.
async fn sample_analysis(state: &AppState, id: &str) -> Result<Arc<Analyzed>, ApiError> {
    if state.entry(id).is_none() && state.catalog().get(id).is_none() {
        return Err(unknown_sample(id));
    }
    let (job, id) = (state.clone(), id.to_string());
    analysis(state, format!("{SAMPLE_KEY}{id}"), move |key, deadline| {
        let budget = job.config().budget;
        match job.entry(&id) {
            Some(entry) => Loaded::of(
                key,
                &entry.sample,
                FrameRange::default(),
                BUILTIN,
                Some(Listed::Builtin(id)),
                &budget,
            ),
            None => {
                let sample = job.catalog().load(&id, deadline)?;
                let source = job.catalog().get(&id).map_or(String::new(), |e| e.source.clone());
                Loaded::of(
                    key,
                    &sample.clone(),
                    FrameRange::default(),
                    &source,
                    Some(Listed::Dataset { id, sample }),
                    &budget,
                )
            }
        }
    })
    .await
}

pub async fn sample(
    State(state): State<AppState>,
    AppPath(id): AppPath<String>,
) -> Result<JsonBytes, ApiError> {
    Ok(JsonBytes(sample_analysis(&state, &id).await?.response.clone()))
}

/// `GET /api/samples/{id}/recording.rrd`: the sample's analysis as a Rerun recording.
#[cfg(feature = "rerun")]
pub async fn recording(
    State(state): State<AppState>,
    AppPath(id): AppPath<String>,
) -> Result<Response, ApiError> {
    let analyzed = sample_analysis(&state, &id).await?;
    let job = state.clone();
    let sample_id = id.clone();
    let rrd = state
        .cached_bytes(
            format!("{}/recording.rrd", analyzed.key),
            cells(&analyzed.drawing.analysis),
            move |_| {
                let entry = job.entry(&sample_id).ok_or_else(|| unknown_sample(&sample_id))?;
                Ok(close_render::record::record(
                    &analyzed.drawing.analysis,
                    &entry.sample.border_frames()?,
                )?)
            },
        )
        .await?;
    let disposition = format!(
        "attachment; filename=\"{}.rrd\"",
        id.replace(|c: char| !c.is_ascii_alphanumeric() && c != '_' && c != '-', "_")
    );
    Ok((
        [
            (header::CONTENT_TYPE, "application/octet-stream".to_string()),
            (header::CONTENT_DISPOSITION, disposition),
        ],
        rrd,
    )
        .into_response())
}

/// Without the `rerun` feature there is no recording to give: say why.
#[cfg(not(feature = "rerun"))]
pub async fn recording(AppPath(id): AppPath<String>) -> ApiError {
    ApiError::NotFound(format!("no recording of {id:?}: this server was built without the `rerun` feature (cargo run --features rerun)"))
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImageQuery {
    size: Option<u32>,
    /// One step's disk pictures (1-based: step k goes from analysed frame k − 1 to k).
    step: Option<usize>,
    /// `png` (the default) or `svg`: the same drawing.
    #[serde(default)]
    format: Format,
    /// The print resolution a PNG states (dots per inch, 72–1200): a 3000 px picture at 300
    /// dpi prints 10 inches wide.
    dpi: Option<u32>,
}

/// Print resolutions a PNG may state, in dots per inch.
const DPI: std::ops::RangeInclusive<u32> = 72..=1200;

/// A picture's side in pixels as drawn: the request's, clamped. The cache is keyed by it,
/// so every size past the limit is one picture, not one per number.
fn picture_size(asked: Option<u32>) -> u32 {
    asked.unwrap_or(DEFAULT_SIZE).clamp(MIN_SIZE, MAX_SIZE)
}

/// What an image or readout URL's key draws from: a cached analysis or drawing, or a
/// listed sample's (analysed again).
async fn drawing_by_key(state: &AppState, key: &str) -> Result<Arc<Drawing>, ApiError> {
    match (state.drawing(key), key.strip_prefix(SAMPLE_KEY)) {
        (Some(hit), _) => Ok(hit),
        (None, Some(id)) => Ok(sample_analysis(state, id).await?.drawing.clone()),
        (None, None) => Ok(kept_analysis(state, key).await?.drawing.clone()),
    }
}

pub async fn image(
    State(state): State<AppState>,
    AppPath((key, file)): AppPath<(String, String)>,
    AppQuery(query): AppQuery<ImageQuery>,
) -> Result<Response, ApiError> {
    let picture = file.strip_suffix(".png").and_then(Picture::from_name).ok_or_else(|| {
        let names: Vec<&str> = Picture::ALL.iter().map(|p| p.name()).collect();
        ApiError::NotFound(format!(
            "no picture {file:?}: expected one of {}.png",
            names.join(".png, ")
        ))
    })?;
    if let Some(dpi) = query.dpi.filter(|dpi| !DPI.contains(dpi)) {
        return Err(ApiError::BadRequest(format!(
            "dpi {dpi} is out of range: a PNG states {} to {} dots per inch",
            DPI.start(),
            DPI.end()
        )));
    }
    let drawing = drawing_by_key(&state, &key).await?;
    let (size, step, format, dpi) = (picture_size(query.size), query.step, query.format, query.dpi);
    let file = state
        .cached_bytes(
            format!("{key}/{}/{size}/{step:?}/{format:?}/{dpi:?}", picture.name()),
            cells(&drawing.analysis),
            move |_| {
                let known = Known { truth: &drawing.truth, mesh: drawing.mesh.as_ref() };
                let output = Output { format, dpi, ..Output::png(size) };
                Ok(render(&drawing.analysis, &View { picture, step }, &output, known)?)
            },
        )
        .await?;
    // The key names the content, so the picture never changes.
    Ok((
        [
            (header::CONTENT_TYPE, format.content_type()),
            (header::CACHE_CONTROL, "public, max-age=86400, immutable"),
        ],
        file,
    )
        .into_response())
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReadoutQuery {
    size: Option<u32>,
    step: Option<usize>,
}

/// `GET /api/readout/{key}?step=&size=`: what reading values off the disk pictures of that
/// step (and marking edges on the border plot) takes, for pictures of that size
/// ([`close_render::readout`]).
pub async fn readout(
    State(state): State<AppState>,
    AppPath(key): AppPath<String>,
    AppQuery(query): AppQuery<ReadoutQuery>,
) -> Result<JsonBytes, ApiError> {
    let drawing = drawing_by_key(&state, &key).await?;
    let (size, step) = (picture_size(query.size), query.step);
    let answer = state
        .cached_bytes(
            format!("{key}/readout/{size}/{step:?}"),
            cells(&drawing.analysis),
            move |_| {
                Ok(to_json(&close_render::readout::readout(
                    &drawing.analysis,
                    &drawing.truth,
                    step,
                    size,
                )?)?
                .to_vec())
            },
        )
        .await?;
    Ok(JsonBytes(answer))
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CellsQuery {
    /// The disk's edge count N.
    n: usize,
    size: Option<u32>,
}

/// `GET /api/cells.png?n=&size=`: which cell each pixel of a disk picture of N = `n` and that
/// size shows ([`close_render::readout::cell_picture`]); the same for every disk of that N.
pub async fn cell_picture(
    State(state): State<AppState>,
    AppQuery(query): AppQuery<CellsQuery>,
) -> Result<Response, ApiError> {
    let (n, size) = (query.n, picture_size(query.size));
    let file = state
        .cached_bytes(format!("cells/{n}/{size}"), u64::from(size).pow(2), move |_| {
            Ok(close_render::readout::cell_picture(n, size)?)
        })
        .await?;
    Ok((
        [
            (header::CONTENT_TYPE, "image/png"),
            (header::CACHE_CONTROL, "public, max-age=86400, immutable"),
        ],
        file,
    )
        .into_response())
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InterpolateRequest {
    border: Vec<[f64; 3]>,
    /// The flat border whose orientation applies when `border` is already folded (as
    /// `POST /api/disk` takes it); by default `border` itself.
    #[serde(default)]
    reference: Option<Vec<[f64; 3]>>,
    /// Between two folds: `from` and `to`; or one fold turned over: its `arcs` (an analysis
    /// step's `arcs`) about `line` (its `line`; by default the line through the first arc's
    /// start and the last arc's end). See [`close_core::interpolate::Motion`].
    #[serde(default)]
    from: Option<Fold>,
    #[serde(default)]
    to: Option<Fold>,
    #[serde(default)]
    arcs: Option<Vec<close_core::geometry::Arc>>,
    #[serde(default)]
    line: Option<Line>,
    /// States evenly spaced from the start to the end, both included (60 by default)…
    #[serde(default)]
    steps: Option<usize>,
    /// …or the states at these fractions of the way (each in [0, 1]), in this order.
    #[serde(default)]
    at: Option<Vec<f64>>,
    /// Folds made on `border` (then the flat cloth) before the motion, in order, each as an
    /// analysis step reports it (`arcs`, `line`): the motion starts from the state they leave,
    /// and the cloth's layers are drawn from the flat cloth through them.
    #[serde(default)]
    prior: Option<Vec<PriorFold>>,
    /// Also give each state as the web app draws it (`states`: the cloth's layers, each
    /// vertex's height and the fold's line).
    #[serde(default)]
    drawn: bool,
}

/// A fold made before the motion: an analysis step's `arcs` and `line`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PriorFold {
    arcs: Vec<close_core::geometry::Arc>,
    #[serde(default)]
    line: Option<Line>,
}

/// States of an interpolation when the request names none.
const DEFAULT_STEPS: usize = 60;

/// Bytes an interpolation's answer may take per point while it is built: the point (24)
/// and its JSON, three floats of at most 24 characters with their brackets and commas (80);
/// drawn, its height and its share of the layers (about as much again).
const INTERPOLATED_POINT_BYTES: usize = 24 + 80;

/// Largest angle (radians, either sign) an interpolation takes: past it a fold's angles
/// lose their meaning to rounding, and their differences overflow.
const MAX_ANGLE: f64 = 1e6;
/// Largest coordinate of a fold line's point: the border is at most 10⁶ radii across.
const MAX_LINE_POINT: f64 = 1e6;

impl InterpolateRequest {
    /// Refuse what cannot be a fold, as `/api/plan` refuses its goal: `from`, `to` and the
    /// `arcs` need finite angles of at most [`MAX_ANGLE`]; a `line` a finite point within
    /// [`MAX_LINE_POINT`] and a finite direction of some length.
    fn check(&self) -> Result<(), ApiError> {
        let angles = [("from", self.from), ("to", self.to)]
            .into_iter()
            .filter_map(|(name, fold)| fold.map(|f| (name, f.ends())))
            .chain(self.arcs.iter().flatten().map(|a| ("arcs", [a.a, a.b])))
            .chain(
                self.prior.iter().flatten().flat_map(|p| &p.arcs).map(|a| ("prior", [a.a, a.b])),
            );
        for (name, fold) in angles {
            if fold.iter().any(|a| !a.is_finite() || a.abs() > MAX_ANGLE) {
                return Err(Error::InvalidArgument(format!(
                    "\"{name}\" needs finite angles of at most {MAX_ANGLE:e} radians, got {fold:?}"
                ))
                .into());
            }
        }
        let prior_lines = self.prior.iter().flatten().filter_map(|p| p.line.as_ref());
        for line in self.line.iter().chain(prior_lines) {
            if line.point.iter().any(|c| !c.is_finite() || c.abs() > MAX_LINE_POINT) {
                return Err(Error::InvalidArgument(format!(
                    "\"line\": the point needs finite coordinates of at most {MAX_LINE_POINT:e}, got [{}, {}]",
                    line.point.x, line.point.y
                ))
                .into());
            }
            let length = line.direction.x.hypot(line.direction.y);
            if !length.is_finite() || length == 0.0 {
                return Err(Error::InvalidArgument(format!(
                    "\"line\": the direction has no length, or not a finite one: [{}, {}]",
                    line.direction.x, line.direction.y
                ))
                .into());
            }
        }
        Ok(())
    }
}

/// `POST /api/interpolate`'s answer when asked to draw (`drawn`): the states of the motion
/// (core's [`Interpolation`]) and each as the web app draws it ([`close_render::cloth`]).
///
/// [`Interpolation`]: close_core::interpolate::Interpolation
#[derive(Serialize)]
struct InterpolateAnswer {
    #[serde(flatten)]
    interpolation: close_core::interpolate::Interpolation,
    states: Vec<close_render::cloth::Drawn>,
}

pub async fn interpolate(
    State(state): State<AppState>,
    AppJson(req): AppJson<InterpolateRequest>,
) -> Result<Response, ApiError> {
    req.check()?;
    let at = match (req.steps, req.at) {
        (Some(_), Some(_)) => {
            return Err(ApiError::BadRequest(
                "give `steps` (evenly spaced states) or `at` (fractions of the way), not both"
                    .into(),
            ))
        }
        (_, Some(at)) => at,
        (steps, None) => {
            let steps = steps.unwrap_or(DEFAULT_STEPS);
            if !close_core::interpolate::STEPS.contains(&steps) {
                return Err(Error::InvalidArgument(format!(
                    "steps must be in {}..={}, got {steps}",
                    close_core::interpolate::STEPS.start(),
                    close_core::interpolate::STEPS.end()
                ))
                .into());
            }
            close_core::interpolate::fractions(steps)
        }
    };
    if req.prior.is_some() && req.reference.is_some() {
        return Err(ApiError::BadRequest(
            "with `prior` folds, `border` is the flat cloth: send no `reference`".into(),
        ));
    }
    state.config().budget.interpolation(req.border.len(), at.len())?;
    let motion = close_core::interpolate::Motion::of(req.from, req.to, req.arcs, req.line)?;
    let prior: Vec<close_core::geometry::Folding> = req
        .prior
        .unwrap_or_default()
        .into_iter()
        .map(|p| close_core::geometry::Folding {
            fold: Fold::span(&p.arcs).unwrap_or_default(),
            arcs: p.arcs,
            line: p.line,
        })
        .collect();
    // The answer's size is known now: reserved before it is built, not found after.
    let points = req.border.len().saturating_mul(at.len().saturating_add(1));
    let per_point = INTERPOLATED_POINT_BYTES * if req.drawn { 2 } else { 1 };
    let reserved = state.0.memory.reserve(points.saturating_mul(per_point)).await?;
    let (border, reference, drawn) = (req.border, req.reference, req.drawn);
    let answer = state
        .run_cpu(Lane::Light, move |_| {
            let frames = match reference {
                Some(reference) => vec![reference, border],
                None => vec![border],
            };
            let prepared = close_core::border::prepare(frames)?;
            // The state to fold is the last frame; without prior folds it is drawn as it lies.
            let given = prepared.frames.last().map_or(&[][..], Vec::as_slice);
            let (base, made) = close_render::cloth::make(given, &prior)?;
            let mut interpolation = close_core::interpolate::motion_at(&base, &motion, &at)?;
            interpolation.border_indices = prepared.border_indices;
            if !drawn {
                return to_json(&interpolation);
            }
            let states =
                close_render::cloth::motion_states(given, &made, &base, &motion, &interpolation);
            to_json(&InterpolateAnswer { interpolation, states })
        })
        .await?;
    let mut response = JsonBytes(answer).into_response();
    response.extensions_mut().insert(reserved);
    Ok(response)
}

/// `POST /api/disk`: the dGLI disk of one border state (e.g. a frame of an interpolation).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DiskRequest {
    border: Vec<[f64; 3]>,
    /// The border whose normalisation (and orientation) applies, as the analysis uses the
    /// start frame's for the end frame; by default `border` itself. A folded border
    /// overlaps itself, so its own orientation is no guide: send the flat one here.
    #[serde(default)]
    reference: Option<Vec<[f64; 3]>>,
    size: Option<u32>,
    /// A colour scale to keep (e.g. through an animation), as the `x-disk-scale` header of
    /// an earlier answer gave it; by default the disk's own.
    #[serde(default)]
    scale: Option<Scale>,
    /// The picture's title (at most [`MAX_TITLE`] characters); by default "dGLI disk ·
    /// current state".
    #[serde(default)]
    title: Option<String>,
    /// Another state of a border of as many vertices: the picture is then the difference of
    /// the two disks, this one's minus that one's.
    #[serde(default)]
    minus: Option<StateRequest>,
}

/// One border state: a border and the flat border whose normalisation applies to it.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StateRequest {
    border: Vec<[f64; 3]>,
    #[serde(default)]
    reference: Option<Vec<[f64; 3]>>,
}

/// Longest title a disk picture takes, in characters.
const MAX_TITLE: usize = 120;

/// `POST /api/disk?format=svg`: the disk as SVG, as any picture URL takes it.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DiskQuery {
    #[serde(default)]
    format: Format,
}

/// A disk picture as the file cache keeps it: the file (PNG or SVG) and the colour scale
/// (s, max) it used.
struct DiskPicture {
    scale: [f64; 2],
    file: Bytes,
}

impl DiskPicture {
    /// Bytes of the scale ahead of the PNG in the cache.
    const HEAD: usize = 16;

    /// The cache's bytes: the scale's two floats (little-endian), then the file.
    fn into_bytes(self) -> Vec<u8> {
        self.scale.iter().flat_map(|v| v.to_le_bytes()).chain(self.file).collect()
    }

    /// The picture from its cache bytes ([`DiskPicture::into_bytes`]).
    fn from_bytes(cached: Bytes) -> DiskPicture {
        let head = Self::HEAD.min(cached.len());
        let float = |k: usize| {
            cached
                .get(8 * k..8 * k + 8)
                .and_then(|b| b.try_into().ok())
                .map_or(0.0, f64::from_le_bytes)
        };
        DiskPicture { scale: [float(0), float(1)], file: cached.slice(head..) }
    }

    /// The answer of `POST /api/disk`: the file as `format`, and in the header `x-disk-scale`
    /// the colour scale it used ("s max"), which a later request can send back as `scale`.
    fn into_response(self, format: Format) -> Response {
        let scale = format!("{} {}", self.scale[0], self.scale[1]);
        (
            [
                (header::CONTENT_TYPE, format.content_type().to_string()),
                (header::CACHE_CONTROL, "no-store".to_string()),
                (DISK_SCALE, scale),
            ],
            self.file,
        )
            .into_response()
    }
}

/// The header naming the colour scale of a disk picture.
const DISK_SCALE: header::HeaderName = header::HeaderName::from_static("x-disk-scale");

fn coordinate_bytes(points: &[[f64; 3]]) -> Vec<u8> {
    points.iter().flatten().flat_map(|c| c.to_le_bytes()).collect()
}

/// The cache key's part for a state subtracted from a disk (none: empty).
fn minus_key(minus: Option<&StateRequest>) -> Vec<u8> {
    minus.map_or_else(Vec::new, |m| {
        let reference = m.reference.as_deref().map(coordinate_bytes).unwrap_or_default();
        [&b"minus"[..], &coordinate_bytes(&m.border), &b"reference"[..], &reference].concat()
    })
}

/// The disk of `border` (normalised as `reference`), or its difference with the disk of
/// `minus`: this one's minus that one's.
fn state_disk(
    border: Vec<[f64; 3]>,
    reference: Option<Vec<[f64; 3]>>,
    minus: Option<StateRequest>,
    deadline: &Deadline,
) -> Result<close_core::disk::Disk> {
    let disk = close_core::disk::of_state(border, reference, deadline)?;
    Ok(match minus {
        Some(minus) => {
            let other = close_core::disk::of_state(minus.border, minus.reference, deadline)?;
            // signed_diff(end) is end − start.
            other.signed_diff(&disk)
        }
        None => disk,
    })
}

pub async fn disk(
    State(state): State<AppState>,
    AppQuery(query): AppQuery<DiskQuery>,
    AppJson(req): AppJson<DiskRequest>,
) -> Result<Response, ApiError> {
    let format = query.format;
    let size = picture_size(req.size);
    // Checked before the cache, which keys "with a reference" apart from "without": a
    // reference too short for a border is refused even when the border alone is cached.
    if let Some(reference) =
        req.reference.as_deref().filter(|r| r.len() < close_core::border::MIN_VERTICES)
    {
        return Err(ApiError::Rejected(
            axum::http::StatusCode::UNPROCESSABLE_ENTITY,
            format!(
                "\"reference\" has {} vertices: a border needs at least {}",
                reference.len(),
                close_core::border::MIN_VERTICES
            ),
        ));
    }
    let reference = req
        .reference
        .as_deref()
        .map(|r| [&b"reference"[..], &coordinate_bytes(r)].concat())
        .unwrap_or_default();
    let scale = match req.scale {
        Some(s) => Some(Scale::fixed(s.s, s.max).ok_or_else(|| {
            ApiError::BadRequest("\"scale\" needs s > 0 and max ≥ 0, both finite".into())
        })?),
        None => None,
    };
    let scale_bytes: Vec<u8> =
        scale.iter().flat_map(|s| [s.s, s.max]).flat_map(f64::to_le_bytes).collect();
    let title = req.title.unwrap_or_else(|| "dGLI disk · current state".into());
    if title.chars().count() > MAX_TITLE {
        return Err(ApiError::BadRequest(format!(
            "\"title\" has {} characters: at most {MAX_TITLE}",
            title.chars().count()
        )));
    }
    if let Some(minus) = &req.minus {
        if minus.border.len() != req.border.len() {
            return Err(ApiError::Rejected(
                axum::http::StatusCode::UNPROCESSABLE_ENTITY,
                format!(
                    "a difference of two disks needs two borders of as many vertices: {} and {}",
                    req.border.len(),
                    minus.border.len()
                ),
            ));
        }
    }
    let minus_bytes = minus_key(req.minus.as_ref());
    let key = content_key(&[
        b"disk",
        &coordinate_bytes(&req.border),
        &reference,
        &size.to_le_bytes(),
        &scale_bytes,
        format.content_type().as_bytes(),
        title.as_bytes(),
        &minus_bytes,
    ]);
    let n = req.border.len() as u64;
    let cells = n * n * if req.minus.is_some() { 2 } else { 1 };
    let cached = state
        .cached_bytes(key, cells, move |deadline| {
            let disk = state_disk(req.border, req.reference, req.minus, deadline)?;
            let output = Output { format, ..Output::png(size) };
            let (file, used) = render_disk(&disk, &title, scale, &output)?;
            Ok(DiskPicture { scale: [used.s, used.max], file: file.into() }.into_bytes())
        })
        .await?;
    Ok(DiskPicture::from_bytes(cached).into_response(format))
}

/// `POST /api/disk/cells`: the values of the disk `POST /api/disk` draws for the same
/// request, and where its disk lies on a picture of that size (the `scale` is not needed).
pub async fn disk_cells(
    State(state): State<AppState>,
    AppJson(req): AppJson<DiskRequest>,
) -> Result<JsonBytes, ApiError> {
    let size = picture_size(req.size);
    let reference = req
        .reference
        .as_deref()
        .map(|r| [&b"reference"[..], &coordinate_bytes(r)].concat())
        .unwrap_or_default();
    let minus_bytes = minus_key(req.minus.as_ref());
    let key = content_key(&[
        b"disk cells",
        &coordinate_bytes(&req.border),
        &reference,
        &size.to_le_bytes(),
        &minus_bytes,
    ]);
    let n = req.border.len() as u64;
    let answer = state
        .cached_bytes(key, n * n, move |deadline| {
            close_render::readout::within_limit(1, req.border.len())?;
            let disk = state_disk(req.border, req.reference, req.minus, deadline)?;
            Ok(to_json(&close_render::readout::DiskCells::of(&disk, size)?)?.to_vec())
        })
        .await?;
    Ok(JsonBytes(answer))
}

/// The analysed state a plan or a verification starts from: `sample` is a Sample JSON
/// object (analysed once, on a worker, and cached by its bytes), the id of a listed sample,
/// or the `key` of an analysis still cached.
async fn drawing_of(state: &AppState, sample: Box<RawValue>) -> Result<Arc<Drawing>, ApiError> {
    let raw = sample.get();
    let drawing =
        match raw.trim_start().as_bytes().first() {
            // An analysis still cached (an upload's "key") or a listed sample's id.
            Some(b'"') => {
                let id: String = serde_json::from_str(raw)
                    .map_err(|e| ApiError::BadRequest(format!("\"sample\": {e}")))?;
                match state.drawing(&id) {
                    Some(hit) => hit,
                    None if state.entry(&id).is_some() || state.catalog().get(&id).is_some() => {
                        sample_analysis(state, &id).await?.drawing.clone()
                    }
                    None if state.uploads().is_some()
                        && state.uploads().is_some_and(|u| u.has(&id)) =>
                    {
                        kept_analysis(state, &id).await?.drawing.clone()
                    }
                    None => sample_analysis(state, &id).await?.drawing.clone(),
                }
            }
            Some(b'{') => {
                let key = content_key(&[b"plan", raw.as_bytes()]);
                let budget = state.config().budget;
                analysis(state, key, move |key, _| {
                    Loaded::of(
                        key,
                        &parse_sample(sample.get().as_bytes())?,
                        FrameRange::default(),
                        UPLOAD,
                        None,
                        &budget,
                    )
                })
                .await?
                .drawing
                .clone()
            }
            _ => return Err(ApiError::BadRequest(
                "\"sample\" must be a Sample JSON object, a listed sample id or an analysis key"
                    .into(),
            )),
        };
    Ok(drawing)
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanRequest {
    /// A Sample JSON object, the id of a built-in sample, or the `key` of an analysis; kept
    /// raw so a sample is parsed once, on a worker.
    sample: Box<RawValue>,
    goal: Goal,
}

/// A plan's goal: one fold `[g1, g2]`, or folds made in order `[[g1, g2], …]`.
#[derive(Debug, Deserialize)]
#[serde(untagged, expecting = "a goal fold [g1, g2] or a list of them [[g1, g2], …]")]
enum Goal {
    One(Fold),
    Sequence(Vec<Fold>),
}

/// Most folds a goal may hold: each is a step of the plan.
const MAX_GOAL_FOLDS: usize = close_core::fold::sequence::MAX_FOLDS * 4;

pub async fn plan(
    State(state): State<AppState>,
    AppJson(req): AppJson<PlanRequest>,
) -> Result<JsonBytes, ApiError> {
    let goal = match req.goal {
        Goal::One(fold) => vec![fold],
        Goal::Sequence(folds) => folds,
    };
    if goal.len() > MAX_GOAL_FOLDS {
        return Err(Error::too_large("goal folds", goal.len(), MAX_GOAL_FOLDS).into());
    }
    if let Some(k) = goal.iter().position(|g| !g.is_finite()) {
        return Err(
            Error::InvalidArgument(format!("goal fold {} needs two finite angles", k + 1)).into()
        );
    }
    let drawing = drawing_of(&state, req.sample).await?;
    let answer = state
        .run_cpu(Lane::Light, move |_| {
            let answer = close_core::plan::answer(&drawing.analysis, &goal)?;
            let states =
                close_render::cloth::plan_states(&drawing.analysis, answer.case, &answer.steps)?;
            to_json(&PlanAnswer { answer, states })
        })
        .await?;
    Ok(JsonBytes(answer))
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VerifyRequest {
    /// As [`PlanRequest::sample`]: the observed state.
    sample: Box<RawValue>,
    /// The goal folds in order, each [g1, g2] in radians.
    goal: Vec<[f64; 2]>,
    /// The line each goal fold is made along, where known (`null` entries: through its points).
    #[serde(default)]
    lines: Vec<Option<close_core::Line>>,
    #[serde(default)]
    tolerance: close_core::verify::Tolerance,
}

/// `POST /api/verify`: the sample's end state against the goal folds
/// ([`close_core::verify::verify`]).
pub async fn verify(
    State(state): State<AppState>,
    AppJson(req): AppJson<VerifyRequest>,
) -> Result<JsonBytes, ApiError> {
    let goal = close_core::verify::Goal { folds: req.goal, lines: req.lines };
    // The goal is checked before the sample is analysed: a bad goal costs nothing.
    close_core::verify::check_goal(&goal, None)?;
    let drawing = drawing_of(&state, req.sample).await?;
    let tolerance = req.tolerance;
    let answer = state
        .run_cpu(Lane::Light, move |_| {
            to_json(&close_core::verify::verify(&drawing.analysis, &goal, tolerance)?)
        })
        .await?;
    Ok(JsonBytes(answer))
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DistanceRequest {
    /// Two states of one cloth: each its folds in order, [f1, f2] in radians.
    a: Vec<[f64; 2]>,
    b: Vec<[f64; 2]>,
    /// The cloth's flat border, for the geometric distance too.
    #[serde(default)]
    border: Option<Vec<[f64; 3]>>,
}

/// `POST /api/distance`: {`folds`, `geometric`} between two states of one cloth
/// ([`close_core::distance`]).
pub async fn distance(
    State(state): State<AppState>,
    AppJson(req): AppJson<DistanceRequest>,
) -> Result<JsonBytes, ApiError> {
    use close_core::distance::{check_folds, fold_distance, geometric_distance, Distance};
    for (name, folds) in [("a", &req.a), ("b", &req.b)] {
        if folds.len() > close_core::distance::MAX_BATCH_FOLDS {
            return Err(Error::too_large(
                "folds",
                folds.len(),
                close_core::distance::MAX_BATCH_FOLDS,
            )
            .into());
        }
        check_folds(name, folds, 0.0)?;
    }
    let answer = state
        .run_cpu(Lane::Light, move |_| {
            // The border is checked as every border (at most MAX_VERTICES vertices); the
            // work is then O(N · folds).
            let geometric = match req.border {
                Some(border) => {
                    let flat = close_core::border::prepare(vec![border])?;
                    Some(geometric_distance(&flat.frames[0], &req.a, &req.b)?)
                }
                None => None,
            };
            to_json(&Distance { folds: fold_distance(&req.a, &req.b), geometric })
        })
        .await?;
    Ok(JsonBytes(answer))
}
