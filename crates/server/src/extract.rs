//! Extractors that reject with [`ApiError`], as in axum's error-handling example: handlers
//! take `AppJson<T>`, `AppPath<T>`, `AppQuery<T>` and never see a rejection. `AppJson`
//! parses a large body on a worker of the app ([`AppState`]).
//!
//! ```
//! use close_server::AppJson;
//! use serde::Deserialize;
//! #[derive(Deserialize)]
//! struct Goal { goal: [f64; 2] }
//! // A handler: `async fn plan(AppJson(req): AppJson<Goal>) -> …`; a body that is not a
//! // `Goal` is answered with `{"error": "..."}` and axum's status (400, 415 or 422).
//! let _ = |AppJson(req): AppJson<Goal>| async move { req.goal[0] };
//! ```

use axum::body::Bytes;
use axum::extract::{FromRequest, FromRequestParts, Path, Query, Request};
use axum::http::request::Parts;
use axum::http::{header, HeaderMap, StatusCode};
use axum::Json;
use serde::de::DeserializeOwned;

use super::state::Lane;
use super::{ApiError, AppState};
use close_io::formats::json::check_nesting;

/// A JSON body of type `T`, nested at most [`close_io::formats::json::MAX_NESTING`] deep
/// anywhere (inside an unknown key too). A body larger than 64 KiB is checked and parsed
/// on a worker, under the request's deadline, never on the async threads: many large
/// bodies at once then wait for the workers instead of holding every other request.
pub struct AppJson<T>(pub T);

/// Bodies up to this size are parsed where they arrive (microseconds of work).
pub(crate) const PARSED_INLINE: usize = 64 * 1024;

/// Whether the body says it is JSON: `application/json` or `application/…+json`.
fn is_json(headers: &HeaderMap) -> bool {
    let essence = headers
        .get(header::CONTENT_TYPE)
        .and_then(|t| t.to_str().ok())
        .and_then(|t| t.split(';').next())
        .unwrap_or("");
    let essence = essence.trim().to_ascii_lowercase();
    essence == "application/json"
        || (essence.starts_with("application/") && essence.ends_with("+json"))
}

/// Check a body's nesting and parse it as a `T`.
fn parse<T: DeserializeOwned>(bytes: &Bytes) -> Result<T, ApiError> {
    check_nesting(bytes).map_err(|e| ApiError::Rejected(StatusCode::BAD_REQUEST, e.to_string()))?;
    let Json(value) = Json::<T>::from_bytes(bytes)?;
    Ok(value)
}

impl<T: DeserializeOwned + Send + 'static> FromRequest<AppState> for AppJson<T> {
    type Rejection = ApiError;

    async fn from_request(request: Request, state: &AppState) -> Result<Self, ApiError> {
        if !is_json(request.headers()) {
            return Err(ApiError::Rejected(
                StatusCode::UNSUPPORTED_MEDIA_TYPE,
                "Expected request with `Content-Type: application/json`".into(),
            ));
        }
        let bytes = Bytes::from_request(request, state).await?;
        if bytes.len() <= PARSED_INLINE {
            return parse(&bytes).map(AppJson);
        }
        state.run_cpu(Lane::Light, move |_| parse(&bytes)).await.map(AppJson)
    }
}

/// Path parameters of type `T`.
pub struct AppPath<T>(pub T);

/// Query parameters of type `T`.
pub struct AppQuery<T>(pub T);

/// The two request-parts extractors differ only in the axum extractor they wrap.
macro_rules! from_parts {
    ($ours:ident, $axum:ident) => {
        impl<S: Send + Sync, T: DeserializeOwned + Send> FromRequestParts<S> for $ours<T> {
            type Rejection = ApiError;

            async fn from_request_parts(parts: &mut Parts, state: &S) -> Result<Self, ApiError> {
                let $axum(value) = $axum::<T>::from_request_parts(parts, state).await?;
                Ok($ours(value))
            }
        }
    };
}

from_parts!(AppPath, Path);
from_parts!(AppQuery, Query);
