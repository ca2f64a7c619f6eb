//! Interpolation of folds: a continuous folding motion, either between two folds on the
//! fold circle (the paper's fold interpolation) or one fold's arcs turned over about its line.
//!
//! **Between two folds.** A fold (f1, f2) folds the border arc walked anticlockwise from f1
//! to f2; its span is s = (f2 − f1) mod 2π. Going from (f1, f2) to (g1, g2), endpoint k
//! moves linearly by d_k, with d1 ≡ g1 − f1 and d2 ≡ g2 − f2 (mod 2π). The folded arc must
//! never jump, so the span moves straight from s_from to s_to without passing 0 or 2π:
//! d2 − d1 = s_to − s_from. Of the d1 = shortest(g1 − f1) + 2πm (m ∈ {0, −1, 1}, in that
//! order on ties) the one with the least travel |d1| + |d2| wins: both endpoints take the
//! shorter way round unless that would make them cross, and then the one whose long way is
//! cheaper goes the other way. Fold t of `steps` (t = 0 … steps−1) is (f1 + τ·d1, f2 + τ·d2)
//! mod 2π, τ = t/(steps−1); the first and last folds are `from` and `to` exactly.
//!
//! **A fold turned over** ([`Motion::Turn`]). A fold of several arcs (a multi-arc fold,
//! `steps[k].arcs` of an analysis) or one made along a line of its own (`steps[k].line`,
//! when its two fold points lie on top of each other) has no path on the fold circle that
//! keeps its line: growing each arc from its first point would fold each about a line of
//! its own. It is turned instead: every vertex strictly inside one of the arcs turns about
//! the one fold line by the angle π·τ, the same angle for every arc at every step, and is
//! drawn from above (x, y of the rotated point, z kept, as the reflection keeps it). With
//! f the foot of p on the line, p(τ) = f + cos(πτ)·(p − f): τ = 0 is the border as given
//! and τ = 1 the reflection across the line, exactly the analysis's prediction
//! ([`crate::fold::apply`]). Vertices outside the arcs never move. Without a line the fold is
//! made along the line through the border points at the first arc's start and the last
//! arc's end, as the analysis makes it ([`Fold::line_on`]).
//!
//! The web app draws the states the server computes with these functions (`POST
//! /api/interpolate`, at any fractions of the way: [`motion_at`]); it has no copy of them.
//!
//! The border goes through [`interpolate`], the one entry: it is validated and oriented by
//! [`crate::border::prepare`], exactly as an analysis's start frame, so a border that the
//! analysis refuses (coincident, collinear, too small or too large) is refused here too;
//! the answer's `border_indices` name the input vertex of each border vertex.
//!
//! ```
//! use close_core::geometry::Fold;
//! use close_core::interpolate::fold_path;
//! use std::f64::consts::PI;
//! // Both endpoints move a quarter turn anticlockwise: the span stays π.
//! let path = fold_path(Fold::new(0.0, PI), Fold::new(PI / 2.0, 1.5 * PI), 3);
//! assert_eq!(path.len(), 3);
//! assert!((path[1].f1 - PI / 4.0).abs() < 1e-12 && (path[1].f2 - 1.25 * PI).abs() < 1e-12);
//! ```

use std::f64::consts::PI;

use serde::{Deserialize, Serialize};

use crate::angle::{wrap_pi, wrap_tau, TAU};
use crate::border::{prepare, to_xyz};
use crate::border::{Point, MAX_VERTICES, MIN_VERTICES};
use crate::error::{Error, Result};
use crate::fold::apply;
use crate::geometry::{Arc, Fold, Folding, Line, Vector2};

/// Fewest and most folds an interpolation may have (both ends included).
pub const STEPS: std::ops::RangeInclusive<usize> = 2..=1000;

/// What moves: a fold sliding along the fold circle, or one fold's arcs turned over.
#[derive(Debug, Clone, PartialEq)]
pub enum Motion {
    /// From fold `from` to fold `to`, each state the flat border reflected across one fold.
    Between { from: Fold, to: Fold },
    /// The `arcs` (each folded anticlockwise from a to b) turned over together about `line`,
    /// or about the line through the first arc's start and the last arc's end when `None`.
    Turn { arcs: Vec<Arc>, line: Option<Line> },
}

