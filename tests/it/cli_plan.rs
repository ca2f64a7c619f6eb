//! `close plan`: the plan printed for a sample, with input vertex indices.

use std::process::Command;

const SQUARE: &str = "tests/fixtures/plan/square_cw_diagonal.json";

fn close(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_close")).args(args).output().expect("the close binary runs")
}

#[test]
fn plan_json_reports_input_vertex_indices() {
    // A 16-vertex square given clockwise, folded along its diagonal: border vertex 4, the
    // folded corner, is input vertex 12. The goal folds the same corner along the line from
    // border vertex 1 to 7 (input vertices 15 and 9: y = x − 0.25), so it goes direct, from
    // where the diagonal put it, (0, 1), to its mirror image (0.25, 0.75).
    let out = close(&["plan", SQUARE, "--goal", "0.39269908169872414,2.748893571891069", "--json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let plan: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(plan["case"], "direct");
    let step = &plan["steps"][0];
    assert_eq!(step["corners"], serde_json::json!([2]));
    assert_eq!(step["picks"][0]["vertex"], 12);
    let from: Vec<f64> = serde_json::from_value(step["picks"][0]["from"].clone()).unwrap();
    let to: Vec<f64> = serde_json::from_value(step["picks"][0]["to"].clone()).unwrap();
    assert!(from[0].abs() < 1e-9 && (from[1] - 1.0).abs() < 1e-9, "{from:?}");
    assert!((to[0] - 0.25).abs() < 1e-9 && (to[1] - 0.75).abs() < 1e-9, "{to:?}");
}

#[test]
fn a_goal_already_reached_needs_no_step() {
    // The goal is the diagonal the square is already folded along.
    let out = close(&["plan", SQUARE, "--goal", "0,3.141592653589793", "--json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let plan: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(plan["case"], "already_there");
    assert_eq!(plan["steps"], serde_json::json!([]));
}

#[test]
fn plan_rejects_a_bad_goal_plainly() {
    let out = close(&["plan", SQUARE, "--goal", "1"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("two angles"));
    let out = close(&["plan", SQUARE, "--goal", "1,1.01"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("more than one edge"));
}
