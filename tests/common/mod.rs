//! Helpers shared by the integration tests: fixture loading and synthetic folds.
#![allow(dead_code)] // each test binary uses its own subset

use std::f64::consts::PI;
use std::path::{Path, PathBuf};

use close::border::Point;
use close::fold::reflect::apply_fold;
use close::formats::{json::parse_sample, Sample};

pub fn fixture(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures").join(path)
}

/// Every sample of a fixture folder, sorted by file name.
pub fn samples_in(dir: &str) -> Vec<Sample> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(fixture(dir)).unwrap().map(|e| e.unwrap().path()).collect();
    files.sort();
    files.iter().map(|f| parse_sample(&std::fs::read(f).unwrap()).unwrap()).collect()
}

/// The reference samples (95 folded + 1 without a fold).
pub fn reference_samples() -> Vec<Sample> {
    let mut all = samples_in("reference/folded");
    all.extend(samples_in("reference/nofold"));
    all
}

/// A square napkin of `per_side` segments a side, anticlockwise from a corner, with a
/// little in-plane jitter so no two sides are exactly collinear.
pub fn napkin(per_side: usize) -> Vec<[f64; 3]> {
    let s = per_side as f64;
    (0..4 * per_side)
        .map(|k| {
            let t = (k % per_side) as f64 / s;
            let (x, y) = [(t, 0.0), (1.0, t), (1.0 - t, 1.0), (0.0, 1.0 - t)][k / per_side];
            [x - 0.5 + 1e-5 * (7.0 * k as f64).sin(), y - 0.5 + 1e-5 * (3.0 * k as f64).cos(), 0.0]
        })
        .collect()
}

/// Fold `start` along border parameters (f1, f2) as the reference generator does: the
/// folded vertices are reflected and lifted by the cloth thickness 0.01.
pub fn fold_frame(start: &[[f64; 3]], f1: f64, f2: f64) -> Vec<[f64; 3]> {
    let n = start.len() as f64;
    let points: Vec<Point> = start.iter().map(|p| Point::new(p[0], p[1], p[2])).collect();
    let fold = [2.0 * PI * f1 / n, 2.0 * PI * f2 / n];
    apply_fold(&points, fold)
        .iter()
        .zip(&points)
        .map(|(e, s)| [e.x, e.y, if e == s { e.z } else { e.z + 0.01 }])
        .collect()
}

pub fn angle_diff(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(2.0 * PI);
    d.min(2.0 * PI - d)
}
