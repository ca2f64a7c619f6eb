//! Every route of the HTTP API, driven in-process with `tower::ServiceExt::oneshot`:
//! the answers on good input, and a JSON 4xx naming the problem for each kind of bad input (unparseable, NaN, empty, too large, mismatched frames, degenerate).

use axum::body::{to_bytes, Body, Bytes};
use axum::http::{header, Method, Request, StatusCode};
use axum::Router;
use serde_json::{json, Value};
use tower::ServiceExt;

use close::server::{app, AppState, Config};
use close::{analyze, dataset, FrameRange};

struct Answer {
    status: StatusCode,
    content_type: String,
    body: Bytes,
}

impl Answer {
    fn json(&self) -> Value {
        serde_json::from_slice(&self.body)
            .unwrap_or_else(|e| panic!("not JSON ({e}): {}", String::from_utf8_lossy(&self.body)))
    }

    /// The `error` text of a JSON error answer with status `status`.
    fn error(&self, status: StatusCode) -> String {
        assert_eq!(self.status, status, "{}", String::from_utf8_lossy(&self.body));
        assert!(
            self.content_type.starts_with("application/json"),
            "error answer is {}",
            self.content_type
        );
        self.json()["error"]
            .as_str()
            .unwrap_or_else(|| panic!("no error text in {}", self.json()))
            .to_string()
    }
}

async fn send(app: &Router, request: Request<Body>) -> Answer {
    let response = app.clone().oneshot(request).await.expect("the router never fails");
    let status = response.status();
    let content_type = response
        .headers()
        .get(header::CONTENT_TYPE)
        .map(|v| v.to_str().unwrap_or("").to_string())
        .unwrap_or_default();
    let body = to_bytes(response.into_body(), usize::MAX).await.expect("body");
    Answer { status, content_type, body }
}

async fn get(app: &Router, uri: &str) -> Answer {
    send(app, Request::get(uri).body(Body::empty()).unwrap()).await
}

async fn post(app: &Router, uri: &str, content_type: &str, body: impl Into<Body>) -> Answer {
    send(
        app,
        Request::post(uri).header(header::CONTENT_TYPE, content_type).body(body.into()).unwrap(),
    )
    .await
}

async fn post_json(app: &Router, uri: &str, body: &Value) -> Answer {
    post(app, uri, "application/json", body.to_string()).await
}

/// A multipart/form-data body of (field, file name, content) parts.
fn multipart(parts: &[(&str, &str, &str)]) -> (String, String) {
    let boundary = "close-test-boundary-7d1f";
    let mut body = String::new();
    for (field, file, content) in parts {
        body.push_str(&format!(
            "--{boundary}\r\nContent-Disposition: form-data; name=\"{field}\"; filename=\"{file}\"\r\nContent-Type: application/octet-stream\r\n\r\n{content}\r\n"
        ));
    }
    body.push_str(&format!("--{boundary}--\r\n"));
    (format!("multipart/form-data; boundary={boundary}"), body)
}

fn text_frame(frame: &[[f64; 3]]) -> String {
    frame.iter().map(|p| format!("{},{},{}\n", p[0], p[1], p[2])).collect()
}

fn first_entry() -> dataset::BuiltinSample {
    dataset::Dataset::builtin()
        .entries()
        .iter()
        .find(|e| e.sample.frames.len() >= 2)
        .cloned()
        .expect("a built-in sample with two frames")
}

fn test_app() -> Router {
    app(AppState::new())
}

async fn assert_healthy(app: &Router) {
    let a = get(app, "/healthz").await;
    assert_eq!(a.status, StatusCode::OK);
    assert_eq!(a.json()["status"], "ok");
}

async fn assert_png(app: &Router, url: &str) {
    let a = get(app, url).await;
    assert_eq!(a.status, StatusCode::OK, "{url}: {}", String::from_utf8_lossy(&a.body));
    assert_eq!(a.content_type, "image/png", "{url}");
    assert!(a.body.starts_with(b"\x89PNG\r\n\x1a\n"), "{url} is not a PNG");
}

/// Equal JSON, numbers to 1e-9 (the analysis sums in parallel, so the last bits may vary).
fn assert_same(a: &Value, b: &Value, at: &str) {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap_or(f64::NAN), y.as_f64().unwrap_or(f64::NAN));
            assert!((x - y).abs() <= 1e-9 * x.abs().max(1.0), "{at}: {x} != {y}");
        }
        (Value::Array(x), Value::Array(y)) => {
            assert_eq!(x.len(), y.len(), "{at}: lengths");
            x.iter()
                .zip(y)
                .enumerate()
                .for_each(|(k, (x, y))| assert_same(x, y, &format!("{at}[{k}]")));
        }
        (Value::Object(x), Value::Object(y)) => {
            assert_eq!(x.keys().collect::<Vec<_>>(), y.keys().collect::<Vec<_>>(), "{at}: keys");
            x.iter().for_each(|(k, x)| assert_same(x, &y[k], &format!("{at}.{k}")));
        }
        _ => assert_eq!(a, b, "{at}"),
    }
}

#[tokio::test]
async fn the_app_and_its_assets_are_served() {
    let app = test_app();
    let index = get(&app, "/").await;
    assert_eq!(index.status, StatusCode::OK);
    assert!(index.content_type.starts_with("text/html"));
    let html = String::from_utf8_lossy(&index.body);
    for asset in ["/assets/app.js", "/assets/app.css"] {
        assert!(html.contains(asset), "index does not load {asset}");
        assert_eq!(get(&app, asset).await.status, StatusCode::OK, "{asset}");
    }
    assert!(get(&app, "/assets/nope.js").await.error(StatusCode::NOT_FOUND).contains("nope.js"));
    assert!(get(&app, "/no/such/route")
        .await
        .error(StatusCode::NOT_FOUND)
        .contains("/no/such/route"));
    assert_healthy(&app).await;
}

#[tokio::test]
async fn json_answers_are_gzipped_when_asked() {
    let app = test_app();
    let request = Request::get(format!("/api/samples/{}", first_entry().id))
        .header(header::ACCEPT_ENCODING, "gzip")
        .body(Body::empty())
        .unwrap();
    let response = app.oneshot(request).await.expect("answer");
    assert_eq!(response.status(), StatusCode::OK);
    assert_eq!(
        response.headers().get(header::CONTENT_ENCODING).map(|v| v.as_bytes()),
        Some(&b"gzip"[..])
    );
}

#[tokio::test]
async fn samples_are_listed_with_thumbnails() {
    let app = test_app();
    let list = get(&app, "/api/samples").await.json();
    let samples = list["samples"].as_array().expect("samples array");
    let dataset = dataset::Dataset::builtin();
    assert_eq!(samples.len(), dataset.entries().len());
    for (s, e) in samples.iter().zip(dataset.entries()) {
        assert_eq!(s["id"], e.id.as_str());
        assert_eq!(s["name"], e.sample.name.as_str());
        assert_eq!(s["category"], e.sample.category.as_str());
        let border = e.sample.border_frames().expect("a built-in border");
        assert_eq!(s["n"], border.len());
        assert_eq!(
            s["frames"],
            e.sample.mesh.as_ref().map_or(e.sample.frames.len(), |m| m.frames.len())
        );
        assert_eq!(s["mesh"], e.sample.mesh.is_some());
    }
    assert!(samples.iter().any(|s| s["mesh"] == true), "the dataset shows a mesh sample");
    assert_png(&app, samples[0]["thumbnail"].as_str().expect("thumbnail url")).await;
}

