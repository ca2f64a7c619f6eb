//! The handlers of the HTTP API (SPEC §4).

use std::sync::Arc;

use axum::body::Bytes;
use axum::extract::rejection::{JsonRejection, PathRejection, QueryRejection};
use axum::extract::{FromRequest, Multipart, Path, Query, Request, State};
use axum::http::{header, Uri};
use axum::response::{IntoResponse, Response};
use axum::Json;
use serde::Deserialize;
use serde_json::{json, Value};

use super::cache::content_key;
use super::{ApiError, AppState};
use crate::analysis::{analyze as run_analysis, Analysis, FrameRange};
use crate::border::{prepare, Normalisation, Point};
use crate::disk::Disk;
use crate::error::Error;
use crate::formats::{json::parse_sample, read_files, Sample};
use crate::render::colour::Scale;
use crate::render::{disk_png_scaled, render_step_png, Picture, DEFAULT_SIZE, MAX_SIZE, MIN_SIZE};

/// Most vertices × steps an interpolation may return (its JSON grows with both).
const MAX_INTERPOLATED_POINTS: usize = 2_000_000;
/// Thumbnail size in the sample list.
const THUMBNAIL_SIZE: u32 = 160;
/// Cache keys of built-in samples start with this; uploads are hex digests.
const SAMPLE_KEY: &str = "sample:";

/// An analysis, with the response JSON already written (a cache hit costs a copy).
pub struct Analyzed {
    pub key: String,
    pub analysis: Analysis,
    pub response: Bytes,
}

impl Analyzed {
    /// Roughly the memory it holds: the frames and the response.
    pub fn bytes(&self) -> usize {
        let a = &self.analysis;
        let floats = 3 * a.frames.iter().map(Vec::len).sum::<usize>();
        8 * floats + self.response.len()
    }
}

fn points(border: &[Point]) -> Vec<[f64; 3]> {
    border.iter().map(|p| [p.x, p.y, p.z]).collect()
}

/// Analyse `sample` and write the response: the CLI's JSON plus what the app draws.
pub(super) fn analyzed(key: String, sample: &Sample, range: FrameRange, extra: Value) -> Result<Analyzed, ApiError> {
    let analysis = run_analysis(&sample.border_frames()?, range)?;
    let mut body = serde_json::to_value(&analysis).map_err(|e| ApiError::Internal(e.to_string()))?;
    let images: serde_json::Map<String, Value> =
        Picture::ALL.iter().map(|p| (p.name().to_string(), format!("/api/images/{key}/{}.png?size={DEFAULT_SIZE}", p.name()).into())).collect();
    let fields = [
        ("key", json!(key)),
        ("name", json!(sample.name)),
        ("category", json!(sample.category)),
        ("frames", json!(frame_count(sample))),
        ("start_border", json!(points(analysis.start_border()))),
        ("end_border", json!(points(analysis.end_border()))),
        ("images", Value::Object(images)),
    ];
    if let (Value::Object(map), Value::Object(more)) = (&mut body, extra) {
        map.extend(fields.into_iter().map(|(k, v)| (k.to_string(), v)));
        map.extend(more);
    }
    let response = Bytes::from(serde_json::to_vec(&body).map_err(|e| ApiError::Internal(e.to_string()))?);
    Ok(Analyzed { key, analysis, response })
}

pub(super) fn json_response(body: Bytes) -> Response {
    ([(header::CONTENT_TYPE, "application/json")], body).into_response()
}

pub async fn healthz() -> Json<Value> {
    Json(json!({ "status": "ok" }))
}

pub async fn not_found(uri: Uri) -> ApiError {
    ApiError::NotFound(format!("no route {}", uri.path()))
}

/// Optional frame range of `POST /api/analyze`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RangeQuery {
    start: Option<usize>,
    end: Option<usize>,
}

/// What an analyze request brought: a Sample JSON body, or named files.
enum Upload {
    Json(Bytes),
    Files(Vec<(String, Vec<u8>)>),
}

