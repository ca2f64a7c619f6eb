//! The CloSE representation: corners from the start disk's rim, and fold coordinates
//! (Kamat, Borràs, Torras, "CloSE", Sec. III-B, corners; Sec. III-C, fold coordinates).
//!
//! **Corners** θ_1 < … < θ_n. The paper takes the layer-1 cells (edges i, i+1 meet at vertex
//! i+1) of the START disk whose |value| exceeds a threshold: the population standard
//! deviation of the disk values after dropping those with a z-score of 7 or more. On a mesh
//! outline every staircase step passes that test, and on a fine polygonal curve every vertex
//! does, so the threshold stays as one input and two more decide at the scale of the cloth:
//! - the border must turn by at least [`CornerParams::min_turn_rad`] between the chords
//!   that reach [`CornerParams::window_share`] of the perimeter back and forward from the
//!   vertex (a staircase along a straight or slanted side turns by nothing at that scale, a
//!   circle by 2π·2·`window_share`);
//! - of the rim cells that pass both tests within one window, only the largest |value| is a
//!   corner (one corner per bend, not one per staircase step);
//! - and only when its bend turns by at least [`CornerParams::min_turn_rad`] at half that
//!   scale too ([`CornerParams::core_window_share`], at a vertex within that reach): a corner
//!   concentrates its turn, so the narrower chords still see all of it, while a smooth curve
//!   spreads it and they see about half (a round neckline whose radius is a few windows turns
//!   past the least turn at the window, not at the core window; two corners close together, a
//!   sleeve's end, keep each its own turn);
//! - a polygon's own vertex is a corner too when it turns by at least
//!   [`CornerParams::min_vertex_turn_rad`] between straight neighbours (the two vertices
//!   either side turn by less than [`CornerParams::straight_share`] of it): a neckline of a few
//!   gentle polygon corners keeps them, a curve (every vertex turns alike) or a staircase
//!   (every step turns back) does not.
//!
//! Each corner is reported as the angle of its vertex, 2πv/N.
//!
//! **CloSE** = ((θ_1 … θ_n), (f1, f2) per fold), all angles in [0, 2π).
//!
//! ```
//! use close_core::close::{corners, CornerParams};
//! use close_core::disk::Disk;
//! use close_core::border::Point;
//! let square: Vec<Point> = (0..16)
//!     .map(|k| {
//!         let (side, t) = (k / 4, (k % 4) as f64 / 4.0);
//!         let (x, y) = [(t, 0.0), (1.0, t), (1.0 - t, 1.0), (0.0, 1.0 - t)][side];
//!         Point::new(x, y, 0.0)
//!     })
//!     .collect();
//! let found = corners(&Disk::of_border(&square), &square, &CornerParams::default());
//! assert_eq!(found.vertices, vec![0, 4, 8, 12]);
//! // A circle of 64 vertices turns at every vertex, and has no corner.
//! let circle: Vec<Point> = (0..64).map(|k| {
//!     let t = close_core::angle::param_to_angle(k as f64, 64);
//!     Point::new(t.cos(), t.sin(), 0.0)
//! }).collect();
//! let round = corners(&Disk::of_border(&circle), &circle, &CornerParams::default());
//! assert!(round.vertices.is_empty());
//! ```

use serde::{Deserialize, Serialize};

use crate::angle::{param_to_angle, wrap_pi};
use crate::border::Point;
use crate::geometry::Fold;

use crate::disk::Disk;

/// z-scores at or beyond this are outliers for the corner threshold: the paper's 7, not a
/// knob.
pub const OUTLIER_Z: f64 = 7.0;

