//! Rerun recordings (feature `rerun`): an analysis as an `.rrd` for the Rerun viewer.
//!
//! Entities, on the `frame` sequence timeline (the input's frame numbers):
//! - `border`: each analysed frame's border as a closed 3D line strip;
//!   `predicted_end`: the start border with the folds applied, at the end frame;
//! - `fold/{k}/points` and `fold/{k}/line`: fold k's points P1, P2 on the border it folds
//!   (the start with folds 1…k−1 applied) and the chord between them, at its step's end frame;
//! - `close/f1`, `close/f2`: the fold coordinates (radians) as scalars, per step;
//!   `close/corners`: the corner count; `close/label`: the label text;
//! - `disk/start`, `disk/end`, `disk/diff`, `disk/signed_diff` (static): each disk unrolled
//!   in polar form as a tensor of L rows (ring d = 1, the rim, first) by 2N columns of
//!   width π/N: the cell of ring d starting at edge a is centred on angle π(2a + d + 1)/N,
//!   so it covers columns 2a + d and 2a + d + 1 (mod 2N).
//!
//! Open the file with `rerun recording.rrd` (the viewer of the same minor version, 0.36).
//! Tested in `tests/record.rs` (with the feature).
//!
//! ```no_run
//! # fn main() -> close_core::Result<()> {
//! use close_render::{analyze, FrameRange};
//! let sample = close_io::formats::json::parse_sample(&std::fs::read("sample.json").unwrap())?;
//! let frames = sample.border_frames()?;
//! let analysis = analyze(&frames, FrameRange::default())?;
//! std::fs::write("sample.rrd", close_render::record::record(&analysis, &frames)?).unwrap();
//! # Ok(()) }
//! ```

use rerun::datatypes::{TensorBuffer, TensorData};
use rerun::{
    LineStrips3D, Points3D, RecordingStream, RecordingStreamBuilder, Scalars, Tensor, TextDocument,
};

use crate::error::{Error, Result};
use close_core::analysis::Analysis;
use close_core::angle::angle_to_param;
use close_core::border::{point_at, BorderFrames, Point};
use close_core::disk::Disk;
use close_core::fold::apply;
use close_core::geometry::Folding;

/// Name of the frame timeline.
pub const TIMELINE: &str = "frame";

fn failed(e: impl std::fmt::Display) -> Error {
    Error::Recording(e.to_string())
}

fn xyz(p: &Point) -> [f32; 3] {
    [p.x as f32, p.y as f32, p.z as f32]
}

/// A border as one closed strip.
fn closed_strip(points: &[Point]) -> Vec<[f32; 3]> {
    points.iter().chain(points.first()).map(xyz).collect()
}

/// The disk unrolled in polar form (see the module doc), rows = rings from the rim.
pub fn polar_image(disk: &Disk) -> (usize, usize, Vec<f64>) {
    let (n, rings) = (disk.n(), disk.layers());
    let width = 2 * n;
    let mut image = vec![0.0; rings * width];
    for d in 1..=rings {
        for a in 0..n {
            let v = disk.ring_value(d, a);
            for c in [2 * a + d, 2 * a + d + 1] {
                image[(d - 1) * width + c % width] = v;
            }
        }
    }
    (rings, width, image)
}

fn log_disk(rec: &RecordingStream, path: &str, disk: &Disk) -> Result<()> {
    let (rows, cols, values) = polar_image(disk);
    let data = TensorData::new(vec![rows as u64, cols as u64], TensorBuffer::F64(values.into()))
        .with_dim_names(["ring (rim first)", "angle (π/N per column)"]);
    rec.log_static(path, &Tensor::new(data)).map_err(failed)
}

/// Record an analysis of `frames` as an in-memory `.rrd` file.
pub fn record(analysis: &Analysis, frames: &BorderFrames) -> Result<Vec<u8>> {
    let (rec, storage) =
        RecordingStreamBuilder::new("close").enabled(true).memory().map_err(failed)?;
    let (start, end) = (analysis.start_frame, analysis.end_frame);
    let Some(analysed) = frames.frames.get(start..=end) else {
        return Err(Error::invalid(format!(
            "the analysis covers frames {start}…{end}, the sample has {}",
            frames.frames.len()
        )));
    };
    for (k, border) in (start..).zip(analysed) {
        rec.set_time_sequence(TIMELINE, k as i64);
        rec.log("border", &LineStrips3D::new([closed_strip(border)])).map_err(failed)?;
    }

    rec.set_time_sequence(TIMELINE, start as i64);
    rec.log("close/corners", &Scalars::single(analysis.corners.len() as f64)).map_err(failed)?;
    rec.log("close/label", &TextDocument::new(analysis.label.text.clone())).map_err(failed)?;
    let n = analysis.n;
    let mut folded = analysis.start_border().to_vec();
    let steps = analysis.steps.iter().filter_map(|s| s.detection.fold.map(|f| (s.to_frame, f)));
    for (k, (frame, fold)) in steps.enumerate() {
        rec.set_time_sequence(TIMELINE, frame as i64);
        let ends = fold.ends().map(|f| xyz(&point_at(&folded, angle_to_param(f, n))));
        let base = format!("fold/{}", k + 1);
        rec.log(format!("{base}/points"), &Points3D::new(ends).with_labels(["f1", "f2"]))
            .map_err(failed)?;
        rec.log(format!("{base}/line"), &LineStrips3D::new([ends])).map_err(failed)?;
        rec.log("close/f1", &Scalars::single(fold.f1)).map_err(failed)?;
        rec.log("close/f2", &Scalars::single(fold.f2)).map_err(failed)?;
        folded = apply(&folded, &Folding::new(fold));
    }
    rec.set_time_sequence(TIMELINE, end as i64);
    rec.log("predicted_end", &LineStrips3D::new([closed_strip(&folded)])).map_err(failed)?;

    let missing = || Error::Recording("the analysis has no frame".into());
    let start = analysis.disk(0).ok_or_else(missing)?;
    let end = analysis.disk(analysis.frames.len() - 1).ok_or_else(missing)?;
    log_disk(&rec, "disk/start", &start)?;
    log_disk(&rec, "disk/end", &end)?;
    log_disk(&rec, "disk/diff", &start.abs_diff(&end))?;
    log_disk(&rec, "disk/signed_diff", &start.signed_diff(&end))?;
    storage.drain_as_bytes().map_err(failed)
}
