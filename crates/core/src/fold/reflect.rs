//! Applying a fold to a border: reflect the folded arcs across the fold line.
//!
//! A [`Folding`] names the arcs (angles; border parameter s = θ·N/2π) and the line. The
//! vertices strictly inside an arc are reflected, in the XY plane, across the line; z is
//! kept. A vertex exactly at an arc's end lies on the line and stays. An ordinary fold
//! (f1, f2) has one arc, f1 → f2, and is made along the line through the border points at
//! f1 and f2; a multi-arc fold turns only its arcs, and what lies between them stays. When
//! the two fold points coincide (a second fold through two stacked layers) the line runs
//! through them in the direction the disks gave ([`Fold::line_on`]).
//!
//! ```
//! use close_core::border::Point;
//! use close_core::fold::apply;
//! use close_core::geometry::{Fold, Folding};
//! use std::f64::consts::PI;
//! let square = [Point::new(0.0, 0.0, 0.0), Point::new(1.0, 0.0, 0.0), Point::new(1.0, 1.0, 0.0), Point::new(0.0, 1.0, 0.0)];
//! // Fold along the diagonal from vertex 0 to vertex 2: vertex 1 lands on vertex 3.
//! let folded = apply(&square, &Folding::new(Fold::new(0.0, PI)));
//! assert!((folded[1] - square[3]).norm() < 1e-12);
//! ```

use crate::border::Point;
#[cfg(doc)]
use crate::geometry::Fold;
use crate::geometry::Folding;

/// The border after `folding`: the vertices inside its arcs reflected in XY across its line
/// ([`Folding::line_on`]), z kept. Without a line (its two points coincide and no direction
/// is known) nothing moves.
pub fn apply(points: &[Point], folding: &Folding) -> Vec<Point> {
    let mut out = points.to_vec();
    let Some(line) = folding.line_on(points) else { return out };
    for arc in &folding.arcs {
        for v in arc.folded_vertices(points.len()) {
            out[v] = line.reflect(&points[v]);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::angle::edge;
    use crate::geometry::{Arc, Fold, Line, Point2, Vector2};

    #[test]
    fn only_the_arcs_of_a_multi_arc_fold_turn() {
        // Arcs 1.5 → 3.5 and 7.5 → 9.5 of 12 vertices: vertices 2, 3, 8, 9 cross y = 0.
        let points: Vec<Point> =
            (0..12).map(|k| Point::new(k as f64, 1.0 + (k as f64).sin(), 0.5)).collect();
        let line = Line { point: Point2::new(0.0, 0.0), direction: Vector2::new(1.0, 0.0) };
        let q = edge(12);
        let arcs = vec![Arc::new(1.5 * q, 3.5 * q), Arc::new(7.5 * q, 9.5 * q)];
        let fold = Fold::span(&arcs).unwrap();
        let out = apply(&points, &Folding { fold, arcs, line: Some(line) });
        for (v, (p, o)) in points.iter().zip(&out).enumerate() {
            let expected = if [2, 3, 8, 9].contains(&v) { Point::new(p.x, -p.y, p.z) } else { *p };
            assert!((o - expected).norm() < 1e-12, "vertex {v}: {o:?}");
        }
    }

    #[test]
    fn a_fold_without_a_line_moves_nothing() {
        let mut points: Vec<Point> =
            (0..8).map(|k| Point::new((k as f64).cos(), (k as f64).sin(), 0.0)).collect();
        points[4] = points[0];
        let fold = Fold::new(0.0, 4.0 * edge(8));
        assert_eq!(apply(&points, &Folding::new(fold)), points);
    }
}
