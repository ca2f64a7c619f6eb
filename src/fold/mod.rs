//! Fold coordinates from the dGLI disks.
//!
//! One step (start frame → end frame) is read from the abs diff disk
//! g = | |end| − |start| |: fold curves are fitted with the paper's loss ([`loss`], [`fit`]),
//! the two lowest-loss distinct curves give the two fold coordinates at the rim, and the
//! signed diff Δ = end − start orders them ([`orientation`]). A step whose diff disk is flat
//! (nothing changed) or shows fewer than two curves has no fold.
//!
//! Honesty rule (SPEC §1): nothing here sees a border, only disks.

pub mod cut;
pub mod fit;
pub mod loss;
pub mod orientation;
pub mod reflect;

use std::f64::consts::PI;

use serde::Serialize;

pub use cut::Cut;
pub use fit::Curve;
pub use orientation::Orientation;

use crate::disk::Disk;

/// A diff disk whose largest cell is below this has no fold.
pub const FLAT_DIFF: f64 = 1e-6;
/// A cut whose same-side pairs change this many times as much, on average, as the pairs
/// across it has no side to it: noise, not a fold. (Measured: folds with noise up to 1.5;
/// noise alone 3.6 and more.)
pub const MAX_SAME_TO_CROSS: f64 = 2.5;

/// How the two fold points are chosen.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FoldMethod {
    /// The cut of least same-side change ([`cut`]), refined on the rim within its edge.
    #[default]
    Cut,
    /// The paper's curves alone: the rims of the two lowest-loss curves ([`fit`]).
    Paper,
}

/// What one step's fold detection found, with the evidence for drawing and debugging.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FoldDetection {
    /// (f1, f2) in [0, 2π), the folded side anticlockwise from f1; `None` without a fold.
    pub fold: Option<[f64; 2]>,
    /// Every distinct curve the paper's loss found, lowest loss first.
    pub curves: Vec<Curve>,
    pub cut: Option<Cut>,
    pub orientation: Option<Orientation>,
}

/// Detect the fold between a start disk and an end disk of the same border.
pub fn detect(start: &Disk, end: &Disk, method: FoldMethod) -> FoldDetection {
    let g = start.abs_diff(end);
    let mut found = FoldDetection { fold: None, curves: Vec::new(), cut: None, orientation: None };
    if g.values().iter().all(|&v| v <= FLAT_DIFF) {
        return found;
    }
    found.curves = fit::fit_curves(&g);
    found.cut = cut::find_cut(&g);
    let points = match method {
        FoldMethod::Paper => (found.curves.len() >= 2).then(|| (found.curves[0].rim, found.curves[1].rim)),
        FoldMethod::Cut => found.cut.filter(|c| c.same_to_cross <= MAX_SAME_TO_CROSS).map(|c| refine_cut(&g, &c)),
    };
    if let Some((p, q)) = points {
        let (fold, orientation) = orientation::orient(start, end, p, q);
        found.fold = Some(fold);
        found.orientation = Some(orientation);
    }
    found
}

/// Angles of a cut's points; a point inside an edge is refined on the rim rings within it.
fn refine_cut(g: &Disk, cut: &Cut) -> (f64, f64) {
    let n = g.n();
    let to_angle = |p: f64| 2.0 * PI * p / n as f64;
    let rim = fit::rim_cells(g);
    let refine = |p: f64, inside: bool| {
        let a = to_angle(p);
        if !inside {
            return a;
        }
        let half = to_angle(0.5);
        fit::refine_rim(&rim, n, a, a - half, a + half).unwrap_or(a)
    };
    (refine(cut.p1, cut.inside_edge[0]), refine(cut.p2, cut.inside_edge[1]))
}
