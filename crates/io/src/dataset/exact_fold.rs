//! The synthetic folding: an exact fold of a flat or folded border, the ground truth of
//! the built-in dataset.
//!
//! This is the fold that Kamat, Borràs, Torras, "CloSE: A Geometric Shape-Agnostic Cloth
//! State Representation" predict from the fold coordinates (f1, f2): the part of the border
//! on the anticlockwise arc from f1 to f2 turns over the line through the border points at
//! f1 and f2. It is written here on its own, not with the predictor's `close_core::fold` nor the
//! primitives it uses (`border::point_at`, `angle::vertices_in_arc`), so that a fault in
//! one is not copied into the other and cancelled in the evaluation.
//!
//! **Mirror.** With P1, P2 the border points at parameters f1, f2 (fractional vertex
//! indices, [`border_point`]) and n̂ the unit XY normal left of P1→P2, a point's signed
//! distance to the line is s(p) = (p − P1)·n̂, and its mirror image is p − 2 s(p) n̂ in XY,
//! z kept. It is an involution: s changes sign and the mirror of the mirror is p.
//!
//! **Fold.** The vertices strictly inside the arc ([`arc_vertices`]) are mirrored. A
//! fold is made only when that arc lies strictly on one side of the line and, on a flat
//! border, the chord P1P2 lies inside the cloth. The folded stack turns over, so a vertex
//! at height z lands at 2·top + thickness − z, top being the highest vertex before the
//! fold: on a flat cloth that is z = thickness, and a second fold puts the flipped layers
//! above everything.
//!
//! ```
//! use close_io::dataset::shapes::{shape, Shape};
//! use close_io::dataset::exact_fold::fold_border;
//! let napkin = shape(Shape::Napkin);
//! // Fold the square along its diagonal from corner 0 to corner 38: corner 19 lands on 57.
//! let folded = fold_border(&napkin, 0.0, 38.0, 0.01).unwrap();
//! assert!((folded[19].xy() - napkin[57].xy()).norm() < 1e-12);
//! assert_eq!(folded[19].z, 0.01);
//! ```

use nalgebra::Vector2;

use close_core::border::Point;
use close_core::error::{Error, FoldProblem, Result};

/// Relative size under which two fold points are one point, and a vertex is on the line.
pub(super) const EPS: f64 = 1e-9;

/// The size that [`EPS`] is relative to: the farthest point from the origin, at least 1.
pub(super) fn scale_of(points: &[Point]) -> f64 {
    points.iter().map(|p| p.coords.norm()).fold(1.0, f64::max)
}

/// Border parameters closer than this (in vertex indices) to a fold point are on the fold
/// line, not inside the arc.
const ON_LINE: f64 = 1e-9;

/// `x` modulo `m` into [0, m), by a floor rather than `rem_euclid`: the generator's own.
fn modulo(x: f64, m: f64) -> f64 {
    let r = x - m * (x / m).floor();
    if r >= m {
        0.0
    } else {
        r
    }
}

/// The point at border parameter `s` (a fractional vertex index, any real, taken modulo
/// N): the fraction s − ⌊s⌋ of the way along the straight edge from vertex ⌊s⌋ to the next.
pub fn border_point(points: &[Point], s: f64) -> Point {
    let n = points.len();
    let s = modulo(s, n as f64);
    let k = (s.floor() as usize).min(n - 1);
    let t = s - k as f64;
    let (a, b) = (points[k].coords, points[(k + 1) % n].coords);
    Point::from(a * (1.0 - t) + b * t)
}

/// The vertices strictly inside the anticlockwise arc from border parameter `s1` to `s2`
/// of an `n`-vertex border, in walking order: vertex v is inside when its anticlockwise
/// offset (v − s1) mod n lies in (ε, span − ε), span = (s2 − s1) mod n, ε = `ON_LINE`.
pub fn arc_vertices(n: usize, s1: f64, s2: f64) -> Vec<usize> {
    let nf = n as f64;
    let span = modulo(s2 - s1, nf);
    let mut inside: Vec<(f64, usize)> = (0..n)
        .map(|v| (modulo(v as f64 - s1, nf), v))
        .filter(|&(offset, _)| offset > ON_LINE && offset < span - ON_LINE)
        .collect();
    inside.sort_by(|a, b| a.0.total_cmp(&b.0));
    inside.into_iter().map(|(_, v)| v).collect()
}

