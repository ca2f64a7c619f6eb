//! The candidates of a fold sequence: each fold a line on the state it is made on, through
//! cut points where the creases meet the border, and which of the arcs left of it turn
//! ([`Move`]); the folds of a candidate made in turn ([`make`]); the folds that can follow
//! on a state of the beam ([`moves_on`]).

use std::f64::consts::PI;

use crate::angle::{distance, ArcVertices};
use crate::border::{point_at, Point};
use crate::geometry::{Line, Point2};

use crate::fold::params::{Params, SequenceParams};
use crate::fold::probe::Probe;
use crate::fold::state::{arcs_left_of, mean_edge, Made, Stack, Turn};

/// Most folds one step may hold: a capacity, not a knob (a synthesised state keeps one bit
/// per fold made, and a sequence's cut points four bits each).
pub const MAX_FOLDS: usize = 4;

/// Where a fold's line lies on the state it is made on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Anchor {
    /// Through the border points at these two parameters.
    Points([f64; 2]),
    /// Through the border point at this parameter, at this angle to the x axis.
    Ray(f64, f64),
}

/// One fold of a candidate sequence.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Move {
    pub(super) anchor: Anchor,
    /// The line runs the other way (its left, the side that turns, is the other side).
    pub(super) reversed: bool,
    pub(super) turn: Turn,
}

impl Move {
    /// The directed line on `state`; `None` when its two points coincide.
    pub(super) fn line(&self, state: &[Point]) -> Option<Line> {
        let line = match self.anchor {
            Anchor::Points([a, b]) => Line::through(&point_at(state, a), &point_at(state, b))?,
            Anchor::Ray(a, phi) => {
                let p = point_at(state, a);
                Line::at_angle(Point2::new(p.x, p.y), phi)
            }
        };
        Some(if self.reversed { Line { direction: -line.direction, ..line } } else { line })
    }

    /// The arcs this fold turns over on `state` (border parameters): `None` when it turns
    /// fewer than two vertices, or leaves fewer than two, or when no cloth lies right of its
    /// line (within [`SequenceParams::on_line_edges`]): a line along a straight side, all the
    /// cloth left of it, turns the whole cloth over, which is no fold though it lands
    /// congruent to one.
    pub(super) fn arcs(
        &self,
        state: &[Point],
        line: &Line,
        on_line_edges: f64,
    ) -> Option<Vec<[f64; 2]>> {
        let n = state.len();
        let right =
            state.iter().map(|p| -line.direction.perp(&(p.xy() - line.point))).fold(0.0, f64::max);
        if right <= on_line_edges * mean_edge(state) {
            return None;
        }
        let left = arcs_left_of(state, line);
        let arcs: Vec<[f64; 2]> = match self.turn {
            Turn::All => left,
            Turn::Holding(v) => {
                left.into_iter().filter(|a| ArcVertices::of(n, a[0], a[1]).contains(v)).collect()
            }
        };
        // A line clipping the border between two vertices turns nothing there.
        let arcs: Vec<[f64; 2]> =
            arcs.into_iter().filter(|a| ArcVertices::of(n, a[0], a[1]).len > 0).collect();
        let moved: usize = arcs.iter().map(|a| ArcVertices::of(n, a[0], a[1]).len).sum();
        (moved >= 2 && moved + 2 <= n).then_some(arcs)
    }

    /// The same fold moved by `delta` edges along the border (for a ray, by `delta[0]` edges
    /// and `delta[1]` times `angle_step` radians).
    pub(super) fn moved(&self, delta: [f64; 2], angle_step: f64) -> Move {
        let anchor = match self.anchor {
            Anchor::Points([a, b]) => Anchor::Points([a + delta[0], b + delta[1]]),
            Anchor::Ray(a, phi) => Anchor::Ray(a + delta[0], phi + delta[1] * angle_step),
        };
        Move { anchor, ..*self }
    }
}

/// The folds of `moves` made in turn on `before`; `None` when one of them cannot be made.
pub(super) fn make(
    before: &[Point],
    moves: &[Move],
    params: &Params,
) -> Option<(Stack, Vec<Made>)> {
    let mut turned = Stack::flat(before);
    let made = moves.iter().map(|m| make_next(&mut turned, m, params)).collect::<Option<_>>()?;
    Some((turned, made))
}

/// The fold `m` made on `turned`; `None` when it cannot be made (`turned` is then left
/// as it was).
pub(super) fn make_next(turned: &mut Stack, m: &Move, params: &Params) -> Option<Made> {
    let line = m.line(&turned.state)?;
    let arcs = m.arcs(&turned.state, &line, params.sequence.on_line_edges)?;
    turned.turn(&arcs, &line, params.synthesis.lift);
    Some(Made { line, arcs })
}

pub(super) fn cost(probe: &Probe, before: &[Point], moves: &[Move], params: &Params) -> f64 {
    make(before, moves, params).map_or(f64::INFINITY, |(turned, _)| probe.cost(&turned))
}

