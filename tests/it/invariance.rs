//! Invariants: CloSE does not change under rotation, translation or uniform scaling of the
//! cloth; relabelling the vertices cyclically shifts every angle; a clockwise border gives
//! the CloSE of its anticlockwise twin. And exact geometry: a reflection fold is found.

use crate::common;

use std::f64::consts::{PI, TAU};

use close::{analyze, Analysis, FrameRange, Sample};
use common::{angle_diff, fold_frame, napkin};

const FOLD: (f64, f64) = (5.3, 44.8);

fn folded_napkin() -> Vec<Vec<[f64; 3]>> {
    let start = napkin(19);
    let end = fold_frame(&start, FOLD.0, FOLD.1);
    vec![start, end]
}

fn run(frames: Vec<Vec<[f64; 3]>>) -> Analysis {
    let sample = Sample::from_frames("t", "napkin", frames);
    analyze(&sample.border_frames().unwrap(), FrameRange::default()).unwrap()
}

fn map(frames: &[Vec<[f64; 3]>], f: impl Fn([f64; 3]) -> [f64; 3]) -> Vec<Vec<[f64; 3]>> {
    frames.iter().map(|fr| fr.iter().map(|&p| f(p)).collect()).collect()
}

fn assert_same_close(a: &Analysis, b: &Analysis, shift: f64) {
    assert_eq!(a.corners.len(), b.corners.len());
    let mut moved: Vec<f64> = a.corners.iter().map(|c| (c + shift).rem_euclid(TAU)).collect();
    moved.sort_by(f64::total_cmp);
    for (x, y) in moved.iter().zip(&b.corners) {
        assert!(angle_diff(*x, *y) < 1e-9, "corners {:?} vs {:?}", a.corners, b.corners);
    }
    assert_eq!(a.folds.len(), 1);
    assert_eq!(b.folds.len(), 1);
    for k in 0..2 {
        assert!(
            angle_diff(a.folds[0].ends()[k] + shift, b.folds[0].ends()[k]) < 1e-4,
            "folds {:?} vs {:?}",
            a.folds,
            b.folds
        );
    }
}

#[test]
fn a_reflection_fold_is_found_where_it_was_made() {
    let a = run(folded_napkin());
    let n = a.n as f64;
    assert_eq!(a.corner_vertices, vec![0, 19, 38, 57]);
    assert_eq!(a.folds.len(), 1);
    let truth = [TAU * FOLD.0 / n, TAU * FOLD.1 / n];
    for k in 0..2 {
        assert!(
            angle_diff(a.folds[0].ends()[k], truth[k]) < 0.5 * 2.0 * PI / n,
            "{:?} vs {truth:?}",
            a.folds
        );
    }
    assert!(a.metrics.unwrap().rmse < 0.02, "{:?}", a.metrics);
}

#[test]
fn rotation_and_translation_leave_close_unchanged() {
    let frames = folded_napkin();
    let (c, s) = (0.7f64.cos(), 0.7f64.sin());
    let moved =
        map(&frames, |p| [c * p[0] - s * p[1] + 3.0, s * p[0] + c * p[1] - 2.0, p[2] + 0.5]);
    assert_same_close(&run(frames), &run(moved), 0.0);
}

#[test]
fn uniform_scaling_leaves_close_unchanged() {
    let frames = folded_napkin();
    for scale in [0.01, 3.7, 250.0] {
        let scaled = map(&frames, |p| [scale * p[0], scale * p[1], scale * p[2]]);
        assert_same_close(&run(frames.clone()), &run(scaled), 0.0);
    }
}

#[test]
fn cyclic_relabelling_shifts_every_angle() {
    let frames = folded_napkin();
    let n = frames[0].len();
    let s = 11;
    // New vertex i is old vertex i + s: an old angle θ becomes θ − 2πs/N.
    let shifted: Vec<Vec<[f64; 3]>> =
        frames.iter().map(|fr| (0..n).map(|i| fr[(i + s) % n]).collect()).collect();
    assert_same_close(&run(frames), &run(shifted), -2.0 * PI * s as f64 / n as f64);
}

#[test]
fn a_clockwise_border_gives_the_close_of_its_anticlockwise_twin() {
    let frames = folded_napkin();
    let n = frames[0].len();
    let clockwise: Vec<Vec<[f64; 3]>> =
        frames.iter().map(|fr| (0..n).map(|i| fr[(n - i) % n]).collect()).collect();
    let (a, b) = (run(frames), run(clockwise));
    assert!(!a.reversed);
    assert!(b.reversed);
    assert_eq!(b.border_indices[..3], [0, n - 1, n - 2]);
    assert_same_close(&a, &b, 0.0);
    // The prediction comes back in border order, which is the twin's order.
    for (p, q) in a.predicted_end.iter().zip(&b.predicted_end) {
        assert!((p[0] - q[0]).abs() < 1e-9 && (p[1] - q[1]).abs() < 1e-9);
    }
}

#[test]
fn second_fold_is_read_from_its_own_step() {
    let start = napkin(19);
    let first = fold_frame(&start, 9.5, 47.5);
    // Fold a corner of the folded cloth (vertices by index on the folded border).
    let second = fold_frame(&first, 66.5, 5.0);
    let a = run(vec![start, first, second]);
    assert_eq!(a.steps.len(), 2);
    assert_eq!(
        a.folds.len(),
        2,
        "{:?}",
        a.steps.iter().map(|s| s.detection.cut).collect::<Vec<_>>()
    );
    assert!(a.label.text.contains("Fold 2"));
}

