//! Fold sequences in one step: the folds that took a flat cloth to a state whose disk alone
//! is seen.
//!
//! Our extension of CloSE, after the paper's "Multi-folds" section (Kamat, Borràs, Torras,
//! "CloSE"): the diff disk of two folds seen at once holds the lines of both. A cloth folded
//! k times, seen flat and folded with no frame between, is read as a sequence of folds, each
//! made on the state the ones before it left: later folds cross stacked layers and may turn
//! several arcs of the border at once.
//!
//! **Where the creases meet the border.** Folds of a flat cloth move each piece between the
//! creases rigidly, so a pair of edges of one piece keeps |dGLI|: a border arc inside one
//! piece holds no change of the abs diff disk g. The border split into m arcs of least
//! change within themselves ([`super::cut::find_cuts`]) puts its m cut points where the
//! creases meet the border. Straight sides hold no change at all (collinear edges have dGLI
//! 0 before and after), so a split at a corner would cost nothing: each pair's change is
//! offset by [`CutParams::start_share`] times its start |dGLI|, which favours arcs whose pairs could
//! have shown a change.
//!
//! **Analysis by synthesis.** Each fold of a candidate sequence is a line on the state it is
//! made on, through two cut points where they lie on that state, or through one in a
//! searched direction where two coincide (stacked layers) or, for the first fold, through
//! one alone (a crease can meet a straight side where no cut shows it), directions taken
//! in the cloth's frame, and the arcs of the border left
//! of it that turn over: all of them, or the one holding a given vertex (a fold of the top
//! layer only). The folds are made in turn ([`super::synth`]: each flap rotated by π about
//! its line, laid above the stack), and the synthesised state's dGLI on probe pairs is
//! compared with the measured end disk (`asinh`-compressed, mean absolute difference). A
//! beam search builds the sequences a fold at a time on a screen of strided pairs; besides
//! the best, the best sequence through each set of cut points is carried on (a sequence's
//! first folds can explain the end disk less than the flat cloth does); the best are
//! refined, all their folds together, by a pattern search over each fold's two parameters,
//! and judged on a larger probe, each at the flap height that fits it best (the cloth's
//! thickness, which sets how far apart its layers lie, shows in the disk).
//!
//! **Layer order.** Two perpendicular half folds done in either order land alike on the
//! table, but for a rigid motion, which no disk sees: what tells them apart is the order of
//! their layers. A sequence whose end lands like the best one's (within [`LayerOrderParams::congruent`]) is
//! compared with it on the order alone: each one's outline with each one's heights. Lines
//! are refined and layers ordered on a truncated loss ([`LayerOrderParams::capped_mismatch`]), as a few pairs
//! of nearly collinear or stacked edges turn measurement noise into large mismatches.
//!
//! **Model selection.** k folds are reported only when they explain markedly more of the end
//! disk than fewer ([`SelectionParams`]): more than the answer so far (the best of
//! fewer folds accepted), and more than any k − 1 of their own (else those are the answer
//! so far, if better); each length is tried in turn; the search runs only when the step's one
//! fold leaves more than [`SelectionParams::explained_by_one_share`] of it unexplained. The search's own best single
//! fold is weighed alike: it replaces the step's fold when it explains markedly more (a
//! fold of several arcs on a flat start, which the step's one-fold search does not make),
//! and sequences are then weighed against it. A fold or sequence that
//! leaves more than [`SelectionParams::unexplained_share`] unexplained is not a confident fold.
//!
//! The end border's coordinates are never read: only its disk.

use std::collections::{HashMap, HashSet};
use std::f64::consts::PI;
use std::sync;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::angle::{distance, ArcVertices};
use crate::border::{point_at, Point};
use crate::budget::Deadline;
use crate::disk::Disk;
use crate::error::Result;
use crate::geometry::{Folding, Line, Point2};
use crate::metrics::aligned_rmse_xy;

use super::cut::find_cuts;
#[cfg(doc)]
use super::params::{CutParams, LayerOrderParams, SelectionParams};
use super::params::{Params, SequenceParams};
use super::read::Seen;
use super::refine::{refine, Costs};
use super::seed::{is_flat, Seed};
use super::state::{arcs_left_of, mean_edge, Made, Stack, Turn};
use super::synth::{sampled_edges, Probe, Synthesis};

/// Most folds one step may hold: a capacity, not a knob (a synthesised state keeps one bit
/// per fold made, and a sequence's cut points four bits each).
pub const MAX_FOLDS: usize = 4;

/// Where a fold's line lies on the state it is made on.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Anchor {
    /// Through the border points at these two parameters.
    Points([f64; 2]),
    /// Through the border point at this parameter, at this angle to the x axis.
    Ray(f64, f64),
}

/// One fold of a candidate sequence.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Move {
    anchor: Anchor,
    /// The line runs the other way (its left, the side that turns, is the other side).
    reversed: bool,
    turn: Turn,
}

