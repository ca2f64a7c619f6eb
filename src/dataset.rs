//! The built-in dataset: synthetic cloth borders and exact folds, generated in memory.
//!
//! **Shapes.** Each shape is a closed polygon listed anticlockwise seen from +z. A side
//! gets a number of segments in proportion to its length (largest-remainder rounding), so
//! every geometric corner is a vertex and the spacing is roughly uniform; the circular towel
//! is sampled at polar angles 2πk/N. The vertices are then centred on their vertex mean and
//! scaled so the farthest one is at distance 1; z = 0.
//!
//! **Fold** with border parameters f1, f2 (fractional vertex indices, [`point_at`]):
//! P1 = point(f1), P2 = point(f2); the vertices strictly inside the anticlockwise arc from
//! f1 to f2 are reflected across the line P1P2 in XY. A fold is accepted only when that arc
//! lies strictly on one side of the line and, on a flat border, the chord P1P2 lies inside
//! the cloth. The folded stack turns over, so a vertex at height z lands at
//! 2·top + thickness − z, top being the highest vertex before the fold: on a flat cloth
//! that is z = thickness, and a second fold puts the flipped layers above everything.
//!
//! **Truth** (SPEC convention): the fold [f1, f2] in angles 2πf/N, and the vertices that
//! moved. Every fold endpoint is written as a point along a side of the shape's polygon,
//! so the fold means the same thing whatever N is.
//!
//! **Meshes.** The napkin and the towel also come as grid meshes of quads whose boundary
//! is their outline ([`grid_mesh`]), folded by the same rule with every vertex on the
//! folded side reflected ([`fold_mesh`]): category `mesh`, the truth as for the border.
//!
//! Variants of a clean fold: Gaussian noise (sd 0.005) on the end frame only, a rotation
//! about z plus a translation of both frames, an in-plane jitter (sd 1e-5) of the start
//! before folding, and a cyclic relabelling of the vertices. Randomness is a seeded
//! splitmix64, so two builds are identical.
//!
//! ```
//! use close::dataset::{builtin, find, fold_border, shape, Shape};
//! let napkin = shape(Shape::Napkin);
//! assert_eq!(napkin.len(), 76);
//! // Fold the square along its diagonal from corner 0 to corner 38: corner 19 lands on 57.
//! let folded = fold_border(&napkin, 0.0, 38.0, 0.01).unwrap();
//! assert!((folded[19].xy() - napkin[57].xy()).norm() < 1e-12);
//! assert!(builtin().len() >= 68);
//! assert!(find("napkin__diagonal").is_some());
//! ```

use std::f64::consts::PI;
use std::sync::OnceLock;

use nalgebra::{Rotation3, Vector3};

use crate::border::{point_at, Point};
use crate::error::{Error, Result};
use crate::fold::reflect::{folded_vertices, reflect_xy};
use crate::formats::{MeshFrames, Sample, Truth};

/// Cloth thickness: the height a folded layer gains.
pub const THICKNESS: f64 = 0.01;
/// Standard deviation of the noise added to a noisy sample's end frame.
pub const END_NOISE: f64 = 0.005;
/// Standard deviation of the in-plane jitter of a jittered sample's start frame.
pub const START_JITTER: f64 = 1e-5;

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
    pub const ALL: [Shape; 7] =
        [Shape::Napkin, Shape::Towel, Shape::CircularTowel, Shape::TShirt, Shape::Top, Shape::Trousers, Shape::Skirt];

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

    /// Polygon corners before normalisation, anticlockwise from vertex 0 (none for the circle).
    fn corners(self) -> &'static [[f64; 2]] {
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
    /// Vertex index of each polygon corner, increasing; side k runs from corner k to
    /// corner k+1. The circle has one "side" all the way round, starting at vertex 0.
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
    by_remainder.sort_by(|&a, &b| (ideal[b] - ideal[b].floor()).total_cmp(&(ideal[a] - ideal[a].floor())));
    let missing = n - counts.iter().sum::<usize>();
    for &k in by_remainder.iter().take(missing) {
        counts[k] += 1;
    }
    counts
}

/// Centre on the vertex mean and scale the farthest vertex to distance 1.
fn normalise(points: Vec<Point>) -> Vec<Point> {
    let centroid = points.iter().map(|p| p.coords).sum::<Vector3<f64>>() / points.len() as f64;
    let radius = points.iter().map(|p| (p.coords - centroid).norm()).fold(0.0, f64::max);
    points.into_iter().map(|p| Point::from((p.coords - centroid) / radius)).collect()
}

/// The normalised outline of a shape.
pub fn outline(kind: Shape) -> Outline {
    let n = kind.vertex_count();
    let corners = kind.corners();
    if corners.is_empty() {
        let points = (0..n)
            .map(|k| {
                let a = 2.0 * PI * k as f64 / n as f64;
                Point::new(a.cos(), a.sin(), 0.0)
            })
            .collect();
        return Outline { points: normalise(points), side_starts: vec![0] };
    }
    let m = corners.len();
    let lengths: Vec<f64> = (0..m)
        .map(|k| {
            let (a, b) = (corners[k], corners[(k + 1) % m]);
            (b[0] - a[0]).hypot(b[1] - a[1])
        })
        .collect();
    let counts = segments_per_side(&lengths, n);
    let mut points = Vec::with_capacity(n);
    let mut side_starts = Vec::with_capacity(m);
    for (k, &count) in counts.iter().enumerate() {
        side_starts.push(points.len());
        let (a, b) = (corners[k], corners[(k + 1) % m]);
        points.extend((0..count).map(|j| {
            let t = j as f64 / count as f64;
            Point::new(a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), 0.0)
        }));
    }
    Outline { points: normalise(points), side_starts }
}

