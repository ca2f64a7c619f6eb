//! One refinement for every fold the search makes: a pattern search over the fold's
//! parameters, each candidate's cost computed once.
//!
//! The exact optimum of a fold is needle sharp (an exact fold runs through vertices or half
//! edges, and stacked layers sharpen it further), so no gradient is followed: from the best
//! candidate so far, every neighbour one step away in each parameter is costed (in
//! parallel), the least replaces it while it costs less, and when none does the step
//! halves, until it is below the last one asked for. A neighbourhood overlaps the last one,
//! so the costs are kept ([`Costs`]). One fold is refined by its two points, or by its line
//! when its arcs follow the line ([`super::synth`]); a sequence by each of its folds' two
//! parameters in turn ([`super::sequence`]).

use std::collections::HashMap;
use std::hash::Hash;

use rayon::prelude::*;

/// The costs of candidates, each computed once, in parallel.
pub(crate) struct Costs<C, K, F> {
    cost: F,
    /// Equal candidates have equal keys (their parameters' bits).
    key: fn(&C) -> K,
    known: HashMap<K, f64>,
}

impl<C: Sync, K: Hash + Ord + Send + Sync, F: Fn(&C) -> f64 + Sync> Costs<C, K, F> {
    pub(crate) fn new(cost: F, key: fn(&C) -> K) -> Self {
        Costs { cost, key, known: HashMap::new() }
    }

    /// The candidate of least cost, the first on a tie; `None` without a candidate.
    pub(crate) fn least(&mut self, candidates: Vec<C>) -> Option<(C, f64)> {
        let key = self.key;
        let mut fresh: Vec<(K, &C)> = candidates
            .iter()
            .map(|c| (key(c), c))
            .filter(|(k, _)| !self.known.contains_key(k))
            .collect();
        fresh.sort_by(|a, b| a.0.cmp(&b.0));
        fresh.dedup_by(|a, b| a.0 == b.0);
        let costs: Vec<f64> = fresh.par_iter().map(|(_, c)| (self.cost)(c)).collect();
        self.known.extend(fresh.into_iter().map(|(k, _)| k).zip(costs));
        candidates
            .into_iter()
            .map(|c| {
                let cost = self.known[&key(&c)];
                (c, cost)
            })
            .min_by(|a, b| a.1.total_cmp(&b.1))
    }
}

/// The pattern search from `best` (a candidate and its cost): the least of
/// `neighbours(centre, h)` replaces the centre while it costs less; when none does, `h`
/// halves, from `first` while it is at least `last`.
pub(crate) fn refine<C: Sync, K: Hash + Ord + Send + Sync, F: Fn(&C) -> f64 + Sync>(
    costs: &mut Costs<C, K, F>,
    mut best: (C, f64),
    (first, last): (f64, f64),
    neighbours: impl Fn(&C, f64) -> Vec<C>,
) -> (C, f64) {
    let mut h = first;
    while h >= last {
        match costs.least(neighbours(&best.0, h)) {
            Some(better) if better.1 < best.1 => best = better,
            _ => h /= 2.0,
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};

    #[test]
    fn the_search_halves_its_step_into_a_sharp_minimum_and_costs_each_candidate_once() {
        // A needle at (0.3125, −0.75), on the grid of eighths the search reaches.
        let calls = AtomicUsize::new(0);
        let cost = |&(x, y): &(f64, f64)| {
            calls.fetch_add(1, Ordering::Relaxed);
            (x - 0.3125).abs() + 10.0 * (y + 0.75).abs()
        };
        let mut costs = Costs::new(cost, |&(x, y): &(f64, f64)| [x.to_bits(), y.to_bits()]);
        let neighbours = |&(x, y): &(f64, f64), h: f64| {
            let steps = [-1.0, 0.0, 1.0];
            steps
                .iter()
                .flat_map(|&dx| steps.iter().map(move |&dy| (x + dx * h, y + dy * h)))
                .filter(|&p| p != (x, y))
                .collect::<Vec<_>>()
        };
        let start = costs.least(vec![(0.0, 0.0)]).unwrap();
        let ((x, y), best) = refine(&mut costs, start, (0.5, 1.0 / 16.0), neighbours);
        assert_eq!((x, y, best), (0.3125, -0.75, 0.0));
        // Every candidate costed once however often its neighbourhoods held it.
        assert_eq!(calls.load(Ordering::Relaxed), costs.known.len());
        // The first of equal candidates wins a tie.
        let tie = costs.least(vec![(0.3125, -0.75), (0.3125, -0.75)]);
        assert_eq!(tie, Some(((0.3125, -0.75), 0.0)));
    }
}
