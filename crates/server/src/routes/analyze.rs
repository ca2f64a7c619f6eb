//! `POST /api/analyze`: a sample uploaded as a Sample JSON body or as files, analysed under
//! its content's key.

use axum::body::Bytes;
use axum::extract::{FromRequest, Multipart, Request, State};
use axum::http::header;
use serde::Deserialize;

use super::analysis::{analysis, Loaded, UPLOAD};
use super::json::JsonBytes;
use crate::state::AppState;
use crate::{ApiError, AppQuery};
use close_core::analysis::FrameRange;
use close_core::error::Error;
use close_io::cache::content_key;
use close_io::formats::{json::parse_sample, read_files, Sample};

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
