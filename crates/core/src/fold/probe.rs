//! The probe a synthesised state is compared with the measured end disk by: a fixed set of
//! pairs of edges, their dGLI compressed and compared (Kamat, Borràs, Torras, "CloSE",
//! Sec. III: the dGLI disk of a state).
//!
//! Probe pairs: every edge near a fold point against a strided sample of all edges, and a
//! strided sample of flap edges against the rest ([`Probe::around`]), or every pair of a
//! strided sample ([`Probe::of`]). Values are compared after `asinh(v / s)`
//! ([`SynthesisParams::flat_scale`], [`SynthesisParams::stacked_scale`]), so that pairs of
//! stacked layers, whose dGLI grows like 1/height, do not drown the others while the
//! synthesised height differs from the real one. Only the pairs a fold changed need a dGLI
//! ([`Probe::cost`]): a probe costs thousands of times per step.

use crate::angle::ArcVertices;
use crate::border::Point;
use crate::disk::Disk;
use crate::gli::dgli_each;

use super::params::SynthesisParams;
use super::state::Stack;

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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fold::fixtures::{fold_by_hand, square};
    use crate::fold::state::flap_axis;
    use crate::fold::synth::line_of;

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
}
