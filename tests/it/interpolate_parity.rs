//! The browser's fold interpolation (`web/fold.mjs`, run in node) agrees with the Rust one
//! (`close::interpolate`) to 1e-9, folds and folded borders, on edge and random cases: folds
//! moving on the fold circle, and folds whose arcs turn over about one line (multi-arc folds
//! of an analysis, and random arcs and lines).

use std::f64::consts::{PI, TAU};
use std::io::Write;
use std::process::{Command, Stdio};

use close::border::{to_xyz, Point};
use close::fold::apply;
use close::geometry::{Point2, Vector2};
use close::interpolate::{interpolate, Motion};
use close::rng::SplitMix64;
use close::{analyze, FrameRange};
use close::{Arc, Fold, Line};
use serde_json::{json, Value};

use crate::common::samples_in;

/// node reads the cases on stdin, runs the module's functions, prints the answers.
const SCRIPT: &str = r#"
const { foldPath, applyFold, turnPath } = await import(process.argv[1]);
let input = "";
for await (const chunk of process.stdin) input += chunk;
const { border, cases, turns } = JSON.parse(input);
const out = cases.map(([from, to, steps]) => {
  const folds = foldPath(from, to, steps);
  return { folds, borders: folds.map((f) => applyFold(border, f)) };
});
const turned = turns.map(({ border, arcs, line, steps }) => turnPath(border, arcs, line, steps));
process.stdout.write(JSON.stringify({ out, turned }));
"#;

/// Runs [`SCRIPT`] on `input` in node.
fn node(input: &Value) -> Value {
    if Command::new("node").arg("--version").output().is_err() {
        panic!("node is not installed: the JS/Rust parity test needs it (apt-get install nodejs)");
    }
    let module = format!("file://{}/web/fold.mjs", env!("CARGO_MANIFEST_DIR"));
    let mut child = Command::new("node")
        .args(["--input-type=module", "-e", SCRIPT, &module])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn node");
    child
        .stdin
        .take()
        .expect("stdin")
        .write_all(input.to_string().as_bytes())
        .expect("write cases");
    let output = child.wait_with_output().expect("node runs");
    assert!(output.status.success(), "node failed: {}", String::from_utf8_lossy(&output.stderr));
    serde_json::from_slice(&output.stdout).expect("node prints JSON")
}

/// The largest coordinate difference between two lists of borders.
fn worst(a: &[Vec<[f64; 3]>], b: &[Vec<[f64; 3]>]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .flat_map(|(p, q)| p.iter().zip(q))
        .flat_map(|(p, q)| (0..3).map(move |c| (p[c] - q[c]).abs()))
        .fold(0.0, f64::max)
}

#[test]
#[ignore = "needs node (apt-get install nodejs); run with `cargo test -- --ignored`"]
fn browser_and_server_interpolate_alike() {
    // An irregular 13-gon (x, y, z), so reflections of every edge are exercised.
    let border: Vec<[f64; 3]> = (0..13)
        .map(|k| k as f64 * TAU / 13.0)
        .map(|a| {
            [
                (1.0 + 0.3 * (3.0 * a).sin()) * a.cos(),
                (1.0 + 0.2 * (2.0 * a).cos()) * a.sin(),
                0.1 * a,
            ]
        })
        .collect();
    let q = PI / 8.0;
    let mut cases: Vec<([f64; 2], [f64; 2], usize)> = vec![
        ([0.0, PI], [PI / 2.0, 1.5 * PI], 5),
        ([15.0 * q, q], [q, 3.0 * q], 9),
        ([0.1, 0.3], [0.2, 0.1], 17),
        ([3.0, 3.0], [3.0, 1.0], 11),
        ([0.0, PI], [PI, 0.0], 8),
        ([-1.0, 7.5], [13.0, -0.2], 6),
    ];
    let mut rng = SplitMix64::new(42);
    cases.extend((0..200).map(|_| {
        let mut angle = || rng.uniform() * 8.0 - 1.0;
        ([angle(), angle()], [angle(), angle()], 2 + (rng.uniform() * 30.0) as usize)
    }));
    let input = json!({ "border": border, "cases": cases.iter().map(|(f, t, s)| json!([f, t, s])).collect::<Vec<_>>(), "turns": [] });
    let js: Vec<Value> = serde_json::from_value(node(&input)["out"].clone()).expect("a list");
    assert_eq!(js.len(), cases.len());

    for ((from, to, steps), js) in cases.iter().zip(&js) {
        let motion = Motion::Between { from: Fold::from(*from), to: Fold::from(*to) };
        let rust = interpolate(border.clone(), None, &motion, *steps).expect("valid case");
        let js_folds: Vec<[f64; 2]> = serde_json::from_value(js["folds"].clone()).expect("folds");
        let js_borders: Vec<Vec<[f64; 3]>> =
            serde_json::from_value(js["borders"].clone()).expect("borders");
        assert_eq!(js_folds.len(), rust.folds.len());
        for (k, (a, b)) in rust.folds.iter().zip(&js_folds).enumerate() {
            assert!(
                (a.f1 - b[0]).abs() < 1e-9 && (a.f2 - b[1]).abs() < 1e-9,
                "{from:?} → {to:?} step {k}: rust {a:?}, js {b:?}"
            );
        }
        let worst = worst(&rust.borders, &js_borders);
        assert!(worst < 1e-9, "{from:?} → {to:?}: borders differ by {worst}");
    }
}

