//! Correctness against the authors' reference implementation's outputs
//! (`tests/fixtures/reference*`, copied from the project's golden data).

mod common;

use std::collections::HashMap;
use std::f64::consts::PI;

use close::eval::{evaluate, report};
use close::{analyze, FrameRange};
use common::{angle_diff, fixture, reference_samples};
use serde::Deserialize;

#[derive(Deserialize)]
struct Vectors {
    #[serde(rename = "N")]
    n: usize,
    start: Vec<f64>,
    end: Vec<f64>,
    flagged: Vec<usize>,
}

/// dGLI cells agree with the reference to 1e-6 relative except on a handful; none is off by
/// more than 1e-2 (finite differences of asin near ±1 amplify rounding), flagged cells aside.
#[test]
fn dgli_matches_the_reference_cell_by_cell() {
    let dir = fixture("reference_vectors");
    let (mut cells, mut off, mut worst) = (0usize, 0usize, 0.0f64);
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let reference: Vectors = serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
        let name = path.file_name().unwrap().to_str().unwrap();
        let sample_path = fixture("reference/folded").join(name);
        let sample = close::formats::json::parse_sample(&std::fs::read(sample_path).unwrap()).unwrap();
        let frames = sample.border_frames().unwrap();
        let analysis = analyze(&frames, FrameRange::default()).unwrap();
        assert_eq!(analysis.n, reference.n);
        let flagged: std::collections::HashSet<usize> = reference.flagged.iter().copied().collect();
        let last = analysis.frames.len() - 1;
        for (mine, theirs) in [(&analysis.disk(0).unwrap(), &reference.start), (&analysis.disk(last).unwrap(), &reference.end)] {
            assert_eq!(mine.values().len(), theirs.len());
            for (k, (a, b)) in mine.values().iter().zip(theirs).enumerate() {
                if flagged.contains(&k) {
                    continue;
                }
                let err = (a - b).abs() / (1.0 + b.abs());
                cells += 1;
                worst = worst.max(err);
                off += usize::from(err > 1e-6);
            }
        }
    }
    assert!(cells > 40_000, "{cells}");
    assert!((off as f64) <= 0.005 * cells as f64, "{off} of {cells} cells beyond 1e-6");
    assert!(worst <= 1e-2, "worst relative error {worst}");
}

#[derive(Deserialize)]
struct CornerInfo {
    corners_vertex: Vec<usize>,
    capped_start: usize,
}

/// Where the reference has no capped (NaN) cells, its corners are ours: its angle
/// 2π(v − ½)/N and ours 2πv/N name the same vertex v.
#[test]
fn corners_match_the_reference_where_it_has_no_nan() {
    let info: HashMap<String, CornerInfo> = serde_json::from_slice(&std::fs::read(fixture("reference_corners.json")).unwrap()).unwrap();
    let mut compared = 0;
    for sample in reference_samples() {
        let reference = &info[&sample.name];
        if reference.capped_start > 0 {
            continue;
        }
        let analysis = analyze(&sample.border_frames().unwrap(), FrameRange::default()).unwrap();
        let mut theirs = reference.corners_vertex.clone();
        theirs.sort_unstable();
        assert_eq!(analysis.corner_vertices, theirs, "{}", sample.name);
        compared += 1;
    }
    assert!(compared >= 60, "{compared}");
}

/// The fold is found on the reference samples, well oriented, and predicts the end border.
#[test]
fn folds_on_the_reference_samples() {
    let samples = reference_samples();
    let results: Vec<_> = samples.iter().map(evaluate).collect();
    let folded: Vec<_> = results.iter().filter(|r| r.name != "napkin__nofold").collect();
    assert_eq!(folded.len(), 95);
    let nofold = results.iter().find(|r| r.name == "napkin__nofold").unwrap();
    assert_eq!(nofold.folds, 0, "a step where nothing changed has no fold");

    let one_fold = folded.iter().filter(|r| r.folds == 1).count();
    assert!(one_fold >= 94, "one fold on {one_fold} of 95");
    // Oriented right: each endpoint within two edges of its own true endpoint, in order.
    let oriented = folded.iter().filter(|r| r.angle_error.is_some_and(|e| e[0].max(e[1]) < 2.0 * 2.0 * PI / 64.0)).count();
    assert!(oriented >= 93, "oriented right on {oriented} of 95");

    let mean = |rs: &[&&close::eval::SampleResult]| rs.iter().map(|r| r.rmse.unwrap()).sum::<f64>() / rs.len() as f64;
    let all: Vec<_> = folded.iter().collect();
    let jitter: Vec<_> = folded.iter().filter(|r| r.name.contains("jitter")).collect();
    assert!(jitter.len() >= 40);
    assert!(mean(&all) <= 0.05, "mean RMSE {}", mean(&all));
    assert!(mean(&jitter) <= 0.02, "jitter mean RMSE {}", mean(&jitter));

    let table = report(results).table();
    assert!(table.contains("overall"));
    println!("{table}");
}

/// Rotated and translated copies of a jittered fold give the same fold (to the rim
/// refinement's tolerance, far below an edge).
#[test]
fn rigid_copies_give_the_same_fold() {
    let samples = reference_samples();
    for rigid in samples.iter().filter(|s| s.name.ends_with("__jitter__rigid")) {
        let plain = samples.iter().find(|s| s.name == rigid.name.trim_end_matches("__rigid")).unwrap();
        let fold = |s: &close::Sample| analyze(&s.border_frames().unwrap(), FrameRange::default()).unwrap().folds;
        let (a, b) = (fold(plain), fold(rigid));
        assert_eq!(a.len(), 1);
        assert_eq!(b.len(), 1);
        for k in 0..2 {
            assert!(angle_diff(a[0][k], b[0][k]) < 1e-4, "{}: {:?} vs {:?}", rigid.name, a, b);
        }
    }
}