/// The normalised border of a shape.
pub fn shape(kind: Shape) -> Vec<Point> {
    outline(kind).points
}

/// 2D cross product of (b − a) and (p − a): positive when p is left of a→b.
fn side_of(a: &Point, b: &Point, p: &Point) -> f64 {
    (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)
}

/// Even-odd test of `p` against the XY polygon `points`.
fn inside_xy(points: &[Point], p: &Point) -> bool {
    let n = points.len();
    (0..n).fold(false, |inside, k| {
        let (a, b) = (points[k], points[(k + 1) % n]);
        let crosses = (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
        inside != crosses
    })
}

/// Whether the chord from `a` to `b` lies inside the (flat) cloth: it crosses no border
/// edge properly, and points along it are inside the polygon. The chord's ends lie on
/// edges themselves; `tolerance` keeps those touches from counting as crossings.
fn chord_inside(points: &[Point], a: &Point, b: &Point, tolerance: f64) -> bool {
    let n = points.len();
    let opposite = |x: f64, y: f64| (x > tolerance && y < -tolerance) || (x < -tolerance && y > tolerance);
    let crosses_an_edge = (0..n).any(|k| {
        let (c, d) = (points[k], points[(k + 1) % n]);
        opposite(side_of(a, b, &c), side_of(a, b, &d)) && opposite(side_of(&c, &d, a), side_of(&c, &d, b))
    });
    const SAMPLES: usize = 64;
    !crosses_an_edge && (1..SAMPLES).all(|j| inside_xy(points, &(a + (b - a) * (j as f64 / SAMPLES as f64))))
}

/// Fold a border along border parameters `f1`, `f2` (see the module doc).
///
/// Errors when a parameter is not finite, the fold points coincide, no vertex lies on the
/// arc, the arc crosses the fold line, or (flat border) the chord leaves the cloth.
pub fn fold_border(points: &[Point], f1: f64, f2: f64, thickness: f64) -> Result<Vec<Point>> {
    let n = points.len();
    if !(f1.is_finite() && f2.is_finite() && thickness.is_finite()) {
        return Err(Error::InvalidArgument(format!("fold ({f1}, {f2}) with thickness {thickness}: not finite")));
    }
    if n < 3 {
        return Err(Error::TooFewVertices { got: n, min: 3 });
    }
    let (a, b) = (point_at(points, f1), point_at(points, f2));
    let scale = points.iter().map(|p| p.coords.norm()).fold(0.0, f64::max).max(1.0);
    if (b.xy() - a.xy()).norm() <= 1e-9 * scale {
        return Err(Error::InvalidArgument(format!("fold ({f1}, {f2}): the two fold points coincide")));
    }
    let to_angle = |f: f64| 2.0 * PI * f / n as f64;
    let arc = folded_vertices(n, [to_angle(f1), to_angle(f2)]);
    if arc.is_empty() {
        return Err(Error::InvalidArgument(format!("fold ({f1}, {f2}): no vertex on the folded arc")));
    }
    let sides: Vec<f64> = arc.iter().map(|&v| side_of(&a, &b, &points[v])).collect();
    let tolerance = 1e-9 * scale * scale;
    if !(sides.iter().all(|&s| s > tolerance) || sides.iter().all(|&s| s < -tolerance)) {
        return Err(Error::InvalidArgument(format!("fold ({f1}, {f2}): the folded arc is not on one side of the fold line")));
    }
    let top = points.iter().map(|p| p.z).fold(f64::NEG_INFINITY, f64::max);
    let flat = points.iter().all(|p| p.z == top);
    if flat && !chord_inside(points, &a, &b, tolerance) {
        return Err(Error::InvalidArgument(format!("fold ({f1}, {f2}): the fold line leaves the cloth")));
    }
    let mut out = points.to_vec();
    for v in arc {
        let r = reflect_xy(&points[v], &a, &b);
        out[v] = Point::new(r.x, r.y, 2.0 * top + thickness - points[v].z);
    }
    Ok(out)
}

/// A fold endpoint: a fraction along a side of the shape's polygon.
type At = (usize, f64);

/// A named fold: anticlockwise from one endpoint to the other is the folded side.
struct FoldSpec {
    name: &'static str,
    from: At,
    to: At,
}

const fn fs(name: &'static str, from: At, to: At) -> FoldSpec {
    FoldSpec { name, from, to }
}

/// The single folds of each shape.
fn single_folds(kind: Shape) -> Vec<FoldSpec> {
    match kind {
        // Sides: 0 bottom, 1 right, 2 top (right to left), 3 left (top to bottom).
        Shape::Napkin => vec![
            fs("half_vertical", (0, 0.5), (2, 0.5)),
            fs("half_vertical_wrap", (2, 0.5), (0, 0.5)),
            fs("half_horizontal", (1, 0.5), (3, 0.5)),
            fs("half_horizontal_wrap", (3, 0.5), (1, 0.5)),
            fs("diagonal", (0, 0.0), (2, 0.0)),
            fs("diagonal_wrap", (3, 0.0), (1, 0.0)),
            fs("corner", (0, 0.63), (1, 0.37)),
            fs("corner_asym_wrap", (3, 0.6), (0, 0.3)),
            fs("askew", (0, 0.28), (2, 0.36)),
            fs("strip_wrap", (2, 0.75), (0, 0.25)),
            fs("big_part", (0, 0.25), (2, 0.75)),
            fs("thirds", (0, 2.0 / 3.0), (2, 1.0 / 3.0)),
        ],
        Shape::Towel => vec![
            fs("half_short", (0, 0.5), (2, 0.5)),
            fs("half_short_wrap", (2, 0.5), (0, 0.5)),
            fs("half_long", (1, 0.5), (3, 0.5)),
            fs("half_long_wrap", (3, 0.5), (1, 0.5)),
            fs("diagonal", (0, 0.0), (2, 0.0)),
            fs("corner45", (0, 0.75), (1, 0.5)),
            fs("askew", (0, 0.2), (2, 0.4)),
            fs("thirds", (0, 2.0 / 3.0), (2, 1.0 / 3.0)),
            fs("thirds_wrap", (2, 2.0 / 3.0), (0, 1.0 / 3.0)),
            fs("strip_long", (1, 0.7), (3, 0.3)),
            fs("big_part", (3, 0.3), (1, 0.7)),
        ],
        // One side all the way round: t is the fraction of the turn from vertex 0.
        Shape::CircularTowel => vec![
            fs("half", (0, 0.133), (0, 0.633)),
            fs("half_wrap", (0, 0.629), (0, 0.129)),
            fs("cap_small", (0, 0.05), (0, 0.23)),
            fs("cap_wrap", (0, 0.917), (0, 0.098)),
            fs("third_cap", (0, 0.156), (0, 0.49)),
            fs("big_wrap", (0, 0.49), (0, 0.155)),
            fs("askew", (0, 0.316), (0, 0.733)),
        ],
        // Corners: 0 hem mid, 1 hem right, 2 right armpit, 3–4 right sleeve end, 5 right
        // shoulder, 6 neck right, 7 V, 8 neck left, 9 left shoulder, 10–11 left sleeve end,
        // 12 left armpit, 13 hem left.
        Shape::TShirt => vec![
            fs("half_vertical", (7, 0.0), (0, 0.0)),
            fs("half_vertical_right", (0, 0.0), (7, 0.0)),
            fs("bottom_up_wrap", (12, 0.45 / 0.95), (1, 0.5 / 0.95)),
            fs("top_down", (1, 0.5 / 0.95), (12, 0.45 / 0.95)),
            fs("sleeve_left", (9, 0.0), (12, 0.0)),
            fs("sleeve_right", (2, 0.0), (5, 0.0)),
            fs("sleeve_right_partial", (2, 0.5), (4, 0.5)),
            fs("diagonal_wrap", (13, 0.4), (5, 0.0)),
            fs("corner_hem", (0, 0.6), (1, 0.2)),
            fs("corner_hem_left", (12, 0.8), (13, 0.4)),
            fs("askew_wrap", (13, 0.2), (1, 0.7)),
        ],
        // Corners: 0–1 hem, 2 right armpit, 3–4 right strap, 5 neck, 6–7 left strap, 8 left armpit.
        Shape::Top => vec![
            fs("half_vertical", (0, 0.5), (5, 0.0)),
            fs("half_vertical_wrap", (5, 0.0), (0, 0.5)),
            fs("bottom_up_wrap", (8, 0.4 / 0.9), (1, 0.5 / 0.9)),
            fs("top_down", (1, 0.5 / 0.9), (8, 0.4 / 0.9)),
            fs("corner_hem", (0, 0.7), (1, 0.3)),
            fs("strap", (2, 0.5), (4, 0.5)),
            fs("askew", (0, 0.1), (2, 0.2)),
            fs("hem_strip_wrap", (8, 0.7), (1, 0.3)),
        ],
        // Corners: 0 left hem outer, 1 left hem inner, 2 crotch, 3 right hem inner,
        // 4 right hem outer, 5 waist right, 6 waist left.
        Shape::Trousers => vec![
            fs("half_vertical_wrap", (5, 0.5), (2, 0.0)),
            fs("half_vertical_right", (2, 0.0), (5, 0.5)),
            fs("legs_up_wrap", (6, 0.25 / 1.1), (4, 0.85 / 1.1)),
            fs("waist_down", (4, 0.85 / 1.1), (6, 0.25 / 1.1)),
            fs("left_cuff_wrap", (6, 0.85 / 1.1), (1, 0.25 / 0.72)),
            fs("right_cuff", (2, 0.47 / 0.72), (4, 0.25 / 1.1)),
            fs("right_leg_askew", (2, 0.5), (4, 0.4)),
            fs("waist_corner", (4, 0.8), (5, 0.2)),
        ],
        // Corners: 0 hem left, 1 hem right, 2 waist right, 3 waist left.
        Shape::Skirt => vec![
            fs("half_vertical", (0, 0.5), (2, 0.5)),
            fs("half_vertical_wrap", (2, 0.5), (0, 0.5)),
            fs("hem_up_wrap", (3, 0.7), (1, 0.3)),
            fs("waist_down", (1, 0.6), (3, 0.4)),
            fs("corner", (0, 0.8), (1, 0.25)),
            fs("askew", (0, 0.3), (2, 0.3)),
            fs("diagonal", (0, 0.0), (2, 0.0)),
        ],
    }
}

/// A fold of the folded cloth: `first` flat, then `second` on the folded border (its
/// endpoints are points of the original sides, wherever the first fold moved them).
struct SecondFoldSpec {
    shape: Shape,
    name: &'static str,
    first: (At, At),
    second: (At, At),
}

/// The second-fold samples. A fold of a stack needs the two layers' free edges apart where
/// the line crosses them (exact halves put them on top of each other and the fold points
/// would coincide), so "half" first folds here leave a margin.
fn second_folds() -> Vec<SecondFoldSpec> {
    let sf = |shape, name, first, second| SecondFoldSpec { shape, name, first, second };
    vec![
        // Right 45 % over, then the whole stack folded top down / bottom up.
        sf(Shape::Napkin, "half_then_half", ((0, 0.55), (2, 0.45)), ((1, 0.5), (3, 0.5))),
        sf(Shape::Napkin, "half_then_half_wrap", ((0, 0.55), (2, 0.45)), ((3, 0.5), (1, 0.5))),
        // Exact half, then the top layer's corner (right side's top end, now on the left).
        sf(Shape::Napkin, "half_then_corner", ((0, 0.5), (2, 0.5)), ((1, 0.75), (2, 0.25))),
        // Letter fold: right third over, then left third over it.
        sf(Shape::Napkin, "thirds_then_thirds", ((0, 2.0 / 3.0), (2, 1.0 / 3.0)), ((2, 2.0 / 3.0), (0, 1.0 / 3.0))),
        // Diagonal, then the top layer's corner (corner 1, now on corner 3).
        sf(Shape::Napkin, "diagonal_then_corner", ((0, 0.0), (2, 0.0)), ((0, 0.7), (1, 0.3))),
        // Short-axis near-half, then the stack along the long axis.
        sf(Shape::Towel, "half_then_half", ((0, 0.55), (2, 0.45)), ((1, 0.5), (3, 0.5))),
        // Long-axis near-half (top down), then the stack's right half over.
        sf(Shape::Towel, "half_long_then_half", ((1, 0.55), (3, 0.45)), ((0, 0.5), (2, 0.5))),
        // Diagonal, then a second fold across the crease taking its far end.
        sf(Shape::Towel, "diagonal_then_diagonal", ((0, 0.0), (2, 0.0)), ((0, 0.75), (2, 0.5))),
        // Half, then the top layer's sleeve.
        sf(Shape::TShirt, "half_then_sleeve", ((7, 0.0), (0, 0.0)), ((9, 0.0), (12, 0.0))),
        // Legs up over the waist part, then the stack's left half over (waist middle to crotch).
        sf(Shape::Trousers, "legs_up_then_half", ((6, 0.25 / 1.1), (4, 0.85 / 1.1)), ((5, 0.5), (2, 0.0))),
    ]
}

/// A seeded splitmix64 generator (Steele, Lea, Flood 2014): small, fast, reproducible.
struct SplitMix64(u64);

impl SplitMix64 {
    /// Seeded from a name (FNV-1a), so a sample's randomness does not depend on the others.
    fn from_name(name: &str) -> Self {
        SplitMix64(name.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| (h ^ b as u64).wrapping_mul(0x0100_0000_01b3)))
    }

    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Standard normal (Box–Muller).
    fn gaussian(&mut self) -> f64 {
        let u1 = 1.0 - self.uniform();
        let u2 = self.uniform();
        (-2.0 * u1.ln()).sqrt() * (2.0 * PI * u2).cos()
    }
}

