//! Planning a fold (Kamat, Borràs, Torras, "CloSE", Sec. V, manipulation planning with the
//! representation): which corners to grasp and where to put them.
//!
//! **High level.** The goal is a sequence of folds (g1, g2), made in order, each on the state
//! the ones before it left. The corners a fold moves are the corners strictly inside its
//! folded arc (anticlockwise from f1 to f2), more than half an edge from its ends
//! ([`crate::geometry::Arc::folds_vertex`]). When the cloth already is in the goal state
//! (its folds, in order, each within [`SAME_FOLD_EDGES`] of the goal's at both ends) the
//! plan is `"already_there"`, with no step. When its folds are the goal's first ones (a flat
//! cloth has none), the goal's other folds are made in order (`"fold"`). If a goal of one
//! fold moves the same corners as the current folds together, one step moves them straight
//! to the goal (`"direct"`); otherwise the current folds are undone, last first, and the
//! goal is folded from the flat cloth (`"unfold_then_fold"`; a goal of no fold, the flat
//! cloth, is the unfolding alone). Goal angles are taken into
//! [0, 2π) before anything else, and come back that way.
//!
//! **Low level.** A step grasps at most two of the corners it moves: of more, the pair
//! whose quadrilateral with the fold-line end points (P1, c_a, c_b, P2, ordered so that it
//! is simple) has the largest XY area. A folded corner goes to its reflection across the
//! fold line (in XY, z kept); an unfolded one back to where it was. A folded side with no
//! corner (a round cloth, a flap) is grasped at its vertex farthest from the fold line:
//! such a pick names no corner, only the border point (its `angle`, 2πv/N). Two moved
//! corners lying on top of each other (a flap folded before) are one place to hold: the
//! other grasp takes the folded vertex farthest from them along the line, so the two hold
//! the flap's edge at both ends (the second fold of a napkin in quarters).
//!
//! All positions are in the flat border's frame: a fold line runs through the border
//! points at its parameters (angle f ↦ parameter fN/2π) of the border it is applied to.
//!
//! ```
//! use close_core::border::Point;
//! use close_core::geometry::Fold;
//! use close_core::plan::plan;
//! use std::f64::consts::PI;
//! let square = [Point::new(0.0, 0.0, 0.0), Point::new(1.0, 0.0, 0.0), Point::new(1.0, 1.0, 0.0), Point::new(0.0, 1.0, 0.0)];
//! // Diagonal fold from corner 1 (vertex 0) to corner 3 (vertex 2): corner 2 goes onto corner 4.
//! let p = plan(&square, &[0, 1, 2, 3], &[], &[Fold::new(0.0, PI)]).unwrap();
//! assert_eq!(p.case, close_core::plan::Case::Fold);
//! assert_eq!(p.steps[0].corners, vec![2]);
//! let to = p.steps[0].picks[0].to;
//! assert!(to[0].abs() < 1e-12 && (to[1] - 1.0).abs() < 1e-12 && to[2] == 0.0);
//! ```

use std::collections::BTreeSet;

use serde::{Deserialize, Serialize};

use crate::analysis::Analysis;
use crate::angle::{angle_to_param, distance, edge, param_to_angle, ON_LINE_EDGES};
use crate::border::{point_at, to_xyz, Point};
use crate::error::{Error, Result};
use crate::fold::apply;
use crate::fold::state::mean_edge;
use crate::geometry::{Arc, Fold, Folding, Line};

/// One grasp: take border vertex `vertex` at `from` and place it at `to`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Pick {
    /// Border vertex index ([`plan_for`] maps it to the input's index through
    /// `border_indices`).
    pub vertex: usize,
    /// Where the grasped point sits on the border, as an angle: 2πv/N, border order
    /// (radians).
    pub angle: f64,
    pub from: [f64; 3],
    pub to: [f64; 3],
}

/// What a step does with its fold.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum Action {
    /// `"fold"`: fold along it.
    Fold,
    /// `"unfold"`: take it back.
    Unfold,
}

/// How the plan reaches the goal (see the module's doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum Case {
    /// `"fold"`: the goal's folds the cloth does not hold yet, made in order (from a flat
    /// cloth, all of them).
    Fold,
    /// `"direct"`: the goal moves the corners the current folds moved; one step.
    Direct,
    /// `"unfold_then_fold"`: the current folds undone, last first, then the goal folded.
    UnfoldThenFold,
    /// `"already_there"`: the cloth is in the goal state; no step.
    AlreadyThere,
}

impl Action {
    /// The name it is serialised as.
    pub fn as_str(self) -> &'static str {
        match self {
            Action::Fold => "fold",
            Action::Unfold => "unfold",
        }
    }
}

impl Case {
    /// The name it is serialised as.
    pub fn as_str(self) -> &'static str {
        match self {
            Case::Fold => "fold",
            Case::Direct => "direct",
            Case::UnfoldThenFold => "unfold_then_fold",
            Case::AlreadyThere => "already_there",
        }
    }
}

