//! Did the fold land: an observed state against a goal sequence of folds, and what would
//! correct it (our extension of CloSE, for a robot's loop; the paper's planning, Sec. V,
//! supplies the correction).
//!
//! The observed state is an analysis (a flat start and the frames after it); the goal is a
//! sequence of folds (g1, g2) in angles of the same start border, optionally each with the
//! line it is made along. The two sequences are matched in order by the least-cost edit of
//! [`crate::distance`]: a goal fold matched to an observed one is **found** when both its
//! points lie within [`Tolerance::edges`] edges of the goal's, **misplaced** otherwise; a goal
//! fold left unmatched is **missing**; an observed fold left unmatched is **extra**. Each
//! point's error is signed (observed − goal, anticlockwise positive) and given in edges and
//! in % of the border (one edge = 100/N %); `short_edges` is how much less of the border the
//! observed fold folds over than the goal's (negative: more).
//!
//! The goal is **reached** when every goal fold is found, none is extra, and the predicted
//! shapes are close: the aligned XY RMSE between the goal's predicted state and the observed
//! one ([`crate::distance`]'s geometric distance) is at most [`Tolerance::aligned_rmse`]
//! (normalised units). Both states are predicted alike from their folds on the start border
//! (`crate::distance::fold_state`), so that the same folds are at 0 whatever the cloth's
//! slide: a fold through its points, or, for an observed fold made through stacked layers,
//! in the direction the disks gave, which the goal fold matched to it takes too (through
//! its own points). A fold of several arcs counts as the fold that spans them. A goal fold
//! whose points lie on top of each other with no line to go by leaves the shape uncompared
//! (`distance.geometric` is `None`): the folds alone decide.
//!
//! The plan is [`crate::plan::plan_for`] from the observed state to the goal's folds in
//! order; `text` says the outcome in
//! one sentence: "goal reached", or the first problems and the grasps that correct them.
//!
//! ```
//! use close_core::{analyze, border::prepare, FrameRange};
//! use close_core::verify::{verify, Goal, Status, Tolerance};
//! use std::f64::consts::PI;
//! // A square of 40 vertices, its right half folded over onto the left along x = 0.5.
//! let square: Vec<[f64; 3]> = (0..40)
//!     .map(|k| {
//!         let t = (k % 10) as f64 / 10.0;
//!         [[t, 0.0], [1.0, t], [1.0 - t, 1.0], [0.0, 1.0 - t]][k / 10]
//!     })
//!     .map(|[x, y]| [x, y, 0.0])
//!     .collect();
//! let folded = square.iter().map(|&[x, y, z]| if x > 0.5 { [1.0 - x, y, 0.01] } else { [x, y, z] }).collect();
//! let observed = analyze(&prepare(vec![square, folded])?, FrameRange::default())?;
//! // The goal: from the bottom side's middle (vertex 5) to the top side's (vertex 25).
//! let edge = 2.0 * PI / 40.0;
//! let answer = verify(&observed, &Goal::folds(vec![[5.0 * edge, 25.0 * edge]]), Tolerance::default())?;
//! assert!(answer.reached, "{}", answer.text);
//! assert_eq!(answer.folds[0].status, Status::Found);
//! // The left half instead: the fold made is not the one wanted.
//! let other = verify(&observed, &Goal::folds(vec![[25.0 * edge, 5.0 * edge]]), Tolerance::default())?;
//! assert!(!other.reached && other.folds[0].other_side);
//! # Ok::<(), close_core::Error>(())
//! ```

use serde::{Deserialize, Serialize};

use crate::analysis::Analysis;
use crate::angle::{edge, wrap_pi};
use crate::border::to_xyz;
use crate::distance::{
    align, check_folds, fold_state, share, Distance, Edit, LineOf, MAX_BATCH_FOLDS,
};
use crate::error::{Error, Result};
use crate::geometry::Line;
use crate::metrics::aligned_rmse_xy;
use crate::plan::{plan_for, Action, Plan};

