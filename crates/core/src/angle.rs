//! Angles on the border circle, in one place.
//!
//! Convention (the paper's disk, vertex-aligned): border vertex k of N sits at angle
//! 2πk/N, so a border parameter s (fractional vertex index) is the angle 2πs/N. Two wraps
//! are needed and are named for their ranges: [`wrap_tau`] into [0, 2π) for positions on
//! the circle, [`wrap_pi`] into (−π, π] for signed differences.
//!
//! ```
//! use close_core::angle::{arc_contains, param_to_angle, wrap_pi, wrap_tau, TAU};
//! assert_eq!(param_to_angle(2.0, 8), TAU / 4.0);
//! assert!((wrap_tau(-0.5) - (TAU - 0.5)).abs() < 1e-12);
//! assert!((wrap_pi(TAU - 0.5) + 0.5).abs() < 1e-12);
//! // The anticlockwise arc from 350° to 10° holds 0°.
//! assert!(arc_contains(350f64.to_radians(), 10f64.to_radians(), 0.0));
//! ```

use std::f64::consts::PI;
pub use std::f64::consts::TAU;

/// `angle` taken into [0, 2π).
pub fn wrap_tau(angle: f64) -> f64 {
    let r = angle.rem_euclid(TAU);
    // rem_euclid can round up to exactly TAU for tiny negative inputs.
    if r >= TAU {
        0.0
    } else {
        r
    }
}

/// `delta` taken into (−π, π].
pub fn wrap_pi(delta: f64) -> f64 {
    let d = (delta + PI).rem_euclid(TAU) - PI;
    if d <= -PI {
        d + TAU
    } else {
        d
    }
}

/// The unsigned angular distance between two angles, in [0, π].
pub fn distance(a: f64, b: f64) -> f64 {
    wrap_pi(a - b).abs()
}

/// Angle of border parameter `s` (fractional vertex index) on an `n`-vertex border.
pub fn param_to_angle(s: f64, n: usize) -> f64 {
    TAU * s / n as f64
}

/// Border parameter in [0, n) of `angle` on an `n`-vertex border.
pub fn angle_to_param(angle: f64, n: usize) -> f64 {
    wrap_tau(angle) * n as f64 / TAU
}

/// One edge of an `n`-vertex border, as an angle.
pub fn edge(n: usize) -> f64 {
    TAU / n as f64
}

/// True when `angle` lies strictly inside the anticlockwise arc from `from` to `to`.
pub fn arc_contains(from: f64, to: f64, angle: f64) -> bool {
    let offset = wrap_tau(angle - from);
    offset > 0.0 && offset < wrap_tau(to - from)
}

/// A corner closer than this many edges to a fold point lies on the fold line: a fold that
/// ends a hair past a corner does not fold it, and one that ends on it gets one answer
/// (`geometry::Arc::folds_vertex`).
pub const ON_LINE_EDGES: f64 = 0.5;

/// The vertices strictly inside the anticlockwise arc from border parameter `s1` to
/// `s2` (fractional vertex indices) of an `n`-vertex border, in walking order. A vertex
/// within `1e-9` of an endpoint lies on the fold line and is not inside.
pub fn vertices_in_arc(n: usize, s1: f64, s2: f64) -> Vec<usize> {
    ArcVertices::of(n, s1, s2).vertices().collect()
}

/// The vertices inside an arc ([`vertices_in_arc`]) as a run: `len` vertices from `first`,
/// cyclically. Asking whether a vertex is inside costs no list.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ArcVertices {
    pub n: usize,
    pub first: usize,
    pub len: usize,
}

impl ArcVertices {
    /// The arc from border parameter `s1` to `s2`; see [`vertices_in_arc`].
    pub fn of(n: usize, s1: f64, s2: f64) -> ArcVertices {
        let nf = n as f64;
        let (start, span) = (s1.rem_euclid(nf), (s2 - s1).rem_euclid(nf));
        let first = (start + 1e-9).floor() as usize + 1;
        // Vertices first, first + 1, … lie inside while v < start + span − 1e-9: counted, not
        // walked (this runs for every line the synthesis tries).
        let end = (start + span - 1e-9).ceil() as usize;
        let len = end.saturating_sub(first).min(n);
        ArcVertices { n, first: first % n.max(1), len }
    }

    /// The vertices, in walking order.
    pub fn vertices(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.len).map(|k| (self.first + k) % self.n)
    }

    /// True when vertex `v` (< n) is inside the arc.
    #[inline]
    pub fn contains(&self, v: usize) -> bool {
        let offset = if v >= self.first { v - self.first } else { v + self.n - self.first };
        offset < self.len
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wraps_are_half_open() {
        assert_eq!(wrap_pi(PI), PI);
        assert_eq!(wrap_pi(-PI), PI);
        assert!((wrap_pi(3.0 * PI) - PI).abs() < 1e-12);
        assert_eq!(wrap_tau(TAU), 0.0);
        assert_eq!(wrap_tau(-1e-18), 0.0);
        assert!(wrap_tau(-1e-9) < TAU);
    }

    #[test]
    fn an_arc_contains_exactly_its_vertices() {
        for n in [3, 8, 13] {
            for k in 0..200 {
                let (s1, s2) = (k as f64 * 0.37 % n as f64, (k as f64 * 0.91 + 0.5) % n as f64);
                let listed = vertices_in_arc(n, s1, s2);
                let arc = ArcVertices::of(n, s1, s2);
                // By the definition: the vertices whose offset from s1 lies strictly inside
                // the span, by more than 1e-9.
                let nf = n as f64;
                let span = (s2 - s1).rem_euclid(nf);
                let inside = |v: usize| {
                    let offset = (v as f64 - s1).rem_euclid(nf);
                    offset > 1e-9 && offset < span - 1e-9
                };
                assert_eq!(arc.len, (0..n).filter(|&v| inside(v)).count(), "{n} {s1} {s2}");
                assert!(
                    (0..n)
                        .all(|v| arc.contains(v) == inside(v) && listed.contains(&v) == inside(v)),
                    "{n} {s1} {s2}"
                );
            }
        }
    }

    #[test]
    fn arc_wraps_through_zero() {
        assert_eq!(vertices_in_arc(8, 6.5, 1.5), vec![7, 0, 1]);
        // Endpoints on vertices are not inside.
        assert_eq!(vertices_in_arc(8, 2.0, 5.0), vec![3, 4]);
        assert_eq!(vertices_in_arc(8, 2.0, 2.0), Vec::<usize>::new());
        assert!(
            !arc_contains(0.0, 1.0, 1.0)
                && arc_contains(0.0, 1.0, 0.5)
                && !arc_contains(0.0, 1.0, 2.0)
        );
    }

    #[test]
    fn distance_is_symmetric_and_short() {
        assert!((distance(0.1, TAU - 0.1) - 0.2).abs() < 1e-12);
        assert_eq!(distance(1.0, 1.0), 0.0);
    }
}