impl Motion {
    /// The motion a request names: `from` and `to`, or `arcs` with an optional `line`.
    pub fn of(
        from: Option<Fold>,
        to: Option<Fold>,
        arcs: Option<Vec<Arc>>,
        line: Option<Line>,
    ) -> Result<Motion> {
        let bad = |what: &str| Err(Error::InvalidArgument(what.into()));
        match (from, to, arcs) {
            (Some(from), Some(to), None) if line.is_none() => Ok(Motion::Between { from, to }),
            (Some(_), Some(_), None) => {
                bad("a line turns arcs over: give `arcs` with it, not `from` and `to`")
            }
            (None, None, Some(arcs)) => Ok(Motion::Turn { arcs, line }),
            (None, None, None) => {
                bad("give the folds `from` and `to`, or the `arcs` of a fold to turn over")
            }
            (Some(_), None, None) | (None, Some(_), None) => {
                bad("`from` and `to` go together: give both")
            }
            (_, _, Some(_)) => bad("give either `from` and `to`, or `arcs`, not both"),
        }
    }
}

/// The folds of a motion and the border folded by each.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Interpolation {
    /// Each state's fold (f1, f2) in [0, 2π) (radians): the fold on the circle, or for a
    /// turned fold the pair that spans its arcs (the first arc's start, the last arc's end),
    /// the same in every state.
    pub folds: Vec<Fold>,
    /// For a turned fold, how far each state is turned (0 as given, 1 folded over), as a
    /// fraction of a half turn (of π radians).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub turns: Option<Vec<f64>>,
    /// For a turned fold, the line its arcs turn about (XY: a point and a unit direction).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub line: Option<Line>,
    /// Each fold's border, vertices in border order.
    pub borders: Vec<Vec<[f64; 3]>>,
    /// For each border vertex, its index in the input (0…N−1 for an anticlockwise border
    /// without repeated vertices).
    pub border_indices: Vec<usize>,
}

/// How far each endpoint moves (d1, d2) going from `from` to `to`.
pub fn displacements(from: Fold, to: Fold) -> [f64; 2] {
    let span_change = wrap_tau(to.f2 - to.f1) - wrap_tau(from.f2 - from.f1);
    let d1 = wrap_pi(to.f1 - from.f1);
    let cost = |d: f64| d.abs() + (d + span_change).abs();
    let best = [d1, d1 - TAU, d1 + TAU].into_iter().fold(d1, |best, d| {
        if cost(d) < cost(best) - 1e-12 {
            d
        } else {
            best
        }
    });
    [best, best + span_change]
}

/// The fold at fraction `tau` of the way from `from` to `to`, in [0, 2π): τ ≤ 0 gives
/// `from` and τ ≥ 1 gives `to` exactly.
pub(crate) fn fold_at(from: Fold, to: Fold, tau: f64) -> Fold {
    if tau <= 0.0 {
        return from.wrapped();
    }
    if tau >= 1.0 {
        return to.wrapped();
    }
    let [d1, d2] = displacements(from, to);
    Fold::new(wrap_tau(from.f1 + tau * d1), wrap_tau(from.f2 + tau * d2))
}

/// The fractions of `steps` evenly spaced states, t/(steps − 1), both ends included.
pub fn fractions(steps: usize) -> Vec<f64> {
    let last = steps.saturating_sub(1).max(1) as f64;
    (0..steps).map(|t| t as f64 / last).collect()
}

/// `steps` folds from `from` to `to` (both included), each in [0, 2π).
pub fn fold_path(from: Fold, to: Fold, steps: usize) -> Vec<Fold> {
    fractions(steps).into_iter().map(|tau| fold_at(from, to, tau)).collect()
}

/// `p` turned about the XY `line` (unit direction) by the fraction `turn` of a half turn,
/// seen from above: f + cos(π·turn)·(p − f), f the foot of p on the line, z kept.
pub fn turn_about(p: &Point, line: &Line, turn: f64) -> Point {
    let (ux, uy) = (line.direction.x, line.direction.y);
    let t = (p.x - line.point.x) * ux + (p.y - line.point.y) * uy;
    let (fx, fy) = (line.point.x + t * ux, line.point.y + t * uy);
    let c = (PI * turn).cos();
    Point::new(fx + c * (p.x - fx), fy + c * (p.y - fy), p.z)
}

/// The line a turned fold uses: `line` checked (finite, a direction of non-zero length, made
/// unit), or the line through the border points at the first arc's start and the last
/// arc's end.
fn turn_line(border: &[Point], arcs: &[Arc], line: Option<Line>) -> Result<Line> {
    let Some(line) = line else {
        let span = Fold::span(arcs).ok_or_else(|| {
            Error::InvalidArgument("a fold to turn over needs at least one arc".into())
        })?;
        return span.line_on(border, None).ok_or_else(|| {
            Error::InvalidArgument(
                "the fold's two points lie on top of each other: give the `line` to turn about"
                    .into(),
            )
        });
    };
    if let Some(bad) = line.point.iter().chain(line.direction.iter()).find(|c| !c.is_finite()) {
        return Err(Error::InvalidArgument(format!(
            "the line's point and direction must be finite numbers, got {bad}"
        )));
    }
    let length = line.direction.x.hypot(line.direction.y);
    if length == 0.0 || !length.is_finite() {
        return Err(Error::InvalidArgument("the line's direction has no length".into()));
    }
    Ok(Line {
        point: line.point,
        direction: Vector2::new(line.direction.x / length, line.direction.y / length),
    })
}

