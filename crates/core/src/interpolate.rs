//! Interpolation between two folds: a continuous folding motion (the paper's fold interpolation on the fold circle).
//!
//! A fold (f1, f2) folds the border arc walked anticlockwise from f1 to f2; its span is
//! s = (f2 − f1) mod 2π. Going from (f1, f2) to (g1, g2), endpoint k moves linearly by
//! d_k, with d1 ≡ g1 − f1 and d2 ≡ g2 − f2 (mod 2π). The folded arc must never jump, so the
//! span moves straight from s_from to s_to without passing 0 or 2π: d2 − d1 = s_to − s_from.
//! Of the d1 = shortest(g1 − f1) + 2πm (m ∈ {0, −1, 1}, in that order on ties) the one with
//! the least travel |d1| + |d2| wins: both endpoints take the shorter way round unless that
//! would make them cross, and then the one whose long way is cheaper goes the other way.
//! Fold t of `steps` (t = 0 … steps−1) is (f1 + τ·d1, f2 + τ·d2) mod 2π, τ = t/(steps−1);
//! the first and last folds are `from` and `to` exactly. `web/fold.mjs` implements the same
//! rules for the browser (a test checks parity).
//!
//! A border given by a user goes through [`interpolate_border`]: it is validated and
//! oriented by [`crate::border::prepare`], exactly as an analysis's start frame, so a border
//! that the analysis refuses (coincident, collinear, too small or too large) is refused here
//! too; the answer's `border_indices` name the input vertex of each border vertex.
//!
//! ```
//! use close_core::interpolate::fold_path;
//! use std::f64::consts::PI;
//! // Both endpoints move a quarter turn anticlockwise: the span stays π.
//! let path = fold_path([0.0, PI], [PI / 2.0, 1.5 * PI], 3);
//! assert_eq!(path.len(), 3);
//! assert!((path[1][0] - PI / 4.0).abs() < 1e-12 && (path[1][1] - 1.25 * PI).abs() < 1e-12);
//! ```

use serde::Serialize;

use crate::angle::{wrap_pi, wrap_tau, TAU};
use crate::border::{prepare, to_xyz};
use crate::border::{Point, MAX_VERTICES, MIN_VERTICES};
use crate::error::{Error, Result};
use crate::fold::reflect::apply_fold;

/// Fewest and most folds an interpolation may have (both ends included).
pub const STEPS: std::ops::RangeInclusive<usize> = 2..=1000;

/// The folds of a motion and the border folded by each.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Interpolation {
    pub folds: Vec<[f64; 2]>,
    /// Each fold's border, vertices in border order.
    pub borders: Vec<Vec<[f64; 3]>>,
    /// For each border vertex, its index in the input (0…N−1 for an anticlockwise border
    /// without repeated vertices).
    pub border_indices: Vec<usize>,
}

/// How far each endpoint moves (d1, d2) going from `from` to `to`.
pub fn displacements(from: [f64; 2], to: [f64; 2]) -> [f64; 2] {
    let span_change = wrap_tau(to[1] - to[0]) - wrap_tau(from[1] - from[0]);
    let d1 = wrap_pi(to[0] - from[0]);
    let cost = |d: f64| d.abs() + (d + span_change).abs();
    let best = [d1, d1 - TAU, d1 + TAU].into_iter().fold(d1, |best, d| if cost(d) < cost(best) - 1e-12 { d } else { best });
    [best, best + span_change]
}

/// `steps` folds from `from` to `to` (both included), each in [0, 2π).
pub fn fold_path(from: [f64; 2], to: [f64; 2], steps: usize) -> Vec<[f64; 2]> {
    let [d1, d2] = displacements(from, to);
    let last = steps.saturating_sub(1).max(1) as f64;
    (0..steps)
        .map(|t| match t {
            0 => [wrap_tau(from[0]), wrap_tau(from[1])],
            t if t + 1 == steps => [wrap_tau(to[0]), wrap_tau(to[1])],
            t => {
                let tau = t as f64 / last;
                [wrap_tau(from[0] + tau * d1), wrap_tau(from[1] + tau * d2)]
            }
        })
        .collect()
}

