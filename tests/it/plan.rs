//! Plans of built-in samples (the library's own unit tests cannot read the dataset, which
//! lives in a crate above it).

use std::f64::consts::PI;

use close::plan::{plan_for, Action, Case};

#[test]
fn a_second_fold_through_stacked_layers_is_undone_from_the_predicted_end() {
    // Folded in half, then in half again: the second fold's two points lie on top of each
    // other after the first, so the line through them points anywhere; the plan must
    // grasp the corners where the analysis's prediction has them, along its line.
    let data = close::dataset::Dataset::builtin();
    let entry = data.get("napkin__half_then_half").expect("a built-in sample");
    let analysis =
        close::analyze(&entry.sample.border_frames().unwrap(), Default::default()).unwrap();
    assert!(
        analysis.steps[1].detection.synthesis.as_ref().and_then(|s| s.direction).is_some(),
        "the second fold's line comes from the disks"
    );
    let p = plan_for(&analysis, &[close::Fold::new(0.0, PI)]).unwrap();
    assert_eq!(p.case, Case::UnfoldThenFold);
    let first = &p.steps[0];
    assert!(first.action == Action::Unfold && !first.picks.is_empty());
    for pick in &first.picks {
        let v = analysis.border_indices.iter().position(|&i| i == pick.vertex).unwrap();
        let now = analysis.predicted_end[v];
        assert!(
            (0..3).all(|c| (pick.from[c] - now[c]).abs() < 1e-9),
            "corner grasped at {:?}, the prediction has it at {now:?}",
            pick.from
        );
    }
}
