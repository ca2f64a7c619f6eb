//! `POST /api/distance`: how far apart two states of one cloth are.

use axum::extract::State;
use serde::Deserialize;

use super::json::{to_json, JsonBytes};
use crate::state::{AppState, Lane};
use crate::{ApiError, AppJson};
use close_core::error::Error;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DistanceRequest {
    /// Two states of one cloth: each its folds in order, [f1, f2] in radians.
    a: Vec<[f64; 2]>,
    b: Vec<[f64; 2]>,
    /// The cloth's flat border, for the geometric distance too.
    #[serde(default)]
    border: Option<Vec<[f64; 3]>>,
}

/// `POST /api/distance`: {`folds`, `geometric`} between two states of one cloth
/// ([`close_core::distance`]).
pub async fn distance(
    State(state): State<AppState>,
    AppJson(req): AppJson<DistanceRequest>,
) -> Result<JsonBytes, ApiError> {
    use close_core::distance::{check_folds, fold_distance, geometric_distance, Distance};
    for (name, folds) in [("a", &req.a), ("b", &req.b)] {
        if folds.len() > close_core::distance::MAX_BATCH_FOLDS {
            return Err(Error::too_large(
                "folds",
                folds.len(),
                close_core::distance::MAX_BATCH_FOLDS,
            )
            .into());
        }
        check_folds(name, folds, 0.0)?;
    }
    let answer = state
        .run_cpu(Lane::Light, move |_| {
            // The border is checked as every border (at most MAX_VERTICES vertices); the
            // work is then O(N · folds).
            let geometric = match req.border {
                Some(border) => {
                    let flat = close_core::border::prepare(vec![border])?;
                    Some(geometric_distance(&flat.frames[0], &req.a, &req.b)?)
                }
                None => None,
            };
            to_json(&Distance { folds: fold_distance(&req.a, &req.b), geometric })
        })
        .await?;
    Ok(JsonBytes(answer))
}