/// `flat` with the `prior` folds made on it in turn, each as an analysis step reports it:
/// its arcs turned over about its line or, without one, the line through its first arc's
/// start and last arc's end on the state it folds. Gives the state they leave and the line
/// each was made along: a motion that plays a fold sequence starts each fold there.
///
/// ```
/// use close_core::border::Point;
/// use close_core::geometry::{Arc, Folding};
/// use close_core::interpolate::fold_in_turn;
/// use std::f64::consts::PI;
/// let square: Vec<Point> = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
///     .iter().map(|p| Point::new(p[0], p[1], 0.0)).collect();
/// // In half along the diagonal through vertices 0 and 2: vertex 1 lands on vertex 3.
/// let half = Folding { fold: Default::default(), arcs: vec![Arc::new(0.0, PI)], line: None };
/// let (state, lines) = fold_in_turn(&square, &[half]).unwrap();
/// assert!((state[1] - square[3]).norm() < 1e-12 && lines.len() == 1);
/// ```
pub fn fold_in_turn(flat: &[Point], prior: &[Folding]) -> Result<(Vec<Point>, Vec<Line>)> {
    let mut state = flat.to_vec();
    let mut lines = Vec::with_capacity(prior.len());
    for (k, fold) in prior.iter().enumerate() {
        let at = |e: Error| match e {
            Error::InvalidArgument(m) => {
                Error::InvalidArgument(format!("prior fold {}: {m}", k + 1))
            }
            other => other,
        };
        if fold.arcs.is_empty() {
            return Err(Error::InvalidArgument(format!("prior fold {} has no arc", k + 1)));
        }
        let angles: Vec<f64> = fold.arcs.iter().flat_map(|a| [a.a, a.b]).collect();
        finite_angles(&angles, "arc angles").map_err(at)?;
        let line = turn_line(&state, &fold.arcs, fold.line).map_err(at)?;
        let span = Fold::span(&fold.arcs).unwrap_or_default();
        state = apply(&state, &Folding { fold: span, arcs: fold.arcs.clone(), line: Some(line) });
        lines.push(line);
    }
    Ok((state, lines))
}

/// The checks every motion makes of its step count.
fn check_steps(steps: usize) -> Result<()> {
    if !STEPS.contains(&steps) {
        return Err(Error::InvalidArgument(format!(
            "steps must be in {}..={}, got {steps}",
            STEPS.start(),
            STEPS.end()
        )));
    }
    Ok(())
}

/// The states asked for by their fractions `at`: as many as [`STEPS`] allows (one at
/// least), each in [0, 1].
fn check_fractions(at: &[f64]) -> Result<()> {
    if at.is_empty() || at.len() > *STEPS.end() {
        return Err(Error::InvalidArgument(format!(
            "`at` must hold 1 to {} fractions, got {}",
            STEPS.end(),
            at.len()
        )));
    }
    match at.iter().find(|t| !(0.0..=1.0).contains(*t)) {
        Some(bad) => Err(Error::InvalidArgument(format!(
            "`at` holds fractions of the motion, from 0 to 1: got {bad}"
        ))),
        None => Ok(()),
    }
}

/// The checks every motion makes of its border.
fn check_border(border: &[Point]) -> Result<()> {
    if border.len() < MIN_VERTICES {
        return Err(Error::TooFewVertices { got: border.len(), min: MIN_VERTICES });
    }
    if border.len() > MAX_VERTICES {
        return Err(Error::too_large("border vertices", border.len(), MAX_VERTICES));
    }
    if let Some(v) = border.iter().position(|p| p.iter().any(|c| !c.is_finite())) {
        return Err(Error::NonFinite { frame: 0, vertex: v });
    }
    Ok(())
}

/// Angles must be finite; `what` names them in the error.
fn finite_angles(angles: &[f64], what: &str) -> Result<()> {
    match angles.iter().find(|a| !a.is_finite()) {
        Some(bad) => {
            Err(Error::InvalidArgument(format!("{what} must be finite numbers, got {bad}")))
        }
        None => Ok(()),
    }
}

/// The border folded along the fold at each fraction `at` of the way (see [`fold_at`]);
/// `border` is taken as given (an anticlockwise border).
fn between(border: &[Point], from: Fold, to: Fold, at: &[f64]) -> Result<Interpolation> {
    finite_angles(&[from.f1, from.f2, to.f1, to.f2], "fold angles")?;
    let folds: Vec<Fold> = at.iter().map(|&tau| fold_at(from, to, tau)).collect();
    let borders = folds
        .iter()
        .map(|&f| apply(border, &Folding::new(f)).iter().map(to_xyz).collect())
        .collect();
    Ok(Interpolation {
        folds,
        turns: None,
        line: None,
        borders,
        border_indices: (0..border.len()).collect(),
    })
}