/// One sample of the built-in dataset.
#[derive(Debug, Clone, PartialEq)]
pub struct Entry {
    /// Stable identifier (the sample name).
    pub id: String,
    pub sample: Sample,
}

/// How a clean fold sample is varied.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Variant {
    Clean,
    Noisy,
    Rotated,
    Jitter,
    Shifted,
}

impl Variant {
    fn suffix(self) -> &'static str {
        match self {
            Variant::Clean => "",
            Variant::Noisy => "__noisy",
            Variant::Rotated => "__rotated",
            Variant::Jitter => "__jitter",
            Variant::Shifted => "__shifted",
        }
    }
}

/// Which variants a shape's k-th fold gets beyond the clean one: a few of each per shape.
fn variants_of(k: usize) -> &'static [Variant] {
    match k {
        0 => &[Variant::Noisy, Variant::Rotated],
        1 => &[Variant::Noisy, Variant::Jitter],
        2 => &[Variant::Shifted],
        4 => &[Variant::Noisy, Variant::Jitter],
        6 => &[Variant::Rotated, Variant::Shifted],
        _ => &[],
    }
}

fn to_arrays(points: &[Point]) -> Vec<[f64; 3]> {
    points.iter().map(|p| [p.x, p.y, p.z]).collect()
}

/// Vertices whose position changed between two frames.
fn moved(start: &[Point], end: &[Point]) -> Vec<usize> {
    (0..start.len()).filter(|&v| start[v] != end[v]).collect()
}

