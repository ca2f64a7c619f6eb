//! The built-in dataset, evaluated once for the whole test suite (`close eval --builtin`
//! runs the same evaluation): every sample analyses, gets one fold per step, and each
//! category stays within twice the accuracy measured when these bounds were set.

use std::collections::{HashMap, HashSet};
use std::sync::OnceLock;

use rayon::prelude::*;

use close::angle::edge;
use close::dataset::Dataset;
use close::eval::{evaluate, report, Report, Stat};

/// Means measured with the default fold method (analysis by synthesis) on 2026-12-01
/// (`close eval --builtin --json`): (category, fold, RMSE, Fréchet, f1 error °, f2 error °). Fold 0 is the
/// category's row (a sequence's final RMSE and its first fold's angles); fold k ≥ 1 is the
/// k-th fold of the category's sequences.
const MEASURED: &[(&str, usize, f64, f64, f64, f64)] = &[
    ("circular_towel", 0, 0.00354, 0.00742, 0.1695, 0.1185),
    ("mesh", 0, 0.00000, 0.00000, 0.0000, 0.0000),
    ("napkin", 0, 0.00233, 0.00506, 0.0759, 0.1053),
    ("napkin_second_fold", 0, 0.00324, 0.00519, 0.1342, 0.1342),
    ("napkin_second_fold", 1, 0.00285, 0.00422, 0.1342, 0.1342),
    ("napkin_second_fold", 2, 0.00324, 0.00519, 0.5447, 0.5056),
    ("physics", 0, 0.00937, 0.02444, 0.3659, 0.9670),
    ("physics_second_fold", 0, 0.03198, 0.06479, 0.5509, 1.5102),
    ("physics_second_fold", 1, 0.00817, 0.03033, 0.5509, 1.5102),
    ("physics_second_fold", 2, 0.03198, 0.06479, 1.7251, 1.6669),
    ("skirt", 0, 0.00266, 0.00666, 0.1617, 0.0070),
    ("top", 0, 0.00300, 0.00686, 0.1438, 0.1307),
    ("towel", 0, 0.00184, 0.00362, 0.0500, 0.0625),
    ("towel_second_fold", 0, 0.00339, 0.00497, 0.1667, 0.1667),
    ("towel_second_fold", 1, 0.00339, 0.00497, 0.1667, 0.1667),
    ("towel_second_fold", 2, 0.00339, 0.00497, 0.0000, 0.0000),
    ("trousers", 0, 0.00256, 0.00609, 0.0953, 0.0810),
    ("trousers_second_fold", 0, 0.00286, 0.00331, 0.0818, 0.0818),
    ("trousers_second_fold", 1, 0.00284, 0.00328, 0.0818, 0.0818),
    ("trousers_second_fold", 2, 0.00286, 0.00331, 0.4500, 3.1500),
    ("tshirt", 0, 0.00194, 0.00462, 0.0576, 0.1206),
    ("tshirt_second_fold", 0, 0.00000, 0.00000, 0.0000, 0.0000),
    ("tshirt_second_fold", 1, 0.00000, 0.00000, 0.0000, 0.0000),
    ("tshirt_second_fold", 2, 0.00000, 0.00000, 0.0000, 0.0000),
];

/// The worst fold-angle error of any sample of a category (f1 or f2, any step), in edges
/// of its border, measured as [`MEASURED`].
const MEASURED_WORST_EDGES: &[(&str, f64)] = &[
    ("circular_towel", 0.131),
    ("mesh", 0.000),
    ("napkin", 0.125),
    ("napkin_second_fold", 0.250),
    ("physics", 2.457),
    ("physics_second_fold", 1.750),
    ("skirt", 0.125),
    ("top", 0.150),
    ("towel", 0.125),
    ("towel_second_fold", 0.075),
    ("trousers", 0.250),
    ("trousers_second_fold", 0.875),
    ("tshirt", 0.250),
    ("tshirt_second_fold", 0.000),
];

/// A bound is twice the measurement, but never tighter than these: exact folds measure
/// rounding noise, which no bound should be made of.
const FLOOR_DISTANCE: f64 = 1e-3;
const FLOOR_DEGREES: f64 = 0.05;
const FLOOR_EDGES: f64 = 0.05;

fn bound(measured: f64, floor: f64) -> f64 {
    (2.0 * measured).max(floor)
}

/// The dataset and its evaluation, computed once for every test of this file.
fn evaluation() -> &'static (Dataset, Report) {
    static EVALUATION: OnceLock<(Dataset, Report)> = OnceLock::new();
    EVALUATION.get_or_init(|| {
        let data = Dataset::builtin();
        let results = data.entries().par_iter().map(|e| evaluate(&e.sample)).collect();
        let report = report(results);
        println!("{}", report.table());
        (data, report)
    })
}