/// A turned fold: the arcs and lines of every folded step of the MuJoCo second folds (the
/// trousers' and the shirt's multi-arc ones among them) on the state before it, and random
/// arcs about random lines (or the default line through the span) on an irregular 13-gon.
#[test]
#[ignore = "needs node (apt-get install nodejs); run with `cargo test -- --ignored`"]
fn browser_and_server_turn_arcs_alike() {
    // A state, its flat reference, its arcs, the line they turn about and the number of
    // interpolated states.
    type Turn = (Vec<Point>, Option<Vec<[f64; 3]>>, Vec<Arc>, Option<Line>, usize);
    let mut turns: Vec<Turn> = Vec::new();
    for sample in samples_in("physics-mujoco/border") {
        let analysis = analyze(&sample.border_frames().unwrap(), FrameRange::default()).unwrap();
        let mut state = analysis.start_border().to_vec();
        let flat: Vec<[f64; 3]> = state.iter().map(to_xyz).collect();
        for step in analysis.foldings() {
            let line = step.line.expect("a fold has a line");
            turns.push((state.clone(), Some(flat.clone()), step.arcs.clone(), Some(line), 9));
            state = apply(&state, &step);
        }
    }
    assert!(
        turns.iter().any(|(_, _, arcs, _, _)| arcs.len() > 1),
        "a multi-arc fold among the cases"
    );
    let gon: Vec<Point> = (0..13)
        .map(|k| k as f64 * TAU / 13.0)
        .map(|a| {
            Point::new(
                (1.0 + 0.3 * (3.0 * a).sin()) * a.cos(),
                (1.0 + 0.2 * (2.0 * a).cos()) * a.sin(),
                0.1 * a,
            )
        })
        .collect();
    let mut rng = SplitMix64::new(7);
    for case in 0..100 {
        let mut cuts: Vec<f64> = (0..2 + 2 * (case % 3)).map(|_| rng.uniform() * TAU).collect();
        cuts.sort_by(f64::total_cmp);
        let arcs: Vec<Arc> = cuts.chunks(2).map(|c| Arc::new(c[0], c[1])).collect();
        let phi = rng.uniform() * PI;
        let line = (case % 4 != 0).then(|| Line {
            point: Point2::new(rng.uniform() - 0.5, rng.uniform() - 0.5),
            direction: Vector2::new(phi.cos(), phi.sin()),
        });
        turns.push((gon.clone(), None, arcs, line, 2 + (rng.uniform() * 20.0) as usize));
    }
    let rust: Vec<_> = turns
        .iter()
        .map(|(border, reference, arcs, line, steps)| {
            let turn = Motion::Turn { arcs: arcs.clone(), line: *line };
            let state = border.iter().map(to_xyz).collect();
            interpolate(state, reference.clone(), &turn, *steps).expect("a valid turn")
        })
        .collect();
    let xyz = |b: &[Point]| b.iter().map(|p| [p.x, p.y, p.z]).collect::<Vec<_>>();
    let input = json!({
        "border": [],
        "cases": [],
        "turns": turns.iter().map(|(border, _, arcs, line, steps)| json!({"border": xyz(border), "arcs": arcs, "line": line, "steps": steps})).collect::<Vec<_>>(),
    });
    let js = node(&input)["turned"].clone();
    for (k, (rust, js)) in rust.iter().zip(js.as_array().expect("a list")).enumerate() {
        let js_turns: Vec<f64> = serde_json::from_value(js["turns"].clone()).expect("turns");
        let js_borders: Vec<Vec<[f64; 3]>> =
            serde_json::from_value(js["borders"].clone()).expect("borders");
        assert_eq!(Some(js_turns), rust.turns, "case {k}");
        let worst = worst(&rust.borders, &js_borders);
        assert!(worst < 1e-9, "case {k} ({:?}): borders differ by {worst}", turns[k].2);
    }
}
