//! Fold sequences read from the start and the end alone (issue 26): a cloth folded twice or
//! three times, the frames between dropped, analysed as [start, end].
//!
//! Two sources, neither of them the method:
//! - the development set's nine two-fold sequences (the six MuJoCo ones and the three
//!   3-frame ones of `tests/fixtures/physics`), against the floor of `endscheck.py`: the
//!   observed folds redone exactly from the start, each step's reflection line (the
//!   perpendicular bisector of its folded vertices' moves) carried onto the synthesised state
//!   by the rigid motion that best maps the observed frame before it onto that state;
//! - exact sequences made here by reflecting every layer on one side of a line, the flap laid
//!   on top (napkins in quarters and eighths, towels in thirds, sides in then in half, and
//!   random convex cloths folded twice along random lines), turned, moved and scaled.

use crate::common;

use close::border::{Normalisation, Point};
use close::metrics::Metrics;
use close::rng::SplitMix64;
use close::{analyze, Analysis, FrameRange, Sample};
use common::fixture;
use serde_json::json;

/// The 2-D rigid motion (c, s, tx, ty) that best maps `p` onto `q` (closed-form Kabsch).
fn kabsch(p: &[[f64; 3]], q: &[[f64; 3]]) -> [f64; 4] {
    let n = p.len() as f64;
    let centre = |a: &[[f64; 3]]| {
        let (x, y) = a.iter().fold((0.0, 0.0), |(x, y), v| (x + v[0], y + v[1]));
        (x / n, y / n)
    };
    let ((px, py), (qx, qy)) = (centre(p), centre(q));
    let (mut dot, mut cross) = (0.0, 0.0);
    for (a, b) in p.iter().zip(q) {
        let (ax, ay, bx, by) = (a[0] - px, a[1] - py, b[0] - qx, b[1] - qy);
        dot += ax * bx + ay * by;
        cross += ax * by - ay * bx;
    }
    let th = cross.atan2(dot);
    let (c, s) = (th.cos(), th.sin());
    [c, s, qx - (c * px - s * py), qy - (s * px + c * py)]
}

/// Reflect the vertices `moved` of `state` across the line through `a` along the unit `u`,
/// each laid on top of the stack (its height mirrored above the highest vertex).
fn reflect(state: &mut [[f64; 3]], moved: &[usize], a: [f64; 2], u: [f64; 2]) {
    let top = state.iter().map(|p| p[2]).fold(f64::NEG_INFINITY, f64::max);
    for &v in moved {
        let (dx, dy) = (state[v][0] - a[0], state[v][1] - a[1]);
        let t = dx * u[0] + dy * u[1];
        state[v] = [
            a[0] + 2.0 * t * u[0] - dx,
            a[1] + 2.0 * t * u[1] - dy,
            2.0 * top + 0.004 - state[v][2],
        ];
    }
}

/// The floor of `endscheck.py`: the observed folds redone exactly from the start.
fn floor(frames: &[Vec<[f64; 3]>], folded: &[Vec<usize>]) -> Vec<[f64; 3]> {
    let mut state = frames[0].clone();
    for (j, moved) in folded.iter().enumerate() {
        let (before, after) = (&frames[j], &frames[j + 1]);
        // The reflection line of the observed step: normal along the folded vertices' mean
        // move, through the mean of their midpoints.
        let (mut nx, mut ny, mut pairs) = (0.0, 0.0, Vec::new());
        for &v in moved {
            let (dx, dy) = (after[v][0] - before[v][0], after[v][1] - before[v][1]);
            let d = dx.hypot(dy);
            if d > 1e-9 {
                nx += dx / d;
                ny += dy / d;
                pairs.push(v);
            }
        }
        let h = nx.hypot(ny);
        assert!(h > 1e-12, "step {j} moved nothing");
        let (nx, ny) = (nx / h, ny / h);
        let c = pairs
            .iter()
            .map(|&v| {
                (before[v][0] + after[v][0]) / 2.0 * nx + (before[v][1] + after[v][1]) / 2.0 * ny
            })
            .sum::<f64>()
            / pairs.len() as f64;
        let [mc, ms, tx, ty] = kabsch(before, &state);
        let a = [mc * c * nx - ms * c * ny + tx, ms * c * nx + mc * c * ny + ty];
        let u = [mc * -ny - ms * nx, ms * -ny + mc * nx];
        reflect(&mut state, moved, a, u);
    }
    state
}