/// How close the observed state must be to the goal to have reached it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Tolerance {
    /// Each fold point within this many edges of the goal's.
    pub edges: f64,
    /// The aligned XY RMSE between the predicted borders at most this (normalised units).
    pub aligned_rmse: f64,
}

impl Default for Tolerance {
    fn default() -> Tolerance {
        Tolerance { edges: 1.5, aligned_rmse: 0.03 }
    }
}

/// A goal: folds (g1, g2) in angles of the start border, made in order, and the line each
/// is made along where it is known (`lines[k]` for fold k; missing entries are unknown).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Goal {
    pub folds: Vec<[f64; 2]>,
    pub lines: Vec<Option<Line>>,
}

impl Goal {
    /// A goal of folds alone (`Fold`s or `[f1, f2]` pairs), each made along the line
    /// through its points.
    pub fn folds<F: Into<[f64; 2]>>(folds: impl IntoIterator<Item = F>) -> Goal {
        Goal { folds: folds.into_iter().map(Into::into).collect(), lines: Vec::new() }
    }
}

/// What became of one goal fold.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// Made, both points within the tolerance.
    Found,
    /// Made, a point (or the side) off.
    Misplaced,
    /// Not made.
    Missing,
}

/// One goal fold against the observed state.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GoalFold {
    /// The goal fold, in [0, 2π) (radians).
    pub goal: [f64; 2],
    pub status: Status,
    /// The observed fold matched to it: its 0-based index among the observed folds, and
    /// the fold, in [0, 2π) (radians); `None` when missing.
    pub observed: Option<usize>,
    pub fold: Option<[f64; 2]>,
    /// Observed − goal at each point, in edges (anticlockwise positive).
    pub error_edges: Option<[f64; 2]>,
    /// The same in % of the border.
    pub error_percent: Option<[f64; 2]>,
    /// How many edges less of the border the observed fold folds over than the goal's
    /// (negative: more).
    pub short_edges: Option<f64>,
    /// The observed fold runs between the goal's points but folds the other side over.
    pub other_side: bool,
}

/// An observed fold that the goal does not hold.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ExtraFold {
    /// 0-based index among the observed folds.
    pub observed: usize,
    /// The fold, in [0, 2π) (radians).
    pub fold: [f64; 2],
    /// What it costs in the distance: the share of the border it folds over.
    pub share: f64,
}

/// The answer of `close verify`, `POST /api/verify` and `close.verify`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Verification {
    pub reached: bool,
    /// The outcome in one sentence.
    pub text: String,
    pub tolerance: Tolerance,
    pub distance: Distance,
    /// One per goal fold, in order.
    pub folds: Vec<GoalFold>,
    pub extra: Vec<ExtraFold>,
    /// The plan from the observed state to the goal's folds in order.
    pub plan: Option<Plan>,
    /// Border vertex count: an edge is 2π/N.
    pub n: usize,
    /// The goal's folds and the observed ones, in [0, 2π) (radians).
    pub goal: Vec<[f64; 2]>,
    pub observed: Vec<[f64; 2]>,
    /// The goal's predicted state: the start border with the goal's folds made in turn
    /// (input coordinates, border order), as the shapes were compared; `None` where a goal
    /// fold has no line to go by.
    pub goal_border: Option<Vec<[f64; 3]>>,
}

/// Checks a tolerance: finite and not negative.
fn check_tolerance(t: &Tolerance) -> Result<()> {
    for (name, v) in [("edges", t.edges), ("aligned_rmse", t.aligned_rmse)] {
        if !(v.is_finite() && v >= 0.0) {
            return Err(Error::InvalidArgument(format!(
                "tolerance {name} must be a finite number ≥ 0, not {v}"
            )));
        }
    }
    Ok(())
}

