//! How a fold found compares with the sample's true fold, for the pictures' legends.
//!
//! An ordinary fold (one arc of the border turned over, the line crossing the border twice)
//! is known by its two fold points, and compared by them: the angles between f1 and t1 and
//! between f2 and t2 on the circle. A *multi-arc* fold (the line crosses the border more
//! than twice: a leg folded over the other) is not: its two reported points are the ends of
//! the arcs it turns, and two folds along one line may name them in another order. Such a
//! fold, found or true, is compared by what it does: the angle between the two lines, their
//! distance (where the found line passes nearest the cloth's centre, as a share of the cloth's
//! radius), and the share of the
//! folded vertices both fold (|A ∩ B| / |A ∪ B|).
//!
//! A true fold's line runs through its two points on the true state before it: the flat
//! cloth with the true folds before it made, each turning over its folded vertices when the
//! sample lists them per fold (`folded_vertices_per_fold`), else its arc.
//!
//! ```
//! use close_render::truth::Agreement;
//! let multi = Agreement::Line { angle: 0.4, offset: 0.012, shared: Some(0.97) };
//! assert_eq!(multi.to_string(), "line 0.4° and 0.012 apart, 97% of its folded vertices shared");
//! assert_eq!(Agreement::Points([1.25, 0.5]).to_string(), "1.2°, 0.5° off");
//! ```

use std::collections::BTreeSet;
use std::fmt;

use close_core::analysis::Analysis;
use close_core::angle::{self, angle_to_param, vertices_in_arc};
use close_core::border::Point;
use close_core::fold::apply;
use close_core::geometry::{Fold, Folding, Line};

/// A sample's true folds, as its file gives them.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Truth {
    /// (t1, t2) per fold.
    pub folds: Vec<Fold>,
    /// Per fold, the vertices (the input's indices) it turned over, when the sample says.
    pub folded: Vec<Option<Vec<usize>>>,
}

impl Truth {
    /// The truth of a sample file: its folds, and what each folded (per fold when listed,
    /// else, for a single fold, the folded vertices).
    pub fn of(truth: &close_io::formats::Truth) -> Truth {
        let folded = (0..truth.folds.len())
            .map(|k| match &truth.folded_vertices_per_fold {
                Some(per_fold) => per_fold.get(k).cloned(),
                None if truth.folds.len() == 1 => truth.folded_vertices.clone(),
                None => None,
            })
            .collect();
        Truth { folds: truth.folds.clone(), folded }
    }

    /// True folds known by their points alone.
    pub fn folds(folds: &[Fold]) -> Truth {
        Truth { folds: folds.to_vec(), folded: vec![None; folds.len()] }
    }

    pub fn is_empty(&self) -> bool {
        self.folds.is_empty()
    }
}

/// How a found fold agrees with its true fold.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Agreement {
    /// Two ordinary folds: how far (degrees) f1 is from t1 and f2 from t2 on the circle.
    Points([f64; 2]),
    /// A multi-arc fold: the angle between the lines (degrees), their distance at the cloth's
    /// centre (a share of its radius), and the share of folded vertices both fold (when the
    /// true folded vertices are known).
    Line { angle: f64, offset: f64, shared: Option<f64> },
}

impl fmt::Display for Agreement {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Agreement::Points([a, b]) => write!(f, "{a:.1}°, {b:.1}° off"),
            Agreement::Line { angle, offset, shared } => {
                write!(f, "line {angle:.1}° and {offset:.3} apart")?;
                match shared {
                    Some(s) => write!(f, ", {:.0}% of its folded vertices shared", 100.0 * s),
                    None => Ok(()),
                }
            }
        }
    }
}

