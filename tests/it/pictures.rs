//! The picture routes the web app relies on: per-step disk pictures
//! (`/api/images/{key}/{picture}.png?step=k`) and a disk colour scale kept through an
//! animation (`POST /api/disk` with `scale`, answered in `x-disk-scale`); and the fold
//! curves drawn on a step's diff end at the fold points the step reports; a mesh sample's
//! mesh picture; `POST /api/disk?format=svg`.

use axum::body::{to_bytes, Body};
use axum::http::{header, Method, Request, StatusCode};
use axum::Router;
use serde_json::{json, Value};
use tower::ServiceExt;

use close::server::{app, AppState};

async fn send(app: &Router, request: Request<Body>) -> (StatusCode, Option<String>, Vec<u8>) {
    let (status, _, scale, body) = send_typed(app, request).await;
    (status, scale, body)
}

/// The answer's status, content type, `x-disk-scale` header and body.
async fn send_typed(
    app: &Router,
    request: Request<Body>,
) -> (StatusCode, String, Option<String>, Vec<u8>) {
    let response = app.clone().oneshot(request).await.expect("the router never fails");
    let status = response.status();
    let header =
        |name: &str| response.headers().get(name).and_then(|v| v.to_str().ok()).map(str::to_string);
    let (kind, scale) = (header("content-type").unwrap_or_default(), header("x-disk-scale"));
    (
        status,
        kind,
        scale,
        to_bytes(response.into_body(), usize::MAX).await.expect("a body").to_vec(),
    )
}

/// Whether `text` is well-formed XML as far as an SVG picture needs: one root element,
/// every tag closed in order, attribute values quoted, no bare `<` or `&` in text.
fn well_formed(text: &str) -> Result<(), String> {
    let mut open: Vec<&str> = Vec::new();
    let mut rest = text.trim();
    let mut roots = 0;
    while let Some(start) = rest.find('<') {
        let between = &rest[..start];
        if between.contains('<')
            || between
                .replace("&amp;", "")
                .replace("&lt;", "")
                .replace("&gt;", "")
                .replace("&quot;", "")
                .contains('&')
        {
            return Err(format!("bare markup in text {between:?}"));
        }
        let end = rest[start..].find('>').ok_or("an unclosed tag")? + start;
        let tag = &rest[start + 1..end];
        if !tag.matches('"').count().is_multiple_of(2) {
            return Err(format!("unbalanced quotes in <{tag}>"));
        }
        if let Some(name) = tag.strip_prefix('/') {
            match open.pop() {
                Some(top) if top == name => {}
                other => return Err(format!("</{name}> closes {other:?}")),
            }
        } else {
            if open.is_empty() {
                roots += 1;
            }
            let name = tag.split_whitespace().next().unwrap_or_default().trim_end_matches('/');
            if !tag.ends_with('/') {
                open.push(name);
            }
        }
        rest = &rest[end + 1..];
    }
    match (open.is_empty(), roots, rest.trim().is_empty()) {
        (true, 1, true) => Ok(()),
        _ => Err(format!("{} elements left open, {roots} roots", open.len())),
    }
}