/// How each observed fold's line was found: in the direction the disks gave where its
/// points lie on top of each other (a fold through stacked layers), through its points
/// otherwise; as the analysis made its `predicted_end`.
fn observed_lines(observed: &Analysis) -> Vec<LineOf> {
    observed
        .steps
        .iter()
        .flat_map(|s| {
            // A step's one fold took the disks' direction only where its points coincide;
            // every fold of a sequence did.
            let sequence = s.folds.len() > 1;
            let from_disks =
                sequence || s.detection.synthesis.as_ref().is_some_and(|x| x.direction.is_some());
            s.foldings().map(move |f| match f.line {
                Some(line) if from_disks => LineOf::Direction([line.direction.x, line.direction.y]),
                _ => LineOf::Points,
            })
        })
        .collect()
}

/// Checks a goal before any work: at most [`MAX_BATCH_FOLDS`] folds, finite, their points
/// more than an edge apart on a border of `n` vertices (when known), no more lines than
/// folds, each line finite with a direction.
pub fn check_goal(goal: &Goal, n: Option<usize>) -> Result<()> {
    if goal.folds.len() > MAX_BATCH_FOLDS {
        return Err(Error::too_large("goal folds", goal.folds.len(), MAX_BATCH_FOLDS));
    }
    if goal.lines.len() > goal.folds.len() {
        return Err(Error::InvalidArgument(format!(
            "the goal has {} lines for {} folds",
            goal.lines.len(),
            goal.folds.len()
        )));
    }
    for (k, line) in goal.lines.iter().enumerate() {
        if let Some(Line { point, direction }) = line {
            let finite = [point.x, point.y, direction.x, direction.y].iter().all(|v| v.is_finite());
            if !finite || direction.norm() == 0.0 {
                return Err(Error::InvalidArgument(format!(
                    "the goal's line {}: a finite point and a non-zero direction are needed",
                    k + 1
                )));
            }
        }
    }
    check_folds("the goal", &goal.folds, n.map_or(0.0, edge))
}