/// The states of the fold that turns `arcs` of `border` over about `line` (see the module
/// doc), turned by each of `turns`: 0 `border` itself and 1 [`crate::fold::apply`] exactly.
/// `border` is taken as [`between`] takes it.
fn turn(
    border: &[Point],
    arcs: &[Arc],
    line: Option<Line>,
    turns: &[f64],
) -> Result<Interpolation> {
    if arcs.is_empty() {
        return Err(Error::InvalidArgument("a fold to turn over needs at least one arc".into()));
    }
    // An arc holds at least one vertex strictly inside: more arcs than vertices is no fold.
    if arcs.len() > border.len() {
        return Err(Error::InvalidArgument(format!(
            "{} arcs on a border of {} vertices",
            arcs.len(),
            border.len()
        )));
    }
    let angles: Vec<f64> = arcs.iter().flat_map(|a| [a.a, a.b]).collect();
    finite_angles(&angles, "arc angles")?;
    let line = turn_line(border, arcs, line)?;
    let folding = Folding {
        fold: Fold::span(arcs).unwrap_or_default(),
        arcs: arcs.to_vec(),
        line: Some(line),
    };
    let mut moved: Vec<usize> = arcs.iter().flat_map(|a| a.folded_vertices(border.len())).collect();
    moved.sort_unstable();
    moved.dedup();
    let borders = turns
        .iter()
        .map(|&turn| {
            // The ends exactly: the border as given, and the analysis's reflection.
            if turn >= 1.0 {
                return apply(border, &folding).iter().map(to_xyz).collect();
            }
            let mut state = border.to_vec();
            if turn > 0.0 {
                for &v in &moved {
                    state[v] = turn_about(&border[v], &line, turn);
                }
            }
            state.iter().map(to_xyz).collect()
        })
        .collect();
    Ok(Interpolation {
        folds: vec![folding.fold.wrapped(); turns.len()],
        turns: Some(turns.to_vec()),
        line: Some(line),
        borders,
        border_indices: (0..border.len()).collect(),
    })
}

/// The states of `motion` on `border` as given (an anticlockwise border, e.g. an analysis's
/// start border; checked for size and finite numbers only) at fractions `at` of the way
/// (each in [0, 1]: 0 the start, 1 the end exactly), in the order given.
///
/// ```
/// use close_core::border::Point;
/// use close_core::geometry::Fold;
/// use close_core::interpolate::{fractions, motion_at, Motion};
/// let square: Vec<Point> = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
///     .iter().map(|p| Point::new(p[0], p[1], 0.0)).collect();
/// let motion = Motion::Between { from: Fold::new(0.0, 3.1), to: Fold::new(0.5, 3.6) };
/// let three = motion_at(&square, &motion, &fractions(3)).unwrap();
/// let middle = motion_at(&square, &motion, &[0.5]).unwrap();
/// assert_eq!(middle.borders[0], three.borders[1]);
/// ```
pub fn motion_at(border: &[Point], motion: &Motion, at: &[f64]) -> Result<Interpolation> {
    check_border(border)?;
    check_fractions(at)?;
    match motion {
        Motion::Between { from, to } => between(border, *from, *to, at),
        Motion::Turn { arcs, line } => turn(border, arcs, *line, at),
    }
}

