//! Cloth outlines of the built-in dataset: napkin, towel, circular towel, T-shirt, top,
//! trousers and skirt.
//!
//! Each shape is a closed polygon listed anticlockwise seen from +z, the border convention
//! of Kamat, Borràs, Torras, "CloSE: A Geometric Shape-Agnostic Cloth State
//! Representation" (its border: a closed polyline P_0 … P_{N−1}, edge k joins P_k and
//! P_{k+1 mod N}). A side gets a number of segments in proportion to its length
//! (largest-remainder rounding), so every geometric corner is a vertex and the spacing is
//! roughly uniform; the circular towel is sampled at polar angles 2πk/N. The vertices are
//! then brought to the normal form of the paper's evaluation ([`Normalisation::of`]: vertex
//! mean at the origin, farthest vertex at distance 1); z = 0.
//!
//! ```
//! use close_io::dataset::shapes::{outline, Shape};
//! let napkin = outline(Shape::Napkin);
//! assert_eq!(napkin.points.len(), 76);
//! // 19 segments a side: the corners are vertices 0, 19, 38 and 57.
//! assert_eq!(napkin.side_starts, vec![0, 19, 38, 57]);
//! // A third of the way along the top side (right to left).
//! assert!((napkin.on_side(2, 1.0 / 3.0) - 44.333).abs() < 1e-3);
//! ```

use close_core::angle::param_to_angle;
use close_core::border::{Normalisation, Point};

/// The cloth shapes of the dataset.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Shape {
    /// Square napkin, N = 76.
    Napkin,
    /// Rectangular towel 2:1, N = 72.
    Towel,
    /// Circular towel, N = 64.
    CircularTowel,
    /// T-shirt with short sleeves and a V neck, N = 100; vertex 0 is the middle of the hem.
    TShirt,
    /// Sleeveless top with straps, N = 90.
    Top,
    /// Trousers (two legs, crotch, waist), N = 100.
    Trousers,
    /// Skirt, a trapezoid wider at the hem, N = 80.
    Skirt,
}

impl Shape {
    pub const ALL: [Shape; 7] = [
        Shape::Napkin,
        Shape::Towel,
        Shape::CircularTowel,
        Shape::TShirt,
        Shape::Top,
        Shape::Trousers,
        Shape::Skirt,
    ];

    /// The name used for sample names and categories.
    pub fn name(self) -> &'static str {
        match self {
            Shape::Napkin => "napkin",
            Shape::Towel => "towel",
            Shape::CircularTowel => "circular_towel",
            Shape::TShirt => "tshirt",
            Shape::Top => "top",
            Shape::Trousers => "trousers",
            Shape::Skirt => "skirt",
        }
    }

    /// Border vertex count.
    pub fn vertex_count(self) -> usize {
        match self {
            Shape::Napkin => 76,
            Shape::Towel => 72,
            Shape::CircularTowel => 64,
            Shape::TShirt | Shape::Trousers => 100,
            Shape::Top => 90,
            Shape::Skirt => 80,
        }
    }

    /// Polygon vertices before normalisation, anticlockwise from border vertex 0 (none for
    /// the circle). Each starts a side; all but the T-shirt's first (mid-hem) are corners.
    pub fn polygon(self) -> &'static [[f64; 2]] {
        match self {
            Shape::Napkin => &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            Shape::Towel => &[[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]],
            Shape::CircularTowel => &[],
            Shape::TShirt => &[
                [0.0, 0.0],
                [0.5, 0.0],
                [0.5, 0.95],
                [0.85, 0.80],
                [1.0, 1.10],
                [0.55, 1.40],
                [0.18, 1.45],
                [0.0, 1.33],
                [-0.18, 1.45],
                [-0.55, 1.40],
                [-1.0, 1.10],
                [-0.85, 0.80],
                [-0.5, 0.95],
                [-0.5, 0.0],
            ],
            Shape::Top => &[
                [-0.5, 0.0],
                [0.5, 0.0],
                [0.5, 0.9],
                [0.3, 1.3],
                [0.15, 1.3],
                [0.0, 1.05],
                [-0.15, 1.3],
                [-0.3, 1.3],
                [-0.5, 0.9],
            ],
            Shape::Trousers => &[
                [-0.45, 0.0],
                [-0.10, 0.0],
                [0.0, 0.72],
                [0.10, 0.0],
                [0.45, 0.0],
                [0.42, 1.10],
                [-0.42, 1.10],
            ],
            Shape::Skirt => &[[-0.7, 0.0], [0.7, 0.0], [0.4, 1.0], [-0.4, 1.0]],
        }
    }
}

