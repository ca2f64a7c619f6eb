//! Answers about the service itself: its health, and a path no route takes.

use axum::http::Uri;
use axum::Json;
use serde::Serialize;

use crate::ApiError;

#[derive(Serialize)]
pub struct Health {
    status: &'static str,
}

pub async fn healthz() -> Json<Health> {
    Json(Health { status: "ok" })
}

pub async fn not_found(uri: Uri) -> ApiError {
    ApiError::NotFound(format!("no route {}", uri.path()))
}