/// `steps` states of `motion` on `border`, validated by [`prepare`] as an analysis
/// validates its frames: `border` is the state to fold and `reference` the flat border whose
/// orientation applies (an analysis's start frame; by default `border` itself, which must
/// then be a valid start frame). A border already folded overlaps itself, so its own area
/// and orientation are no guide: send the flat one as `reference`. With `prior` folds,
/// `border` is the flat cloth and the motion starts from the state they leave
/// ([`fold_in_turn`]): fold k of a sequence played after folds 1…k−1.
///
/// ```
/// use close_core::geometry::{Arc, Fold, Folding};
/// use close_core::interpolate::{interpolate, Motion};
/// let square = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
/// let between = Motion::Between { from: Fold::new(0.0, 3.1), to: Fold::new(0.5, 3.6) };
/// assert_eq!(interpolate(square.clone(), None, &[], &between, 5).unwrap().borders.len(), 5);
/// let line = vec![[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [2.0, 2.0, 0.0], [3.0, 3.0, 0.0]];
/// assert!(interpolate(line.clone(), None, &[], &between, 5).is_err());
/// // A state with no area of its own is fine against a flat reference.
/// assert!(interpolate(line, Some(square.clone()), &[], &between, 5).is_ok());
/// // Vertex 1 turned over about the diagonal through vertices 0 and 2: on vertex 3 at the end.
/// let turn = Motion::Turn { arcs: vec![Arc::new(0.0, std::f64::consts::PI)], line: None };
/// let motion = interpolate(square.clone(), None, &[], &turn, 3).unwrap();
/// assert!((motion.borders[2][1][0] - 0.0).abs() < 1e-12 && (motion.borders[2][1][1] - 1.0).abs() < 1e-12);
/// // After that fold (vertex 1 on vertex 3), vertex 3 turned over the same diagonal lands on (1, 0).
/// let pi = std::f64::consts::PI;
/// let first = Folding { fold: Fold::new(0.0, pi), arcs: vec![Arc::new(0.0, pi)], line: None };
/// let second = Motion::Turn { arcs: vec![Arc::new(pi, 0.0)], line: None };
/// let played = interpolate(square, None, &[first], &second, 2).unwrap();
/// assert!((played.borders[1][3][0] - 1.0).abs() < 1e-12 && played.borders[1][3][1].abs() < 1e-12);
/// ```
pub fn interpolate(
    border: Vec<[f64; 3]>,
    reference: Option<Vec<[f64; 3]>>,
    prior: &[Folding],
    motion: &Motion,
    steps: usize,
) -> Result<Interpolation> {
    if !prior.is_empty() && reference.is_some() {
        return Err(Error::InvalidArgument(
            "with `prior` folds, `border` is the flat cloth: send no `reference`".into(),
        ));
    }
    let frames = match reference {
        Some(reference) => vec![reference, border],
        None => vec![border],
    };
    let prepared = prepare(frames)?;
    // prepare gives one frame per frame given: the state is the last.
    let given = prepared.frames.last().map_or(&[][..], Vec::as_slice);
    check_steps(steps)?;
    let (state, _) = fold_in_turn(given, prior)?;
    let motion = motion_at(&state, motion, &fractions(steps))?;
    Ok(Interpolation { border_indices: prepared.border_indices, ..motion })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// A square of 4·k vertices, side 2, centred at the origin, anticlockwise.
    fn square(k: usize) -> Vec<Point> {
        let c = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
        (0..4 * k)
            .map(|v| {
                let (a, b, t) = (c[v / k], c[(v / k + 1) % 4], (v % k) as f64 / k as f64);
                Point::new(a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1), 0.0)
            })
            .collect()
    }

    /// `steps` evenly spaced states of a turned fold, as [`interpolate`] asks for them.
    fn turn_steps(
        border: &[Point],
        arcs: &[Arc],
        line: Option<Line>,
        steps: usize,
    ) -> Result<Interpolation> {
        check_steps(steps)?;
        motion_at(border, &Motion::Turn { arcs: arcs.to_vec(), line }, &fractions(steps))
    }

    /// `steps` evenly spaced states between two folds, as [`interpolate`] asks for them.
    fn between_steps(
        border: &[Point],
        from: Fold,
        to: Fold,
        steps: usize,
    ) -> Result<Interpolation> {
        check_steps(steps)?;
        motion_at(border, &Motion::Between { from, to }, &fractions(steps))
    }

    fn motion() -> Motion {
        Motion::Between { from: Fold::new(0.0, 1.0), to: Fold::new(1.0, 2.0) }
    }

    /// The line y = 0, rightwards.
    fn x_axis() -> Line {
        Line { point: crate::geometry::Point2::new(0.0, 0.0), direction: Vector2::new(1.0, 0.0) }
    }

    /// `border` folded by `arcs` over `line`, as the analysis folds it.
    fn folded(border: &[Point], arcs: &[Arc], line: Line) -> Vec<[f64; 3]> {
        let fold = Fold::span(arcs).unwrap();
        apply(border, &Folding { fold, arcs: arcs.to_vec(), line: Some(line) })
            .iter()
            .map(to_xyz)
            .collect()
    }

    /// Two legs joined at the top, anticlockwise from the left leg's outer hem corner, a
    /// vertex every 0.1: the line y = 0 crosses the border 4 times, once per leg side. The
    /// two arcs below it (border parameters) are the hems.
    fn two_legs() -> (Vec<Point>, Vec<Arc>) {
        let corners: [(f64, f64); 7] = [
            (-1.0, -1.0),
            (-0.4, -1.0),
            (0.0, 0.5),
            (0.4, -1.0),
            (1.0, -1.0),
            (1.0, 1.0),
            (-1.0, 1.0),
        ];
        let mut points = Vec::new();
        for (k, a) in corners.iter().enumerate() {
            let b = corners[(k + 1) % corners.len()];
            let pieces = ((b.0 - a.0).hypot(b.1 - a.1) / 0.1).round() as usize;
            points.extend((0..pieces).map(|i| {
                let t = i as f64 / pieces as f64;
                Point::new(a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1), 0.01)
            }));
        }
        // The parameter where the side from vertex k to k + 1 crosses y = 0.
        let n = points.len();
        let crossings: Vec<f64> = (0..n)
            .filter_map(|k| {
                let (a, b) = (points[k], points[(k + 1) % n]);
                ((a.y < 0.0) != (b.y < 0.0)).then(|| k as f64 + a.y / (a.y - b.y))
            })
            .collect();
        assert_eq!(crossings.len(), 4);
        let angle = |s: f64| s * TAU / n as f64;
        // Below the line: from the last crossing (the right outer side) round through
        // vertex 0 to the first, and between the second and the third (the inner sides).
        let arcs = vec![
            Arc::new(angle(crossings[3]), angle(crossings[0])),
            Arc::new(angle(crossings[1]), angle(crossings[2])),
        ];
        (points, arcs)
    }

    #[test]
    fn a_turned_fold_turns_only_its_arcs_by_one_angle() {
        let (legs, arcs) = two_legs();
        let line = x_axis();
        let steps = 9;
        let motion = turn_steps(&legs, &arcs, Some(line), steps).unwrap();
        let below: Vec<bool> = legs.iter().map(|p| p.y < 0.0).collect();
        assert!(below.iter().filter(|&&b| b).count() > 10);
        // The ends exactly: the border as given, and the analysis's reflection.
        assert_eq!(motion.borders[0], legs.iter().map(to_xyz).collect::<Vec<_>>());
        assert_eq!(motion.borders[steps - 1], folded(&legs, &arcs, line));
        assert_eq!(
            motion.turns.as_deref(),
            Some(&[0.0, 0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875, 1.0][..])
        );
        assert_eq!(motion.folds, vec![Fold::new(arcs[0].a, arcs[1].b); steps]);
        for (t, state) in motion.borders.iter().enumerate() {
            let c = (PI * t as f64 / 8.0).cos();
            for (v, (p, q)) in legs.iter().zip(state).enumerate() {
                if below[v] {
                    // Both hems, the same angle: x and z kept, y scaled by cos(πτ).
                    assert!(
                        (q[0] - p.x).abs() < 1e-12 && (q[1] - c * p.y).abs() < 1e-12 && q[2] == p.z,
                        "step {t}, vertex {v}: {q:?}"
                    );
                } else {
                    // The crotch between the hems and everything above the line stay.
                    assert_eq!(*q, to_xyz(p), "step {t}, vertex {v}");
                }
            }
        }
    }

    #[test]
    fn a_turned_fold_without_a_line_folds_along_its_span() {
        let (legs, arcs) = two_legs();
        let motion = turn_steps(&legs, &arcs, None, 3).unwrap();
        let line = Fold::new(arcs[0].a, arcs[1].b).line_on(&legs, None).unwrap();
        assert_eq!(motion.line, Some(line));
        assert_eq!(motion.borders[2], folded(&legs, &arcs, line));
        // A given line is made unit.
        let long = turn_steps(
            &legs,
            &arcs,
            Some(Line { direction: Vector2::new(3.0, 0.0), ..x_axis() }),
            3,
        )
        .unwrap();
        assert_eq!(long.line.map(|l| l.direction), Some(Vector2::new(1.0, 0.0)));
    }

    #[test]
    fn bad_turns_are_named() {
        let (legs, arcs) = two_legs();
        let flat = Line { direction: Vector2::new(0.0, 0.0), ..x_axis() };
        assert!(turn_steps(&legs, &arcs, Some(flat), 3)
            .unwrap_err()
            .to_string()
            .contains("no length"));
        let nan = Line { point: crate::geometry::Point2::new(f64::NAN, 0.0), ..x_axis() };
        assert!(turn_steps(&legs, &arcs, Some(nan), 3).unwrap_err().to_string().contains("finite"));
        assert!(turn_steps(&legs, &[], None, 3)
            .unwrap_err()
            .to_string()
            .contains("at least one arc"));
        assert!(turn_steps(&legs, &[Arc::new(0.0, f64::INFINITY)], None, 3)
            .unwrap_err()
            .to_string()
            .contains("arc angles"));
        assert!(turn_steps(&legs, &vec![Arc::new(0.0, 1.0); legs.len() + 1], None, 3)
            .unwrap_err()
            .to_string()
            .contains("arcs on a border"));
        assert!(turn_steps(&legs, &arcs, None, 1).unwrap_err().to_string().contains("steps"));
        // Two fold points on top of each other give no line: the error asks for one.
        let mut stacked = legs.clone();
        let n = legs.len();
        stacked[n / 2] = stacked[0];
        let q = TAU / n as f64;
        assert!(turn_steps(&stacked, &[Arc::new(0.0, (n / 2) as f64 * q)], None, 3)
            .unwrap_err()
            .to_string()
            .contains("`line`"));
    }

    #[test]
    fn states_at_any_fractions_are_the_evenly_spaced_ones_there() {
        let (legs, arcs) = two_legs();
        for motion in [motion(), Motion::Turn { arcs, line: None }] {
            let even = motion_at(&legs, &motion, &fractions(9)).unwrap();
            let at = motion_at(&legs, &motion, &[0.5, 0.0, 1.0, 0.125]).unwrap();
            for (k, t) in [4, 0, 8, 1].into_iter().enumerate() {
                assert_eq!(at.borders[k], even.borders[t], "{motion:?} at state {t}");
                assert_eq!(at.folds[k], even.folds[t]);
            }
        }
        for (bad, says) in [
            (&[][..], "1 to 1000"),
            (&[0.5, 1.5][..], "from 0 to 1"),
            (&[f64::NAN][..], "from 0 to 1"),
        ] {
            let err = motion_at(&legs, &motion(), bad).unwrap_err().to_string();
            assert!(err.contains(says), "{bad:?}: {err}");
        }
        assert!(motion_at(&legs, &motion(), &vec![0.5; 1001]).is_err());
    }

    #[test]
    fn a_motion_is_one_of_the_two_forms() {
        let line = Some(x_axis());
        let (f, g, arc) = (Fold::new(0.0, 1.0), Fold::new(1.0, 2.0), Arc::new(0.0, 1.0));
        assert_eq!(Motion::of(Some(f), Some(g), None, None), Ok(motion()));
        assert_eq!(
            Motion::of(None, None, Some(vec![arc]), line),
            Ok(Motion::Turn { arcs: vec![arc], line })
        );
        for (from, to, arcs, line, says) in [
            (None, None, None, None, "give the folds"),
            (Some(f), None, None, None, "go together"),
            (None, Some(f), None, None, "go together"),
            (Some(f), Some(g), Some(vec![arc]), None, "not both"),
            (Some(f), None, Some(vec![arc]), None, "not both"),
            (Some(f), Some(g), None, line, "give `arcs`"),
        ] {
            assert!(
                Motion::of(from, to, arcs, line).unwrap_err().to_string().contains(says),
                "{says}"
            );
        }
    }

    /// Pairs of folds covering wraps through 0, crossing cases, tiny and huge spans.
    fn cases() -> Vec<(Fold, Fold)> {
        let q = PI / 8.0;
        let pairs: Vec<([f64; 2], [f64; 2])> = vec![
            ([0.0, PI], [PI / 2.0, 1.5 * PI]),
            ([15.0 * q, q], [q, 3.0 * q]),
            ([0.1, 0.3], [6.0, 0.2]),
            ([0.1, 0.3], [0.2, 0.1]),
            ([0.2, 6.0], [0.1, 0.3]),
            ([1.0, 1.2], [4.0, 4.3]),
            ([5.5, 2.0], [0.5, 3.9]),
            ([3.0, 2.9], [0.2, 0.1]),
            ([0.0, PI], [PI, 0.0]),
        ];
        pairs.into_iter().map(|(a, b)| (a.into(), b.into())).collect()
    }

    #[test]
    fn endpoints_are_hit_exactly() {
        for (from, to) in cases() {
            let path = fold_path(from, to, 17);
            assert_eq!(path[0], Fold::new(wrap_tau(from.f1), wrap_tau(from.f2)));
            assert_eq!(path[16], Fold::new(wrap_tau(to.f1), wrap_tau(to.f2)));
        }
    }

    #[test]
    fn span_moves_monotonically_and_never_wraps() {
        for (from, to) in cases() {
            let path = fold_path(from, to, 101);
            let spans: Vec<f64> = path.iter().map(|f| wrap_tau(f.f2 - f.f1)).collect();
            let (s0, s1) = (spans[0], spans[100]);
            for w in spans.windows(2) {
                // The span moves in the direction of s1 − s0, by equal steps: no jump of ~2π.
                assert!(
                    ((w[1] - w[0]) - (s1 - s0) / 100.0).abs() < 1e-9,
                    "{from:?} → {to:?}: {w:?}"
                );
            }
        }
    }

    #[test]
    fn each_step_moves_little() {
        for (from, to) in cases() {
            let path = fold_path(from, to, 201);
            for w in path.windows(2) {
                for (a, b) in [(w[0].f1, w[1].f1), (w[0].f2, w[1].f2)] {
                    // No endpoint travels a full turn: under 2π / 200 per step.
                    assert!(wrap_pi(b - a).abs() <= TAU / 200.0 + 1e-12, "{from:?} → {to:?}");
                }
            }
        }
    }

    #[test]
    fn endpoints_take_the_shorter_way_when_they_do_not_cross() {
        let [d1, d2] = displacements(Fold::new(0.1, 3.0), Fold::new(6.2, 3.2));
        assert!((d1 - (6.2 - 0.1 - TAU)).abs() < 1e-12 && (d2 - 0.2).abs() < 1e-12);
    }

    #[test]
    fn crossing_endpoints_send_one_the_long_way() {
        // Shortest ways: f1 0.1 → 0.2 forward, f2 0.3 → 0.1 back: the span would pass 0
        // (0.2 → −0.1); it must grow from 0.2 to 2π − 0.1 instead.
        let from = Fold::new(0.1, 0.3);
        let to = Fold::new(0.2, 0.1);
        let [d1, d2] = displacements(from, to);
        let (s0, s1) = (wrap_tau(from.f2 - from.f1), wrap_tau(to.f2 - to.f1));
        assert!(((d2 - d1) - (s1 - s0)).abs() < 1e-12);
        assert!(d1.abs() > PI || d2.abs() > PI, "one endpoint goes the long way: {d1} {d2}");
    }

    #[test]
    fn a_square_folds_continuously() {
        let sq = square(8);
        let motion = between_steps(
            &sq,
            Fold::new(PI / 4.0 + 0.01, 1.25 * PI + 0.01),
            Fold::new(0.0, PI),
            61,
        )
        .unwrap();
        assert_eq!(motion.borders.len(), 61);
        for w in motion.borders.windows(2) {
            let jump = w[0]
                .iter()
                .zip(&w[1])
                .map(|(a, b)| ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt())
                .fold(0.0, f64::max);
            assert!(jump < 0.25, "a vertex jumped by {jump}");
        }
        let last = apply(&sq, &Folding::new(Fold::new(0.0, PI)));
        assert!(motion.borders[60]
            .iter()
            .zip(&last)
            .all(|(a, b)| (a[0] - b.x).abs() < 1e-12 && (a[1] - b.y).abs() < 1e-12));
    }

    #[test]
    fn bad_arguments_are_named() {
        let sq = square(2);
        let (f, g) = (Fold::new(0.0, 1.0), Fold::new(1.0, 2.0));
        assert!(between_steps(&sq, f, g, 1).unwrap_err().to_string().contains("steps"));
        assert!(between_steps(&sq, Fold::new(f64::NAN, 1.0), g, 5)
            .unwrap_err()
            .to_string()
            .contains("finite"));
        assert!(matches!(between_steps(&sq[..3], f, g, 5), Err(Error::TooFewVertices { .. })));
    }

    #[test]
    fn a_users_border_is_validated_as_an_analysis_validates_it() {
        let raw: Vec<[f64; 3]> = square(2).iter().map(to_xyz).collect();
        let ok = interpolate(raw.clone(), None, &[], &motion(), 5).unwrap();
        assert_eq!(ok.border_indices, (0..8).collect::<Vec<_>>());
        for bad in [
            raw[..3].to_vec(),
            vec![[1.0, 2.0, 0.0]; 8],
            (0..8).map(|k| [k as f64, 2.0 * k as f64, 0.0]).collect(),
        ] {
            let ours = interpolate(bad.clone(), None, &[], &motion(), 5).unwrap_err();
            assert_eq!(ours, prepare(vec![bad]).unwrap_err(), "the same refusal as the analysis");
        }
        // A clockwise border is walked anticlockwise, vertex 0 first, as the analysis does.
        let mut cw = raw.clone();
        cw[1..].reverse();
        let reversed = interpolate(cw, None, &[], &motion(), 5).unwrap();
        assert_eq!(reversed.border_indices, [0, 7, 6, 5, 4, 3, 2, 1]);
        assert_eq!(reversed.borders, ok.borders);
        // A square folded in half has no area of its own: against the flat one, it folds on,
        // in its own vertex order; against a reference of another vertex count, it is refused.
        let half: Vec<[f64; 3]> = apply(&square(2), &Folding::new(Fold::new(PI / 4.0, 1.25 * PI)))
            .iter()
            .map(to_xyz)
            .collect();
        assert!(interpolate(half.clone(), None, &[], &motion(), 5).is_err());
        let on = interpolate(half.clone(), Some(raw.clone()), &[], &motion(), 5).unwrap();
        assert_eq!(on.border_indices, (0..8).collect::<Vec<_>>());
        let half_points: Vec<Point> = half.iter().map(crate::border::from_xyz).collect();
        assert_eq!(
            on.borders,
            between_steps(&half_points, Fold::new(0.0, 1.0), Fold::new(1.0, 2.0), 5)
                .unwrap()
                .borders
        );
        assert!(matches!(
            interpolate(half, Some(raw[..6].to_vec()), &[], &motion(), 5),
            Err(Error::FrameSizeMismatch { .. })
        ));
    }
}
