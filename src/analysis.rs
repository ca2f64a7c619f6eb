//! The whole pipeline of `close analyze`: frames in, CloSE, label, prediction and metrics out.
//!
//! Frames K_start … K_end of a prepared sample are each turned into a dGLI disk, on
//! borders normalised by the START frame's transform (dGLI scales with 1/size). Step k
//! (frame k−1 → k) gives at most one fold. The predicted end applies the folds in order to
//! the start border, in the input's coordinates.

use nalgebra::Point3;
use rayon::prelude::*;
use serde::Serialize;

use crate::border::{BorderFrames, Normalisation, Point};
use crate::close::{corners, Corners};
use crate::disk::Disk;
use crate::error::{Error, Result};
use crate::fold::{detect, reflect::apply_fold, FoldDetection, FoldMethod};
use crate::label::{label, Label};
use crate::metrics::Metrics;

/// Which frames to analyse (defaults: first and last).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct FrameRange {
    pub start: Option<usize>,
    pub end: Option<usize>,
}

/// How to analyse: which frames, and how fold points are chosen.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Options {
    pub frames: FrameRange,
    pub method: FoldMethod,
}

/// One step between consecutive frames.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Step {
    pub from_frame: usize,
    pub to_frame: usize,
    #[serde(flatten)]
    pub detection: FoldDetection,
    /// The start border with the folds found up to this step applied, against this
    /// step's true end frame.
    pub metrics: Metrics,
}

/// Everything `close analyze` reports.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Analysis {
    /// Border vertex count.
    pub n: usize,
    /// Corner angles (radians, increasing).
    pub corners: Vec<f64>,
    pub corner_vertices: Vec<usize>,
    pub corner_threshold: f64,
    /// One [f1, f2] per detected fold, in order.
    pub folds: Vec<[f64; 2]>,
    pub label: Label,
    pub border_indices: Vec<usize>,
    /// Where the border came from ("border", "mesh boundary loop", "mesh silhouette", …).
    pub border_source: String,
    /// True when the input was clockwise and was walked the other way.
    pub reversed: bool,
    pub warnings: Vec<String>,
    pub start_frame: usize,
    pub end_frame: usize,
    pub steps: Vec<Step>,
    /// The start border with the folds applied, input coordinates, border order.
    pub predicted_end: Vec<[f64; 3]>,
    pub metrics: Option<Metrics>,
    /// Start and end borders (input coordinates, border order), for drawing.
    #[serde(skip)]
    pub start_border: Vec<Point>,
    #[serde(skip)]
    pub end_border: Vec<Point>,
    #[serde(skip)]
    pub disk_start: Disk,
    #[serde(skip)]
    pub disk_end: Disk,
}

impl Analysis {
    /// The CloSE of the end state.
    pub fn close(&self) -> crate::close::Close {
        crate::close::Close { corners: self.corners.clone(), folds: self.folds.clone() }
    }
}

fn to_array(p: &Point3<f64>) -> [f64; 3] {
    [p.x, p.y, p.z]
}

/// Analyse frames `range` of a prepared sample.
pub fn analyze(sample: &BorderFrames, range: FrameRange) -> Result<Analysis> {
    analyze_with(sample, Options { frames: range, ..Options::default() })
}

/// Analyse with explicit [`Options`].
pub fn analyze_with(sample: &BorderFrames, options: Options) -> Result<Analysis> {
    let range = options.frames;
    let last = sample.frames.len() - 1;
    let start = range.start.unwrap_or(0);
    let end = range.end.unwrap_or(last);
    if start > last || end > last {
        return Err(Error::InvalidArgument(format!("frame {} does not exist (the sample has frames 0…{last})", start.max(end))));
    }
    if end < start {
        return Err(Error::InvalidArgument(format!("end frame {end} comes before start frame {start}")));
    }
    let start_border = &sample.frames[start];
    let norm = Normalisation::of(start_border)?;
    let disks: Vec<Disk> = (start..=end).into_par_iter().map(|k| Disk::of_border(&norm.apply_all(&sample.frames[k]))).collect();
    let found: Corners = corners(&disks[0]);
    let mut predicted = start_border.clone();
    let mut steps = Vec::with_capacity(disks.len().saturating_sub(1));
    for (k, pair) in disks.windows(2).enumerate() {
        let detection = detect(&pair[0], &pair[1], options.method);
        if let Some(fold) = detection.fold {
            predicted = apply_fold(&predicted, fold);
        }
        let to_frame = start + k + 1;
        let metrics = Metrics::measure(&norm, &predicted, &sample.frames[to_frame]);
        steps.push(Step { from_frame: start + k, to_frame, detection, metrics });
    }
    let folds: Vec<[f64; 2]> = steps.iter().filter_map(|s| s.detection.fold).collect();
    let end_border = &sample.frames[end];
    let metrics = steps.last().map(|s| s.metrics);
    let n = sample.len();
    let label = label(n, &found.vertices, &folds);
    let mut disks = disks;
    let disk_end = disks.pop().expect("at least one frame");
    let disk_start = if disks.is_empty() { disk_end.clone() } else { disks.swap_remove(0) };
    Ok(Analysis {
        n,
        corners: found.angles,
        corner_vertices: found.vertices,
        corner_threshold: found.threshold,
        folds,
        label,
        border_indices: sample.border_indices.clone(),
        border_source: sample.source.clone(),
        reversed: sample.reversed,
        warnings: sample.warnings.clone(),
        start_frame: start,
        end_frame: end,
        steps,
        predicted_end: predicted.iter().map(to_array).collect(),
        metrics,
        start_border: start_border.clone(),
        end_border: end_border.clone(),
        disk_start,
        disk_end,
    })
}
