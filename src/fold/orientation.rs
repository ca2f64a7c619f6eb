//! Which side of a fold was folded over, read from the signed diff disk.
//!
//! A fold reflects the folded arc in a vertical plane and lifts it: the dGLI of a pair of
//! edges that both lie on the folded arc changes sign (reflection reverses linking; a
//! vertical lift commutes with it), while a pair on the unfolded arc keeps its value. So for
//! each of the two arcs between the fold points we measure
//! `flip = Σ|end − start| / Σ(|start| + |end|)` over the pairs inside it: near 1 on the
//! folded side, near 0 on the other. Straight sides carry signal through every pair across
//! them, not only through corners.
//!
//! Tie-break, when the two arcs flip alike (within [`TIE_MARGIN`]) or carry no signal: the
//! arc with fewer vertices is the folded one (a cloth is folded smaller part over larger),
//! and for equal arcs the one that starts at the smaller angle.

use std::f64::consts::PI;

use crate::disk::Disk;

/// Flip scores closer than this are a tie.
pub const TIE_MARGIN: f64 = 0.1;

/// How the orientation was decided.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
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
    let span = (to - from).rem_euclid(2.0 * PI);
    let inside = |v: usize| {
        let offset = (2.0 * PI * v as f64 / n as f64 - from).rem_euclid(2.0 * PI);
        offset > 0.0 && offset < span
    };
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
pub fn orient(start: &Disk, end: &Disk, p: f64, q: f64) -> ([f64; 2], Orientation) {
    let n = start.n();
    let forward = edges_inside(n, p, q);
    let backward = edges_inside(n, q, p);
    let flip_forward = flip_score(start, end, &forward);
    let flip_backward = flip_score(start, end, &backward);
    let tie_break = (flip_forward - flip_backward).abs() < TIE_MARGIN;
    let swapped = if tie_break {
        let (span_forward, span_backward) = ((q - p).rem_euclid(2.0 * PI), (p - q).rem_euclid(2.0 * PI));
        if (span_forward - span_backward).abs() > 1e-9 {
            span_backward < span_forward
        } else {
            q < p
        }
    } else {
        flip_backward > flip_forward
    };
    let fold = if swapped { [q, p] } else { [p, q] };
    (fold, Orientation { flip_forward, flip_backward, tie_break, swapped })
}
