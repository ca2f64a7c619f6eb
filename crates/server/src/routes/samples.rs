//! Listed samples (built-in or from a dataset): their rows' thumbnails, their analyses under
//! `sample:{id}`, and their Rerun recordings.

use std::sync::Arc;

use axum::extract::State;
#[cfg(feature = "rerun")]
use axum::http::header;
#[cfg(feature = "rerun")]
use axum::response::{IntoResponse, Response};

use super::analysis::{analysis, frame_count, Listed, Loaded, BUILTIN};
use super::json::JsonBytes;
#[cfg(feature = "rerun")]
use super::pictures::cells;
use crate::answer::SampleRow;
use crate::state::{Analyzed, AppState};
use crate::{ApiError, AppPath};
use close_core::analysis::FrameRange;
use close_core::border::BorderFrames;

/// Thumbnail size in the sample list.
const THUMBNAIL_SIZE: u32 = 160;
/// Cache keys of built-in samples start with this; uploads are hex digests.
pub(super) const SAMPLE_KEY: &str = "sample:";

impl SampleRow {
    pub(crate) fn builtin(e: &close_io::dataset::BuiltinSample) -> SampleRow {
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

    pub(crate) fn dataset(e: &close_io::catalog::Entry) -> SampleRow {
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
pub(super) async fn sample_analysis(state: &AppState, id: &str) -> Result<Arc<Analyzed>, ApiError> {
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