/// Verify the `observed` state against the `goal`: see the module's doc.
pub fn verify(observed: &Analysis, goal: &Goal, tolerance: Tolerance) -> Result<Verification> {
    check_tolerance(&tolerance)?;
    let n = observed.n;
    check_goal(goal, Some(n))?;
    let goal_folds: Vec<[f64; 2]> =
        goal.folds.iter().map(|f| f.map(crate::angle::wrap_tau)).collect();
    let observed_folds = crate::distance::pairs(&observed.folds);
    let alignment = align(&goal_folds, &observed_folds);
    let to_edges = |delta: f64| delta / edge(n);
    let mut folds: Vec<GoalFold> = goal_folds
        .iter()
        .map(|&g| GoalFold {
            goal: g,
            status: Status::Missing,
            observed: None,
            fold: None,
            error_edges: None,
            error_percent: None,
            short_edges: None,
            other_side: false,
        })
        .collect();
    let mut extra = Vec::new();
    let observed_lines = observed_lines(observed);
    // Each goal fold's line: its own; or, matched to an observed fold made through stacked
    // layers, that fold's direction through the goal's own points; or through its points.
    let mut goal_lines: Vec<LineOf> = (0..goal_folds.len())
        .map(|k| match goal.lines.get(k).copied().flatten() {
            Some(Line { point, direction }) => {
                LineOf::Given(Line { point, direction: direction / direction.norm() })
            }
            None => LineOf::Points,
        })
        .collect();
    for edit in &alignment.edits {
        match *edit {
            Edit::Matched { a, b } => {
                let (g, o) = (goal_folds[a], observed_folds[b]);
                let error = [to_edges(wrap_pi(o[0] - g[0])), to_edges(wrap_pi(o[1] - g[1]))];
                let within = |e: f64| e.abs() <= tolerance.edges;
                let other_side = !(within(error[0]) && within(error[1]))
                    && within(to_edges(wrap_pi(o[0] - g[1])))
                    && within(to_edges(wrap_pi(o[1] - g[0])));
                let found = within(error[0]) && within(error[1]);
                folds[a] = GoalFold {
                    status: if found { Status::Found } else { Status::Misplaced },
                    observed: Some(b),
                    fold: Some(o),
                    error_edges: Some(error),
                    error_percent: Some(error.map(|e| 100.0 * e / n as f64)),
                    short_edges: Some((share(g) - share(o)) * n as f64),
                    other_side,
                    ..folds[a]
                };
                if let (LineOf::Points, Some(&LineOf::Direction(d))) =
                    (goal_lines[a], observed_lines.get(b))
                {
                    goal_lines[a] = LineOf::Direction(d);
                }
            }
            Edit::OnlyA { .. } => {}
            Edit::OnlyB { b } => extra.push(ExtraFold {
                observed: b,
                fold: observed_folds[b],
                share: share(observed_folds[b]),
            }),
        }
    }
    // Both states predicted alike from their folds (so that the same folds are at 0), and
    // normalised by the start border's transform.
    let start = observed.start_border();
    let goal_state = fold_state(start, &goal_folds, &goal_lines).ok();
    let geometric = goal_state
        .as_ref()
        .and_then(|g| Some((g, fold_state(start, &observed_folds, &observed_lines).ok()?)))
        .map(|(g, o)| {
            let norm = &observed.normalisation;
            aligned_rmse_xy(&norm.apply_all(g), &norm.apply_all(&o))
        });
    let reached = folds.iter().all(|f| f.status == Status::Found)
        && extra.is_empty()
        && geometric.is_none_or(|g| g <= tolerance.aligned_rmse);
    let goal_sequence: Vec<crate::Fold> = goal_folds.iter().map(|&g| g.into()).collect();
    let plan = Some(plan_for(observed, &goal_sequence)?);
    let distance = Distance { folds: alignment.distance, geometric };
    let text = sentence(reached, &folds, &extra, distance, &tolerance, plan.as_ref());
    Ok(Verification {
        reached,
        text,
        tolerance,
        distance,
        folds,
        extra,
        plan,
        n,
        goal: goal_folds,
        observed: observed_folds,
        goal_border: goal_state.map(|g| g.iter().map(to_xyz).collect()),
    })
}

