//! VR-Folding Zarr stores: a real store written by Python's zarr 2.x + numcodecs (Blosc lz4,
//! byte shuffle) by `tests/fixtures/vrfolding/make_store.py`, cut into fold actions and
//! evaluated; broken stores give errors naming the problem.
#![cfg(feature = "vrfolding")]

use std::path::{Path, PathBuf};

use close::vrfolding::{evaluate, is_store, Store};
use close::{eval, Error, FoldMethod};

fn fixture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/vrfolding/vr_simulation_folding2_dataset.zarr")
}

#[test]
fn the_fixture_is_cut_into_two_folds_per_video() {
    let store = Store::open(&fixture()).unwrap();
    assert_eq!(store.categories(), ["Skirt", "Top", "Trousers", "Tshirt"]);
    let videos = store.videos().unwrap();
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
        assert!(folds.border_indices.len() >= 8 && folds.border_indices.iter().all(|&i| i < folds.vertices));
    }
}

#[test]
fn eval_gives_table_rows_per_category_and_fold() {
    let store = Store::open(&fixture()).unwrap();
    let results = store.videos().unwrap().iter().flat_map(|v| evaluate(&store, v, FoldMethod::default())).collect();
    let report = eval::report(results);
    let names: Vec<&str> = report.categories.iter().map(|s| s.category.as_str()).collect();
    assert_eq!(names, ["Skirt/fold1", "Skirt/fold2", "Top/fold1", "Top/fold2", "Trousers/fold1", "Trousers/fold2", "Tshirt/fold1", "Tshirt/fold2"]);
    for row in &report.categories {
        let dropped = usize::from(row.category == "Trousers/fold2");
        assert_eq!((row.count, row.dropped, row.errors), (2 - dropped, dropped, 0), "{}", row.category);
        assert_eq!(row.fold_count_misses, 0, "{}", row.category);
        let rmse = row.rmse.unwrap().mean;
        // First folds are single clean folds; second folds stack on them and are harder.
        let bound = if row.category.ends_with("fold1") { 0.05 } else { 1.0 };
        assert!(rmse.is_finite() && rmse < bound, "{} RMSE {rmse}", row.category);
    }
    assert_eq!((report.overall.count, report.overall.dropped), (15, 1));
    let table = report.table();
    assert!(table.contains("Trousers/fold2") && table.contains("dropped"));
}
