//! The picture routes the web app relies on: per-step disk pictures
//! (`/api/images/{key}/{picture}.png?step=k`) and a disk colour scale kept through an
//! animation (`POST /api/disk` with `scale`, answered in `x-disk-scale`); and the fold
//! curves drawn on a step's diff end at the fold points the step reports.

use axum::body::{to_bytes, Body};
use axum::http::{header, Method, Request, StatusCode};
use axum::Router;
use serde_json::{json, Value};
use tower::ServiceExt;

use close::server::{app, AppState};

async fn send(app: &Router, request: Request<Body>) -> (StatusCode, Option<String>, Vec<u8>) {
    let response = app.clone().oneshot(request).await.expect("the router never fails");
    let status = response.status();
    let scale = response.headers().get("x-disk-scale").and_then(|v| v.to_str().ok()).map(str::to_string);
    (status, scale, to_bytes(response.into_body(), usize::MAX).await.expect("a body").to_vec())
}

async fn get(app: &Router, uri: &str) -> (StatusCode, Vec<u8>) {
    let (status, _, body) = send(app, Request::get(uri).body(Body::empty()).expect("request")).await;
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
    for picture in ["disk_start", "disk_end", "diff", "signed_diff"] {
        let (_, whole) = get(&app, &format!("/api/images/{key}/{picture}.png?size=120")).await;
        let (s1, one) = get(&app, &format!("/api/images/{key}/{picture}.png?size=120&step=1")).await;
        let (s2, two) = get(&app, &format!("/api/images/{key}/{picture}.png?size=120&step=2")).await;
        assert_eq!((s1, s2), (StatusCode::OK, StatusCode::OK), "{picture}");
        assert!(is_png(&one) && is_png(&two));
        assert_ne!(one, two, "{picture}: steps 1 and 2 drew the same picture");
        assert_ne!(whole, two, "{picture}: step 2 is the whole analysis");
    }
    let (status, body) = get(&app, &format!("/api/images/{key}/diff.png?step=3")).await;
    assert_eq!(status, StatusCode::BAD_REQUEST);
    let error: Value = serde_json::from_slice(&body).expect("a JSON error");
    assert!(error["error"].as_str().is_some_and(|e| e.contains("step 3") && e.contains("1…2")), "{error}");
    let (status, _) = get(&app, &format!("/api/images/{key}/close.png?step=1")).await;
    assert_eq!(status, StatusCode::BAD_REQUEST);
    // The list's thumbnails are their own small drawing.
    let (status, body) = get(&app, &format!("/api/images/{key}/thumbnail.png?size=100")).await;
    assert!(status == StatusCode::OK && is_png(&body));
}

#[tokio::test]
async fn a_disk_keeps_the_scale_it_is_given() {
    let app = app(AppState::new());
    let square: Vec<[f64; 3]> = (0..16)
        .map(|k| {
            let (side, t) = (k / 4, (k % 4) as f64 / 4.0);
            let c = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
            let (a, b) = (c[side], c[(side + 1) % 4]);
            [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), 0.0]
        })
        .collect();
    let (status, scale, own) = post_disk(&app, &json!({ "border": square, "size": 100 })).await;
    assert_eq!(status, StatusCode::OK);
    let scale = scale.expect("the x-disk-scale header");
    let parts: Vec<f64> = scale.split(' ').map(|v| v.parse().expect("a number")).collect();
    assert!(parts.len() == 2 && parts[0] > 0.0 && parts[1] > 0.0, "{scale}");
    // The same scale sent back draws the same picture; another scale another one.
    let (_, again, same) = post_disk(&app, &json!({ "border": square, "size": 100, "scale": { "s": parts[0], "max": parts[1] } })).await;
    assert_eq!(again.as_deref(), Some(scale.as_str()));
    assert_eq!(own, same);
    let (_, other_scale, other) = post_disk(&app, &json!({ "border": square, "size": 100, "scale": { "s": 10.0 * parts[0], "max": parts[1] } })).await;
    assert_ne!(own, other);
    assert_eq!(other_scale, Some(format!("{} {}", 10.0 * parts[0], parts[1])));
    let (status, _, body) = post_disk(&app, &json!({ "border": square, "scale": { "s": 0.0, "max": 1.0 } })).await;
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
            if curves.len() != fold.len() {
                misses.push(format!("{} step {}: {} curves for {} fold points", entry.id, k + 1, curves.len(), fold.len()));
            }
            for c in curves.iter().filter(|c| !(c.loss < 0.0)) {
                misses.push(format!("{} step {}: the curve to {:.1}° has loss {} (no fold evidence)", entry.id, k + 1, c.rim.to_degrees(), c.loss));
            }
            for f in fold {
                let nearest = curves.iter().map(|c| close::angle::distance(c.a0 + c.a1, f)).fold(f64::INFINITY, f64::min);
                if nearest > 10f64.to_radians() {
                    misses.push(format!("{} step {}: fold point {:.1}° is {:.1}° from the nearest curve end", entry.id, k + 1, f.to_degrees(), nearest.to_degrees()));
                }
            }
        }
    }
    assert!(steps > 150, "only {steps} fold steps");
    assert!(misses.is_empty(), "{misses:#?}");
}
