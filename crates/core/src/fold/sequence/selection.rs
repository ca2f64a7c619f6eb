//! How many folds a step is read as: k folds only when they explain markedly more of the
//! end disk than fewer (the model selection of [`super`]), and what the answer says.

use serde::{Deserialize, Serialize};

use crate::border::Point;
use crate::budget::Deadline;
use crate::error::Result;
use crate::geometry::Folding;

use super::beam::{all_pairs, judge_made, search, Judged, Probes};
use super::candidate::{merged, MAX_FOLDS};
use crate::fold::params::Params;
#[cfg(doc)]
use crate::fold::params::SelectionParams;
use crate::fold::probe::{sampled_edges, Probe};
use crate::fold::read::Seen;
use crate::fold::seed::{is_flat, Seed};
use crate::fold::state::{Made, Stack};
use crate::fold::synth::Synthesis;

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
    pub(super) fn explained(
        &self,
        judge: &Probe,
        before: &[Point],
        unfolded: f64,
    ) -> Vec<ExplainedFold> {
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
    // The seed judged as the step reports it: its angles, its line through their points.
    // (Judged in the placement's own border parameters instead, the shares explained move
    // in their last digits.)
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
    use crate::disk::Disk;
    use crate::fold::fixtures::{fold_all, unit_square};
    use crate::fold::{read, FoldMethod};
    use std::f64::consts::PI;

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
    fn one_fold_stays_one_and_two_are_found_as_two() {
        let flat = unit_square(24);
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
        let flat = unit_square(24);
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
    fn a_cancelled_deadline_stops_the_search() {
        let flat = unit_square(24);
        let quarters = fold_all(&fold_all(&flat, [0.013, 0.0], PI / 2.0), [0.0, 0.013], 0.0);
        let (start, end) = (Disk::of_border(&flat), Disk::of_border(&quarters));
        let deadline = Deadline::default();
        deadline.cancel();
        let stopped = read(&flat, &start, &end, FoldMethod::Cut, 3, &Params::default(), &deadline);
        assert!(matches!(stopped, Err(crate::error::Error::Cancelled)), "{stopped:?}");
    }
}
