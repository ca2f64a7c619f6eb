//! How far a predicted border is from the true one: RMSE, discrete Fréchet distance, and
//! the RMSE left after the best rigid motion.
//!
//! All are measured on the XY (zenithal) projection after the normalisation of the
//! START border (centroid to origin, farthest vertex at distance 1), so they read in
//! unit-circle units whatever the cloth's size.
//!
//! The dGLI, and so CloSE, does not change when the whole cloth is moved, so no prediction
//! read from the disks can know that the cloth slid across the table while it was folded.
//! [`aligned_rmse_xy`] separates that part of the error: it is the RMSE once the prediction
//! is rotated and translated in XY onto the truth as well as it can be (the 2D Kabsch
//! problem, solved in closed form: centre both, rotate by atan2(Σ p×q, Σ p·q)).
//!
//! ```
//! use close_core::border::Point;
//! use close_core::metrics::{aligned_rmse_xy, frechet_xy, rmse_xy};
//! let a = [Point::new(0.0, 0.0, 0.0), Point::new(1.0, 0.0, 0.0), Point::new(1.0, 1.0, 0.0)];
//! let b = [Point::new(0.0, 0.0, 5.0), Point::new(1.0, 0.0, 0.0), Point::new(1.0, 1.0, 0.0)];
//! assert_eq!(rmse_xy(&a, &b), 0.0); // z does not count
//! assert_eq!(frechet_xy(&a, &b), 0.0);
//! // The same triangle slid along x: an RMSE of 0.5, none of it seen by the disks.
//! let slid: Vec<Point> = a.iter().map(|p| Point::new(p.x + 0.5, p.y, p.z)).collect();
//! assert!((rmse_xy(&a, &slid) - 0.5).abs() < 1e-12);
//! assert!(aligned_rmse_xy(&a, &slid) < 1e-12);
//! ```

use serde::{Deserialize, Serialize};

use crate::border::{Normalisation, Point};
use crate::geometry::{Point2, Vector2};

/// Error of a predicted end border against the true one.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Metrics {
    pub rmse: f64,
    pub frechet: f64,
    /// The RMSE once the prediction is moved rigidly onto the truth ([`aligned_rmse_xy`]):
    /// the part of `rmse` that the representation can see.
    pub aligned_rmse: f64,
}

impl Metrics {
    /// Metrics of `predicted` against `truth`, both normalised by `start`'s transform.
    pub fn measure(norm: &Normalisation, predicted: &[Point], truth: &[Point]) -> Metrics {
        let p = norm.apply_all(predicted);
        let t = norm.apply_all(truth);
        Metrics {
            rmse: rmse_xy(&p, &t),
            frechet: frechet_xy(&p, &t),
            aligned_rmse: aligned_rmse_xy(&p, &t),
        }
    }
}

/// Squared XY distance: the Fréchet recursion only takes maxima and minima, so it runs on
/// squares and takes one root at the end (hypot per cell was most of its cost).
fn dist2_xy(a: &Point, b: &Point) -> f64 {
    (a.x - b.x).powi(2) + (a.y - b.y).powi(2)
}

/// Root mean square of the XY distances between corresponding vertices.
pub fn rmse_xy(a: &[Point], b: &[Point]) -> f64 {
    let n = a.len().min(b.len()).max(1);
    (a.iter().zip(b).map(|(p, q)| dist2_xy(p, q)).sum::<f64>() / n as f64).sqrt()
}

/// RMSE in XY of `a` against `b` after the rotation and translation of `a` that bring it
/// closest to `b` (a mirror image is not a rigid motion: it stays apart). At most
/// [`rmse_xy`], since not moving is one of the motions.
pub fn aligned_rmse_xy(a: &[Point], b: &[Point]) -> f64 {
    let motion = RigidMotion::fit_xy(a, b);
    let moved: Vec<Point> = a.iter().map(|p| motion.apply(p)).collect();
    rmse_xy(&moved, b)
}

/// A rotation about the vertical followed by a translation, in XY (z kept).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidMotion {
    /// Anticlockwise rotation, radians.
    pub angle: f64,
    /// The rotation is about this point, which then moves to `to`.
    from: Point2,
    to: Point2,
}