fn points(frame: &[[f64; 3]]) -> Vec<Point> {
    frame.iter().map(|p| Point::new(p[0], p[1], p[2])).collect()
}

/// The metrics of `predicted` against `end`, normalised by `start` as the judge does.
fn measure(start: &[[f64; 3]], predicted: &[[f64; 3]], end: &[[f64; 3]]) -> Metrics {
    let norm = Normalisation::of(&points(start)).unwrap();
    Metrics::measure(&norm, &points(predicted), &points(end))
}

fn start_and_end(frames: &[Vec<[f64; 3]>]) -> Analysis {
    let two = Sample::from_frames(
        "start and end",
        "cloth",
        vec![frames[0].clone(), frames[frames.len() - 1].clone()],
    );
    analyze(&two.border_frames().unwrap(), FrameRange::default()).unwrap()
}

fn mean(values: impl Iterator<Item = f64>) -> f64 {
    let (sum, n) = values.fold((0.0, 0), |(s, n), v| (s + v, n + 1));
    sum / f64::from(n.max(1))
}

/// The nine development sequences, their middle frames dropped: the right fold count on at
/// least 8, the RMSE and the aligned RMSE within 1.5 times the floor's (issue 26's targets;
/// measured 9 of 9, RMSE 0.0441 against 0.0398, aligned 0.0161 against 0.0331; one fold per
/// step gave 0.696 and 0.521). The raw RMSE holds only when the layers are ordered right: a
/// sequence whose layers lie in another order lands as the end turned by a half turn.
#[test]
fn development_sequences_from_start_and_end() {
    let mut files: Vec<_> = ["physics-mujoco/border", "physics"]
        .iter()
        .flat_map(|d| std::fs::read_dir(fixture(d)).unwrap().map(|e| e.unwrap().path()))
        .collect();
    files.sort();
    let mut rows = Vec::new();
    for file in files {
        let json: serde_json::Value =
            serde_json::from_slice(&std::fs::read(&file).unwrap()).unwrap();
        let folded: Vec<Vec<usize>> = match json["truth"]["folded_vertices_per_fold"].as_array() {
            Some(per_fold) if per_fold.len() >= 2 => per_fold
                .iter()
                .map(|f| {
                    f.as_array().unwrap().iter().map(|v| v.as_u64().unwrap() as usize).collect()
                })
                .collect(),
            _ => continue,
        };
        let frames: Vec<Vec<[f64; 3]>> = serde_json::from_value(json["frames"].clone()).unwrap();
        assert_eq!(frames.len(), folded.len() + 1, "{file:?}");
        let analysis = start_and_end(&frames);
        let (start, end) = (&frames[0], &frames[frames.len() - 1]);
        let floor = measure(start, &floor(&frames, &folded), end);
        let found = analysis.metrics.unwrap();
        println!(
            "{:40} folds {} of {}: RMSE {:.4} (floor {:.4}), aligned {:.4} (floor {:.4})",
            file.file_stem().unwrap().to_string_lossy(),
            analysis.folds.len(),
            folded.len(),
            found.rmse,
            floor.rmse,
            found.aligned_rmse,
            floor.aligned_rmse
        );
        rows.push((analysis.folds.len() == folded.len(), found, floor));
        // Read as a person names them: two halves are quarters; a sleeve, then the shirt in
        // half, is not thirds (its sleeve flap is far shorter than the half).
        let name = file.file_stem().unwrap().to_string_lossy().into_owned();
        let sequence = analysis.label.sequence.as_ref().map(|s| (json!(s.class), &s.in_half));
        println!("  {}", analysis.label.text);
        if name.contains("half_then_half") || name.contains("half_then_quarter") {
            assert_eq!(sequence.as_ref().map(|s| &s.0), Some(&json!("in_quarters")), "{name}");
        }
        if name.contains("sleeve_then_half") {
            assert_eq!(sequence, Some((json!("folds"), &vec![false, true])), "{name}");
        }
    }
    assert_eq!(rows.len(), 9);
    let right = rows.iter().filter(|r| r.0).count();
    let rmse = mean(rows.iter().map(|r| r.1.rmse));
    let floor_rmse = mean(rows.iter().map(|r| r.2.rmse));
    let aligned = mean(rows.iter().map(|r| r.1.aligned_rmse));
    let floor_aligned = mean(rows.iter().map(|r| r.2.aligned_rmse));
    println!("{right}/9 right; RMSE {rmse:.4} (floor {floor_rmse:.4}), aligned {aligned:.4} (floor {floor_aligned:.4})");
    assert!(right >= 8, "{right} of 9 with the right fold count");
    assert!(rmse <= 1.5 * floor_rmse, "RMSE {rmse} against the floor's {floor_rmse}");
    assert!(
        aligned <= 1.5 * floor_aligned,
        "aligned {aligned} against the floor's {floor_aligned}"
    );
}