/// One manipulation: fold along `fold`, or undo it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct PlanStep {
    pub action: Action,
    /// The fold (f1, f2) in [0, 2π) (radians).
    pub fold: Fold,
    /// 1-based numbers of every corner the step moves (corner k is the k-th corner in
    /// border order, `corners[k - 1]` of the analysis).
    pub corners: Vec<usize>,
    /// Their vertex indices (0-based), in the same order: border vertices, which
    /// [`plan_for`] maps to the input's indices as it maps each pick's `vertex`.
    pub corner_vertices: Vec<usize>,
    /// At most two grasps.
    pub picks: Vec<Pick>,
    /// The line the step folds along (or unfolds), on the state it starts from; `None`
    /// where the fold's two points coincide there.
    pub line: Option<Line>,
}

/// The plan from the current state to the goal folds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Plan {
    pub case: Case,
    pub steps: Vec<PlanStep>,
}

impl Plan {
    /// The plan as `close plan` prints it without `--json`: the case, then one line per
    /// step (its fold, the 1-based corners it moves) and one per grasp (vertex, from → to).
    pub fn text(&self) -> String {
        let mut text = self.case.as_str().to_string();
        let xyz = |v: [f64; 3]| format!("({:.4}, {:.4}, {:.4})", v[0], v[1], v[2]);
        for (k, step) in self.steps.iter().enumerate() {
            text += &format!(
                "\n{}. {} ({:.4}, {:.4}), corners {:?}",
                k + 1,
                step.action.as_str(),
                step.fold.f1,
                step.fold.f2,
                step.corners
            );
            for p in &step.picks {
                text += &format!("\n   vertex {}: {} -> {}", p.vertex, xyz(p.from), xyz(p.to));
            }
        }
        text
    }
}

/// A current fold within this many edges of the goal at both ends is the goal.
pub const SAME_FOLD_EDGES: f64 = 0.5;

/// Border parameter of angle `f` on a border of `n` vertices.
fn param(f: f64, n: usize) -> f64 {
    angle_to_param(f, n)
}

/// Twice the signed XY area of a polygon (shoelace).
fn twice_area(polygon: &[Point]) -> f64 {
    let n = polygon.len();
    (0..n)
        .map(|k| polygon[k].x * polygon[(k + 1) % n].y - polygon[(k + 1) % n].x * polygon[k].y)
        .sum()
}

/// Whether XY segments ab and cd cross at a point inside both.
fn segments_cross(a: &Point, b: &Point, c: &Point, d: &Point) -> bool {
    let side =
        |p: &Point, q: &Point, r: &Point| (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x);
    side(a, b, c) * side(a, b, d) < 0.0 && side(c, d, a) * side(c, d, b) < 0.0
}

/// XY area of the simple quadrilateral through P1, the two corners and P2.
fn trapezoid_area(p1: &Point, a: &Point, b: &Point, p2: &Point) -> f64 {
    // P1→a→b→P2 is a bow tie when P1a crosses bP2 (or ab crosses P2P1): swap the corners.
    let bow_tie = segments_cross(p1, a, b, p2) || segments_cross(a, b, p2, p1);
    let quad = if bow_tie { [*p1, *b, *a, *p2] } else { [*p1, *a, *b, *p2] };
    twice_area(&quad).abs() / 2.0
}

/// The vertices a step grasps among `moved` (the corners it moves, or the whole folded arc
/// when that holds no corner), folding `border` along `line`, the line through `p1`, `p2`
/// unless those lie stacked. Two corners lying on top of each other (a flap folded before)
/// are one place to hold: the other grasp goes to the folded vertex farthest from them along
/// the line, so the two hold the flap's edge at both ends.
fn grasped(
    border: &[Point],
    moved: &[usize],
    arc: &[usize],
    (p1, p2): (&Point, &Point),
    line: Option<&Line>,
) -> Vec<usize> {
    let chosen = corners_grasped(border, moved, arc, p1, p2);
    let mean_edge = mean_edge(border);
    match (chosen.as_slice(), line) {
        (&[a, b], Some(line)) if (border[a] - border[b]).xy().norm() <= mean_edge => {
            let along = |v: usize| ((border[v] - border[a]).xy().dot(&line.direction)).abs();
            let far = arc.iter().copied().max_by(|&u, &v| along(u).total_cmp(&along(v)));
            match far {
                Some(v) if along(v) > mean_edge => vec![a, v],
                _ => vec![a],
            }
        }
        _ => chosen,
    }
}