/// The knobs of the corner tests at the scale of the cloth (see the module doc), passed in
/// ([`crate::analysis::Options::corners`]). Measured on the reference polygons and the
/// physics outlines (`tests/it/reference.rs`,
/// `corners_match_the_reference_on_polygons_and_a_round_cloth_has_none`;
/// `tests/it/physics.rs`, `physics_folds`, every sample's own corners) and on the T-shirt
/// necklines of this module's tests (commit f6d8d45).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CornerParams {
    /// Least turn of the border, at the scale of [`CornerParams::window_share`], at a
    /// corner (radians). Default π/4 (45°): a scoop neckline turns by ~33° at that scale.
    pub min_turn_rad: f64,
    /// Share of the perimeter each chord of the turn test spans, on either side of a
    /// vertex. Default 0.025.
    pub window_share: f64,
    /// The narrower chords of the concentration test, as a share of the perimeter.
    /// Default half of 0.025: a tight round neckline turns by about half its turn there,
    /// a corner by all of it.
    pub core_window_share: f64,
    /// Least turn of an isolated polygon vertex, between straight neighbours, at a corner
    /// (radians). Default π/9 (20°); chosen, not measured.
    pub min_vertex_turn_rad: f64,
    /// The neighbours of an isolated polygon vertex turn, together, by less than this share
    /// of it. Default 0.25; chosen, not measured.
    pub straight_share: f64,
}

impl Default for CornerParams {
    fn default() -> CornerParams {
        CornerParams {
            min_turn_rad: std::f64::consts::FRAC_PI_4,
            window_share: 0.025,
            core_window_share: 0.025 / 2.0,
            min_vertex_turn_rad: std::f64::consts::PI / 9.0,
            straight_share: 0.25,
        }
    }
}

/// Corners found on a disk's rim.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Corners {
    /// Corner vertices, increasing.
    pub vertices: Vec<usize>,
    /// Their angles 2πv/N, increasing, in [0, 2π).
    pub angles: Vec<f64>,
    /// The |value| a rim cell had to exceed.
    pub threshold: f64,
}

fn mean_std(values: impl Iterator<Item = f64> + Clone) -> (f64, f64) {
    let (count, sum) = values.clone().fold((0usize, 0.0), |(c, s), v| (c + 1, s + v));
    if count == 0 {
        return (0.0, 0.0);
    }
    let mean = sum / count as f64;
    let var = values.map(|v| (v - mean).powi(2)).sum::<f64>() / count as f64;
    (mean, var.sqrt())
}

/// The corner threshold of a disk: std of its values without the |z| ≥ 7 outliers.
pub(crate) fn corner_threshold(disk: &Disk) -> f64 {
    let values = disk.values();
    let (mean, std) = mean_std(values.iter().copied());
    if std == 0.0 {
        return 0.0;
    }
    mean_std(values.iter().copied().filter(|v| ((v - mean) / std).abs() < OUTLIER_Z)).1
}

/// The corners of a start state: its disk and its border (the same, normalised, state),
/// with the knobs `params`.
pub fn corners(disk: &Disk, border: &[Point], params: &CornerParams) -> Corners {
    let n = disk.n();
    let threshold = corner_threshold(disk);
    let rim = |v: usize| disk.get((v + n - 1) % n, v).abs();
    let reach = window_reach(border, params.window_share);
    let core = window_reach(border, params.core_window_share);
    let passes = |v: usize| threshold > 0.0 && rim(v) > threshold;
    let min_turn = params.min_turn_rad;
    let candidate: Vec<bool> =
        (0..n).map(|v| passes(v) && turn(border, v, &reach).abs() >= min_turn).collect();
    // The bend at v is concentrated when a vertex within the core window of it turns by
    // the least turn at that scale too (the corner need not be the vertex of the largest
    // rim cell).
    let concentrated = |v: usize| {
        let (back, forward) = core[v];
        (0..=back)
            .map(|k| (v + n - k % n) % n)
            .chain((1..=forward).map(|k| (v + k) % n))
            .any(|u| turn(border, u, &core).abs() >= min_turn)
    };
    let single: Vec<(usize, usize)> = vec![(1, 1); n];
    let vertex_turn: Vec<f64> = (0..n).map(|v| turn(border, v, &single).abs()).collect();
    let isolated = |v: usize| {
        let around: f64 = [n - 2, n - 1, 1, 2].iter().map(|&k| vertex_turn[(v + k) % n]).sum();
        vertex_turn[v] >= params.min_vertex_turn_rad
            && around < params.straight_share * vertex_turn[v]
    };
    // One corner per bend: the largest rim cell among the candidates within its window
    // (the earlier one on a tie).
    let vertices: Vec<usize> = (0..n)
        .filter(|&v| {
            let (back, forward) = reach[v];
            let largest = (1..=back)
                .map(|k| (v + n - k % n) % n)
                .all(|u| !candidate[u] || rim(u) < rim(v))
                && (1..=forward).map(|k| (v + k) % n).all(|u| !candidate[u] || rim(u) <= rim(v));
            (candidate[v] && largest && concentrated(v)) || (passes(v) && isolated(v))
        })
        .collect();
    let angles = vertices.iter().map(|&v| param_to_angle(v as f64, n)).collect();
    Corners { vertices, angles, threshold }
}