/// The outcome in one sentence: "goal reached", or the problems and the first step of the
/// plan that corrects them.
fn sentence(
    reached: bool,
    folds: &[GoalFold],
    extra: &[ExtraFold],
    distance: Distance,
    tolerance: &Tolerance,
    plan: Option<&Plan>,
) -> String {
    let shape = match distance.geometric {
        Some(g) => format!("shapes {g:.3} apart (tolerance {})", tolerance.aligned_rmse),
        None => "shape not compared (a stacked fold has no line)".to_string(),
    };
    if reached {
        let worst = folds
            .iter()
            .filter_map(|f| f.error_edges)
            .flat_map(|e| e.map(f64::abs))
            .fold(0.0, f64::max);
        return if folds.is_empty() {
            "goal reached: the cloth is flat".to_string()
        } else {
            format!(
                "goal reached: every fold point within {worst:.1} edges (tolerance {}), {shape}",
                tolerance.edges
            )
        };
    }
    let mut problems: Vec<String> = folds
        .iter()
        .enumerate()
        .filter_map(|(k, f)| {
            let k = k + 1;
            match (f.status, f.error_edges, f.short_edges) {
                (Status::Found, ..) => None,
                (Status::Missing, ..) => Some(format!("fold {k} is missing")),
                _ if f.other_side => Some(format!("fold {k} folds the other side over")),
                (Status::Misplaced, Some(error), Some(short)) => {
                    let worst = error[0].abs().max(error[1].abs());
                    Some(if short.abs() >= 0.5 * worst {
                        if short > 0.0 {
                            format!("fold {k} is {short:.1} edges short")
                        } else {
                            format!("fold {k} goes {:.1} edges too far", -short)
                        }
                    } else {
                        format!(
                            "fold {k} is {worst:.1} edges off (points {:+.1}, {:+.1})",
                            error[0], error[1]
                        )
                    })
                }
                _ => None,
            }
        })
        .collect();
    problems.extend(
        extra
            .iter()
            .map(|e| format!("an extra fold ({:.2}, {:.2}) was made", e.fold[0], e.fold[1])),
    );
    if problems.is_empty() {
        problems.push(format!("every fold is within tolerance but the {shape}"));
    }
    let mut text = problems.join("; ");
    if let Some(step) = plan.and_then(|p| p.steps.first()) {
        // Rounded first, so that a coordinate a hair below zero does not print as "-0.000".
        let c = |x: f64| ((x * 1e3).round() / 1e3) + 0.0;
        let xyz = |v: [f64; 3]| format!("({:.3}, {:.3}, {:.3})", c(v[0]), c(v[1]), c(v[2]));
        let grasps: Vec<String> = step
            .picks
            .iter()
            .map(|p| {
                format!(
                    "grasp vertex {} at {} and place it at {}",
                    p.vertex,
                    xyz(p.from),
                    xyz(p.to)
                )
            })
            .collect();
        if !grasps.is_empty() {
            let first = if step.action == Action::Unfold { "unfold first: " } else { "" };
            text += &format!(": {first}{}", grasps.join(", then "));
        }
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::angle::param_to_angle;
    use crate::border::{prepare, Point};
    use crate::geometry::{Point2, Vector2};
    use crate::{analyze, FrameRange};
    use std::f64::consts::PI;

    /// A square of `4·per_side` vertices, side 1.
    fn square(per_side: usize) -> Vec<Point> {
        (0..4 * per_side)
            .map(|k| {
                let t = (k % per_side) as f64 / per_side as f64;
                let (x, y) = [(t, 0.0), (1.0, t), (1.0 - t, 1.0), (0.0, 1.0 - t)][k / per_side];
                Point::new(x, y, 0.0)
            })
            .collect()
    }

    /// The analysis of the square folded exactly along `folds` (border parameters), each
    /// along the line through its points, the folded layer lifted.
    fn observed(sq: &[Point], folds: &[[f64; 2]]) -> Analysis {
        observed_along(sq, folds, &[])
    }

    /// [`observed`], fold k along `lines[k]` where given.
    fn observed_along(sq: &[Point], folds: &[[f64; 2]], lines: &[Option<Line>]) -> Analysis {
        let n = sq.len();
        let xyz = |s: &[Point]| s.iter().map(|p| [p.x, p.y, p.z]).collect::<Vec<_>>();
        let mut frames = vec![xyz(sq)];
        let mut state = sq.to_vec();
        for (k, f) in folds.iter().enumerate() {
            let fold = f.map(|s| param_to_angle(s, n));
            let next = crate::distance::fold_state(
                &state,
                &[fold],
                &[lines.get(k).copied().flatten().map_or(LineOf::Points, LineOf::Given)],
            )
            .unwrap();
            state = next
                .iter()
                .zip(&state)
                .map(|(p, q)| if p == q { *p } else { Point::new(p.x, p.y, 0.01 * (k + 1) as f64) })
                .collect();
            frames.push(xyz(&state));
        }
        analyze(&prepare(frames).unwrap(), FrameRange::default()).unwrap()
    }

    fn goal(n: usize, folds: &[[f64; 2]]) -> Goal {
        Goal::folds(folds.iter().map(|f| f.map(|s| param_to_angle(s, n))))
    }

    #[test]
    fn an_exact_fold_reaches_its_goal() {
        let sq = square(10);
        for fold in [[5.0, 25.0], [0.0, 20.0], [5.0, 15.0], [32.0, 8.0]] {
            let answer =
                verify(&observed(&sq, &[fold]), &goal(40, &[fold]), Tolerance::default()).unwrap();
            assert!(answer.reached, "{fold:?}: {}", answer.text);
            assert!(answer.text.starts_with("goal reached"), "{}", answer.text);
            let f = &answer.folds[0];
            assert_eq!((f.status, f.observed), (Status::Found, Some(0)));
            assert!(f.error_edges.unwrap().iter().all(|e| e.abs() < 0.3), "{f:?}");
            assert!(
                answer.distance.folds < 0.3 / 40.0 * 2.0
                    && answer.distance.geometric.unwrap() < 0.01
            );
            assert!(answer.extra.is_empty());
        }
    }

    #[test]
    fn a_short_fold_is_told_with_its_grasp() {
        let sq = square(10);
        // Made: the right side folded from vertex 8 to 22 (x = 0.8 … 0.8); wanted: x = 0.5.
        let answer =
            verify(&observed(&sq, &[[8.0, 22.0]]), &goal(40, &[[5.0, 25.0]]), Tolerance::default())
                .unwrap();
        assert!(!answer.reached);
        let f = &answer.folds[0];
        assert_eq!(f.status, Status::Misplaced);
        let [e1, e2] = f.error_edges.unwrap();
        assert!((e1 - 3.0).abs() < 0.3 && (e2 + 3.0).abs() < 0.3, "{e1} {e2}");
        assert!((f.error_percent.unwrap()[0] - 7.5).abs() < 0.8);
        assert!((f.short_edges.unwrap() - 6.0).abs() < 0.5, "{f:?}");
        assert!(
            answer.text.starts_with("fold 1 is 6.0 edges short: grasp vertex"),
            "{}",
            answer.text
        );
        // The plan grasps the folded corners where they lie and puts them at x = 0.
        let plan = answer.plan.unwrap();
        assert_eq!(plan.steps[0].picks.len(), 2);
        // Moving a fold point by an edge costs 1/N: 6 edges of points.
        assert!((answer.distance.folds - 6.0 / 40.0).abs() < 0.02, "{}", answer.distance.folds);
    }

    #[test]
    fn a_missing_and_an_extra_fold_are_named() {
        let sq = square(10);
        // Made: half, then a corner of the stack; wanted: the half alone.
        let made = observed(&sq, &[[5.0, 25.0], [2.0, 36.0]]);
        assert_eq!(made.folds.len(), 2, "the test needs two observed folds: {:?}", made.folds);
        let answer = verify(&made, &goal(40, &[[5.0, 25.0]]), Tolerance::default()).unwrap();
        assert!(!answer.reached);
        assert_eq!(answer.folds[0].status, Status::Found);
        assert_eq!(answer.extra.len(), 1);
        assert_eq!(answer.extra[0].observed, 1);
        assert!(answer.text.contains("an extra fold"), "{}", answer.text);
        // Wanted: half and a quarter; made: the half alone.
        let half = observed(&sq, &[[5.0, 25.0]]);
        let answer =
            verify(&half, &goal(40, &[[5.0, 25.0], [15.0, 35.0]]), Tolerance::default()).unwrap();
        assert_eq!(answer.folds[1].status, Status::Missing);
        assert!(answer.text.starts_with("fold 2 is missing"), "{}", answer.text);
        assert!((answer.distance.folds - 0.5).abs() < 0.02, "{:?}", answer.distance);
        // The plan makes the missing fold on the state the half left.
        let plan = answer.plan.expect("a plan");
        assert_eq!((plan.case, plan.steps.len()), (crate::plan::Case::Fold, 1));
    }

    #[test]
    fn the_other_side_folded_is_not_the_goal() {
        let sq = square(10);
        let answer =
            verify(&observed(&sq, &[[5.0, 25.0]]), &goal(40, &[[25.0, 5.0]]), Tolerance::default())
                .unwrap();
        assert!(!answer.reached && answer.folds[0].other_side);
        assert!(answer.text.starts_with("fold 1 folds the other side over"), "{}", answer.text);
    }

    #[test]
    fn the_flat_cloth_against_a_goal_plans_the_fold() {
        let sq = square(10);
        let answer =
            verify(&observed(&sq, &[]), &goal(40, &[[0.0, 20.0]]), Tolerance::default()).unwrap();
        assert!(!answer.reached);
        assert!(answer.text.starts_with("fold 1 is missing: grasp vertex 10 at (1.000, 0.000, 0.000) and place it at (0.000, 1.000, 0.000)"), "{}", answer.text);
        assert!((answer.distance.folds - 0.5).abs() < 1e-12);
        // And the flat cloth is its own empty goal.
        let flat = verify(&observed(&sq, &[]), &Goal::default(), Tolerance::default()).unwrap();
        assert!(flat.reached && flat.distance.folds == 0.0, "{}", flat.text);
    }

    #[test]
    fn the_tolerance_decides() {
        let sq = square(10);
        let made = observed(&sq, &[[6.0, 24.0]]);
        let wanted = goal(40, &[[5.0, 25.0]]);
        assert!(
            verify(&made, &wanted, Tolerance::default()).unwrap().folds[0].status == Status::Found
        );
        let strict = Tolerance { edges: 0.5, ..Tolerance::default() };
        assert!(!verify(&made, &wanted, strict).unwrap().reached);
        let shape_only = Tolerance { aligned_rmse: 1e-4, ..Tolerance::default() };
        let answer = verify(&made, &wanted, shape_only).unwrap();
        assert!(
            !answer.reached
                && answer.text.contains("every fold is within tolerance but the shapes"),
            "{}",
            answer.text
        );
    }

    #[test]
    fn a_stacked_goal_fold_borrows_the_observed_line() {
        let sq = square(10);
        let quarters = [[5.0, 25.0], [15.0, 35.0]];
        // The second fold's points (the middles of the right and left sides) meet at
        // (0, 0.5) after the first: it is made along y = 0.5.
        let line = Line { point: Point2::new(0.0, 0.5), direction: Vector2::new(1.0, 0.0) };
        let made = observed_along(&sq, &quarters, &[None, Some(line)]);
        assert_eq!(made.folds.len(), 2, "{:?}", made.folds);
        let answer = verify(&made, &goal(40, &quarters), Tolerance::default()).unwrap();
        assert!(answer.reached, "{}", answer.text);
        assert!(answer.distance.geometric.unwrap() < 0.03);
    }

    #[test]
    fn bad_goals_and_tolerances_are_named() {
        let made = observed(&square(10), &[[5.0, 25.0]]);
        let message = |g: Goal, t: Tolerance| verify(&made, &g, t).unwrap_err().to_string();
        let ok = Tolerance::default();
        assert!(message(Goal::folds(vec![[f64::NAN, 1.0]]), ok).contains("not finite"));
        assert!(message(Goal::folds(vec![[1.0, 1.05]]), ok).contains("more than"));
        assert!(message(Goal::folds(vec![[0.0, PI]; 65]), ok).contains("too large"));
        let bad = Tolerance { edges: -1.0, ..ok };
        assert!(message(Goal::folds(vec![[0.0, PI]]), bad).contains("tolerance edges"));
        let lines = Goal { folds: vec![[0.0, PI]], lines: vec![None, None] };
        assert!(message(lines, ok).contains("2 lines for 1 folds"));
        let flat = Line { point: Point2::new(0.0, 0.0), direction: Vector2::new(0.0, 0.0) };
        let lines = Goal { folds: vec![[0.0, PI]], lines: vec![Some(flat)] };
        assert!(message(lines, ok).contains("non-zero direction"));
    }
}