/// The line each true fold is made along (`None` where its two points coincide), and the
/// true state before it, which it folds.
pub fn true_lines(analysis: &Analysis, truth: &Truth) -> Vec<(Option<Line>, Vec<Point>)> {
    let mut state = analysis.start_border().to_vec();
    let border_of = border_order(analysis);
    truth
        .folds
        .iter()
        .enumerate()
        .map(|(k, &fold)| {
            let before = state.clone();
            let line = fold.line_on(&state, None);
            if let Some(line) = &line {
                state = match truth.folded.get(k).and_then(Option::as_ref) {
                    Some(folded) => {
                        let mut next = state.clone();
                        for v in folded.iter().filter_map(|&v| border_of(v)) {
                            next[v] = line.reflect(&state[v]);
                        }
                        next
                    }
                    None => {
                        apply(&state, &Folding { fold, arcs: vec![fold.arc()], line: Some(*line) })
                    }
                };
            }
            (line, before)
        })
        .collect()
}

/// The border index of input vertex `v`, if the border holds it.
fn border_order(analysis: &Analysis) -> impl Fn(usize) -> Option<usize> + '_ {
    move |v| analysis.border_indices.iter().position(|&i| i == v)
}

/// How found fold `k` of `analysis` agrees with true fold `k` (`None` when either is
/// missing), its true line `line` (see [`true_lines`]).
pub fn agreement(
    analysis: &Analysis,
    truth: &Truth,
    k: usize,
    line: Option<&Line>,
) -> Option<Agreement> {
    let (found, true_fold) = (analysis.folds.get(k)?, truth.folds.get(k)?);
    let folding = analysis.foldings().into_iter().nth(k);
    let arcs = folding.as_ref().map(|f| f.arcs.clone()).unwrap_or_default();
    let n = analysis.n;
    // The vertices each turned over, as input indices.
    let found_set: BTreeSet<usize> = arcs
        .iter()
        .flat_map(|arc| arc.folded_vertices(n))
        .map(|v| analysis.border_indices[v])
        .collect();
    let true_set: Option<BTreeSet<usize>> =
        truth.folded.get(k).and_then(Option::as_ref).map(|s| s.iter().copied().collect());
    let true_arc: BTreeSet<usize> =
        vertices_in_arc(n, angle_to_param(true_fold.f1, n), angle_to_param(true_fold.f2, n))
            .into_iter()
            .map(|v| analysis.border_indices[v])
            .collect();
    let multi = arcs.len() > 1 || true_set.as_ref().is_some_and(|s| *s != true_arc);
    if !multi {
        return Some(Agreement::Points([
            angle::distance(found.f1, true_fold.f1).to_degrees(),
            angle::distance(found.f2, true_fold.f2).to_degrees(),
        ]));
    }
    let found_line = folding?.line?;
    let line = line?;
    let cross = found_line.direction.perp(&line.direction);
    let dot = found_line.direction.dot(&line.direction);
    // Lines have no direction: the angle between them is at most 90°.
    let angle = cross.abs().atan2(dot.abs()).to_degrees();
    let (centre, radius) = centre_and_radius(analysis.start_border());
    // How far the true line passes from where the found one passes nearest the centre.
    let along = (centre[0] - found_line.point.x) * found_line.direction.x
        + (centre[1] - found_line.point.y) * found_line.direction.y;
    let foot = [
        found_line.point.x + along * found_line.direction.x,
        found_line.point.y + along * found_line.direction.y,
    ];
    let offset = distance_to(line, foot).abs() / radius.max(f64::MIN_POSITIVE);
    let shared = true_set.map(|t| {
        let union = t.union(&found_set).count();
        if union == 0 {
            1.0
        } else {
            t.intersection(&found_set).count() as f64 / union as f64
        }
    });
    Some(Agreement::Line { angle, offset, shared })
}

/// The XY centroid of `points` and the distance of the farthest from it.
fn centre_and_radius(points: &[Point]) -> ([f64; 2], f64) {
    let n = points.len().max(1) as f64;
    let c = points.iter().fold([0.0, 0.0], |c, p| [c[0] + p.x / n, c[1] + p.y / n]);
    let r = points.iter().map(|p| (p.x - c[0]).hypot(p.y - c[1])).fold(0.0, f64::max);
    (c, r)
}

/// Signed distance of XY point `p` from `line`.
fn distance_to(line: &Line, p: [f64; 2]) -> f64 {
    (p[1] - line.point.y) * line.direction.x - (p[0] - line.point.x) * line.direction.y
}