/// The border folded along each fold of [`fold_path`]; `border` is taken as given (an
/// anticlockwise border, e.g. an analysis's start border), checked for size and finite
/// coordinates only: see [`interpolate_border`] for a user's input.
pub fn interpolate(border: &[Point], from: [f64; 2], to: [f64; 2], steps: usize) -> Result<Interpolation> {
    if !STEPS.contains(&steps) {
        return Err(Error::InvalidArgument(format!("steps must be in {}..={}, got {steps}", STEPS.start(), STEPS.end())));
    }
    if let Some(bad) = from.iter().chain(&to).find(|a| !a.is_finite()) {
        return Err(Error::InvalidArgument(format!("fold angles must be finite numbers, got {bad}")));
    }
    if border.len() < MIN_VERTICES {
        return Err(Error::TooFewVertices { got: border.len(), min: MIN_VERTICES });
    }
    if border.len() > MAX_VERTICES {
        return Err(Error::too_large("border vertices", border.len(), MAX_VERTICES));
    }
    if let Some(v) = border.iter().position(|p| p.iter().any(|c| !c.is_finite())) {
        return Err(Error::NonFinite { frame: 0, vertex: v });
    }
    let folds = fold_path(from, to, steps);
    let borders = folds.iter().map(|&f| apply_fold(border, f).iter().map(to_xyz).collect()).collect();
    Ok(Interpolation { folds, borders, border_indices: (0..border.len()).collect() })
}

