//! The one error type of the HTTP API: every failure is a status code and `{"error": "..."}`.
//!
//! Library errors map by kind: input that cannot be read is 400, input that reads but is no
//! usable border is 422, too large is 413; axum's own rejections keep their status and
//! text. A 500 is left for a failure of the server itself: a worker that died, a picture
//! or a recording that could not be written. The match over library errors is exhaustive,
//! so a new variant does not compile until it is given a status.

use axum::extract::multipart::{MultipartError, MultipartRejection};
use axum::extract::rejection::{BytesRejection, JsonRejection, PathRejection, QueryRejection};
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use axum::Json;

use crate::answer::ErrorBody;
use close_core::error::Error;

/// Why a request failed.
#[derive(Debug)]
pub enum ApiError {
    /// The input was read but is wrong (a bad border, too large, …).
    Input(Error),
    /// A file, a dataset entry or a store could not be read.
    Read(close_io::error::Error),
    /// A picture or a recording could not be made.
    Picture(close_render::error::Error),
    /// The body is not JSON or a multipart form.
    UnsupportedMediaType(String),
    /// No such sample, image or route.
    NotFound(String),
    /// A well-formed request asking for something impossible.
    BadRequest(String),
    /// Rejected by an extractor or a layer before reaching the handler.
    Rejected(StatusCode, String),
    /// The server failed (a worker panicked or the pool shut down).
    Internal(String),
}

impl ApiError {
    pub fn status(&self) -> StatusCode {
        match self {
            ApiError::Input(e) => input_status(e),
            ApiError::Read(e) => read_status(e),
            ApiError::Picture(close_render::error::Error::Core(e)) => input_status(e),
            // A picture or recording that cannot be made is our bug, not bad input.
            ApiError::Picture(_) => StatusCode::INTERNAL_SERVER_ERROR,
            ApiError::UnsupportedMediaType(_) => StatusCode::UNSUPPORTED_MEDIA_TYPE,
            ApiError::NotFound(_) => StatusCode::NOT_FOUND,
            ApiError::BadRequest(_) => StatusCode::BAD_REQUEST,
            ApiError::Rejected(status, _) => *status,
            ApiError::Internal(_) => StatusCode::INTERNAL_SERVER_ERROR,
        }
    }

    pub fn message(&self) -> String {
        match self {
            ApiError::Input(e) => e.to_string(),
            ApiError::Read(e) => e.to_string(),
            ApiError::Picture(e) => e.to_string(),
            ApiError::UnsupportedMediaType(m)
            | ApiError::NotFound(m)
            | ApiError::BadRequest(m)
            | ApiError::Internal(m) => m.clone(),
            ApiError::Rejected(status, m) if *status == StatusCode::PAYLOAD_TOO_LARGE => {
                format!("request body too large: {m}")
            }
            ApiError::Rejected(_, m) => m.clone(),
        }
    }
}

/// The status of a library error (no catch-all: a new variant must be given its status).
fn input_status(e: &Error) -> StatusCode {
    match e {
        Error::Empty { .. } | Error::InvalidArgument(_) | Error::InvalidFold { .. } => {
            StatusCode::BAD_REQUEST
        }
        Error::TooLarge { .. } | Error::OverBudget { .. } => StatusCode::PAYLOAD_TOO_LARGE,
        // The request's time ran out (its answer is usually the time-out layer's 408).
        Error::Cancelled => StatusCode::REQUEST_TIMEOUT,
        Error::TooFewVertices { .. }
        | Error::NonFinite { .. }
        | Error::FrameSizeMismatch { .. }
        | Error::Degenerate { .. }
        | Error::Mesh(_) => StatusCode::UNPROCESSABLE_ENTITY,
    }
}

/// The status of a reader's error (no catch-all either).
fn read_status(e: &close_io::error::Error) -> StatusCode {
    use close_io::error::Error as Read;
    match e {
        Read::Core(e) => input_status(e),
        Read::Parse { .. } => StatusCode::BAD_REQUEST,
        // A user's dataset file that cannot be read is bad input; an unknown id is a 404.
        Read::Store { .. } => StatusCode::UNPROCESSABLE_ENTITY,
        Read::UnknownSample { .. } => StatusCode::NOT_FOUND,
        // Naming the file does not change what is wrong with it.
        Read::InFile { error, .. } => read_status(error),
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let status = self.status();
        if status.is_server_error() {
            tracing::error!(error = %self.message(), "request failed");
        }
        (status, Json(ErrorBody { error: self.message() })).into_response()
    }
}

impl From<Error> for ApiError {
    fn from(e: Error) -> Self {
        ApiError::Input(e)
    }
}

impl From<close_io::error::Error> for ApiError {
    fn from(e: close_io::error::Error) -> Self {
        ApiError::Read(e)
    }
}

impl From<close_render::error::Error> for ApiError {
    fn from(e: close_render::error::Error) -> Self {
        ApiError::Picture(e)
    }
}