/// A rectangle `w` by `h` centred on the origin, `per_unit` vertices per unit of length,
/// anticlockwise from its lower left corner.
fn rectangle(w: f64, h: f64, per_unit: f64) -> Vec<[f64; 3]> {
    let corners =
        [[-w / 2.0, -h / 2.0], [w / 2.0, -h / 2.0], [w / 2.0, h / 2.0], [-w / 2.0, h / 2.0]];
    let mut out = Vec::new();
    for k in 0..4 {
        let (a, b) = (corners[k], corners[(k + 1) % 4]);
        let len = (b[0] - a[0]).hypot(b[1] - a[1]);
        let steps = (len * per_unit).round() as usize;
        for i in 0..steps {
            let t = i as f64 / steps as f64;
            out.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), 0.0]);
        }
    }
    out
}

/// `start` folded along each directed line (a point and an angle, in the coordinates of the
/// state it is made on) in turn: every vertex left of it, whatever its layer, reflected
/// across it and laid on top.
fn fold_in_turn(start: &[[f64; 3]], lines: &[([f64; 2], f64)]) -> Vec<[f64; 3]> {
    let mut state = start.to_vec();
    for &(a, angle) in lines {
        let u = [angle.cos(), angle.sin()];
        let moved: Vec<usize> = (0..state.len())
            .filter(|&v| u[0] * (state[v][1] - a[1]) - u[1] * (state[v][0] - a[0]) > 0.0)
            .collect();
        reflect(&mut state, &moved, a, u);
    }
    state
}

/// Both frames turned by `angle`, scaled by `scale` and moved by `shift`, with a small
/// deterministic in-plane jitter of `noise` (normalised units) on every vertex.
fn placed(
    frame: &[[f64; 3]],
    angle: f64,
    scale: f64,
    shift: [f64; 2],
    noise: f64,
) -> Vec<[f64; 3]> {
    let (c, s) = (angle.cos(), angle.sin());
    frame
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let j = noise * ((12.9898 * k as f64).sin() * 43758.5453).fract();
            let (x, y) = (p[0] + j, p[1] - j);
            [scale * (c * x - s * y) + shift[0], scale * (s * x + c * y) + shift[1], scale * p[2]]
        })
        .collect()
}

/// One exact sequence of the generator: a name, a start, its lines in order and how a
/// person reads it (`label.sequence.class`; of a garment's sides in and its fold in half
/// across, the two orders lay the same outline).
struct Exact {
    name: &'static str,
    start: Vec<[f64; 3]>,
    lines: Vec<([f64; 2], f64)>,
    reads: &'static [&'static str],
}

/// Napkins in quarters and eighths, a towel in thirds, a garment's sides in then in half.
/// Lines sit a little off the vertices (no vertex lies on a crease).
fn exact_sequences() -> Vec<Exact> {
    use std::f64::consts::FRAC_PI_2 as UP;
    let d = 0.013;
    vec![
        Exact {
            name: "napkin in quarters",
            start: rectangle(1.0, 1.0, 30.0),
            lines: vec![([d, 0.0], UP), ([0.0, d], 0.0)],
            reads: &["in_quarters"],
        },
        Exact {
            name: "napkin in quarters, across",
            start: rectangle(1.0, 1.0, 30.0),
            lines: vec![([0.0, -d], 0.0), ([d, 0.0], -UP)],
            reads: &["in_quarters"],
        },
        Exact {
            name: "napkin in eighths",
            start: rectangle(1.0, 1.0, 40.0),
            lines: vec![([d, 0.0], UP), ([0.0, d], 0.0), ([0.25 + d, 0.0], UP)],
            reads: &["in_eighths"],
        },
        Exact {
            name: "towel in thirds",
            start: rectangle(1.5, 1.0, 30.0),
            lines: vec![([-0.25 + d, 0.0], UP), ([0.25 - d, 0.0], -UP)],
            reads: &["in_thirds"],
        },
        Exact {
            name: "sides in, then in half",
            start: rectangle(1.0, 1.4, 30.0),
            lines: vec![([-0.25 + d, 0.0], UP), ([0.25 - d, 0.0], -UP), ([0.0, d], 0.0)],
            reads: &["sides_in_then_half", "half_then_sides_in"],
        },
    ]
}