/// The XY line through two points, as a point and its unit left normal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mirror {
    origin: Vector2<f64>,
    normal: Vector2<f64>,
}

impl Mirror {
    /// The line through `a` and `b` in XY; `None` when they coincide there.
    pub fn through(a: &Point, b: &Point) -> Option<Mirror> {
        let d = b.xy() - a.xy();
        let length = d.norm();
        let scale = scale_of(&[*a, *b]);
        (length > EPS * scale)
            .then(|| Mirror { origin: a.xy().coords, normal: Vector2::new(-d.y, d.x) / length })
    }

    /// Signed XY distance of `p` from the line, positive on its left.
    pub fn side(&self, p: &Point) -> f64 {
        (p.xy().coords - self.origin).dot(&self.normal)
    }

    /// The mirror image of `p` across the line in XY; z kept.
    pub fn reflect(&self, p: &Point) -> Point {
        let xy = p.xy().coords - 2.0 * self.side(p) * self.normal;
        Point::new(xy.x, xy.y, p.z)
    }
}

/// 2D cross product of (b − a) and (p − a): positive when p is left of a→b.
fn cross(a: &Point, b: &Point, p: &Point) -> f64 {
    (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)
}

/// Even-odd test of `p` against the XY polygon `points`.
fn inside_xy(points: &[Point], p: &Point) -> bool {
    let n = points.len();
    (0..n).fold(false, |inside, k| {
        let (a, b) = (points[k], points[(k + 1) % n]);
        let crosses =
            (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
        inside != crosses
    })
}

/// Whether the chord from `a` to `b` lies inside the (flat) cloth: it crosses no border
/// edge properly, and points along it are inside the polygon. The chord's ends lie on
/// edges themselves; `tolerance` keeps those touches from counting as crossings.
fn chord_inside(points: &[Point], a: &Point, b: &Point, tolerance: f64) -> bool {
    let n = points.len();
    let opposite =
        |x: f64, y: f64| (x > tolerance && y < -tolerance) || (x < -tolerance && y > tolerance);
    let crosses_an_edge = (0..n).any(|k| {
        let (c, d) = (points[k], points[(k + 1) % n]);
        opposite(cross(a, b, &c), cross(a, b, &d)) && opposite(cross(&c, &d, a), cross(&c, &d, b))
    });
    const SAMPLES: usize = 64;
    !crosses_an_edge
        && (1..SAMPLES).all(|j| inside_xy(points, &(a + (b - a) * (j as f64 / SAMPLES as f64))))
}

/// A checked fold of a border: its mirror line, the side of it that folds (+1 left, −1
/// right), the vertices on the folded arc and the thickness a folded layer gains.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Fold {
    pub mirror: Mirror,
    pub side: f64,
    pub arc: Vec<usize>,
    pub thickness: f64,
}

impl Fold {
    /// Check the fold of `points` along border parameters `f1`, `f2` (see the module doc).
    ///
    /// Errors when a parameter or the thickness is not finite, the fold points coincide, no
    /// vertex lies on the arc, the arc crosses the fold line, or (flat border) the chord
    /// leaves the cloth.
    pub(super) fn of(points: &[Point], f1: f64, f2: f64, thickness: f64) -> Result<Fold> {
        let fail = |problem| Error::InvalidFold { f1, f2, problem };
        let n = points.len();
        if !(f1.is_finite() && f2.is_finite() && thickness.is_finite()) {
            return Err(fail(FoldProblem::NotFinite));
        }
        if n < 3 {
            return Err(fail(FoldProblem::TooFewVertices));
        }
        let (a, b) = (border_point(points, f1), border_point(points, f2));
        let mirror = Mirror::through(&a, &b).ok_or(fail(FoldProblem::PointsCoincide))?;
        let arc = arc_vertices(n, f1, f2);
        let scale = scale_of(points);
        let sides: Vec<f64> = arc.iter().map(|&v| mirror.side(&points[v])).collect();
        let side = match sides.first() {
            None => return Err(fail(FoldProblem::EmptyArc)),
            Some(s) => s.signum(),
        };
        if !sides.iter().all(|&s| s * side > EPS * scale) {
            return Err(fail(FoldProblem::ArcCrossesLine));
        }
        let flat = points.iter().all(|p| p.z == points[0].z);
        if flat && !chord_inside(points, &a, &b, EPS * scale * scale) {
            return Err(fail(FoldProblem::LeavesCloth));
        }
        Ok(Fold { mirror, side, arc, thickness })
    }

