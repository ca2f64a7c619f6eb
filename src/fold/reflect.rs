//! Applying a fold to a border: reflect the folded arc across the fold line.
//!
//! Fold (f1, f2) in angles; s = f·N/2π are border parameters. The vertices strictly inside
//! the anticlockwise arc from s1 to s2 are reflected, in the XY plane, across the line
//! through the border points at s1 and s2; z is kept. A vertex exactly at s1 or s2 lies on
//! the line and stays.
//!
//! ```
//! use close::border::Point;
//! use close::fold::reflect::apply_fold;
//! use std::f64::consts::PI;
//! let square = [Point::new(0.0, 0.0, 0.0), Point::new(1.0, 0.0, 0.0), Point::new(1.0, 1.0, 0.0), Point::new(0.0, 1.0, 0.0)];
//! // Fold along the diagonal from vertex 0 to vertex 2: vertex 1 lands on vertex 3.
//! let folded = apply_fold(&square, [0.0, PI]);
//! assert!((folded[1] - square[3]).norm() < 1e-12);
//! ```

use std::f64::consts::PI;

use crate::border::{point_at, Point};

/// Indices of the vertices strictly inside the anticlockwise arc from angle f1 to f2.
pub fn folded_vertices(n: usize, fold: [f64; 2]) -> Vec<usize> {
    let s1 = fold[0].rem_euclid(2.0 * PI) * n as f64 / (2.0 * PI);
    let span = (fold[1] - fold[0]).rem_euclid(2.0 * PI) * n as f64 / (2.0 * PI);
    (0..n)
        .filter(|&v| {
            let offset = (v as f64 - s1).rem_euclid(n as f64);
            offset > 1e-9 && offset < span - 1e-9
        })
        .collect()
}

/// Reflect `p` across the XY line through `a` and `b` (z kept); `p` itself when a = b in XY.
pub fn reflect_xy(p: &Point, a: &Point, b: &Point) -> Point {
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let len2 = dx * dx + dy * dy;
    if len2 <= f64::EPSILON * (a.coords.norm_squared() + b.coords.norm_squared()).max(f64::MIN_POSITIVE) {
        return *p;
    }
    let (px, py) = (p.x - a.x, p.y - a.y);
    let t = (px * dx + py * dy) / len2;
    let (fx, fy) = (a.x + t * dx, a.y + t * dy);
    Point::new(2.0 * fx - p.x, 2.0 * fy - p.y, p.z)
}

/// The border after folding it along (f1, f2).
pub fn apply_fold(points: &[Point], fold: [f64; 2]) -> Vec<Point> {
    let n = points.len();
    let to_param = |f: f64| f.rem_euclid(2.0 * PI) * n as f64 / (2.0 * PI);
    let (a, b) = (point_at(points, to_param(fold[0])), point_at(points, to_param(fold[1])));
    let mut out = points.to_vec();
    for v in folded_vertices(n, fold) {
        out[v] = reflect_xy(&points[v], &a, &b);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn folded_arc_wraps_through_zero() {
        let n = 8;
        let q = 2.0 * PI / n as f64;
        assert_eq!(folded_vertices(n, [6.5 * q, 1.5 * q]), vec![0, 1, 7]);
        // Endpoints on vertices are not folded.
        assert_eq!(folded_vertices(n, [2.0 * q, 5.0 * q]), vec![3, 4]);
    }

    #[test]
    fn reflection_is_an_involution() {
        let (a, b) = (Point::new(0.0, 0.0, 0.0), Point::new(1.0, 2.0, 5.0));
        let p = Point::new(0.3, -0.7, 0.25);
        let r = reflect_xy(&p, &a, &b);
        assert_eq!(r.z, p.z);
        assert!((reflect_xy(&r, &a, &b) - p).norm() < 1e-12);
    }
}
