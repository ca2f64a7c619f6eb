//! Properties of the geometry, on random input (proptest): wraps and arcs of the border
//! circle, a fold applied twice, an interpolation's ends, and a plan's result.

use std::f64::consts::{PI, TAU};

use close::angle::{
    self, distance, edge, param_to_angle, wrap_pi, wrap_tau, ArcVertices, ON_LINE_EDGES,
};
use close::border::{to_xyz, Point};
use close::fold::apply;
use close::interpolate::{displacements, fold_path, interpolate, Motion};
use close::plan::{plan, Action, Case};
use close::{Arc, Fold, Folding};
use proptest::prelude::*;

/// A star-shaped polygon, anticlockwise: vertex k at angle 2π(k + jitter)/n, radius in [0.5, 1].
fn star() -> impl Strategy<Value = Vec<Point>> {
    (6usize..40).prop_flat_map(|n| prop::collection::vec((0.5f64..1.0, -0.3f64..0.3), n)).prop_map(
        |radii| {
            let n = radii.len();
            radii
                .iter()
                .enumerate()
                .map(|(k, &(r, jitter))| {
                    let t = param_to_angle(k as f64 + jitter, n);
                    Point::new(r * t.cos(), r * t.sin(), 0.0)
                })
                .collect()
        },
    )
}

