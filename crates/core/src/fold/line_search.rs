//! The fold of a stacked start state, found by turning it over every line in turn: the seed
//! of a step whose start an earlier fold has stacked ([`super::synth`] then places it).

use std::f64::consts::PI;

use rayon::prelude::*;

use crate::angle::ArcVertices;
use crate::border::Point;
use crate::disk::Disk;
use crate::geometry::{Line, Vector2};

use super::params::SynthesisParams;
use super::probe::{sampled_edges, Probe};
use super::state::{arcs_left_of, flap_axis, mean_edge, Stack, Turn};
use super::synth::{line_at, Synthesis};

/// A fold of a stacked start state, found by turning it over every line in turn.
///
/// When an earlier fold has stacked layers, a pair of edges on the same side of the new fold can
/// change a lot (the layers slide, and the dGLI of stacked edges grows like 1/height), so the cut
/// ([`super::cut`]) loses its footing. We try lines instead: 2·[`SynthesisParams::directions`]
/// directions and offsets one mean edge apart across the state; each turns over one arc of the
/// border that lies to its left (a fold may turn the top layer only). The line whose synthesised
/// disks match the measured `end` disk best (on a strided sample of all pairs) give the candidates,
/// best first: [`SynthesisParams::line_candidates`] distinct arcs, each with the points where the
/// border crosses its line, and the line's direction. None of them when no line beats leaving the
/// state as it was by [`SynthesisParams::max_mismatch_share`]. The exact optimum is needle sharp on
/// stacked layers, so the caller places each ([`place`]).
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