/// Every exact sequence, placed two ways, from start and end alone. Issue 26 asks the right
/// fold count on at least 90 % and RMSE ≤ 0.01; measured: 10 of 10, all within an aligned
/// RMSE of 0.004 and an RMSE of 0.0053. Placed on the table's axes with no noise, a crease
/// meeting two straight sides square to them leaves every pair within an arc unchanged at
/// both ends; the cut finder's tie-break towards where the rows of g jump puts its points
/// there (without it, 8 of 10). The unturned napkin in eighths lands where it lies only
/// because a line along a side, which turns the whole cloth over, is no fold (with it, its
/// true first fold is crowded out of the carried states and it lands moved rigidly, RMSE
/// 1.71), and the noisy sides-in napkin turned only because a twin moving the cloth
/// markedly further is not taken for its layer order (without that, RMSE 1.40). What is
/// held: at least 9 right, each of those on the end up to a rigid motion, all of those on
/// the end as it lies, each read as a whole as a person says it (`label.sequence.class`),
/// and none of the others reported as a confident fold.
#[test]
fn exact_sequences_from_start_and_end() {
    let mut right = 0;
    let mut total = 0;
    let mut worst: f64 = 0.0;
    let mut landed = 0;
    for case in exact_sequences() {
        let end = fold_in_turn(&case.start, &case.lines);
        for (angle, scale, shift, noise) in
            [(0.0, 1.0, [0.0, 0.0], 0.0), (0.7, 3.0, [5.0, -2.0], 1e-4)]
        {
            let frames =
                [&case.start, &end].map(|f| placed(f, angle, scale, shift, noise)).to_vec();
            let analysis = start_and_end(&frames);
            let m = analysis.metrics.unwrap();
            println!(
                "{} (turned {angle}): folds {} of {}, RMSE {:.4}, aligned {:.4}",
                case.name,
                analysis.folds.len(),
                case.lines.len(),
                m.rmse,
                m.aligned_rmse
            );
            total += 1;
            if analysis.folds.len() == case.lines.len() {
                right += 1;
                worst = worst.max(m.aligned_rmse);
                landed += usize::from(m.rmse <= 0.01);
                let reads = analysis.label.sequence.as_ref().map(|s| json!(s.class));
                assert!(
                    reads.as_ref().is_some_and(|class| case.reads.iter().any(|r| class == r)),
                    "{} read {reads:?}: {}",
                    case.name,
                    analysis.label.text
                );
            } else {
                assert!(
                    analysis.steps[0].unexplained,
                    "{}: {} folds reported with confidence",
                    case.name,
                    analysis.folds.len()
                );
            }
        }
    }
    println!("{right}/{total} right, worst aligned RMSE of those {worst:.4}, {landed} on the end");
    assert!(right >= 9, "{right} of {total} with the right fold count");
    assert_eq!(landed, right, "{landed} of {right} within an RMSE of 0.01");
    assert!(worst <= 0.01, "aligned RMSE {worst}");
}

/// Flat trousers (waist 1 wide, legs 2 long, the crotch halfway up) sampled `per_unit`
/// vertices per unit of length, anticlockwise from the left leg's outer foot.
fn trousers(per_unit: f64) -> Vec<[f64; 3]> {
    let corners =
        [[-0.5, -1.0], [-0.1, -1.0], [0.0, 0.0], [0.1, -1.0], [0.5, -1.0], [0.5, 1.0], [-0.5, 1.0]];
    let mut out = Vec::new();
    for k in 0..corners.len() {
        let (a, b): ([f64; 2], [f64; 2]) = (corners[k], corners[(k + 1) % corners.len()]);
        let steps = ((b[0] - a[0]).hypot(b[1] - a[1]) * per_unit).round().max(1.0) as usize;
        for i in 0..steps {
            let t = i as f64 / steps as f64;
            out.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), 0.0]);
        }
    }
    out
}

