//! Gauss linking integral of two segments and its derivative along a vertical lift (dGLI).
//!
//! **GLI** of segments AB and CD is Levitt's exact formula without the 1/4π factor: with
//! n1 = unit(AC×AD), n2 = unit(AD×BD), n3 = unit(BD×BC), n4 = unit(BC×AC),
//! `G = sign(((D−C)×(B−A))·(C−A)) · Σ asin(n_k·n_{k+1})`.
//! Each dot product is clamped to [−1, 1] and a zero normal counts as zero, so nearly
//! collinear or touching segments give a finite value where the reference gives NaN.
//!
//! **dGLI** lifts B and D along +z: `(G(A, B+2εẑ, C, D+2εẑ) − G(A, B+εẑ, C, D+εẑ)) / ε`
//! with ε = 1e-5; the second lift is added to the first, as the reference does.
//!
//! ```
//! use close::border::Point;
//! use close::gli::{dgli, gli};
//! // Two parallel segments in the plane do not link, and lifting them changes that.
//! let (a, b) = (Point::new(0.0, 0.0, 0.0), Point::new(1.0, 0.0, 0.0));
//! let (c, d) = (Point::new(0.0, 1.0, 0.0), Point::new(1.0, 1.0, 0.0));
//! assert_eq!(gli(&a, &b, &c, &d), 0.0);
//! assert!(dgli(&a, &b, &c, &d).is_finite());
//! ```

use nalgebra::Vector3;

use crate::border::Point;

/// The lift of the finite difference (the paper's footnote).
pub const EPSILON: f64 = 1e-5;

#[inline(always)]
fn unit(v: Vector3<f64>) -> Vector3<f64> {
    let norm = v.norm();
    if norm > 0.0 {
        v / norm
    } else {
        Vector3::zeros()
    }
}

#[inline(always)]
fn asin_clamped(x: f64) -> f64 {
    x.clamp(-1.0, 1.0).asin()
}

/// Sign that is 0 at 0 (`f64::signum` gives ±1 there).
#[inline(always)]
fn sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// Gauss linking integral of segments AB and CD (no 1/4π factor), never NaN.
#[inline]
pub fn gli(a: &Point, b: &Point, c: &Point, d: &Point) -> f64 {
    let ac = c - a;
    let ad = d - a;
    let bc = c - b;
    let bd = d - b;
    let s = sign((d - c).cross(&(b - a)).dot(&ac));
    if s == 0.0 {
        return 0.0;
    }
    let n1 = unit(ac.cross(&ad));
    let n2 = unit(ad.cross(&bd));
    let n3 = unit(bd.cross(&bc));
    let n4 = unit(bc.cross(&ac));
    s * (asin_clamped(n1.dot(&n2)) + asin_clamped(n2.dot(&n3)) + asin_clamped(n3.dot(&n4)) + asin_clamped(n4.dot(&n1)))
}

/// dGLI of edges AB and CD: the finite-difference derivative of [`gli`] as B and D are
/// lifted along +z.
#[inline]
pub fn dgli(a: &Point, b: &Point, c: &Point, d: &Point) -> f64 {
    let lift = Vector3::new(0.0, 0.0, EPSILON);
    let (b1, d1) = (b + lift, d + lift);
    let (b2, d2) = (b1 + lift, d1 + lift);
    let value = (gli(a, &b2, c, &d2) - gli(a, &b1, c, &d1)) / EPSILON;
    if value.is_finite() {
        value
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossing_segments_link_by_half_a_turn_each_way() {
        // Segments crossing over each other (one above, one below) subtend a solid angle
        // approaching 2π as they come together: Levitt's G tends to ±2π.
        let a = Point::new(-1.0, 0.0, 0.0);
        let b = Point::new(1.0, 0.0, 0.0);
        let c = Point::new(0.0, -1.0, 1e-6);
        let d = Point::new(0.0, 1.0, 1e-6);
        let g = gli(&a, &b, &c, &d);
        assert!((g.abs() - 2.0 * std::f64::consts::PI).abs() < 1e-4, "{g}");
        // Swapping which segment is on top flips the sign.
        let c2 = Point::new(0.0, -1.0, -1e-6);
        let d2 = Point::new(0.0, 1.0, -1e-6);
        assert!(gli(&a, &b, &c2, &d2) * g < 0.0);
    }

    #[test]
    fn collinear_and_touching_segments_stay_finite() {
        let p = |x: f64| Point::new(x, 0.0, 0.0);
        assert_eq!(gli(&p(0.0), &p(1.0), &p(2.0), &p(3.0)), 0.0);
        assert!(dgli(&p(0.0), &p(1.0), &p(1.0), &p(2.0)).is_finite());
        assert!(dgli(&p(0.0), &p(0.0), &p(1.0), &p(2.0)).is_finite());
    }
}
