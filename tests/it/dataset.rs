//! The built-in dataset, evaluated once for the whole test binary ([`builtin`]; `close eval
//! --builtin` runs the same evaluation): every sample analyses, gets one fold per step, and
//! each category stays within its quality bar.
//!
//! The bars are requirements, not measurements: the measurements are the snapshot
//! `tests/snapshots/builtin.json`, which `readme.rs` holds equal to the binary's output. A
//! bar only moves when the requirement does.

use std::collections::{HashMap, HashSet};

use close::angle::edge;
use close::eval::Stat;

use crate::common::builtin;

/// Quality bars of a category's means: RMSE, Fréchet (normalised units), f1 and f2 error
/// (degrees); and of its worst fold point, in edges of the sample's border.
struct Bar {
    rmse: f64,
    frechet: f64,
    degrees: f64,
    worst_edges: f64,
}

/// Exact synthetic folds at random points off the grid: on average the fold points within
/// a fraction of a degree and the prediction within 1 % of the cloth's size; no fold point
/// a whole edge off (a fold point a little way from a corner is the hardest case).
const SYNTHETIC: Bar = Bar { rmse: 0.01, frechet: 0.02, degrees: 0.6, worst_edges: 1.0 };
/// Second folds of the synthetic set, scored fold by fold (the second from the observed
/// first).
const SYNTHETIC_SECOND: Bar = Bar { rmse: 0.012, frechet: 0.025, degrees: 3.0, worst_edges: 1.5 };
/// Simulated cloth: the commanded fold line itself is off by about 0.01 RMSE (first folds)
/// and 0.02 (second), see assets/physics/README.md.
const PHYSICS: Bar = Bar { rmse: 0.02, frechet: 0.05, degrees: 2.0, worst_edges: 4.0 };
const PHYSICS_SECOND: Bar = Bar { rmse: 0.06, frechet: 0.12, degrees: 4.0, worst_edges: 4.0 };

fn bar(category: &str) -> &'static Bar {
    match category {
        "physics" => &PHYSICS,
        "physics_second_fold" => &PHYSICS_SECOND,
        c if c.ends_with("_second_fold") => &SYNTHETIC_SECOND,
        _ => &SYNTHETIC,
    }
}

#[test]
fn every_sample_analyses_with_one_fold_per_step() {
    let (data, report) = (&builtin().data, &builtin().report);
    assert_eq!(report.overall.count, data.entries().len());
    let failures: Vec<String> = report
        .samples
        .iter()
        .filter_map(|r| r.error.as_ref().map(|e| format!("{}: {e}", r.name)))
        .collect();
    assert!(failures.is_empty(), "{failures:#?}");
    let misses: Vec<String> = report
        .samples
        .iter()
        .filter(|r| r.folds != r.expected_folds)
        .map(|r| format!("{}: {} folds, expected {}", r.name, r.folds, r.expected_folds))
        .collect();
    assert!(misses.is_empty(), "{misses:#?}");
    for summary in &report.categories {
        assert!(
            summary.by_fold.iter().all(|f| f.found == f.count),
            "{}: a step without a fold",
            summary.category
        );
    }
}

#[test]
fn accuracy_per_category_within_its_bar() {
    let report = &builtin().report;
    let mean = |s: Option<Stat>, what: &str, row: &str| {
        s.unwrap_or_else(|| panic!("{row}: no {what}")).mean
    };
    for summary in &report.categories {
        let bar = bar(&summary.category);
        let rows = std::iter::once((
            summary.category.to_string(),
            [summary.rmse, summary.frechet, summary.f1_error, summary.f2_error],
        ))
        .chain(summary.by_fold.iter().map(|f| {
            (
                format!("{} fold {}", summary.category, f.fold),
                [f.rmse, f.frechet, f.f1_error, f.f2_error],
            )
        }));
        for (row, stats) in rows {
            let found = [
                mean(stats[0], "RMSE", &row),
                mean(stats[1], "Fréchet", &row),
                mean(stats[2], "f1 error", &row).to_degrees(),
                mean(stats[3], "f2 error", &row).to_degrees(),
            ];
            let limits = [bar.rmse, bar.frechet, bar.degrees, bar.degrees];
            for ((name, found), limit) in
                ["RMSE", "Fréchet", "f1 error °", "f2 error °"].iter().zip(found).zip(limits)
            {
                assert!(found <= limit, "{row}: {name} {found:.5} above its bar {limit}");
            }
        }
    }
}

#[test]
fn worst_fold_angle_per_sample_in_edges() {
    let (data, report) = (&builtin().data, &builtin().report);
    let n: HashMap<&str, usize> = data
        .entries()
        .iter()
        .map(|e| (e.id.as_str(), e.sample.border_frames().map_or(0, |b| b.len())))
        .collect();
    let mut worst: HashMap<&str, (f64, &str)> = HashMap::new();
    for r in &report.samples {
        let edges = edge(n[r.name.as_str()]);
        let errors = r
            .angle_error
            .iter()
            .chain(r.steps.iter().filter_map(|s| s.angle_error.as_ref()))
            .flatten();
        let e = errors.fold(0.0, |m: f64, &a| m.max(a / edges));
        let slot = worst.entry(r.category.as_str()).or_insert((0.0, ""));
        if e >= slot.0 {
            *slot = (e, r.name.as_str());
        }
    }
    for (category, (e, name)) in &worst {
        let limit = bar(category).worst_edges;
        println!("{category}: worst {e:.3} edges ({name})");
        assert!(*e <= limit, "{category}: {name} is {e:.3} edges off (bar {limit})");
    }
}

#[test]
fn ids_are_unique_and_names_readable() {
    let data = &builtin().data;
    let ids: HashSet<&str> = data.entries().iter().map(|e| e.id.as_str()).collect();
    assert_eq!(ids.len(), data.entries().len(), "repeated ids");
    for e in data.entries() {
        assert_eq!(e.id, e.sample.name);
        // `shape__fold[__variant]`: lowercase words joined by `_`, parts by `__`.
        let parts: Vec<&str> = e.id.split("__").collect();
        assert!((2..=3).contains(&parts.len()), "{}", e.id);
        for part in parts {
            let words_ok = !part.is_empty()
                && part.split('_').all(|w| {
                    !w.is_empty() && w.chars().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit())
                });
            assert!(words_ok, "{}: unreadable part {part:?}", e.id);
        }
        assert!(e.id.len() <= 48, "{} is too long to read", e.id);
        assert!(!e.sample.category.is_empty(), "{}: no category", e.id);
    }
}