/// Build a sample from its frames (border parameters of the folds given) and a variant.
fn make_sample(name: String, category: &str, frames: Vec<Vec<Point>>, folds: &[[f64; 2]], variant: Variant) -> Sample {
    let n = frames[0].len();
    let mut rng = SplitMix64::from_name(&name);
    let mut folded = moved(&frames[0], &frames[frames.len() - 1]);
    let mut folds = folds.to_vec();
    let frames = match variant {
        Variant::Clean | Variant::Jitter => frames,
        Variant::Noisy => {
            let mut frames = frames;
            if let Some(end) = frames.last_mut() {
                for p in end.iter_mut() {
                    *p += Vector3::new(rng.gaussian(), rng.gaussian(), rng.gaussian()) * END_NOISE;
                }
            }
            frames
        }
        Variant::Rotated => {
            let rotation = Rotation3::from_axis_angle(&Vector3::z_axis(), 2.0 * PI * rng.uniform());
            let offset = Vector3::new(4.0 * rng.uniform() - 2.0, 4.0 * rng.uniform() - 2.0, 0.0);
            frames.iter().map(|f| f.iter().map(|p| rotation * p + offset).collect()).collect()
        }
        Variant::Shifted => {
            // New vertex i is old vertex (i + shift) mod N: parameters move back by shift.
            let shift = 1 + (rng.next_u64() % (n as u64 - 1)) as usize;
            for f in folds.iter_mut().flatten() {
                *f = (*f - shift as f64).rem_euclid(n as f64);
            }
            for v in folded.iter_mut() {
                *v = (*v + n - shift) % n;
            }
            folded.sort_unstable();
            frames.iter().map(|f| (0..n).map(|i| f[(i + shift) % n]).collect()).collect()
        }
    };
    let angle = |f: f64| 2.0 * PI * f / n as f64;
    Sample {
        name,
        category: category.to_string(),
        frames: frames.iter().map(|f| to_arrays(f)).collect(),
        mesh: None,
        truth: Some(Truth {
            folds: folds.iter().map(|f| [angle(f[0]), angle(f[1])]).collect(),
            folded_vertices: Some(folded),
        }),
    }
}