/// `made` with folds `j` and `j + 1` made as one when they run along one line, turning the
/// same side (a multi-arc fold made as two): fold `j` turning every arc left of its line.
pub(super) fn merged(
    before: &[Point],
    made: &[Made],
    j: usize,
    params: &Params,
) -> Option<Vec<Made>> {
    let (a, b) = (&made[j].line, &made[j + 1].line);
    let (u, v) = (a.direction.normalize(), b.direction.normalize());
    let apart = u.perp(&(b.point - a.point)).abs();
    let near = params.synthesis.coincide_edges * mean_edge(before);
    if u.dot(&v) < params.sequence.parallel_cos || apart > near {
        return None;
    }
    let state = Stack::of(before, &made[..j], params.synthesis.lift).state;
    let mut joined = made[..j].to_vec();
    joined.push(Made { line: *a, arcs: arcs_left_of(&state, a) });
    joined.extend_from_slice(&made[j + 2..]);
    Some(joined)
}

/// Where the directions of lines through lone or stacked cut points start: the cloth's
/// frame, not the table's, so that a turned cloth is searched alike.
#[derive(Debug, Clone, Copy)]
pub(super) enum Frame<'a> {
    /// The flat cloth, with the directions square to its straight sides (radians).
    Flat(&'a [f64]),
    /// After a fold along a line of this direction (radians).
    After(f64),
}

/// The angle between two lines of directions `a` and `b` (radians), in [0, π/2].
pub(super) fn between_lines(a: f64, b: f64) -> f64 {
    distance(2.0 * a, 2.0 * b) / 2.0
}

/// The directions square to the straight sides of `border` (runs of at least
/// [`SequenceParams::side_edges`] edges turning less than [`SequenceParams::side_turn_rad`]
/// from one to the next), each once, in radians modulo π.
pub(super) fn square_to_sides(border: &[Point], params: &SequenceParams) -> Vec<f64> {
    let side_turn = params.side_turn_rad;
    let n = border.len();
    let heading = |k: usize| {
        let d = border[(k + 1) % n] - border[k];
        d.y.atan2(d.x)
    };
    let turn = |k: usize| distance(heading((k + 1) % n), heading(k));
    // From a corner, so that no side is cut in two where the border starts.
    let Some(corner) = (0..n).find(|&k| turn(k) >= side_turn) else { return Vec::new() };
    let mut squares: Vec<f64> = Vec::new();
    let mut run = 1;
    for k in (corner + 1..=corner + n).map(|k| k % n) {
        if turn(k) < side_turn {
            run += 1;
            continue;
        }
        let square = (heading(k) + PI / 2.0).rem_euclid(PI);
        if run >= params.side_edges
            && squares.iter().all(|&a| between_lines(a, square) >= side_turn)
        {
            squares.push(square);
        }
        run = 1;
    }
    squares
}

/// The folds that can be made on `state` along lines through two of the cut `points` that no fold
/// before it ran through (creases meet the border at points of their own), each with the indices of
/// the two points. Where two points lie together (stacked layers) the line's direction is searched,
/// from the last fold's (or on a flat cloth the border's at the point), every π /
/// [`SequenceParams::coarse_directions`] (the search tries the best again finer). On a flat cloth
/// lines through each point alone are tried too, square to each straight side: a crease that meets
/// a straight side square to it leaves both its pieces on that side's line, so no cut shows it
/// there.
pub(super) fn moves_on(
    state: &[Point],
    points: &[f64],
    used: &[usize],
    frame: Frame,
    params: &Params,
) -> Vec<(Move, [usize; 2])> {
    let n = state.len();
    let near = params.synthesis.coincide_edges * mean_edge(state);
    let coarse = params.sequence.coarse_directions;
    let free: Vec<usize> = (0..points.len()).filter(|k| !used.contains(k)).collect();
    let mut anchors: Vec<(Anchor, [usize; 2])> = Vec::new();
    for (k, &i) in free.iter().enumerate() {
        if let Frame::Flat(squares) = frame {
            anchors.extend(squares.iter().map(|&phi| (Anchor::Ray(points[i], phi), [i, i])));
        }
        for &j in &free[k + 1..] {
            let (a, b) = (points[i], points[j]);
            let (pa, pb) = (point_at(state, a), point_at(state, b));
            let apart = (pa.xy() - pb.xy()).norm();
            if apart >= near {
                anchors.push((Anchor::Points([a, b]), [i, j]));
            }
            if apart < params.sequence.ray_reach * near {
                // The cut points lie within an edge or two of the creases, so two that
                // should meet may not quite.
                let base = match frame {
                    Frame::After(heading) => heading,
                    Frame::Flat(_) => {
                        let along = point_at(state, a + 0.5) - point_at(state, a - 0.5);
                        along.y.atan2(along.x)
                    }
                };
                anchors.extend(
                    (0..coarse)
                        .map(|d| (Anchor::Ray(a, base + PI * d as f64 / coarse as f64), [i, j])),
                );
            }
        }
    }
    let mut moves = Vec::new();
    for (anchor, through) in anchors {
        for reversed in [false, true] {
            let m = Move { anchor, reversed, turn: Turn::All };
            let Some(line) = m.line(state) else { continue };
            let left = arcs_left_of(state, &line);
            moves.push((m, through));
            if left.len() > 1 {
                for arc in &left {
                    let inside = ArcVertices::of(n, arc[0], arc[1]);
                    let middle = inside.vertices().nth(inside.len / 2);
                    if let Some(v) = middle {
                        moves.push((Move { turn: Turn::Holding(v), ..m }, through));
                    }
                }
            }
        }
    }
    moves
}

