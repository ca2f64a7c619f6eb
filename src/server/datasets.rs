//! The user's datasets in the sample list (`close serve --dataset PATH`, [`crate::catalog`]).
//!
//! `GET /api/samples?category=&q=&offset=&limit=` merges the built-in list (source
//! `"builtin"`) with the catalog's entries (source: their folder or store; `error` when one
//! cannot be read), filters both alike and pages the result; without `limit` it is the whole
//! list. `GET /api/samples/{id}` answers built-in ids as before and falls back to the
//! catalog: the sample is loaded and analysed on first request and cached like any analysis.

use axum::extract::rejection::{PathRejection, QueryRejection};
use axum::extract::{Path, Query, State};
use axum::response::Response;
use axum::Json;
use serde_json::{json, Value};

use super::{routes, ApiError, AppState};
use crate::analysis::FrameRange;
use crate::catalog;

/// Cache keys of dataset samples start with this.
const DATASET_KEY: &str = "dataset:";

pub async fn samples(State(state): State<AppState>, query: Result<Query<catalog::Query>, QueryRejection>) -> Result<Json<Value>, ApiError> {
    let Query(query) = query.map_err(|e| ApiError::BadRequest(format!("bad list query: {e} (expected ?category=&q=&offset=&limit=)")))?;
    let Json(builtin) = routes::samples(State(state.clone())).await;
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
    Ok(Json(json!({ "samples": page, "total": total, "offset": query.offset, "limit": query.limit, "categories": categories })))
}

pub async fn sample(State(state): State<AppState>, id: Result<Path<String>, PathRejection>) -> Result<Response, ApiError> {
    let dataset_id = match &id {
        Ok(Path(id)) if state.dataset().get(id).is_none() && state.catalog().get(id).is_some() => id.clone(),
        _ => return routes::sample(State(state), id).await,
    };
    let catalog = state.catalog().clone();
    let done = state
        .analysis(format!("{DATASET_KEY}{dataset_id}"), move |key| {
            let sample = catalog.load(&dataset_id)?;
            let source = catalog.get(&dataset_id).map(|e| e.source.clone());
            routes::analyzed(key, &sample, FrameRange::default(), json!({ "id": dataset_id, "source": source, "sample": *sample }))
        })
        .await?;
    Ok(routes::json_response(done.response.clone()))
}
