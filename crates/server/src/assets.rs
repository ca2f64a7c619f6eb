//! The web app's static files, embedded in the binary so it runs from anywhere.

use axum::extract::Path;
use axum::http::header;
use axum::response::{IntoResponse, Response};

use super::error::ApiError;

/// Content types of the app's files.
const CSS: &str = "text/css; charset=utf-8";
const JS: &str = "text/javascript; charset=utf-8";

/// (file name, content type, content) of every file under `web/` but `index.html`: the
/// stylesheet, the favicon and the ES modules (no build step: the browser loads them as they are).
const FILES: [(&str, &str, &str); 16] = [
    ("app.css", CSS, include_str!("../../../web/app.css")),
    ("favicon.svg", "image/svg+xml", include_str!("../../../web/favicon.svg")),
    ("app.js", JS, include_str!("../../../web/app.js")),
    ("api.js", JS, include_str!("../../../web/api.js")),
    ("store.js", JS, include_str!("../../../web/store.js")),
    ("router.js", JS, include_str!("../../../web/router.js")),
    ("format.js", JS, include_str!("../../../web/format.js")),
    ("circle.js", JS, include_str!("../../../web/circle.js")),
    ("draw.js", JS, include_str!("../../../web/draw.js")),
    ("result.js", JS, include_str!("../../../web/result.js")),
    ("readout.js", JS, include_str!("../../../web/readout.js")),
    ("view-browse.js", JS, include_str!("../../../web/view-browse.js")),
    ("view-upload.js", JS, include_str!("../../../web/view-upload.js")),
    ("view-interpolate.js", JS, include_str!("../../../web/view-interpolate.js")),
    ("view-plan.js", JS, include_str!("../../../web/view-plan.js")),
    ("view-compare.js", JS, include_str!("../../../web/view-compare.js")),
];

const INDEX: &str = include_str!("../../../web/index.html");

fn file(content_type: &'static str, body: &'static str) -> Response {
    ([(header::CONTENT_TYPE, content_type), (header::CACHE_CONTROL, "no-cache")], body)
        .into_response()
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_file_of_the_app_is_served() {
        let dir = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../web"));
        for entry in std::fs::read_dir(dir).unwrap() {
            let name = entry.unwrap().file_name().into_string().unwrap();
            if name != "index.html" {
                assert!(FILES.iter().any(|(n, _, _)| *n == name), "web/{name} is not in FILES");
            }
        }
        // Every module the page imports is one of them.
        for (_, _, body) in FILES.iter().filter(|(n, _, _)| n.ends_with("js")) {
            for import in body
                .lines()
                .filter_map(|l| l.split(" from \"./").nth(1))
                .map(|rest| rest.trim_end_matches("\";"))
            {
                assert!(
                    FILES.iter().any(|(n, _, _)| *n == import),
                    "./{import} is imported but not served"
                );
            }
        }
    }
}