/// A sequence being built: the cut set its folds run through, its folds, and the cut points
/// they ran through.
#[derive(Clone)]
pub(super) struct Partial {
    pub(super) set: usize,
    pub(super) moves: Vec<Move>,
    pub(super) used: Vec<usize>,
}

impl Move {
    /// The fold as bits, to tell equal folds apart from the others.
    pub(super) fn bits(&self) -> [u64; 4] {
        let (kind, [a, b]) = match self.anchor {
            Anchor::Points(points) => (0, points),
            Anchor::Ray(point, phi) => (1, [point, phi]),
        };
        let turn = match self.turn {
            Turn::All => u64::MAX,
            Turn::Holding(v) => v as u64,
        };
        [kind + 2 * u64::from(self.reversed), a.to_bits(), b.to_bits(), turn]
    }
}

/// `moves` as bits, to tell equal sequences of folds apart from the others.
pub(super) fn key(moves: &[Move]) -> Vec<u64> {
    moves.iter().flat_map(Move::bits).collect()
}

/// The cut set a sequence's folds run through and how many times they ran through each of
/// its points (four bits a point), in any order: a set has at most 8 points, and a sequence
/// at most [`MAX_FOLDS`] folds of two points each.
pub(super) type Through = (usize, u32);

/// `through` with the cut points `points` added.
pub(super) fn through_also((set, counts): Through, points: &[usize]) -> Through {
    debug_assert!(points.iter().all(|&k| k < 8));
    (set, points.iter().fold(counts, |c, &k| c + (1 << (4 * k))))
}

impl Partial {
    /// The cut set and the cut points its folds ran through, in any order.
    pub(super) fn through(&self) -> Through {
        through_also((self.set, 0), &self.used)
    }

    /// This sequence with `candidate`'s fold made next.
    pub(super) fn then(&self, candidate: &Candidate) -> Partial {
        let mut longer = self.clone();
        longer.moves.push(candidate.next);
        longer.used.extend(candidate.points);
        longer
    }
}

/// One more fold on a state of the beam.
#[derive(Clone, Copy)]
pub(super) struct Candidate {
    /// The beam state it is made on.
    pub(super) parent: usize,
    pub(super) next: Move,
    /// The cut points its line runs through.
    pub(super) points: [usize; 2],
    /// Its sequence's [`Partial::through`].
    pub(super) through: Through,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fold::fixtures::unit_square;

    #[test]
    fn a_line_along_a_side_turns_nothing_over() {
        // Rays from vertex 0, the bottom left corner, along the bottom side: the whole
        // square lies left of it or on it (a flip, no fold); a degree up, a sliver of the
        // bottom side lies right of it and the rest folds over it.
        let state = unit_square(8);
        let ray =
            |angle: f64| Move { anchor: Anchor::Ray(0.0, angle), reversed: false, turn: Turn::All };
        let on_line = Params::default().sequence.on_line_edges;
        let arcs = |m: Move| m.arcs(&state, &m.line(&state).expect("a ray has a line"), on_line);
        assert_eq!(arcs(ray(0.0)), None);
        let sliver = arcs(ray(1f64.to_radians())).expect("a fold");
        assert_eq!(sliver.len(), 1);
        // Stack the other way round, the line leaves the whole square right of it: no arc.
        assert_eq!(arcs(Move { reversed: true, ..ray(0.0) }), None);
    }

    #[test]
    fn straight_sides_give_the_directions_square_to_them() {
        // A square, turned: two directions, square to its sides, whatever vertex it starts at.
        for (angle, from) in [(0.0, 0), (0.3, 5)] {
            let (c, s) = (f64::cos(angle), f64::sin(angle));
            let mut turned: Vec<Point> = unit_square(12)
                .iter()
                .map(|p| Point::new(c * p.x - s * p.y, s * p.x + c * p.y, 0.0))
                .collect();
            turned.rotate_left(from);
            let mut squares = square_to_sides(&turned, &SequenceParams::default());
            squares.sort_by(f64::total_cmp);
            assert_eq!(squares.len(), 2, "{squares:?}");
            assert!(
                between_lines(squares[0], angle) < 1e-9
                    || between_lines(squares[0], angle + PI / 2.0) < 1e-9
            );
            assert!((between_lines(squares[0], squares[1]) - PI / 2.0).abs() < 1e-9);
        }
        // A circle has no straight side.
        let circle: Vec<Point> = (0..100)
            .map(|k| {
                let t = 2.0 * PI * k as f64 / 100.0;
                Point::new(t.cos(), t.sin(), 0.0)
            })
            .collect();
        assert!(square_to_sides(&circle, &SequenceParams::default()).is_empty());
    }
}
