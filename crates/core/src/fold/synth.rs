//! Fold points to a fraction of an edge, by analysis by synthesis on the disks.
//!
//! The cut ([`super::cut`]) says which edges were turned over, to half an edge. Where, inside
//! the crease edges, the cloth really folded, and along which line the flap was turned,
//! decides where every flap vertex lands, so we measure it the way the paper's
//! representation sees it (Kamat, Borràs, Torras, "CloSE", Sec. III: the dGLI disk of a
//! state): for a candidate fold we synthesise the end state from the START border of the
//! step (the flap turned over the line, i.e. rotated by π about it, and laid
//! [`SynthesisParams::lift`] above the highest vertex), compute the dGLI of a fixed set of probe pairs on it,
//! and compare them with the measured END disk. The candidate whose disk matches best wins.
//! The end border's coordinates are never read, only its disk.
//!
//! Probe pairs: every edge near a fold point against a strided sample of all edges, and a
//! strided sample of flap edges against the rest. Values are compared after
//! `asinh(v / s)` ([`SynthesisParams::flat_scale`], [`SynthesisParams::stacked_scale`]), so that pairs of stacked layers, whose dGLI grows like 1/height,
//! do not drown the others while the synthesised height differs from the real one.
//!
//! Two parametrisations: normally the line runs through the border points at s1 and s2,
//! both searched within [`SynthesisParams::reach_edges`] of the cut. When those two points (nearly) coincide
//! in the step's start frame (a second fold through two stacked layers), they do not give a
//! direction, so the line is the midpoint of the two points and a searched direction.

use std::f64::consts::PI;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::angle::ArcVertices;
use crate::border::{point_at, Point};
use crate::disk::Disk;
use crate::geometry::{Line, Point2, Vector2};
use crate::gli::dgli_each;

use super::params::SynthesisParams;
use super::refine::{refine, Costs};
use super::state::{arcs_left_of, flap_axis, mean_edge, Stack, Turn};

thread_local! {
    /// [`Probe::cost`]'s buffers (each pair's value, the pairs that need a dGLI), kept per
    /// thread: it runs thousands of times per step, and allocating them was a tenth of it.
    static COST_BUFFERS: std::cell::RefCell<(Vec<Option<f64>>, Vec<usize>)> = const { std::cell::RefCell::new((Vec::new(), Vec::new())) };
}

/// Per vertex of a border of `n`: whether it lies strictly inside one of `arcs`.
fn moved_mask(n: usize, arcs: &[[f64; 2]]) -> Vec<bool> {
    let mut moved = vec![false; n];
    for arc in arcs {
        for v in ArcVertices::of(n, arc[0], arc[1]).vertices() {
            moved[v] = true;
        }
    }
    moved
}

/// The probe pairs, their measured end values and their values in the step's start state.
pub(crate) struct Probe {
    pairs: Vec<(usize, usize)>,
    measured: Vec<f64>,
    start: Vec<f64>,
    /// A pair of edges both on the flap takes the negated start value instead of a dGLI.
    /// Turning the flap over is a rotation by π about a horizontal line, which reverses the
    /// vertical lift of the dGLI: on a flat start the result is the mirror image of the start
    /// and the negation is exact; on a stacked one it holds to first order in ε, which is
    /// close enough to screen lines ([`search_line`]) but not to refine them.
    flap_negates: bool,
    /// The compression's scale ([`SynthesisParams::flat_scale`],
    /// [`SynthesisParams::stacked_scale`]).
    scale: f64,
    /// Most a pair's mismatch counts for ([`Probe::capped`]; infinite unless capped).
    cap: f64,
}

impl Probe {
    /// Probe `pairs`, compressed, on the start disk and the measured end disk.
    /// `flat`: whether the step starts flat, which sets the compression's scale.
    pub(crate) fn of(
        pairs: Vec<(usize, usize)>,
        start: &Disk,
        end: &Disk,
        flap_negates: bool,
        scale: f64,
    ) -> Probe {
        let measured = pairs.iter().map(|&(i, j)| compress(end.get(i, j), scale)).collect();
        let start = pairs.iter().map(|&(i, j)| compress(start.get(i, j), scale)).collect();
        Probe { pairs, measured, start, flap_negates, scale, cap: f64::INFINITY }
    }