/// The start border of a variant: the outline, jittered in plane for [`Variant::Jitter`].
fn start_of(outline: &Outline, name: &str, variant: Variant) -> Vec<Point> {
    let mut start = outline.points.clone();
    if variant == Variant::Jitter {
        let mut rng = SplitMix64::from_name(&format!("{name}/start"));
        for p in start.iter_mut() {
            p.x += START_JITTER * rng.gaussian();
            p.y += START_JITTER * rng.gaussian();
        }
    }
    start
}

fn param(outline: &Outline, at: At) -> f64 {
    outline.on_side(at.0, at.1)
}

/// The mesh samples: (shape, fold name) of a grid mesh folded like the border sample of
/// that name. Rectangular shapes only (a grid fills them).
const MESH_FOLDS: [(Shape, &str); 3] = [(Shape::Napkin, "half_vertical"), (Shape::Napkin, "diagonal"), (Shape::Towel, "corner45")];

/// A flat grid mesh and its boundary.
#[derive(Debug, Clone, PartialEq)]
pub struct GridMesh {
    pub vertices: Vec<Point>,
    /// Quads of vertex indices.
    pub faces: Vec<Vec<usize>>,
    /// The boundary vertices in the outline's order: anticlockwise from the bottom-left
    /// corner, as the mesh's border is found.
    pub ring: Vec<usize>,
}

/// A grid mesh of a rectangular shape: (w+1)×(h+1) vertices, id = j·(w+1) + i, quads,
/// with w segments along the bottom and h up the side as the outline has, normalised as the
/// outline is (a grid and its outline share the centre and the farthest vertex). Errors for
/// a shape that is no rectangle.
pub fn grid_mesh(kind: Shape) -> Result<GridMesh> {
    let (o, corners) = (outline(kind), kind.corners());
    let &[[0.0, 0.0], [width, 0.0], [_, height], [0.0, _]] = corners else {
        return Err(Error::InvalidArgument(format!("a grid mesh needs a rectangle, and the {} is not one", kind.name())));
    };
    let (w, h) = (o.side_starts[1] - o.side_starts[0], o.side_starts[2] - o.side_starts[1]);
    let id = |i: usize, j: usize| j * (w + 1) + i;
    let raw = (0..=h).flat_map(|j| (0..=w).map(move |i| Point::new(i as f64 / w as f64 * width, j as f64 / h as f64 * height, 0.0))).collect();
    let faces = (0..h).flat_map(|j| (0..w).map(move |i| vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)])).collect();
    let ring = (0..w)
        .map(|i| id(i, 0))
        .chain((0..h).map(|j| id(w, j)))
        .chain((0..w).map(|i| id(w - i, h)))
        .chain((0..h).map(|j| id(0, h - j)))
        .collect();
    Ok(GridMesh { vertices: normalise(raw), faces, ring })
}