/// The corners a step grasps among `moved` (see [`grasped`]).
fn corners_grasped(
    border: &[Point],
    moved: &[usize],
    arc: &[usize],
    p1: &Point,
    p2: &Point,
) -> Vec<usize> {
    match moved {
        [] => {
            // No corner: the farthest vertex from the line (ties go to the earlier vertex).
            let line = Line::through(p1, p2);
            let reflect = |p: &Point| line.map_or(*p, |l| l.reflect(p));
            let distance = |v: usize| (reflect(&border[v]) - border[v]).norm();
            let far = arc.iter().copied().fold(None, |best: Option<usize>, v| match best {
                Some(b) if distance(b) >= distance(v) => Some(b),
                _ => Some(v),
            });
            far.into_iter().collect()
        }
        [_] | [_, _] => moved.to_vec(),
        _ => {
            let mut best = (f64::NEG_INFINITY, 0, 0);
            for (i, &a) in moved.iter().enumerate() {
                for &b in &moved[i + 1..] {
                    let area = trapezoid_area(p1, &border[a], &border[b], p2);
                    if area > best.0 {
                        best = (area, a, b);
                    }
                }
            }
            vec![best.1, best.2]
        }
    }
}

/// Corners strictly inside the folded `arc`, off the line ([`Arc::folds_vertex`], as in
/// [`crate::label`]), as vertex indices.
fn corners_moved(n: usize, corners: &[usize], arc: Arc) -> Vec<usize> {
    corners.iter().copied().filter(|&c| arc.folds_vertex(n, c, ON_LINE_EDGES)).collect()
}

/// A step that makes `folding` on `before` (or, `unfold`, takes the folded state back):
/// its arcs turn over its line ([`Folding::line_on`]); `from_state` gives where a grasped
/// vertex is now when the step starts a fold.
fn step(
    action: Action,
    before: &[Point],
    corners: &[usize],
    folding: &Folding,
    from_state: &[Point],
) -> PlanStep {
    let (n, fold) = (before.len(), folding.fold);
    let (p1, p2) = (point_at(before, param(fold.f1, n)), point_at(before, param(fold.f2, n)));
    let line = folding.line_on(before);
    let reflect = |p: &Point| line.as_ref().map_or(*p, |l| l.reflect(p));
    let arc: Vec<usize> = folding.arcs.iter().flat_map(|a| a.folded_vertices(n)).collect();
    let moved: Vec<usize> =
        folding.arcs.iter().flat_map(|&a| corners_moved(n, corners, a)).collect();
    let picks = grasped(before, &moved, &arc, (&p1, &p2), line.as_ref())
        .into_iter()
        .map(|v| {
            let folded = reflect(&before[v]);
            let (from, to) = if action == Action::Unfold {
                (folded, before[v])
            } else {
                (from_state[v], folded)
            };
            Pick {
                vertex: v,
                angle: param_to_angle(v as f64, n),
                from: to_xyz(&from),
                to: to_xyz(&to),
            }
        })
        .collect();
    let number = |c: usize| corners.iter().position(|&k| k == c).map_or(0, |i| i + 1);
    PlanStep {
        action,
        fold,
        corners: moved.iter().map(|&c| number(c)).collect(),
        corner_vertices: moved,
        picks,
        line,
    }
}

fn check_fold(name: &str, fold: Fold, n: usize) -> Result<()> {
    if !fold.is_finite() {
        return Err(Error::InvalidArgument(format!(
            "{name} ({}, {}) is not finite",
            fold.f1, fold.f2
        )));
    }
    let edge = edge(n);
    if distance(fold.f1, fold.f2) <= edge {
        return Err(Error::InvalidArgument(format!(
            "{name} ({:.4}, {:.4}): its two angles must be more than one edge ({edge:.4} rad) apart",
            fold.f1, fold.f2
        )));
    }
    Ok(())
}

