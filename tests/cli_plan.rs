//! `close plan`: the plan printed for a sample, with input vertex indices.

use std::process::Command;

const SQUARE: &str = "tests/fixtures/plan/square_cw_diagonal.json";

fn close(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_close")).args(args).output().expect("the close binary runs")
}

#[test]
fn plan_json_reports_input_vertex_indices() {
    // A 16-vertex square given clockwise, folded along its diagonal: border vertex 4, the
    // folded corner, is input vertex 12. The goal is the same diagonal.
    let out = close(&["plan", SQUARE, "--goal", "0,3.141592653589793", "--json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let plan: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(plan["case"], "direct");
    let step = &plan["steps"][0];
    assert_eq!(step["corners"], serde_json::json!([2]));
    assert_eq!(step["picks"][0]["vertex"], 12);
    let to: Vec<f64> = serde_json::from_value(step["picks"][0]["to"].clone()).unwrap();
    assert!(to[0].abs() < 1e-9 && (to[1] - 1.0).abs() < 1e-9, "{to:?}");
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
