//! VR-Folding Zarr stores: a real store written by Python's zarr 2.x + numcodecs (Blosc lz4,
//! byte shuffle) by `tests/fixtures/vrfolding/make_store.py`, cut into fold actions and
//! evaluated; broken stores give errors naming the problem.
#![cfg(feature = "vrfolding")]

use std::path::{Path, PathBuf};

use close::eval::evaluate_video;
use close::io_error::Error as Read;
use close::vrfolding::{is_store, Store};
use close::{eval, FoldMethod};

fn fixture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/vrfolding/vr_simulation_folding2_dataset.zarr")
}

#[test]
fn the_fixture_is_cut_into_two_folds_per_video() {
    let store = Store::open(&fixture()).unwrap();
    assert_eq!(store.categories(), ["Skirt", "Top", "Trousers", "Tshirt"]);
    let videos = store.videos().unwrap().0;
    assert_eq!(videos.len(), 8);
    for video in &videos {
        assert_eq!(video.frames.len(), 10, "{}", video.id);
        let folds = store.folds(video).unwrap();
        // idle, action 1 (frames 1–4: the right hand lets go after 3, the left after 4),
        // idle, action 2 (frames 6–8, the left hand alone), idle.
        let spans: Vec<(usize, usize)> = folds.actions.iter().map(|a| (a.start, a.end)).collect();
        assert_eq!(spans, [(1, 4), (6, 8)], "{} {}", video.category, video.id);
        assert!(!folds.unfinished);
        let broken = video.category == "Trousers" && video.id == "00004";
        assert_eq!(folds.broken, [false, broken], "{}", video.id);
        assert_eq!(folds.frames.len(), if broken { 2 } else { 3 });
        assert!(
            folds.border_indices.len() >= 8
                && folds.border_indices.iter().all(|&i| i < folds.vertices)
        );
    }
}

#[test]
fn eval_gives_table_rows_per_category_and_fold() {
    let store = Store::open(&fixture()).unwrap();
    let results = store
        .videos()
        .unwrap()
        .0
        .iter()
        .flat_map(|v| evaluate_video(&store, v, FoldMethod::default()))
        .collect();
    let report = eval::report(results);
    let names: Vec<&str> = report.categories.iter().map(|s| s.category.as_str()).collect();
    assert_eq!(
        names,
        [
            "Skirt/fold1",
            "Skirt/fold2",
            "Top/fold1",
            "Top/fold2",
            "Trousers/fold1",
            "Trousers/fold2",
            "Tshirt/fold1",
            "Tshirt/fold2"
        ]
    );
    for row in &report.categories {
        let dropped = usize::from(row.category == "Trousers/fold2");
        assert_eq!(
            (row.count, row.dropped, row.errors),
            (2 - dropped, dropped, 0),
            "{}",
            row.category
        );
        assert_eq!(row.fold_count_misses, 0, "{}", row.category);
        let rmse = row.rmse.unwrap().mean;
        // First folds are single clean folds; second folds stack layers and are the method's
        // hard case, so only their presence is checked here.
        assert!(rmse.is_finite(), "{} RMSE {rmse}", row.category);
        if row.category.ends_with("fold1") {
            assert!(rmse < 0.05, "{} RMSE {rmse}", row.category);
        }
    }
    assert_eq!((report.overall.count, report.overall.dropped), (15, 1));
    let table = report.table();
    assert!(table.contains("Trousers/fold2") && table.contains("dropped"));
}