/// For each vertex, how many edges back and forward a `window` share of the perimeter
/// reaches (at least one, less than half the border).
fn window_reach(border: &[Point], window: f64) -> Vec<(usize, usize)> {
    let n = border.len();
    let length = |k: usize| (border[(k + 1) % n].xy() - border[k % n].xy()).norm();
    let perimeter: f64 = (0..n).map(length).sum();
    let span = window * perimeter;
    let most = (n / 2).saturating_sub(1).max(1);
    let walk = |edges: &mut dyn Iterator<Item = usize>| {
        let mut run = 0.0;
        let mut count = 0;
        for e in edges {
            run += length(e);
            count += 1;
            if run >= span || count >= most {
                break;
            }
        }
        count.max(1)
    };
    (0..n)
        .map(|v| {
            (walk(&mut (1..=n).map(|k| (v + n - k) % n)), walk(&mut (v..v + n).map(|k| k % n)))
        })
        .collect()
}

/// The turn of the border at `v` between the chords from `reach[v]` edges back and forward.
fn turn(border: &[Point], v: usize, reach: &[(usize, usize)]) -> f64 {
    let n = border.len();
    let (back, forward) = reach[v];
    let (a, b, c) =
        (border[(v + n - back % n) % n].xy(), border[v].xy(), border[(v + forward) % n].xy());
    let (u, w) = (b - a, c - b);
    wrap_pi(w.y.atan2(w.x) - u.y.atan2(u.x))
}