    /// The same probe, each pair's mismatch counting at most `cap` (a truncated loss, robust
    /// to the few pairs whose dGLI turns noise into large values).
    pub(crate) fn capped(self, cap: f64) -> Probe {
        Probe { cap, ..self }
    }

    /// Probe pairs around the ends of the folded `arcs`: every edge near them against a
    /// strided sample of all edges, and sampled edges of the folded arcs against the rest.
    /// On a flat start the flap's pairs take their negated start values ([`Probe::flap_negates`]).
    /// [`SynthesisParams::samples`] edges are sampled, [`SynthesisParams::near_edges`] taken
    /// either side of each end.
    pub(crate) fn around(
        start: &Disk,
        end: &Disk,
        arcs: &[[f64; 2]],
        flap_negates: bool,
        scale: f64,
        params: &SynthesisParams,
    ) -> Probe {
        let n = end.n();
        let sampled = sampled_edges(n, params.samples);
        let reach = params.near_edges as isize;
        let mut near: Vec<usize> = Vec::new();
        for p in arcs.iter().flatten() {
            let k = p.floor() as isize;
            for d in -reach..=reach {
                near.push((k + d).rem_euclid(n as isize) as usize);
            }
        }
        near.sort_unstable();
        near.dedup();
        let mut pairs: Vec<(usize, usize)> = Vec::new();
        for &i in &near {
            pairs.extend(
                sampled.iter().chain(&near).filter(|&&j| j != i).map(|&j| (i.min(j), i.max(j))),
            );
        }
        // Flap against the rest: sampled edges on either side of the cut.
        let turned = moved_mask(n, arcs);
        let (inside, outside): (Vec<usize>, Vec<usize>) =
            sampled.iter().partition(|&&e| turned[e] && turned[(e + 1) % n]);
        for &i in &inside {
            pairs.extend(outside.iter().map(|&j| (i.min(j), i.max(j))));
        }
        pairs.sort_unstable();
        pairs.dedup();
        Probe::of(pairs, start, end, flap_negates, scale)
    }

    /// Mean mismatch of the synthesised state `turned` with the measured end disk (each
    /// pair's at most the probe's cap).
    ///
    /// Only pairs with an edge the fold moved and one it did not need a dGLI: a pair of
    /// unmoved edges keeps its start value, and a pair on the flap may take the negated one
    /// (see [`Probe::flap_negates`]).
    pub(crate) fn cost(&self, turned: &Stack) -> f64 {
        let (state, next) = (&turned.state, |e: usize| turned.next(e));
        COST_BUFFERS.with_borrow_mut(|(values, across)| {
            values.clear();
            values.extend(self.pairs.iter().zip(&self.start).map(|(&(i, j), start)| {
                // Edges moved by the same folds moved together, rigidly: each turn over
                // negates their pair (exactly on a flat start, see `flap_negates`).
                match (turned.edge_group(i), turned.edge_group(j)) {
                    (Some(0), Some(0)) => Some(*start),
                    (Some(a), Some(b)) if a == b && self.flap_negates => {
                        Some(if a.count_ones() % 2 == 1 { -start } else { *start })
                    }
                    _ => None,
                }
            }));
            across.clear();
            across.extend((0..values.len()).filter(|&k| values[k].is_none()));
            let mut slots = across.iter();
            dgli_each(
                across.iter().map(|&k| {
                    let (i, j) = self.pairs[k];
                    [&state[i], &state[next(i)], &state[j], &state[next(j)]]
                }),
                |v| {
                    if let Some(&k) = slots.next() {
                        values[k] = Some(compress(v, self.scale));
                    }
                },
            );
            let total: f64 = values
                .iter()
                .zip(&self.measured)
                .map(|(value, m)| (value.unwrap_or(0.0) - m).abs().min(self.cap))
                .sum();
            total / self.pairs.len().max(1) as f64
        })
    }

