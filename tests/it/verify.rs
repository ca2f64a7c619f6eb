//! `close verify` and `close::verify` on folds nobody here chose: the simulators' commanded
//! folds (`truth.folds`) against what the analysis saw of the cloth, and the command line.

use std::process::Command;

use crate::common::{fixture, samples_in};
use close::verify::{verify, Goal, Status, Tolerance};
use close::{analyze, FrameRange};

fn close(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_close")).args(args).output().expect("the close binary runs")
}

#[test]
fn every_state_reaches_its_own_folds_at_distance_zero() {
    // Through the whole pipeline, the multi-arc and stacked folds included: the analysed
    // folds as the goal are found where they are, and the shapes agree exactly.
    for dir in ["physics", "physics-mujoco/border"] {
        for sample in samples_in(dir) {
            let analysis =
                analyze(&sample.border_frames().unwrap(), FrameRange::default()).unwrap();
            let answer =
                verify(&analysis, &Goal::folds(analysis.folds.clone()), Tolerance::default())
                    .unwrap();
            assert!(answer.reached, "{}: {}", sample.name, answer.text);
            assert_eq!(answer.distance.folds, 0.0, "{}", sample.name);
            assert!(
                answer.distance.geometric.unwrap() < 1e-9,
                "{}: {:?}",
                sample.name,
                answer.distance
            );
        }
    }
}

#[test]
fn the_simulators_commanded_folds_are_reached_where_the_cloth_took_them() {
    // The first simulator's folds (`tests/fixtures/physics`), against the fold each run
    // commanded. Measured (2026-12-02): every single fold reached but the pentagon's askew
    // one, which the cloth took 2.4 edges short of the command (its README's floor for it
    // is the highest of the set); both two-fold sequences reached; the shirt's sleeve
    // then half not (its first fold 1.9 edges short).
    let (mut reached, mut total) = (0, 0);
    for sample in samples_in("physics") {
        let truth = sample.truth.as_ref().expect("physics folds have truth").folds.clone();
        let analysis = analyze(&sample.border_frames().unwrap(), FrameRange::default()).unwrap();
        let answer = verify(&analysis, &Goal::folds(truth.clone()), Tolerance::default()).unwrap();
        total += 1;
        reached += usize::from(answer.reached);
        // Whatever the outcome, every goal fold was made: none is missing, and the error
        // of each point is under three edges.
        for (k, f) in answer.folds.iter().enumerate() {
            assert_ne!(
                f.status,
                Status::Missing,
                "{}: fold {}: {}",
                sample.name,
                k + 1,
                answer.text
            );
            let worst = f.error_edges.unwrap().map(f64::abs);
            assert!(worst[0].max(worst[1]) < 3.0, "{}: fold {}: {worst:?}", sample.name, k + 1);
        }
        assert_eq!(answer.reached, answer.text.starts_with("goal reached"), "{}", answer.text);
    }
    assert_eq!(total, 10);
    assert!(reached >= 8, "{reached} of {total} commanded folds reached");
}

const SQUARE: &str = "tests/fixtures/plan/square_cw_diagonal.json";

#[test]
fn the_command_line_says_reached_or_what_to_do() {
    // A 16-vertex square folded along its diagonal from border vertex 0 to 8.
    let out = close(&["verify", SQUARE, "--goal", "0,3.141592653589793"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(String::from_utf8_lossy(&out.stdout).starts_with("goal reached"));
    // The other diagonal was wanted: four edges off at both points, and the plan's grasps.
    let out = close(&["verify", SQUARE, "--goal", "1.5707963267948966,4.71238898038469", "--json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["reached"], false);
    assert_eq!(v["folds"][0]["status"], "misplaced");
    let errors: Vec<f64> = serde_json::from_value(v["folds"][0]["error_edges"].clone()).unwrap();
    assert!(errors.iter().all(|e| (e.abs() - 4.0).abs() < 1e-9), "{errors:?}");
    assert_eq!(v["distance"]["folds"], 0.5);
    assert_eq!(v["plan"]["case"], "unfold_then_fold");
    assert!(v["text"].as_str().unwrap().contains("grasp vertex 12"), "{}", v["text"]);
    // A sequence of two goal folds: the second is missing, and the plan makes it on the state
    // the first left.
    let out = close(&["verify", SQUARE, "--goal", "0,3.141592653589793;1.5,4.0", "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        (v["folds"][0]["status"].as_str(), v["folds"][1]["status"].as_str()),
        (Some("found"), Some("missing"))
    );
    assert_eq!(v["plan"]["case"], "fold");
    let steps = v["plan"]["steps"].as_array().expect("steps");
    assert_eq!(steps.len(), 1, "{}", v["plan"]);
    assert_eq!(steps[0]["fold"], serde_json::json!([1.5, 4.0]));
}

#[test]
fn the_command_line_refuses_bad_goals_plainly() {
    for (goal, words) in [
        ("1", "not two angles"),
        ("1,2;3", "fold 2"),
        ("1,x", "fold 1"),
        ("1,1.01", "more than"),
        ("nan,1", "not finite"),
    ] {
        let out = close(&["verify", SQUARE, "--goal", goal]);
        assert!(!out.status.success(), "{goal}");
        let error = String::from_utf8_lossy(&out.stderr);
        assert!(error.contains(words), "{goal}: {error}");
    }
    let out = close(&["verify", SQUARE, "--goal", "0,3", "--tolerance-edges=-1"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("tolerance edges"));
    assert!(fixture("plan/square_cw_diagonal.json").is_file());
}