/// Issue 26 item 5: a line across both legs of flat trousers, below the crotch, crosses the
/// border four times, and both leg ends turn over: one fold of two arcs, not one arc that
/// also turns the crotch, nor a second fold added for a sliver. Exact reflections, placed
/// two ways, at three heights.
#[test]
fn a_fold_across_both_legs_of_flat_trousers_turns_two_arcs() {
    use std::f64::consts::PI;
    let start = trousers(20.0);
    for y in [-0.7, -0.5 + 0.013, -0.37] {
        let end = fold_in_turn(&start, &[([0.0, y], PI)]);
        for (angle, scale, shift, noise) in
            [(0.0, 1.0, [0.0, 0.0], 0.0), (2.1, 0.3, [-4.0, 9.0], 1e-4)]
        {
            let frames = [&start, &end].map(|f| placed(f, angle, scale, shift, noise)).to_vec();
            let analysis = start_and_end(&frames);
            let m = analysis.metrics.unwrap();
            let arcs: Vec<usize> = analysis.foldings().iter().map(|f| f.arcs.len()).collect();
            println!("line at y = {y} (turned {angle}): arcs {arcs:?}, RMSE {:.4}", m.rmse);
            assert_eq!(arcs, vec![2], "y = {y}: one fold of two arcs");
            assert!(m.rmse <= 0.01 && m.aligned_rmse <= 0.01, "y = {y}: {m:?}");
        }
    }
}

/// A square shrunk to 40 % and jittered by a quarter of its side is no fold, nor a
/// sequence of them: its best candidate leaves the end disk unexplained, so the step is
/// flagged ("changed, but no fold found") and that candidate is only listed.
#[test]
fn a_shrunk_jittered_square_is_changed_but_no_fold() {
    let start = common::napkin(19);
    let mut rng = close::rng::SplitMix64::new(5);
    let mut noise = |scale: f64| (rng.uniform() - 0.5) * scale;
    let shrunk: Vec<[f64; 3]> = start
        .iter()
        .map(|p| [0.4 * p[0] + noise(0.5), 0.4 * p[1] + noise(0.5), noise(0.05)])
        .collect();
    let analysis = start_and_end(&[start, shrunk]);
    let step = &analysis.steps[0];
    assert!(analysis.folds.is_empty(), "{:?}", analysis.folds);
    assert!(step.unexplained && step.folds.is_empty(), "{:?}", step.explained);
    assert!(analysis.label.text.contains("changed, but no fold found"), "{}", analysis.label.text);
}

