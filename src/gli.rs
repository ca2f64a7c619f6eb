//! Gauss linking integral of two segments and its derivative along a vertical lift (dGLI),
//! the cell value of the dGLI disk in Kamat, Borràs, Torras, "CloSE: A Geometric
//! Shape-Agnostic Cloth State Representation" (the GLI itself after Levitt).
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

/// Van Oosterom–Strackee: the solid angle Ω of the spherical triangle (u1, u2, u3) of unit
/// vectors is 2·arg(X + iY) with Y = u1·(u2×u3), X = 1 + u1·u2 + u2·u3 + u3·u1.
#[inline(always)]
fn triangle(u1: &Vector3<f64>, u2: &Vector3<f64>, u3: &Vector3<f64>) -> (f64, f64) {
    (1.0 + u1.dot(u2) + u2.dot(u3) + u3.dot(u1), u1.dot(&u2.cross(u3)))
}

/// Complex product: arguments add.
#[inline(always)]
fn mul((a, b): (f64, f64), (c, d): (f64, f64)) -> (f64, f64) {
    (a * c - b * d, a * d + b * c)
}

/// The spherical quadrilateral (u1, u2, u3, u4) as two triangles, as a complex number whose
/// argument is half its signed solid angle.
#[inline(always)]
fn quadrilateral(u1: &Vector3<f64>, u2: &Vector3<f64>, u3: &Vector3<f64>, u4: &Vector3<f64>) -> (f64, f64) {
    mul(triangle(u1, u2, u3), triangle(u1, u3, u4))
}

/// [`dgli`] computed the fast way, as used for whole disks.
///
/// Levitt's G is the signed solid angle of the spherical quadrilateral of directions
/// (C−A, D−A, D−B, C−B). Written with Van Oosterom–Strackee's formula as the argument of a
/// complex number, the difference G(2ε) − G(ε) is the argument of one ratio: one `atan2`
/// per pair instead of eight `asin`, and no cancellation between two nearly equal sums.
/// C−A and D−B do not change with the lift, so their directions are shared. Agrees with
/// [`dgli`] to rounding wherever the asin form is well conditioned, and stays accurate
/// where it is not (nearly collinear edges).
#[inline]
pub fn dgli_fast(a: &Point, b: &Point, c: &Point, d: &Point) -> f64 {
    let lift = Vector3::new(0.0, 0.0, EPSILON);
    let (b1, d1) = (b + lift, d + lift);
    let (b2, d2) = (b1 + lift, d1 + lift);
    let ca = unit(c - a);
    let db = unit(d - b);
    let q1 = quadrilateral(&ca, &unit(d1 - a), &db, &unit(c - b1));
    let q2 = quadrilateral(&ca, &unit(d2 - a), &db, &unit(c - b2));
    // arg(q2 · conj(q1)) = (G(2ε) − G(ε)) / 2, with Levitt's sign opposite to the triangles'.
    let (re, im) = mul(q2, (q1.0, -q1.1));
    let value = -2.0 * im.atan2(re) / EPSILON;
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
    fn the_fast_form_agrees_with_levitts() {
        // Deterministic pseudo-random segment pairs at many scales and distances.
        let mut state = 0x2545F4914F6CDD1Du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let mut worst = 0.0f64;
        for _ in 0..2000 {
            let p = |x: f64, y: f64, z: f64| Point::new(x, y, z);
            let a = p(next(), next(), 0.05 * next());
            let b = p(next(), next(), 0.05 * next());
            let c = p(next(), next(), 0.05 * next());
            let d = p(next(), next(), 0.05 * next());
            let (slow, fast) = (dgli(&a, &b, &c, &d), dgli_fast(&a, &b, &c, &d));
            worst = worst.max((slow - fast).abs() / (1.0 + slow.abs()));
        }
        assert!(worst < 1e-6, "worst relative difference {worst}");
    }

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
