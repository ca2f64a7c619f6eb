//! Fold sequences in one step: the folds that took a state to one whose disk alone is seen.
//!
//! Our extension of CloSE, after the paper's "Multi-folds" section (Kamat, Borràs, Torras,
//! "CloSE", Sec. V): the diff disk of two folds seen at once holds the lines of both. A cloth
//! folded k times, seen flat and folded with no frame between, is read as a sequence of
//! folds, each made on the state the ones before it left (later folds cross stacked layers,
//! and may turn several arcs of the border at once).
//!
//! **Where the creases meet the border.** Folds of a flat cloth move each piece between the
//! creases rigidly, so a pair of edges of one piece keeps |dGLI|: a border arc inside one
//! piece holds no change of the abs diff disk. The border split into m arcs of least change
//! within themselves ([`super::cut::find_cuts`]) puts its m cut points where the creases meet
//! the border (m = 2 is the one fold's cut).
//!
//! **Analysis by synthesis.** Each fold of a candidate sequence is a line on the state it is
//! made on, through two cut points (where they lie on that state), or through one and a
//! direction when the two coincide there (stacked layers), and the arcs of the border left of
//! it that turn over: all of them, or the one holding a given vertex (a fold may turn the top
//! layer only). The folds are made in turn ([`super::synth`]: the flap rotated by π about the
//! line, laid above the stack), and the synthesised state's dGLI on probe pairs is compared
//! with the measured end disk. A beam search builds the sequences a fold at a time, on a
//! screen of strided pairs; the best are refined, all their folds together, by a pattern
//! search over each fold's two parameters. The end border's coordinates are never read.

use std::f64::consts::PI;

use rayon::prelude::*;

use crate::angle::ArcVertices;
use crate::border::{point_at, Point};
use crate::disk::Disk;

use super::cut::find_cuts;
use super::synth::{
    arcs_left_of, mean_edge, sampled_edges, Probe, Turned, COINCIDE_EDGES, DIRECTIONS, LIFT,
    SAMPLES, SCREEN_SAMPLES,
};
use crate::geometry::{Line, Point2};

/// Most folds of one sequence.
pub const MAX_FOLDS: usize = 4;
/// Sequences kept at each length of the beam search.
fn beam_width() -> usize { std::env::var("SEQ_BEAM").ok().and_then(|v| v.parse().ok()).unwrap_or(8) }
/// Sequences of each length refined in full.
const REFINED: usize = 6;
/// First folds carried on to the second: all there are, up to this many.
const FIRST_BEAM: usize = 96;

/// Which of the arcs left of a fold's line turn over.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Turn {
    /// All of them (one arc for a line crossing the border twice; several for a
    /// multi-arc fold).
    All,
    /// The one holding this vertex: a fold of one layer of a stack.
    Holding(usize),
}

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
        Some(if self.reversed {
            Line { point: line.point, direction: -line.direction }
        } else {
            line
        })
    }

    /// The arcs this fold turns over on `state` (border parameters): `None` when it turns
    /// fewer than two vertices, or leaves fewer than two.
    fn arcs(&self, state: &[Point], line: &Line) -> Option<Vec<[f64; 2]>> {
        let n = state.len();
        let left = arcs_left_of(state, line);
        let arcs = match self.turn {
            Turn::All => left,
            Turn::Holding(v) => {
                left.into_iter().filter(|a| ArcVertices::of(n, a[0], a[1]).contains(v)).collect()
            }
        };
        let moved: usize = arcs.iter().map(|a| ArcVertices::of(n, a[0], a[1]).len).sum();
        (moved >= 2 && moved + 2 <= n).then_some(arcs)
    }

    /// The same fold moved by `delta` edges along the border (and, for a ray, radians in its
    /// direction, `angle_step` per edge step).
    fn moved(&self, delta: [f64; 2], angle_step: f64) -> Move {
        let anchor = match self.anchor {
            Anchor::Points([a, b]) => Anchor::Points([a + delta[0], b + delta[1]]),
            Anchor::Ray(a, phi) => Anchor::Ray(a + delta[0], phi + delta[1] * angle_step),
        };
        Move { anchor, ..*self }
    }
}

