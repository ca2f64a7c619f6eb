//! `POST /api/interpolate`: the states of a motion between two folds, or of one fold turned
//! over, after any folds made before it.

use axum::extract::State;
use axum::response::{IntoResponse, Response};
use serde::{Deserialize, Serialize};

use super::json::{to_json, JsonBytes};
use crate::state::{AppState, Lane};
use crate::{ApiError, AppJson};
use close_core::error::Error;
use close_core::geometry::{Fold, Line};

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InterpolateRequest {
    border: Vec<[f64; 3]>,
    /// The flat border whose orientation applies when `border` is already folded (as
    /// `POST /api/disk` takes it); by default `border` itself.
    #[serde(default)]
    reference: Option<Vec<[f64; 3]>>,
    /// Between two folds: `from` and `to`; or one fold turned over: its `arcs` (an analysis
    /// step's `arcs`) about `line` (its `line`; by default the line through the first arc's
    /// start and the last arc's end). See [`close_core::interpolate::Motion`].
    #[serde(default)]
    from: Option<Fold>,
    #[serde(default)]
    to: Option<Fold>,
    #[serde(default)]
    arcs: Option<Vec<close_core::geometry::Arc>>,
    #[serde(default)]
    line: Option<Line>,
    /// States evenly spaced from the start to the end, both included (60 by default)…
    #[serde(default)]
    steps: Option<usize>,
    /// …or the states at these fractions of the way (each in [0, 1]), in this order.
    #[serde(default)]
    at: Option<Vec<f64>>,
    /// Folds made on `border` (then the flat cloth) before the motion, in order, each as an
    /// analysis step reports it (`arcs`, `line`): the motion starts from the state they leave,
    /// and the cloth's layers are drawn from the flat cloth through them.
    #[serde(default)]
    prior: Option<Vec<PriorFold>>,
    /// Also give each state as the web app draws it (`states`: the cloth's layers, each
    /// vertex's height and the fold's line).
    #[serde(default)]
    drawn: bool,
}

/// A fold made before the motion: an analysis step's `arcs` and `line`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PriorFold {
    arcs: Vec<close_core::geometry::Arc>,
    #[serde(default)]
    line: Option<Line>,
}

/// States of an interpolation when the request names none.
const DEFAULT_STEPS: usize = 60;

/// Bytes an interpolation's answer may take per point while it is built: the point (24)
/// and its JSON, three floats of at most 24 characters with their brackets and commas (80);
/// drawn, its height and its share of the layers (about as much again).
const INTERPOLATED_POINT_BYTES: usize = 24 + 80;

/// Largest angle (radians, either sign) an interpolation takes: past it a fold's angles
/// lose their meaning to rounding, and their differences overflow.
const MAX_ANGLE: f64 = 1e6;
/// Largest coordinate of a fold line's point: the border is at most 10⁶ radii across.
const MAX_LINE_POINT: f64 = 1e6;

impl InterpolateRequest {
    /// Refuse what cannot be a fold, as `/api/plan` refuses its goal: `from`, `to` and the
    /// `arcs` need finite angles of at most [`MAX_ANGLE`]; a `line` a finite point within
    /// [`MAX_LINE_POINT`] and a finite direction of some length.
    fn check(&self) -> Result<(), ApiError> {
        let angles = [("from", self.from), ("to", self.to)]
            .into_iter()
            .filter_map(|(name, fold)| fold.map(|f| (name, f.ends())))
            .chain(self.arcs.iter().flatten().map(|a| ("arcs", [a.a, a.b])))
            .chain(
                self.prior.iter().flatten().flat_map(|p| &p.arcs).map(|a| ("prior", [a.a, a.b])),
            );
        for (name, fold) in angles {
            if fold.iter().any(|a| !a.is_finite() || a.abs() > MAX_ANGLE) {
                return Err(Error::InvalidArgument(format!(
                    "\"{name}\" needs finite angles of at most {MAX_ANGLE:e} radians, got {fold:?}"
                ))
                .into());
            }
        }
        let prior_lines = self.prior.iter().flatten().filter_map(|p| p.line.as_ref());
        for line in self.line.iter().chain(prior_lines) {
            if line.point.iter().any(|c| !c.is_finite() || c.abs() > MAX_LINE_POINT) {
                return Err(Error::InvalidArgument(format!(
                    "\"line\": the point needs finite coordinates of at most {MAX_LINE_POINT:e}, got [{}, {}]",
                    line.point.x, line.point.y
                ))
                .into());
            }
            let length = line.direction.x.hypot(line.direction.y);
            if !length.is_finite() || length == 0.0 {
                return Err(Error::InvalidArgument(format!(
                    "\"line\": the direction has no length, or not a finite one: [{}, {}]",
                    line.direction.x, line.direction.y
                ))
                .into());
            }
        }
        Ok(())
    }
}

