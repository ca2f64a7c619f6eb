//! The beam search of fold sequences: a fold at a time on the states of the beam, screened
//! on strided pairs, the best of each length settled (refined, all their folds together)
//! and judged at the flap height that fits them best.

use std::collections::{HashMap, HashSet};
use std::f64::consts::PI;
use std::sync;

use rayon::prelude::*;

use crate::border::Point;
use crate::budget::Deadline;
use crate::disk::Disk;
use crate::error::Result;
use crate::metrics::aligned_rmse_xy;

use super::candidate::{
    cost, key, make, make_next, moves_on, square_to_sides, through_also, Anchor, Candidate, Frame,
    Move, Partial, Through,
};
use super::layer_order::layer_order;
use crate::fold::cut::find_cuts;
use crate::fold::params::Params;
#[cfg(doc)]
use crate::fold::params::SequenceParams;
use crate::fold::probe::Probe;
use crate::fold::read::Seen;
use crate::fold::refine::{refine, Costs};
use crate::fold::state::{Made, Stack};

/// A candidate sequence screened.
pub(super) struct Scored {
    pub(super) cost: f64,
    pub(super) candidate: Candidate,
    /// What its folds moved ([`Stack::groups`]), shared by the equal sequences.
    pub(super) groups: sync::Arc<[u8]>,
}

impl Scored {
    /// The sequence, its folds made on `beam`'s state.
    pub(super) fn partial(&self, beam: &[Partial]) -> Partial {
        beam[self.candidate.parent].then(&self.candidate)
    }
}