/// Fold a whole mesh as [`fold_border`] folds its boundary `ring`: the line through the
/// boundary points at parameters f1, f2, and every vertex on the folded arc's side of it
/// (interior ones too) reflected and stacked on top.
pub fn fold_mesh(vertices: &[Point], ring: &[usize], f1: f64, f2: f64, thickness: f64) -> Result<Vec<Point>> {
    let boundary: Vec<Point> = ring.iter().map(|&k| vertices[k]).collect();
    // Checks the fold, and tells which side of the line the folded arc lies on.
    let folded = fold_border(&boundary, f1, f2, thickness)?;
    let Some(v) = (0..ring.len()).find(|&v| folded[v] != boundary[v]) else {
        return Err(Error::InvalidArgument(format!("fold ({f1}, {f2}) moves no vertex")));
    };
    let (a, b) = (point_at(&boundary, f1), point_at(&boundary, f2));
    let side = side_of(&a, &b, &boundary[v]).signum();
    let top = vertices.iter().map(|p| p.z).fold(f64::NEG_INFINITY, f64::max);
    let scale = vertices.iter().map(|p| p.coords.norm()).fold(0.0, f64::max).max(1.0);
    let tolerance = 1e-9 * scale * scale;
    Ok(vertices
        .iter()
        .map(|p| {
            if side * side_of(&a, &b, p) > tolerance {
                let r = reflect_xy(p, &a, &b);
                Point::new(r.x, r.y, 2.0 * top + thickness - p.z)
            } else {
                *p
            }
        })
        .collect())
}

/// The mesh samples of [`MESH_FOLDS`], category `mesh`.
fn mesh_samples() -> Result<Vec<Sample>> {
    MESH_FOLDS
        .iter()
        .map(|&(kind, fold)| {
            let name = format!("{}_mesh__{fold}", kind.name());
            let spec = single_folds(kind).into_iter().find(|s| s.name == fold).ok_or_else(|| Error::InvalidArgument(format!("no fold {fold}")))?;
            let o = outline(kind);
            let f = [param(&o, spec.from), param(&o, spec.to)];
            let GridMesh { vertices: flat, faces, ring } = grid_mesh(kind)?;
            let folded = fold_mesh(&flat, &ring, f[0], f[1], THICKNESS).map_err(|e| Error::InvalidArgument(format!("built-in sample {name}: {e}")))?;
            let angle = |x: f64| 2.0 * PI * x / ring.len() as f64;
            Ok(Sample {
                name,
                category: "mesh".into(),
                frames: Vec::new(),
                truth: Some(Truth { folds: vec![[angle(f[0]), angle(f[1])]], folded_vertices: Some(moved(&flat, &folded)) }),
                mesh: Some(MeshFrames::new(faces, vec![to_arrays(&flat), to_arrays(&folded)])),
            })
        })
        .collect()
}

/// Generate the whole dataset (what [`builtin`] caches).
fn generate() -> Result<Vec<Entry>> {
    let mut samples = Vec::new();
    for kind in Shape::ALL {
        let outline = outline(kind);
        for (k, spec) in single_folds(kind).iter().enumerate() {
            let f = [param(&outline, spec.from), param(&outline, spec.to)];
            for &variant in std::iter::once(&Variant::Clean).chain(variants_of(k)) {
                let name = format!("{}__{}{}", kind.name(), spec.name, variant.suffix());
                let start = start_of(&outline, &name, variant);
                let end = fold_border(&start, f[0], f[1], THICKNESS)
                    .map_err(|e| Error::InvalidArgument(format!("built-in sample {name}: {e}")))?;
                samples.push(make_sample(name, kind.name(), vec![start, end], &[f], variant));
            }
        }
    }
    for spec in second_folds() {
        let outline = outline(spec.shape);
        let name = format!("{}__{}", spec.shape.name(), spec.name);
        let f = [param(&outline, spec.first.0), param(&outline, spec.first.1)];
        let g = [param(&outline, spec.second.0), param(&outline, spec.second.1)];
        let fold = |border: &[Point], f: [f64; 2]| {
            fold_border(border, f[0], f[1], THICKNESS).map_err(|e| Error::InvalidArgument(format!("built-in sample {name}: {e}")))
        };
        let start = outline.points.clone();
        let once = fold(&start, f)?;
        let twice = fold(&once, g)?;
        let category = format!("{}_second_fold", spec.shape.name());
        samples.push(make_sample(name, &category, vec![start, once, twice], &[f, g], Variant::Clean));
    }
    samples.extend(mesh_samples()?);
    Ok(samples.into_iter().map(|sample| Entry { id: sample.name.clone(), sample }).collect())
}

/// The built-in dataset, generated once on first use.
pub fn builtin() -> &'static [Entry] {
    static DATASET: OnceLock<Vec<Entry>> = OnceLock::new();
    // The specs are constants checked by the tests: a failure here is a bug in this file.
    DATASET.get_or_init(|| generate().expect("the built-in fold specs are valid"))
}

