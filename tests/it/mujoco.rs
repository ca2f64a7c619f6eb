//! Second folds on stacked cloth from a second simulator (`tests/fixtures/physics-mujoco`, a
//! copy of the MuJoCo 4.0 flex-cloth development set): triangulated meshes, layers that slide
//! and bunch, and fold lines that cross a stacked border four or six times (multi-arc folds).
//! Also multi-arc folds from this file's own generator, written without `close::fold`.

use crate::common;

use std::f64::consts::TAU;

use close::{analyze, Analysis, FrameRange, Sample};
use common::{angle_diff, fixture, samples_in};

/// The floor of each development sequence's shape (the commanded line itself, XY RMSE after
/// the SPEC normalisation, step 2), from the set's README. A prediction that finds where the
/// cloth really folded may beat it.
fn floor(name: &str) -> f64 {
    let floors = [
        ("circ", 0.0555),
        ("napkin", 0.0857),
        ("shirt", 0.0408),
        ("skirt", 0.0837),
        ("towel", 0.0435),
        ("trousers", 0.0152),
    ];
    floors
        .iter()
        .find(|(shape, _)| name.split('_').next() == Some(shape))
        .map(|&(_, f)| f)
        .unwrap_or_else(|| panic!("no floor for {name}"))
}

fn analysed(dir: &str) -> Vec<(Sample, Analysis)> {
    samples_in(dir)
        .into_iter()
        .map(|s| {
            let a = analyze(&s.border_frames().unwrap(), FrameRange::default()).unwrap();
            (s, a)
        })
        .collect()
}

/// `truth.multi_arc` of a fixture (not part of the `Truth` the library reads).
fn multi_arc(name: &str) -> bool {
    let text =
        std::fs::read_to_string(fixture(&format!("physics-mujoco/border/{name}.json"))).unwrap();
    let doc: serde_json::Value = serde_json::from_str(&text).unwrap();
    doc["truth"]["multi_arc"].as_bool().unwrap_or(false)
}