/// A 408 when a body read failed because the body came too slowly ([`BodyTooSlow`] among
/// the error's sources): the client's pace, not its content.
fn too_slow(error: &(dyn std::error::Error + 'static)) -> Option<ApiError> {
    let mut source = Some(error);
    while let Some(s) = source {
        if let Some(slow) = s.downcast_ref::<BodyTooSlow>() {
            return Some(ApiError::Rejected(StatusCode::REQUEST_TIMEOUT, slow.to_string()));
        }
        source = s.source();
    }
    None
}

/// axum rejections all carry a status and a text: keep both (a body too slow is a 408).
macro_rules! from_rejection {
    ($($t:ty),*) => {$(
        impl From<$t> for ApiError {
            fn from(r: $t) -> Self {
                too_slow(&r).unwrap_or_else(|| ApiError::Rejected(r.status(), r.body_text()))
            }
        }
    )*};
}

from_rejection!(JsonRejection, BytesRejection, PathRejection, QueryRejection, MultipartRejection);

/// True when the body's length limit (axum's `DefaultBodyLimit`, tower-http's limit layer:
/// both `http_body_util::Limited`) is among the error's sources: found by its type.
fn over_length_limit(error: &(dyn std::error::Error + 'static)) -> bool {
    let mut source = Some(error);
    while let Some(s) = source {
        if s.is::<http_body_util::LengthLimitError>() {
            return true;
        }
        source = s.source();
    }
    false
}

/// A form that could not be read is the client's doing: a body too slow (408) or over the
/// limit (413: the body's `LengthLimitError`, found by type among the error's sources; axum's
/// own status misses tower-http's limit layer), or a malformed form (400), never a server
/// fault.
impl From<MultipartError> for ApiError {
    fn from(e: MultipartError) -> Self {
        if let Some(slow) = too_slow(&e) {
            return slow;
        }
        if over_length_limit(&e) {
            return ApiError::Rejected(
                StatusCode::PAYLOAD_TOO_LARGE,
                "request body too large: the form is larger than the limit".into(),
            );
        }
        let status =
            if e.status().is_client_error() { e.status() } else { StatusCode::BAD_REQUEST };
        ApiError::Rejected(status, format!("could not read the form: {}", e.body_text()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn input_errors_are_4xx_and_our_failures_5xx() {
        use close_io::error::{Error as Read, Format};
        use close_render::error::Error as Picture;
        let status = |e: ApiError| e.status();
        assert_eq!(status(Read::parse(Format::Text, "x").into()), StatusCode::BAD_REQUEST);
        assert_eq!(
            status(Read::from(Error::too_large("frames", 2000, 1000)).in_file("a.json").into()),
            StatusCode::PAYLOAD_TOO_LARGE
        );
        assert_eq!(
            status(Error::Mesh(close_core::error::MeshError::NoFaces).into()),
            StatusCode::UNPROCESSABLE_ENTITY
        );
        assert_eq!(status(Read::UnknownSample { id: "x".into() }.into()), StatusCode::NOT_FOUND);
        assert_eq!(
            status(Error::OverBudget { what: "cells", got: 2, limit: 1 }.into()),
            StatusCode::PAYLOAD_TOO_LARGE
        );
        assert_eq!(status(Error::Cancelled.into()), StatusCode::REQUEST_TIMEOUT);
        assert_eq!(
            status(Error::FrameSizeMismatch { frame: 1, expected: 4, got: 3 }.into()),
            StatusCode::UNPROCESSABLE_ENTITY
        );
        assert_eq!(status(Picture::invalid("x".into()).into()), StatusCode::BAD_REQUEST);
        assert_eq!(
            status(Picture::Render("font".into()).into()),
            StatusCode::INTERNAL_SERVER_ERROR
        );
        assert_eq!(
            status(Picture::Recording("encoder".into()).into()),
            StatusCode::INTERNAL_SERVER_ERROR
        );
    }

    #[tokio::test]
    async fn a_form_over_the_body_limit_is_413_found_by_the_errors_type() {
        use axum::extract::{DefaultBodyLimit, Multipart};
        use tower::ServiceExt;
        async fn read(mut form: Multipart) -> Result<(), ApiError> {
            while let Some(field) = form.next_field().await? {
                field.bytes().await?;
            }
            Ok(())
        }
        let app = axum::Router::new()
            .route("/", axum::routing::post(read))
            .layer(DefaultBodyLimit::max(64));
        let form = |size: usize| {
            let body = format!(
                "--b\r\nContent-Disposition: form-data; name=\"f\"\r\n\r\n{}\r\n--b--\r\n",
                "x".repeat(size)
            );
            axum::http::Request::post("/")
                .header("content-type", "multipart/form-data; boundary=b")
                .body(axum::body::Body::from(body))
                .expect("request")
        };
        let small = app.clone().oneshot(form(4)).await.expect("answer");
        assert_eq!(small.status(), StatusCode::OK);
        let large = app.oneshot(form(1000)).await.expect("answer");
        assert_eq!(large.status(), StatusCode::PAYLOAD_TOO_LARGE);
        let body = axum::body::to_bytes(large.into_body(), 1 << 16).await.expect("body");
        let text = String::from_utf8_lossy(&body);
        assert!(text.starts_with(r#"{"error":"request body too large: "#), "{text}");
    }
}

/// Why a body read failed: it arrived slower than the minimum rate (bytes a second).
#[derive(Debug, thiserror::Error)]
#[error("the request body arrives slower than {0} bytes a second")]
pub struct BodyTooSlow(pub u64);