/// Plan from the current state (the flat border, its corner vertices, the folds made so far
/// in order) to the goal folds (g1, g2) in order, all folds in angles. Each fold turns its
/// arcs (a fold without any turns its own arc) over its line, by default the line through
/// its two fold points of the state before it ([`Folding::line_on`]): a fold through two
/// stacked layers has its two fold points (nearly) on top of each other, so the line
/// through them is no guide, and an analysis gives its line.
pub fn plan(
    flat: &[Point],
    corner_vertices: &[usize],
    current_folds: &[Folding],
    goal: &[Fold],
) -> Result<Plan> {
    let n = flat.len();
    if n < crate::border::MIN_VERTICES {
        return Err(Error::TooFewVertices { got: n, min: crate::border::MIN_VERTICES });
    }
    if let Some(v) = flat.iter().position(|p| !p.coords.iter().all(|c| c.is_finite())) {
        return Err(Error::NonFinite { frame: 0, vertex: v });
    }
    if let Some(&c) = corner_vertices.iter().find(|&&c| c >= n) {
        return Err(Error::InvalidArgument(format!(
            "corner vertex {c} does not exist (the border has {n} vertices)"
        )));
    }
    for (k, &g) in goal.iter().enumerate() {
        check_fold(&format!("goal fold {}", k + 1), g, n)?;
    }
    let goal: Vec<Fold> = goal.iter().map(|g| g.wrapped()).collect();
    for (k, f) in current_folds.iter().enumerate() {
        check_fold(&format!("current fold {}", k + 1), f.fold, n)?;
    }
    let current_folds: Vec<Folding> = current_folds
        .iter()
        .map(|f| match f.arcs.is_empty() {
            true => Folding { arcs: vec![f.fold.arc()], ..f.clone() },
            false => f.clone(),
        })
        .collect();
    let corners: Vec<usize> =
        corner_vertices.iter().copied().collect::<BTreeSet<_>>().into_iter().collect();
    // The line of each current fold, and states[k], the border after the first k folds.
    let (states, made) = made_in_turn(flat, current_folds.clone());
    let current = states.last().expect("the flat state");
    let same = |a: Fold, b: Fold| {
        let close = |x: f64, y: f64| distance(x, y) <= SAME_FOLD_EDGES * edge(n);
        close(a.f1, b.f1) && close(a.f2, b.f2)
    };
    let held = current_folds.len();
    if held <= goal.len() && current_folds.iter().zip(&goal).all(|(c, &g)| same(c.fold, g)) {
        if held == goal.len() {
            return Ok(Plan { case: Case::AlreadyThere, steps: Vec::new() });
        }
        // The goal's first folds are made: the others follow, on the state they leave.
        let steps = fold_in_turn(flat, &states[held], &corners, &goal[held..]);
        return Ok(Plan { case: Case::Fold, steps });
    }
    if let [only] = goal[..] {
        let folded_now: BTreeSet<usize> = current_folds
            .iter()
            .flat_map(|f| {
                f.arcs.iter().flat_map(|&a| corners_moved(n, &corners, a)).collect::<Vec<_>>()
            })
            .collect();
        let folded_by_goal: BTreeSet<usize> =
            corners_moved(n, &corners, only.arc()).into_iter().collect();
        if folded_now == folded_by_goal {
            return Ok(Plan {
                case: Case::Direct,
                steps: vec![step(Action::Fold, flat, &corners, &Folding::new(only), current)],
            });
        }
    }
    let mut steps: Vec<PlanStep> = (0..made.len())
        .rev()
        .map(|k| step(Action::Unfold, &states[k], &corners, &made[k], &states[k]))
        .collect();
    steps.extend(fold_in_turn(flat, flat, &corners, &goal));
    Ok(Plan { case: Case::UnfoldThenFold, steps })
}

/// `folds` made in turn on `flat`, each along its line on the state before it: the states
/// (flat first) and the folds with their lines.
fn made_in_turn(flat: &[Point], folds: Vec<Folding>) -> (Vec<Vec<Point>>, Vec<Folding>) {
    let mut states = vec![flat.to_vec()];
    let mut made = Vec::with_capacity(folds.len());
    for f in folds {
        let before = states.last().expect("the flat state");
        let along = Folding { line: f.line_on(before), ..f };
        states.push(apply(before, &along));
        made.push(along);
    }
    (states, made)
}

/// The steps that make `goal` in order from `state`, each fold on the state the ones
/// before it left, along [`goal_line`].
fn fold_in_turn(
    flat: &[Point],
    state: &[Point],
    corners: &[usize],
    goal: &[Fold],
) -> Vec<PlanStep> {
    let mut before = state.to_vec();
    goal.iter()
        .map(|&g| {
            let folding = Folding { line: goal_line(flat, &before, g), ..Folding::new(g) };
            let made = step(Action::Fold, &before, corners, &folding, &before);
            before = apply(&before, &folding);
            made
        })
        .collect()
}

/// The line a goal fold is made along on `state`: through its two points there; where they
/// lie stacked (within a mean edge: the fold crosses layers folded before it, as the second
/// fold of a napkin folded in quarters does at the first crease), through them on the flat
/// cloth, the table's frame, which the bottom layer keeps.
fn goal_line(flat: &[Point], state: &[Point], goal: Fold) -> Option<Line> {
    let n = flat.len();
    let ends = |border: &[Point]| [goal.f1, goal.f2].map(|f| point_at(border, param(f, n)));
    let [a, b] = ends(state);
    if (a - b).xy().norm() > mean_edge(flat) {
        Line::through(&a, &b)
    } else {
        let [a, b] = ends(flat);
        Line::through(&a, &b)
    }
}

/// Plan from an analysis to the goal folds: from its start border, corners and folds (each
/// along the line the analysis reports for it, so the plan starts from its predicted end), with
/// every pick's `vertex` and every step's `corner_vertices` given as indices in the
/// analysis's INPUT (through `border_indices`: the input vertex for a border, the mesh
/// vertex for a mesh).
pub fn plan_for(analysis: &Analysis, goal: &[Fold]) -> Result<Plan> {
    // Each fold along the line the analysis made it along (its `predicted_end`).
    let mut plan =
        plan(analysis.start_border(), &analysis.corner_vertices, &analysis.foldings(), goal)?;
    let input = |v: usize| {
        analysis.border_indices.get(v).copied().ok_or_else(|| {
            Error::InvalidArgument(format!(
                "border vertex {v} has no input index ({} known)",
                analysis.border_indices.len()
            ))
        })
    };
    for step in &mut plan.steps {
        for pick in &mut step.picks {
            pick.vertex = input(pick.vertex)?;
        }
        for v in &mut step.corner_vertices {
            *v = input(*v)?;
        }
    }
    Ok(plan)
}