impl Move {
    /// The directed line on `state`; `None` when its two points coincide.
    fn line(&self, state: &[Point]) -> Option<Line> {
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
    fn arcs(&self, state: &[Point], line: &Line, on_line_edges: f64) -> Option<Vec<[f64; 2]>> {
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
    fn moved(&self, delta: [f64; 2], angle_step: f64) -> Move {
        let anchor = match self.anchor {
            Anchor::Points([a, b]) => Anchor::Points([a + delta[0], b + delta[1]]),
            Anchor::Ray(a, phi) => Anchor::Ray(a + delta[0], phi + delta[1] * angle_step),
        };
        Move { anchor, ..*self }
    }
}

/// The folds of `moves` made in turn on `before`; `None` when one of them cannot be made.
fn make(before: &[Point], moves: &[Move], params: &Params) -> Option<(Stack, Vec<Made>)> {
    let mut turned = Stack::flat(before);
    let made = moves.iter().map(|m| make_next(&mut turned, m, params)).collect::<Option<_>>()?;
    Some((turned, made))
}

/// The fold `m` made on `turned`; `None` when it cannot be made (`turned` is then left
/// as it was).
fn make_next(turned: &mut Stack, m: &Move, params: &Params) -> Option<Made> {
    let line = m.line(&turned.state)?;
    let arcs = m.arcs(&turned.state, &line, params.sequence.on_line_edges)?;
    turned.turn(&arcs, &line, params.synthesis.lift);
    Some(Made { line, arcs })
}

fn cost(probe: &Probe, before: &[Point], moves: &[Move], params: &Params) -> f64 {
    make(before, moves, params).map_or(f64::INFINITY, |(turned, _)| probe.cost(&turned))
}

/// `made` with folds `j` and `j + 1` made as one when they run along one line, turning the
/// same side (a multi-arc fold made as two): fold `j` turning every arc left of its line.
fn merged(before: &[Point], made: &[Made], j: usize, params: &Params) -> Option<Vec<Made>> {
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

/// Every pair of `edges`.
fn all_pairs(edges: &[usize]) -> Vec<(usize, usize)> {
    edges
        .iter()
        .enumerate()
        .flat_map(|(k, &i)| edges[k + 1..].iter().map(move |&j| (i, j)))
        .collect()
}

/// Where the directions of lines through lone or stacked cut points start: the cloth's
/// frame, not the table's, so that a turned cloth is searched alike.
#[derive(Debug, Clone, Copy)]
enum Frame<'a> {
    /// The flat cloth, with the directions square to its straight sides (radians).
    Flat(&'a [f64]),
    /// After a fold along a line of this direction (radians).
    After(f64),
}

/// The angle between two lines of directions `a` and `b` (radians), in [0, π/2].
fn between_lines(a: f64, b: f64) -> f64 {
    distance(2.0 * a, 2.0 * b) / 2.0
}

/// The directions square to the straight sides of `border` (runs of at least
/// [`SequenceParams::side_edges`] edges turning less than [`SequenceParams::side_turn_rad`]
/// from one to the next), each once, in radians modulo π.
fn square_to_sides(border: &[Point], params: &SequenceParams) -> Vec<f64> {
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

/// The folds that can be made on `state` along lines through two of the cut `points` that
/// no fold before it ran through (creases meet the border at points of their own), each with
/// the indices of the two points. Where two points lie together (stacked layers) the line's
/// direction is searched, from the last fold's (or on a flat cloth the border's at the
/// point), every π / [`SequenceParams::coarse_directions`] (the search tries the best again finer). On a
/// flat cloth lines through each point alone are tried too, square to each straight side: a
/// crease that meets a straight side square to it leaves both its pieces on that side's
/// line, so no cut shows it there.
fn moves_on(
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
struct Partial {
    set: usize,
    moves: Vec<Move>,
    used: Vec<usize>,
}

impl Move {
    /// The fold as bits, to tell equal folds apart from the others.
    fn bits(&self) -> [u64; 4] {
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
fn key(moves: &[Move]) -> Vec<u64> {
    moves.iter().flat_map(Move::bits).collect()
}

/// The cut set a sequence's folds run through and how many times they ran through each of
/// its points (four bits a point), in any order: a set has at most 8 points, and a sequence
/// at most [`MAX_FOLDS`] folds of two points each.
type Through = (usize, u32);

/// `through` with the cut points `points` added.
fn through_also((set, counts): Through, points: &[usize]) -> Through {
    debug_assert!(points.iter().all(|&k| k < 8));
    (set, points.iter().fold(counts, |c, &k| c + (1 << (4 * k))))
}

impl Partial {
    /// The cut set and the cut points its folds ran through, in any order.
    fn through(&self) -> Through {
        through_also((self.set, 0), &self.used)
    }

    /// This sequence with `candidate`'s fold made next.
    fn then(&self, candidate: &Candidate) -> Partial {
        let mut longer = self.clone();
        longer.moves.push(candidate.next);
        longer.used.extend(candidate.points);
        longer
    }
}

/// One more fold on a state of the beam.
#[derive(Clone, Copy)]
struct Candidate {
    /// The beam state it is made on.
    parent: usize,
    next: Move,
    /// The cut points its line runs through.
    points: [usize; 2],
    /// Its sequence's [`Partial::through`].
    through: Through,
}

/// A candidate sequence screened.
struct Scored {
    cost: f64,
    candidate: Candidate,
    /// What its folds moved ([`Stack::groups`]), shared by the equal sequences.
    groups: sync::Arc<[u8]>,
}

impl Scored {
    /// The sequence, its folds made on `beam`'s state.
    fn partial(&self, beam: &[Partial]) -> Partial {
        beam[self.candidate.parent].then(&self.candidate)
    }
}

/// `candidates` (each on a state of `beam`, made in `parents`) screened on
/// `probes.screen`, best first; once per distinct sequence of folds: the cut sets share many
/// points, so the same folds come from several of them. More than [`SequenceParams::glanced`] are first
/// glanced at on `probes.glance`, and only the best so many of them, and the best through
/// each set of cut points (which the beam carries on), screened. Those that cannot be made,
/// or come after `deadline`, are left out.
fn screen(
    beam: &[Partial],
    parents: &[Option<(Stack, Vec<Made>)>],
    probes: &Probes,
    candidates: Vec<Candidate>,
    deadline: &Deadline,
    params: &Params,
) -> Vec<Scored> {
    let glanced_best = params.sequence.glanced;
    // Equal sequences: equal folds on equal beam states.
    let mut states: HashMap<Vec<u64>, usize> = HashMap::new();
    let state_of: Vec<usize> =
        beam.iter().enumerate().map(|(k, p)| *states.entry(key(&p.moves)).or_insert(k)).collect();
    let mut first: HashMap<(usize, [u64; 4]), usize> = HashMap::new();
    let mut distinct: Vec<usize> = Vec::new();
    let slots: Vec<usize> = candidates
        .iter()
        .enumerate()
        .map(|(k, c)| {
            *first.entry((state_of[c.parent], c.next.bits())).or_insert_with(|| {
                distinct.push(k);
                distinct.len() - 1
            })
        })
        .collect();
    // Candidate k's state: its fold made on a copy of its parent's.
    let made = |k: usize| -> Option<Stack> {
        let c = &candidates[k];
        let mut turned = parents[c.parent].as_ref()?.0.clone();
        make_next(&mut turned, &c.next, params)?;
        Some(turned)
    };
    let mut wanted = vec![true; distinct.len()];
    if distinct.len() > glanced_best {
        let glanced: Vec<f64> = distinct
            .par_iter()
            .map(|&c| match made(c) {
                Some(turned) if !deadline.expired() => probes.glance.cost(&turned),
                _ => f64::INFINITY,
            })
            .collect();
        let mut ranked = glanced.clone();
        let (_, &mut worst, _) = ranked.select_nth_unstable_by(glanced_best - 1, f64::total_cmp);
        for (want, &cost) in wanted.iter_mut().zip(&glanced) {
            *want = cost <= worst;
        }
        let mut by_glance: Vec<usize> = (0..candidates.len()).collect();
        by_glance.sort_by(|&a, &b| glanced[slots[a]].total_cmp(&glanced[slots[b]]));
        let mut through = HashSet::new();
        for k in by_glance {
            if through.insert(candidates[k].through) {
                wanted[slots[k]] = true;
            }
        }
    }
    let screened: Vec<Option<(f64, sync::Arc<[u8]>)>> = distinct
        .par_iter()
        .zip(&wanted)
        .map(|(&c, &wanted)| {
            if !wanted || deadline.expired() {
                return None;
            }
            let turned = made(c)?;
            Some((probes.screen.cost(&turned), turned.groups().into()))
        })
        .collect();
    let mut scored: Vec<Scored> = candidates
        .into_iter()
        .zip(slots)
        .filter_map(|(candidate, slot)| {
            let (cost, groups) = screened[slot].clone()?;
            Some(Scored { cost, candidate, groups })
        })
        .collect();
    scored.sort_by(|a, b| a.cost.total_cmp(&b.cost));
    scored
}

/// A sequence judged at the flap height that fits it best.
struct Judged {
    /// Mean mismatch on the judging probe.
    cost: f64,
    made: Vec<Made>,
    lift: f64,
    /// The synthesised end state at that height.
    state: Vec<Point>,
}

/// `made` judged on `judge` at each of `lifts` (at least one, [`SequenceParams::lifts`]), the
/// best kept.
fn judge_made(judge: &Probe, before: &[Point], made: Vec<Made>, lifts: &[f64]) -> Judged {
    let (cost, lift, state) = lifts
        .iter()
        .map(|&lift| {
            let t = Stack::of(before, &made, lift);
            (judge.cost(&t), lift, t.state)
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .expect("Params::check keeps a lift to try");
    Judged { cost, made, lift, state }
}

/// The probes of one step: the screen (strided pairs, for the beam), the judge (more
/// strided pairs, every sequence and the one fold judged alike) and the order test's.
struct Probes {
    screen: Probe,
    /// A quarter of `screen`'s pairs, to rank many candidates before screening the best.
    glance: Probe,
    judge: Probe,
    order: Probe,
}

/// The best sequence of each length from one fold up to `max_folds`, judged on `probes`,
/// with the sequences of its length judged about as well (its twins and alternatives; none
/// for one fold); a length of two or more whose best one `deeper` rejects is the last
/// searched (the model selection needs no longer ones).
/// [`Cancelled`](crate::error::Error::Cancelled) once `deadline` expires: the search is checked between candidates.
fn search(
    seen: &Seen,
    probes: &Probes,
    params: &Params,
    max_folds: usize,
    deeper: impl Fn(&Judged) -> bool,
    deadline: &Deadline,
) -> Result<Vec<(Judged, Vec<Judged>)>> {
    let Seen { before, start, end } = *seen;
    let n = before.len();
    let g = start.abs_diff(end);
    let weight = params.cut.start_share;
    let offset: Vec<f64> =
        g.values().iter().zip(start.values()).map(|(c, s)| c - weight * s.abs()).collect();
    let Ok(offset) = Disk::from_values(n, offset) else { return Ok(Vec::new()) };
    // Cut points of as many arcs as the sequences could make: 2 per fold line on a flat
    // cloth, more where it crosses layers.
    let cut_sets: Vec<Vec<f64>> = [4usize, 6, 8]
        .into_iter()
        .filter(|&m| m <= 2 * max_folds + 2 && m < n)
        .filter_map(|m| find_cuts(&offset, m, &params.cut).map(|c| c.points))
        .collect();
    let (q, lift) = (&params.sequence, params.synthesis.lift);
    let squares = square_to_sides(before, q);
    let mut beam: Vec<Partial> = (0..cut_sets.len())
        .map(|set| Partial { set, moves: Vec::new(), used: Vec::new() })
        .collect();
    // Sequences refined and judged, those that cannot be made, or come after `deadline`, left out.
    let judge_all = |chosen: Vec<Vec<Move>>| -> Vec<Judged> {
        chosen
            .into_par_iter()
            .filter_map(|moves| {
                if deadline.expired() {
                    return None;
                }
                let moves = settle(seen, moves, params);
                let (_, made) = make(before, &moves, params)?;
                Some(judge_made(&probes.judge, before, made, &q.lifts))
            })
            .collect()
    };
    let mut found = Vec::new();
    for level in 0..max_folds {
        deadline.check()?;
        // Every fold through the free cut points on each state of the beam, made once: each
        // candidate makes only its last fold on a copy.
        let parents: Vec<Option<(Stack, Vec<Made>)>> =
            beam.par_iter().map(|partial| make(before, &partial.moves, params)).collect();
        let (squares, cut_sets) = (&squares, &cut_sets);
        let candidates: Vec<Candidate> = beam
            .par_iter()
            .zip(&parents)
            .enumerate()
            .flat_map_iter(|(parent, (partial, made))| {
                let through = partial.through();
                made.iter().flat_map(move |(turned, made)| {
                    let frame =
                        made.last().map_or(Frame::Flat(squares), |m| Frame::After(m.line.angle()));
                    moves_on(&turned.state, &cut_sets[partial.set], &partial.used, frame, params)
                        .into_iter()
                        .map(move |(next, points)| Candidate {
                            parent,
                            next,
                            points,
                            through: through_also(through, &points),
                        })
                })
            })
            .collect();
        let mut scored = screen(&beam, &parents, probes, candidates, deadline, params);
        // Rays were tried every π / `coarse_directions`: the best are tried again a fine step
        // either side.
        let finer: Vec<Candidate> = scored
            .iter()
            .filter(|s| matches!(s.candidate.next.anchor, Anchor::Ray(..)))
            .take(q.finer_rays)
            .flat_map(|s| {
                let step = PI / params.synthesis.directions as f64;
                [-1.0, 1.0].map(|d| Candidate {
                    next: s.candidate.next.moved([0.0, d], step),
                    ..s.candidate
                })
            })
            .collect();
        scored.extend(screen(&beam, &parents, probes, finer, deadline, params));
        scored.sort_by(|a, b| a.cost.total_cmp(&b.cost));
        // Distinct by what the folds moved.
        let width = if level == 0 { q.first_beam } else { q.beam };
        let mut kept: Vec<&Scored> = Vec::new();
        for s in &scored {
            if kept.len() == width {
                break;
            }
            if kept.iter().all(|k| k.groups != s.groups) {
                kept.push(s);
            }
        }
        if kept.is_empty() {
            break;
        }
        // Carried on: the beam, and the best sequence through each set of cut points the
        // beam does not hold, with its last fold turning the smaller part and with it
        // turning the larger, unless it moves what one carried already moves. The end disk
        // ranks a sequence's first folds poorly when its last ones are still to come (sides
        // folded in leave a cloth folded in half less explained than the flat one), but
        // which creases they are, and which side of each turned, are few enough to keep.
        let mut carried: Vec<Partial> = kept.iter().map(|k| k.partial(&beam)).collect();
        let smaller =
            |s: &Scored| 2 * s.groups.iter().filter(|&&g| g & (1 << level) != 0).count() <= n;
        let mut through: HashSet<(Through, bool)> =
            kept.iter().map(|k| (k.candidate.through, smaller(k))).collect();
        let mut moved: HashSet<sync::Arc<[u8]>> = kept.iter().map(|k| k.groups.clone()).collect();
        for s in &scored {
            if through.insert((s.candidate.through, smaller(s))) && moved.insert(s.groups.clone()) {
                carried.push(s.partial(&beam));
            }
        }
        if level == 0 {
            // The search's own best single fold, for the model selection to weigh against
            // the step's detected one: a fold whose crease meets two straight sides square
            // to them is found here, through one cut point in a searched direction.
            let singles =
                judge_all(kept.iter().take(q.singles).map(|k| k.partial(&beam).moves).collect());
            let best = singles.into_iter().min_by(|a, b| a.cost.total_cmp(&b.cost));
            found.extend(best.map(|one| (one, Vec::new())));
            beam = carried;
            continue;
        }
        // Refined: the best of each state the beam came from first.
        let mut chosen: Vec<Vec<Move>> = Vec::new();
        let mut prefixes: Vec<usize> = Vec::new();
        for k in &kept {
            if chosen.len() < q.refined && !prefixes.contains(&k.candidate.parent) {
                prefixes.push(k.candidate.parent);
                chosen.push(k.partial(&beam).moves);
            }
        }
        for k in &kept {
            let moves = k.partial(&beam).moves;
            if chosen.len() < q.refined && !chosen.contains(&moves) {
                chosen.push(moves);
            }
        }
        let mut judged = judge_all(chosen);
        deadline.check()?;
        judged.sort_by(|a, b| a.cost.total_cmp(&b.cost));
        // The best one's twins (another order of the same folds) are refined too, so that
        // the layer order can decide between them.
        if let Some(first) = judged.first() {
            let seen: Vec<Vec<u8>> =
                judged.iter().map(|j| Stack::of(before, &j.made, lift).groups().to_vec()).collect();
            let mut twins: Vec<(Vec<Move>, sync::Arc<[u8]>)> = Vec::new();
            for s in scored.iter().filter(|s| !seen.iter().any(|g| **g == *s.groups)) {
                if twins.len() == q.twins {
                    break;
                }
                if twins.iter().any(|t| t.1 == s.groups) {
                    continue;
                }
                let moves = s.partial(&beam).moves;
                let Some((t, _)) = make(before, &moves, params) else { continue };
                // Unrefined, a twin lands less alike.
                if aligned_rmse_xy(&t.state, &first.state) < 2.0 * params.layer_order.congruent {
                    twins.push((moves, s.groups.clone()));
                }
            }
            let twins: Vec<Vec<Move>> = twins.into_iter().map(|t| t.0).collect();
            judged.extend(judge_all(twins));
            deadline.check()?;
            judged.sort_by(|a, b| a.cost.total_cmp(&b.cost));
            // Refined from different starts, two may have become one.
            let mut groups: Vec<Vec<u8>> = Vec::new();
            judged.retain(|j| {
                let g = Stack::of(before, &j.made, lift).groups().to_vec();
                let new = !groups.contains(&g);
                groups.push(g);
                new
            });
        }
        if let Some(best) = layer_order(before, &probes.order, &mut judged, params) {
            let last = !deeper(&best);
            found.push((best, judged));
            if last {
                break;
            }
        }
        beam = carried;
    }
    Ok(found)
}

/// Take out of `judged` (best first) the sequence of least mismatch, but that one which
/// explains the end disk about as well ([`SelectionParams::about_as_well_share`]) and lands
/// like it (within [`LayerOrderParams::congruent`]), its layers stacked in another order,
/// whose heights fit the measured disk better, on each one's outline, on `probe`, and which
/// moves the cloth from `before` not markedly further ([`LayerOrderParams::further_share`]).
fn layer_order(
    before: &[Point],
    probe: &Probe,
    judged: &mut Vec<Judged>,
    params: &Params,
) -> Option<Judged> {
    let (order, about_as_well) = (&params.layer_order, params.selection.about_as_well_share);
    let with = |xy: &[Point], z: &[Point]| -> Vec<Point> {
        xy.iter().zip(z).map(|(p, q)| Point::new(p.x, p.y, q.z)).collect()
    };
    // How far each moves the cloth across the table.
    let moved: Vec<f64> = judged
        .iter()
        .map(|j| j.state.iter().zip(before).map(|(p, q)| (p.xy() - q.xy()).norm()).sum::<f64>())
        .collect();
    let mut best = 0;
    for k in 1..judged.len() {
        let (a, b) = (&judged[best].state, &judged[k].state);
        if judged[k].cost > (1.0 + about_as_well) * judged[0].cost
            || aligned_rmse_xy(a, b) > order.congruent
            || moved[k] > (1.0 + order.further_share) * moved[best]
        {
            continue;
        }
        // Positive when the other's heights fit better, on either outline.
        let evidence = (probe.cost_of_state(a) - probe.cost_of_state(&with(a, b)))
            + (probe.cost_of_state(&with(b, a)) - probe.cost_of_state(b));
        if evidence > 0.0 {
            best = k;
        }
    }
    (!judged.is_empty()).then(|| judged.remove(best))
}

/// Settle every fold of `moves` together, by the refinement ([`refine`]) over each fold's
/// two parameters (all eight neighbours of one fold at a time).
fn settle(seen: &Seen, moves: Vec<Move>, params: &Params) -> Vec<Move> {
    let Seen { before, start, end } = *seen;
    let arcs: Vec<[f64; 2]> = make(before, &moves, params)
        .map(|(_, made)| made.into_iter().flat_map(|m| m.arcs).collect())
        .unwrap_or_default();
    let synthesis = &params.synthesis;
    let probe = Probe::around(start, end, &arcs, true, synthesis.stacked_scale, synthesis)
        .capped(params.layer_order.capped_mismatch);
    let angle_step = PI / synthesis.directions as f64;
    let mut costs = Costs::new(
        |moves: &Vec<Move>| cost(&probe, before, moves, params),
        |moves: &Vec<Move>| key(moves),
    );
    let Some(best) = costs.least(vec![moves]) else { unreachable!("one candidate given") };
    let neighbours = |centre: &Vec<Move>, h: f64| -> Vec<Vec<Move>> {
        (0..centre.len())
            .flat_map(|k| {
                [-1.0, 0.0, 1.0].into_iter().flat_map(move |d1| {
                    [-1.0, 0.0, 1.0].into_iter().filter(move |&d2| (d1, d2) != (0.0, 0.0)).map(
                        move |d2| {
                            let mut moved = centre.clone();
                            moved[k] = centre[k].moved([d1 * h, d2 * h], angle_step);
                            moved
                        },
                    )
                })
            })
            .collect()
    };
    refine(&mut costs, best, (0.5, synthesis.step_edges), neighbours).0
}

/// One fold of a step's sequence and the share of the step's end-disk mismatch it explained.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct ExplainedFold {
    /// The fold as made: its `line` lies on the synthesised state it was made on
    /// (normalised coordinates of the step's start frame).
    #[serde(flatten)]
    pub folding: Folding,
    /// Share of the step's mismatch (the start state's against the end disk) this fold took
    /// away, on the probe every candidate of the step is judged by: the folds' shares add up
    /// to the share the sequence explains. `None` when not judged (`--method paper`).
    pub explained: Option<f64>,
}

/// Another sequence that explains a step's end disk about as well as the one reported.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Alternative {
    pub folds: Vec<ExplainedFold>,
    /// Share of the step's mismatch the sequence explains (the reported one's for
    /// comparison is `StepFolds::explained`).
    pub explained: f64,
}

/// What a step's end disk was explained by.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct StepFolds {
    /// The step's folds, in the order made; empty without a confident fold.
    pub folds: Vec<ExplainedFold>,
    /// Other sequences explaining it about as well; for a step whose best candidate was not
    /// confident, that candidate.
    pub alternatives: Vec<Alternative>,
    /// Share of the step's mismatch `folds` explain.
    pub explained: f64,
    /// True when the best fold or sequence found left more than
    /// [`SelectionParams::unexplained_share`] of the
    /// mismatch: the step changed, but no fold found explains it, and none is reported.
    pub unexplained: bool,
}

impl Judged {
    /// The share of `unfolded` each fold took away, in turn, at the judged height.
    fn explained(&self, judge: &Probe, before: &[Point], unfolded: f64) -> Vec<ExplainedFold> {
        let n = before.len();
        let mut previous = unfolded;
        (1..=self.made.len())
            .map(|k| {
                let now = judge.cost(&Stack::of(before, &self.made[..k], self.lift));
                let share = (previous - now) / unfolded;
                previous = now;
                ExplainedFold { folding: self.made[k - 1].folding(n), explained: Some(share) }
            })
            .collect()
    }
}

/// The folds of one step seen as `seen`: its seed (`single`, placed as `placed` says), or,
/// when that leaves its end disk unexplained and the step starts flat, the sequence of up to
/// `max_folds` folds ([`MAX_FOLDS`] at most) that explains it markedly better, by the
/// model selection of the module's documentation.
/// [`Cancelled`](crate::error::Error::Cancelled) once `deadline` expires.
pub(crate) fn explain(
    seen: &Seen,
    single: &Seed,
    placed: Option<&Synthesis>,
    max_folds: usize,
    params: &Params,
    deadline: &Deadline,
) -> Result<StepFolds> {
    let Seen { before, start, end } = *seen;
    let n = before.len();
    let fold = single.fold;
    let direction = placed.and_then(|s| s.direction);
    let single_folding =
        || Folding { fold, arcs: single.arcs.clone(), line: fold.line_on(before, direction) };
    if !is_flat(before) {
        // A stacked start keeps its one fold, judged by its own placement.
        let explained = placed.map_or(1.0, |s| {
            if s.unfolded_mismatch > 0.0 {
                1.0 - s.mismatch / s.unfolded_mismatch
            } else {
                1.0
            }
        });
        return Ok(StepFolds {
            folds: vec![ExplainedFold { folding: single_folding(), explained: Some(explained) }],
            explained,
            ..StepFolds::default()
        });
    }
    let (synthesis, select) = (&params.synthesis, &params.selection);
    let scale = synthesis.stacked_scale;
    let strided = |samples: usize| all_pairs(&sampled_edges(n, samples));
    let every_other: Vec<usize> =
        sampled_edges(n, synthesis.screen_samples).into_iter().step_by(2).collect();
    let glanced_pairs = all_pairs(&every_other);
    let probes = Probes {
        screen: Probe::of(strided(synthesis.screen_samples), start, end, true, scale),
        glance: Probe::of(glanced_pairs, start, end, true, scale),
        judge: Probe::of(strided(synthesis.samples), start, end, true, scale),
        order: Probe::of(strided(params.layer_order.order_samples), start, end, false, scale)
            .capped(params.layer_order.capped_mismatch),
    };
    let lifts = &params.sequence.lifts;
    let unfolded = probes.judge.unfolded();
    let share = |cost: f64| if unfolded > 0.0 { cost / unfolded } else { 0.0 };
    let Some(line) = single_folding().line else { return Ok(StepFolds::default()) };
    let made = Made::from_angles(line, &single.arcs, n);
    let one = judge_made(&probes.judge, before, vec![made], lifts);
    let mut left = share(one.cost);
    // The answer so far, its alternatives, and whether it is the step's own detected fold.
    let mut chosen = (one, Vec::new(), true);
    if max_folds >= 2 && left > select.explained_by_one_share {
        // A sequence leaving less than `min_gain_share` unexplained cannot be beaten markedly:
        // no longer one is searched.
        let deeper = |best: &Judged| share(best.cost) >= select.min_gain_share;
        let max_folds = max_folds.min(MAX_FOLDS);
        for (best, others) in search(seen, &probes, params, max_folds, deeper, deadline)? {
            let now = share(best.cost);
            if now > select.markedly_share * left || left - now < select.min_gain_share {
                // Not markedly better than the answer so far; a longer one still may be
                // (a sequence's first folds can explain little before its last is made).
                continue;
            }
            if best.made.len() == 1 {
                // The search's own fold, markedly better than the step's: one the one-fold
                // search did not make (a fold of several arcs on a flat start).
                left = now;
                chosen = (best, others, false);
                continue;
            }
            // Its own folds less any one are a (k − 1)-fold answer too: each fold must add
            // markedly to the others, or they are the answer (a multi-arc fold the step's
            // one-fold search did not make, with a sliver before or after it).
            let folds = best.made.len();
            let dropped = (0..folds).map(|skip| {
                (0..folds).filter(|&k| k != skip).map(|k| best.made[k].clone()).collect()
            });
            let joined = (0..folds - 1).filter_map(|j| merged(before, &best.made, j, params));
            let fewer = dropped
                .chain(joined)
                .map(|made| judge_made(&probes.judge, before, made, lifts))
                .min_by(|a, b| a.cost.total_cmp(&b.cost))
                .expect("a sequence holds two folds or more");
            let without_one = share(fewer.cost);
            if now <= select.markedly_share * without_one
                && without_one - now >= select.min_gain_share
            {
                left = now;
                chosen = (best, others, false);
            } else {
                // As many folds as the answer so far: the better one is kept, and longer
                // sequences are still tried against it.
                if without_one < left {
                    left = without_one;
                    chosen = (fewer, Vec::new(), false);
                }
            }
        }
    }
    let (best, others, detected) = chosen;
    let alternative = |j: &Judged| Alternative {
        folds: j.explained(&probes.judge, before, unfolded),
        explained: 1.0 - share(j.cost),
    };
    if left > select.unexplained_share {
        return Ok(StepFolds {
            alternatives: vec![alternative(&best)],
            unexplained: true,
            ..StepFolds::default()
        });
    }
    let folds = if detected {
        // The step's own fold as detected (not round-tripped through border parameters).
        vec![ExplainedFold { folding: single_folding(), explained: Some(1.0 - left) }]
    } else {
        best.explained(&probes.judge, before, unfolded)
    };
    Ok(StepFolds {
        folds,
        alternatives: others
            .iter()
            .filter(|o| o.cost <= (1.0 + select.about_as_well_share) * best.cost)
            .map(alternative)
            .collect(),
        explained: 1.0 - left,
        unexplained: false,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fold::{read, FoldMethod};

    /// A square of side 1 centred on the origin, `per_side` vertices a side.
    fn square(per_side: usize) -> Vec<Point> {
        let s = per_side as f64;
        (0..4 * per_side)
            .map(|k| {
                let t = (k % per_side) as f64 / s;
                let (x, y) = [(t, 0.0), (1.0, t), (1.0 - t, 1.0), (0.0, 1.0 - t)][k / per_side];
                Point::new(x - 0.5, y - 0.5, 0.0)
            })
            .collect()
    }

    /// Every vertex left of the line through `a` at `angle`, whatever its layer, reflected
    /// across it and laid on top (independent of [`Stack`]).
    fn fold_all(state: &[Point], a: [f64; 2], angle: f64) -> Vec<Point> {
        let u = [angle.cos(), angle.sin()];
        let top = state.iter().map(|p| p.z).fold(f64::NEG_INFINITY, f64::max);
        state
            .iter()
            .map(|p| {
                let (dx, dy) = (p.x - a[0], p.y - a[1]);
                if u[0] * dy - u[1] * dx <= 0.0 {
                    return *p;
                }
                let t = dx * u[0] + dy * u[1];
                Point::new(
                    a[0] + 2.0 * t * u[0] - dx,
                    a[1] + 2.0 * t * u[1] - dy,
                    2.0 * top + 0.004 - p.z,
                )
            })
            .collect()
    }

    fn explained(before: &[Point], after: &[Point], max_folds: usize) -> StepFolds {
        let (start, end) = (Disk::of_border(before), Disk::of_border(after));
        let reading = read(
            before,
            &start,
            &end,
            FoldMethod::Cut,
            max_folds,
            &Params::default(),
            &Deadline::default(),
        );
        reading.expect("no deadline").folds
    }

    #[test]
    fn a_line_along_a_side_turns_nothing_over() {
        // Rays from vertex 0, the bottom left corner, along the bottom side: the whole
        // square lies left of it or on it (a flip, no fold); a degree up, a sliver of the
        // bottom side lies right of it and the rest folds over it.
        let state = square(8);
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
    fn one_fold_stays_one_and_two_are_found_as_two() {
        let flat = square(24);
        let half = fold_all(&flat, [0.013, 0.0], PI / 2.0);
        let once = explained(&flat, &half, 3);
        assert_eq!(once.folds.len(), 1, "explained {}", once.explained);
        assert!(!once.unexplained);
        let quarters = fold_all(&half, [0.0, 0.013], 0.0);
        let twice = explained(&flat, &quarters, 3);
        assert_eq!(twice.folds.len(), 2, "explained {}", twice.explained);
        let explained_by_one = Params::default().selection.explained_by_one_share;
        assert!(twice.explained > 1.0 - explained_by_one, "{}", twice.explained);
        // The folds' shares add up to the sequence's.
        let sum: f64 = twice.folds.iter().filter_map(|f| f.explained).sum();
        assert!((sum - twice.explained).abs() < 1e-9, "{sum} vs {}", twice.explained);
        // One fold asked for: one fold given, whatever it leaves.
        assert!(explained(&flat, &quarters, 1).folds.len() <= 1);
    }

    /// The search works in the cloth's frame: turning the cloth on the table by an angle no
    /// searched direction is a multiple of turns nothing it finds (the second fold of
    /// quarters runs through stacked layers, where directions are searched).
    #[test]
    fn a_turned_cloth_is_read_alike() {
        let turn = |state: &[Point], angle: f64| -> Vec<Point> {
            let (c, s) = (angle.cos(), angle.sin());
            state.iter().map(|p| Point::new(c * p.x - s * p.y, s * p.x + c * p.y, p.z)).collect()
        };
        let flat = square(24);
        let quarters = fold_all(&fold_all(&flat, [0.013, 0.0], PI / 2.0), [0.0, 0.013], 0.0);
        let plain = explained(&flat, &quarters, 2);
        for angle in [0.3, 2.0] {
            let turned = explained(&turn(&flat, angle), &turn(&quarters, angle), 2);
            assert_eq!(turned.folds.len(), plain.folds.len(), "turned by {angle}");
            assert!(
                (turned.explained - plain.explained).abs() < 1e-3,
                "turned by {angle}: explained {} against {}",
                turned.explained,
                plain.explained
            );
        }
    }

    #[test]
    fn straight_sides_give_the_directions_square_to_them() {
        // A square, turned: two directions, square to its sides, whatever vertex it starts at.
        for (angle, from) in [(0.0, 0), (0.3, 5)] {
            let (c, s) = (f64::cos(angle), f64::sin(angle));
            let mut turned: Vec<Point> = square(12)
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

    #[test]
    fn a_cancelled_deadline_stops_the_search() {
        let flat = square(24);
        let quarters = fold_all(&fold_all(&flat, [0.013, 0.0], PI / 2.0), [0.0, 0.013], 0.0);
        let (start, end) = (Disk::of_border(&flat), Disk::of_border(&quarters));
        let deadline = Deadline::default();
        deadline.cancel();
        let stopped = read(&flat, &start, &end, FoldMethod::Cut, 3, &Params::default(), &deadline);
        assert!(matches!(stopped, Err(crate::error::Error::Cancelled)), "{stopped:?}");
    }
}