/// A shape's normalised border and where each polygon side starts.
#[derive(Debug, Clone, PartialEq)]
pub struct Outline {
    pub points: Vec<Point>,
    /// Vertex index of each polygon vertex, increasing; side k runs from vertex
    /// `side_starts[k]` to `side_starts[k+1]`. The circle has one "side" all the way round,
    /// starting at vertex 0.
    pub side_starts: Vec<usize>,
}

impl Outline {
    /// Border parameter of the point a fraction `t` along side `side`. Sides are sampled
    /// uniformly, so this is exactly that point of the polygon.
    pub fn on_side(&self, side: usize, t: f64) -> f64 {
        let n = self.points.len();
        let k = side % self.side_starts.len();
        let start = self.side_starts[k];
        let end = self.side_starts.get(k + 1).copied().unwrap_or(n + self.side_starts[0]);
        (start as f64 + t * (end - start) as f64).rem_euclid(n as f64)
    }
}

/// Segments per side in proportion to its length, by largest-remainder rounding.
fn segments_per_side(lengths: &[f64], n: usize) -> Vec<usize> {
    let total: f64 = lengths.iter().sum();
    let ideal: Vec<f64> = lengths.iter().map(|l| l / total * n as f64).collect();
    let mut counts: Vec<usize> = ideal.iter().map(|x| x.floor() as usize).collect();
    let mut by_remainder: Vec<usize> = (0..lengths.len()).collect();
    // Stable sort: equal remainders go to the earlier side.
    by_remainder
        .sort_by(|&a, &b| (ideal[b] - ideal[b].floor()).total_cmp(&(ideal[a] - ideal[a].floor())));
    let missing = n - counts.iter().sum::<usize>();
    for &k in by_remainder.iter().take(missing) {
        counts[k] += 1;
    }
    counts
}

/// The points in the normal form (vertex mean at 0, farthest vertex at 1).
///
/// Only for the constant polygons of this module and their grids, whose vertices never
/// all coincide (the tests build every one).
pub(super) fn normalise(points: &[Point]) -> Vec<Point> {
    Normalisation::of(points).expect("a built-in outline has distinct vertices").apply_all(points)
}

/// The normalised outline of a shape.
pub fn outline(kind: Shape) -> Outline {
    let n = kind.vertex_count();
    let polygon = kind.polygon();
    if polygon.is_empty() {
        let points: Vec<Point> = (0..n)
            .map(|k| {
                let a = param_to_angle(k as f64, n);
                Point::new(a.cos(), a.sin(), 0.0)
            })
            .collect();
        return Outline { points: normalise(&points), side_starts: vec![0] };
    }
    let m = polygon.len();
    let lengths: Vec<f64> = (0..m)
        .map(|k| {
            let (a, b) = (polygon[k], polygon[(k + 1) % m]);
            (b[0] - a[0]).hypot(b[1] - a[1])
        })
        .collect();
    let counts = segments_per_side(&lengths, n);
    let mut points = Vec::with_capacity(n);
    let mut side_starts = Vec::with_capacity(m);
    for (k, &count) in counts.iter().enumerate() {
        side_starts.push(points.len());
        let (a, b) = (polygon[k], polygon[(k + 1) % m]);
        points.extend((0..count).map(|j| {
            let t = j as f64 / count as f64;
            Point::new(a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), 0.0)
        }));
    }
    Outline { points: normalise(&points), side_starts }
}

/// The normalised border of a shape.
pub fn shape(kind: Shape) -> Vec<Point> {
    outline(kind).points
}

#[cfg(test)]
mod tests {
    use super::*;
    use close_core::angle::TAU;
    use close_core::border::signed_area_xy;
    use nalgebra::Vector3;

    /// The exterior turning angle at each vertex of a closed XY polyline, in (−π, π]: how far
    /// the direction turns from the incoming to the outgoing edge (positive = left).
    fn turning_angles(points: &[Point]) -> Vec<f64> {
        let n = points.len();
        (0..n)
            .map(|v| {
                let (a, b, c) = (points[(v + n - 1) % n], points[v], points[(v + 1) % n]);
                let (u, w) = (b - a, c - b);
                (u.x * w.y - u.y * w.x).atan2(u.x * w.x + u.y * w.y)
            })
            .collect()
    }

