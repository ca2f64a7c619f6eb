//! An upload's analysis later, by the key its answer gave: cached, or analysed again from
//! the data folder (`close serve --data-dir`), or an error saying why it is gone.

use std::sync::Arc;

use axum::extract::State;

use super::analysis::{analysis, Loaded, UPLOAD};
use super::json::JsonBytes;
use super::samples::{sample_analysis, SAMPLE_KEY};
use crate::state::{Analyzed, AppState};
use crate::{ApiError, AppPath};
use close_core::analysis::FrameRange;

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
pub(super) async fn kept_analysis(state: &AppState, key: &str) -> Result<Arc<Analyzed>, ApiError> {
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