/// [`interpolate`] a user's border, validated by [`prepare`] as an analysis validates its
/// frames: `border` is the state to fold and `reference` the flat border whose orientation
/// applies (an analysis's start frame; by default `border` itself, which must then be a
/// valid start frame). A border already folded overlaps itself, so its own area and
/// orientation are no guide: send the flat one as `reference`.
///
/// ```
/// use close_core::interpolate::interpolate_border;
/// let square = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
/// assert_eq!(interpolate_border(square.clone(), None, [0.0, 3.1], [0.5, 3.6], 5).unwrap().borders.len(), 5);
/// let line = vec![[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [2.0, 2.0, 0.0], [3.0, 3.0, 0.0]];
/// assert!(interpolate_border(line.clone(), None, [0.0, 3.1], [0.5, 3.6], 5).is_err());
/// // A state with no area of its own is fine against a flat reference.
/// assert!(interpolate_border(line, Some(square), [0.0, 3.1], [0.5, 3.6], 5).is_ok());
/// ```
pub fn interpolate_border(border: Vec<[f64; 3]>, reference: Option<Vec<[f64; 3]>>, from: [f64; 2], to: [f64; 2], steps: usize) -> Result<Interpolation> {
    let frames = match reference {
        Some(reference) => vec![reference, border],
        None => vec![border],
    };
    let prepared = prepare(frames)?;
    // prepare gives one frame per frame given: the state is the last.
    let state = prepared.frames.last().map_or(&[][..], Vec::as_slice);
    let motion = interpolate(state, from, to, steps)?;
    Ok(Interpolation { border_indices: prepared.border_indices, ..motion })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// A square of 4·k vertices, side 2, centred at the origin, anticlockwise.
    fn square(k: usize) -> Vec<Point> {
        let c = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
        (0..4 * k)
            .map(|v| {
                let (a, b, t) = (c[v / k], c[(v / k + 1) % 4], (v % k) as f64 / k as f64);
                Point::new(a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1), 0.0)
            })
            .collect()
    }

    /// Pairs of folds covering wraps through 0, crossing cases, tiny and huge spans.
    fn cases() -> Vec<([f64; 2], [f64; 2])> {
        let q = PI / 8.0;
        vec![
            ([0.0, PI], [PI / 2.0, 1.5 * PI]),
            ([15.0 * q, q], [q, 3.0 * q]),
            ([0.1, 0.3], [6.0, 0.2]),
            ([0.1, 0.3], [0.2, 0.1]),
            ([0.2, 6.0], [0.1, 0.3]),
            ([1.0, 1.2], [4.0, 4.3]),
            ([5.5, 2.0], [0.5, 3.9]),
            ([3.0, 2.9], [0.2, 0.1]),
            ([0.0, PI], [PI, 0.0]),
        ]
    }

    #[test]
    fn endpoints_are_hit_exactly() {
        for (from, to) in cases() {
            let path = fold_path(from, to, 17);
            assert_eq!(path[0], [wrap_tau(from[0]), wrap_tau(from[1])]);
            assert_eq!(path[16], [wrap_tau(to[0]), wrap_tau(to[1])]);
        }
    }

    #[test]
    fn span_moves_monotonically_and_never_wraps() {
        for (from, to) in cases() {
            let path = fold_path(from, to, 101);
            let spans: Vec<f64> = path.iter().map(|f| wrap_tau(f[1] - f[0])).collect();
            let (s0, s1) = (spans[0], spans[100]);
            for w in spans.windows(2) {
                // The span moves in the direction of s1 − s0, by equal steps: no jump of ~2π.
                assert!(((w[1] - w[0]) - (s1 - s0) / 100.0).abs() < 1e-9, "{from:?} → {to:?}: {w:?}");
            }
        }
    }

    #[test]
    fn each_step_moves_little() {
        for (from, to) in cases() {
            let path = fold_path(from, to, 201);
            for w in path.windows(2) {
                for (a, b) in w[0].iter().zip(&w[1]) {
                    // No endpoint travels a full turn: under 2π / 200 per step.
                    assert!(wrap_pi(b - a).abs() <= TAU / 200.0 + 1e-12, "{from:?} → {to:?}");
                }
            }
        }
    }

    #[test]
    fn endpoints_take_the_shorter_way_when_they_do_not_cross() {
        let [d1, d2] = displacements([0.1, 3.0], [6.2, 3.2]);
        assert!((d1 - (6.2 - 0.1 - TAU)).abs() < 1e-12 && (d2 - 0.2).abs() < 1e-12);
    }

    #[test]
    fn crossing_endpoints_send_one_the_long_way() {
        // Shortest ways: f1 0.1 → 0.2 forward, f2 0.3 → 0.1 back: the span would pass 0
        // (0.2 → −0.1); it must grow from 0.2 to 2π − 0.1 instead.
        let from = [0.1, 0.3];
        let to = [0.2, 0.1];
        let [d1, d2] = displacements(from, to);
        let (s0, s1) = (wrap_tau(from[1] - from[0]), wrap_tau(to[1] - to[0]));
        assert!(((d2 - d1) - (s1 - s0)).abs() < 1e-12);
        assert!(d1.abs() > PI || d2.abs() > PI, "one endpoint goes the long way: {d1} {d2}");
    }

    #[test]
    fn a_square_folds_continuously() {
        let sq = square(8);
        let motion = interpolate(&sq, [PI / 4.0 + 0.01, 1.25 * PI + 0.01], [0.0, PI], 61).unwrap();
        assert_eq!(motion.borders.len(), 61);
        for w in motion.borders.windows(2) {
            let jump = w[0].iter().zip(&w[1]).map(|(a, b)| ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt()).fold(0.0, f64::max);
            assert!(jump < 0.25, "a vertex jumped by {jump}");
        }
        let last = apply_fold(&sq, [0.0, PI]);
        assert!(motion.borders[60].iter().zip(&last).all(|(a, b)| (a[0] - b.x).abs() < 1e-12 && (a[1] - b.y).abs() < 1e-12));
    }

    #[test]
    fn bad_arguments_are_named() {
        let sq = square(2);
        assert!(interpolate(&sq, [0.0, 1.0], [1.0, 2.0], 1).unwrap_err().to_string().contains("steps"));
        assert!(interpolate(&sq, [f64::NAN, 1.0], [1.0, 2.0], 5).unwrap_err().to_string().contains("finite"));
        assert!(matches!(interpolate(&sq[..3], [0.0, 1.0], [1.0, 2.0], 5), Err(Error::TooFewVertices { .. })));
    }

    #[test]
    fn a_users_border_is_validated_as_an_analysis_validates_it() {
        let raw: Vec<[f64; 3]> = square(2).iter().map(to_xyz).collect();
        let ok = interpolate_border(raw.clone(), None, [0.0, 1.0], [1.0, 2.0], 5).unwrap();
        assert_eq!(ok.border_indices, (0..8).collect::<Vec<_>>());
        for bad in [raw[..3].to_vec(), vec![[1.0, 2.0, 0.0]; 8], (0..8).map(|k| [k as f64, 2.0 * k as f64, 0.0]).collect()] {
            let ours = interpolate_border(bad.clone(), None, [0.0, 1.0], [1.0, 2.0], 5).unwrap_err();
            assert_eq!(ours, prepare(vec![bad]).unwrap_err(), "the same refusal as the analysis");
        }
        // A clockwise border is walked anticlockwise, vertex 0 first, as the analysis does.
        let mut cw = raw.clone();
        cw[1..].reverse();
        let reversed = interpolate_border(cw, None, [0.0, 1.0], [1.0, 2.0], 5).unwrap();
        assert_eq!(reversed.border_indices, [0, 7, 6, 5, 4, 3, 2, 1]);
        assert_eq!(reversed.borders, ok.borders);
        // A square folded in half has no area of its own: against the flat one, it folds on,
        // in its own vertex order; against a reference of another vertex count, it is refused.
        let half: Vec<[f64; 3]> = apply_fold(&square(2), [PI / 4.0, 1.25 * PI]).iter().map(to_xyz).collect();
        assert!(interpolate_border(half.clone(), None, [0.0, 1.0], [1.0, 2.0], 5).is_err());
        let on = interpolate_border(half.clone(), Some(raw.clone()), [0.0, 1.0], [1.0, 2.0], 5).unwrap();
        assert_eq!(on.border_indices, (0..8).collect::<Vec<_>>());
        let half_points: Vec<Point> = half.iter().map(crate::border::from_xyz).collect();
        assert_eq!(on.borders, interpolate(&half_points, [0.0, 1.0], [1.0, 2.0], 5).unwrap().borders);
        assert!(matches!(interpolate_border(half, Some(raw[..6].to_vec()), [0.0, 1.0], [1.0, 2.0], 5), Err(Error::FrameSizeMismatch { .. })));
    }
}