/// A private copy of the fixture's Skirt category (a whole store) to break.
fn copy_store(name: &str) -> PathBuf {
    let to = std::env::temp_dir().join(format!("close-vrfolding-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&to);
    std::fs::create_dir_all(&to).unwrap();
    std::fs::copy(fixture().join(".zgroup"), to.join(".zgroup")).unwrap();
    crate::common::copy_dir(&fixture().join("Skirt"), &to.join("Skirt"));
    to
}

/// The first video's error after `breaking` a copy of the store (path: frame 0's group).
fn error_after(name: &str, breaking: impl FnOnce(&Path)) -> String {
    let root = copy_store(name);
    let store = Store::open(&root).unwrap();
    let video = store.videos().unwrap().0.remove(0);
    breaking(&root.join(video.frames[0].trim_start_matches('/')));
    let error = store.folds(&video).unwrap_err();
    assert!(matches!(error, Read::Store { .. }), "{error:?}");
    std::fs::remove_dir_all(&root).unwrap();
    error.to_string()
}

fn edit_json(path: &Path, edit: impl FnOnce(&mut serde_json::Value)) {
    let mut value: serde_json::Value =
        serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap();
    edit(&mut value);
    std::fs::write(path, value.to_string()).unwrap();
}

#[test]
fn a_missing_group_is_named() {
    let e = error_after("missing-group", |frame| {
        std::fs::remove_dir_all(frame.join("grip_vertex_id")).unwrap()
    });
    assert!(e.contains("grip_vertex_id/left_grip_vertex_id") && e.contains("missing"), "{e}");
    let root = copy_store("no-samples");
    std::fs::rename(root.join("Skirt/samples"), root.join("Skirt/frames")).unwrap();
    let e = Store::open(&root).err().unwrap().to_string();
    assert!(e.contains("samples/"), "{e}");
    std::fs::remove_dir_all(&root).unwrap();
    let e = Store::open(&fixture().join("Skirt/samples/nothing-here")).err().unwrap().to_string();
    assert!(e.contains("not a folder"), "{e}");
}

#[test]
fn an_array_of_the_wrong_shape_or_type_is_named() {
    let e = error_after("shape", |frame| {
        edit_json(&frame.join("mesh/cloth_verts/.zarray"), |z| {
            let rows = z["shape"][0].as_u64().unwrap();
            z["shape"] = serde_json::json!([rows * 3]);
            z["chunks"] = serde_json::json!([rows * 3]);
        })
    });
    assert!(e.contains("cloth_verts") && e.contains("expected [rows, 3]"), "{e}");
    let e = error_after("type", |frame| {
        edit_json(&frame.join("mesh/cloth_verts/.zarray"), |z| {
            z["dtype"] = "<i4".into();
            z["fill_value"] = 0.into();
        })
    });
    assert!(e.contains("data type int32, expected float32 or float64"), "{e}");
    let e = error_after("face-type", |frame| {
        edit_json(&frame.join("mesh/cloth_faces_tri/.zarray"), |z| z["dtype"] = "<f4".into())
    });
    assert!(e.contains("cloth_faces_tri") && e.contains("expected integers"), "{e}");
}

#[test]
fn an_unknown_codec_is_named() {
    let e = error_after("codec", |frame| {
        edit_json(&frame.join("mesh/cloth_verts/.zarray"), |z| {
            z["compressor"]["id"] = "nosuchcodec".into()
        })
    });
    assert!(e.contains("cloth_verts") && e.contains("nosuchcodec"), "{e}");
}

#[test]
fn a_truncated_chunk_is_an_error() {
    let e = error_after("truncated", |frame| {
        let chunk = frame.join("mesh/cloth_verts/0.0");
        let bytes = std::fs::read(&chunk).unwrap();
        std::fs::write(&chunk, &bytes[..bytes.len() / 2]).unwrap();
    });
    assert!(e.contains("cloth_verts") && e.contains("cannot decode"), "{e}");
}

#[test]
fn grip_ids_out_of_range_and_videos_without_action_are_errors() {
    let bad = fixture().parent().unwrap().join("bad");
    for (store, expected) in [
        ("grip_out_of_range.zarr", "gripped vertex 10000 is out of range"),
        ("no_action.zarr", "no fold action"),
    ] {
        let store = Store::open(&bad.join(store)).unwrap();
        let video = store.videos().unwrap().0.remove(0);
        let e = store.folds(&video).unwrap_err().to_string();
        assert!(e.contains(expected), "{e}");
        // In an evaluation the video is one error in its row, not a panic.
        let rows = evaluate_video(&store, &video, FoldMethod::default());
        assert_eq!(
            (rows.len(), rows[0].category.as_str(), rows[0].error.is_some()),
            (1, "Skirt/fold1", true)
        );
    }
}

#[test]
fn a_category_folder_is_a_store_of_one_category() {
    assert!(
        is_store(&fixture())
            && is_store(&fixture().join("Top"))
            && !is_store(&fixture().join("Top/samples/missing"))
    );
    let store = Store::open(&fixture().join("Top")).unwrap();
    assert_eq!(store.categories(), ["Top"]);
    assert_eq!(store.videos().unwrap().0.len(), 2);
}

fn close_cli(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_close")).args(args).output().unwrap()
}

#[test]
fn the_cli_evaluates_analyses_and_exports_a_store() {
    let store = fixture();
    let store = store.to_str().unwrap();
    let out = close_cli(&["eval", store, "--json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let rows: Vec<&str> = v["categories"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["category"].as_str().unwrap())
        .collect();
    assert_eq!(rows.len(), 8, "{rows:?}");
    assert_eq!(
        (v["overall"]["count"].as_u64(), v["overall"]["dropped"].as_u64()),
        (Some(15), Some(1))
    );

    let out = close_cli(&["analyze", store, "--video", "Tshirt/00001", "--fold", "2"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let a: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!((a["fold"].as_u64(), a["steps"].as_array().map(Vec::len)), (Some(2), Some(2)));
    assert_eq!(a["actions"], serde_json::json!([{"start": 1, "end": 4}, {"start": 6, "end": 8}]));
    // border_indices are mesh vertex ids.
    assert!(a["border_indices"]
        .as_array()
        .unwrap()
        .iter()
        .any(|i| i.as_u64().unwrap() >= a["n"].as_u64().unwrap()));
    for (args, expected) in [
        (vec!["analyze", store, "--video", "00004", "--fold", "2"], "broken"),
        (vec!["analyze", store, "--video", "nope"], "no video \"nope\""),
        (vec!["analyze", store], "--video"),
        (vec!["analyze", store, "--video", "00001", "--fold", "3"], "3"),
    ] {
        let out = close_cli(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            !out.status.success() && stderr.contains(expected) && !stderr.contains("panicked"),
            "{args:?}: {stderr}"
        );
    }

    let dir = std::env::temp_dir().join(format!("close-vrfolding-export-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let out = close_cli(&["dataset", dir.to_str().unwrap(), "--from", store]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 15);
    // The exported folds score as the store's rows do.
    let exported: serde_json::Value =
        serde_json::from_slice(&close_cli(&["eval", dir.to_str().unwrap(), "--json"]).stdout)
            .unwrap();
    for (a, b) in
        exported["categories"].as_array().unwrap().iter().zip(v["categories"].as_array().unwrap())
    {
        assert_eq!(a["category"], b["category"]);
        let (x, y) = (a["rmse"]["mean"].as_f64().unwrap(), b["rmse"]["mean"].as_f64().unwrap());
        assert!((x - y).abs() < 1e-9, "{}: {x} vs {y}", a["category"]);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

mod server {
    use super::*;
    use axum::body::{to_bytes, Body};
    use axum::http::{Request, StatusCode};
    use close::server::{app, AppState, Config};
    use serde_json::Value;
    use tower::ServiceExt;

    async fn get(app: &axum::Router, uri: &str) -> (StatusCode, Value) {
        let response =
            app.clone().oneshot(Request::get(uri).body(Body::empty()).unwrap()).await.unwrap();
        let status = response.status();
        let body = to_bytes(response.into_body(), usize::MAX).await.unwrap();
        (status, serde_json::from_slice(&body).unwrap())
    }

    #[tokio::test]
    async fn datasets_are_listed_filtered_paged_and_analysed_lazily() {
        let folder =
            std::env::temp_dir().join(format!("close-vrfolding-dataset-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&folder);
        std::fs::create_dir_all(&folder).unwrap();
        std::fs::write(folder.join("oops.json"), "not json").unwrap();
        let state = AppState::with_config(Config {
            datasets: vec![fixture(), folder.clone()],
            ..Config::default()
        });
        let app = app(state);

        let (status, all) = get(&app, "/api/samples").await;
        assert_eq!(status, StatusCode::OK);
        let samples = all["samples"].as_array().unwrap();
        let builtin = samples.iter().filter(|s| s["source"] == "builtin").count();
        assert!(builtin > 100);
        // 8 videos × 2 folds, one unreadable file; the broken fold is found on loading.
        assert_eq!(samples.len(), builtin + 16 + 1);
        assert_eq!(all["total"].as_u64(), Some(samples.len() as u64));
        for s in samples {
            for key in ["id", "name", "category", "n", "frames", "source", "error"] {
                assert!(s.get(key).is_some(), "{key} missing in {s}");
            }
        }
        let oops = samples.iter().find(|s| s["name"] == "oops.json").unwrap();
        assert!(oops["error"].as_str().unwrap().contains("parse"), "{oops}");

        // Fold 2 of a video follows fold 1: a second fold, filed as the built-in ones are.
        let (_, tshirts) =
            get(&app, "/api/samples?category=Tshirt_second_fold&offset=1&limit=2").await;
        assert_eq!(
            (tshirts["total"].as_u64(), tshirts["samples"].as_array().unwrap().len()),
            (Some(2), 1)
        );
        assert!(tshirts["samples"]
            .as_array()
            .unwrap()
            .iter()
            .all(|s| s["category"] == "Tshirt_second_fold"));
        let (_, found) = get(&app, "/api/samples?q=00003%20fold%202").await;
        assert_eq!(found["total"].as_u64(), Some(1), "{found}");
        let (status, _) = get(&app, "/api/samples?offset=many").await;
        assert_eq!(status, StatusCode::BAD_REQUEST);

        let id = found["samples"][0]["id"].as_str().unwrap();
        let (status, analysis) = get(&app, &format!("/api/samples/{id}")).await;
        assert_eq!(status, StatusCode::OK, "{analysis}");
        assert_eq!(
            (analysis["steps"].as_array().map(Vec::len), analysis["id"].as_str()),
            (Some(2), Some(id))
        );
        let (_, broken) = get(&app, "/api/samples?q=00004%20fold%202").await;
        let (status, error) =
            get(&app, &format!("/api/samples/{}", broken["samples"][0]["id"].as_str().unwrap()))
                .await;
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
        assert!(error["error"].as_str().unwrap().contains("broken"), "{error}");
        let (status, _) =
            get(&app, &format!("/api/samples/{}", oops["id"].as_str().unwrap())).await;
        assert!(status.is_client_error());
        let (status, _) = get(&app, "/api/samples/no-such-id").await;
        assert_eq!(status, StatusCode::NOT_FOUND);
        std::fs::remove_dir_all(&folder).unwrap();
    }
}
