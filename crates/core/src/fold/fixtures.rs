//! Shapes the fold modules' tests share, made without the fold search: a square border and
//! a fold of it by hand.

use crate::border::Point;

/// A square of side 2·`half` centred on the origin, `per_side` edges a side, anticlockwise
/// from (−half, −half), at height `z(k)` for vertex k.
pub(crate) fn square(per_side: usize, half: f64, z: impl Fn(usize) -> f64) -> Vec<Point> {
    (0..4 * per_side)
        .map(|k| {
            let t = -half + 2.0 * half * (k % per_side) as f64 / per_side as f64;
            let (x, y) = [(t, -half), (half, t), (-t, half), (-half, -t)][k / per_side];
            Point::new(x, y, z(k))
        })
        .collect()
}

/// The border point at parameter `s`, by the test's own interpolation.
pub(crate) fn at(points: &[Point], s: f64) -> Point {
    let n = points.len();
    let (k, t) = (s.floor() as usize % n, s - s.floor());
    Point::from(points[k].coords * (1.0 - t) + points[(k + 1) % n].coords * t)
}

/// `before` folded by hand: every vertex v with 0 < (v − s1) mod n < (s2 − s1) mod n
/// reflected across the XY line through the border points at s1 and s2, and turned over
/// at height `axis` (z ↦ 2·axis − z).
pub(crate) fn fold_by_hand(before: &[Point], s: [f64; 2], axis: f64) -> Vec<Point> {
    let nf = before.len() as f64;
    let (a, b) = (at(before, s[0]), at(before, s[1]));
    let (ux, uy) = ((b.x - a.x) / (b - a).xy().norm(), (b.y - a.y) / (b - a).xy().norm());
    let span = (s[1] - s[0]).rem_euclid(nf);
    before
        .iter()
        .enumerate()
        .map(|(v, p)| {
            let offset = (v as f64 - s[0]).rem_euclid(nf);
            if offset <= 0.0 || offset >= span {
                return *p;
            }
            let t = (p.x - a.x) * ux + (p.y - a.y) * uy;
            let (fx, fy) = (a.x + t * ux, a.y + t * uy);
            Point::new(2.0 * fx - p.x, 2.0 * fy - p.y, 2.0 * axis - p.z)
        })
        .collect()
}

/// A square of side 1 centred on the origin, `per_side` vertices a side.
pub(crate) fn unit_square(per_side: usize) -> Vec<Point> {
    let s = per_side as f64;
    (0..4 * per_side)
        .map(|k| {
            let t = (k % per_side) as f64 / s;
            let (x, y) = [(t, 0.0), (1.0, t), (1.0 - t, 1.0), (0.0, 1.0 - t)][k / per_side];
            Point::new(x - 0.5, y - 0.5, 0.0)
        })
        .collect()
}

/// Every vertex left of the line through `a` at `angle`, whatever its layer, reflected
/// across it and laid on top (independent of the fold search's state).
pub(crate) fn fold_all(state: &[Point], a: [f64; 2], angle: f64) -> Vec<Point> {
    let u = [angle.cos(), angle.sin()];
    let top = state.iter().map(|p| p.z).fold(f64::NEG_INFINITY, f64::max);
    state
        .iter()
        .map(|p| {
            let (dx, dy) = (p.x - a[0], p.y - a[1]);
            if u[0] * dy - u[1] * dx <= 0.0 {
                return *p;
            }
            let t = dx * u[0] + dy * u[1];
            Point::new(
                a[0] + 2.0 * t * u[0] - dx,
                a[1] + 2.0 * t * u[1] - dy,
                2.0 * top + 0.004 - p.z,
            )
        })
        .collect()
}