    /// Mean mismatch of any `state` of the border with the measured end disk, every pair's
    /// dGLI computed (the probe is made without `flap_negates`).
    pub(crate) fn cost_of_state(&self, state: &[Point]) -> f64 {
        debug_assert!(!self.flap_negates);
        self.cost(&Stack::flat(state).all_moved())
    }

    /// Mean mismatch of the start state left as it was.
    pub(crate) fn unfolded(&self) -> f64 {
        self.start.iter().zip(&self.measured).map(|(s, m)| (s - m).abs().min(self.cap)).sum::<f64>()
            / self.pairs.len().max(1) as f64
    }
}

/// asinh(v / scale), written out: the standard library's careful form (hypot, ln_1p) is a
/// fifth of the cost of a probe, and the few ulps it saves do not matter to a mismatch.
pub(crate) fn compress(v: f64, scale: f64) -> f64 {
    let a = (v / scale).abs();
    let magnitude = if a < 1e150 { (a + (a * a + 1.0).sqrt()).ln() } else { (2.0 * a).ln() };
    magnitude.copysign(v)
}

/// A strided sample of at most `samples` edges of `n`.
pub(crate) fn sampled_edges(n: usize, samples: usize) -> Vec<usize> {
    (0..n).step_by(n.div_ceil(samples).max(1)).collect()
}

/// A fold found by synthesis: the border parameters of its points and the line used.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Synthesis {
    /// Border parameters (fractional vertex indices) of the two fold points, in [0, N); the
    /// folded side runs anticlockwise from the first. For a fold of several arcs, the first
    /// point of the first arc and the last point of the last: the pair that spans them.
    pub s: [f64; 2],
    /// The folded arcs (border parameters, each anticlockwise from its first point), in
    /// walking order from `s[0]`: one arc, `s` itself, unless the fold line crosses the
    /// border more than twice and turns several arcs over (`synth::place`).
    pub arcs: Vec<[f64; 2]>,
    /// The direction found on the disks when the fold points coincide (a unit vector);
    /// `None` when the line runs through the two fold points.
    #[cfg_attr(feature = "schema", schemars(with = "Option<[f64; 2]>"))]
    pub direction: Option<Vector2>,
    /// Mean probe mismatch of the best candidate.
    pub mismatch: f64,
    /// Mean probe mismatch of the start state left as it was (no fold), for comparison.
    pub unfolded_mismatch: f64,
}

impl Synthesis {
    /// A fold at border parameters `s`, one arc along the line through its points, not yet
    /// measured: what `synth::place` starts from when the cut gives the points.
    pub fn guess(s: [f64; 2]) -> Synthesis {
        Synthesis {
            s,
            arcs: vec![s],
            direction: None,
            mismatch: f64::INFINITY,
            unfolded_mismatch: f64::INFINITY,
        }
    }
}

/// The line of a candidate: through the two fold points, or through their midpoint at `phi`.
fn line_of(before: &[Point], s: [f64; 2], phi: Option<f64>) -> Option<Line> {
    let (a, b) = (point_at(before, s[0]), point_at(before, s[1]));
    match phi {
        None => Line::through(&a, &b),
        Some(phi) => Some(Line::at_angle(Point2::new((a.x + b.x) / 2.0, (a.y + b.y) / 2.0), phi)),
    }
}

/// The line through the border point at parameter `s` of `points` at angle `phi`.
fn crossing_line(points: &[Point], s: f64, phi: f64) -> Line {
    let p = point_at(points, s);
    Line::at_angle(Point2::new(p.x, p.y), phi)
}

/// Place a candidate fold (`guess`: the cut's points, [`Synthesis::guess`], or a
/// candidate of [`search_line`]) on the step's start border `before` (normalised) against
/// the measured `end` disk, by the refinement ([`refine`]). A fold of one arc is placed by
/// its two points (and the direction of its line when they coincide, from the guess's
/// direction when it has one). A fold of several arcs is placed by its line (direction and
/// offset), the arcs following it. The result's `mismatch` is infinite when the guess holds
/// several arcs and gives no line.
pub(crate) fn place(
    before: &[Point],
    start: &Disk,
    end: &Disk,
    guess: &Synthesis,
    params: &SynthesisParams,
) -> Synthesis {
    let heading = guess.direction.map(|d| d.y.atan2(d.x));
    match (guess.arcs.len(), heading) {
        (0 | 1, heading) => place_points(before, start, end, guess.s, heading, params),
        (_, Some(phi)) => {
            place_line(before, start, end, &crossing_line(before, guess.s[0], phi), params)
        }
        (_, None) => match line_of(before, guess.s, None) {
            Some(line) => place_line(before, start, end, &line, params),
            None => Synthesis { mismatch: f64::INFINITY, ..guess.clone() },
        },
    }
}

