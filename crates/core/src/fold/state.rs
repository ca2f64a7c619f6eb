//! A synthesised state: a border with folds made on it, layer on layer, as the fold search
//! makes them and the pictures draw them.
//!
//! A fold as made ([`Made`]) is a line and the arcs of the border it turned over (border
//! parameters, [`Made::folding`] gives the angles a step reports). Making it on a
//! [`Stack`] rotates each vertex of its arcs by π about the line, laid `lift` above the
//! highest vertex: the flap's layers reverse their order and lie above everything else, as
//! a folded cloth lands. The stack remembers which folds moved each vertex, which the probe
//! reads (the probe of `super::synth`) and the sequence search tells candidates apart by.
//!
//! ```
//! use close_core::border::Point;
//! use close_core::fold::state::{Made, Stack};
//! use close_core::geometry::{Line, Point2, Vector2};
//! // A square folded in half along x = 0.5: vertices 1 and 2 (x = 1) turn over, a layer up.
//! let square: Vec<Point> = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
//!     .iter().map(|p| Point::new(p[0], p[1], 0.0)).collect();
//! let line = Line { point: Point2::new(0.5, 0.0), direction: Vector2::new(0.0, 1.0) };
//! let mut stack = Stack::flat(&square);
//! stack.fold(&Made { line, arcs: vec![[0.5, 2.5]] }, 0.02);
//! let folded = stack.points();
//! assert!((folded[1].x - 0.0).abs() < 1e-12 && (folded[1].z - 0.02).abs() < 1e-12);
//! assert_eq!(folded[0], square[0]);
//! ```

use crate::angle::{angle_to_param, param_to_angle, wrap_tau, ArcVertices};
use crate::border::Point;
use crate::geometry::{Arc, Fold, Folding, Line};

/// A fold as made on the state before it: the line it folds along and the arcs of the
/// border it turned over (border parameters, each anticlockwise from its first point, in
/// walking order).
#[derive(Debug, Clone, PartialEq)]
pub struct Made {
    pub line: Line,
    pub arcs: Vec<[f64; 2]>,
}

impl Made {
    /// The fold turning `arcs` (angles, as a step reports them) over `line` on a border of
    /// `n` vertices: the angles back in the border parameters a fold is made in.
    pub fn from_angles(line: Line, arcs: &[Arc], n: usize) -> Made {
        Made { line, arcs: arcs.iter().map(|a| a.ends().map(|x| angle_to_param(x, n))).collect() }
    }

    /// As a [`Folding`] (angles) of a border of `n` vertices: where the border parameters
    /// of the search become the angles a step reports.
    pub fn folding(&self, n: usize) -> Folding {
        let angle = |s: f64| wrap_tau(param_to_angle(s, n));
        let arcs: Vec<Arc> = self.arcs.iter().map(|&[a, b]| Arc::new(angle(a), angle(b))).collect();
        let fold = Fold::span(&arcs).unwrap_or_default();
        Folding { fold, arcs, line: Some(self.line) }
    }
}

/// Which of the arcs left of a fold's line turn over.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Turn {
    /// All of them (one arc for a line crossing the border twice; several for a
    /// multi-arc fold).
    All,
    /// The one holding this vertex: a fold of one layer of a stack.
    Holding(usize),
}

/// A synthesised state and which folds moved each of its vertices.
#[derive(Debug, Clone, PartialEq)]
pub struct Stack {
    pub(crate) state: Vec<Point>,
    /// Per vertex: the folds that moved it, one bit per fold in the order they were made
    /// (bit 0 the first; folds past the eighth share bit 7), 0 for a vertex no fold moved.
    group: Vec<u8>,
    /// Folds made so far.
    folds: u32,
}

impl Stack {
    /// `points` (a border) with no fold made.
    pub fn flat(points: &[Point]) -> Stack {
        Stack { state: points.to_vec(), group: vec![0; points.len()], folds: 0 }
    }

    /// The state after turning the `arcs` (border parameters, each anticlockwise from its
    /// first point) of `before` over `line`: a rotation by π about the horizontal line at
    /// height `axis` ([`flap_axis`]), so the flap's layers reverse their order and lie above
    /// everything else.
    pub(crate) fn new(before: &[Point], axis: f64, arcs: &[[f64; 2]], line: &Line) -> Stack {
        let mut stack = Stack::flat(before);
        stack.fold_about(axis, arcs, line);
        stack
    }