/// The CloSE of one state: corners and the folds that led to it, in order.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Close {
    /// Corner angles on the border circle, 2πv/N for corner vertex v (radians, increasing).
    pub corners: Vec<f64>,
    /// One [f1, f2] per fold, in order, in [0, 2π) (radians).
    pub folds: Vec<Fold>,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The polyline through `corners`, each side cut into edges of about `step`, without its
    /// last point (so that pieces chain, and a piece that ends at its first point closes).
    fn path(corners: &[[f64; 2]], step: f64) -> Vec<Point> {
        corners
            .windows(2)
            .flat_map(|side| {
                let (a, b) = (side[0], side[1]);
                let edges = ((b[0] - a[0]).hypot(b[1] - a[1]) / step).round().max(1.0) as usize;
                (0..edges).map(move |k| {
                    let t = k as f64 / edges as f64;
                    Point::new(a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), 0.0)
                })
            })
            .collect()
    }

    fn found(border: &[Point]) -> Vec<[f64; 2]> {
        corners(&Disk::of_border(border), border, &CornerParams::default())
            .vertices
            .iter()
            .map(|&v| [border[v].x, border[v].y])
            .collect()
    }

    fn near(a: [f64; 2], b: [f64; 2], tolerance: f64) -> bool {
        (a[0] - b[0]).hypot(a[1] - b[1]) <= tolerance
    }

    #[test]
    fn a_staircase_side_has_no_corners() {
        // A right triangle whose hypotenuse is a mesh outline's staircase of 20 steps: its
        // three corners, and none of the 39 turns of the stairs.
        let h = 0.1;
        let mut border = path(&[[0.0, 0.0], [2.0, 0.0], [2.0, 2.0]], h);
        for k in 0..20 {
            let (x, y) = (2.0 - k as f64 * h, 2.0 - k as f64 * h);
            border.push(Point::new(x, y, 0.0));
            border.push(Point::new(x - h, y, 0.0));
        }
        let corners = found(&border);
        let truth = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0]];
        assert_eq!(corners.len(), 3, "{corners:?}");
        assert!(truth.iter().all(|&t| corners.iter().any(|&c| near(c, t, 1.5 * h))), "{corners:?}");
    }

    #[test]
    fn a_circle_has_no_corners() {
        for (n, stretch) in [(24, 1.0), (64, 1.0), (300, 1.0), (120, 1.6)] {
            let circle: Vec<Point> = (0..n)
                .map(|k| {
                    let t = param_to_angle(k as f64, n);
                    Point::new(stretch * t.cos(), t.sin(), 0.0)
                })
                .collect();
            assert!(found(&circle).is_empty(), "N = {n}, stretch {stretch}: {:?}", found(&circle));
        }
    }

    /// A T-shirt outline (body 2 wide, sleeves, shoulders) with a round neckline of radius
    /// `neck` dipping between the neck points (±neck, 1), edges of about `step`; and its
    /// ten corners.
    fn tshirt(neck: f64, step: f64) -> (Vec<Point>, Vec<[f64; 2]>) {
        let neck_edges = (std::f64::consts::PI * neck / step).round() as usize;
        let neckline = (0..neck_edges).map(|k| {
            let t = -std::f64::consts::PI * k as f64 / neck_edges as f64;
            Point::new(neck * t.cos(), 1.0 + neck * t.sin(), 0.0)
        });
        let border = path(
            &[[-1.0, -1.5], [1.0, -1.5], [1.0, 0.3], [2.0, 0.3], [2.0, 1.0], [neck, 1.0]],
            step,
        )
        .into_iter()
        .chain(neckline)
        .chain(path(&[[-neck, 1.0], [-2.0, 1.0], [-2.0, 0.3], [-1.0, 0.3], [-1.0, -1.5]], step))
        .collect();
        let truth = vec![
            [-1.0, -1.5],
            [1.0, -1.5],
            [1.0, 0.3],
            [2.0, 0.3],
            [2.0, 1.0],
            [neck, 1.0],
            [-neck, 1.0],
            [-2.0, 1.0],
            [-2.0, 0.3],
            [-1.0, 0.3],
        ];
        (border, truth)
    }

    type Points = Vec<[f64; 2]>;

    /// The corners found on a T-shirt, and those of them that are not its own.
    fn shirt_corners(neck: f64) -> (Points, Points, Points) {
        let step = 0.05;
        let (border, truth) = tshirt(neck, step);
        let corners = found(&border);
        let spurious = corners
            .iter()
            .copied()
            .filter(|&c| !truth.iter().any(|&t| near(c, t, 1.5 * step)))
            .collect();
        (corners, truth, spurious)
    }

    #[test]
    fn a_curved_neckline_has_no_corners_but_the_shirt_has_all_its_own() {
        // A scoop neckline (radius 0.6, 30 % of the body's width): at the scale of the turn
        // test (the window, 2.5 % of the perimeter, about 0.34 here) it turns by ~33°, under
        // the least turn of 45°.
        let (corners, truth, spurious) = shirt_corners(0.6);
        assert!(truth.iter().all(|&t| corners.iter().any(|&c| near(c, t, 0.075))), "{corners:?}");
        assert!(spurious.is_empty(), "corners in the neckline or along a side: {spurious:?}");
    }

    #[test]
    fn a_tight_round_neckline_spreads_its_turn_and_has_no_corner() {
        // Radius 0.4 (a fifth of the body's width): ~48° at the window, past the least turn,
        // but only about half of it at the core window, where every corner of the shirt keeps
        // all of its own.
        let params = CornerParams::default();
        let (border, _) = tshirt(0.4, 0.05);
        let reach = window_reach(&border, params.window_share);
        let widest = (0..border.len())
            .filter(|&v| border[v].x.abs() < 0.35 && (0.55..0.95).contains(&border[v].y))
            .map(|v| turn(&border, v, &reach).abs())
            .fold(0.0, f64::max);
        assert!(
            widest >= params.min_turn_rad,
            "the neckline must turn past the least turn at the window for this test to mean anything: {}",
            widest.to_degrees()
        );
        let (corners, truth, spurious) = shirt_corners(0.4);
        assert!(truth.iter().all(|&t| corners.iter().any(|&c| near(c, t, 0.075))), "{corners:?}");
        assert!(spurious.is_empty(), "corners in the neckline: {spurious:?}");
    }
}
