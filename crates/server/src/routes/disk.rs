//! `POST /api/disk` and `POST /api/disk/cells`: the dGLI disk of any border state (or the
//! difference of two) as a picture, and its values.

use axum::body::Bytes;
use axum::extract::State;
use axum::http::header;
use axum::response::{IntoResponse, Response};
use serde::Deserialize;

use super::json::{to_json, JsonBytes};
use super::pictures::picture_size;
use crate::state::AppState;
use crate::{ApiError, AppJson, AppQuery};
use close_core::budget::Deadline;
use close_core::error::Result;
use close_io::cache::content_key;
use close_render::colour::Scale;
use close_render::{render_disk, Format, Output};

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
