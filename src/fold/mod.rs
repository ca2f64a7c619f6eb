//! Fold coordinates from the dGLI disks.
//!
//! One step (start frame → end frame) is read from the abs diff disk
//! g = | |end| − |start| |: fold curves are fitted with the paper's loss ([`loss`], [`fit`]),
//! the two lowest-loss distinct curves give the two fold coordinates at the rim, and the
//! signed diff Δ = end − start orders them ([`orientation`]). A step whose diff disk is flat
//! (nothing changed) or shows fewer than two curves has no fold.
//!
//! Honesty rule (SPEC §1): nothing here sees a border, only disks.

pub mod fit;
pub mod loss;
pub mod orientation;
pub mod reflect;

use serde::Serialize;

pub use fit::Curve;
pub use orientation::Orientation;

use crate::disk::Disk;

/// A diff disk whose largest cell is below this has no fold.
pub const FLAT_DIFF: f64 = 1e-6;

/// What one step's fold detection found, with the evidence for drawing and debugging.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FoldDetection {
    /// (f1, f2) in [0, 2π), the folded side anticlockwise from f1; `None` without a fold.
    pub fold: Option<[f64; 2]>,
    /// Every distinct curve found, lowest loss first.
    pub curves: Vec<Curve>,
    pub orientation: Option<Orientation>,
}

/// Detect the fold between a start disk and an end disk of the same border.
pub fn detect(start: &Disk, end: &Disk) -> FoldDetection {
    let g = start.abs_diff(end);
    if g.values().iter().all(|&v| v <= FLAT_DIFF) {
        return FoldDetection { fold: None, curves: Vec::new(), orientation: None };
    }
    let curves = fit::fit_curves(&g);
    if curves.len() < 2 {
        return FoldDetection { fold: None, curves, orientation: None };
    }
    let (fold, orientation) = orientation::orient(start, end, curves[0].rim, curves[1].rim);
    FoldDetection { fold: Some(fold), curves, orientation: Some(orientation) }
}