/// A fold of a sequence as made: its line on the state before it and the arcs it turned.
#[derive(Debug, Clone, PartialEq)]
pub struct SequenceFold {
    /// The line, on the synthesised state the fold was made on (normalised coordinates of the
    /// step's start), directed so that the arcs turned lie on its left.
    pub line: Line,
    /// The arcs turned over (border parameters, each anticlockwise from its first point), in
    /// walking order.
    pub arcs: Vec<[f64; 2]>,
}

impl SequenceFold {
    /// The pair of border parameters that spans the arcs: the first point of the first arc
    /// and the last point of the last.
    pub fn span(&self) -> [f64; 2] {
        match (self.arcs.first(), self.arcs.last()) {
            (Some(first), Some(last)) => [first[0], last[1]],
            _ => [0.0; 2],
        }
    }
}

/// A sequence of folds found by synthesis.
#[derive(Debug, Clone, PartialEq)]
pub struct Sequence {
    pub folds: Vec<SequenceFold>,
    /// Mean probe mismatch of the synthesised end state with the measured end disk, on the
    /// probe every sequence of the step is judged by.
    pub mismatch: f64,
    /// The same after each fold of the sequence in turn (the last is `mismatch`).
    pub mismatches: Vec<f64>,
    /// The same for the start state left as it was.
    pub unfolded_mismatch: f64,
}

/// The state after `moves` made in turn on `before`, with each fold as made; `None` when
/// one of them cannot be made.
fn synthesise(before: &[Point], moves: &[Move]) -> Option<(Turned, Vec<SequenceFold>)> {
    synthesise_at(before, moves, LIFT)
}

/// [`synthesise`] with each flap laid `lift` above the stack.
fn synthesise_at(before: &[Point], moves: &[Move], lift: f64) -> Option<(Turned, Vec<SequenceFold>)> {
    let mut turned = Turned::unfolded(before);
    let mut folds = Vec::with_capacity(moves.len());
    for m in moves {
        let line = m.line(&turned.state)?;
        let arcs = m.arcs(&turned.state, &line)?;
        turned.fold(&arcs, &line, lift);
        folds.push(SequenceFold { line, arcs });
    }
    Some((turned, folds))
}

fn cost(probe: &Probe, before: &[Point], moves: &[Move]) -> f64 {
    synthesise(before, moves).map_or(f64::INFINITY, |(turned, _)| probe.cost(&turned))
}

/// The folds that can be made on `state` along lines through the cut `points`.
fn moves_on(state: &[Point], points: &[f64]) -> Vec<Move> {
    let n = state.len();
    let near = COINCIDE_EDGES * mean_edge(state);
    let mut anchors: Vec<Anchor> = Vec::new();
    let mut rays: Vec<Point> = Vec::new();
    for (k, &a) in points.iter().enumerate() {
        for &b in &points[k + 1..] {
            let (pa, pb) = (point_at(state, a), point_at(state, b));
            if (pa.xy() - pb.xy()).norm() >= near {
                anchors.push(Anchor::Points([a, b]));
            } else if rays.iter().all(|r| (r.xy() - pa.xy()).norm() >= near) {
                // Layers stacked there: the line's direction is searched.
                rays.push(pa);
                anchors.extend(
                    (0..DIRECTIONS).map(|d| Anchor::Ray(a, PI * d as f64 / DIRECTIONS as f64)),
                );
            }
        }
    }
    let mut moves = Vec::new();
    for anchor in anchors {
        for reversed in [false, true] {
            let m = Move { anchor, reversed, turn: Turn::All };
            let Some(line) = m.line(state) else { continue };
            let left = arcs_left_of(state, &line);
            moves.push(m);
            if left.len() > 1 {
                for arc in &left {
                    let inside = ArcVertices::of(n, arc[0], arc[1]);
                    let middle = inside.vertices().nth(inside.len / 2);
                    if let Some(v) = middle {
                        moves.push(Move { turn: Turn::Holding(v), ..m });
                    }
                }
            }
        }
    }
    moves
}