/// Fold points (border parameters) and, when searched, the line's direction.
type Points = ([f64; 2], Option<f64>);

/// The bits of fold points, to tell equal ones apart.
fn points_key(&(s, phi): &Points) -> [u64; 3] {
    [s[0].to_bits(), s[1].to_bits(), phi.map_or(u64::MAX, f64::to_bits)]
}

/// Place the fold points `s` (border parameters, the folded side anticlockwise from s[0])
/// on the step's start border `before` (normalised) against the measured `end` disk: the
/// refinement over all eight neighbours in (s1, s2), so a line sliding along both sides at
/// once is followed, within [`SynthesisParams::reach_edges`] of `s`. When the two points
/// coincide the direction is searched too: from `heading` (the direction of a line that
/// gave `s`, radians) or else the best of [`SynthesisParams::directions`] per half turn,
/// again over a half turn from the best start, then with the points.
fn place_points(
    before: &[Point],
    start: &Disk,
    end: &Disk,
    s: [f64; 2],
    heading: Option<f64>,
    params: &SynthesisParams,
) -> Synthesis {
    let n = before.len();
    let nf = n as f64;
    let flat = super::seed::is_flat(before);
    let probe = Probe::around(start, end, &[s], flat, params.scale(flat), params);
    let axis = flap_axis(before, params.lift);
    let directions = params.directions;
    let cost = |&(s, phi): &Points| {
        let s = s.map(|x| x.rem_euclid(nf));
        line_of(before, s, phi)
            .map_or(f64::INFINITY, |line| probe.cost(&Stack::new(before, axis, &[s], &line)))
    };
    let mut costs = Costs::new(cost, points_key);
    let half_turn = |costs: &mut Costs<_, _, _>, s: [f64; 2]| {
        costs
            .least((0..directions).map(|k| (s, Some(PI * k as f64 / directions as f64))).collect())
            .and_then(|((_, phi), _)| phi)
    };
    let (a, b) = (point_at(before, s[0]), point_at(before, s[1]));
    let coincide = (a.xy() - b.xy()).norm() < params.coincide_edges * mean_edge(before);
    let phi = if coincide { heading.or_else(|| half_turn(&mut costs, s)) } else { None };
    // Start from the best of the given points and their snaps to the vertices either side and
    // the nearest half edge: exact data folds through those, and its optimum is needle sharp.
    let snaps = |x: f64| [x, x.floor(), x.ceil(), (2.0 * x).round() / 2.0];
    let starts = snaps(s[0])
        .into_iter()
        .flat_map(|a| snaps(s[1]).into_iter().map(move |b| ([a, b], phi)))
        .collect();
    let start = costs.least(starts).map_or(s, |((t, _), _)| t);
    let phi = if coincide { half_turn(&mut costs, start) } else { None };
    let best = costs.least(vec![(start, phi)]).unwrap_or(((start, phi), f64::INFINITY));
    // Steps of h edges along the border and h times π / `directions` in angle.
    let angle_step = PI / directions as f64;
    let neighbours = |&(centre, centre_phi): &Points, h: f64| -> Vec<Points> {
        let turns: &[f64] = if centre_phi.is_some() { &[-1.0, 0.0, 1.0] } else { &[0.0] };
        [-1.0, 0.0, 1.0]
            .iter()
            .flat_map(|&d1| {
                [-1.0, 0.0, 1.0]
                    .iter()
                    .flat_map(move |&d2| turns.iter().map(move |&dp| (d1, d2, dp)))
            })
            .filter(|&step| step != (0.0, 0.0, 0.0))
            .map(|(d1, d2, dp)| {
                let phi = centre_phi.map(|p| p + dp * (h * angle_step));
                ([centre[0] + d1 * h, centre[1] + d2 * h], phi)
            })
            .filter(|(t, _)| {
                (t[0] - s[0]).abs() <= params.reach_edges
                    && (t[1] - s[1]).abs() <= params.reach_edges
            })
            .collect()
    };
    let ((s, phi), mismatch) = refine(&mut costs, best, (0.5, params.step_edges), neighbours);
    let s = s.map(|x| x.rem_euclid(nf));
    Synthesis {
        s,
        arcs: vec![s],
        direction: phi.map(|p| Vector2::new(p.cos(), p.sin())),
        mismatch,
        unfolded_mismatch: probe.unfolded(),
    }
}