    /// Turns sharper than this make a corner (every polygon corner of the dataset turns more;
    /// the 64-gon of the circle turns 5.6° at each vertex).
    const CORNER_TURN: f64 = TAU / 36.0;

    #[test]
    fn shapes_are_normalised_closed_and_anticlockwise() {
        for kind in Shape::ALL {
            let o = outline(kind);
            let n = o.points.len();
            assert_eq!(n, kind.vertex_count(), "{kind:?}");
            let centroid = o.points.iter().map(|p| p.coords).sum::<Vector3<f64>>() / n as f64;
            assert!(centroid.norm() < 1e-12, "{kind:?} centroid {centroid}");
            let radius = o.points.iter().map(|p| p.coords.norm()).fold(0.0, f64::max);
            assert!((radius - 1.0).abs() < 1e-12, "{kind:?} radius {radius}");
            assert!(signed_area_xy(&o.points) > 0.0, "{kind:?} is clockwise");
            // Closed without a repeated vertex: every edge, the closing one too, is a
            // segment of about the same length (uniform sampling).
            let edges: Vec<f64> =
                (0..n).map(|k| (o.points[(k + 1) % n] - o.points[k]).norm()).collect();
            let mean = edges.iter().sum::<f64>() / n as f64;
            assert!(
                edges.iter().all(|&e| e > 0.5 * mean && e < 1.5 * mean),
                "{kind:?} edges {edges:?}"
            );
            // Full turn of a simple anticlockwise polygon.
            let total: f64 = turning_angles(&o.points).iter().sum();
            assert!((total - TAU).abs() < 1e-9, "{kind:?} turns {total}");
        }
    }

    #[test]
    fn corners_are_vertices_at_the_side_starts() {
        for kind in Shape::ALL {
            let o = outline(kind);
            let corners: Vec<usize> = turning_angles(&o.points)
                .iter()
                .enumerate()
                .filter(|(_, t)| t.abs() > CORNER_TURN)
                .map(|(v, _)| v)
                .collect();
            let expected = match kind {
                Shape::CircularTowel => 0,
                Shape::TShirt => 13,
                Shape::Top => 9,
                Shape::Trousers => 7,
                Shape::Napkin | Shape::Towel | Shape::Skirt => 4,
            };
            assert_eq!(corners.len(), expected, "{kind:?}: {corners:?}");
            // Every corner starts a side (the T-shirt's side 0 starts at the middle of the hem).
            assert!(corners.iter().all(|c| o.side_starts.contains(c)), "{kind:?}");
            // Between corners the border runs straight.
            let straight = turning_angles(&o.points)
                .iter()
                .enumerate()
                .filter(|(v, _)| !o.side_starts.contains(v))
                .all(|(_, t)| t.abs() < 1e-9);
            assert_eq!(straight, kind != Shape::CircularTowel, "{kind:?}");
        }
        // The reference's vertex layout: 19 segments per napkin side, 24/12/24/12 on the towel.
        assert_eq!(outline(Shape::Napkin).side_starts, vec![0, 19, 38, 57]);
        assert_eq!(outline(Shape::Towel).side_starts, vec![0, 24, 36, 60]);
    }

    #[test]
    fn on_side_walks_the_polygon() {
        let towel = outline(Shape::Towel);
        assert_eq!(towel.on_side(1, 0.5), 30.0);
        // The last side wraps to vertex 0, and side numbers wrap too.
        assert_eq!(towel.on_side(3, 0.5), 66.0);
        assert_eq!(towel.on_side(3, 1.0), 0.0);
        assert_eq!(towel.on_side(4, 0.25), 6.0);
        let circle = outline(Shape::CircularTowel);
        assert_eq!(circle.on_side(0, 0.25), 16.0);
    }

    #[test]
    fn largest_remainder_rounding_keeps_the_total() {
        assert_eq!(segments_per_side(&[1.0, 1.0, 1.0], 10), vec![4, 3, 3]);
        assert_eq!(segments_per_side(&[2.0, 1.0, 1.0], 9), vec![5, 2, 2]);
        assert_eq!(segments_per_side(&[1.0, 2.9, 0.1], 8), vec![2, 6, 0]);
    }
}