/// Sequences of up to `max_folds` folds that take `before` (the step's start border,
/// normalised, with disk `start`) to a state with the measured `end` disk: the best of each
/// length, shortest first, each judged on the same probe. Empty when the disks do not differ.
pub fn search(before: &[Point], start: &Disk, end: &Disk, max_folds: usize) -> Vec<Sequence> {
    let n = before.len();
    let flat = super::is_flat(before);
    let lambda: f64 = std::env::var("SEQ_LAMBDA").ok().and_then(|v| v.parse().ok()).unwrap_or(0.05);
    let g = {
        let g = start.abs_diff(end);
        let values = g.values().iter().zip(start.values()).map(|(c, s)| c - lambda * s.abs()).collect();
        Disk::from_values(n, values).expect("the diff disk's own size")
    };
    let max_folds = max_folds.min(MAX_FOLDS);
    // Cut points of as many arcs as the sequences could make: 2 per fold line on a flat
    // cloth, doubled by each layer it crosses.
    let cut_sets: Vec<Vec<f64>> = [2usize, 4, 6, 8]
        .into_iter()
        .filter(|&m| m <= 2 * max_folds + 2 && m < n)
        .filter_map(|m| find_cuts(&g, m).map(|c| c.points))
        .collect();
    if cut_sets.is_empty() {
        return Vec::new();
    }
    if std::env::var("SEQ_DEBUG").is_ok() {
        eprintln!("  cut sets {cut_sets:?}");
    }
    let all_pairs = |samples: usize| {
        let edges = sampled_edges(n, samples);
        let pairs: Vec<(usize, usize)> = edges
            .iter()
            .enumerate()
            .flat_map(|(k, &i)| edges[k + 1..].iter().map(move |&j| (i, j)))
            .collect();
        pairs
    };
    let cap: f64 = std::env::var("SEQ_CAP").ok().and_then(|v| v.parse().ok()).unwrap_or(f64::INFINITY);
    let screen = Probe::of(all_pairs(SCREEN_SAMPLES), start, end, flat, scale_flat(flat)).capped(cap);
    let judge = Probe::of(all_pairs(SAMPLES), start, end, flat, scale_flat(flat));
    let mut beam: Vec<Vec<Move>> = vec![Vec::new()];
    let mut best: Vec<Sequence> = Vec::new();
    let debug = std::env::var("SEQ_DEBUG").is_ok();
    for level in 0..max_folds {
        // Every fold through the cut points on each state of the beam, screened.
        let mut scored: Vec<(f64, usize, Vec<Move>, Vec<u8>)> = beam
            .par_iter()
            .enumerate()
            .flat_map_iter(|(p, moves)| {
                let state = synthesise(before, moves).map(|(t, _)| t.state).unwrap_or_default();
                let mut next = Vec::new();
                for points in &cut_sets {
                    for m in moves_on(&state, points) {
                        let mut longer = moves.clone();
                        longer.push(m);
                        next.push((p, longer));
                    }
                }
                next
            })
            .filter_map(|(p, moves)| {
                let (turned, _) = synthesise(before, &moves)?;
                Some((screen.cost(&turned), p, moves, turned.groups().to_vec()))
            })
            .collect();
        scored.sort_by(|a, b| a.0.total_cmp(&b.0));
        if debug {
            for (rank, (c, p, m, _)) in scored.iter().enumerate().take(40) {
                let folds = synthesise(before, m).map(|(_, f)| f).unwrap_or_default();
                eprintln!("    screen #{rank} {c:.4} prefix {p}: {:?}", folds.iter().map(|f| f.arcs.iter().map(|a| [(a[0]*10.0).round()/10.0, (a[1]*10.0).round()/10.0]).collect::<Vec<_>>()).collect::<Vec<_>>());
            }
        }
        // Distinct by what the folds moved: the beam carries every first fold on (a
        // sequence's first folds explain little alone), then the best few.
        let width = if level == 0 { FIRST_BEAM } else { beam_width() };
        let mut kept: Vec<(f64, usize, Vec<Move>, Vec<u8>)> = Vec::new();
        for s in &scored {
            if kept.len() == width {
                break;
            }
            if kept.iter().all(|k| k.3 != s.3) {
                kept.push(s.clone());
            }
        }
        if kept.is_empty() {
            break;
        }
        // Refined: the best of each state the beam came from, the best few overall.
        let mut chosen: Vec<Vec<Move>> = Vec::new();
        let mut prefixes: Vec<usize> = Vec::new();
        for k in &kept {
            if chosen.len() < REFINED && !prefixes.contains(&k.1) {
                prefixes.push(k.1);
                chosen.push(k.2.clone());
            }
        }
        for k in &kept {
            if chosen.len() < REFINED && !chosen.contains(&k.2) {
                chosen.push(k.2.clone());
            }
        }
        let judge_all = |chosen: Vec<Vec<Move>>| -> Vec<Judged> {
            chosen
                .into_par_iter()
                .filter_map(|moves| {
                    let moves = refine(before, start, end, flat, moves).1;
                    judged_at_best_lift(&judge, before, moves)
                })
                .collect()
        };
        let mut judged = judge_all(chosen);
        judged.sort_by(|a, b| a.cost.total_cmp(&b.cost));
        // The best one's twins: sequences that land alike on the table (another order of
        // the same folds), refined too, so that the layer order can decide between them.
        if let Some(first) = judged.first() {
            let groups: Vec<Vec<u8>> = judged
                .iter()
                .filter_map(|j| synthesise(before, &j.moves).map(|(t, _)| t.groups().to_vec()))
                .collect();
            let twins: Vec<Vec<Move>> = scored
                .iter()
                .take(TWIN_SCAN)
                .filter(|s| !groups.contains(&s.3))
                .filter_map(|s| {
                    let (t, _) = synthesise(before, &s.2)?;
                    (crate::metrics::aligned_rmse_xy(&t.state, &first.state) < CONGRUENT)
                        .then(|| s.2.clone())
                })
                .take(TWINS)
                .collect();
            if debug {
                eprintln!("    twins: {}", twins.len());
            }
            judged.extend(judge_all(twins));
            judged.sort_by(|a, b| a.cost.total_cmp(&b.cost));
        }
        if debug {
            for j in &judged {
                let folds = synthesise(before, &j.moves).map(|(_, f)| f).unwrap_or_default();
                eprintln!("    cand judge {:.4} ratio {:.3} lift {}: {:?}", j.cost, j.cost / judge.unfolded(), j.lift, folds.iter().map(|f| f.arcs.iter().map(|a| [a[0].round(), a[1].round()]).collect::<Vec<_>>()).collect::<Vec<_>>());
            }
        }
        let order_probe = Probe::of(all_pairs(ORDER_SAMPLES), start, end, false, scale_flat(flat));
        let Some(winner) = layer_order(&order_probe, judged, debug) else { break };
        let Some((_, folds)) = synthesise_at(before, &winner.moves, winner.lift) else { break };
        let mismatches = (1..=winner.moves.len())
            .map(|k| {
                synthesise_at(before, &winner.moves[..k], winner.lift)
                    .map_or(f64::INFINITY, |(t, _)| judge.cost(&t))
            })
            .collect::<Vec<_>>();
        best.push(Sequence {
            folds,
            mismatch: winner.cost,
            mismatches,
            unfolded_mismatch: judge.unfolded(),
        });
        beam = kept.into_iter().map(|(_, _, moves, _)| moves).collect();
    }
    best
}