/// `POST /api/interpolate`'s answer when asked to draw (`drawn`): the states of the motion
/// (core's [`Interpolation`]) and each as the web app draws it ([`close_render::cloth`]).
///
/// [`Interpolation`]: close_core::interpolate::Interpolation
#[derive(Serialize)]
struct InterpolateAnswer {
    #[serde(flatten)]
    interpolation: close_core::interpolate::Interpolation,
    states: Vec<close_render::cloth::Drawn>,
}

pub async fn interpolate(
    State(state): State<AppState>,
    AppJson(req): AppJson<InterpolateRequest>,
) -> Result<Response, ApiError> {
    req.check()?;
    let at = match (req.steps, req.at) {
        (Some(_), Some(_)) => {
            return Err(ApiError::BadRequest(
                "give `steps` (evenly spaced states) or `at` (fractions of the way), not both"
                    .into(),
            ))
        }
        (_, Some(at)) => at,
        (steps, None) => {
            let steps = steps.unwrap_or(DEFAULT_STEPS);
            if !close_core::interpolate::STEPS.contains(&steps) {
                return Err(Error::InvalidArgument(format!(
                    "steps must be in {}..={}, got {steps}",
                    close_core::interpolate::STEPS.start(),
                    close_core::interpolate::STEPS.end()
                ))
                .into());
            }
            close_core::interpolate::fractions(steps)
        }
    };
    if req.prior.is_some() && req.reference.is_some() {
        return Err(ApiError::BadRequest(
            "with `prior` folds, `border` is the flat cloth: send no `reference`".into(),
        ));
    }
    state.config().budget.interpolation(req.border.len(), at.len())?;
    let motion = close_core::interpolate::Motion::of(req.from, req.to, req.arcs, req.line)?;
    let prior: Vec<close_core::geometry::Folding> = req
        .prior
        .unwrap_or_default()
        .into_iter()
        .map(|p| close_core::geometry::Folding {
            fold: Fold::span(&p.arcs).unwrap_or_default(),
            arcs: p.arcs,
            line: p.line,
        })
        .collect();
    // The answer's size is known now: reserved before it is built, not found after.
    let points = req.border.len().saturating_mul(at.len().saturating_add(1));
    let per_point = INTERPOLATED_POINT_BYTES * if req.drawn { 2 } else { 1 };
    let reserved = state.0.memory.reserve(points.saturating_mul(per_point)).await?;
    let (border, reference, drawn) = (req.border, req.reference, req.drawn);
    let answer = state
        .run_cpu(Lane::Light, move |_| {
            let frames = match reference {
                Some(reference) => vec![reference, border],
                None => vec![border],
            };
            let prepared = close_core::border::prepare(frames)?;
            // The state to fold is the last frame; without prior folds it is drawn as it lies.
            let given = prepared.frames.last().map_or(&[][..], Vec::as_slice);
            let (base, made) = close_render::cloth::make(given, &prior)?;
            let mut interpolation = close_core::interpolate::motion_at(&base, &motion, &at)?;
            interpolation.border_indices = prepared.border_indices;
            if !drawn {
                return to_json(&interpolation);
            }
            let states =
                close_render::cloth::motion_states(given, &made, &base, &motion, &interpolation);
            to_json(&InterpolateAnswer { interpolation, states })
        })
        .await?;
    let mut response = JsonBytes(answer).into_response();
    response.extensions_mut().insert(reserved);
    Ok(response)
}
