//! The user's datasets in the sample list (`close serve --dataset PATH`, [`crate::catalog`]).
//!
//! `GET /api/samples?category=&q=&offset=&limit=` merges the built-in list (source
//! `"builtin"`) with the catalog's entries (source: their folder or store; `error` when one
//! cannot be read), filters both alike and pages the result; without `limit` it is the whole
//! list. `GET /api/samples/{id}` answers built-in ids as before and falls back to the
//! catalog: the sample is loaded and analysed on first request and cached like any analysis.

use axum::extract::State;
use serde_json::{json, Value};

use super::routes::{self, JsonBytes, Listed, Loaded};
use super::{ApiError, AppPath, AppQuery, AppState};
use crate::analysis::FrameRange;
use crate::catalog;

/// Cache keys of dataset samples start with this.
const DATASET_KEY: &str = "dataset:";

pub async fn samples(State(state): State<AppState>, AppQuery(query): AppQuery<catalog::Query>) -> Result<JsonBytes, ApiError> {
    let JsonBytes(builtin) = routes::samples(State(state.clone())).await?;
    let builtin: Value = serde_json::from_slice(&builtin).map_err(|e| ApiError::Internal(format!("the built-in list: {e}")))?;
    let text = |v: &Value, key: &str| v[key].as_str().unwrap_or_default().to_string();
    let mut all: Vec<Value> = builtin["samples"]
        .as_array()
        .cloned()
        .unwrap_or_default()
        .into_iter()
        .map(|mut v| {
            v["source"] = "builtin".into();
            v["error"] = Value::Null;
            v
        })
        .collect();
    all.extend(state.catalog().entries().iter().filter_map(|e| serde_json::to_value(e).ok()));
    let mut categories: Vec<(String, usize)> = Vec::new();
    for v in &all {
        let c = text(v, "category");
        match categories.iter_mut().find(|(name, _)| *name == c) {
            Some((_, count)) => *count += 1,
            None => categories.push((c, 1)),
        }
    }
    let matching: Vec<Value> = all.into_iter().filter(|v| query.matches(&text(v, "id"), &text(v, "name"), &text(v, "category"))).collect();
    let total = matching.len();
    let page: Vec<Value> = matching.into_iter().skip(query.offset).take(query.limit.unwrap_or(usize::MAX)).collect();
    let categories: Vec<Value> = categories.into_iter().map(|(name, count)| json!({ "name": name, "count": count })).collect();
    let body = json!({ "samples": page, "total": total, "offset": query.offset, "limit": query.limit, "categories": categories });
    Ok(JsonBytes(serde_json::to_vec(&body).map_err(|e| ApiError::Internal(e.to_string()))?.into()))
}

pub async fn sample(State(state): State<AppState>, AppPath(id): AppPath<String>) -> Result<JsonBytes, ApiError> {
    if state.dataset().get(&id).is_some() || state.catalog().get(&id).is_none() {
        return routes::sample(State(state), AppPath(id)).await;
    }
    let (catalog, budget) = (state.catalog().clone(), state.config().budget);
    let done = routes::analysis(&state, format!("{DATASET_KEY}{id}"), move |key, deadline| {
        let sample = catalog.load(&id, deadline)?;
        let source = catalog.get(&id).map(|e| e.source.clone()).unwrap_or_default();
        Loaded::of(key, &sample.clone(), FrameRange::default(), Some(Listed::Dataset { id, source, sample }), &budget)
    })
    .await?;
    Ok(JsonBytes(done.response.clone()))
}