#[test]
fn every_sample_analyses_with_one_fold_per_step() {
    let (data, report) = evaluation();
    assert_eq!(report.overall.count, data.entries().len());
    let failures: Vec<String> = report.samples.iter().filter_map(|r| r.error.as_ref().map(|e| format!("{}: {e}", r.name))).collect();
    assert!(failures.is_empty(), "{failures:#?}");
    let misses: Vec<String> = report
        .samples
        .iter()
        .filter(|r| r.folds != r.expected_folds)
        .map(|r| format!("{}: {} folds, expected {}", r.name, r.folds, r.expected_folds))
        .collect();
    assert!(misses.is_empty(), "{misses:#?}");
    for summary in &report.categories {
        assert!(summary.by_fold.iter().all(|f| f.found == f.count), "{}: a step without a fold", summary.category);
    }
}

#[test]
fn accuracy_per_category_within_twice_the_measured() {
    let (_, report) = evaluation();
    let mean = |s: Option<Stat>, what: &str, row: &str| s.unwrap_or_else(|| panic!("{row}: no {what}")).mean;
    let mut checked = HashSet::new();
    for &(category, fold, rmse, frechet, f1, f2) in MEASURED {
        let summary = report.categories.iter().find(|s| s.category == category).unwrap_or_else(|| panic!("no category {category}"));
        let row = format!("{category} fold {fold}");
        let stats = match fold {
            0 => [summary.rmse, summary.frechet, summary.f1_error, summary.f2_error],
            k => {
                let f = summary.by_fold.iter().find(|f| f.fold == k).unwrap_or_else(|| panic!("{row}: no such fold row"));
                [f.rmse, f.frechet, f.f1_error, f.f2_error]
            }
        };
        let found = [
            mean(stats[0], "RMSE", &row),
            mean(stats[1], "Fréchet", &row),
            mean(stats[2], "f1 error", &row).to_degrees(),
            mean(stats[3], "f2 error", &row).to_degrees(),
        ];
        let limits = [bound(rmse, FLOOR_DISTANCE), bound(frechet, FLOOR_DISTANCE), bound(f1, FLOOR_DEGREES), bound(f2, FLOOR_DEGREES)];
        for ((name, found), limit) in ["RMSE", "Fréchet", "f1 error °", "f2 error °"].iter().zip(found).zip(limits) {
            assert!(found <= limit, "{row}: {name} {found:.5} above {limit:.5}");
        }
        checked.insert(category);
    }
    // A new category needs its own measured bounds.
    for summary in &report.categories {
        assert!(checked.contains(summary.category.as_str()), "{}: no bounds", summary.category);
    }
}

#[test]
fn worst_fold_angle_per_sample_in_edges() {
    let (data, report) = evaluation();
    let n: HashMap<&str, usize> = data.entries().iter().map(|e| (e.id.as_str(), e.sample.border_frames().map_or(0, |b| b.len()))).collect();
    let mut worst: HashMap<&str, (f64, &str)> = HashMap::new();
    for r in &report.samples {
        let edges = edge(n[r.name.as_str()]);
        let errors = r.angle_error.iter().chain(r.steps.iter().filter_map(|s| s.angle_error.as_ref())).flatten();
        let e = errors.fold(0.0, |m: f64, &a| m.max(a / edges));
        let slot = worst.entry(r.category.as_str()).or_insert((0.0, ""));
        if e >= slot.0 {
            *slot = (e, r.name.as_str());
        }
    }
    for (category, (e, name)) in &worst {
        let measured = MEASURED_WORST_EDGES.iter().find(|m| m.0 == *category).unwrap_or_else(|| panic!("{category}: no bound")).1;
        println!("{category}: worst {e:.3} edges ({name})");
        assert!(*e <= bound(measured, FLOOR_EDGES), "{category}: {name} is {e:.3} edges off (measured worst {measured})");
    }
}

#[test]
fn ids_are_unique_and_names_readable() {
    let data = Dataset::builtin();
    let ids: HashSet<&str> = data.entries().iter().map(|e| e.id.as_str()).collect();
    assert_eq!(ids.len(), data.entries().len(), "repeated ids");
    for e in data.entries() {
        assert_eq!(e.id, e.sample.name);
        // `shape__fold[__variant]`: lowercase words joined by `_`, parts by `__`.
        let parts: Vec<&str> = e.id.split("__").collect();
        assert!((2..=3).contains(&parts.len()), "{}", e.id);
        for part in parts {
            let words_ok = !part.is_empty() && part.split('_').all(|w| !w.is_empty() && w.chars().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit()));
            assert!(words_ok, "{}: unreadable part {part:?}", e.id);
        }
        assert!(e.id.len() <= 48, "{} is too long to read", e.id);
        assert!(!e.sample.category.is_empty(), "{}: no category", e.id);
    }
}