/// `candidates` (each on a state of `beam`, made in `parents`) screened on `probes.screen`, best
/// first; once per distinct sequence of folds: the cut sets share many points, so the same folds
/// come from several of them. More than [`SequenceParams::glanced`] are first glanced at on
/// `probes.glance`, and only the best so many of them, and the best through each set of cut points
/// (which the beam carries on), screened. Those that cannot be made, or come after `deadline`, are
/// left out.
pub(super) fn screen(
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
pub(super) struct Judged {
    /// Mean mismatch on the judging probe.
    pub(super) cost: f64,
    pub(super) made: Vec<Made>,
    pub(super) lift: f64,
    /// The synthesised end state at that height.
    pub(super) state: Vec<Point>,
}

/// `made` judged on `judge` at each of `lifts` (at least one, [`SequenceParams::lifts`]), the
/// best kept.
pub(super) fn judge_made(
    judge: &Probe,
    before: &[Point],
    made: Vec<Made>,
    lifts: &[f64],
) -> Judged {
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
pub(super) struct Probes {
    pub(super) screen: Probe,
    /// A quarter of `screen`'s pairs, to rank many candidates before screening the best.
    pub(super) glance: Probe,
    pub(super) judge: Probe,
    pub(super) order: Probe,
}

/// What every level of one step's beam search reads: the step, its probes and knobs, the
/// sets of cut points its folds run through, and the directions square to the flat
/// cloth's straight sides.
struct BeamSearch<'a> {
    seen: Seen<'a>,
    probes: &'a Probes,
    params: &'a Params,
    deadline: &'a Deadline,
    cut_sets: Vec<Vec<f64>>,
    squares: Vec<f64>,
}

impl<'a> BeamSearch<'a> {
    /// The search of `seen` for sequences of up to `max_folds` folds; `None` when the offset
    /// disk the creases are placed on cannot be made.
    fn new(
        seen: Seen<'a>,
        probes: &'a Probes,
        params: &'a Params,
        deadline: &'a Deadline,
        max_folds: usize,
    ) -> Option<BeamSearch<'a>> {
        let Seen { before, start, end } = seen;
        let n = before.len();
        let g = start.abs_diff(end);
        let weight = params.cut.start_share;
        let offset: Vec<f64> =
            g.values().iter().zip(start.values()).map(|(c, s)| c - weight * s.abs()).collect();
        let offset = Disk::from_values(n, offset).ok()?;
        // Cut points of as many arcs as the sequences could make: 2 per fold line on a flat
        // cloth, more where it crosses layers.
        let cut_sets: Vec<Vec<f64>> = [4usize, 6, 8]
            .into_iter()
            .filter(|&m| m <= 2 * max_folds + 2 && m < n)
            .filter_map(|m| find_cuts(&offset, m, &params.cut).map(|c| c.points))
            .collect();
        let squares = square_to_sides(before, &params.sequence);
        Some(BeamSearch { seen, probes, params, deadline, cut_sets, squares })
    }

    /// Every fold through the free cut points on each state of the beam (made in
    /// `parents`).
    fn candidates(
        &self,
        beam: &[Partial],
        parents: &[Option<(Stack, Vec<Made>)>],
    ) -> Vec<Candidate> {
        let (squares, cut_sets, params) = (&self.squares, &self.cut_sets, self.params);
        beam.par_iter()
            .zip(parents)
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
            .collect()
    }

    /// The candidates of a level screened, best first: rays were tried every
    /// π / `coarse_directions`, and the best are tried again a fine step either side.
    fn scored(&self, beam: &[Partial], parents: &[Option<(Stack, Vec<Made>)>]) -> Vec<Scored> {
        let (probes, deadline, params) = (self.probes, self.deadline, self.params);
        let candidates = self.candidates(beam, parents);
        let mut scored = screen(beam, parents, probes, candidates, deadline, params);
        let step = PI / params.synthesis.directions as f64;
        let finer: Vec<Candidate> = scored
            .iter()
            .filter(|s| matches!(s.candidate.next.anchor, Anchor::Ray(..)))
            .take(params.sequence.finer_rays)
            .flat_map(|s| {
                [-1.0, 1.0].map(|d| Candidate {
                    next: s.candidate.next.moved([0.0, d], step),
                    ..s.candidate
                })
            })
            .collect();
        scored.extend(screen(beam, parents, probes, finer, deadline, params));
        scored.sort_by(|a, b| a.cost.total_cmp(&b.cost));
        scored
    }

    /// Sequences refined and judged; those that cannot be made, or come after the deadline,
    /// left out.
    fn judge_all(&self, chosen: Vec<Vec<Move>>) -> Vec<Judged> {
        let (before, params) = (self.seen.before, self.params);
        chosen
            .into_par_iter()
            .filter_map(|moves| {
                if self.deadline.expired() {
                    return None;
                }
                let moves = settle(&self.seen, moves, params);
                let (_, made) = make(before, &moves, params)?;
                Some(judge_made(&self.probes.judge, before, made, &params.sequence.lifts))
            })
            .collect()
    }

    /// `judged` (best first) with the twins of its best one (another order of the same
    /// folds, from `scored`) refined too, so that the layer order can decide between them,
    /// and no two that refined into one.
    fn with_twins(
        &self,
        beam: &[Partial],
        scored: &[Scored],
        mut judged: Vec<Judged>,
    ) -> Result<Vec<Judged>> {
        let (before, params) = (self.seen.before, self.params);
        let lift = params.synthesis.lift;
        let Some(first) = judged.first() else { return Ok(judged) };
        let seen: Vec<Vec<u8>> =
            judged.iter().map(|j| Stack::of(before, &j.made, lift).groups().to_vec()).collect();
        let mut twins: Vec<(Vec<Move>, sync::Arc<[u8]>)> = Vec::new();
        for s in scored.iter().filter(|s| !seen.iter().any(|g| **g == *s.groups)) {
            if twins.len() == params.sequence.twins {
                break;
            }
            if twins.iter().any(|t| t.1 == s.groups) {
                continue;
            }
            let moves = s.partial(beam).moves;
            let Some((t, _)) = make(before, &moves, params) else { continue };
            // Unrefined, a twin lands less alike.
            if aligned_rmse_xy(&t.state, &first.state) < 2.0 * params.layer_order.congruent {
                twins.push((moves, s.groups.clone()));
            }
        }
        let twins: Vec<Vec<Move>> = twins.into_iter().map(|t| t.0).collect();
        judged.extend(self.judge_all(twins));
        self.deadline.check()?;
        judged.sort_by(|a, b| a.cost.total_cmp(&b.cost));
        // Refined from different starts, two may have become one.
        let mut groups: Vec<Vec<u8>> = Vec::new();
        judged.retain(|j| {
            let g = Stack::of(before, &j.made, lift).groups().to_vec();
            let new = !groups.contains(&g);
            groups.push(g);
            new
        });
        Ok(judged)
    }
}

/// The best `width` of `scored` (best first), distinct by what their folds moved.
fn kept(scored: &[Scored], width: usize) -> Vec<&Scored> {
    let mut kept: Vec<&Scored> = Vec::new();
    for s in scored {
        if kept.len() == width {
            break;
        }
        if kept.iter().all(|k| k.groups != s.groups) {
            kept.push(s);
        }
    }
    kept
}

