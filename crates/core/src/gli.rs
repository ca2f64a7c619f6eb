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
//! use close_core::border::Point;
//! use close_core::gli::{dgli, gli};
//! // Two parallel segments in the plane do not link, and lifting them changes that.
//! let (a, b) = (Point::new(0.0, 0.0, 0.0), Point::new(1.0, 0.0, 0.0));
//! let (c, d) = (Point::new(0.0, 1.0, 0.0), Point::new(1.0, 1.0, 0.0));
//! assert_eq!(gli(&a, &b, &c, &d), 0.0);
//! assert!(dgli(&a, &b, &c, &d).is_finite());
//! ```

use std::ops::{Add, Div, Mul, Sub};

use nalgebra::Vector3;
use wide::{f64x4, CmpGt, CmpLe};

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
    s * (asin_clamped(n1.dot(&n2))
        + asin_clamped(n2.dot(&n3))
        + asin_clamped(n3.dot(&n4))
        + asin_clamped(n4.dot(&n1)))
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

/// The arithmetic of [`dgli_fast`], on one pair (`f64`) or on four pairs at once (`f64x4`):
/// one kernel, so a disk computed four cells at a time equals one computed cell by cell, bit
/// for bit.
trait Lane:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self>
{
    fn splat(x: f64) -> Self;
    fn sqrt(self) -> Self;
    /// `self` where it is positive, else 1 (the length of a zero vector, see [`Ray`]).
    fn positive_or_one(self) -> Self;
    /// [`atan2_small`] lane by lane.
    fn atan2_small(y: Self, x: Self) -> Self;
    /// `self` where it is finite, else 0.
    fn finite_or_zero(self) -> Self;
}

