//! The browser's fold interpolation (`web/fold.mjs`, run in node) agrees with the Rust one
//! (`close::interpolate`) to 1e-9, folds and folded borders, on edge and random cases.

use std::f64::consts::{PI, TAU};
use std::io::Write;
use std::process::{Command, Stdio};

use close::border::Point;
use close::interpolate::interpolate;
use close::rng::SplitMix64;
use serde_json::{json, Value};

/// node reads the cases on stdin, runs the module's functions, prints the answers.
const SCRIPT: &str = r#"
const { foldPath, applyFold } = await import(process.argv[1]);
let input = "";
for await (const chunk of process.stdin) input += chunk;
const { border, cases } = JSON.parse(input);
const out = cases.map(([from, to, steps]) => {
  const folds = foldPath(from, to, steps);
  return { folds, borders: folds.map((f) => applyFold(border, f)) };
});
process.stdout.write(JSON.stringify(out));
"#;

#[test]
#[ignore = "needs node (apt-get install nodejs); run with `cargo test -- --ignored`"]
fn browser_and_server_interpolate_alike() {
    if Command::new("node").arg("--version").output().is_err() {
        panic!("node is not installed: the JS/Rust parity test needs it (apt-get install nodejs)");
    }
    // An irregular 13-gon (x, y, z), so reflections of every edge are exercised.
    let border: Vec<[f64; 3]> =
        (0..13).map(|k| k as f64 * TAU / 13.0).map(|a| [(1.0 + 0.3 * (3.0 * a).sin()) * a.cos(), (1.0 + 0.2 * (2.0 * a).cos()) * a.sin(), 0.1 * a]).collect();
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
    let input = json!({ "border": border, "cases": cases.iter().map(|(f, t, s)| json!([f, t, s])).collect::<Vec<_>>() });

    let module = format!("file://{}/web/fold.mjs", env!("CARGO_MANIFEST_DIR"));
    let mut child = Command::new("node")
        .args(["--input-type=module", "-e", SCRIPT, &module])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn node");
    child.stdin.take().expect("stdin").write_all(input.to_string().as_bytes()).expect("write cases");
    let output = child.wait_with_output().expect("node runs");
    assert!(output.status.success(), "node failed: {}", String::from_utf8_lossy(&output.stderr));
    let js: Vec<Value> = serde_json::from_slice(&output.stdout).expect("node prints JSON");
    assert_eq!(js.len(), cases.len());

    let points: Vec<Point> = border.iter().map(|&p| Point::from(p)).collect();
    for ((from, to, steps), js) in cases.iter().zip(&js) {
        let rust = interpolate(&points, *from, *to, *steps).expect("valid case");
        let js_folds: Vec<[f64; 2]> = serde_json::from_value(js["folds"].clone()).expect("folds");
        let js_borders: Vec<Vec<[f64; 3]>> = serde_json::from_value(js["borders"].clone()).expect("borders");
        assert_eq!(js_folds.len(), rust.folds.len());
        for (k, (a, b)) in rust.folds.iter().zip(&js_folds).enumerate() {
            assert!((a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9, "{from:?} → {to:?} step {k}: rust {a:?}, js {b:?}");
        }
        for (k, (a, b)) in rust.borders.iter().zip(&js_borders).enumerate() {
            let worst = a.iter().zip(b).flat_map(|(p, q)| (0..3).map(move |c| (p[c] - q[c]).abs())).fold(0.0, f64::max);
            assert!(worst < 1e-9, "{from:?} → {to:?} step {k}: borders differ by {worst}");
        }
    }
}