/// The sequences carried on from level `level` of a search of a border of `n` vertices: the
/// `kept`, and the best of `scored` through each set of cut points they do not hold, with
/// its last fold turning the smaller part and with it turning the larger, unless it moves
/// what one carried already moves. The end disk ranks a sequence's first folds poorly when
/// its last ones are still to come (sides folded in leave a cloth folded in half less
/// explained than the flat one), but which creases they are, and which side of each
/// turned, are few enough to keep.
fn carried(
    beam: &[Partial],
    kept: &[&Scored],
    scored: &[Scored],
    level: usize,
    n: usize,
) -> Vec<Partial> {
    let mut carried: Vec<Partial> = kept.iter().map(|k| k.partial(beam)).collect();
    let smaller = |s: &Scored| 2 * s.groups.iter().filter(|&&g| g & (1 << level) != 0).count() <= n;
    let mut through: HashSet<(Through, bool)> =
        kept.iter().map(|k| (k.candidate.through, smaller(k))).collect();
    let mut moved: HashSet<sync::Arc<[u8]>> = kept.iter().map(|k| k.groups.clone()).collect();
    for s in scored {
        if through.insert((s.candidate.through, smaller(s))) && moved.insert(s.groups.clone()) {
            carried.push(s.partial(beam));
        }
    }
    carried
}

/// The `refined` of `kept` to refine: the best of each state the beam came from first.
fn chosen(beam: &[Partial], kept: &[&Scored], refined: usize) -> Vec<Vec<Move>> {
    let mut chosen: Vec<Vec<Move>> = Vec::new();
    let mut prefixes: Vec<usize> = Vec::new();
    for k in kept {
        if chosen.len() < refined && !prefixes.contains(&k.candidate.parent) {
            prefixes.push(k.candidate.parent);
            chosen.push(k.partial(beam).moves);
        }
    }
    for k in kept {
        let moves = k.partial(beam).moves;
        if chosen.len() < refined && !chosen.contains(&moves) {
            chosen.push(moves);
        }
    }
    chosen
}

/// The best sequence of each length from one fold up to `max_folds`, judged on `probes`, with the
/// sequences of its length judged about as well (its twins and alternatives; none for one fold); a
/// length of two or more whose best one `deeper` rejects is the last searched (the model selection
/// needs no longer ones). [`Cancelled`](crate::error::Error::Cancelled) once `deadline` expires:
/// the search is checked between candidates.
pub(super) fn search(
    seen: &Seen,
    probes: &Probes,
    params: &Params,
    max_folds: usize,
    deeper: impl Fn(&Judged) -> bool,
    deadline: &Deadline,
) -> Result<Vec<(Judged, Vec<Judged>)>> {
    let Some(search) = BeamSearch::new(*seen, probes, params, deadline, max_folds) else {
        return Ok(Vec::new());
    };
    let (before, q) = (seen.before, &params.sequence);
    let mut beam: Vec<Partial> = (0..search.cut_sets.len())
        .map(|set| Partial { set, moves: Vec::new(), used: Vec::new() })
        .collect();
    let mut found = Vec::new();
    for level in 0..max_folds {
        deadline.check()?;
        // The states of the beam made once: each candidate makes only its last fold on a copy.
        let parents: Vec<Option<(Stack, Vec<Made>)>> =
            beam.par_iter().map(|partial| make(before, &partial.moves, params)).collect();
        let scored = search.scored(&beam, &parents);
        let kept = kept(&scored, if level == 0 { q.first_beam } else { q.beam });
        if kept.is_empty() {
            break;
        }
        let carried = carried(&beam, &kept, &scored, level, before.len());
        if level == 0 {
            // The search's own best single fold, for the model selection to weigh against
            // the step's detected one: a fold whose crease meets two straight sides square
            // to them is found here, through one cut point in a searched direction.
            let singles = search
                .judge_all(kept.iter().take(q.singles).map(|k| k.partial(&beam).moves).collect());
            let best = singles.into_iter().min_by(|a, b| a.cost.total_cmp(&b.cost));
            found.extend(best.map(|one| (one, Vec::new())));
            beam = carried;
            continue;
        }
        let mut judged = search.judge_all(chosen(&beam, &kept, q.refined));
        deadline.check()?;
        judged.sort_by(|a, b| a.cost.total_cmp(&b.cost));
        let mut judged = search.with_twins(&beam, &scored, judged)?;
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

/// Settle every fold of `moves` together, by the refinement ([`refine`]) over each fold's
/// two parameters (all eight neighbours of one fold at a time).
pub(super) fn settle(seen: &Seen, moves: Vec<Move>, params: &Params) -> Vec<Move> {
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

/// Every pair of `edges`.
pub(super) fn all_pairs(edges: &[usize]) -> Vec<(usize, usize)> {
    edges
        .iter()
        .enumerate()
        .flat_map(|(k, &i)| edges[k + 1..].iter().map(move |&j| (i, j)))
        .collect()
}
