//! An analysis's pictures (`GET /api/images/{key}/{picture}.png`), what reading values off
//! them takes (`GET /api/readout/{key}`), and which cell each pixel of a disk picture shows
//! (`GET /api/cells.png`).

use std::sync::Arc;

use axum::extract::State;
use axum::http::header;
use axum::response::{IntoResponse, Response};
use serde::Deserialize;

use super::json::{to_json, JsonBytes};
use super::samples::{sample_analysis, SAMPLE_KEY};
use super::uploads::kept_analysis;
use crate::state::{AppState, Drawing};
use crate::{ApiError, AppPath, AppQuery};
use close_core::analysis::Analysis;
use close_render::{
    render, Format, Known, Output, Picture, View, DEFAULT_SIZE, MAX_SIZE, MIN_SIZE,
};

/// dGLI cells of the pictures of `analysis` (two disks at most).
pub(super) fn cells(analysis: &Analysis) -> u64 {
    2 * (analysis.n as u64).pow(2)
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
pub(super) fn picture_size(asked: Option<u32>) -> u32 {
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