/// The built-in sample with this id.
pub fn find(id: &str) -> Option<&'static Entry> {
    builtin().iter().find(|e| e.id == id)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::eval::evaluate;
    use crate::fold::reflect::apply_fold;
    use std::collections::HashSet;

    fn is_second_fold(e: &Entry) -> bool {
        e.sample.category.ends_with("_second_fold")
    }

    /// Frames of a border sample or of a mesh sample.
    fn frame_count(e: &Entry) -> usize {
        e.sample.mesh.as_ref().map_or(e.sample.frames.len(), |m| m.frames.len())
    }

    #[test]
    fn generation_is_deterministic_and_ids_unique() {
        let clock = std::time::Instant::now();
        let a = generate().unwrap();
        println!("generated {} samples in {:?}", a.len(), clock.elapsed());
        let b = generate().unwrap();
        assert_eq!(a, b);
        let ids: HashSet<&str> = a.iter().map(|e| e.id.as_str()).collect();
        assert_eq!(ids.len(), a.len());
        assert!(a.iter().all(|e| e.id == e.sample.name));
    }

    #[test]
    fn enough_single_and_second_folds() {
        let data = builtin();
        let singles = data.iter().filter(|e| !is_second_fold(e)).count();
        let seconds = data.iter().filter(|e| is_second_fold(e)).count();
        println!("{singles} single-fold and {seconds} second-fold samples");
        assert!(singles >= 60, "{singles} single-fold samples");
        assert!(seconds >= 8, "{seconds} second-fold samples");
        for e in data {
            let frames = if is_second_fold(e) { 3 } else { 2 };
            assert_eq!(frame_count(e), frames, "{}", e.id);
            assert_eq!(e.sample.truth.as_ref().map(|t| t.folds.len()), Some(frames - 1), "{}", e.id);
        }
        assert_eq!(find("napkin__half_vertical__noisy").map(|e| e.sample.category.as_str()), Some("napkin"));
        assert!(find("no such sample").is_none());
    }

    #[test]
    fn shapes_are_normalised_anticlockwise_with_corners_on_vertices() {
        for kind in Shape::ALL {
            let o = outline(kind);
            assert_eq!(o.points.len(), kind.vertex_count(), "{kind:?}");
            let centroid = o.points.iter().map(|p| p.coords).sum::<Vector3<f64>>() / o.points.len() as f64;
            assert!(centroid.norm() < 1e-12, "{kind:?} centroid {centroid}");
            let radius = o.points.iter().map(|p| p.coords.norm()).fold(0.0, f64::max);
            assert!((radius - 1.0).abs() < 1e-12, "{kind:?} radius {radius}");
            assert!(crate::border::signed_area_xy(&o.points) > 0.0, "{kind:?} is clockwise");
            // Every polygon corner is a vertex: the direction changes exactly at side starts
            // (the T-shirt's side 0 starts at the middle of the straight hem).
            let n = o.points.len();
            let turns: Vec<usize> = (0..n)
                .filter(|&v| side_of(&o.points[(v + n - 1) % n], &o.points[v], &o.points[(v + 1) % n]).abs() > 1e-9)
                .collect();
            let expected: Vec<usize> = match kind {
                Shape::CircularTowel => (0..n).collect(),
                Shape::TShirt => o.side_starts[1..].to_vec(),
                _ => o.side_starts.clone(),
            };
            assert_eq!(turns, expected, "{kind:?}");
        }
        // The reference's vertex layout: 19 segments per napkin side, 24/12/24/12 on the towel.
        assert_eq!(outline(Shape::Napkin).side_starts, vec![0, 19, 38, 57]);
        assert_eq!(outline(Shape::Towel).side_starts, vec![0, 24, 36, 60]);
    }

    #[test]
    fn largest_remainder_rounding_keeps_the_total() {
        assert_eq!(segments_per_side(&[1.0, 1.0, 1.0], 10), vec![4, 3, 3]);
        assert_eq!(segments_per_side(&[2.0, 1.0, 1.0], 9), vec![5, 2, 2]);
        assert_eq!(segments_per_side(&[1.0, 2.9, 0.1], 8), vec![2, 6, 0]);
    }

    #[test]
    fn fold_border_reflects_the_arc_and_rejects_bad_folds() {
        // The error names the problem.
        let reason = |r: Result<Vec<Point>>| match r {
            Err(Error::InvalidArgument(m)) => m,
            other => panic!("expected an invalid fold, got {other:?}"),
        };
        let napkin = shape(Shape::Napkin);
        let folded = fold_border(&napkin, 9.5, 47.5, THICKNESS).unwrap();
        // Vertical half fold: vertex 19 (bottom-right) lands on vertex 0 (bottom-left), on top.
        assert!((folded[19].xy() - napkin[0].xy()).norm() < 1e-12);
        assert_eq!(folded[19].z, THICKNESS);
        assert_eq!(folded[9], napkin[9]);
        assert_eq!(folded[48], napkin[48]);
        // After an exact half, a bottom-up fold of the stack has coinciding fold points.
        assert!(reason(fold_border(&folded, 66.5, 28.5, THICKNESS)).contains("coincide"));
        // With a margin it works, and turns the stack over: the lower layer lands on top.
        let folded = fold_border(&napkin, 10.45, 46.55, THICKNESS).unwrap();
        let twice = fold_border(&folded, 66.5, 28.5, THICKNESS).unwrap();
        assert!((twice[0].z - 3.0 * THICKNESS).abs() < 1e-15);
        assert!((twice[19].z - 2.0 * THICKNESS).abs() < 1e-15);
        assert!(reason(fold_border(&napkin, f64::NAN, 3.0, THICKNESS)).contains("not finite"));
        assert!(reason(fold_border(&napkin, 5.0, 5.5, THICKNESS)).contains("no vertex"));
        // Trousers: from the left hem to the right outseam the arc passes the crotch (above
        // the line) and the right hem (below it).
        let trousers = outline(Shape::Trousers);
        let (a, b) = (trousers.on_side(0, 0.5), trousers.on_side(4, 0.5));
        assert!(reason(fold_border(&trousers.points, a, b, THICKNESS)).contains("one side"));
        // T-shirt: folding the V of the neck down along a line across the neck opening.
        let tshirt = outline(Shape::TShirt);
        let (a, b) = (tshirt.on_side(6, 0.5), tshirt.on_side(7, 0.5));
        assert!(reason(fold_border(&tshirt.points, a, b, THICKNESS)).contains("leaves the cloth"));
    }

    #[test]
    fn truth_folds_reproduce_the_end_frames() {
        for e in builtin() {
            let truth = e.sample.truth.as_ref().unwrap();
            // The border as the analysis sees it (a mesh's boundary, in border order).
            let b = e.sample.border_frames().unwrap();
            let start = &b.frames[0];
            let predicted = truth.folds.iter().fold(start.clone(), |b, &f| apply_fold(&b, f));
            let end = b.frames.last().unwrap();
            let worst = predicted.iter().zip(end).map(|(p, q)| (p.xy() - q.xy()).norm()).fold(0.0, f64::max);
            let tolerance = if e.id.ends_with("__noisy") { 6.0 * END_NOISE } else { 1e-9 };
            assert!(worst < tolerance, "{}: worst XY error {worst}", e.id);
            // The truth lists input vertices: of a mesh, interior ones too.
            let mut moved: Vec<usize> = (0..start.len()).filter(|&v| (predicted[v] - start[v]).norm() > 0.0).map(|v| b.border_indices[v]).collect();
            moved.sort_unstable();
            let on_border: HashSet<usize> = b.border_indices.iter().copied().collect();
            let listed: Vec<usize> = truth.folded_vertices.iter().flatten().copied().filter(|v| on_border.contains(v)).collect();
            assert_eq!(listed, moved, "{}", e.id);
        }
    }

    #[test]
    fn every_sample_prepares_without_repair() {
        for e in builtin() {
            let b = e.sample.border_frames().unwrap_or_else(|err| panic!("{}: {err}", e.id));
            assert!(!b.reversed && b.warnings.is_empty(), "{}: {:?}", e.id, b.warnings);
            match &e.sample.mesh {
                Some(_) => assert_eq!(b.source, "mesh boundary loop", "{}", e.id),
                None => assert_eq!(b.len(), e.sample.frames[0].len(), "{}", e.id),
            }
        }
    }

    /// The fold detector over the dataset: printed for tuning, with a sanity floor. Every
    /// sample is analysed here (`evaluate` runs `analyze`), so none may fail.
    #[test]
    fn every_sample_analyses_and_most_clean_ones_get_one_fold() {
        use rayon::prelude::*;
        let results: Vec<_> = builtin().par_iter().map(|e| evaluate(&e.sample)).collect();
        let clean: Vec<_> = results.iter().filter(|r| !r.name.contains("__noisy") && r.expected_folds == 1).collect();
        let one_fold = clean.iter().filter(|r| r.folds == 1).count();
        let report = crate::eval::report(results.clone());
        println!("{}", report.table());
        for r in results.iter().filter(|r| r.folds != r.expected_folds) {
            println!("miss: {} found {} folds, expected {}", r.name, r.folds, r.expected_folds);
        }
        println!("clean single folds with exactly one fold: {one_fold}/{}", clean.len());
        let failures: Vec<String> = results.iter().filter_map(|r| r.error.as_ref().map(|e| format!("{}: {e}", r.name))).collect();
        assert!(failures.is_empty(), "{failures:#?}");
        assert!(one_fold * 10 > clean.len() * 8, "{one_fold} of {} clean samples got one fold", clean.len());
    }

    #[test]
    fn mesh_samples_have_the_border_of_their_border_twins() {
        let meshes: Vec<&Entry> = builtin().iter().filter(|e| e.sample.mesh.is_some()).collect();
        assert_eq!(meshes.len(), MESH_FOLDS.len());
        for e in meshes {
            let twin = find(&e.id.replace("_mesh__", "__")).unwrap_or_else(|| panic!("{}: no border twin", e.id));
            let (mesh, border) = (e.sample.border_frames().unwrap(), twin.sample.border_frames().unwrap());
            assert_eq!(mesh.len(), border.len(), "{}", e.id);
            for (m, b) in mesh.frames.iter().zip(&border.frames) {
                let worst = m.iter().zip(b).map(|(p, q)| (p - q).norm()).fold(0.0, f64::max);
                assert!(worst < 1e-12, "{}: frames differ by {worst}", e.id);
            }
            assert_eq!(e.sample.truth.as_ref().map(|t| &t.folds), twin.sample.truth.as_ref().map(|t| &t.folds));
            // Interior vertices fold too: more moved than the border's share.
            let moved = e.sample.truth.as_ref().and_then(|t| t.folded_vertices.as_ref()).map_or(0, Vec::len);
            let moved_on_border = twin.sample.truth.as_ref().and_then(|t| t.folded_vertices.as_ref()).map_or(0, Vec::len);
            assert!(moved > moved_on_border, "{}: {moved} mesh vertices moved", e.id);
        }
        assert!(grid_mesh(Shape::Skirt).is_err());
    }

    #[test]
    fn splitmix64_matches_the_published_sequence() {
        // First outputs for seed 0 (reference implementation by Vigna).
        let mut rng = SplitMix64(0);
        assert_eq!(rng.next_u64(), 0xe220_a839_7b1d_cdaf);
        assert_eq!(rng.next_u64(), 0x6e78_9e6a_a1b9_65f4);
    }
}