/// The line at angle `phi` to the x axis whose signed distance from the origin (along its
/// left normal) is `rho`.
pub(crate) fn line_at(phi: f64, rho: f64) -> Line {
    Line {
        point: Point2::new(-rho * phi.sin(), rho * phi.cos()),
        direction: Vector2::new(phi.cos(), phi.sin()),
    }
}

/// Place a fold that turns every arc of the border left of `line` over it: a line that
/// crosses a stacked border 2k times (k ≥ 2) folds k arcs at once (the stacked legs of
/// trousers folded in half; a shirt's hem with a sleeve lying across it). The fold points
/// no longer give the line, so the line itself is refined ([`refine`]), over its direction
/// and offset from `line`, and the arcs follow it. The result spans the arcs: `s` runs from
/// the first point of the first arc to the last point of the last.
fn place_line(
    before: &[Point],
    start: &Disk,
    end: &Disk,
    line: &Line,
    params: &SynthesisParams,
) -> Synthesis {
    let phi0 = line.angle();
    let rho0 = line.direction.x * line.point.y - line.direction.y * line.point.x;
    let flat = super::seed::is_flat(before);
    let arcs = arcs_left_of(before, line);
    let probe = Probe::around(start, end, &arcs, flat, params.scale(flat), params);
    let axis = flap_axis(before, params.lift);
    let folded = |phi: f64, rho: f64| {
        let line = line_at(phi, rho);
        let arcs = arcs_left_of(before, &line);
        (line, arcs)
    };
    let cost = |&[phi, rho]: &[f64; 2]| {
        let (line, arcs) = folded(phi, rho);
        if arcs.is_empty() {
            f64::INFINITY
        } else {
            probe.cost(&Stack::new(before, axis, &arcs, &line))
        }
    };
    let mut costs = Costs::new(cost, |&[phi, rho]: &[f64; 2]| [phi.to_bits(), rho.to_bits()]);
    let best = costs.least(vec![[phi0, rho0]]).unwrap_or(([phi0, rho0], f64::INFINITY));
    // Steps of h mean edges in offset and h times π / `directions` in angle.
    let (edge, angle_step) = (mean_edge(before), PI / params.directions as f64);
    let neighbours = |&[phi, rho]: &[f64; 2], h: f64| -> Vec<[f64; 2]> {
        [-1.0, 0.0, 1.0]
            .iter()
            .flat_map(|&dp| [-1.0, 0.0, 1.0].iter().map(move |&dr| (dp, dr)))
            .filter(|&step| step != (0.0, 0.0))
            .map(|(dp, dr)| [phi + dp * (h * angle_step), rho + dr * (h * edge)])
            .collect()
    };
    let ([phi, rho], mismatch) = refine(&mut costs, best, (1.0, params.step_edges), neighbours);
    let (line, arcs) = folded(phi, rho);
    let s = match (arcs.first(), arcs.last()) {
        (Some(first), Some(last)) => [first[0], last[1]],
        _ => [0.0; 2],
    };
    Synthesis {
        s,
        arcs,
        direction: Some(line.direction),
        mismatch,
        unfolded_mismatch: probe.unfolded(),
    }
}