#[tokio::test]
async fn a_sample_comes_with_its_analysis_and_pictures() {
    let app = test_app();
    let entry = first_entry();
    let a = get(&app, &format!("/api/samples/{}", entry.id)).await;
    assert_eq!(a.status, StatusCode::OK);
    let v = a.json();
    // The CLI's JSON, field for field.
    let cli = serde_json::to_value(
        analyze(&entry.sample.border_frames().unwrap(), FrameRange::default()).unwrap(),
    )
    .unwrap();
    for (key, value) in cli.as_object().unwrap() {
        assert_same(&v[key], value, key);
    }
    for key in [
        "folds",
        "corners",
        "label",
        "predicted_end",
        "metrics",
        "images",
        "sample",
        "start_border",
    ] {
        assert!(!v[key].is_null(), "missing {key}");
    }
    assert!(v["label"]["text"].as_str().is_some_and(|t| !t.is_empty()));
    assert!(v["metrics"]["rmse"].as_f64().is_some());
    assert_eq!(v["sample"]["frames"].as_array().map(Vec::len), Some(entry.sample.frames.len()));
    for picture in ["disk_start", "disk_end", "diff", "signed_diff", "close", "borders"] {
        assert_png(
            &app,
            v["images"][picture].as_str().unwrap_or_else(|| panic!("no {picture} image")),
        )
        .await;
    }
    // A picture of another size is another PNG.
    let small = get(&app, &format!("/api/images/sample:{}/close.png?size=100", entry.id)).await;
    let large = get(&app, &format!("/api/images/sample:{}/close.png?size=300", entry.id)).await;
    assert_ne!(small.body, large.body);

    let missing = get(&app, "/api/samples/no-such-sample").await.error(StatusCode::NOT_FOUND);
    assert!(missing.contains("no-such-sample"), "{missing}");
    assert_healthy(&app).await;
}

#[tokio::test]
async fn uploads_of_each_kind_give_the_same_analysis() {
    let app = test_app();
    let entry = first_entry();
    let sample_json = serde_json::to_string(&entry.sample).unwrap();
    let by_json = post(&app, "/api/analyze", "application/json", sample_json.clone()).await;
    assert_eq!(by_json.status, StatusCode::OK, "{}", String::from_utf8_lossy(&by_json.body));
    let by_json = by_json.json();

    let (ct, body) = multipart(&[("sample", "napkin.json", &sample_json)]);
    let by_file = post(&app, "/api/analyze", &ct, body).await.json();

    let frames = &entry.sample.frames;
    let (start, end) = (text_frame(&frames[0]), text_frame(&frames[frames.len() - 1]));
    let (ct, body) = multipart(&[("start", "start.txt", &start), ("end", "end.txt", &end)]);
    let by_text = post(&app, "/api/analyze", &ct, body).await.json();

    // The analysis, flattened into the typed answer with what the app draws.
    for key in [
        "key",
        "name",
        "category",
        "frames",
        "n",
        "close",
        "folds",
        "start_border",
        "end_border",
        "images",
    ] {
        assert!(!by_json[key].is_null(), "missing {key}");
    }
    assert_eq!(by_json["close"]["folds"], by_json["folds"]);
    assert_eq!(by_json["name"], entry.sample.name.as_str());
    for v in [&by_file, &by_text] {
        assert_same(&v["folds"], &by_json["folds"], "folds");
        assert_same(&v["corners"], &by_json["corners"], "corners");
        assert_eq!(v["label"]["text"], by_json["label"]["text"]);
        assert_eq!(v["images"].as_object().map(|m| m.len()), Some(6));
    }
    assert_png(&app, by_text["images"]["diff"].as_str().unwrap()).await;
}

#[tokio::test]
async fn analyses_are_cached_by_content_and_frame_range() {
    let app = test_app();
    let body = serde_json::to_string(&first_entry().sample).unwrap();
    let first = post(&app, "/api/analyze", "application/json", body.clone()).await;
    let again = post(&app, "/api/analyze", "application/json", body.clone()).await;
    assert_eq!(first.body, again.body);
    let one_frame =
        post(&app, "/api/analyze?start=0&end=0", "application/json", body.clone()).await.json();
    assert_ne!(one_frame["key"], first.json()["key"]);
    assert_eq!(one_frame["folds"], json!([]));
    assert!(one_frame["metrics"].is_null());
    let bad_range =
        post(&app, "/api/analyze?start=0&end=99", "application/json", body.clone()).await;
    assert!(bad_range.error(StatusCode::BAD_REQUEST).contains("frame 99"));
    let bad_query = post(&app, "/api/analyze?start=abc", "application/json", body).await;
    assert!(bad_query.error(StatusCode::BAD_REQUEST).contains("start"));
}

// Issue 18 item 15: an answer's image URLs outlive its analysis in the cache. With room for
// 2 analyses and 4 drawings, the first upload's analysis is gone after 3 more, yet its
// pictures draw; the drawings cache is bounded too: 4 more later, its URLs are 404.
#[tokio::test]
async fn image_urls_outlive_the_analysis_cache() {
    let app = app(AppState::with_config(Config {
        cached_analyses: 2,
        cached_drawings: 4,
        ..Config::default()
    }));
    let entry = first_entry();
    let upload =
        |name: &str| json!({ "name": name, "category": "napkin", "frames": entry.sample.frames });
    let analyze = |name: String| {
        let (app, body) = (app.clone(), upload(&name));
        async move {
            let a = post_json(&app, "/api/analyze", &body).await;
            assert_eq!(a.status, StatusCode::OK, "{name}: {}", String::from_utf8_lossy(&a.body));
            a.json()
        }
    };
    let first = analyze("first".into()).await;
    for k in 0..3 {
        analyze(format!("pushes the first out {k}")).await;
    }
    let images = first["images"].as_object().expect("images");
    assert_eq!(images.len(), 6);
    for url in images.values() {
        assert_png(&app, url.as_str().expect("a URL")).await;
    }
    for k in 0..4 {
        analyze(format!("pushes the first drawing out {k}")).await;
    }
    let gone = get(&app, images["close"].as_str().expect("a URL")).await;
    assert!(
        gone.error(StatusCode::NOT_FOUND).contains("Upload the sample again"),
        "{}",
        String::from_utf8_lossy(&gone.body)
    );
}

/// A square border of `k` vertices a side, in frames.
fn square(k: usize) -> Vec<[f64; 3]> {
    let c = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
    (0..4 * k)
        .map(|v| {
            let (a, b, t) = (c[v / k], c[(v / k + 1) % 4], (v % k) as f64 / k as f64);
            [a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1), 0.0]
        })
        .collect()
}

