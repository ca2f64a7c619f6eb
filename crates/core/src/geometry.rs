//! Fold geometry as types: a point of the table, a fold on the border circle, the arcs it
//! turns over and the line it is made along.
//!
//! Convention (Kamat, Borràs, Torras, "CloSE", the fold coordinates): border vertex k of N
//! sits at angle 2πk/N of the border circle. A [`Fold`] (f1, f2) folds the border arc walked
//! anticlockwise from f1 to f2 over the line through the border points at f1 and f2. A fold
//! line that crosses a stacked border 2k times turns k separate arcs over at once (our
//! extension of CloSE, a *multi-arc fold*): each is an [`Arc`] [a, b], folded anticlockwise
//! from a to b, and the fold is the pair that spans them (a of the first arc, b of the
//! last). A [`Line`] lies in the XY plane (the table): a point and a unit direction; folding
//! across it reflects a vertex in XY and keeps its z. A [`Folding`] is one fold as it is
//! made: the fold, its arcs and its line.
//!
//! On the wire a fold and an arc are `[f1, f2]` and `[a, b]` (radians), a line is
//! `{"point": [x, y], "direction": [dx, dy]}`.
//!
//! ```
//! use close_core::border::Point;
//! use close_core::geometry::{Fold, Line};
//! use std::f64::consts::PI;
//! let square = [
//!     Point::new(0.0, 0.0, 0.0),
//!     Point::new(1.0, 0.0, 0.0),
//!     Point::new(1.0, 1.0, 0.0),
//!     Point::new(0.0, 1.0, 0.0),
//! ];
//! // The diagonal fold from vertex 0 (angle 0) to vertex 2 (angle π) turns vertex 1 over.
//! let fold = Fold::new(0.0, PI);
//! assert_eq!(fold.arc().folded_vertices(4), vec![1]);
//! let line: Line = fold.line_on(&square, None).unwrap();
//! assert!((line.reflect(&square[1]) - square[3]).norm() < 1e-12);
//! assert_eq!(serde_json::to_string(&fold).unwrap(), format!("[0.0,{PI}]"));
//! ```

use serde::{Deserialize, Serialize};

use crate::angle::{angle_to_param, edge, param_to_angle, vertices_in_arc, wrap_tau};
use crate::border::{point_at, Point};

/// A point of the XY plane (the table).
pub type Point2 = nalgebra::Point2<f64>;
/// A vector of the XY plane: a direction, an offset.
pub type Vector2 = nalgebra::Vector2<f64>;

/// A fold (f1, f2) on the border circle, radians: the border walked anticlockwise from f1
/// to f2 is the side folded over. Serialised as `[f1, f2]`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(from = "[f64; 2]", into = "[f64; 2]")]
pub struct Fold {
    pub f1: f64,
    pub f2: f64,
}

/// An arc [a, b] of the border circle, radians, walked anticlockwise from a to b: a side a
/// fold turns over. Serialised as `[a, b]`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(from = "[f64; 2]", into = "[f64; 2]")]
pub struct Arc {
    pub a: f64,
    pub b: f64,
}

impl Fold {
    /// The fold whose folded side runs anticlockwise from angle `f1` to `f2` (radians).
    pub const fn new(f1: f64, f2: f64) -> Fold {
        Fold { f1, f2 }
    }

    /// The two fold points, `[f1, f2]`.
    pub const fn ends(self) -> [f64; 2] {
        [self.f1, self.f2]
    }

    /// The arc this fold folds: anticlockwise from f1 to f2.
    pub const fn arc(self) -> Arc {
        Arc { a: self.f1, b: self.f2 }
    }

    /// The fold that spans `arcs` (given in walking order): from the first arc's start to
    /// the last arc's end; `None` without an arc.
    pub fn span(arcs: &[Arc]) -> Option<Fold> {
        Some(Fold::new(arcs.first()?.a, arcs.last()?.b))
    }

    /// Both angles through `f`.
    pub fn map(self, f: impl Fn(f64) -> f64) -> Fold {
        Fold::new(f(self.f1), f(self.f2))
    }

    /// Both angles taken into [0, 2π).
    pub fn wrapped(self) -> Fold {
        self.map(wrap_tau)
    }

    /// True when both angles are finite numbers.
    pub fn is_finite(self) -> bool {
        self.f1.is_finite() && self.f2.is_finite()
    }

    /// The line this fold is made along on `points` (a border, vertex k at angle 2πk/N):
    /// through the border points at f1 and f2, or, with a `direction` (when the two points
    /// coincide, a fold through stacked layers, the disks give it), through their midpoint
    /// in that direction. `None` when the two points coincide and no direction is given.
    pub fn line_on(self, points: &[Point], direction: Option<Vector2>) -> Option<Line> {
        let n = points.len();
        let (a, b) = (
            point_at(points, angle_to_param(self.f1, n)),
            point_at(points, angle_to_param(self.f2, n)),
        );
        match direction {
            Some(direction) => {
                Some(Line { point: Point2::new((a.x + b.x) / 2.0, (a.y + b.y) / 2.0), direction })
            }
            None => Line::through(&a, &b),
        }
    }
}