#[test]
fn the_xml_check_finds_broken_documents() {
    assert_eq!(well_formed(r#"<svg a="1"><text x="2">a &amp; b</text><image/></svg>"#), Ok(()));
    for bad in [
        "<svg><text></svg>",
        r#"<svg a="1><x/></svg>"#,
        "<svg>a & b</svg>",
        "<svg/><svg/>",
        "<svg>",
    ] {
        assert!(well_formed(bad).is_err(), "{bad}");
    }
}

/// The id of the first built-in mesh sample in the list.
async fn a_mesh_sample(app: &Router) -> String {
    let (_, body) = get(app, "/api/samples").await;
    let rows: Value = serde_json::from_slice(&body).expect("the sample list");
    let rows =
        rows.as_array().cloned().or_else(|| rows["samples"].as_array().cloned()).expect("rows");
    rows.iter()
        .find(|r| r["category"] == "mesh")
        .and_then(|r| r["id"].as_str())
        .expect("a mesh sample")
        .to_string()
}

#[tokio::test]
async fn a_mesh_sample_shows_its_mesh_as_png_and_svg() {
    let app = app(AppState::new());
    let id = a_mesh_sample(&app).await;
    let (status, body) = get(&app, &format!("/api/samples/{id}")).await;
    assert_eq!(status, StatusCode::OK);
    let analysis: Value = serde_json::from_slice(&body).expect("the analysis");
    let url = analysis["images"]["mesh"]
        .as_str()
        .unwrap_or_else(|| panic!("{id} lists no mesh picture: {}", analysis["images"]))
        .to_string();
    let (status, kind, _, png) =
        send_typed(&app, Request::get(&url).body(Body::empty()).expect("request")).await;
    assert_eq!((status, kind.as_str()), (StatusCode::OK, "image/png"));
    assert!(is_png(&png));
    let (status, kind, _, svg) = send_typed(
        &app,
        Request::get(format!("{url}&format=svg")).body(Body::empty()).expect("request"),
    )
    .await;
    assert_eq!((status, kind.as_str()), (StatusCode::OK, "image/svg+xml"));
    let svg = String::from_utf8(svg).expect("UTF-8");
    well_formed(&svg).unwrap_or_else(|e| panic!("{e}"));
    // The border loop is a vector line; the filled faces the pixels under it.
    assert!(
        svg.contains("<polyline")
            && svg.contains("data:image/png;base64,")
            && svg.contains("height z")
    );

    // A border sample has no mesh to show: its analysis lists none, and asking says why.
    let (_, body) = get(&app, "/api/samples/napkin__half_then_half").await;
    let border: Value = serde_json::from_slice(&body).expect("the analysis");
    assert!(border["images"].get("mesh").is_none(), "{}", border["images"]);
    assert!(border["images"].get("borders").is_some());
    let (status, body) = get(&app, "/api/images/sample:napkin__half_then_half/mesh.png").await;
    assert_eq!(status, StatusCode::BAD_REQUEST);
    assert!(
        String::from_utf8_lossy(&body).contains("mesh samples only"),
        "{}",
        String::from_utf8_lossy(&body)
    );
}

#[tokio::test]
async fn a_disk_answers_svg_when_asked() {
    let app = app(AppState::new());
    let square = square();
    let disk = |format: &str| {
        Request::builder()
            .method(Method::POST)
            .uri(format!("/api/disk{format}"))
            .header(header::CONTENT_TYPE, "application/json")
            .body(Body::from(json!({ "border": square, "size": 200 }).to_string()))
            .expect("request")
    };
    let (status, kind, png_scale, png) = send_typed(&app, disk("")).await;
    assert_eq!((status, kind.as_str()), (StatusCode::OK, "image/png"));
    assert!(is_png(&png));
    let (status, kind, svg_scale, svg) = send_typed(&app, disk("?format=svg")).await;
    assert_eq!((status, kind.as_str()), (StatusCode::OK, "image/svg+xml"));
    // The same drawing: the same scale, and the text is text.
    assert_eq!(png_scale, svg_scale);
    let svg = String::from_utf8(svg).expect("UTF-8");
    well_formed(&svg).unwrap_or_else(|e| panic!("{e}"));
    assert!(svg.contains("<text") && svg.contains("dGLI disk"), "{}", &svg[..svg.len().min(300)]);
    let (status, _, _, body) = send_typed(&app, disk("?format=gif")).await;
    assert_eq!(status, StatusCode::BAD_REQUEST, "{}", String::from_utf8_lossy(&body));
}

async fn get(app: &Router, uri: &str) -> (StatusCode, Vec<u8>) {
    let (status, _, body) =
        send(app, Request::get(uri).body(Body::empty()).expect("request")).await;
    (status, body)
}

async fn post_disk(app: &Router, body: &Value) -> (StatusCode, Option<String>, Vec<u8>) {
    let request = Request::builder()
        .method(Method::POST)
        .uri("/api/disk")
        .header(header::CONTENT_TYPE, "application/json")
        .body(Body::from(body.to_string()))
        .expect("request");
    send(app, request).await
}

fn is_png(body: &[u8]) -> bool {
    body.starts_with(b"\x89PNG")
}

#[tokio::test]
async fn a_second_fold_has_pictures_per_step() {
    let app = app(AppState::new());
    let key = "sample:napkin__half_then_half";
    // The fold circle follows the step too (its other step's fold faded).
    for picture in ["disk_start", "disk_end", "diff", "signed_diff", "close"] {
        let (_, whole) = get(&app, &format!("/api/images/{key}/{picture}.png?size=120")).await;
        let (s1, one) =
            get(&app, &format!("/api/images/{key}/{picture}.png?size=120&step=1")).await;
        let (s2, two) =
            get(&app, &format!("/api/images/{key}/{picture}.png?size=120&step=2")).await;
        assert_eq!((s1, s2), (StatusCode::OK, StatusCode::OK), "{picture}");
        assert!(is_png(&one) && is_png(&two));
        assert_ne!(one, two, "{picture}: steps 1 and 2 drew the same picture");
        assert_ne!(whole, two, "{picture}: step 2 is the whole analysis");
    }
    let (status, body) = get(&app, &format!("/api/images/{key}/diff.png?step=3")).await;
    assert_eq!(status, StatusCode::BAD_REQUEST);
    let error: Value = serde_json::from_slice(&body).expect("a JSON error");
    assert!(
        error["error"].as_str().is_some_and(|e| e.contains("step 3") && e.contains("1…2")),
        "{error}"
    );
    let (status, _) = get(&app, &format!("/api/images/{key}/thumbnail.png?step=1")).await;
    assert_eq!(status, StatusCode::BAD_REQUEST);
    // The list's thumbnails are their own small drawing.
    let (status, body) = get(&app, &format!("/api/images/{key}/thumbnail.png?size=100")).await;
    assert!(status == StatusCode::OK && is_png(&body));
}

/// A unit square border of 16 vertices.
fn square() -> Vec<[f64; 3]> {
    (0..16)
        .map(|k| {
            let (side, t) = (k / 4, (k % 4) as f64 / 4.0);
            let c = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
            let (a, b) = (c[side], c[(side + 1) % 4]);
            [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), 0.0]
        })
        .collect()
}

#[tokio::test]
async fn a_disk_keeps_the_scale_it_is_given() {
    let app = app(AppState::new());
    let square = square();
    let (status, scale, own) = post_disk(&app, &json!({ "border": square, "size": 100 })).await;
    assert_eq!(status, StatusCode::OK);
    let scale = scale.expect("the x-disk-scale header");
    let parts: Vec<f64> = scale.split(' ').map(|v| v.parse().expect("a number")).collect();
    assert!(parts.len() == 2 && parts[0] > 0.0 && parts[1] > 0.0, "{scale}");
    // The same scale sent back draws the same picture; another scale another one.
    let (_, again, same) = post_disk(
        &app,
        &json!({ "border": square, "size": 100, "scale": { "s": parts[0], "max": parts[1] } }),
    )
    .await;
    assert_eq!(again.as_deref(), Some(scale.as_str()));
    assert_eq!(own, same);
    let (_, other_scale, other) = post_disk(&app, &json!({ "border": square, "size": 100, "scale": { "s": 10.0 * parts[0], "max": parts[1] } })).await;
    assert_ne!(own, other);
    assert_eq!(other_scale, Some(format!("{} {}", 10.0 * parts[0], parts[1])));
    let (status, _, body) =
        post_disk(&app, &json!({ "border": square, "scale": { "s": 0.0, "max": 1.0 } })).await;
    assert_eq!(status, StatusCode::BAD_REQUEST, "{}", String::from_utf8_lossy(&body));
}

/// In every fold step of the built-in set, each reported fold point ends one of the step's
/// curves, those drawn on its diff disk (before, 50 of 173 steps had a fold point more than
/// 10° from every curve drawn: the curves were the free fits, not the fold's). A curve
/// fitted through a fold point ends there by construction (`curves_through` pins
/// a0 = rim − a1), so what is checked is that there is one per fold point and that each is
/// a fold curve of the diff disk, not just a line: its paper loss is negative.
#[test]
fn every_reported_fold_point_ends_a_drawn_curve() {
    let shared = crate::common::builtin();
    let (mut steps, mut misses) = (0, Vec::new());
    for (entry, analysis) in shared.data.entries().iter().zip(&shared.analyses) {
        let analysis = analysis.as_ref().unwrap_or_else(|e| panic!("{}: {e}", entry.id));
        for (k, step) in analysis.steps.iter().enumerate() {
            let Some(fold) = step.detection.fold else { continue };
            steps += 1;
            let curves = &step.detection.curves;
            if curves.len() != fold.ends().len() {
                misses.push(format!(
                    "{} step {}: {} curves for {} fold points",
                    entry.id,
                    k + 1,
                    curves.len(),
                    fold.ends().len()
                ));
            }
            for c in curves.iter().filter(|c| c.loss.is_nan() || c.loss >= 0.0) {
                misses.push(format!(
                    "{} step {}: the curve to {:.1}° has loss {} (no fold evidence)",
                    entry.id,
                    k + 1,
                    c.rim.to_degrees(),
                    c.loss
                ));
            }
            for f in fold.ends() {
                let nearest = curves
                    .iter()
                    .map(|c| close::angle::distance(c.a0 + c.a1, f))
                    .fold(f64::INFINITY, f64::min);
                if nearest > 10f64.to_radians() {
                    misses.push(format!(
                        "{} step {}: fold point {:.1}° is {:.1}° from the nearest curve end",
                        entry.id,
                        k + 1,
                        f.to_degrees(),
                        nearest.to_degrees()
                    ));
                }
            }
        }
    }
    assert!(steps > 150, "only {steps} fold steps");
    assert!(misses.is_empty(), "{misses:#?}");
}

/// Issue 28 item 2: a fold of several arcs (a leg folded over the other) is compared with its
/// truth by its line and the vertices it folds, not by its two points, which two folds
/// along one line may name in another order.
#[test]
fn a_multi_arc_fold_is_compared_with_its_truth_by_line_and_folded_set() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/physics-mujoco/border/trousers_q1_leg_over_leg_then_half.json");
    let sample = close::formats::json::parse_sample(&std::fs::read(path).expect("the fixture"))
        .expect("a sample");
    let analysis = close::analyze(&sample.border_frames().expect("frames"), Default::default())
        .expect("analysed");
    let truth = close::render::truth::Truth::of(sample.truth.as_ref().expect("its truth"));
    assert!(analysis.foldings().iter().any(|f| f.arcs.len() > 1), "a multi-arc fold is found");
    let lines = close::render::truth::true_lines(&analysis, &truth);
    let foldings = analysis.foldings();
    for (k, (line, _)) in lines.iter().enumerate() {
        let agreement =
            close::render::truth::agreement(&analysis, &truth, k, line.as_ref()).expect("compared");
        println!("fold {}: {agreement}", k + 1);
        if foldings[k].arcs.len() > 1 {
            let close::render::truth::Agreement::Line { angle, offset, shared } = agreement else {
                panic!("fold {}: compared by its points: {agreement}", k + 1);
            };
            assert!(angle < 5.0 && offset < 0.05, "fold {}: {agreement}", k + 1);
            assert!(shared.is_some_and(|s| s > 0.9), "fold {}: {agreement}", k + 1);
        }
    }
    // The legend says so.
    let svg = close::render::render(
        &analysis,
        &close::render::View::whole(close::render::Picture::Borders),
        &close::render::Output::svg(480),
        close::render::Known { truth: &truth, mesh: None },
    )
    .expect("the border plot");
    let svg = String::from_utf8(svg).expect("text");
    assert!(svg.contains("fold 2 (true: line"), "{}", &svg[svg.len().saturating_sub(3000)..]);
    // Every text stays inside the picture: a legend entry too long for a row is broken into
    // lines (it ran off the right edge).
    for text in svg.split("<text ").skip(1) {
        let attr = |name: &str| -> f64 {
            let start = text.find(&format!("{name}=\"")).expect("the attribute") + name.len() + 2;
            text[start..].split('"').next().and_then(|v| v.parse().ok()).expect("a number")
        };
        let (x, length) = (attr("x"), attr("textLength"));
        assert!(x >= 0.0 && x + length <= 480.5, "a text runs off the picture: {text:.120}");
    }
}