    /// `before` with the folds `made` made in turn, each flap laid `lift` above the stack.
    pub fn of(before: &[Point], made: &[Made], lift: f64) -> Stack {
        let mut stack = Stack::flat(before);
        for m in made {
            stack.fold(m, lift);
        }
        stack
    }

    /// Make `made` on the state, on top of the folds already made, the flap laid `lift`
    /// above the stack (its height's units: the state's own).
    pub fn fold(&mut self, made: &Made, lift: f64) {
        self.turn(&made.arcs, &made.line, lift);
    }

    /// [`Stack::fold`] of the `arcs` turned over `line`.
    pub(crate) fn turn(&mut self, arcs: &[[f64; 2]], line: &Line, lift: f64) {
        let axis = flap_axis(&self.state, lift);
        self.fold_about(axis, arcs, line);
    }

    fn fold_about(&mut self, axis: f64, arcs: &[[f64; 2]], line: &Line) {
        let bit = 1u8 << self.folds.min(7);
        let n = self.state.len();
        for arc in arcs {
            for v in ArcVertices::of(n, arc[0], arc[1]).vertices() {
                let p = self.state[v];
                let r = line.reflect(&p);
                self.state[v] = Point::new(r.x, r.y, 2.0 * axis - p.z);
                self.group[v] |= bit;
            }
        }
        self.folds += 1;
    }

    /// The border as it lies: each vertex where its folds took it, at its layer's height.
    pub fn points(&self) -> &[Point] {
        &self.state
    }

    /// Per vertex: the folds that moved it, one bit per fold in the order made.
    pub(crate) fn groups(&self) -> &[u8] {
        &self.group
    }

    /// The vertex after `e`, without a remainder (this runs for every probe pair).
    #[inline]
    pub(crate) fn next(&self, e: usize) -> usize {
        if e + 1 == self.state.len() {
            0
        } else {
            e + 1
        }
    }

    /// The folds that moved edge `e`: `Some(group)` when they moved both of its ends alike.
    #[inline]
    pub(crate) fn edge_group(&self, e: usize) -> Option<u8> {
        let g = self.group[e];
        (g == self.group[self.next(e)]).then_some(g)
    }

    /// Every vertex counted as moved, so that no pair of edges keeps its start value: a
    /// state to be probed in full (the probe's `cost_of_state`, [`super::probe`]).
    pub(crate) fn all_moved(mut self) -> Stack {
        self.group.fill(1);
        self
    }
}

/// Height of the axis a flap of `before` is turned about: `lift`/2 above its highest vertex,
/// so the flap lies `lift` above the stack.
pub(crate) fn flap_axis(before: &[Point], lift: f64) -> f64 {
    before.iter().map(|p| p.z).fold(f64::NEG_INFINITY, f64::max) + lift / 2.0
}

/// Mean XY length of the edges of `points`.
pub(crate) fn mean_edge(points: &[Point]) -> f64 {
    let n = points.len();
    (0..n).map(|k| (points[(k + 1) % n].xy() - points[k].xy()).norm()).sum::<f64>() / n as f64
}