/// A fold of a stacked start state, found by turning it over every line in turn.
///
/// When an earlier fold has stacked layers, a pair of edges on the same side of the new fold
/// can change a lot (the layers slide, and the dGLI of stacked edges grows like 1/height),
/// so the cut ([`super::cut`]) loses its footing. We try lines instead: 2·[`SynthesisParams::directions`]
/// directions and offsets one mean edge apart across the state; each turns over one arc of
/// the border that lies to its left (a fold may turn the top layer only). The line whose
/// synthesised disks match the measured `end` disk best (on a strided sample of all pairs)
/// give the candidates, best first: [`SynthesisParams::line_candidates`] distinct arcs, each with the points
/// where the border crosses its line, and the line's direction. None of them when no line
/// beats leaving the state as it was by [`SynthesisParams::max_mismatch_share`]. The exact optimum is
/// needle sharp on stacked layers, so the caller places each ([`place`]).
pub(crate) fn search_line(
    before: &[Point],
    start: &Disk,
    end: &Disk,
    params: &SynthesisParams,
) -> Vec<Synthesis> {
    let n = before.len();
    let sampled = sampled_edges(n, params.screen_samples);
    let pairs = sampled
        .iter()
        .flat_map(|&i| sampled.iter().filter(move |&&j| j > i).map(move |&j| (i, j)))
        .collect();
    let probe = Probe::of(pairs, start, end, true, params.stacked_scale);
    let unfolded = probe.unfolded();
    let axis = flap_axis(before, params.lift);
    let directions = params.directions;
    let reach = before.iter().map(|p| p.x.hypot(p.y)).fold(0.0, f64::max);
    let step = mean_edge(before).max(reach / 200.0);
    let offsets = (2.0 * reach / step).ceil() as usize;
    let mut found: Vec<(Vec<[f64; 2]>, f64, f64, Turn)> = (0..2 * directions)
        .into_par_iter()
        .flat_map_iter(|k| {
            (0..offsets).map(move |m| (PI * k as f64 / directions as f64, -reach + m as f64 * step))
        })
        .flat_map_iter(|(phi, rho)| {
            let line = line_at(phi, rho);
            turns_of(before, &line).into_iter().map(move |(arcs, turn)| (arcs, phi, line, turn))
        })
        .map(|(arcs, phi, line, turn)| {
            let mismatch = probe.cost(&Stack::new(before, axis, &arcs, &line));
            (arcs, phi, mismatch, turn)
        })
        .collect();
    found.sort_by(|a, b| a.2.total_cmp(&b.2));
    // The best few distinct turns (by their arcs' ends, to the vertex) of each kind (the
    // one arc of a line crossing the border twice, every arc of one crossing it 2k times,
    // one arc of several: a fold may turn one layer's flap only): on exactly stacked layers
    // the grid misses the needle of the true line, and the partial turns of other lines
    // would crowd it out.
    let kind = |(arcs, turn): (&[[f64; 2]], Turn)| match turn {
        Turn::All if arcs.len() == 1 => 0,
        Turn::All => 1,
        Turn::Holding(_) => 2,
    };
    let mut kept: Vec<Synthesis> = Vec::new();
    for wanted in 0..3 {
        let mut taken = 0;
        for (arcs, phi, mismatch, _) in found.iter().filter(|f| kind((&f.0, f.3)) == wanted) {
            if taken == params.line_candidates || *mismatch >= params.max_mismatch_share * unfolded
            {
                break;
            }
            let key =
                |arcs: &[[f64; 2]]| arcs.iter().map(|a| a.map(f64::round)).collect::<Vec<_>>();
            if kept.iter().all(|k| key(&k.arcs) != key(arcs)) {
                let s = [arcs[0][0], arcs[arcs.len() - 1][1]];
                kept.push(Synthesis {
                    s,
                    arcs: arcs.clone(),
                    direction: Some(Vector2::new(phi.cos(), phi.sin())),
                    mismatch: *mismatch,
                    unfolded_mismatch: unfolded,
                });
                taken += 1;
            }
        }
    }
    kept
}

