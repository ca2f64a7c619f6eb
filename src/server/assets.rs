//! The web app's static files, embedded in the binary so it runs from anywhere.

use axum::extract::Path;
use axum::http::header;
use axum::response::{IntoResponse, Response};

use super::error::ApiError;

/// (file name, content type, content) of every file under `web/` but `index.html`.
const FILES: [(&str, &str, &str); 3] = [
    ("app.css", "text/css; charset=utf-8", include_str!("../../web/app.css")),
    ("app.js", "text/javascript; charset=utf-8", include_str!("../../web/app.js")),
    ("fold.mjs", "text/javascript; charset=utf-8", include_str!("../../web/fold.mjs")),
];

const INDEX: &str = include_str!("../../web/index.html");

fn file(content_type: &'static str, body: &'static str) -> Response {
    ([(header::CONTENT_TYPE, content_type), (header::CACHE_CONTROL, "no-cache")], body).into_response()
}

pub async fn index() -> Response {
    file("text/html; charset=utf-8", INDEX)
}

pub async fn asset(Path(name): Path<String>) -> Result<Response, ApiError> {
    FILES
        .iter()
        .find(|(n, _, _)| *n == name)
        .map(|(_, ty, body)| file(ty, body))
        .ok_or_else(|| ApiError::NotFound(format!("no asset named {name}")))
}