/// `POST /api/plan`'s answer (and Python's `close.plan`): the plan, and the state it starts from.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Answer {
    pub case: Case,
    pub steps: Vec<PlanStep>,
    /// The goal folds in order, in [0, 2π) (radians), as the plan's steps.
    pub goal: Vec<Fold>,
    /// The start state's folds, in order, in [0, 2π) (radians).
    pub folds: Vec<Fold>,
    /// The line each current fold was made along (as the analysis's `steps[k].line`).
    pub lines: Vec<Option<Line>>,
    /// The start state's corner angles, 2πv/N for corner vertex v (radians, increasing).
    pub corners: Vec<f64>,
    pub start_border: Vec<[f64; 3]>,
    pub border_indices: Vec<usize>,
}

/// [`plan_for`] with the analysed state it starts from: the answer of `POST /api/plan`.
pub fn answer(analysis: &Analysis, goal: &[Fold]) -> Result<Answer> {
    let plan = plan_for(analysis, goal)?;
    Ok(Answer {
        case: plan.case,
        steps: plan.steps,
        goal: goal.iter().map(|g| g.wrapped()).collect(),
        folds: analysis.folds.clone(),
        lines: analysis.foldings().iter().map(|f| f.line).collect(),
        corners: analysis.corners.clone(),
        start_border: analysis.start_border().iter().map(to_xyz).collect(),
        border_indices: analysis.border_indices.clone(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{PI, TAU};

    /// A closed polygon with `per_side` segments on every side.
    fn polygon(corners: &[[f64; 2]], per_side: usize) -> (Vec<Point>, Vec<usize>) {
        let m = corners.len();
        let points = (0..m * per_side)
            .map(|k| {
                let (a, b, t) = (
                    corners[k / per_side],
                    corners[(k / per_side + 1) % m],
                    (k % per_side) as f64 / per_side as f64,
                );
                Point::new(a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), 0.0)
            })
            .collect();
        (points, (0..m).map(|c| c * per_side).collect())
    }

    /// [`plan`] of ordinary folds given as pairs.
    fn plan_folds(
        flat: &[Point],
        corners: &[usize],
        current: &[[f64; 2]],
        goal: [f64; 2],
    ) -> Result<Plan> {
        let current: Vec<Folding> = current.iter().map(|&f| Folding::new(f.into())).collect();
        plan(flat, corners, &current, &[goal.into()])
    }

    fn angle(s: f64, n: usize) -> f64 {
        param_to_angle(s, n)
    }

    /// Angles are fractions of 2π, so positions come back to within rounding.
    fn assert_pick(pick: &Pick, vertex: usize, from: [f64; 2], to: [f64; 2]) {
        let near = |a: [f64; 3], b: [f64; 2]| {
            (a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12 && a[2] == 0.0
        };
        assert!(
            pick.vertex == vertex && near(pick.from, from) && near(pick.to, to),
            "{pick:?}: expected vertex {vertex} {from:?} → {to:?}"
        );
    }

    fn square() -> (Vec<Point>, Vec<usize>) {
        polygon(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]], 4)
    }

    #[test]
    fn diagonal_goal_puts_the_one_corner_on_the_opposite_corner() {
        let (sq, corners) = square();
        let p = plan_folds(&sq, &corners, &[], [angle(0.0, 16), angle(8.0, 16)]).unwrap();
        assert_eq!(p.case, Case::Fold);
        assert_eq!(p.steps.len(), 1);
        let s = &p.steps[0];
        assert_eq!((s.action, s.corners.clone()), (Action::Fold, vec![2]));
        assert_eq!(s.picks.len(), 1);
        assert_pick(&s.picks[0], 4, [1.0, 0.0], [0.0, 1.0]);
    }

    #[test]
    fn half_fold_picks_both_corners() {
        let (sq, corners) = square();
        // Line x = 0.5 from the bottom middle (2) to the top middle (10): right half folded.
        let p = plan_folds(&sq, &corners, &[], [angle(2.0, 16), angle(10.0, 16)]).unwrap();
        let s = &p.steps[0];
        assert_eq!(s.corners, vec![2, 3]);
        assert_eq!(s.corner_vertices, vec![4, 8]);
        assert_eq!(s.picks.len(), 2);
        assert_pick(&s.picks[0], 4, [1.0, 0.0], [0.0, 0.0]);
        assert_pick(&s.picks[1], 8, [1.0, 1.0], [0.0, 1.0]);
        assert_eq!(
            p.text(),
            "fold\n1. fold (0.7854, 3.9270), corners [2, 3]\n   \
             vertex 4: (1.0000, 0.0000, 0.0000) -> (0.0000, 0.0000, 0.0000)\n   \
             vertex 8: (1.0000, 1.0000, 0.0000) -> (0.0000, 1.0000, 0.0000)"
        );
    }

    #[test]
    fn a_plan_of_a_clockwise_input_names_the_inputs_vertices() {
        // A square of 40 vertices with its right half folded onto the left, given
        // anticlockwise and then clockwise (vertex 0 first, then the others in the reverse
        // order: the same border once walked anticlockwise).
        let flat: Vec<[f64; 3]> = (0..40)
            .map(|k| {
                let t = (k % 10) as f64 / 10.0;
                let [x, y] = [[t, 0.0], [1.0, t], [1.0 - t, 1.0], [0.0, 1.0 - t]][k / 10];
                [x, y, 0.0]
            })
            .collect();
        let fold = |p: &[f64; 3]| if p[0] > 0.5 { [1.0 - p[0], p[1], 0.01] } else { *p };
        let folded: Vec<[f64; 3]> = flat.iter().map(fold).collect();
        let reversed = |f: &[[f64; 3]]| (0..40).map(|i| f[(40 - i) % 40]).collect::<Vec<_>>();
        let goal = [0.0, PI];
        let plan_of = |frames: Vec<Vec<[f64; 3]>>| {
            let frames = crate::border::prepare(frames).unwrap();
            plan_for(
                &crate::analysis::analyze(&frames, Default::default()).unwrap(),
                &[goal.into()],
            )
            .unwrap()
        };
        let ccw = plan_of(vec![flat.clone(), folded.clone()]);
        let cw = plan_of(vec![reversed(&flat), reversed(&folded)]);
        assert!(!ccw.steps.is_empty() && ccw.steps.len() == cw.steps.len());
        for (a, b) in ccw.steps.iter().zip(&cw.steps) {
            // Input vertex v of the anticlockwise list is vertex 40 − v of the clockwise one.
            let mut mirrored: Vec<usize> =
                a.corner_vertices.iter().map(|v| (40 - v) % 40).collect();
            let mut got = b.corner_vertices.clone();
            mirrored.sort_unstable();
            got.sort_unstable();
            assert!(!got.is_empty());
            assert_eq!(got, mirrored);
            assert_eq!(a.corners.len(), a.corner_vertices.len());
            for pick in &b.picks {
                assert!(b.corner_vertices.contains(&pick.vertex), "{pick:?} of {b:?}");
            }
        }
    }

    #[test]
    fn same_corners_go_direct_from_where_they_are() {
        let (sq, corners) = square();
        let current = [angle(2.0, 16), angle(10.0, 16)];
        // A slightly askew fold of the same right side moves corners 2 and 3 again.
        let p = plan_folds(&sq, &corners, &[current], [angle(3.0, 16), angle(9.0, 16)]).unwrap();
        assert_eq!(p.case, Case::Direct);
        assert_eq!(p.steps.len(), 1);
        let s = &p.steps[0];
        assert_eq!(s.corners, vec![2, 3]);
        // Grasped where the current fold put them (on the left side), placed by the new line x = 0.75.
        assert_pick(&s.picks[0], 4, [0.0, 0.0], [0.5, 0.0]);
        assert_pick(&s.picks[1], 8, [0.0, 1.0], [0.5, 1.0]);
    }

    #[test]
    fn other_corners_unfold_first() {
        let (sq, corners) = square();
        let current = [angle(2.0, 16), angle(10.0, 16)];
        // Top half instead: corners 3 and 4.
        let p = plan_folds(&sq, &corners, &[current], [angle(6.0, 16), angle(14.0, 16)]).unwrap();
        assert_eq!(p.case, Case::UnfoldThenFold);
        let actions: Vec<Action> = p.steps.iter().map(|s| s.action).collect();
        assert_eq!(actions, [Action::Unfold, Action::Fold]);
        let (unfold, fold) = (&p.steps[0], &p.steps[1]);
        assert_eq!((unfold.fold, unfold.corners.clone()), (current.into(), vec![2, 3]));
        assert_pick(&unfold.picks[0], 4, [0.0, 0.0], [1.0, 0.0]);
        assert_pick(&unfold.picks[1], 8, [0.0, 1.0], [1.0, 1.0]);
        assert_eq!(fold.corners, vec![3, 4]);
        assert_pick(&fold.picks[0], 8, [1.0, 1.0], [1.0, 0.0]);
        assert_pick(&fold.picks[1], 12, [0.0, 1.0], [0.0, 0.0]);
    }

    #[test]
    fn a_fold_ending_a_hair_past_a_corner_does_not_fold_it() {
        let (sq, corners) = square();
        // A detected diagonal fold just short of 2π and just past π: still corner 2 alone.
        let detected = [TAU - 1e-9, PI + 1e-9];
        let p = plan_folds(&sq, &corners, &[detected], [angle(1.0, 16), angle(7.0, 16)]).unwrap();
        assert_eq!(p.case, Case::Direct);
        assert_eq!(p.steps[0].corners, vec![2]);
        let pick = &p.steps[0].picks[0];
        assert_eq!(pick.vertex, 4);
        // Grasped where the detected fold put it (a nanometre off the opposite corner).
        assert!((pick.from[0] - 0.0).abs() < 1e-8 && (pick.from[1] - 1.0).abs() < 1e-8, "{pick:?}");
    }

    #[test]
    fn two_folds_unfold_last_first() {
        let (sq, corners) = square();
        // Right quarter over (x = 0.75), then the stack's bottom half up (y = 0.5).
        let current = [[angle(3.0, 16), angle(9.0, 16)], [angle(14.0, 16), angle(6.0, 16)]];
        let p = plan_folds(&sq, &corners, &current, [angle(0.0, 16), angle(8.0, 16)]).unwrap();
        assert_eq!(p.case, Case::UnfoldThenFold);
        let summary: Vec<(Action, [f64; 2], Vec<usize>)> =
            p.steps.iter().map(|s| (s.action, s.fold.into(), s.corners.clone())).collect();
        assert_eq!(
            summary,
            vec![
                (Action::Unfold, current[1], vec![1, 2]),
                (Action::Unfold, current[0], vec![2, 3]),
                (Action::Fold, [0.0, PI], vec![2])
            ]
        );
        assert_pick(&p.steps[0].picks[0], 0, [0.0, 1.0], [0.0, 0.0]);
        assert_pick(&p.steps[0].picks[1], 4, [0.5, 1.0], [0.5, 0.0]);
        assert_pick(&p.steps[1].picks[0], 4, [0.5, 0.0], [1.0, 0.0]);
        assert_pick(&p.steps[2].picks[0], 4, [1.0, 0.0], [0.0, 1.0]);
    }

    #[test]
    fn of_three_corners_the_largest_trapezoid_wins() {
        // A house, folded along y = 1: corners (4,2), (3,3), (0,2) are on the folded side.
        // Areas with P1 = (4,1), P2 = (0,1): {(4,2),(3,3)} 4.5, {(4,2),(0,2)} 4, {(3,3),(0,2)} 5.5.
        let (house, corners) =
            polygon(&[[0.0, 0.0], [4.0, 0.0], [4.0, 2.0], [3.0, 3.0], [0.0, 2.0]], 4);
        let n = house.len();
        let p = plan_folds(&house, &corners, &[], [angle(6.0, n), angle(18.0, n)]).unwrap();
        let s = &p.steps[0];
        assert_eq!(s.corners, vec![3, 4, 5]);
        assert_eq!(s.picks.len(), 2);
        assert_pick(&s.picks[0], 12, [3.0, 3.0], [3.0, -1.0]);
        assert_pick(&s.picks[1], 16, [0.0, 2.0], [0.0, 0.0]);
        let q = |a: [f64; 2], b: [f64; 2]| {
            let pt = |c: [f64; 2]| Point::new(c[0], c[1], 0.0);
            trapezoid_area(&pt([4.0, 1.0]), &pt(a), &pt(b), &pt([0.0, 1.0]))
        };
        assert_eq!(q([4.0, 2.0], [3.0, 3.0]), 4.5);
        // Given in the order that makes a bow tie, the quadrilateral is reordered.
        assert_eq!(q([0.0, 2.0], [4.0, 2.0]), 4.0);
    }

    #[test]
    fn a_flap_without_corners_is_grasped_at_its_farthest_vertex() {
        // A circle of 16 vertices folded from vertex 2 to vertex 6: the arc's middle, 4, is farthest.
        let circle: Vec<Point> = (0..16)
            .map(|k| Point::new(angle(k as f64, 16).cos(), angle(k as f64, 16).sin(), 0.0))
            .collect();
        let p = plan_folds(&circle, &[], &[], [angle(2.0, 16), angle(6.0, 16)]).unwrap();
        assert!(p.steps[0].corners.is_empty());
        assert_eq!(p.steps[0].picks.iter().map(|k| k.vertex).collect::<Vec<_>>(), vec![4]);
    }

    #[test]
    fn the_goal_already_reached_needs_no_step() {
        let (sq, corners) = square();
        let current = [angle(2.0, 16), angle(10.0, 16)];
        // The same fold, given one turn further round: already there, no motion.
        let p =
            plan_folds(&sq, &corners, &[current], [current[0] + TAU, current[1] - TAU]).unwrap();
        assert_eq!(p.case, Case::AlreadyThere);
        assert!(p.steps.is_empty());
        // A quarter of an edge off is the same fold; a whole edge is not.
        assert_eq!(
            plan_folds(&sq, &corners, &[current], [current[0] + angle(0.25, 16), current[1]])
                .unwrap()
                .case,
            Case::AlreadyThere
        );
        assert_eq!(
            plan_folds(&sq, &corners, &[current], [current[0] + angle(1.0, 16), current[1]])
                .unwrap()
                .case,
            Case::Direct
        );
    }

    #[test]
    fn goal_angles_come_back_wrapped() {
        let (sq, corners) = square();
        let p = plan_folds(&sq, &corners, &[], [7.0, 100.0]).unwrap();
        let Fold { f1: g1, f2: g2 } = p.steps[0].fold;
        assert!((0.0..TAU).contains(&g1) && (0.0..TAU).contains(&g2));
        assert!((g1 - (7.0 - TAU)).abs() < 1e-12 && (g2 - 100.0f64.rem_euclid(TAU)).abs() < 1e-12);
    }

    #[test]
    fn cases_and_actions_are_serialised_by_their_names() {
        for case in [Case::Fold, Case::Direct, Case::UnfoldThenFold, Case::AlreadyThere] {
            assert_eq!(serde_json::to_value(case).unwrap(), case.as_str());
        }
        for action in [Action::Fold, Action::Unfold] {
            assert_eq!(serde_json::to_value(action).unwrap(), action.as_str());
        }
    }

    #[test]
    fn bad_goals_are_named() {
        let (sq, corners) = square();
        let message = |r: Result<Plan>| r.unwrap_err().to_string();
        assert!(message(plan_folds(&sq, &corners, &[], [f64::NAN, 1.0])).contains("not finite"));
        assert!(message(plan_folds(&sq, &corners, &[], [1.0, 1.0 + angle(1.0, 16)]))
            .contains("more than one edge"));
        assert!(message(plan_folds(&sq, &corners, &[], [0.1, 0.1 + TAU]))
            .contains("more than one edge"));
        assert!(message(plan_folds(&sq, &[3, 99], &[], [0.0, PI])).contains("corner vertex 99"));
        assert!(message(plan_folds(&sq[..3], &[], &[], [0.0, PI])).contains("too few vertices"));
    }

    /// A goal of two folds (a square in quarters) is made in order: from flat, both folds,
    /// the second on the state the first left, its grasped corners (on top of the stack) put
    /// where the second fold reflects them; with the first made, the second alone; with both,
    /// nothing; to the flat cloth (no goal fold), both unfolded, last first.
    #[test]
    fn a_goal_sequence_is_folded_in_order() {
        // Corners at vertices 0, 4, 8, 12 of a 2 × 2 square centred on the origin.
        let (flat, corners) = polygon(&[[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]], 4);
        let n = flat.len();
        let at = |v: f64| angle(v, n);
        // In half along x = 0 (the right half onto the left), then along y = 0 (the top onto
        // the bottom, both layers): its points, (±1, 0) flat, lie stacked at (-1, 0).
        let goal = [Fold::new(at(2.0), at(10.0)), Fold::new(at(6.0), at(14.0))];
        let p = plan(&flat, &corners, &[], &goal).unwrap();
        assert_eq!(p.case, Case::Fold);
        assert_eq!(p.steps.len(), 2);
        assert!(p.steps.iter().all(|s| s.action == Action::Fold));
        // The second fold moves the two top corners, which the first stacked at (-1, 1): one
        // grasp holds them, the other the top edge's far end at the crease, (0, 1); both go
        // to their reflections across y = 0.
        let mut from_x: Vec<f64> = p.steps[1].picks.iter().map(|pick| pick.from[0]).collect();
        from_x.sort_by(f64::total_cmp);
        assert!(from_x.len() == 2 && (from_x[0] + 1.0).abs() < 1e-9 && from_x[1].abs() < 1e-9);
        for pick in &p.steps[1].picks {
            assert!(
                (pick.from[1] - 1.0).abs() < 1e-9 && (pick.to[1] + 1.0).abs() < 1e-9,
                "{pick:?}"
            );
        }
        let line = p.steps[1].line.expect("a line");
        assert!(line.direction.y.abs() < 1e-9, "the second line runs along x: {line:?}");
        let first = Folding::new(goal[0]);
        let rest = plan(&flat, &corners, &[first], &goal).unwrap();
        assert_eq!((rest.case, rest.steps.len()), (Case::Fold, 1));
        assert_eq!(rest.steps[0].fold, goal[1]);
        let both = [Folding::new(goal[0]), Folding::new(goal[1])];
        assert_eq!(plan(&flat, &corners, &both, &goal).unwrap().case, Case::AlreadyThere);
        // The flat cloth as the goal: unfold, last fold first.
        let flatten = plan(&flat, &corners, &both, &[]).unwrap();
        assert_eq!(flatten.case, Case::UnfoldThenFold);
        assert!(
            flatten.steps.iter().all(|s| s.action == Action::Unfold) && flatten.steps.len() == 2
        );
        assert_eq!(plan(&flat, &corners, &[], &[]).unwrap().case, Case::AlreadyThere);
    }
}