impl Lane for f64 {
    #[inline(always)]
    fn splat(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn positive_or_one(self) -> Self {
        if self > 0.0 {
            self
        } else {
            1.0
        }
    }
    #[inline(always)]
    fn atan2_small(y: Self, x: Self) -> Self {
        atan2_small(y, x)
    }
    #[inline(always)]
    fn finite_or_zero(self) -> Self {
        if self.is_finite() {
            self
        } else {
            0.0
        }
    }
}

impl Lane for f64x4 {
    #[inline(always)]
    fn splat(x: f64) -> Self {
        f64x4::splat(x)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64x4::sqrt(self)
    }
    #[inline(always)]
    fn positive_or_one(self) -> Self {
        self.cmp_gt(f64x4::ZERO).blend(self, f64x4::ONE)
    }
    #[inline(always)]
    fn atan2_small(y: Self, x: Self) -> Self {
        let small = x.cmp_gt(f64x4::ZERO) & y.abs().cmp_le(x * 0.125);
        if small.all() {
            atan_series(y / x)
        } else {
            let (y, x) = (y.to_array(), x.to_array());
            f64x4::new(std::array::from_fn(|l| atan2_small(y[l], x[l])))
        }
    }
    #[inline(always)]
    fn finite_or_zero(self) -> Self {
        self.is_finite().blend(self, f64x4::ZERO)
    }
}

/// A 3-vector of lanes.
#[derive(Clone, Copy)]
struct V3<L> {
    x: L,
    y: L,
    z: L,
}

impl<L: Lane> V3<L> {
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        V3 { x: self.x - o.x, y: self.y - o.y, z: self.z - o.z }
    }
    #[inline(always)]
    fn dot(self, o: Self) -> L {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    #[inline(always)]
    fn cross(self, o: Self) -> Self {
        V3 {
            x: self.y * o.z - self.z * o.y,
            y: self.z * o.x - self.x * o.z,
            z: self.x * o.y - self.y * o.x,
        }
    }
    /// The point lifted by ε.
    #[inline(always)]
    fn lifted(self) -> Self {
        V3 { z: self.z + L::splat(EPSILON), ..self }
    }
}

impl From<&Point> for V3<f64> {
    fn from(p: &Point) -> Self {
        V3 { x: p.x, y: p.y, z: p.z }
    }
}

impl From<[&Point; 4]> for V3<f64x4> {
    fn from(p: [&Point; 4]) -> Self {
        V3 {
            x: f64x4::new(p.map(|p| p.x)),
            y: f64x4::new(p.map(|p| p.y)),
            z: f64x4::new(p.map(|p| p.z)),
        }
    }
}

/// A direction given by an unnormalised vector and its length (1 for the zero vector, whose
/// direction counts as zero, as a unit vector would).
#[derive(Clone, Copy)]
struct Ray<L> {
    v: V3<L>,
    len: L,
}

impl<L: Lane> Ray<L> {
    #[inline(always)]
    fn new(v: V3<L>) -> Self {
        Ray { v, len: v.dot(v).sqrt().positive_or_one() }
    }
}

/// Van Oosterom–Strackee: the solid angle Ω of the spherical triangle of the directions
/// (a, b, c) is 2·arg(X + iY) with Y = a·(b×c), X = |a||b||c| + (a·b)|c| + (b·c)|a| + (c·a)|b|
/// (the unit-vector form scaled by |a||b||c| > 0, which leaves the argument: no division).
#[inline(always)]
fn triangle<L: Lane>(a: &Ray<L>, b: &Ray<L>, c: &Ray<L>) -> (L, L) {
    (
        a.len * b.len * c.len + a.v.dot(b.v) * c.len + b.v.dot(c.v) * a.len + c.v.dot(a.v) * b.len,
        a.v.dot(b.v.cross(c.v)),
    )
}

/// Complex product: arguments add.
#[inline(always)]
fn mul<L: Lane>((a, b): (L, L), (c, d): (L, L)) -> (L, L) {
    (a * c - b * d, a * d + b * c)
}

/// The spherical quadrilateral (u1, u2, u3, u4) as two triangles, as a complex number whose
/// argument is half its signed solid angle.
#[inline(always)]
fn quadrilateral<L: Lane>(u1: &Ray<L>, u2: &Ray<L>, u3: &Ray<L>, u4: &Ray<L>) -> (L, L) {
    mul(triangle(u1, u2, u3), triangle(u1, u3, u4))
}

/// atan t for |t| ≤ 1/8 by its Taylor series to t¹⁵ (it leaves out less than 1e-15 relative).
#[inline(always)]
fn atan_series<L: Lane>(t: L) -> L {
    let t2 = t * t;
    // atan t = t·Σ (−t²)^k / (2k + 1), Horner from k = 7.
    const C: [f64; 8] =
        [1.0, -1.0 / 3.0, 1.0 / 5.0, -1.0 / 7.0, 1.0 / 9.0, -1.0 / 11.0, 1.0 / 13.0, -1.0 / 15.0];
    t * C.iter().rev().fold(L::splat(0.0), |acc, &c| acc * t2 + L::splat(c))
}

/// atan2(y, x), by its Taylor series where the angle is small (|y| ≤ x/8), which is nearly
/// every cell of a disk: the lift ε changes the solid angle little. libm's atan2 was a third
/// of the cost of a disk.
#[inline(always)]
fn atan2_small(y: f64, x: f64) -> f64 {
    if x > 0.0 && y.abs() <= 0.125 * x {
        atan_series(y / x)
    } else {
        y.atan2(x)
    }
}

/// The dGLI of edges AB and CD in any [`Lane`]; see [`dgli_fast`].
#[inline(always)]
fn dgli_lanes<L: Lane>(a: V3<L>, b: V3<L>, c: V3<L>, d: V3<L>) -> L {
    let (b1, d1) = (b.lifted(), d.lifted());
    let (b2, d2) = (b1.lifted(), d1.lifted());
    let ca = Ray::new(c.sub(a));
    let db = Ray::new(d.sub(b));
    let q1 = quadrilateral(&ca, &Ray::new(d1.sub(a)), &db, &Ray::new(c.sub(b1)));
    let q2 = quadrilateral(&ca, &Ray::new(d2.sub(a)), &db, &Ray::new(c.sub(b2)));
    // arg(q2 · conj(q1)) = (G(2ε) − G(ε)) / 2, with Levitt's sign opposite to the triangles'.
    let (re, im) = mul(q2, (q1.0, L::splat(0.0) - q1.1));
    (L::splat(-2.0) * L::atan2_small(im, re) / L::splat(EPSILON)).finite_or_zero()
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
    dgli_lanes(V3::from(a), V3::from(b), V3::from(c), V3::from(d))
}

/// [`dgli_fast`] of four pairs at once, `[a, b, c, d]` each, in SIMD lanes; equal to it
/// bit for bit.
///
/// ```
/// use close_core::border::Point;
/// use close_core::gli::{dgli_fast, dgli_fast_x4};
/// let p = |x: f64, y: f64, z: f64| Point::new(x, y, z);
/// let pairs = [0.0, 0.5, 1.0, 1.5].map(|h| [p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0), p(0.0, 1.0, h), p(1.0, 0.5, h)]);
/// let four = dgli_fast_x4(pairs.each_ref().map(|[a, b, c, d]| [a, b, c, d]));
/// for (k, [a, b, c, d]) in pairs.iter().enumerate() {
///     assert_eq!(four[k].to_bits(), dgli_fast(a, b, c, d).to_bits());
/// }
/// ```
#[inline]
pub fn dgli_fast_x4(pairs: [[&Point; 4]; 4]) -> [f64; 4] {
    let corner = |k: usize| V3::from(pairs.map(|p| p[k]));
    dgli_lanes(corner(0), corner(1), corner(2), corner(3)).to_array()
}

/// [`dgli_fast`] of every pair `[a, b, c, d]` of `pairs`, in order, four at a time.
#[inline]
pub(crate) fn dgli_each<'a>(
    pairs: impl IntoIterator<Item = [&'a Point; 4]>,
    mut put: impl FnMut(f64),
) {
    let unused = Point::origin();
    let mut batch = [[&unused; 4]; 4];
    let mut filled = 0;
    for pair in pairs {
        batch[filled] = pair;
        filled += 1;
        if filled == 4 {
            dgli_fast_x4(batch).into_iter().for_each(&mut put);
            filled = 0;
        }
    }
    for [a, b, c, d] in &batch[..filled] {
        put(dgli_fast(a, b, c, d));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn four_lanes_equal_one_by_one_bit_for_bit() {
        // Near and far pairs, so some lanes take the series and some libm's atan2.
        let mut rng = crate::rng::SplitMix64::new(9);
        let mut next = || rng.range(-1.0, 1.0);
        let mut fallback = 0;
        for k in 0..4000 {
            let spread = [1.0, 1e-3, 1e-5][k % 3];
            let points: Vec<Point> = (0..16)
                .map(|_| Point::new(spread * next(), spread * next(), 0.5 * spread * next()))
                .collect();
            let pairs: [[&Point; 4]; 4] =
                std::array::from_fn(|l| std::array::from_fn(|c| &points[4 * l + c]));
            let four = dgli_fast_x4(pairs);
            for (l, [a, b, c, d]) in pairs.iter().enumerate() {
                assert_eq!(
                    four[l].to_bits(),
                    dgli_fast(a, b, c, d).to_bits(),
                    "pair {k}, lane {l}"
                );
            }
            // An angle beyond atan(1/8) is outside the series.
            fallback += usize::from(four.iter().any(|v| v.abs() * EPSILON / 2.0 > 0.125f64.atan()));
        }
        assert!(fallback > 0, "no lane took libm's atan2");
    }

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
    fn the_small_angle_series_is_atan2() {
        for k in -1000..=1000 {
            let y = k as f64 * 1.3e-4;
            for x in [1e-9, 0.5, 1.0, 7.0] {
                let (fast, exact) = (atan2_small(y * x, x), (y * x).atan2(x));
                assert!(
                    (fast - exact).abs() <= 1e-15 * exact.abs().max(1e-300),
                    "{y} {x}: {fast} vs {exact}"
                );
            }
        }
        assert_eq!(atan2_small(1.0, -1.0), 1.0f64.atan2(-1.0));
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