/// `close analyze --max-folds K` on a napkin folded in quarters, seen flat and folded: the
/// JSON names the step's sequence (`steps[0].folds`, each with its fold, arcs, line and the
/// share it explained; top-level `folds` every fold in order); `--max-folds 1` searches no
/// sequence; 0 is refused with a clear error.
#[test]
fn the_cli_names_the_sequence_and_takes_max_folds() {
    let dir = common::TempDir::new("sequence-cli");
    let start = rectangle(1.0, 1.0, 30.0);
    let end = fold_in_turn(&start, &exact_sequences()[0].lines);
    let sample = Sample::from_frames("quarters", "napkin", vec![start, end]);
    let path = dir.0.join("quarters.json");
    std::fs::write(&path, serde_json::to_vec(&sample).unwrap()).unwrap();
    let run = |extra: &[&str]| {
        let mut args = vec!["analyze", path.to_str().unwrap(), "--json"];
        args.extend(extra);
        std::process::Command::new(env!("CARGO_BIN_EXE_close")).args(&args).output().unwrap()
    };
    let out = run(&[]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let step = &v["steps"][0];
    let folds = step["folds"].as_array().unwrap();
    assert_eq!(folds.len(), 2, "{step}");
    assert_eq!(v["folds"].as_array().unwrap().len(), 2);
    let mut shares = 0.0;
    for (k, fold) in folds.iter().enumerate() {
        assert_eq!(fold["fold"], v["folds"][k]);
        assert!(fold["arcs"].as_array().is_some_and(|a| !a.is_empty()), "{fold}");
        assert!(fold["line"]["direction"].is_array(), "{fold}");
        shares += fold["explained"].as_f64().unwrap();
    }
    assert!((shares - step["explained"].as_f64().unwrap()).abs() < 1e-9);
    assert_eq!(step["unexplained"], false);
    assert!(step["alternatives"].is_array());
    assert_eq!(v["label"]["sequence"]["class"], "in_quarters", "{}", v["label"]["text"]);
    // One fold of quarters leaves most of the end disk unexplained: no confident fold.
    let one = run(&["--max-folds", "1"]);
    assert!(one.status.success());
    let v: serde_json::Value = serde_json::from_slice(&one.stdout).unwrap();
    assert!(v["folds"].as_array().unwrap().is_empty(), "{}", v["folds"]);
    assert_eq!(v["steps"][0]["unexplained"], true);
    assert!(v["label"]["text"].as_str().unwrap().contains("changed, but no fold found"));
    let refused = run(&["--max-folds", "0"]);
    assert!(!refused.status.success());
    assert!(String::from_utf8_lossy(&refused.stderr).contains("max-folds"));
}

/// A random line across `state` (a direction and a point within 0.3 of the cloth's reach of
/// its centroid, pointing the other way half the time) that turns over between 20 % and
/// 60 % of the vertices, as `fold_in_turn` takes it.
fn random_line(rng: &mut SplitMix64, state: &[[f64; 3]]) -> ([f64; 2], f64) {
    let n = state.len() as f64;
    let centre =
        [state.iter().map(|p| p[0]).sum::<f64>() / n, state.iter().map(|p| p[1]).sum::<f64>() / n];
    let reach =
        state.iter().map(|p| (p[0] - centre[0]).hypot(p[1] - centre[1])).fold(0.0, f64::max);
    loop {
        let angle = std::f64::consts::TAU * rng.uniform();
        let offset = 0.6 * reach * (rng.uniform() - 0.5);
        let a = [centre[0] - offset * angle.sin(), centre[1] + offset * angle.cos()];
        let u = [angle.cos(), angle.sin()];
        let left =
            state.iter().filter(|p| u[0] * (p[1] - a[1]) - u[1] * (p[0] - a[0]) > 0.0).count();
        let share = left as f64 / n;
        if (0.2..=0.6).contains(&share) {
            return (a, angle);
        }
    }
}

/// Issue 26's property: a random convex cloth (a square, a towel, a hexagon or a disk of
/// 40–101 vertices) folded twice along random lines, each line on the state the one before
/// left, every layer on its side turned and laid on top; then turned, moved and scaled, with
/// in-plane noise on every other one; [start, end] alone. Each is read as two folds landing
/// on the end within the RMSE of 0.01, aligned (the cloth's slide is not in its
/// disks). Measured: 16 of 16, worst aligned RMSE 0.0076 (one of the coarsest cloths, N = 40).
#[test]
fn a_random_cloth_folded_twice_is_read_as_two_folds() {
    let mut rng = SplitMix64::new(26);
    for index in 0..16 {
        let start = crate::unseen::random_start(&mut rng, index);
        let first = random_line(&mut rng, &start);
        let once = fold_in_turn(&start, &[first]);
        let second = random_line(&mut rng, &once);
        let end = fold_in_turn(&start, &[first, second]);
        let angle = std::f64::consts::TAU * rng.uniform();
        let noise = if index % 2 == 0 { 0.0 } else { 1e-4 };
        let frames = [&start, &end].map(|f| placed(f, angle, 2.0, [1.0, -3.0], noise)).to_vec();
        let analysis = start_and_end(&frames);
        let aligned = analysis.metrics.unwrap().aligned_rmse;
        println!(
            "{index} (N = {}): {} folds, aligned {aligned:.4}",
            start.len(),
            analysis.folds.len()
        );
        assert_eq!(analysis.folds.len(), 2, "cloth {index}: lines {first:?}, {second:?}");
        assert!(aligned <= 0.01, "cloth {index}: aligned RMSE {aligned}");
    }
}