impl From<[f64; 2]> for Fold {
    fn from([f1, f2]: [f64; 2]) -> Fold {
        Fold { f1, f2 }
    }
}

impl From<Fold> for [f64; 2] {
    fn from(fold: Fold) -> [f64; 2] {
        [fold.f1, fold.f2]
    }
}

impl Arc {
    /// The arc walked anticlockwise from angle `a` to `b` (radians).
    pub const fn new(a: f64, b: f64) -> Arc {
        Arc { a, b }
    }

    /// The two ends, `[a, b]`.
    pub const fn ends(self) -> [f64; 2] {
        [self.a, self.b]
    }

    /// Both ends through `f`.
    pub fn map(self, f: impl Fn(f64) -> f64) -> Arc {
        Arc::new(f(self.a), f(self.b))
    }

    /// Indices of the vertices of an `n`-vertex border strictly inside the arc, in walking
    /// order: the vertices a fold of this arc moves (one at an end lies on the fold line).
    pub fn folded_vertices(self, n: usize) -> Vec<usize> {
        vertices_in_arc(n, angle_to_param(self.a, n), angle_to_param(self.b, n))
    }

    /// True when border vertex `v` of an `n`-vertex border lies strictly inside the arc and
    /// more than `margin` edges from both of its ends: the vertices a fold moves are those
    /// with `margin` 0, the corners it folds those with [`crate::angle::ON_LINE_EDGES`]
    /// (closer to a fold point, a corner is on the line). With `margin` 0 this is
    /// [`crate::angle::arc_contains`] of the vertex's angle.
    pub fn folds_vertex(self, n: usize, v: usize, margin: f64) -> bool {
        let offset = wrap_tau(param_to_angle(v as f64, n) - self.a);
        let off_line = margin * edge(n);
        offset > off_line && offset < wrap_tau(self.b - self.a) - off_line
    }
}

impl From<[f64; 2]> for Arc {
    fn from([a, b]: [f64; 2]) -> Arc {
        Arc { a, b }
    }
}

impl From<Arc> for [f64; 2] {
    fn from(arc: Arc) -> [f64; 2] {
        [arc.a, arc.b]
    }
}

/// A fold line in the XY plane: a point and a unit direction. Serialised as
/// `{"point": [x, y], "direction": [dx, dy]}`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct Line {
    /// A point of the line, [x, y] (in the coordinates of the border it lies on).
    #[cfg_attr(feature = "schema", schemars(with = "[f64; 2]"))]
    pub point: Point2,
    /// Its direction, [dx, dy]: a unit vector (no angle).
    #[cfg_attr(feature = "schema", schemars(with = "[f64; 2]"))]
    pub direction: Vector2,
}

impl Line {
    /// The line through the XY projections of `a` and `b`; `None` when they coincide.
    pub fn through(a: &Point, b: &Point) -> Option<Line> {
        let (dx, dy) = (b.x - a.x, b.y - a.y);
        let len = dx.hypot(dy);
        (len > 1e-12 * (1.0 + a.coords.norm() + b.coords.norm())).then(|| Line {
            point: Point2::new(a.x, a.y),
            direction: Vector2::new(dx / len, dy / len),
        })
    }

    /// The line through `point` at angle `phi` to the x axis.
    pub(crate) fn at_angle(point: Point2, phi: f64) -> Line {
        Line { point, direction: Vector2::new(phi.cos(), phi.sin()) }
    }

    /// The angle of the line's direction to the x axis (the inverse of [`Line::at_angle`]).
    pub(crate) fn angle(&self) -> f64 {
        self.direction.y.atan2(self.direction.x)
    }

    /// Reflection of `p` across the line, in XY, z kept.
    pub fn reflect(&self, p: &Point) -> Point {
        let (ux, uy) = (self.direction.x, self.direction.y);
        let (px, py) = (p.x - self.point.x, p.y - self.point.y);
        let t = px * ux + py * uy;
        Point::new(self.point.x + 2.0 * t * ux - px, self.point.y + 2.0 * t * uy - py, p.z)
    }
}

/// One fold as it is made: where it lies on the border circle, the arcs it turns over, and
/// the line it is made along. Serialised as `{"fold", "arcs", "line"}`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Folding {
    /// The fold (f1, f2) in [0, 2π) (radians); for several arcs, the pair that spans them.
    pub fold: Fold,
    /// The arcs turned over, each [a, b] in [0, 2π) (radians), in walking order from f1:
    /// `[fold.arc()]` for an ordinary fold.
    pub arcs: Vec<Arc>,
    /// The line the arcs turn over; `None`: through the border points at f1 and f2 of the
    /// state the fold is applied to ([`Fold::line_on`]).
    pub line: Option<Line>,
}

impl Folding {
    /// An ordinary fold: its one arc, along the line through its two points.
    pub fn new(fold: Fold) -> Folding {
        Folding { fold, arcs: vec![fold.arc()], line: None }
    }