#[test]
fn noise_without_a_fold_is_no_fold() {
    let start = napkin(19);
    let mut rng = close::rng::SplitMix64::new(7);
    let mut noise = || (rng.uniform() - 0.5) * 0.01;
    let end: Vec<[f64; 3]> =
        start.iter().map(|p| [p[0] + noise(), p[1] + noise(), p[2] + noise()]).collect();
    let a = run(vec![start, end]);
    assert!(a.folds.is_empty(), "{:?}", a.steps[0].detection.cut);
    assert!(a.label.text.contains("not folded"));
}

#[test]
fn a_fold_across_exactly_straight_sides_stays_within_its_edge() {
    // No jitter: the sides are exactly straight, so the rim near the fold points does not
    // change at all and each point is only known to lie in its edge. Nearby corners must not
    // drag it out.
    let per_side = 6;
    let start: Vec<[f64; 3]> = (0..4 * per_side)
        .map(|k| {
            let t = (k % per_side) as f64 / per_side as f64;
            let (x, y) = [(t, 0.0), (1.0, t), (1.0 - t, 1.0), (0.0, 1.0 - t)][k / per_side];
            [x - 0.5, y - 0.5, 0.0]
        })
        .collect();
    let end = fold_frame(&start, 3.0, 15.0);
    let a = run(vec![start, end]);
    let edge = 2.0 * PI / 24.0;
    assert_eq!(a.folds.len(), 1);
    for (found, truth) in a.folds[0].ends().iter().zip([3.0 * edge, 15.0 * edge]) {
        assert!(angle_diff(*found, truth) <= 0.5 * edge + 1e-9, "{:?}", a.folds);
    }
}

/// The folded cloth then slid and turned on the table as a whole: the disks, and so the fold,
/// cannot tell, the RMSE grows by the slide, and the aligned RMSE (the error once the
/// prediction is moved rigidly onto the end) stays what it was.
#[test]
fn a_slide_after_the_fold_costs_rmse_but_not_aligned_rmse() {
    let frames = folded_napkin();
    let (c, s) = (0.3f64.cos(), 0.3f64.sin());
    let slid = vec![
        frames[0].clone(),
        frames[1]
            .iter()
            .map(|p| [c * p[0] - s * p[1] + 4.0, s * p[0] + c * p[1] + 1.0, p[2]])
            .collect(),
    ];
    let (still, moved) = (run(frames), run(slid));
    assert_eq!(still.folds, moved.folds);
    let (a, b) = (still.metrics.unwrap(), moved.metrics.unwrap());
    assert!(b.rmse > a.rmse + 1.0, "{a:?} vs {b:?}");
    assert!((a.aligned_rmse - b.aligned_rmse).abs() < 1e-9, "{a:?} vs {b:?}");
    assert!(a.aligned_rmse <= a.rmse);
}

/// A cloth only moved, not folded, is in the state it was: no fold, and no "changed" note;
/// one crumpled has changed, though no fold explains it.
#[test]
fn a_cloth_only_moved_is_not_said_to_have_changed_one_crumpled_is() {
    let start = napkin(19);
    let (c, s) = (1.1f64.cos(), 1.1f64.sin());
    let moved: Vec<[f64; 3]> = start
        .iter()
        .map(|p| [c * p[0] - s * p[1] - 3.0, s * p[0] + c * p[1] + 2.0, p[2]])
        .collect();
    let a = run(vec![start, moved]);
    assert!(a.folds.is_empty(), "{:?}", a.folds);
    assert!(a.metrics.unwrap().rmse > 1.0);
    assert!(!a.label.text.contains("changed"), "{}", a.label.text);
    // Crumpled on the table instead (each vertex moved at random, a quarter of the side at
    // most), it is no fold but no longer the same cloth.
    let start = napkin(19);
    let mut rng = close::rng::SplitMix64::new(11);
    let mut noise = |scale: f64| (rng.uniform() - 0.5) * scale;
    let crumpled: Vec<[f64; 3]> =
        start.iter().map(|p| [p[0] + noise(0.5), p[1] + noise(0.5), p[2] + noise(0.05)]).collect();
    let a = run(vec![start, crumpled]);
    assert!(a.folds.is_empty(), "{:?}", a.folds);
    assert!(a.label.text.contains("changed, but no fold found"), "{}", a.label.text);
}

/// A napkin folded in half, then turned by 10° and slid on the table, then folded again
/// across its two stacked layers (the fold points coincide, so the line's direction comes
/// from the disks). The turn happened between the folds, so the second line must turn with
/// the predicted state: the prediction is then the true end up to one rigid motion.
#[test]
fn a_second_fold_turns_with_a_cloth_turned_between_folds() {
    let start = napkin(19);
    // Left half onto the right (the folded side runs anticlockwise from the top's middle).
    let half = fold_frame(&start, 47.5, 9.5);
    // Then the top half of both layers down across y = 0, its layers reversed on top.
    let quarter: Vec<[f64; 3]> = half
        .iter()
        .map(|&[x, y, z]| if y > 1e-9 { [x, -y, 0.05 - z] } else { [x, y, z] })
        .collect();
    let (c, s) = (10f64.to_radians().cos(), 10f64.to_radians().sin());
    let turned = |frame: &[[f64; 3]]| {
        frame
            .iter()
            .map(|&[x, y, z]| [c * x - s * y + 0.3, s * x + c * y + 0.1, z])
            .collect::<Vec<_>>()
    };
    let a = run(vec![start, turned(&half), turned(&quarter)]);
    assert_eq!(a.folds.len(), 2, "{:?}", a.folds);
    assert!(
        a.steps[1].detection.synthesis.as_ref().and_then(|s| s.direction).is_some(),
        "the second fold's points should coincide"
    );
    let m = a.metrics.unwrap();
    assert!(m.aligned_rmse < 0.01, "{m:?}");
}