    /// `p` turned over onto a stack whose highest point is at `top`: mirrored, and its
    /// height z taken to 2·top + thickness − z.
    pub(super) fn turn_over(&self, p: &Point, top: f64) -> Point {
        let r = self.mirror.reflect(p);
        Point::new(r.x, r.y, 2.0 * top + self.thickness - p.z)
    }
}

/// The highest z of `points`.
pub(super) fn top(points: &[Point]) -> f64 {
    points.iter().map(|p| p.z).fold(f64::NEG_INFINITY, f64::max)
}

/// Fold a border along border parameters `f1`, `f2` (see the module doc): the arc's
/// vertices mirrored and stacked `thickness` above the cloth.
pub fn fold_border(points: &[Point], f1: f64, f2: f64, thickness: f64) -> Result<Vec<Point>> {
    let fold = Fold::of(points, f1, f2, thickness)?;
    let top = top(points);
    let mut out = points.to_vec();
    for &v in &fold.arc {
        out[v] = fold.turn_over(&points[v], top);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dataset::shapes::{outline, shape, Shape};
    use close_core::rng::SplitMix64;

    const THICKNESS: f64 = 0.01;

    fn problem(r: Result<Vec<Point>>) -> FoldProblem {
        match r {
            Err(Error::InvalidFold { problem, .. }) => problem,
            other => panic!("expected an invalid fold, got {other:?}"),
        }
    }

    #[test]
    fn the_mirror_is_an_involution_that_keeps_z() {
        let mut rng = SplitMix64::new(11);
        for _ in 0..100 {
            let mut point =
                || Point::new(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0), rng.range(-1.0, 1.0));
            let (a, b, p) = (point(), point(), point());
            let m = Mirror::through(&a, &b).unwrap();
            let r = m.reflect(&p);
            assert_eq!(r.z, p.z);
            assert!((m.reflect(&r) - p).norm() < 1e-12);
            assert!((m.side(&r) + m.side(&p)).abs() < 1e-12);
            // The line's own points stay, and distances to them are kept.
            assert!((m.reflect(&a).xy() - a.xy()).norm() < 1e-12);
            assert!(((r.xy() - b.xy()).norm() - (p.xy() - b.xy()).norm()).abs() < 1e-12);
        }
        let p = Point::new(1.0, 2.0, 0.0);
        assert!(Mirror::through(&p, &Point::new(1.0, 2.0, 5.0)).is_none());
        // The x axis mirrors (3, 2) to (3, −2); its left is +y.
        let x_axis = Mirror::through(&Point::origin(), &Point::new(1.0, 0.0, 0.0)).unwrap();
        assert_eq!(x_axis.reflect(&Point::new(3.0, 2.0, 0.5)), Point::new(3.0, -2.0, 0.5));
        assert_eq!(x_axis.side(&Point::new(3.0, 2.0, 0.5)), 2.0);
    }

    #[test]
    fn fold_border_mirrors_the_arc_and_stacks_it() {
        let napkin = shape(Shape::Napkin);
        let folded = fold_border(&napkin, 9.5, 47.5, THICKNESS).unwrap();
        // Vertical half fold: vertex 19 (bottom-right) lands on vertex 0 (bottom-left), on top.
        assert!((folded[19].xy() - napkin[0].xy()).norm() < 1e-12);
        assert_eq!(folded[19].z, THICKNESS);
        assert_eq!(folded[9], napkin[9]);
        assert_eq!(folded[48], napkin[48]);
        assert_eq!((0..76).filter(|&v| folded[v] != napkin[v]).count(), 38);
        // A second fold with a margin turns the stack over: the lower layer lands on top.
        let folded = fold_border(&napkin, 10.45, 46.55, THICKNESS).unwrap();
        let twice = fold_border(&folded, 66.5, 28.5, THICKNESS).unwrap();
        assert!((twice[0].z - 3.0 * THICKNESS).abs() < 1e-15);
        assert!((twice[19].z - 2.0 * THICKNESS).abs() < 1e-15);
    }

    #[test]
    fn bad_folds_name_their_problem() {
        let napkin = shape(Shape::Napkin);
        // After an exact half, a bottom-up fold of the stack has coinciding fold points.
        let half = fold_border(&napkin, 9.5, 47.5, THICKNESS).unwrap();
        assert_eq!(problem(fold_border(&half, 66.5, 28.5, THICKNESS)), FoldProblem::PointsCoincide);
        assert_eq!(problem(fold_border(&napkin, f64::NAN, 3.0, THICKNESS)), FoldProblem::NotFinite);
        assert_eq!(problem(fold_border(&napkin, 1.0, 3.0, f64::INFINITY)), FoldProblem::NotFinite);
        assert_eq!(problem(fold_border(&napkin, 5.0, 5.5, THICKNESS)), FoldProblem::EmptyArc);
        assert_eq!(
            problem(fold_border(&napkin[..2], 0.0, 1.0, THICKNESS)),
            FoldProblem::TooFewVertices
        );
        // Trousers: from the left hem to the right outseam the arc passes the crotch (above
        // the line) and the right hem (below it).
        let trousers = outline(Shape::Trousers);
        let (a, b) = (trousers.on_side(0, 0.5), trousers.on_side(4, 0.5));
        assert_eq!(
            problem(fold_border(&trousers.points, a, b, THICKNESS)),
            FoldProblem::ArcCrossesLine
        );
        // T-shirt: folding the V of the neck down along a line across the neck opening.
        let tshirt = outline(Shape::TShirt);
        let (a, b) = (tshirt.on_side(6, 0.5), tshirt.on_side(7, 0.5));
        assert_eq!(problem(fold_border(&tshirt.points, a, b, THICKNESS)), FoldProblem::LeavesCloth);
    }

    #[test]
    fn border_points_and_arcs_of_the_generator() {
        let square = [
            Point::new(0.0, 0.0, 0.0),
            Point::new(1.0, 0.0, 0.0),
            Point::new(1.0, 1.0, 0.0),
            Point::new(0.0, 1.0, 0.0),
        ];
        assert_eq!(border_point(&square, 0.25), Point::new(0.25, 0.0, 0.0));
        assert_eq!(border_point(&square, 3.5), Point::new(0.0, 0.5, 0.0));
        assert_eq!(border_point(&square, -0.5), Point::new(0.0, 0.5, 0.0));
        assert_eq!(border_point(&square, 6.0), square[2]);
        // Open arcs: through vertex 0, and endpoints on vertices left out.
        assert_eq!(arc_vertices(8, 6.5, 1.5), vec![7, 0, 1]);
        assert_eq!(arc_vertices(8, 2.0, 5.0), vec![3, 4]);
        assert_eq!(arc_vertices(8, 2.0, 2.0), Vec::<usize>::new());
        assert_eq!(arc_vertices(8, 5.0, 2.0 + 1e-12), vec![6, 7, 0, 1]);
        // The two arcs between two points split the vertices off the line between them.
        let mut rng = SplitMix64::new(5);
        for _ in 0..200 {
            let (s1, s2) = (rng.range(-8.0, 16.0), rng.range(-8.0, 16.0));
            let (one, other) = (arc_vertices(8, s1, s2), arc_vertices(8, s2, s1));
            let on_line = (0..8)
                .filter(|&v| {
                    [s1, s2].iter().any(|s| {
                        modulo(v as f64 - s, 8.0).min(8.0 - modulo(v as f64 - s, 8.0)) <= ON_LINE
                    })
                })
                .count();
            assert_eq!(one.len() + other.len() + on_line, 8, "{s1} {s2}");
            assert!(one.iter().all(|v| !other.contains(v)));
        }
    }

    #[test]
    fn chords_and_insides() {
        let square = [
            Point::new(0.0, 0.0, 0.0),
            Point::new(1.0, 0.0, 0.0),
            Point::new(1.0, 1.0, 0.0),
            Point::new(0.0, 1.0, 0.0),
        ];
        assert!(inside_xy(&square, &Point::new(0.5, 0.5, 0.0)));
        assert!(!inside_xy(&square, &Point::new(1.5, 0.5, 0.0)));
        assert!(chord_inside(
            &square,
            &Point::new(0.0, 0.5, 0.0),
            &Point::new(1.0, 0.5, 0.0),
            1e-12
        ));
        // An L: the chord between the two arm tips cuts across the notch.
        let l = [(0.0, 0.0), (2.0, 0.0), (2.0, 1.0), (1.0, 1.0), (1.0, 2.0), (0.0, 2.0)]
            .map(|(x, y)| Point::new(x, y, 0.0));
        assert!(!chord_inside(&l, &Point::new(2.0, 0.5, 0.0), &Point::new(0.5, 2.0, 0.0), 1e-12));
        assert_eq!(cross(&square[0], &square[1], &square[3]), 1.0);
    }
}