impl RigidMotion {
    /// The motion that brings `a` closest to `b`, vertex by vertex, in the least-squares
    /// sense (2D Kabsch: centre both, rotate by atan2(Σ p×q, Σ p·q)); the identity when
    /// either is empty.
    pub(crate) fn fit_xy(a: &[Point], b: &[Point]) -> RigidMotion {
        let n = a.len().min(b.len());
        if n == 0 {
            return RigidMotion { angle: 0.0, from: Point2::origin(), to: Point2::origin() };
        }
        let (a, b) = (&a[..n], &b[..n]);
        let centroid = |s: &[Point]| {
            let (x, y) = s.iter().fold((0.0, 0.0), |(x, y), p| (x + p.x, y + p.y));
            Point2::new(x / n as f64, y / n as f64)
        };
        let (from, to) = (centroid(a), centroid(b));
        let (dot, cross) = a.iter().zip(b).fold((0.0, 0.0), |(dot, cross), (p, q)| {
            let (px, py, qx, qy) = (p.x - from.x, p.y - from.y, q.x - to.x, q.y - to.y);
            (dot + px * qx + py * qy, cross + px * qy - py * qx)
        });
        RigidMotion { angle: cross.atan2(dot), from, to }
    }

    /// `v` (an XY direction) turned by the motion's rotation.
    pub(crate) fn rotate(&self, v: Vector2) -> Vector2 {
        let (sin, cos) = self.angle.sin_cos();
        Vector2::new(cos * v.x - sin * v.y, sin * v.x + cos * v.y)
    }

    /// `p` moved.
    pub fn apply(&self, p: &Point) -> Point {
        let v = self.rotate(Vector2::new(p.x - self.from.x, p.y - self.from.y));
        Point::new(self.to.x + v.x, self.to.y + v.y, p.z)
    }
}

/// Discrete Fréchet distance in XY between two closed vertex sequences, both walked from
/// vertex 0 back to vertex 0. Eiter–Mannila's dynamic programme, one row at a time: a few
/// lines, so no geometry crate is pulled in for it.
pub fn frechet_xy(a: &[Point], b: &[Point]) -> f64 {
    if a.is_empty() || b.is_empty() {
        return 0.0;
    }
    let closed = |s: &[Point]| s.iter().chain(s.first()).copied().collect::<Vec<_>>();
    let (a, b) = (closed(a), closed(b));
    let mut prev = vec![0.0_f64; b.len()];
    let mut cur = vec![0.0_f64; b.len()];
    for (i, p) in a.iter().enumerate() {
        for (j, q) in b.iter().enumerate() {
            let d = dist2_xy(p, q);
            cur[j] = match (i, j) {
                (0, 0) => d,
                (0, _) => cur[j - 1].max(d),
                (_, 0) => prev[0].max(d),
                _ => prev[j].min(prev[j - 1]).min(cur[j - 1]).max(d),
            };
        }
        std::mem::swap(&mut prev, &mut cur);
    }
    prev[b.len() - 1].sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frechet_of_a_shifted_copy_is_the_shift() {
        let a: Vec<Point> = (0..10).map(|k| Point::new(k as f64, 0.0, 0.0)).collect();
        let b: Vec<Point> = a.iter().map(|p| Point::new(p.x, 0.5, 0.0)).collect();
        assert!((frechet_xy(&a, &b) - 0.5).abs() < 1e-12);
        assert!((rmse_xy(&a, &b) - 0.5).abs() < 1e-12);
    }

    #[test]
    fn aligned_rmse_ignores_a_rigid_motion_but_not_a_change_of_shape() {
        let square: Vec<Point> = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 1.5]]
            .iter()
            .map(|&[x, y]| Point::new(x, y, 0.0))
            .collect();
        let (sin, cos) = 0.7_f64.sin_cos();
        let moved: Vec<Point> = square
            .iter()
            .map(|p| Point::new(3.0 + cos * p.x - sin * p.y, -2.0 + sin * p.x + cos * p.y, 0.0))
            .collect();
        assert!(rmse_xy(&square, &moved) > 1.0);
        assert!(aligned_rmse_xy(&square, &moved) < 1e-12);
        // A mirror image is no rigid motion of the plane: the roof vertex cannot be matched.
        let mirrored: Vec<Point> = square.iter().map(|p| Point::new(p.x, 1.5 - p.y, 0.0)).collect();
        assert!(aligned_rmse_xy(&square, &mirrored) > 0.3);
        // One vertex off by 0.5 against four that agree: the motion cannot hide it all.
        let mut bent = square.clone();
        bent[4].x += 0.5;
        let (aligned, raw) = (aligned_rmse_xy(&square, &bent), rmse_xy(&square, &bent));
        assert!(aligned <= raw && aligned > 0.1, "aligned {aligned}, raw {raw}");
    }

    #[test]
    fn frechet_sees_order_not_just_positions() {
        let a = [Point::new(0.0, 0.0, 0.0), Point::new(1.0, 0.0, 0.0), Point::new(0.0, 1.0, 0.0)];
        let b = [Point::new(0.0, 0.0, 0.0), Point::new(0.0, 1.0, 0.0), Point::new(1.0, 0.0, 0.0)];
        assert!(frechet_xy(&a, &b) > 0.5);
    }
}
