//! Which side of a fold was folded over, read from the signed diff disk (Kamat, Borràs,
//! Torras, "CloSE", Sec. III-C: the fold coordinates are ordered so that the folded side
//! runs anticlockwise from f1 to f2).
//!
//! A fold reflects the folded arc in a vertical plane and lifts it: the dGLI of a pair of
//! edges that both lie on the folded arc changes sign (reflection reverses linking; a
//! vertical lift commutes with it), while a pair on the unfolded arc keeps its value. So for
//! each of the two arcs between the fold points we measure
//! `flip = Σ|end − start| / Σ(|start| + |end|)` over the pairs inside it: near 1 on the
//! folded side, near 0 on the other. Straight sides carry signal through every pair across
//! them, not only through corners.
//!
//! Tie-break, when the two arcs flip alike (within [`DetectParams::tie_share`]) or carry no signal:
//! the arc with fewer vertices is the folded one (a cloth is folded smaller part over larger), and
//! for equal arcs the one that starts at the smaller angle.

use super::params::DetectParams;
use crate::angle::wrap_tau;
use crate::disk::Disk;
use crate::geometry::{Arc, Fold};

/// How the orientation was decided.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Orientation {
    /// Flip score of the arc anticlockwise from the first to the second fold point as given.
    pub flip_forward: f64,
    /// Flip score of the other arc.
    pub flip_backward: f64,
    /// True when the tie-break decided.
    pub tie_break: bool,
    /// True when the given order had to be swapped.
    pub swapped: bool,
}

/// Edges lying wholly inside the anticlockwise arc from angle `from` to angle `to`.
fn edges_inside(n: usize, from: f64, to: f64) -> Vec<usize> {
    let inside = |v: usize| Arc::new(from, to).folds_vertex(n, v, 0.0);
    (0..n).filter(|&e| inside(e) && inside((e + 1) % n)).collect()
}

fn flip_score(start: &Disk, end: &Disk, edges: &[usize]) -> f64 {
    let (mut change, mut size) = (0.0, 0.0);
    for (k, &i) in edges.iter().enumerate() {
        for &j in &edges[k + 1..] {
            let (s, e) = (start.get(i, j), end.get(i, j));
            change += (e - s).abs();
            size += s.abs() + e.abs();
        }
    }
    if size > 0.0 {
        change / size
    } else {
        0.0
    }
}

/// Order the fold points `(p, q)` so that the folded side runs anticlockwise from the first.
pub fn orient(
    start: &Disk,
    end: &Disk,
    p: f64,
    q: f64,
    params: &DetectParams,
) -> (Fold, Orientation) {
    let n = start.n();
    let forward = edges_inside(n, p, q);
    let backward = edges_inside(n, q, p);
    let flip_forward = flip_score(start, end, &forward);
    let flip_backward = flip_score(start, end, &backward);
    let tie_break = (flip_forward - flip_backward).abs() < params.tie_share;
    let swapped = if tie_break {
        let (span_forward, span_backward) = (wrap_tau(q - p), wrap_tau(p - q));
        if (span_forward - span_backward).abs() > 1e-9 {
            span_backward < span_forward
        } else {
            q < p
        }
    } else {
        flip_backward > flip_forward
    };
    let fold = if swapped { Fold::new(q, p) } else { Fold::new(p, q) };
    (fold, Orientation { flip_forward, flip_backward, tie_break, swapped })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::angle::param_to_angle;
    use crate::border::Point;

    fn square() -> Vec<Point> {
        (0..16)
            .map(|k| {
                let t = (k % 4) as f64 / 4.0;
                let (x, y) = [(t, 0.0), (1.0, t), (1.0 - t, 1.0), (0.0, 1.0 - t)][k / 4];
                Point::new(x + 1e-6 * (k as f64).sin(), y, 0.0)
            })
            .collect()
    }

    #[test]
    fn the_flipping_side_is_the_folded_one() {
        let start = square();
        // The bottom-left corner's flap (vertices 15, 0, 1) folded over the diagonal.
        let end: Vec<Point> =
            start
                .iter()
                .map(|p| {
                    if p.x + p.y < 0.5 - 1e-3 {
                        Point::new(0.5 - p.y, 0.5 - p.x, 0.02)
                    } else {
                        *p
                    }
                })
                .collect();
        let (a, b) = (param_to_angle(14.0, 16), param_to_angle(2.0, 16));
        let params = DetectParams::default();
        let (fold, how) = orient(&Disk::of_border(&start), &Disk::of_border(&end), a, b, &params);
        assert_eq!(fold, Fold::new(a, b));
        assert!(!how.swapped && how.flip_forward > how.flip_backward + params.tie_share, "{how:?}");
    }

    #[test]
    fn without_signal_the_shorter_arc_is_folded() {
        let start = square();
        let disk = Disk::of_border(&start);
        let (a, b) = (param_to_angle(3.0, 16), param_to_angle(6.0, 16));
        let (fold, how) = orient(&disk, &disk, b, a, &DetectParams::default());
        assert!(how.tie_break && how.swapped);
        assert_eq!(fold, Fold::new(a, b));
    }

    #[test]
    fn edges_inside_an_arc_through_zero() {
        assert_eq!(edges_inside(8, param_to_angle(6.5, 8), param_to_angle(1.5, 8)), vec![0, 7]);
    }

    #[test]
    fn points_given_the_wrong_way_round_are_swapped() {
        // A square of 16 vertices; the arc from vertex 2 to vertex 10 (its right half) folded.
        let square: Vec<Point> = (0..16)
            .map(|k| {
                let t = (k % 4) as f64 / 4.0;
                let (x, y) = [(t, 0.0), (1.0, t), (1.0 - t, 1.0), (0.0, 1.0 - t)][k / 4];
                Point::new(x, y, 0.0)
            })
            .collect();
        let end: Vec<Point> = square
            .iter()
            .map(|p| if p.x > 0.5 { Point::new(1.0 - p.x, p.y, 0.02) } else { *p })
            .collect();
        let (p, q) =
            (crate::angle::param_to_angle(10.0, 16), crate::angle::param_to_angle(2.0, 16));
        // Given the wrong way round, the points are swapped.
        let params = crate::fold::params::DetectParams::default();
        let (fold, how) = orient(&Disk::of_border(&square), &Disk::of_border(&end), p, q, &params);
        assert_eq!(fold, crate::geometry::Fold::new(q, p));
        assert!(how.swapped && !how.tie_break);
    }
}
