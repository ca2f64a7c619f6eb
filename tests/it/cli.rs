//! The `close` command line: analyze and eval on real files, and a clear error (never a
//! panic) for every kind of bad input (unparseable, NaN, empty, too large, mismatched frames, degenerate).

use crate::common;

use std::path::PathBuf;
use std::process::{Command, Output};

use common::{fixture, fold_frame, napkin, TempDir};

fn close(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_close")).args(args).output().unwrap()
}

fn write(dir: &TempDir, name: &str, contents: &[u8]) -> String {
    let path = dir.0.join(name);
    std::fs::write(&path, contents).unwrap();
    path.display().to_string()
}

fn frame_text(frame: &[[f64; 3]]) -> String {
    frame.iter().map(|p| format!("{},{},{}\n", p[0], p[1], p[2])).collect()
}

#[test]
fn analyze_prints_the_spec_fields() {
    let path: PathBuf = fixture("reference/folded/napkin__corner_sym__jitter.json");
    let out = close(&["analyze", path.to_str().unwrap(), "--json", "--disks"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for key in [
        "n",
        "corners",
        "folds",
        "label",
        "border_indices",
        "predicted_end",
        "metrics",
        "disk_start",
        "disk_end",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    assert_eq!(v["n"], 76);
    assert_eq!(v["folds"].as_array().unwrap().len(), 1);
    assert_eq!(v["disk_start"].as_array().unwrap().len(), 76 * 75 / 2);
    assert_eq!(v["label"]["folds"][0]["class"], "corner_folded");
    assert!(v["label"]["text"].as_str().unwrap().contains("Corner 2 is folded"));
    assert!(v["metrics"]["rmse"].as_f64().unwrap() < 0.05);
}

#[test]
fn analyze_reads_one_text_file_per_frame() {
    let dir = TempDir::new("cli-text");
    let start = napkin(10);
    let end = fold_frame(&start, 5.0, 25.0);
    let a = write(&dir, "start.csv", frame_text(&start).as_bytes());
    let b = write(&dir, "end.txt", frame_text(&end).replace(',', " ").as_bytes());
    let out = close(&["analyze", &a, &b, "--json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["folds"].as_array().unwrap().len(), 1);
    assert_eq!(v["label"]["folds"][0]["class"], "folded_in_half");
}

#[test]
fn every_bad_input_gets_a_clear_error() {
    let dir = TempDir::new("cli-bad");
    let square = frame_text(&napkin(3));
    let cases: Vec<(Vec<String>, &str)> = vec![
        (vec![write(&dir, "garbage.json", b"{not json")], "could not parse sample JSON"),
        (vec![write(&dir, "empty.json", b"")], "empty"),
        (vec![write(&dir, "empty.txt", b"")], "no vertex"),
        (vec![write(&dir, "words.txt", b"0,0,0\n1,one,0\n")], "line 2"),
        (vec![write(&dir, "nan.txt", square.replacen("0.5", "NaN", 1).as_bytes())], "non-finite"),
        (
            vec![write(&dir, "few.json", br#"{"frames": [[[0,0,0],[1,0,0],[0,1,0]]]}"#)],
            "too few vertices",
        ),
        (
            vec![write(
                &dir,
                "line.json",
                br#"{"frames": [[[0,0,0],[1,1,0],[2,2,0],[3,3,0],[4,4,0]]]}"#,
            )],
            "degenerate",
        ),
        (
            vec![write(
                &dir,
                "same.json",
                br#"{"frames": [[[1,1,1],[1,1,1],[1,1,1],[1,1,1],[1,1,1]]]}"#,
            )],
            "degenerate",
        ),
        (
            vec![
                write(&dir, "a.txt", square.as_bytes()),
                write(&dir, "b.txt", frame_text(&napkin(4)).as_bytes()),
            ],
            "has 16 vertices but frame 0 has 12",
        ),
        (vec![write(&dir, "huge.txt", "0 0 0\n".repeat(6000).as_bytes())], "too large"),
        (vec![write(&dir, "mesh.stl", b"solid")], "unknown file type"),
        (vec![dir.0.join("missing.json").display().to_string()], "No such file"),
    ];
    for (files, expected) in cases {
        let mut args = vec!["analyze"];
        args.extend(files.iter().map(String::as_str));
        let out = close(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{files:?} should fail");
        assert!(stderr.to_lowercase().contains(&expected.to_lowercase()), "{files:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{files:?}: {stderr}");
    }
}

#[test]
fn frame_range_is_checked() {
    let path = fixture("reference/folded/napkin__diag_half.json");
    let out = close(&["analyze", path.to_str().unwrap(), "--start", "3"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("frame 3 does not exist"));
}

/// Two reference samples of two categories: the table has their rows (the whole
/// reference set is evaluated in tests/reference.rs, the built-in set in tests/dataset.rs).
#[test]
fn eval_prints_a_table_per_category() {
    let dir = TempDir::new("cli-eval");
    for name in ["napkin__corner_sym__jitter.json", "towel__half_short.json"] {
        std::fs::copy(fixture("reference/folded").join(name), dir.0.join(name)).unwrap();
    }
    let out = close(&["eval", dir.0.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let table = String::from_utf8(out.stdout).unwrap();
    for row in ["napkin", "towel", "overall"] {
        assert!(table.lines().any(|l| l.starts_with(row)), "no row {row} in\n{table}");
    }
    let json = close(&["eval", fixture("reference/nofold").to_str().unwrap(), "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&json.stdout).unwrap();
    assert_eq!(v["overall"]["count"], 1);
    assert_eq!(v["overall"]["fold_count_misses"], 0);
}

#[test]
fn eval_scores_second_folds_apart() {
    let dir = TempDir::new("cli-second");
    let start = napkin(19);
    let first = fold_frame(&start, 9.5, 47.5);
    // Then the bottom-left corner of the folded cloth (a single layer there).
    let second = fold_frame(&first, 66.5, 5.0);
    let n = start.len() as f64;
    let angle = |f: f64| 2.0 * std::f64::consts::PI * f / n;
    let sample = serde_json::json!({
        "name": "half_then_half", "category": "napkin_second_fold",
        "frames": [start, first, second],
        "truth": {"folds": [[angle(9.5), angle(47.5)], [angle(66.5), angle(5.0)]]},
    });
    write(&dir, "twice.json", sample.to_string().as_bytes());
    let out = close(&["eval", dir.0.to_str().unwrap(), "--json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let folds = &v["categories"][0]["by_fold"];
    assert_eq!(folds.as_array().unwrap().len(), 2);
    for k in 0..2 {
        assert_eq!(folds[k]["found"], 1);
        assert!(folds[k]["rmse"]["mean"].as_f64().unwrap() < 0.05, "{folds}");
        assert!(folds[k]["f1_error"]["mean"].as_f64().unwrap() < 0.05, "{folds}");
    }
    let table = String::from_utf8(close(&["eval", dir.0.to_str().unwrap()]).stdout).unwrap();
    assert!(table.contains("  fold 2"), "{table}");
}

/// `close dataset` writes every built-in sample, and the files read back as samples that
/// `close eval` takes (two of them here: the built-in evaluation runs in tests/dataset.rs).
#[test]
fn the_builtin_dataset_exports_and_evaluates() {
    let dir = TempDir::new("cli-dataset");
    let out = close(&["dataset", dir.0.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let data = close::dataset::Dataset::builtin();
    let files = std::fs::read_dir(&dir.0).unwrap().count();
    assert_eq!(files, data.entries().len());
    let picked = ["napkin__diagonal", "physics__h1_half_left_onto_right_31x31"]
        .map(|id| dir.0.join(format!("{id}.json")));
    let exported = close::formats::json::parse_sample(&std::fs::read(&picked[0]).unwrap()).unwrap();
    assert_eq!(Some(&exported), data.get("napkin__diagonal").map(|e| &e.sample));
    let eval = close(&["eval", picked[0].to_str().unwrap(), picked[1].to_str().unwrap(), "--json"]);
    assert!(eval.status.success(), "{}", String::from_utf8_lossy(&eval.stderr));
    let v: serde_json::Value = serde_json::from_slice(&eval.stdout).unwrap();
    assert_eq!(v["overall"]["count"], 2);
    assert_eq!(v["overall"]["errors"], 0);
    let categories: Vec<&str> =
        v["categories"].as_array().unwrap().iter().filter_map(|c| c["category"].as_str()).collect();
    assert_eq!(categories, ["napkin", "physics"]);
}

/// A server whose address is taken fails at once, saying so, with the status of a failure
/// (1), not of a command line that does not fit (2, as an address that does not parse).
#[test]
fn a_taken_address_is_a_failure_to_serve_not_a_usage_error() {
    let taken = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let addr = taken.local_addr().unwrap().to_string();
    let out = close(&["serve", "--addr", &addr]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains(&format!("cannot serve on {addr}")), "{stderr}");
    let out = close(&["serve", "--addr", "not-an-address"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("--addr not-an-address"), "{stderr}");
}
