//! The one fold a step's disks point to (Kamat, Borràs, Torras, "CloSE", Sec. III-C), which
//! seeds the search ([`super::read`]).
//!
//! One step (start state → end state) is read from the abs diff disk g = | |end| − |start| |. The
//! paper fits fold curves with its loss ([`super::loss`], [`fit`]); its free fit is kept as
//! [`FoldMethod::Paper`], and the curves of every fold found are fitted through its points, for
//! drawing. By default, on a flat start the cut of least same-side change ([`cut`]) says which
//! edges turned over, to half an edge, the signed diff Δ = end − start orders its points
//! ([`orientation`]), and analysis by synthesis on the disks ([`synth`]) places each fold point
//! within its edge. On a stacked start (an earlier fold) the cut loses its footing and the line
//! search ([`super::line_search`]) tries lines instead. A step whose diff disk is flat, or whose
//! change has no side to it, has no seed.

use serde::{Deserialize, Serialize};

use super::loss::RingTables;
use super::params::Params;
use super::{cut, fit, line_search, orientation, synth};
use super::{Curve, Cut, Orientation, Synthesis};
use crate::angle::{angle_to_param, param_to_angle, wrap_tau};
use crate::border::Point;
use crate::disk::Disk;
use crate::geometry::{Arc, Fold, Folding};

/// A start state whose heights span no more than this (normalised units) is flat: a
/// rounding tolerance, not a knob.
const FLAT_HEIGHT: f64 = 1e-9;

/// How the two fold points are chosen.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, serde::Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum FoldMethod {
    /// The cut of least same-side change (`cut`), placed within its edges by synthesis
    /// (`synth`); a line search on a stacked start.
    #[default]
    Cut,
    /// The paper's curves alone: the rims of the two lowest-loss curves (`fit`).
    Paper,
}

/// What a step's disks showed of its fold, for drawing and debugging: how the one fold it
/// was seeded with was found. The step's folds themselves are the search's answer
/// ([`super::read`]).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Evidence {
    /// The fold's curves on the diff disk. With [`FoldMethod::Cut`], the paper's curve through
    /// each fold point (`fit::curves_through`); with [`FoldMethod::Paper`], every distinct
    /// curve of the free fit, lowest loss first (`fit::fit_curves`), the first two giving the
    /// fold.
    pub curves: Vec<Curve>,
    pub cut: Option<Cut>,
    /// How the side was chosen; `None` when the start was stacked (the line search turns a
    /// known side over, the line search) or there is no fold.
    pub orientation: Option<Orientation>,
    /// The placement by synthesis (`synth`); its `direction` is set when the fold points
    /// coincide in the step's start frame and the line's direction came from the disks.
    pub synthesis: Option<Synthesis>,
}

/// A step's first fold and the evidence of its seed, as a step reports them: the first fold
/// repeats `folds[0]` of the step, and the evidence is [`Evidence`]'s, field by field (the
/// names a step's answer has carried since its first version).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct FoldDetection {
    /// (f1, f2) in [0, 2π), the folded side anticlockwise from f1: the step's first fold,
    /// `None` without a fold. For a fold of several arcs, the pair that spans them (the first
    /// point of the first arc, the last point of the last). In radians.
    pub fold: Option<Fold>,
    /// The arcs the first fold turned over, each [a, b] in [0, 2π) folded anticlockwise from
    /// a to b, in walking order from f1: `[fold]` when the fold line crosses the border
    /// twice, k arcs when it crosses 2k times (our extension of CloSE: a *multi-arc fold*).
    /// Empty without a fold. In radians.
    pub arcs: Vec<Arc>,
    /// [`Evidence::curves`].
    pub curves: Vec<Curve>,
    /// [`Evidence::cut`].
    pub cut: Option<Cut>,
    /// [`Evidence::orientation`].
    pub orientation: Option<Orientation>,
    /// [`Evidence::synthesis`].
    pub synthesis: Option<Synthesis>,
}