fn close_points(a: &Point, b: &Point) -> bool {
    (a - b).norm() < 1e-9
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn wraps_land_in_their_ranges_and_keep_the_angle(x in -1e6f64..1e6) {
        let (t, p) = (wrap_tau(x), wrap_pi(x));
        prop_assert!((0.0..TAU).contains(&t), "wrap_tau({x}) = {t}");
        prop_assert!(p > -PI && p <= PI, "wrap_pi({x}) = {p}");
        // Both differ from x by whole turns.
        let tolerance = 1e-9 * (1.0 + x.abs());
        for wrapped in [t, p] {
            let turns = (x - wrapped) / TAU;
            prop_assert!((turns - turns.round()).abs() * TAU < tolerance, "{x} → {wrapped}");
        }
    }

    #[test]
    fn distance_is_symmetric_and_at_most_a_half_turn(a in -20.0f64..20.0, b in -20.0f64..20.0) {
        let d = distance(a, b);
        prop_assert!((0.0..=PI).contains(&d));
        // Symmetric to rounding: wrap_pi(−x) and −wrap_pi(x) may differ in the last bit.
        prop_assert!((d - distance(b, a)).abs() < 1e-12);
        prop_assert!((distance(a + TAU, b) - d).abs() < 1e-9);
    }

    #[test]
    fn an_arc_holds_the_vertices_strictly_between_its_ends(n in 3usize..200, u1 in 0.0f64..1.0, u2 in 0.0f64..1.0) {
        let nf = n as f64;
        let (s1, s2) = (u1 * nf, u2 * nf);
        let span = (s2 - s1).rem_euclid(nf);
        let offset = |v: usize| (v as f64 - s1).rem_euclid(nf);
        let arc = ArcVertices::of(n, s1, s2);
        let listed = angle::vertices_in_arc(n, s1, s2);
        prop_assert_eq!(arc.len, listed.len());
        for v in 0..n {
            let inside = offset(v) > 1e-9 && offset(v) < span - 1e-9;
            prop_assert_eq!(arc.contains(v), inside, "vertex {} of {}, arc {} → {}", v, n, s1, s2);
            prop_assert_eq!(listed.contains(&v), inside);
        }
        // As many vertices as whole edges fit in the arc's length, give or take one.
        prop_assert!((arc.len as f64 - span).abs() <= 1.0 + 1e-9, "{} vertices in an arc of {} edges", arc.len, span);
        // Walked in order from s1.
        prop_assert!(listed.windows(2).all(|w| offset(w[0]) < offset(w[1])));
        // The other arc holds the rest, but for vertices on an end.
        let other = ArcVertices::of(n, s2, s1);
        let on_end = |v: usize| [s1, s2].iter().any(|&s| { let d = (v as f64 - s).rem_euclid(nf); d.min(nf - d) <= 1e-9 });
        for v in 0..n {
            prop_assert!(!(arc.contains(v) && other.contains(v)));
            prop_assert!(arc.contains(v) || other.contains(v) || on_end(v) || span <= 1e-9, "vertex {} in neither arc", v);
        }
    }

    #[test]
    fn a_folded_vertex_is_one_inside_the_arc_off_its_ends(n in 4usize..100, u1 in 0.0f64..1.0, u2 in 0.0f64..1.0, margin in 0.0f64..1.0) {
        let nf = n as f64;
        let arc = Arc::new(u1 * TAU, u2 * TAU);
        let (s1, span) = (u1 * nf, ((u2 - u1) * nf).rem_euclid(nf));
        for v in 0..n {
            let offset = (v as f64 - s1).rem_euclid(nf);
            // Away from the decision's edges, where rounding of angle and parameter may differ.
            if [offset - margin, span - margin - offset].iter().all(|d| d.abs() > 1e-6) {
                prop_assert_eq!(arc.folds_vertex(n, v, margin), offset > margin && offset < span - margin);
            }
        }
    }

    #[test]
    fn a_fold_applied_twice_along_its_line_is_undone(border in star(), u in 0.0f64..1.0, v in 0.0f64..1.0) {
        let n = border.len();
        let fold = Fold::new(u * TAU, v * TAU);
        prop_assume!(distance(fold.f1, fold.f2) > edge(n));
        let line = fold.line_on(&border, None);
        prop_assume!(line.is_some());
        let line = line.unwrap();
        let along = Folding { line: Some(line), ..Folding::new(fold) };
        let once = apply(&border, &along);
        let twice = apply(&once, &along);
        for (k, (a, b)) in border.iter().zip(&twice).enumerate() {
            prop_assert!(close_points(a, b), "vertex {}: {:?} → {:?}", k, a, b);
        }
        // A reflection keeps each vertex's distance to the line's points.
        let p = Point::new(line.point.x, line.point.y, 0.0);
        prop_assert!(border.iter().zip(&once).all(|(a, b)| ((a - p).norm() - (b - p).norm()).abs() < 1e-9));
    }

    #[test]
    fn an_interpolation_ends_at_its_goal_without_a_jump(border in star(), from in -10.0f64..10.0, from_span in 0.3f64..6.0, to in -10.0f64..10.0, to_span in 0.3f64..6.0, steps in 2usize..40) {
        let (from, to) = (Fold::new(from, from + from_span), Fold::new(to, to + to_span));
        let path = fold_path(from, to, steps);
        prop_assert_eq!(path.len(), steps);
        prop_assert_eq!(path[0], from.wrapped());
        prop_assert_eq!(path[steps - 1], to.wrapped());
        // The displacements lead from the start to the goal, and each step moves by its share.
        let d = displacements(from, to);
        for k in 0..2 {
            prop_assert!(distance(from.ends()[k] + d[k], to.ends()[k]) < 1e-9, "endpoint {}: {:?} + {:?} ≠ {:?}", k, from, d, to);
            for w in path.windows(2) {
                prop_assert!(distance(w[0].ends()[k], w[1].ends()[k]) <= d[k].abs() / (steps - 1) as f64 + 1e-9);
            }
        }
        // The last border is the border folded along the goal.
        let raw: Vec<[f64; 3]> = border.iter().map(to_xyz).collect();
        let motion = interpolate(raw, None, &[], &Motion::Between { from, to }, steps).unwrap();
        let goal = apply(&border, &Folding::new(to));
        let last = motion.borders.last().unwrap();
        prop_assert!(last.iter().zip(&goal).all(|(a, b)| close_points(&Point::new(a[0], a[1], a[2]), b)));
    }

    #[test]
    fn a_plan_reaches_its_goal(border in star(), corner_picks in prop::collection::vec(0.0f64..1.0, 0..6), folds in prop::collection::vec(0.0f64..1.0, 0..3), goal_seed in (0.0f64..1.0, 0.0f64..1.0)) {
        let n = border.len();
        let mut corners: Vec<usize> = corner_picks.iter().map(|u| (u * n as f64) as usize % n).collect();
        corners.sort_unstable();
        corners.dedup();
        let fold = |u: f64, w: f64| {
            let e = edge(n);
            let f1 = u * TAU;
            Fold::new(f1, wrap_tau(f1 + 2.0 * e + w * (TAU - 4.0 * e)))
        };
        let current: Vec<Fold> = folds.iter().enumerate().map(|(k, &u)| fold(u, (0.37 * (k + 1) as f64 + u) % 1.0)).collect();
        let goal = fold(goal_seed.0, goal_seed.1);
        let foldings: Vec<Folding> = current.iter().map(|&f| Folding::new(f)).collect();
        let p = plan(&border, &corners, &foldings, &[goal]).unwrap();
        let goal_state = apply(&border, &Folding::new(goal));
        match p.case {
            Case::AlreadyThere => {
                prop_assert!(p.steps.is_empty() && current.len() == 1);
                prop_assert!((0..2).all(|k| distance(current[0].ends()[k], goal.ends()[k]) <= 0.5 * edge(n) + 1e-12));
                return Ok(());
            }
            Case::Fold => {
                prop_assert!(current.is_empty() && p.steps.len() == 1);
            }
            Case::Direct => {
                prop_assert!(!current.is_empty() && p.steps.len() == 1);
            }
            Case::UnfoldThenFold => {
                // Every current fold undone, last first, back to the flat border.
                prop_assert_eq!(p.steps.len(), current.len() + 1);
                for (step, f) in p.steps.iter().zip(current.iter().rev()) {
                    prop_assert!(step.action == Action::Unfold && step.fold == *f);
                }
                for pick in &p.steps[current.len() - 1].picks {
                    prop_assert!(close_points(&Point::new(pick.to[0], pick.to[1], pick.to[2]), &border[pick.vertex]));
                }
            }
        }
        // The last step folds the goal, moving the corners it folds to where the goal puts them.
        let last = p.steps.last().unwrap();
        prop_assert_eq!(last.action, Action::Fold);
        prop_assert_eq!(last.fold, goal.wrapped());
        let folded: Vec<usize> = (0..corners.len()).filter(|&k| goal.arc().folds_vertex(n, corners[k], ON_LINE_EDGES)).map(|k| k + 1).collect();
        prop_assert_eq!(&last.corners, &folded);
        prop_assert!(!last.picks.is_empty() && last.picks.len() <= 2);
        for pick in &last.picks {
            prop_assert!(close_points(&Point::new(pick.to[0], pick.to[1], pick.to[2]), &goal_state[pick.vertex]), "{:?}", pick);
        }
    }
}