    /// The line the fold is made along on `points`: its own line, or the line through its
    /// two points there; `None` when it has no line and its two points coincide.
    pub fn line_on(&self, points: &[Point]) -> Option<Line> {
        self.line.or_else(|| self.fold.line_on(points, None))
    }
}

impl From<Fold> for Folding {
    fn from(fold: Fold) -> Folding {
        Folding::new(fold)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::angle::{arc_contains, ON_LINE_EDGES};

    #[test]
    fn folds_and_arcs_travel_as_pairs() {
        let fold = Fold::new(0.25, 3.5);
        assert_eq!(serde_json::to_value(fold).unwrap(), serde_json::json!([0.25, 3.5]));
        assert_eq!(serde_json::from_str::<Fold>("[0.25, 3.5]").unwrap(), fold);
        assert_eq!(serde_json::to_value(fold.arc()).unwrap(), serde_json::json!([0.25, 3.5]));
        assert!(serde_json::from_str::<Arc>("[1, 2, 3]").is_err());
        let line = Line::at_angle(Point2::new(1.0, 2.0), 0.0);
        assert_eq!(
            serde_json::to_value(line).unwrap(),
            serde_json::json!({"point": [1.0, 2.0], "direction": [1.0, 0.0]})
        );
        assert_eq!(
            serde_json::from_value::<Line>(serde_json::to_value(line).unwrap()).unwrap(),
            line
        );
        let folding = Folding::new(fold);
        assert_eq!(
            serde_json::to_value(&folding).unwrap(),
            serde_json::json!({"fold": [0.25, 3.5], "arcs": [[0.25, 3.5]], "line": null})
        );
    }

    #[test]
    fn a_fold_spans_the_arcs_it_turns() {
        let arcs = [Arc::new(1.0, 2.0), Arc::new(3.0, 4.0)];
        assert_eq!(Fold::span(&arcs), Some(Fold::new(1.0, 4.0)));
        assert_eq!(Fold::span(&[]), None);
    }

    #[test]
    fn a_folded_vertex_is_inside_the_arc_and_off_its_ends() {
        let n = 8;
        let at = |s: f64| param_to_angle(s, n);
        // The arc from vertex 1.2 to 5.6: vertices 2 to 5 inside, 1 and 6 not.
        let arc = Arc::new(at(1.2), at(5.6));
        let inside: Vec<usize> = (0..n).filter(|&v| arc.folds_vertex(n, v, 0.0)).collect();
        assert_eq!(inside, vec![2, 3, 4, 5]);
        assert_eq!(arc.folded_vertices(n), inside);
        assert!(
            (0..n).all(|v| arc.folds_vertex(n, v, 0.0) == arc_contains(arc.a, arc.b, at(v as f64)))
        );
        // Off the line: vertex 5 is 0.6 edges from the end, vertex 2 0.8 from the start.
        let off: Vec<usize> = (0..n).filter(|&v| arc.folds_vertex(n, v, ON_LINE_EDGES)).collect();
        assert_eq!(off, vec![2, 3, 4, 5]);
        let near_ends = Arc::new(at(1.7), at(5.4));
        let off: Vec<usize> =
            (0..n).filter(|&v| near_ends.folds_vertex(n, v, ON_LINE_EDGES)).collect();
        assert_eq!(off, vec![3, 4]);
        // Through zero, and a vertex exactly on a fold point is on the line.
        let through_zero = Arc::new(at(6.0), at(2.0));
        let off: Vec<usize> = (0..n).filter(|&v| through_zero.folds_vertex(n, v, 0.0)).collect();
        assert_eq!(off, vec![0, 1, 7]);
        assert_eq!(through_zero.folded_vertices(n), vec![7, 0, 1]);
    }

    #[test]
    fn reflection_is_an_involution() {
        let line = Line::through(&Point::new(0.0, 0.0, 0.0), &Point::new(1.0, 2.0, 5.0)).unwrap();
        let p = Point::new(0.3, -0.7, 0.25);
        let r = line.reflect(&p);
        assert_eq!(r.z, p.z);
        assert!((line.reflect(&r) - p).norm() < 1e-12);
        assert_eq!(Line::through(&p, &Point::new(0.3, -0.7, 9.0)), None);
    }

    #[test]
    fn a_fold_with_a_direction_runs_through_the_midpoint() {
        let points = [
            Point::new(0.0, 0.0, 0.0),
            Point::new(2.0, 0.0, 0.0),
            Point::new(2.0, 2.0, 0.0),
            Point::new(0.0, 2.0, 0.0),
        ];
        let fold = Fold::new(0.0, std::f64::consts::PI);
        let up = Vector2::new(0.0, 1.0);
        let line = fold.line_on(&points, Some(up)).unwrap();
        assert_eq!((line.point, line.direction), (Point2::new(1.0, 1.0), up));
        assert_eq!(Folding::new(fold).line_on(&points), fold.line_on(&points, None));
    }
}