#[test]
fn every_second_fold_is_found_near_its_floor() {
    let runs = analysed("physics-mujoco/border");
    assert_eq!(runs.len(), 6);
    let (mut rmse, mut floors) = (Vec::new(), Vec::new());
    for (sample, analysis) in &runs {
        assert_eq!(analysis.folds.len(), 2, "{}: {:?}", sample.name, analysis.folds);
        let m = analysis.metrics.unwrap();
        let f = floor(&sample.name);
        // Measured (2026-12-02): 1.28–1.47 × the floor, the shirt below it.
        assert!(m.rmse <= 1.6 * f, "{}: RMSE {:.4} against a floor of {f}", sample.name, m.rmse);
        // This cloth slides across the table as it folds (its unfolded part moved rigidly by up
        // to 0.11 on the skirt), which the disks cannot see; once the prediction is moved
        // rigidly onto the end, every sequence is below its floor (measured 0.33–0.93 ×).
        assert!(
            m.aligned_rmse <= f,
            "{}: aligned RMSE {:.4} against a floor of {f}",
            sample.name,
            m.aligned_rmse
        );
        rmse.push(m.rmse);
        floors.push(f);
        // A fold of several arcs is reported as its arcs, and its fold spans them.
        let step = &analysis.steps[1].detection;
        if multi_arc(&sample.name) {
            // The target for a fold of several arcs (measured: shirt 0.95 ×, trousers
            // 1.47 ×).
            assert!(
                m.rmse <= 1.5 * f,
                "{}: RMSE {:.4} against a floor of {f}",
                sample.name,
                m.rmse
            );
            assert!(step.arcs.len() >= 2, "{}: arcs {:?}", sample.name, step.arcs);
            let text = &analysis.label.folds[1].text;
            assert!(
                text.contains("multi-arc fold")
                    && text.contains(&format!("crosses the border {} times", 2 * step.arcs.len())),
                "{}: {text}",
                sample.name
            );
            // The fold circle draws each arc.
            let png = close::render::render(
                analysis,
                &close::render::View::whole(close::render::Picture::Close),
                &close::render::Output::png(400),
                Default::default(),
            )
            .unwrap();
            assert!(png.starts_with(b"\x89PNG"), "{}", sample.name);
        }
        let fold = step.fold.unwrap();
        assert_eq!(close::Fold::span(&step.arcs), Some(fold), "{}", sample.name);
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    // Measured 0.0716 against a mean floor of 0.0541 (1.32 ×).
    assert!(
        mean(&rmse) <= 1.4 * mean(&floors),
        "mean RMSE {:.4}, mean floor {:.4}",
        mean(&rmse),
        mean(&floors)
    );
}

/// The triangulated mesh of each sequence gives its border form's border in the same order,
/// walked from the vertex the mesh rule starts at (its lowest, the bottom-left corner:
/// `close::mesh::start_lowest`), and then the same folds. Where the border form starts
/// there too (every outline with a level bottom edge) the two are one input; a round
/// cloth's border form starts a vertex before its lowest point, and its folds agree once
/// that shift is undone.
#[test]
fn a_mesh_gives_its_border_forms_border_and_folds() {
    let mut same = 0;
    for ((border, by_border), (mesh, by_mesh)) in
        analysed("physics-mujoco/border").iter().zip(&analysed("physics-mujoco/mesh"))
    {
        assert_eq!(border.name, mesh.name);
        let n = by_border.n;
        assert_eq!(by_mesh.n, n, "{}", mesh.name);
        let xyz = |frame: &[close::border::Point]| {
            frame.iter().map(|p| [p.x, p.y, p.z]).collect::<Vec<_>>()
        };
        let (b, m) = (xyz(by_border.start_border()), xyz(by_mesh.start_border()));
        let shift = (0..n)
            .find(|&k| (0..n).all(|v| b[(v + k) % n] == m[v]))
            .unwrap_or_else(|| panic!("{}: not the same border", mesh.name));
        // The mesh starts where the rule, applied to the border form, says.
        assert_eq!(shift, close::mesh::start_lowest((0..n).collect(), &b)[0], "{}", mesh.name);
        // Every frame, vertex by vertex.
        for (fb, fm) in by_border.frames.iter().zip(&by_mesh.frames) {
            assert!(
                (0..n).all(|v| fb[(v + shift) % n] == fm[v]),
                "{}: a later frame differs",
                mesh.name
            );
        }
        assert_eq!(by_mesh.folds.len(), by_border.folds.len(), "{}", mesh.name);
        if shift == 0 {
            same += 1;
            assert_eq!(by_mesh.folds, by_border.folds, "{}", mesh.name);
            assert_eq!(by_mesh.metrics, by_border.metrics, "{}", mesh.name);
            continue;
        }
        for (fm, fb) in by_mesh.folds.iter().zip(&by_border.folds) {
            for (am, ab) in fm.ends().iter().zip(fb.ends()) {
                // The probes sample edges by index, so the shift moves them: measured 0.56
                // edges apart on the round cloth.
                let edges = angle_diff(*am + TAU * shift as f64 / n as f64, ab) * n as f64 / TAU;
                assert!(
                    edges <= 1.0,
                    "{}: {fm:?} vs {fb:?} ({edges:.2} edges after a shift of {shift})",
                    mesh.name
                );
            }
        }
        let (rm, rb) = (by_mesh.metrics.unwrap().rmse, by_border.metrics.unwrap().rmse);
        assert!(
            (rm - rb).abs() <= 0.01,
            "{}: RMSE {rm:.4} from the mesh, {rb:.4} from the border",
            mesh.name
        );
    }
    // The five outlines with a level bottom edge (napkin, shirt, skirt, towel, trousers).
    assert!(same >= 5, "{same} of 6 meshes start where their border form does");
}

/// A two-legged outline (trousers), anticlockwise from the outer corner of the left hem, a
/// vertex about every `step`: the legs' hems at y = −0.5, the crotch at (0, `crotch`), the
/// inner hem corners at x = `inner[0]` and `inner[1]`.
fn two_legs(step: f64, crotch: f64, inner: [f64; 2]) -> Vec<[f64; 3]> {
    let corners = [
        [-0.4, -0.5],
        [inner[0], -0.5],
        [0.0, crotch],
        [inner[1], -0.5],
        [0.4, -0.5],
        [0.4, 0.5],
        [-0.4, 0.5],
    ];
    let mut out = Vec::new();
    for (k, a) in corners.iter().enumerate() {
        let b = corners[(k + 1) % corners.len()];
        let len = (b[0] - a[0]).hypot(b[1] - a[1]);
        let pieces = (len / step).ceil() as usize;
        out.extend((0..pieces).map(|i| {
            let t = i as f64 / pieces as f64;
            [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), 0.0]
        }));
    }
    out
}

/// This generator's own fold of a state: every vertex on the far side of the line
/// `normal · p = offset` (XY) is reflected across it and turned over above the rest
/// (z ↦ top − z): the whole side, however many arcs of the border it holds.
fn turn_over(state: &[[f64; 3]], normal: [f64; 2], offset: f64, top: f64) -> Vec<[f64; 3]> {
    state
        .iter()
        .map(|&[x, y, z]| {
            let d = normal[0] * x + normal[1] * y - offset;
            if d < 0.0 {
                [x - 2.0 * d * normal[0], y - 2.0 * d * normal[1], top - z]
            } else {
                [x, y, z]
            }
        })
        .collect()
}