/// The turns a line offers ([`Turn`]): all the arcs left of it, and when it crosses the
/// border more than twice each of them alone (held by its first vertex), each as its arcs
/// in walking order from the first. A turn of fewer than two vertices, or one that leaves
/// fewer than two behind, is left out.
fn turns_of(before: &[Point], line: &Line) -> Vec<(Vec<[f64; 2]>, Turn)> {
    let n = before.len();
    let arcs = arcs_left_of(before, line);
    let size = |arc: &[f64; 2]| ArcVertices::of(n, arc[0], arc[1]).len;
    let sizes: Vec<usize> = arcs.iter().map(size).collect();
    let fits = |moved: usize| moved >= 2 && moved + 2 <= n;
    if let [arc] = arcs[..] {
        return if fits(sizes[0]) { vec![(vec![arc], Turn::All)] } else { Vec::new() };
    }
    let mut turns: Vec<(Vec<[f64; 2]>, Turn)> = arcs
        .iter()
        .zip(&sizes)
        .filter(|(_, &m)| fits(m))
        .map(|(&arc, _)| {
            let first = ArcVertices::of(n, arc[0], arc[1]).first;
            (vec![arc], Turn::Holding(first))
        })
        .collect();
    if arcs.len() > 1 && fits(sizes.iter().sum()) {
        turns.push((arcs, Turn::All));
    }
    turns
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::rng::SplitMix64;

    /// A square of side 2·`half` centred on the origin, `per_side` edges a side, anticlockwise
    /// from (−half, −half), at height `z(k)` for vertex k.
    fn square(per_side: usize, half: f64, z: impl Fn(usize) -> f64) -> Vec<Point> {
        (0..4 * per_side)
            .map(|k| {
                let t = -half + 2.0 * half * (k % per_side) as f64 / per_side as f64;
                let (x, y) = [(t, -half), (half, t), (-t, half), (-half, -t)][k / per_side];
                Point::new(x, y, z(k))
            })
            .collect()
    }

    /// The border point at parameter `s`, by the test's own interpolation.
    fn at(points: &[Point], s: f64) -> Point {
        let n = points.len();
        let (k, t) = (s.floor() as usize % n, s - s.floor());
        Point::from(points[k].coords * (1.0 - t) + points[(k + 1) % n].coords * t)
    }

    /// `before` folded by hand: every vertex v with 0 < (v − s1) mod n < (s2 − s1) mod n
    /// reflected across the XY line through the border points at s1 and s2, and turned over
    /// at height `axis` (z ↦ 2·axis − z).
    fn fold_by_hand(before: &[Point], s: [f64; 2], axis: f64) -> Vec<Point> {
        let nf = before.len() as f64;
        let (a, b) = (at(before, s[0]), at(before, s[1]));
        let (ux, uy) = ((b.x - a.x) / (b - a).xy().norm(), (b.y - a.y) / (b - a).xy().norm());
        let span = (s[1] - s[0]).rem_euclid(nf);
        before
            .iter()
            .enumerate()
            .map(|(v, p)| {
                let offset = (v as f64 - s[0]).rem_euclid(nf);
                if offset <= 0.0 || offset >= span {
                    return *p;
                }
                let t = (p.x - a.x) * ux + (p.y - a.y) * uy;
                let (fx, fy) = (a.x + t * ux, a.y + t * uy);
                Point::new(2.0 * fx - p.x, 2.0 * fy - p.y, 2.0 * axis - p.z)
            })
            .collect()
    }

    #[test]
    fn the_cost_shortcuts_equal_a_full_dgli_of_the_folded_border() {
        let params = SynthesisParams::default();
        // A flat start (flap pairs negated) and a wavy one (every moved pair computed).
        let flat = square(10, 0.7, |_| 0.0);
        let wavy = square(10, 0.7, |k| 0.03 * (k as f64 * 0.7).sin());
        for (before, flap_negates) in [(flat, true), (wavy, false)] {
            let s = [3.4, 17.7];
            let axis = flap_axis(&before, params.lift);
            let folded = fold_by_hand(&before, s, axis);
            let (start, end) = (Disk::of_border(&before), Disk::of_border(&folded));
            let scale = params.scale(flap_negates);
            let probe = Probe::around(&start, &end, &[s], flap_negates, scale, &params);
            let line = line_of(&before, s, None).expect("two distinct fold points");
            let turned = Stack::new(&before, axis, &[s], &line);
            // The probe holds all three kinds of pair: unmoved, on the flap, across the fold.
            let (flap, unmoved) = (
                |e: usize| turned.edge_group(e) == Some(1),
                |e: usize| turned.edge_group(e) == Some(0),
            );
            let has =
                |kind: &dyn Fn(usize, usize) -> bool| probe.pairs.iter().any(|&(i, j)| kind(i, j));
            assert!(
                has(&|i, j| unmoved(i) && unmoved(j))
                    && has(&|i, j| flap(i) && flap(j))
                    && has(&|i, j| flap(i) != flap(j))
            );
            let cost = probe.cost(&turned);
            assert!(cost < 1e-9, "flap negated: {flap_negates}: the synthesised disk differs from the folded border's by {cost}");
            // The same probe tells another fold apart.
            let other = [5.0, 15.0];
            let wrong =
                Stack::new(&before, axis, &[other], &line_of(&before, other, None).unwrap());
            assert!(probe.cost(&wrong) > 1e-2, "{}", probe.cost(&wrong));
        }
    }

    #[test]
    fn a_capped_probe_is_not_pulled_by_a_few_wild_pairs() {
        let params = SynthesisParams::default();
        let before = square(10, 0.7, |_| 0.0);
        let (s, other) = ([3.4, 17.7], [5.0, 15.0]);
        let axis = flap_axis(&before, params.lift);
        let start = Disk::of_border(&before);
        // The folded border's disk with one value in a hundred made wild, as noise makes the
        // dGLI of nearly collinear edges.
        let folded = Disk::of_border(&fold_by_hand(&before, s, axis));
        let wild: Vec<f64> = folded
            .values()
            .iter()
            .enumerate()
            .map(|(k, &v)| if k % 100 == 7 { v + 1e6 } else { v })
            .collect();
        let end = Disk::from_values(before.len(), wild).expect("a disk's own values");
        let turn = |fold: [f64; 2]| {
            Stack::new(&before, axis, &[fold], &line_of(&before, fold, None).unwrap())
        };
        let (right, wrong) = (turn(s), turn(other));
        let plain = Probe::around(&start, &end, &[s], true, params.flat_scale, &params);
        let capped =
            Probe::around(&start, &end, &[s], true, params.flat_scale, &params).capped(1.5);
        // Each pair counts at most the cap: the wild pairs no longer outweigh the fold, and
        // the right fold stands out from the wrong one by far more.
        let ratio = |probe: &Probe| probe.cost(&wrong) / probe.cost(&right);
        assert!(capped.cost(&right) < 0.15 * plain.cost(&right));
        assert!(ratio(&capped) > 4.0 * ratio(&plain), "{} {}", ratio(&capped), ratio(&plain));
        // A cap above every mismatch changes nothing.
        let loose = Probe::around(&start, &end, &[s], true, params.flat_scale, &params).capped(1e9);
        assert_eq!(loose.cost(&wrong), plain.cost(&wrong));
    }

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

    #[test]
    fn an_off_grid_fold_is_placed_within_a_tenth_of_an_edge() {
        // Folds through seeded random points along two edges, not at vertices or half edges;
        // refine starts from the nearest half edges, as the cut gives them.
        let before = square(10, 0.7, |_| 0.0);
        let start = Disk::of_border(&before);
        let mut rng = SplitMix64::new(16);
        for _ in 0..4 {
            let truth = [
                rng.below(6) as f64 + 2.0 + rng.range(0.1, 0.9),
                rng.below(6) as f64 + 21.0 + rng.range(0.1, 0.9),
            ];
            // Laid at a height of its own, not the synthesis's lift.
            let end = Disk::of_border(&fold_by_hand(&before, truth, 0.006));
            let guess = truth.map(|s| (2.0 * s).round() / 2.0);
            let params = SynthesisParams::default();
            let found = place(&before, &start, &end, &Synthesis::guess(guess), &params);
            let error = [0, 1].map(|k| (found.s[k] - truth[k]).abs());
            assert!(
                error.iter().all(|&e| e <= 0.1),
                "truth {truth:?}, found {:?}: {error:?} edges off",
                found.s
            );
            assert!(found.mismatch < 0.2 * found.unfolded_mismatch, "{found:?}");
        }
    }
}