impl Upload {
    async fn from_request(request: Request, state: &AppState) -> Result<Upload, ApiError> {
        let content_type = request.headers().get(header::CONTENT_TYPE).and_then(|t| t.to_str().ok()).unwrap_or("").to_ascii_lowercase();
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

    /// Form files `sample` (one or more), or `start` and `end`.
    async fn files(mut form: Multipart) -> Result<Upload, ApiError> {
        let (mut samples, mut start, mut end) = (Vec::new(), None, None);
        while let Some(field) = form.next_field().await? {
            let name = field.name().unwrap_or_default().to_string();
            let file = field.file_name().filter(|f| !f.is_empty()).map(str::to_string);
            let bytes = field.bytes().await?.to_vec();
            match name.as_str() {
                "sample" => samples.push((file.unwrap_or_else(|| "sample.json".into()), bytes)),
                "start" => start = Some((file.unwrap_or_else(|| "start.txt".into()), bytes)),
                "end" => end = Some((file.unwrap_or_else(|| "end.txt".into()), bytes)),
                other => return Err(ApiError::BadRequest(format!("unknown form field {other:?}: send files named \"sample\", or \"start\" and \"end\""))),
            }
        }
        let files = match (samples.is_empty(), start, end) {
            (false, None, None) => samples,
            (false, _, _) => return Err(ApiError::BadRequest("send either \"sample\" or \"start\"/\"end\" files, not both".into())),
            (true, Some(s), e) => std::iter::once(s).chain(e).collect(),
            (true, None, Some(_)) => return Err(ApiError::BadRequest("an \"end\" file needs a \"start\" file".into())),
            (true, None, None) => return Err(Error::Empty { what: "the form holds no file: send \"sample\", or \"start\" and \"end\"" }.into()),
        };
        Ok(Upload::Files(files))
    }

    /// Content key of the upload and the frame range.
    fn key(&self, range: &RangeQuery) -> String {
        let range = format!("{:?}-{:?}", range.start, range.end);
        match self {
            Upload::Json(bytes) => content_key(&[b"json", bytes, range.as_bytes()]),
            Upload::Files(files) => {
                let mut parts: Vec<&[u8]> = vec![b"files", range.as_bytes()];
                parts.extend(files.iter().flat_map(|(name, bytes)| [name.as_bytes(), bytes.as_slice()]));
                content_key(&parts)
            }
        }
    }

    fn sample(&self) -> Result<Sample, Error> {
        match self {
            Upload::Json(bytes) => parse_sample(bytes),
            Upload::Files(files) => read_files(files),
        }
    }
}

pub async fn analyze(
    State(state): State<AppState>,
    range: Result<Query<RangeQuery>, QueryRejection>,
    request: Request,
) -> Result<Response, ApiError> {
    let Query(range) = range?;
    let upload = Upload::from_request(request, &state).await?;
    let key = upload.key(&range);
    let range = FrameRange { start: range.start, end: range.end };
    let done = state.analysis(key, move |key| analyzed(key, &upload.sample()?, range, json!({}))).await?;
    Ok(json_response(done.response.clone()))
}

/// Frames of a border or mesh sample.
fn frame_count(sample: &Sample) -> usize {
    sample.mesh.as_ref().map_or(sample.frames.len(), |m| m.frames.len())
}

pub async fn samples(State(state): State<AppState>) -> Json<Value> {
    let list: Vec<Value> = state
        .dataset()
        .entries()
        .iter()
        .map(|e| {
            json!({
                "id": e.id,
                "name": e.sample.name,
                "category": e.sample.category,
                "n": e.sample.border_frames().map_or(0, |b| b.len()),
                "frames": frame_count(&e.sample),
                "mesh": e.sample.mesh.is_some(),
                "thumbnail": format!("/api/images/{SAMPLE_KEY}{}/thumbnail.png?size={THUMBNAIL_SIZE}", e.id),
            })
        })
        .collect();
    Json(json!({ "samples": list }))
}

/// The analysis of built-in sample `id`, cached under its id.
async fn sample_analysis(state: &AppState, id: &str) -> Result<Arc<super::Analyzed>, ApiError> {
    let entry = state.dataset().get(id).cloned().ok_or_else(|| ApiError::NotFound(format!("no built-in sample {id:?}; GET /api/samples lists them")))?;
    state
        .analysis(format!("{SAMPLE_KEY}{id}"), move |key| {
            let mut extra = json!({ "id": entry.id, "sample": entry.sample });
            if cfg!(feature = "rerun") {
                extra["recording"] = json!(format!("/api/samples/{}/recording.rrd", entry.id));
            }
            analyzed(key, &entry.sample, FrameRange::default(), extra)
        })
        .await
}

pub async fn sample(State(state): State<AppState>, id: Result<Path<String>, PathRejection>) -> Result<Response, ApiError> {
    let Path(id) = id?;
    Ok(json_response(sample_analysis(&state, &id).await?.response.clone()))
}

/// `GET /api/samples/{id}/recording.rrd`: the sample's analysis as a Rerun recording.
#[cfg(feature = "rerun")]
pub async fn recording(State(state): State<AppState>, id: Result<Path<String>, PathRejection>) -> Result<Response, ApiError> {
    let Path(id) = id?;
    let analyzed = sample_analysis(&state, &id).await?;
    let entry = state.dataset().get(&id).cloned().ok_or_else(|| ApiError::NotFound(format!("no built-in sample {id:?}")))?;
    let rrd = state
        .cached_bytes(format!("{}/recording.rrd", analyzed.key), move || {
            Ok(crate::record::record(&analyzed.analysis, &entry.sample.border_frames()?)?)
        })
        .await?;
    let disposition = format!("attachment; filename=\"{}.rrd\"", id.replace(|c: char| !c.is_ascii_alphanumeric() && c != '_' && c != '-', "_"));
    Ok(([(header::CONTENT_TYPE, "application/octet-stream".to_string()), (header::CONTENT_DISPOSITION, disposition)], rrd).into_response())
}

/// Without the `rerun` feature there is no recording to give: say why.
#[cfg(not(feature = "rerun"))]
pub async fn recording(id: Result<Path<String>, PathRejection>) -> ApiError {
    let name = id.map(|Path(id)| id).unwrap_or_default();
    ApiError::NotFound(format!(
        "no recording of {name:?}: this server was built without the `rerun` feature (cargo run --features rerun)"
    ))
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImageQuery {
    size: Option<u32>,
    /// One step's disk pictures (1-based: step k goes from analysed frame k − 1 to k).
    step: Option<usize>,
}

pub async fn image(
    State(state): State<AppState>,
    path: Result<Path<(String, String)>, PathRejection>,
    query: Result<Query<ImageQuery>, QueryRejection>,
) -> Result<Response, ApiError> {
    let (Path((key, file)), Query(query)) = (path?, query?);
    let picture = file.strip_suffix(".png").and_then(Picture::from_name).ok_or_else(|| {
        let names: Vec<&str> = Picture::ALL.iter().map(|p| p.name()).collect();
        ApiError::NotFound(format!("no picture {file:?}: expected one of {}.png", names.join(".png, ")))
    })?;
    let analyzed = match (state.cached_analysis(&key), key.strip_prefix(SAMPLE_KEY)) {
        (Some(hit), _) => hit,
        (None, Some(id)) => sample_analysis(&state, id).await?,
        (None, None) => return Err(ApiError::NotFound(format!("no analysis {key:?} (it may have expired): analyse the sample again"))),
    };
    let (size, step) = (query.size.unwrap_or(DEFAULT_SIZE), query.step);
    let png = state
        .cached_bytes(format!("{key}/{}/{size}/{step:?}", picture.name()), move || {
            Ok(render_step_png(&analyzed.analysis, picture, step, size, size)?)
        })
        .await?;
    // The key names the content, so the picture never changes.
    Ok(([(header::CONTENT_TYPE, "image/png"), (header::CACHE_CONTROL, "public, max-age=86400, immutable")], png).into_response())
}

fn default_steps() -> usize {
    60
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InterpolateRequest {
    border: Vec<[f64; 3]>,
    from: [f64; 2],
    to: [f64; 2],
    #[serde(default = "default_steps")]
    steps: usize,
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
}

/// The answer of `POST /api/disk`: the PNG, and in the header `x-disk-scale` the colour
/// scale it used ("s max"), which a later request can send back as `scale`.
fn disk_response(cached: Bytes) -> Response {
    // The cache holds the scale's two floats ahead of the PNG.
    let (head, png) = cached.split_at(16.min(cached.len()));
    let float = |k: usize| head.get(8 * k..8 * k + 8).and_then(|b| b.try_into().ok()).map_or(0.0, f64::from_le_bytes);
    let scale = format!("{} {}", float(0), float(1));
    ([(header::CONTENT_TYPE, "image/png".to_string()), (header::CACHE_CONTROL, "no-store".to_string()), (DISK_SCALE, scale)], Bytes::copy_from_slice(png))
        .into_response()
}

/// The header naming the colour scale of a disk picture.
const DISK_SCALE: header::HeaderName = header::HeaderName::from_static("x-disk-scale");

fn coordinate_bytes(points: &[[f64; 3]]) -> Vec<u8> {
    points.iter().flatten().flat_map(|c| c.to_le_bytes()).collect()
}

pub async fn disk(State(state): State<AppState>, body: Result<Json<DiskRequest>, JsonRejection>) -> Result<Response, ApiError> {
    let Json(req) = body?;
    let size = req.size.unwrap_or(DEFAULT_SIZE).clamp(MIN_SIZE, MAX_SIZE);
    let reference = req.reference.as_deref().map(coordinate_bytes).unwrap_or_default();
    let scale = match req.scale {
        Some(s) => Some(Scale::fixed(s.s, s.max).ok_or_else(|| ApiError::BadRequest("\"scale\" needs s > 0 and max ≥ 0, both finite".into()))?),
        None => None,
    };
    let scale_bytes: Vec<u8> = scale.iter().flat_map(|s| [s.s, s.max]).flat_map(f64::to_le_bytes).collect();
    let key = content_key(&[b"disk", &coordinate_bytes(&req.border), &reference, &size.to_le_bytes(), &scale_bytes]);
    let cached = state
        .cached_bytes(key, move || {
            let frames = match req.reference {
                Some(reference) => vec![reference, req.border],
                None => vec![req.border],
            };
            let border = prepare(frames)?;
            let (start, now) = (&border.frames[0], &border.frames[border.frames.len() - 1]);
            let disk = Disk::of_border(&Normalisation::of(start)?.apply_all(now));
            let (png, used) = disk_png_scaled(&disk, "dGLI disk · current state", scale, size, size)?;
            Ok([used.s, used.max].iter().flat_map(|v| v.to_le_bytes()).chain(png).collect())
        })
        .await?;
    Ok(disk_response(cached))
}

pub async fn interpolate(State(state): State<AppState>, body: Result<Json<InterpolateRequest>, JsonRejection>) -> Result<Json<Value>, ApiError> {
    let Json(req) = body?;
    if req.border.len().saturating_mul(req.steps) > MAX_INTERPOLATED_POINTS {
        return Err(Error::too_large("points in one answer (vertices × steps)", req.border.len().saturating_mul(req.steps), MAX_INTERPOLATED_POINTS).into());
    }
    let border: Vec<Point> = req.border.iter().map(|&p| Point::from(p)).collect();
    let motion = state.run_cpu(move || Ok(crate::interpolate::interpolate(&border, req.from, req.to, req.steps)?)).await?;
    Ok(Json(json!(motion)))
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanRequest {
    /// A Sample JSON object, the id of a built-in sample, or the `key` of an analysis.
    sample: Value,
    goal: [f64; 2],
}

pub async fn plan(State(state): State<AppState>, body: Result<Json<PlanRequest>, JsonRejection>) -> Result<Json<Value>, ApiError> {
    let Json(req) = body?;
    if req.goal.iter().any(|g| !g.is_finite()) {
        return Err(Error::InvalidArgument("the goal fold needs two finite angles".into()).into());
    }
    let analyzed = match req.sample {
        // An analysis still cached (an upload's "key") or a built-in sample's id.
        Value::String(id) => match state.cached_analysis(&id) {
            Some(hit) => hit,
            None => sample_analysis(&state, &id).await?,
        },
        Value::Object(_) => {
            let sample = parse_sample(req.sample.to_string().as_bytes())?;
            let key = content_key(&[b"plan", &serde_json::to_vec(&sample).unwrap_or_default()]);
            state.analysis(key, move |key| analyzed(key, &sample, FrameRange::default(), json!({}))).await?
        }
        _ => return Err(ApiError::BadRequest("\"sample\" must be a Sample JSON object, a built-in sample id or an analysis key".into())),
    };
    let goal = req.goal;
    let result = state
        .run_cpu(move || {
            let a = &analyzed.analysis;
            let mut plan = crate::plan::plan(a.start_border(), &a.corner_vertices, &a.folds, goal)?;
            // The planner counts border vertices; the user knows their input's indices.
            for pick in plan.steps.iter_mut().flat_map(|s| s.picks.iter_mut()) {
                pick.vertex = a.border_indices.get(pick.vertex).copied().unwrap_or(pick.vertex);
            }
            Ok(json!({
                "case": plan.case,
                "steps": plan.steps,
                "goal": goal,
                "folds": a.folds,
                "corners": a.corners,
                "start_border": points(a.start_border()),
                "border_indices": a.border_indices,
            }))
        })
        .await?;
    Ok(Json(result))
}