fn rmse(a: &[close::border::Point], b: &[[f64; 3]]) -> f64 {
    (a.iter().zip(b).map(|(p, q)| (p.x - q[0]).powi(2) + (p.y - q[1]).powi(2)).sum::<f64>()
        / a.len() as f64)
        .sqrt()
}

/// Leg over leg, then the stacked legs folded across: the second line crosses the border
/// four times and both hems turn over. The analysis reports the two arcs, its prediction
/// turns only them (the crotch stays), and the two arcs hold exactly the moved vertices.
#[test]
fn generated_stacked_legs_fold_as_two_arcs() {
    for (crotch, inner, hem_line) in
        [(0.15, [-0.1, 0.06], -0.1), (0.1, [-0.06, 0.1], -0.2), (0.2, [-0.12, 0.08], 0.0)]
    {
        let flat = two_legs(0.02, crotch, inner);
        // Leg over leg: the left half over x = 0, a layer up.
        let legs = turn_over(&flat, [1.0, 0.0], 0.0, 0.004);
        // The stacked legs' hems up over y = hem_line.
        let folded = turn_over(&legs, [0.0, 1.0], hem_line, 0.02);
        let moved: Vec<usize> = (0..flat.len()).filter(|&v| folded[v] != legs[v]).collect();
        let sample =
            Sample::from_frames("two legs", "trousers", vec![flat.clone(), legs, folded.clone()]);
        let analysis = analyze(&sample.border_frames().unwrap(), FrameRange::default()).unwrap();
        let case = format!("crotch {crotch}, hems {inner:?}, line y = {hem_line}");
        assert_eq!(analysis.folds.len(), 2, "{case}: {:?}", analysis.folds);
        let arcs = &analysis.steps[1].detection.arcs;
        assert_eq!(arcs.len(), 2, "{case}: {arcs:?}");
        let n = flat.len();
        let mut turned: Vec<usize> = arcs.iter().flat_map(|a| a.folded_vertices(n)).collect();
        turned.sort_unstable();
        let missed = moved.iter().filter(|v| !turned.contains(v)).count()
            + turned.iter().filter(|v| !moved.contains(v)).count();
        assert!(missed <= 4, "{case}: {missed} vertices differ between the arcs and the fold");
        let predicted: Vec<close::border::Point> = analysis
            .predicted_end
            .iter()
            .map(|p| close::border::Point::new(p[0], p[1], p[2]))
            .collect();
        let error = rmse(&predicted, &folded);
        assert!(error < 0.01, "{case}: RMSE {error:.4}");
    }
}

/// Each step's fold, turned over by the interpolation along the line and arcs the analysis
/// reports, starts on the state before it, never moves a vertex outside its arcs, and ends
/// on the analysis's prediction: step by step from the start border to `predicted_end`.
#[test]
fn interpolation_turns_each_steps_arcs_onto_the_prediction() {
    let mut multi_arc = 0;
    for (sample, analysis) in analysed("physics-mujoco/border") {
        let n = analysis.n;
        let mut state = analysis.start_border().to_vec();
        for (k, step) in
            analysis.steps.iter().enumerate().filter(|(_, s)| s.detection.fold.is_some())
        {
            let arcs = &step.detection.arcs;
            multi_arc += usize::from(arcs.len() > 1);
            let before: Vec<[f64; 3]> = state.iter().map(close::border::to_xyz).collect();
            let start = analysis.start_border().iter().map(close::border::to_xyz).collect();
            let turn = close::interpolate::Motion::Turn { arcs: arcs.clone(), line: step.line };
            let motion =
                close::interpolate::interpolate(before.clone(), Some(start), &[], &turn, 11)
                    .unwrap();
            assert_eq!(
                motion.borders[0],
                before,
                "{} step {}: turn 0 is the state before",
                sample.name,
                k + 1
            );
            let inside: Vec<usize> = arcs.iter().flat_map(|a| a.folded_vertices(n)).collect();
            for (t, border) in motion.borders.iter().enumerate() {
                for v in (0..n).filter(|v| !inside.contains(v)) {
                    assert_eq!(
                        border[v],
                        before[v],
                        "{} step {}, turn {t}: vertex {v} lies outside the arcs {arcs:?}",
                        sample.name,
                        k + 1
                    );
                }
            }
            state = motion.borders[10].iter().map(close::border::from_xyz).collect();
        }
        let worst = state
            .iter()
            .zip(&analysis.predicted_end)
            .map(|(p, q)| (p.x - q[0]).abs().max((p.y - q[1]).abs()).max((p.z - q[2]).abs()))
            .fold(0.0, f64::max);
        assert!(worst < 1e-12, "{}: the last turn is {worst} off the prediction", sample.name);
    }
    // The fixtures' multi-arc second folds (trousers, shirt) are among them.
    assert!(multi_arc >= 1, "no multi-arc step among the fixtures");
}