/// Two sequences whose end states lie alike on the table, but for a rigid motion, this
/// close (aligned RMSE, normalised units), differ in how their layers are stacked.
const CONGRUENT: f64 = 0.05;

/// A refined sequence judged at the flap height that fits it best.
struct Judged {
    cost: f64,
    moves: Vec<Move>,
    lift: f64,
    state: Vec<Point>,
}

/// `moves` judged on `judge` at each of [`LIFTS`], the best kept: the layers' spacing is
/// the cloth's own thickness, which the disk shows.
fn judged_at_best_lift(judge: &Probe, before: &[Point], moves: Vec<Move>) -> Option<Judged> {
    LIFTS
        .iter()
        .filter_map(|&lift| {
            let (turned, _) = synthesise_at(before, &moves, lift)?;
            Some((judge.cost(&turned), lift, turned.state))
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(cost, lift, state)| Judged { cost, moves, lift, state })
}

/// Scored sequences searched for twins of the best one.
const TWIN_SCAN: usize = 400;
/// Twins refined.
const TWINS: usize = 3;

/// The sequence of least mismatch among `judged` (best first), but that one whose end lands
/// like it (within [`CONGRUENT`]), its layers stacked in another order, is compared with it
/// on the order alone: each one's outline with each one's heights, on `probe`.
fn layer_order(probe: &Probe, judged: Vec<Judged>, debug: bool) -> Option<Judged> {
    let with = |xy: &[Point], z: &[Point]| -> Vec<Point> {
        xy.iter().zip(z).map(|(p, q)| Point::new(p.x, p.y, q.z)).collect()
    };
    let mut it = judged.into_iter();
    let mut best = it.next()?;
    for other in it {
        if crate::metrics::aligned_rmse_xy(&best.state, &other.state) > CONGRUENT {
            continue;
        }
        let (a, b) = (&best.state, &other.state);
        // Positive when `other`'s heights fit better, on either outline.
        let evidence = (probe.cost_of_state(a) - probe.cost_of_state(&with(a, b)))
            + (probe.cost_of_state(&with(b, a)) - probe.cost_of_state(b));
        if debug {
            eprintln!("    order evidence for the other ({:.4} vs {:.4}): {evidence:.4}", other.cost, best.cost);
        }
        if evidence > 0.0 && std::env::var("SEQ_NO_ORDER").is_err() {
            best = other;
        }
    }
    Some(best)
}

/// Flap heights above the stack tried when sequences are judged (normalised units: a
/// cloth's thickness, doubled at a crease, is 0.5–4 % of its size).
const LIFTS: [f64; 7] = [0.0025, 0.005, 0.0075, 0.01, 0.02, 0.04, 0.08];

/// Edges sampled for the layer-order test, all pairs of them.
const ORDER_SAMPLES: usize = 96;

/// Whether the probe values of a step from a flat start are compared at the flat scale.
fn scale_flat(flat: bool) -> bool {
    flat && std::env::var("SEQ_STACKED_SCALE").is_err()
}

/// Refine every fold of `moves` together: a pattern search over each fold's two parameters
/// (all eight neighbours of one fold at a time), the step halving when none is better.
fn refine(
    before: &[Point],
    start: &Disk,
    end: &Disk,
    flat: bool,
    moves: Vec<Move>,
) -> (f64, Vec<Move>) {
    let arcs: Vec<[f64; 2]> = synthesise(before, &moves)
        .map(|(_, folds)| folds.into_iter().flat_map(|f| f.arcs).collect())
        .unwrap_or_default();
    let probe = Probe::around(start, end, &arcs, scale_flat(flat));
    let angle_step = PI / DIRECTIONS as f64;
    let mut best = (cost(&probe, before, &moves), moves);
    let mut h = 0.5;
    while h >= 0.125 {
        let centre = best.1.clone();
        let neighbours: Vec<Vec<Move>> = (0..centre.len())
            .flat_map(|k| {
                let centre = &centre;
                [-1.0, 0.0, 1.0].into_iter().flat_map(move |d1| {
                    [-1.0, 0.0, 1.0].into_iter().filter_map(move |d2| {
                        if d1 == 0.0 && d2 == 0.0 {
                            return None;
                        }
                        let mut moved = centre.clone();
                        moved[k] = centre[k].moved([d1 * h, d2 * h], angle_step);
                        Some(moved)
                    })
                })
            })
            .collect();
        let better = neighbours
            .into_par_iter()
            .map(|m| (cost(&probe, before, &m), m))
            .min_by(|a, b| a.0.total_cmp(&b.0));
        match better {
            Some(b) if b.0 < best.0 => best = b,
            _ => h /= 2.0,
        }
    }
    best
}

/// Lab only.
pub fn debug_score(before: &[Point], start: &Disk, end: &Disk, lines: &[Line]) -> Vec<f64> {
    let n = before.len();
    let flat = super::is_flat(before);
    let edges = sampled_edges(n, SAMPLES);
    let pairs: Vec<(usize, usize)> = edges
        .iter()
        .enumerate()
        .flat_map(|(k, &i)| edges[k + 1..].iter().map(move |&j| (i, j)))
        .collect();
    let judge = Probe::of(pairs, start, end, flat, scale_flat(flat));
    let mut turned = Turned::unfolded(before);
    let mut out = vec![judge.unfolded()];
    for line in lines {
        let arcs = arcs_left_of(&turned.state, line);
        eprintln!("arcs {arcs:?}");
        turned.fold(&arcs, line, LIFT);
        out.push(judge.cost(&turned));
    }
    let full = Disk::of_border(&turned.state);
    let diff: f64 = full.values().iter().zip(end.values()).map(|(a, b)| (a - b).abs()).sum::<f64>() / full.values().len() as f64;
    eprintln!("full-disk mean abs diff of the synthesised end {diff}; z {:?}", turned.state.iter().map(|p| p.z).collect::<Vec<_>>());
    out
}
