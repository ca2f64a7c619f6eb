//! `POST /api/plan` and `POST /api/verify`: a plan to goal folds from an analysed state, and
//! an observed state checked against them.

use std::sync::Arc;

use axum::extract::State;
use serde::Deserialize;
use serde_json::value::RawValue;

use super::analysis::{analysis, Loaded, UPLOAD};
use super::json::{to_json, JsonBytes};
use super::samples::sample_analysis;
use super::uploads::kept_analysis;
use crate::answer::PlanAnswer;
use crate::state::{AppState, Drawing, Lane};
use crate::{ApiError, AppJson};
use close_core::analysis::FrameRange;
use close_core::error::Error;
use close_core::geometry::Fold;
use close_io::cache::content_key;
use close_io::formats::json::parse_sample;

/// The analysed state a plan or a verification starts from: `sample` is a Sample JSON
/// object (analysed once, on a worker, and cached by its bytes), the id of a listed sample,
/// or the `key` of an analysis still cached.
async fn drawing_of(state: &AppState, sample: Box<RawValue>) -> Result<Arc<Drawing>, ApiError> {
    let raw = sample.get();
    let drawing =
        match raw.trim_start().as_bytes().first() {
            // An analysis still cached (an upload's "key") or a listed sample's id.
            Some(b'"') => {
                let id: String = serde_json::from_str(raw)
                    .map_err(|e| ApiError::BadRequest(format!("\"sample\": {e}")))?;
                match state.drawing(&id) {
                    Some(hit) => hit,
                    None if state.entry(&id).is_some() || state.catalog().get(&id).is_some() => {
                        sample_analysis(state, &id).await?.drawing.clone()
                    }
                    None if state.uploads().is_some()
                        && state.uploads().is_some_and(|u| u.has(&id)) =>
                    {
                        kept_analysis(state, &id).await?.drawing.clone()
                    }
                    None => sample_analysis(state, &id).await?.drawing.clone(),
                }
            }
            Some(b'{') => {
                let key = content_key(&[b"plan", raw.as_bytes()]);
                let budget = state.config().budget;
                analysis(state, key, move |key, _| {
                    Loaded::of(
                        key,
                        &parse_sample(sample.get().as_bytes())?,
                        FrameRange::default(),
                        UPLOAD,
                        None,
                        &budget,
                    )
                })
                .await?
                .drawing
                .clone()
            }
            _ => return Err(ApiError::BadRequest(
                "\"sample\" must be a Sample JSON object, a listed sample id or an analysis key"
                    .into(),
            )),
        };
    Ok(drawing)
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanRequest {
    /// A Sample JSON object, the id of a built-in sample, or the `key` of an analysis; kept
    /// raw so a sample is parsed once, on a worker.
    sample: Box<RawValue>,
    goal: Goal,
}

/// A plan's goal: one fold `[g1, g2]`, or folds made in order `[[g1, g2], …]`.
#[derive(Debug, Deserialize)]
#[serde(untagged, expecting = "a goal fold [g1, g2] or a list of them [[g1, g2], …]")]
enum Goal {
    One(Fold),
    Sequence(Vec<Fold>),
}

/// Most folds a goal may hold: each is a step of the plan.
const MAX_GOAL_FOLDS: usize = close_core::fold::sequence::MAX_FOLDS * 4;

pub async fn plan(
    State(state): State<AppState>,
    AppJson(req): AppJson<PlanRequest>,
) -> Result<JsonBytes, ApiError> {
    let goal = match req.goal {
        Goal::One(fold) => vec![fold],
        Goal::Sequence(folds) => folds,
    };
    if goal.len() > MAX_GOAL_FOLDS {
        return Err(Error::too_large("goal folds", goal.len(), MAX_GOAL_FOLDS).into());
    }
    if let Some(k) = goal.iter().position(|g| !g.is_finite()) {
        return Err(
            Error::InvalidArgument(format!("goal fold {} needs two finite angles", k + 1)).into()
        );
    }
    let drawing = drawing_of(&state, req.sample).await?;
    let answer = state
        .run_cpu(Lane::Light, move |_| {
            let answer = close_core::plan::answer(&drawing.analysis, &goal)?;
            let states =
                close_render::cloth::plan_states(&drawing.analysis, answer.case, &answer.steps)?;
            to_json(&PlanAnswer { answer, states })
        })
        .await?;
    Ok(JsonBytes(answer))
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VerifyRequest {
    /// As [`PlanRequest::sample`]: the observed state.
    sample: Box<RawValue>,
    /// The goal folds in order, each [g1, g2] in radians.
    goal: Vec<[f64; 2]>,
    /// The line each goal fold is made along, where known (`null` entries: through its points).
    #[serde(default)]
    lines: Vec<Option<close_core::Line>>,
    #[serde(default)]
    tolerance: close_core::verify::Tolerance,
}

/// `POST /api/verify`: the sample's end state against the goal folds
/// ([`close_core::verify::verify`]).
pub async fn verify(
    State(state): State<AppState>,
    AppJson(req): AppJson<VerifyRequest>,
) -> Result<JsonBytes, ApiError> {
    let goal = close_core::verify::Goal { folds: req.goal, lines: req.lines };
    // The goal is checked before the sample is analysed: a bad goal costs nothing.
    close_core::verify::check_goal(&goal, None)?;
    let drawing = drawing_of(&state, req.sample).await?;
    let tolerance = req.tolerance;
    let answer = state
        .run_cpu(Lane::Light, move |_| {
            to_json(&close_core::verify::verify(&drawing.analysis, &goal, tolerance)?)
        })
        .await?;
    Ok(JsonBytes(answer))
}