impl FoldDetection {
    /// The record of a step whose first fold is `first` (as made), seeded as `evidence` says.
    pub fn of(evidence: Evidence, first: Option<&Folding>) -> FoldDetection {
        let Evidence { curves, cut, orientation, synthesis } = evidence;
        FoldDetection {
            fold: first.map(|f| f.fold),
            arcs: first.map(|f| f.arcs.clone()).unwrap_or_default(),
            curves,
            cut,
            orientation,
            synthesis,
        }
    }
}

/// The one fold a step's disks point to before any is judged: its fold and arcs (angles).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Seed {
    pub(crate) fold: Fold,
    pub(crate) arcs: Vec<Arc>,
}

/// True when every vertex of `points` lies at one height (a cloth flat on the table).
pub(crate) fn is_flat(points: &[Point]) -> bool {
    let (lo, hi) = points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| (lo.min(p.z), hi.max(p.z)));
    hi - lo <= FLAT_HEIGHT
}

/// The one fold a step's disks point to, and the evidence for it: on a flat start the cut,
/// oriented and placed; on a stacked one the best of the lines turned over, each placed;
/// with [`FoldMethod::Paper`] the paper's two lowest curves, oriented. None when the diff
/// disk is flat ([`super::params::DetectParams::flat_diff`]), the cut has no side to it, or
/// no line explains the step.
///
/// `before` is the step's start border, normalised as the disks were (`start` is its disk);
/// `end` is the disk of the step's end state. Only disks are compared: `before` is the state
/// that candidate folds are applied to ([`synth`]), the end border is never seen.
pub(crate) fn seed(
    before: &[Point],
    start: &Disk,
    end: &Disk,
    method: FoldMethod,
    params: &Params,
) -> (Evidence, Option<Seed>) {
    let g = start.abs_diff(end);
    let mut evidence = Evidence::default();
    if g.values().iter().all(|&v| v <= params.detect.flat_diff) {
        return (evidence, None);
    }
    let n = g.n();
    // The loss is tabulated while the cut is searched and placed: both are independent and
    // neither fills both cores alone.
    let (tables, (cut, by_cut)) = rayon::join(
        || RingTables::new(&g, &params.curves),
        || {
            let cut = cut::find_cut(&g);
            let by_cut =
                (method == FoldMethod::Cut).then(|| fold_by_cut(before, start, end, cut, params));
            (cut, by_cut)
        },
    );
    evidence.cut = cut;
    let mut seed = None;
    match by_cut {
        None => {
            evidence.curves = fit::fit_curves(&g, &tables, params);
            if let [first, second, ..] = evidence.curves[..] {
                let (fold, orientation) =
                    orientation::orient(start, end, first.rim, second.rim, &params.detect);
                seed = Some(Seed { fold, arcs: vec![fold.arc()] });
                evidence.orientation = Some(orientation);
            }
        }
        Some((placed, orientation)) => {
            evidence.orientation = orientation;
            if let Some(placed) = placed {
                let angle = |[a, b]: [f64; 2]| [a, b].map(|s| wrap_tau(param_to_angle(s, n)));
                let fold = Fold::from(angle(placed.s));
                evidence.curves = fit::curves_through(&tables, n, fold);
                let arcs = placed.arcs.iter().map(|&arc| Arc::from(angle(arc))).collect();
                seed = Some(Seed { fold, arcs });
                evidence.synthesis = Some(placed);
            }
        }
    }
    (evidence, seed)
}