#[tokio::test]
async fn bad_uploads_are_named_4xx_and_the_server_keeps_serving() {
    let app = test_app();
    let sq = json!(square(3));
    let cases: Vec<(&str, String, StatusCode, &str)> = vec![
        ("application/json", "this is not json".into(), StatusCode::BAD_REQUEST, "parse"),
        ("application/json", "".into(), StatusCode::BAD_REQUEST, "empty"),
        (
            "application/json",
            r#"{"frames": [[[NaN, 0, 0]]]}"#.into(),
            StatusCode::BAD_REQUEST,
            "parse",
        ),
        (
            "application/json",
            r#"{"frames": [[[1e400, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]]}"#.into(),
            StatusCode::BAD_REQUEST,
            "number",
        ),
        (
            "application/json",
            r#"{"frames": [[["a", 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]]}"#.into(),
            StatusCode::BAD_REQUEST,
            "parse",
        ),
        ("application/json", r#"{"name": "no frames"}"#.into(), StatusCode::BAD_REQUEST, "frames"),
        (
            "application/json",
            json!({"frames": [sq, square(2)]}).to_string(),
            StatusCode::UNPROCESSABLE_ENTITY,
            "frame 1 has 8 vertices",
        ),
        (
            "application/json",
            json!({"frames": [[[0, 0, 0], [1, 0, 0], [1, 1, 0]]]}).to_string(),
            StatusCode::UNPROCESSABLE_ENTITY,
            "too few",
        ),
        (
            "application/json",
            json!({"frames": [[[0, 0, 0], [1, 1, 0], [2, 2, 0], [3, 3, 0], [4, 4, 0]]]})
                .to_string(),
            StatusCode::UNPROCESSABLE_ENTITY,
            "degenerate",
        ),
        (
            "application/json",
            json!({"frames": [square(1300)]}).to_string(),
            StatusCode::PAYLOAD_TOO_LARGE,
            "5200 vertices",
        ),
        ("text/plain", "0,0,0".into(), StatusCode::UNSUPPORTED_MEDIA_TYPE, "text/plain"),
        ("", "0,0,0".into(), StatusCode::UNSUPPORTED_MEDIA_TYPE, "content type"),
    ];
    for (content_type, body, status, words) in cases {
        let request = Request::post("/api/analyze");
        let request = if content_type.is_empty() {
            request
        } else {
            request.header(header::CONTENT_TYPE, content_type)
        };
        let error = send(&app, request.body(Body::from(body.clone())).unwrap()).await.error(status);
        assert!(
            error.to_lowercase().contains(&words.to_lowercase()),
            "{body:.60}: {error:?} should name {words:?}"
        );
    }

    let (ct, body) = multipart(&[]);
    assert!(post(&app, "/api/analyze", &ct, body)
        .await
        .error(StatusCode::BAD_REQUEST)
        .contains("no file"));
    let (ct, body) = multipart(&[("frames", "a.txt", "0,0,0")]);
    assert!(post(&app, "/api/analyze", &ct, body)
        .await
        .error(StatusCode::BAD_REQUEST)
        .contains("\"frames\""));
    let (ct, body) = multipart(&[("end", "end.txt", "0,0,0")]);
    assert!(post(&app, "/api/analyze", &ct, body)
        .await
        .error(StatusCode::BAD_REQUEST)
        .contains("start"));
    let (ct, body) = multipart(&[
        ("start", "a.txt", "0,0,0\n1,0,0\n1,1,0\n0,1,0\n"),
        ("end", "b.txt", "0,0,0\nx,y\n"),
    ]);
    assert!(post(&app, "/api/analyze", &ct, body)
        .await
        .error(StatusCode::BAD_REQUEST)
        .contains("b.txt"));
    let (ct, body) = multipart(&[("sample", "cloth.xls", "…")]);
    assert!(post(&app, "/api/analyze", &ct, body)
        .await
        .error(StatusCode::BAD_REQUEST)
        .contains(".xls"));
    let broken = "--b\r\nContent-Disposition: form-data; name=\"sample\"\r\n\r\nunterminated";
    post(&app, "/api/analyze", "multipart/form-data; boundary=b", broken)
        .await
        .error(StatusCode::BAD_REQUEST);
    post(&app, "/api/analyze", "multipart/form-data", "no boundary")
        .await
        .error(StatusCode::BAD_REQUEST);

    let wrong_method = send(
        &app,
        Request::builder().method(Method::PUT).uri("/api/analyze").body(Body::empty()).unwrap(),
    )
    .await;
    assert!(wrong_method.error(StatusCode::METHOD_NOT_ALLOWED).contains("method"));
    assert_healthy(&app).await;
}

#[tokio::test]
async fn bodies_over_the_limit_are_413() {
    let app = app(AppState::with_config(Config { body_limit: 1024, ..Config::default() }));
    let big = json!({"frames": [square(100)]}).to_string();
    assert!(big.len() > 1024);
    // Announced by Content-Length: refused before reading.
    let announced = Request::post("/api/analyze")
        .header(header::CONTENT_TYPE, "application/json")
        .header(header::CONTENT_LENGTH, big.len())
        .body(Body::from(big.clone()))
        .unwrap();
    assert!(send(&app, announced).await.error(StatusCode::PAYLOAD_TOO_LARGE).contains("too large"));
    // No Content-Length (as when streamed): cut while reading.
    let unannounced = post(&app, "/api/analyze", "application/json", big.clone()).await;
    assert!(unannounced.error(StatusCode::PAYLOAD_TOO_LARGE).contains("too large"));
    let (ct, body) = multipart(&[("sample", "big.json", &big)]);
    assert!(post(&app, "/api/analyze", &ct, body)
        .await
        .error(StatusCode::PAYLOAD_TOO_LARGE)
        .contains("too large"));
    assert_healthy(&app).await;
}

#[tokio::test]
async fn unknown_pictures_and_analyses_are_404() {
    let app = test_app();
    let id = &first_entry().id;
    assert!(get(&app, &format!("/api/images/sample:{id}/rainbow.png"))
        .await
        .error(StatusCode::NOT_FOUND)
        .contains("rainbow"));
    assert!(get(&app, &format!("/api/images/sample:{id}/close.jpg"))
        .await
        .error(StatusCode::NOT_FOUND)
        .contains("close.jpg"));
    assert!(get(&app, "/api/images/0123abcd/close.png")
        .await
        .error(StatusCode::NOT_FOUND)
        .contains("0123abcd"));
    assert!(get(&app, "/api/images/sample:nope/close.png")
        .await
        .error(StatusCode::NOT_FOUND)
        .contains("nope"));
    assert!(get(&app, &format!("/api/images/sample:{id}/close.png?size=big"))
        .await
        .error(StatusCode::BAD_REQUEST)
        .contains("size"));
    assert_healthy(&app).await;
}

#[tokio::test]
async fn interpolation_moves_from_one_fold_to_the_other() {
    let app = test_app();
    let border = square(4);
    let a = post_json(
        &app,
        "/api/interpolate",
        &json!({"border": border, "from": [0.5, 3.6], "to": [1.0, 4.0], "steps": 9}),
    )
    .await;
    assert_eq!(a.status, StatusCode::OK, "{}", String::from_utf8_lossy(&a.body));
    let v = a.json();
    let folds: Vec<[f64; 2]> = serde_json::from_value(v["folds"].clone()).unwrap();
    let borders: Vec<Vec<[f64; 3]>> = serde_json::from_value(v["borders"].clone()).unwrap();
    assert_eq!((folds.len(), borders.len()), (9, 9));
    assert_eq!((folds[0], folds[8]), ([0.5, 3.6], [1.0, 4.0]));
    assert!(borders.iter().all(|b| b.len() == border.len()));
    assert_eq!(v["border_indices"], json!((0..border.len()).collect::<Vec<_>>()));
    // A folded state folds on against its flat reference, in its own vertex order.
    let on = post_json(&app, "/api/interpolate", &json!({"border": borders[8], "reference": border, "from": [1.0, 4.0], "to": [0.5, 3.0], "steps": 3})).await;
    assert_eq!(on.status, StatusCode::OK, "{}", String::from_utf8_lossy(&on.body));
    let motion = close::interpolate::Motion::Between {
        from: close::Fold::new(1.0, 4.0),
        to: close::Fold::new(0.5, 3.0),
    };
    let expected =
        close::interpolate::interpolate(borders[8].clone(), Some(border.clone()), &[], &motion, 3)
            .unwrap();
    assert_eq!(on.json()["borders"], json!(expected.borders));

    for (body, status, words) in [
        (
            json!({"border": border, "from": [0, 1], "to": [1, 2], "steps": 1}),
            StatusCode::BAD_REQUEST,
            "steps",
        ),
        (
            json!({"border": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "from": [0, 1], "to": [1, 2]}),
            StatusCode::UNPROCESSABLE_ENTITY,
            "too few",
        ),
        (json!({"border": border, "from": [0, 1]}), StatusCode::BAD_REQUEST, "`to`"),
        (
            json!({"border": square(2000), "from": [0, 1], "to": [1, 2], "steps": 1000}),
            StatusCode::PAYLOAD_TOO_LARGE,
            "steps",
        ),
    ] {
        let error = post_json(&app, "/api/interpolate", &body).await.error(status);
        assert!(error.contains(words), "{error:?} should name {words:?}");
    }
    assert!(post(&app, "/api/interpolate", "text/plain", "{}")
        .await
        .error(StatusCode::UNSUPPORTED_MEDIA_TYPE)
        .contains("application/json"));
    assert_healthy(&app).await;
}

/// The other form of `/api/interpolate`: a fold's arcs (an analysis step's `arcs` and `line`)
/// turned over, only they moving, ending on the reflection across the line.
#[tokio::test]
async fn interpolation_turns_a_folds_arcs_over() {
    let app = test_app();
    let border = square(4);
    // Corners 1 and 3 of the square (vertices 4 and 12 of 16) turned over the diagonal.
    let q = std::f64::consts::TAU / 16.0;
    let arcs = [[3.0 * q, 5.0 * q], [11.0 * q, 13.0 * q]];
    let line = json!({"point": [0.0, 0.0], "direction": [1.0, 1.0]});
    let a = post_json(
        &app,
        "/api/interpolate",
        &json!({"border": border, "arcs": arcs, "line": line, "steps": 5}),
    )
    .await;
    assert_eq!(a.status, StatusCode::OK, "{}", String::from_utf8_lossy(&a.body));
    let v = a.json();
    let borders: Vec<Vec<[f64; 3]>> = serde_json::from_value(v["borders"].clone()).unwrap();
    assert_eq!(borders.len(), 5);
    assert_eq!(v["turns"], json!([0.0, 0.25, 0.5, 0.75, 1.0]));
    assert_eq!(v["folds"], json!(vec![[3.0 * q, 13.0 * q]; 5]));
    let direction: [f64; 2] = serde_json::from_value(v["line"]["direction"].clone()).unwrap();
    assert!(
        direction.iter().all(|d| (d - std::f64::consts::FRAC_1_SQRT_2).abs() < 1e-15),
        "made unit: {direction:?}"
    );
    assert_eq!(borders[0], border);
    for (k, p) in border.iter().enumerate() {
        let end = borders[4][k];
        if k == 4 || k == 12 {
            assert!(
                (end[0] - p[1]).abs() < 1e-12 && (end[1] - p[0]).abs() < 1e-12,
                "vertex {k} mirrored: {end:?}"
            );
        } else {
            assert!(borders.iter().all(|b| b[k] == *p), "vertex {k} outside the arcs moved");
        }
    }
    for (body, words) in [
        (json!({"border": border, "arcs": arcs, "from": [0, 1], "to": [1, 2]}), "not both"),
        (json!({"border": border, "from": [0, 1], "to": [1, 2], "line": line}), "give `arcs`"),
        (json!({"border": border}), "give the folds"),
        (json!({"border": border, "arcs": []}), "at least one arc"),
        (
            json!({"border": border, "arcs": arcs, "line": {"point": [0, 0], "direction": [0, 0]}}),
            "no length",
        ),
    ] {
        let error = post_json(&app, "/api/interpolate", &body).await.error(StatusCode::BAD_REQUEST);
        assert!(error.contains(words), "{error:?} should name {words:?}");
    }
    let error = post_json(
        &app,
        "/api/interpolate",
        &json!({"border": border, "arcs": arcs, "line": {"point": [0, 0]}}),
    )
    .await
    .error(StatusCode::UNPROCESSABLE_ENTITY);
    assert!(error.contains("direction"), "{error:?}");
    assert_healthy(&app).await;
}

/// A motion after earlier folds (`prior`), at any fractions (`at`): its states are the
/// analysis's own at the ends, and each comes with the cloth as drawn (layers, heights, line).
#[tokio::test]
async fn interpolation_after_prior_folds_at_any_fraction_comes_with_its_layers() {
    let app = test_app();
    let entry =
        dataset::Dataset::builtin().get("napkin__half_then_half").expect("a second fold").clone();
    let analysis = analyze(&entry.sample.border_frames().unwrap(), FrameRange::default()).unwrap();
    let start: Vec<[f64; 3]> = analysis.start_border().iter().map(close::border::to_xyz).collect();
    let steps = serde_json::to_value(&analysis.steps).unwrap();
    let (first, second) = (&steps[0], &steps[1]);
    let body = json!({
        "border": start,
        "prior": [{"arcs": first["arcs"], "line": first["line"]}],
        "arcs": second["arcs"],
        "line": second["line"],
        "at": [1.0, 0.0, 0.5],
        "drawn": true,
    });
    let v = post_json(&app, "/api/interpolate", &body).await.json();
    let borders: Vec<Vec<[f64; 3]>> = serde_json::from_value(v["borders"].clone()).unwrap();
    assert_eq!((borders.len(), v["turns"].clone()), (3, json!([1.0, 0.0, 0.5])));
    // t = 1: the analysis's prediction; t = 0: the state the first fold left.
    let off = |a: &[[f64; 3]], b: &[[f64; 3]]| {
        a.iter().zip(b).map(|(p, q)| (p[0] - q[0]).hypot(p[1] - q[1])).fold(0.0, f64::max)
    };
    assert!(off(&borders[0], &analysis.predicted_end) < 1e-9);
    assert!(off(&borders[1], &analysis.steps[0].predicted) < 1e-9);
    let states = v["states"].as_array().expect("states");
    assert_eq!(states.len(), 3);
    // Folded twice: four layers at the end, two (base and flap) at its start.
    let flips = |k: usize| -> Vec<u64> {
        states[k]["layers"]
            .as_array()
            .unwrap()
            .iter()
            .map(|l| l["flips"].as_u64().unwrap())
            .collect()
    };
    assert_eq!(flips(0).len(), 4, "{:?}", flips(0));
    assert_eq!(flips(1), [0, 1]);
    let heights: Vec<f64> = serde_json::from_value(states[0]["heights"].clone()).unwrap();
    assert_eq!(heights.len(), analysis.n);
    assert!(heights.iter().any(|&h| h > 0.0), "turned layers lie above the table");
    assert!(states[2]["segment"].is_array(), "the fold's line: {}", states[2]["segment"]);
    // Not asked to draw, the answer is the motion's alone.
    let mut plain = body.clone();
    plain.as_object_mut().unwrap().remove("drawn");
    let plain = post_json(&app, "/api/interpolate", &plain).await.json();
    assert!(plain.get("states").is_none() && plain["borders"] == v["borders"]);
    for (body, words) in [
        (
            json!({"border": start, "from": [0, 1], "to": [1, 2], "steps": 3, "at": [0.5]}),
            "not both",
        ),
        (json!({"border": start, "from": [0, 1], "to": [1, 2], "at": [1.5]}), "from 0 to 1"),
        (json!({"border": start, "from": [0, 1], "to": [1, 2], "at": []}), "fractions"),
        (
            json!({"border": start, "reference": start, "prior": [], "from": [0, 1], "to": [1, 2]}),
            "`reference`",
        ),
        (json!({"border": start, "prior": [{"arcs": []}], "from": [0, 1], "to": [1, 2]}), "no arc"),
    ] {
        let error = post_json(&app, "/api/interpolate", &body).await.error(StatusCode::BAD_REQUEST);
        assert!(error.contains(words), "{error:?} should name {words:?}");
    }
    // A plan comes with the states it goes through as drawn: now, then one per step.
    let plan =
        post_json(&app, "/api/plan", &json!({"sample": entry.id, "goal": [0.3, 3.4]})).await.json();
    let states = plan["states"].as_array().expect("plan states");
    assert_eq!(states.len(), plan["steps"].as_array().unwrap().len() + 1);
    let now: Vec<[f64; 3]> = serde_json::from_value(states[0]["border"].clone()).unwrap();
    assert!(off(&now, &analysis.predicted_end) < 1e-9, "now is the analysed state");
    assert!(states.iter().skip(1).all(|s| s["segment"].is_array()));
    assert_healthy(&app).await;
}

#[tokio::test]
async fn plans_reach_the_goal_with_input_vertex_indices() {
    let app = test_app();
    let entry = first_entry();
    let goal = [0.3, 3.4];
    let by_id = post_json(&app, "/api/plan", &json!({"sample": entry.id, "goal": goal})).await;
    assert_eq!(by_id.status, StatusCode::OK, "{}", String::from_utf8_lossy(&by_id.body));
    let v = by_id.json();
    assert!(v["case"].as_str().is_some_and(|c| !c.is_empty()));
    let steps = v["steps"].as_array().expect("steps");
    assert!(!steps.is_empty());
    let n = entry.sample.frames[0].len() as u64;
    for step in steps {
        assert!(
            step["action"].is_string() && step["fold"].is_array() && step["corners"].is_array()
        );
        for pick in step["picks"].as_array().unwrap() {
            assert!(pick["vertex"].as_u64().is_some_and(|k| k < n));
            assert_eq!(pick["from"].as_array().map(Vec::len), Some(3));
        }
    }
    assert_eq!(v["border_indices"].as_array().map(Vec::len), Some(n as usize));
    let by_sample =
        post_json(&app, "/api/plan", &json!({"sample": entry.sample, "goal": goal})).await.json();
    assert_same(&by_sample["steps"], &v["steps"], "steps");
    // An upload is planned by its analysis key while the analysis is cached.
    let uploaded =
        post_json(&app, "/api/analyze", &serde_json::to_value(&entry.sample).unwrap()).await.json();
    let by_key = post_json(&app, "/api/plan", &json!({"sample": uploaded["key"], "goal": goal}))
        .await
        .json();
    assert_same(&by_key["steps"], &v["steps"], "steps");

    // The goal comes back in [0, 2π), as the steps; the current fold as the goal: nothing to do.
    let far = post_json(&app, "/api/plan", &json!({"sample": entry.id, "goal": [7.0, 100.0]}))
        .await
        .json();
    let wrapped: Vec<[f64; 2]> = serde_json::from_value(far["goal"].clone()).expect("the goal");
    let wrapped = wrapped[0];
    assert!(wrapped.iter().all(|g| (0.0..std::f64::consts::TAU).contains(g)), "{wrapped:?}");
    assert!((wrapped[0] - (7.0 - std::f64::consts::TAU)).abs() < 1e-12, "{wrapped:?}");
    let there = post_json(&app, "/api/plan", &json!({"sample": entry.id, "goal": v["folds"][0]}))
        .await
        .json();
    assert_eq!(
        (there["case"].as_str(), there["steps"].as_array().map(Vec::len)),
        (Some("already_there"), Some(0)),
        "{there}"
    );
    // Each current fold's line, as the analysis made it.
    assert_eq!(v["lines"].as_array().map(Vec::len), v["folds"].as_array().map(Vec::len));
    assert!(post_json(&app, "/api/plan", &json!({"sample": "nope", "goal": goal}))
        .await
        .error(StatusCode::NOT_FOUND)
        .contains("nope"));
    assert!(post_json(&app, "/api/plan", &json!({"sample": 7, "goal": goal}))
        .await
        .error(StatusCode::BAD_REQUEST)
        .contains("sample"));
    assert!(post_json(&app, "/api/plan", &json!({"sample": {"frames": 3}, "goal": goal}))
        .await
        .error(StatusCode::BAD_REQUEST)
        .contains("parse"));
    assert!(post_json(&app, "/api/plan", &json!({"sample": entry.id, "goal": [1]}))
        .await
        .error(StatusCode::UNPROCESSABLE_ENTITY)
        .contains("a goal fold [g1, g2] or a list of them"));
    // A goal of several folds is made in order; one of too many is refused.
    use std::f64::consts::PI;
    let flat = json!({"name": "flat", "frames": [square(8), square(8)]});
    let quarters = json!([[0.25 * PI, 1.25 * PI], [0.75 * PI, 1.75 * PI]]);
    let both =
        post_json(&app, "/api/plan", &json!({"sample": flat, "goal": quarters})).await.json();
    assert_eq!(both["case"], json!("fold"), "{both}");
    assert_eq!(both["steps"].as_array().map(Vec::len), Some(2), "{both}");
    assert_eq!(both["states"].as_array().map(Vec::len), Some(3), "{both}");
    // No goal fold: the flat cloth, which this one already is.
    let none = post_json(&app, "/api/plan", &json!({"sample": flat, "goal": []})).await.json();
    assert_eq!(none["case"], json!("already_there"), "{none}");
    let many = vec![[0.25 * PI, 1.25 * PI]; 100];
    assert!(post_json(&app, "/api/plan", &json!({"sample": flat, "goal": many}))
        .await
        .error(StatusCode::PAYLOAD_TOO_LARGE)
        .contains("goal folds"));
    assert_healthy(&app).await;
}

#[tokio::test]
async fn the_disk_of_any_border_state_is_a_png() {
    let app = test_app();
    let flat = square(5);
    let folded: Vec<Vec<[f64; 3]>> = serde_json::from_value(
        post_json(
            &app,
            "/api/interpolate",
            &json!({"border": flat, "from": [0.3, 0.3], "to": [0.3, 3.44], "steps": 3}),
        )
        .await
        .json()["borders"]
            .clone(),
    )
    .unwrap();
    let disk = async |body: Value| {
        let a = post_json(&app, "/api/disk", &body).await;
        assert_eq!(a.status, StatusCode::OK, "{}", String::from_utf8_lossy(&a.body));
        assert_eq!(a.content_type, "image/png");
        assert!(a.body.starts_with(b"\x89PNG\r\n\x1a\n"));
        a.body
    };
    let flat_png = disk(json!({"border": flat, "size": 200})).await;
    assert_eq!(
        flat_png,
        disk(json!({"border": flat, "size": 200})).await,
        "the same border, the same picture"
    );
    let half = disk(json!({"border": folded[1], "reference": flat, "size": 200})).await;
    let full = disk(json!({"border": folded[2], "reference": flat, "size": 200})).await;
    assert!(flat_png != half && half != full, "the disk follows the fold");
    // A sample's end frame against its start gives the analysis's end disk.
    let entry = first_entry();
    let analysis = analyze(&entry.sample.border_frames().unwrap(), FrameRange::default()).unwrap();
    let frames = &entry.sample.frames;
    let end =
        disk(json!({"border": frames[frames.len() - 1], "reference": frames[0], "size": 200}))
            .await;
    assert_eq!(
        end,
        close::render::render_disk(
            &analysis.disk(analysis.frames.len() - 1).unwrap(),
            "dGLI disk · current state",
            None,
            &close::render::Output::png(200)
        )
        .unwrap()
        .0
    );
    // The disk does not depend on where the cloth lies, but does on the picture's size.
    let shifted: Vec<[f64; 3]> = flat.iter().map(|p| [p[0] + 3.0, p[1] - 1.0, p[2]]).collect();
    assert_eq!(flat_png, disk(json!({"border": shifted, "size": 200})).await);
    assert_ne!(flat_png, disk(json!({"border": flat, "size": 120})).await);

    for (body, status, words) in [
        (
            json!({"border": [[0, 0, 0], [1, 0, 0], [0, 1, 0]]}),
            StatusCode::UNPROCESSABLE_ENTITY,
            "too few",
        ),
        (
            json!({"border": square(2), "reference": square(3)}),
            StatusCode::UNPROCESSABLE_ENTITY,
            "frame 1 has 8 vertices",
        ),
        (
            json!({"border": [[0, 0, 0], [1, 1, 0], [2, 2, 0], [3, 3, 0]]}),
            StatusCode::UNPROCESSABLE_ENTITY,
            "degenerate",
        ),
        (json!({"border": square(2000)}), StatusCode::PAYLOAD_TOO_LARGE, "vertices"),
        (json!({"border": [[0, 0]]}), StatusCode::UNPROCESSABLE_ENTITY, "border"),
        (json!({"size": 100}), StatusCode::UNPROCESSABLE_ENTITY, "border"),
        (json!({"border": flat, "colour": "red"}), StatusCode::UNPROCESSABLE_ENTITY, "colour"),
    ] {
        let error = post_json(&app, "/api/disk", &body).await.error(status);
        assert!(error.contains(words), "{error:?} should name {words:?}");
    }
    assert!(post(&app, "/api/disk", "application/json", "{\"border\": [[0, 0")
        .await
        .error(StatusCode::BAD_REQUEST)
        .contains("JSON"));
    assert!(post(&app, "/api/disk", "text/plain", "{}")
        .await
        .error(StatusCode::UNSUPPORTED_MEDIA_TYPE)
        .contains("application/json"));
    assert_healthy(&app).await;
}

#[cfg(not(feature = "rerun"))]
#[tokio::test]
async fn without_the_rerun_feature_recordings_are_404_saying_why() {
    let app = test_app();
    let id = &first_entry().id;
    let error =
        get(&app, &format!("/api/samples/{id}/recording.rrd")).await.error(StatusCode::NOT_FOUND);
    assert!(error.contains("without the `rerun` feature"), "{error}");
    assert!(
        get(&app, &format!("/api/samples/{id}")).await.json().get("recording").is_none(),
        "no download offered"
    );
    assert_healthy(&app).await;
}

#[cfg(feature = "rerun")]
#[tokio::test]
async fn a_sample_recording_downloads_as_rrd() {
    use rerun::external::re_log_encoding::DecoderApp;
    use rerun::log::{Chunk, LogMsg};

    let app = test_app();
    let id = &first_entry().id;
    let url = format!("/api/samples/{id}/recording.rrd");
    assert_eq!(get(&app, &format!("/api/samples/{id}")).await.json()["recording"], url.as_str());
    let a = get(&app, &url).await;
    assert_eq!(a.status, StatusCode::OK, "{}", String::from_utf8_lossy(&a.body));
    assert_eq!(a.content_type, "application/octet-stream");
    assert!(a.body.starts_with(b"RRF2") && a.body.len() > 1000, "{} bytes", a.body.len());
    // It decodes, with the borders and the disks in it.
    let entities: Vec<String> = DecoderApp::decode_eager(&a.body[..])
        .expect("an RRD stream")
        .filter_map(|msg| match msg.expect("a decodable message") {
            LogMsg::ArrowMsg(_, arrow) => {
                Some(Chunk::from_arrow_msg(&arrow).expect("a chunk").entity_path().to_string())
            }
            _ => None,
        })
        .collect();
    for expected in ["/border", "/fold/1/line", "/disk/start"] {
        assert!(entities.iter().any(|e| e == expected), "{expected} missing from {entities:?}");
    }
    assert_eq!(get(&app, &url).await.body, a.body, "cached");
    assert!(get(&app, "/api/samples/nope/recording.rrd")
        .await
        .error(StatusCode::NOT_FOUND)
        .contains("nope"));
    assert_healthy(&app).await;
}

/// A Wavefront OBJ of one mesh frame (1-based faces).
fn obj(vertices: &[[f64; 3]], faces: &[Vec<usize>]) -> String {
    let v = vertices.iter().map(|p| format!("v {} {} {}\n", p[0], p[1], p[2]));
    let f = faces.iter().map(|f| {
        format!("f {}\n", f.iter().map(|k| (k + 1).to_string()).collect::<Vec<_>>().join(" "))
    });
    v.chain(f).collect()
}

#[tokio::test]
async fn mesh_uploads_name_how_their_border_was_found() {
    let app = test_app();
    let dataset = dataset::Dataset::builtin();
    let entry =
        dataset.entries().iter().find(|e| e.sample.mesh.is_some()).expect("a built-in mesh sample");
    let mesh = entry.sample.mesh.as_ref().unwrap();
    let (f0, f1) = (obj(&mesh.frames[0], &mesh.faces), obj(&mesh.frames[1], &mesh.faces));
    let (ct, body) = multipart(&[("sample", "frame0.obj", &f0), ("sample", "frame1.obj", &f1)]);
    let a = post(&app, "/api/analyze", &ct, body).await;
    assert_eq!(a.status, StatusCode::OK, "{}", String::from_utf8_lossy(&a.body));
    let v = a.json();
    assert_eq!(v["border_source"], "mesh boundary loop");
    assert_eq!(v["frames"], 2);
    // The same analysis as the built-in sample's, border indices being mesh vertices.
    let builtin = get(&app, &format!("/api/samples/{}", entry.id)).await.json();
    for key in ["n", "corners", "folds", "border_indices", "border_source"] {
        assert_same(&v[key], &builtin[key], key);
    }
    assert!(v["border_indices"]
        .as_array()
        .unwrap()
        .iter()
        .all(|k| k.as_u64().is_some_and(|k| (k as usize) < mesh.frames[0].len())));
    assert_png(&app, v["images"]["signed_diff"].as_str().unwrap()).await;

    // A frame with other vertices is named, as is a mesh with no face.
    let (ct, body) = multipart(&[
        ("sample", "frame0.obj", &f0),
        ("sample", "short.obj", &obj(&mesh.frames[1][1..], &mesh.faces[..1])),
    ]);
    assert!(post(&app, "/api/analyze", &ct, body)
        .await
        .error(StatusCode::UNPROCESSABLE_ENTITY)
        .contains("short.obj"));
    let (ct, body) = multipart(&[("sample", "points.obj", &obj(&mesh.frames[0], &[]))]);
    assert!(post(&app, "/api/analyze", &ct, body)
        .await
        .error(StatusCode::UNPROCESSABLE_ENTITY)
        .contains("no face"));
    assert_healthy(&app).await;
}

/// A folder holding copies of two physics fixtures (a single fold and a fold sequence, both
/// with their truth), as `close serve --dataset` would be given.
fn physics_folder(name: &str) -> std::path::PathBuf {
    let folder = std::env::temp_dir().join(format!("close-http-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&folder);
    std::fs::create_dir_all(&folder).expect("a scratch folder");
    let fixtures = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/physics");
    for file in ["h1_half_left_onto_right_31x31.json", "q3_napkin_half_then_quarter_31x31.json"] {
        std::fs::copy(fixtures.join(file), folder.join(file)).expect("copy a fixture");
    }
    folder
}

#[tokio::test]
async fn dataset_samples_are_rows_analyses_pictures_and_plans_like_built_in_ones() {
    let folder = physics_folder("dataset");
    let app =
        app(AppState::with_config(Config { datasets: vec![folder.clone()], ..Config::default() }));
    let list = get(&app, "/api/samples").await.json();
    let rows = list["samples"].as_array().expect("rows");
    let keys = |row: &Value| {
        row.as_object().map(|o| o.keys().cloned().collect::<Vec<_>>()).unwrap_or_default()
    };
    let builtin = rows.iter().find(|r| r["source"] == "builtin").expect("a built-in row");
    let ours: Vec<&Value> =
        rows.iter().filter(|r| r["source"] == folder.display().to_string().as_str()).collect();
    assert_eq!(ours.len(), 2, "{ours:?}");
    for row in &ours {
        // One shape for every source.
        assert_eq!(keys(row), keys(builtin), "{row} / {builtin}");
        assert!(row["error"].is_null() && row["n"].as_u64() > Some(0), "{row}");
        assert_png(&app, row["thumbnail"].as_str().expect("a thumbnail URL")).await;
    }
    // The sequence is filed as the built-in sequences are.
    let sequence = ours.iter().find(|r| r["frames"] == 3).expect("the three-frame sample");
    assert_eq!(sequence["category"], "napkin_second_fold");
    let in_category = rows.iter().filter(|r| r["category"] == "napkin_second_fold").count();
    let counted = list["categories"]
        .as_array()
        .expect("categories")
        .iter()
        .find(|c| c["name"] == "napkin_second_fold")
        .map(|c| c["count"].clone());
    assert_eq!(counted, Some(json!(in_category)));

    // Analysed as a built-in sample is: its id, its sample, its truth, its provenance.
    let id = sequence["id"].as_str().expect("id");
    let analysis = get(&app, &format!("/api/samples/{id}")).await.json();
    assert_eq!(
        (analysis["id"].as_str(), analysis["source"].as_str()),
        (Some(id), Some(folder.display().to_string().as_str()))
    );
    assert_eq!(
        analysis["truth"]["folds"].as_array().map(Vec::len),
        Some(2),
        "{}",
        analysis["truth"]
    );
    for url in analysis["images"].as_object().expect("images").values() {
        assert_png(&app, url.as_str().expect("a URL")).await;
    }
    // The truth is drawn beside the found folds, with the angle errors (item 12).
    let circle = get(&app, &format!("/api/images/sample:{id}/close.png?format=svg")).await;
    let circle = String::from_utf8_lossy(&circle.body);
    assert!(
        circle.matches(" · ○ ").count() == 2 && circle.matches("° off").count() == 2,
        "{}",
        &circle[circle.len().saturating_sub(3000)..]
    );
    let borders = get(&app, &format!("/api/images/sample:{id}/borders.png?format=svg")).await;
    let borders = String::from_utf8_lossy(&borders.body);
    assert!(
        borders.contains(">fold 1 (true: ")
            && borders.contains(">fold 2 (true: ")
            && borders.matches("° off").count() == 2,
        "{}",
        &borders[borders.len().saturating_sub(3000)..]
    );
    // Planned by its id.
    let plan = post_json(&app, "/api/plan", &json!({ "sample": id, "goal": [0.5, 3.5] })).await;
    assert_eq!(plan.status, StatusCode::OK, "{}", String::from_utf8_lossy(&plan.body));
    assert_eq!(plan.json()["folds"], analysis["folds"]);
    let unknown =
        post_json(&app, "/api/plan", &json!({ "sample": "d0-nothing", "goal": [0.5, 3.5] })).await;
    assert!(unknown.error(StatusCode::NOT_FOUND).contains("GET /api/samples lists them"));
    let builtin =
        get(&app, &format!("/api/samples/{}", builtin["id"].as_str().expect("id"))).await.json();
    assert_eq!(builtin["source"], "builtin");
    std::fs::remove_dir_all(&folder).expect("clean up");
}

#[tokio::test]
async fn an_upload_keeps_its_truth_and_says_it_is_an_upload() {
    let app = test_app();
    let folder = physics_folder("upload");
    let body =
        std::fs::read(folder.join("h1_half_left_onto_right_31x31.json")).expect("the fixture");
    let given: Value = serde_json::from_slice(&body).expect("JSON");
    let a = post(&app, "/api/analyze", "application/json", body).await;
    assert_eq!(a.status, StatusCode::OK, "{}", String::from_utf8_lossy(&a.body));
    let a = a.json();
    assert_eq!(a["source"], "upload");
    assert_eq!(a["truth"]["folds"], given["truth"]["folds"]);
    // Without a truth there is none in the answer.
    let entry = first_entry();
    let bare = json!({ "name": "bare", "frames": entry.sample.frames });
    let b = post_json(&app, "/api/analyze", &bare).await.json();
    assert!(b.get("truth").is_none(), "{}", b["truth"]);
    std::fs::remove_dir_all(&folder).expect("clean up");
}

#[tokio::test]
async fn every_picture_is_also_an_svg_of_the_same_drawing() {
    let app = test_app();
    let entry = first_entry();
    let analysis = get(&app, &format!("/api/samples/{}", entry.id)).await.json();
    for (name, url) in analysis["images"].as_object().expect("images") {
        let url = url.as_str().expect("a URL");
        let svg = get(&app, &format!("{url}&format=svg")).await;
        assert_eq!(
            (svg.status, svg.content_type.as_str()),
            (StatusCode::OK, "image/svg+xml"),
            "{name}"
        );
        let text = String::from_utf8_lossy(&svg.body);
        // Text stays text, lines stay lines; the fills are the PNG's pixels under them.
        assert!(
            text.starts_with("<svg") && text.trim_end().ends_with("</svg>"),
            "{name}: {}",
            &text[..text.len().min(200)]
        );
        assert!(text.contains("<text") && text.contains("<polyline"), "{name}");
        // The border plot is drawn in strokes and text alone (its axes too): no pixels.
        assert_eq!(text.contains("data:image/png;base64,"), name != "borders", "{name}");
        assert_png(&app, url).await;
    }
    let thumbnail = format!("/api/images/sample:{}/thumbnail.png?format=svg", entry.id);
    assert_eq!(get(&app, &thumbnail).await.content_type, "image/svg+xml");
    let bad = get(&app, &format!("/api/images/sample:{}/close.png?format=gif", entry.id)).await;
    assert!(
        bad.error(StatusCode::BAD_REQUEST).contains("format"),
        "{}",
        String::from_utf8_lossy(&bad.body)
    );
    // A PNG for print states its resolution: pHYs, 300 dpi = 11811 pixels per metre.
    let print = get(&app, &format!("/api/images/sample:{}/borders.png?dpi=300", entry.id)).await;
    let at = print.body.windows(4).position(|w| w == b"pHYs").expect("a pHYs chunk");
    let per_metre = u32::from_be_bytes(print.body[at + 4..at + 8].try_into().expect("4 bytes"));
    assert_eq!(per_metre, 11811);
    let bad = get(&app, &format!("/api/images/sample:{}/borders.png?dpi=5", entry.id)).await;
    assert!(bad.error(StatusCode::BAD_REQUEST).contains("72 to 1200 dots per inch"));
}

#[tokio::test]
async fn a_readout_gives_the_disks_values_and_where_the_pictures_draw_them() {
    let app = test_app();
    let entry = dataset::Dataset::builtin()
        .get("napkin__half_then_half")
        .expect("a built-in second fold")
        .clone();
    let analysis = analyze(&entry.sample.border_frames().unwrap(), FrameRange::default()).unwrap();
    // Values come ring by ring (close::render::readout::rings).
    let close_to = |got: &Value, want: &close::disk::Disk| {
        let got: Vec<f64> = serde_json::from_value(got.clone()).expect("numbers");
        let want = close::render::readout::rings(want);
        got.len() == want.len()
            && got
                .iter()
                .zip(&want)
                .all(|(a, &b)| (a - b as f64).abs() <= 1e-6 * (b as f64).abs().max(1e-3))
    };
    // Step 2 compares analysed frames 1 and 2; the whole span, the first and the last.
    for (step, (from, to)) in [("&step=2", (1, 2)), ("", (0, 2))] {
        let r = get(&app, &format!("/api/readout/sample:{}?size=300{step}", entry.id)).await.json();
        assert_eq!(
            (r["n"].as_u64(), r["from_frame"].as_u64(), r["to_frame"].as_u64()),
            (Some(analysis.n as u64), Some(from as u64), Some(to as u64))
        );
        assert!(
            close_to(&r["start"], &analysis.disk(from).unwrap())
                && close_to(&r["end"], &analysis.disk(to).unwrap()),
            "step {step:?}"
        );
        let layout = close::render::disk_picture::Layout::of(300, 300);
        assert_eq!(r["disk"], json!({ "cx": layout.cx, "cy": layout.cy, "radius": layout.radius }));
        assert!(
            r["borders"]["y"][0].as_f64().is_some_and(|a| a < 0.0),
            "pixels grow downwards: {}",
            r["borders"]
        );
    }
    let error = get(&app, &format!("/api/readout/sample:{}?step=3", entry.id))
        .await
        .error(StatusCode::BAD_REQUEST);
    assert!(error.contains("step 3"), "{error}");
    assert!(get(&app, "/api/readout/0123abcd")
        .await
        .error(StatusCode::NOT_FOUND)
        .contains("Upload the sample again"));
    assert!(get(&app, &format!("/api/readout/sample:{}?colour=red", entry.id))
        .await
        .error(StatusCode::BAD_REQUEST)
        .contains("colour"));

    // One state's cells: the end frame against the start is the analysis's end disk.
    let frames = &entry.sample.frames;
    let cells = post_json(
        &app,
        "/api/disk/cells",
        &json!({ "border": frames[frames.len() - 1], "reference": frames[0], "size": 200 }),
    )
    .await
    .json();
    assert!(close_to(&cells["values"], &analysis.disk(analysis.frames.len() - 1).unwrap()));
    // Which cell each pixel shows: the cell picture of that N and size.
    let picture = get(&app, &format!("/api/cells.png?n={}&size=200", analysis.n)).await;
    assert_eq!((picture.status, picture.content_type.as_str()), (StatusCode::OK, "image/png"));
    assert_eq!(picture.body, close::render::readout::cell_picture(analysis.n, 200).unwrap());
    assert!(get(&app, "/api/cells.png?n=2").await.error(StatusCode::BAD_REQUEST).contains("edges"));
    assert_eq!(
        cells["disk"]["cx"].as_f64(),
        Some(close::render::disk_picture::Layout::of(200, 200).cx)
    );
    let many: Vec<[f64; 3]> = (0..1500)
        .map(|k| (k as f64 * std::f64::consts::TAU / 1500.0).sin_cos())
        .map(|(s, c)| [c, s, 0.0])
        .collect();
    assert!(post_json(&app, "/api/disk/cells", &json!({ "border": many }))
        .await
        .error(StatusCode::PAYLOAD_TOO_LARGE)
        .contains("disk values"));
    assert!(post_json(
        &app,
        "/api/disk/cells",
        &json!({ "border": [[0, 0, 0], [1, 0, 0], [0, 1, 0]] })
    )
    .await
    .error(StatusCode::UNPROCESSABLE_ENTITY)
    .contains("too few"));
    assert_healthy(&app).await;
}

#[tokio::test]
async fn verify_answers_reached_or_what_to_do_and_distance_measures() {
    let app = test_app();
    let entry = first_entry();
    let analysed = get(&app, &format!("/api/samples/{}", entry.id)).await.json();
    let observed = analysed["folds"].clone();
    // Its own folds: reached, at distance 0; by id, by sample and by analysis key alike.
    let by_id =
        post_json(&app, "/api/verify", &json!({"sample": entry.id, "goal": observed})).await.json();
    assert_eq!(by_id["reached"], true, "{by_id}");
    assert_eq!(by_id["distance"]["folds"], 0.0);
    assert!(by_id["text"].as_str().unwrap().starts_with("goal reached"));
    let by_sample =
        post_json(&app, "/api/verify", &json!({"sample": entry.sample, "goal": observed}))
            .await
            .json();
    assert_same(&by_sample["folds"], &by_id["folds"], "folds");
    // Another goal: not reached, with a plan and the share of the border it is away.
    let goal = json!([[0.3, 3.4]]);
    let other = post_json(
        &app,
        "/api/verify",
        &json!({"sample": entry.id, "goal": goal, "tolerance": {"edges": 0.5}}),
    )
    .await
    .json();
    assert_eq!(other["reached"], false);
    assert_eq!(other["tolerance"]["edges"], 0.5);
    assert_eq!(other["tolerance"]["aligned_rmse"], 0.03);
    assert!(other["distance"]["folds"].as_f64().unwrap() > 0.0);
    assert!(other["plan"]["steps"].is_array(), "{other}");
    for (body, status, words) in [
        (json!({"sample": entry.id, "goal": [[1.0, 1.0]]}), StatusCode::BAD_REQUEST, "more than"),
        (json!({"sample": entry.id, "goal": [1.0, 2.0]}), StatusCode::UNPROCESSABLE_ENTITY, "goal"),
        (json!({"sample": "nope", "goal": goal}), StatusCode::NOT_FOUND, "nope"),
        (
            json!({"sample": entry.id, "goal": goal, "tolerance": {"edges": -1}}),
            StatusCode::BAD_REQUEST,
            "tolerance",
        ),
        (
            json!({"sample": entry.id, "goal": goal, "lines": [{"point": [0, 0], "direction": [0, 0]}]}),
            StatusCode::BAD_REQUEST,
            "direction",
        ),
    ] {
        let error = post_json(&app, "/api/verify", &body).await.error(status);
        assert!(error.contains(words), "{body}: {error:?} should name {words:?}");
    }

    // The distance: one fold point an edge off on a 16-vertex square is 1/16 of the border.
    let edge = std::f64::consts::TAU / 16.0;
    let square: Vec<[f64; 3]> = (0..16)
        .map(|k| {
            let t = (k % 4) as f64 / 4.0;
            let [x, y] = [[t, 0.0], [1.0, t], [1.0 - t, 1.0], [0.0, 1.0 - t]][k / 4];
            [x, y, 0.0]
        })
        .collect();
    let d = post_json(
        &app,
        "/api/distance",
        &json!({"a": [[0.0, 8.0 * edge]], "b": [[edge, 8.0 * edge]], "border": square}),
    )
    .await
    .json();
    assert!((d["folds"].as_f64().unwrap() - 1.0 / 16.0).abs() < 1e-12, "{d}");
    assert!(d["geometric"].as_f64().unwrap() > 0.0);
    let without =
        post_json(&app, "/api/distance", &json!({"a": [], "b": [[0.0, 8.0 * edge]]})).await.json();
    assert_eq!((without["folds"].as_f64(), without["geometric"].is_null()), (Some(0.5), true));
    assert!(post_json(&app, "/api/distance", &json!({"a": [[0, "x"]], "b": []}))
        .await
        .error(StatusCode::UNPROCESSABLE_ENTITY)
        .contains("a"));
    let short = post_json(
        &app,
        "/api/distance",
        &json!({"a": [], "b": [], "border": [[0, 0, 0], [1, 0, 0], [0, 1, 0]]}),
    )
    .await;
    assert!(short.error(StatusCode::UNPROCESSABLE_ENTITY).contains("too few"), "{}", short.json());
    assert_healthy(&app).await;
}
