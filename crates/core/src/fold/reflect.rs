//! Applying a fold to a border: reflect the folded arc across the fold line.
//!
//! Fold (f1, f2) in angles; s = f·N/2π are border parameters. The vertices strictly inside
//! the anticlockwise arc from s1 to s2 are reflected, in the XY plane, across the line
//! through the border points at s1 and s2; z is kept. A vertex exactly at s1 or s2 lies on
//! the line and stays.
//!
//! ```
//! use close_core::border::Point;
//! use close_core::fold::reflect::apply_fold;
//! use std::f64::consts::PI;
//! let square = [Point::new(0.0, 0.0, 0.0), Point::new(1.0, 0.0, 0.0), Point::new(1.0, 1.0, 0.0), Point::new(0.0, 1.0, 0.0)];
//! // Fold along the diagonal from vertex 0 to vertex 2: vertex 1 lands on vertex 3.
//! let folded = apply_fold(&square, [0.0, PI]);
//! assert!((folded[1] - square[3]).norm() < 1e-12);
//! ```
//!
//! When the two fold points coincide (a second fold through two stacked layers) the line
//! runs through them in the direction the disks gave ([`fold_line`]).

use crate::angle::{angle_to_param, vertices_in_arc};
use crate::border::{point_at, Point};

use super::synth::Line;

/// Indices of the vertices strictly inside the anticlockwise arc from angle f1 to f2, in
/// walking order.
pub fn folded_vertices(n: usize, fold: [f64; 2]) -> Vec<usize> {
    vertices_in_arc(n, angle_to_param(fold[0], n), angle_to_param(fold[1], n))
}

/// Reflect `p` across the XY line through `a` and `b` (z kept); `p` itself when a = b in XY.
pub fn reflect_xy(p: &Point, a: &Point, b: &Point) -> Point {
    Line::through(a, b).map_or(*p, |line| line.reflect(p))
}

/// The line a fold (f1, f2) of `points` is made along: through the border points at f1 and
/// f2, or, when a `direction` is given (the two points coincide, see
/// [`super::synth`]), through their midpoint in that direction. `None` when the two points
/// coincide and no direction is given.
pub fn fold_line(points: &[Point], fold: [f64; 2], direction: Option<[f64; 2]>) -> Option<Line> {
    let n = points.len();
    let (a, b) = (
        point_at(points, angle_to_param(fold[0], n)),
        point_at(points, angle_to_param(fold[1], n)),
    );
    match direction {
        Some(direction) => Some(Line { point: [(a.x + b.x) / 2.0, (a.y + b.y) / 2.0], direction }),
        None => Line::through(&a, &b),
    }
}

/// The border after folding it along (f1, f2) across `line`: the folded arc reflected in XY,
/// z kept.
pub fn apply_fold_line(points: &[Point], fold: [f64; 2], line: &Line) -> Vec<Point> {
    apply_arcs(points, &[fold], line)
}

/// The border after a fold of several arcs (a multi-arc fold, angles [a, b] each folded
/// anticlockwise from a to b) across `line`: only the vertices inside the arcs are
/// reflected in XY, z kept; what lies between the arcs stays.
pub fn apply_arcs(points: &[Point], arcs: &[[f64; 2]], line: &Line) -> Vec<Point> {
    let mut out = points.to_vec();
    for &arc in arcs {
        for v in folded_vertices(points.len(), arc) {
            out[v] = line.reflect(&points[v]);
        }
    }
    out
}

/// The border after folding it along (f1, f2), across the line through the two fold points.
pub fn apply_fold(points: &[Point], fold: [f64; 2]) -> Vec<Point> {
    match fold_line(points, fold, None) {
        Some(line) => apply_fold_line(points, fold, &line),
        None => points.to_vec(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::angle::edge;

    #[test]
    fn folded_arc_wraps_through_zero() {
        let n = 8;
        let q = edge(n);
        assert_eq!(folded_vertices(n, [6.5 * q, 1.5 * q]), vec![7, 0, 1]);
        // Endpoints on vertices are not folded.
        assert_eq!(folded_vertices(n, [2.0 * q, 5.0 * q]), vec![3, 4]);
    }

    #[test]
    fn a_multi_arc_fold_turns_only_its_arcs() {
        // Arcs 1.5 → 3.5 and 7.5 → 9.5 of 12 vertices: vertices 2, 3, 8, 9 cross y = 0.
        let points: Vec<Point> =
            (0..12).map(|k| Point::new(k as f64, 1.0 + (k as f64).sin(), 0.5)).collect();
        let line = Line { point: [0.0, 0.0], direction: [1.0, 0.0] };
        let q = edge(12);
        let out = apply_arcs(&points, &[[1.5 * q, 3.5 * q], [7.5 * q, 9.5 * q]], &line);
        for (v, (p, o)) in points.iter().zip(&out).enumerate() {
            let expected = if [2, 3, 8, 9].contains(&v) { Point::new(p.x, -p.y, p.z) } else { *p };
            assert!((o - expected).norm() < 1e-12, "vertex {v}: {o:?}");
        }
    }

    #[test]
    fn reflection_is_an_involution() {
        let (a, b) = (Point::new(0.0, 0.0, 0.0), Point::new(1.0, 2.0, 5.0));
        let p = Point::new(0.3, -0.7, 0.25);
        let r = reflect_xy(&p, &a, &b);
        assert_eq!(r.z, p.z);
        assert!((reflect_xy(&r, &a, &b) - p).norm() < 1e-12);
    }
}