/// [`FoldMethod::Cut`]: on a flat start the cut, oriented, placed; on a stacked one the
/// best of the lines turned over, each placed. The orientation is `None` on a stacked start.
fn fold_by_cut(
    before: &[Point],
    start: &Disk,
    end: &Disk,
    cut: Option<Cut>,
    params: &Params,
) -> (Option<Synthesis>, Option<Orientation>) {
    let n = start.n();
    let synthesis = &params.synthesis;
    if is_flat(before) {
        let Some(cut) = cut.filter(|c| c.same_to_cross <= params.detect.max_same_to_cross) else {
            return (None, None);
        };
        let (p, q) = (param_to_angle(cut.p1, n), param_to_angle(cut.p2, n));
        let (fold, orientation) = orientation::orient(start, end, p, q, &params.detect);
        let s = [fold.f1, fold.f2].map(|f| angle_to_param(f, n));
        let refined = synth::place(before, start, end, &Synthesis::guess(s), synthesis);
        (Some(refined), Some(orientation))
    } else {
        let refined = line_search::search_line(before, start, end, synthesis)
            .iter()
            .map(|found| synth::place(before, start, end, found, synthesis))
            .filter(|r| r.mismatch < synthesis.max_mismatch_share * r.unfolded_mismatch)
            .min_by(|a, b| a.mismatch.total_cmp(&b.mismatch));
        (refined, None)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::angle::edge;

    /// A square of `4·per_side` vertices, slightly jittered.
    fn square(per_side: usize) -> Vec<Point> {
        (0..4 * per_side)
            .map(|k| {
                let t = (k % per_side) as f64 / per_side as f64;
                let (x, y) = [(t, 0.0), (1.0, t), (1.0 - t, 1.0), (0.0, 1.0 - t)][k / per_side];
                Point::new(x - 0.5 + 1e-6 * (k as f64).sin(), y - 0.5, 0.0)
            })
            .collect()
    }

    /// The square with the vertices x > c turned over the line x = c, a layer above.
    fn folded(points: &[Point], c: f64) -> Vec<Point> {
        points
            .iter()
            .map(|p| if p.x > c + 1e-9 { Point::new(2.0 * c - p.x, p.y, p.z + 0.02) } else { *p })
            .collect()
    }

    fn run(before: &[Point], after: &[Point]) -> (Evidence, Option<Seed>) {
        let (start, end) = (Disk::of_border(before), Disk::of_border(after));
        seed(before, &start, &end, FoldMethod::Cut, &Params::default())
    }

    #[test]
    fn nothing_changed_is_no_fold() {
        let s = square(6);
        let (found, seed) = run(&s, &s);
        assert_eq!(seed, None);
        assert!(found.cut.is_none() && found.curves.is_empty());
    }

    #[test]
    fn a_fold_inside_edges_is_placed_within_the_edge() {
        // x = 0.1 cuts the bottom side at vertex 3.6 and the top side at 14.4 (per side 6).
        let s = square(6);
        let (found, seed) = run(&s, &folded(&s, 0.1));
        let Fold { f1, f2 } = seed.unwrap().fold;
        let n = s.len();
        let e = edge(n);
        assert!(crate::angle::distance(f1, param_to_angle(3.6, n)) < 0.2 * e, "{}", f1 / e);
        assert!(crate::angle::distance(f2, param_to_angle(14.4, n)) < 0.2 * e, "{}", f2 / e);
        assert!(found.orientation.is_some() && found.synthesis.is_some());
    }

    #[test]
    fn a_stacked_second_fold_is_found_by_its_line() {
        // Right half over the left (x = 0), then the stack's top half down (y = 0).
        let s = square(6);
        let half = folded(&s, 0.0);
        let top = half
            .iter()
            .map(|p| if p.y > 1e-9 { Point::new(p.x, -p.y, 0.1 - p.z) } else { *p })
            .collect::<Vec<_>>();
        let (found, seed) = run(&half, &top);
        let Fold { f1, f2 } = seed.unwrap().fold;
        let n = s.len();
        // The folded arc runs from the right side's middle (vertex 9) to the left side's (21),
        // both on the line, where they lie on top of each other: within an edge of them.
        assert!(
            crate::angle::distance(f1, param_to_angle(9.0, n)) <= edge(n) + 1e-9,
            "{}",
            f1 / edge(n)
        );
        assert!(
            crate::angle::distance(f2, param_to_angle(21.0, n)) <= edge(n) + 1e-9,
            "{}",
            f2 / edge(n)
        );
        // The line came from the disks: horizontal.
        let direction =
            found.synthesis.as_ref().and_then(|s| s.direction).expect("the fold points coincide");
        assert!(direction.y.abs() < 0.1, "{direction:?}");
        assert!(found.orientation.is_none(), "a stacked start is not oriented by flips");
    }
}