/// Compare's pictures: a disk titled as asked, and the difference of two states' disks.
#[tokio::test]
async fn a_disk_takes_a_title_and_a_state_to_subtract() {
    let app = app(AppState::new());
    let flat = square();
    let moved: Vec<[f64; 3]> = flat.iter().map(|p| [p[0] * 1.1, p[1], p[2]]).collect();
    let svg = |body: Value| {
        let app = app.clone();
        async move {
            let request = Request::builder()
                .method(Method::POST)
                .uri("/api/disk?format=svg")
                .header(header::CONTENT_TYPE, "application/json")
                .body(Body::from(body.to_string()))
                .unwrap();
            let (status, _, _, body) = send_typed(&app, request).await;
            (status, String::from_utf8_lossy(&body).into_owned())
        }
    };
    let (status, titled) = svg(json!({"border": flat, "title": "A · napkin after step 1"})).await;
    assert_eq!(status, StatusCode::OK);
    assert!(titled.contains("A · napkin after step 1"), "the title is not drawn");
    // The difference of a state with itself is zero everywhere; with another, it is not.
    let cells = |minus: &[[f64; 3]]| {
        let app = app.clone();
        let body = json!({"border": flat, "minus": {"border": minus}, "size": 120});
        async move {
            let request = Request::builder()
                .method(Method::POST)
                .uri("/api/disk/cells")
                .header(header::CONTENT_TYPE, "application/json")
                .body(Body::from(body.to_string()))
                .unwrap();
            let (status, _, body) = send(&app, request).await;
            assert_eq!(status, StatusCode::OK, "{}", String::from_utf8_lossy(&body));
            let v: Value = serde_json::from_slice(&body).unwrap();
            serde_json::from_value::<Vec<f64>>(v["values"].clone()).unwrap()
        }
    };
    assert!(cells(&flat).await.iter().all(|&v| v == 0.0));
    assert!(cells(&moved).await.iter().any(|&v| v.abs() > 1e-3));
    let (status, error) =
        svg(json!({"border": flat, "minus": {"border": &flat[..flat.len() - 1]}})).await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert!(error.contains("as many vertices"), "{error}");
    let (status, error) = svg(json!({"border": flat, "title": "x".repeat(121)})).await;
    assert_eq!(status, StatusCode::BAD_REQUEST);
    assert!(error.contains("at most 120"), "{error}");
}