/// The arcs of the border left of `line`, each as the border parameters where it enters and
/// leaves that side (anticlockwise from the first), in walking order starting after the
/// widest gap between them, so that the first point of the first arc and the last point of
/// the last span them all as tightly as they can.
pub(crate) fn arcs_left_of(before: &[Point], line: &Line) -> Vec<[f64; 2]> {
    let n = before.len();
    let (ux, uy) = (line.direction.x, line.direction.y);
    let d: Vec<f64> =
        before.iter().map(|p| ux * (p.y - line.point.y) - uy * (p.x - line.point.x)).collect();
    // The vertex after k, without a remainder: this runs for every vertex of every line tried.
    let next = |k: usize| if k + 1 == n { 0 } else { k + 1 };
    let crossing = |k: usize| k as f64 + d[k] / (d[k] - d[next(k)]);
    let enters = (0..n).filter(|&k| d[k] <= 0.0 && d[next(k)] > 0.0);
    let mut arcs: Vec<[f64; 2]> = enters
        .filter_map(|k| {
            // The arc runs until the first edge that leaves the side.
            let leave = (k + 1..n).chain(0..k + 1).find(|&j| d[j] > 0.0 && d[next(j)] <= 0.0)?;
            Some([crossing(k), crossing(leave)])
        })
        .collect();
    if arcs.len() > 1 {
        let nf = n as f64;
        let gap =
            |k: usize| (arcs[k][0] - arcs[(k + arcs.len() - 1) % arcs.len()][1]).rem_euclid(nf);
        let widest = (0..arcs.len()).max_by(|&a, &b| gap(a).total_cmp(&gap(b))).unwrap_or(0);
        arcs.rotate_left(widest);
    }
    arcs
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fold::fixtures::{at, square};
    use crate::geometry::{Point2, Vector2};

    #[test]
    fn arcs_left_of_a_line_are_where_the_border_crosses_it() {
        // y = 0.6 rightwards across a unit square of 16 vertices: its left is above; the border
        // crosses on edge 6 (y 0.5 → 0.75) and edge 13 (0.75 → 0.5).
        let unit = square(4, 0.5, |_| 0.0)
            .iter()
            .map(|p| Point::new(p.x + 0.5, p.y + 0.5, 0.0))
            .collect::<Vec<_>>();
        let across = Line { point: Point2::new(0.0, 0.6), direction: Vector2::new(1.0, 0.0) };
        let arcs = arcs_left_of(&unit, &across);
        assert_eq!(arcs.len(), 1);
        assert!((arcs[0][0] - 6.4).abs() < 1e-12 && (arcs[0][1] - 13.6).abs() < 1e-12, "{arcs:?}");
        // Turned round, the line's left is below: the arc from 13.6 round to 6.4.
        let below = arcs_left_of(
            &unit,
            &Line { point: Point2::new(0.0, 0.6), direction: Vector2::new(-1.0, 0.0) },
        );
        assert!(
            below.len() == 1
                && (below[0][0] - 13.6).abs() < 1e-12
                && (below[0][1] - 6.4).abs() < 1e-12,
            "{below:?}"
        );
        // A line that misses the border gives no arc; one that cuts off a single vertex, an arc
        // of that vertex alone (too small to fold, the candidates' size check leaves it out).
        assert!(arcs_left_of(
            &unit,
            &Line { point: Point2::new(0.0, 2.0), direction: Vector2::new(-1.0, 0.0) }
        )
        .is_empty());
        let h = 0.5f64.sqrt();
        let corner = arcs_left_of(
            &unit,
            &Line { point: Point2::new(0.05, 0.05), direction: Vector2::new(-h, h) },
        );
        assert!(
            corner.len() == 1 && ArcVertices::of(16, corner[0][0], corner[0][1]).vertices().eq([0]),
            "{corner:?}"
        );

        // A U (open upwards) crossed by y = 1.5: both prongs, each its own arc.
        let corners = [
            [0.0, 0.0],
            [3.0, 0.0],
            [3.0, 2.0],
            [2.0, 2.0],
            [2.0, 1.0],
            [1.0, 1.0],
            [1.0, 2.0],
            [0.0, 2.0],
        ];
        let u: Vec<Point> = (0..corners.len() * 4)
            .map(|k| {
                let (a, b, t) =
                    (corners[k / 4], corners[(k / 4 + 1) % corners.len()], (k % 4) as f64 / 4.0);
                Point::new(a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), 0.0)
            })
            .collect();
        let line = Line { point: Point2::new(0.0, 1.5), direction: Vector2::new(1.0, 0.0) };
        let arcs = arcs_left_of(&u, &line);
        assert_eq!(arcs.len(), 2, "{arcs:?}");
        for s in &arcs {
            // Each end lies on the line, and the arc's vertices above it, the rest below.
            assert!(s.iter().all(|&e| (at(&u, e).y - 1.5).abs() < 1e-12), "{s:?}");
            let inside = ArcVertices::of(u.len(), s[0], s[1]);
            assert!(inside.vertices().all(|v| u[v].y > 1.5));
            assert!(inside.len >= 2);
        }
        let above: usize = arcs.iter().map(|s| ArcVertices::of(u.len(), s[0], s[1]).len).sum();
        assert_eq!(above, u.iter().filter(|p| p.y > 1.5).count());
    }
}