/// Issue 28 item 5: the border plot follows the step the disks show: step k draws frames
/// k − 1 and k, that step's prediction and its fold alone; the readout of the step maps that
/// plot and gives the borders it draws.
#[test]
fn the_border_plot_of_a_step_draws_that_step() {
    use close::render::{readout::readout, render, truth::Truth, Known, Output, Picture, View};
    let (_, analysis) = crate::common::builtin().analysed("napkin__half_then_half");
    assert_eq!(analysis.steps.len(), 2);
    let svg = |step| {
        let view = View { picture: Picture::Borders, step };
        String::from_utf8(render(analysis, &view, &Output::svg(480), Known::default()).unwrap())
            .expect("text")
    };
    let (whole, first, second) = (svg(None), svg(Some(1)), svg(Some(2)));
    assert!(whole.contains(">fold 1<") && whole.contains(">fold 2<"), "both folds in the whole");
    assert!(first.contains(">Borders (XY) · step 1<") && first.contains(">fold 1<"));
    assert!(!first.contains(">fold 2<"), "step 1 draws its own fold alone");
    assert!(second.contains(">fold 2<") && !second.contains(">fold 1<"));
    let view = View { picture: Picture::Borders, step: Some(3) };
    assert!(render(analysis, &view, &Output::svg(480), Known::default()).is_err());
    let r = readout(analysis, &Truth::default(), Some(2), 480).expect("a readout");
    let frame = |k: usize| analysis.frames[k].iter().map(close::border::to_xyz).collect::<Vec<_>>();
    assert_eq!(r.border_frames, [frame(1), frame(2)]);
}
