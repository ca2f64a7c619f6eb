//! The cloth border: a closed polyline listed anticlockwise seen from +z.
//!
//! Convention (SPEC §1): vertices P_0 … P_{N−1}, edge k joins P_k and P_{k+1 mod N}, and a
//! border parameter `s` (fractional vertex index) sits at angle 2πs/N. Preparing a sample
//! validates every frame, closes and merges duplicates, and orients the border
//! anticlockwise by the sign of the start frame's XY area (shoelace formula).
//!
//! ```
//! use close::border::prepare;
//! // A unit square listed clockwise is reversed, keeping vertex 0 first.
//! let cw = vec![vec![[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0], [1.0, 0.0, 0.0]]];
//! let b = prepare(cw).unwrap();
//! assert!(b.reversed);
//! assert_eq!(b.border_indices, vec![0, 3, 2, 1]);
//! ```

use nalgebra::{Point3, Vector3};

use crate::error::{Error, Result};

/// A 3D point of a border.
pub type Point = Point3<f64>;

/// Fewest vertices a border may have.
pub const MIN_VERTICES: usize = 4;
/// Most vertices a border may have (a dGLI disk holds N(N−1)/2 cells).
pub const MAX_VERTICES: usize = 5_000;
/// A border whose farthest vertex is this close to distance 1 counts as unit-sized.
pub const UNIT_RADIUS_TOLERANCE: f64 = 1e-4;
/// Most frames a sample may have.
pub const MAX_FRAMES: usize = 1_000;

/// A point as the `[x, y, z]` array that JSON and the file formats use.
pub fn to_xyz(p: &Point) -> [f64; 3] {
    [p.x, p.y, p.z]
}

/// The point of an `[x, y, z]` array.
pub fn from_xyz(p: &[f64; 3]) -> Point {
    Point::new(p[0], p[1], p[2])
}

/// Point at border parameter `s` (fractional vertex index, taken cyclically): the point
/// `P_⌊s⌋ + frac(s)·(P_⌊s⌋+1 − P_⌊s⌋)`.
pub fn point_at(points: &[Point], s: f64) -> Point {
    let n = points.len();
    let s = s.rem_euclid(n as f64);
    let k = (s.floor() as usize).min(n - 1);
    let t = s - k as f64;
    let a = points[k];
    let b = points[(k + 1) % n];
    a + (b - a) * t
}

/// Signed area of the XY projection (positive when anticlockwise seen from +z).
pub fn signed_area_xy(points: &[Point]) -> f64 {
    let n = points.len();
    (0..n)
        .map(|k| {
            let (a, b) = (points[k], points[(k + 1) % n]);
            a.x * b.y - b.x * a.y
        })
        .sum::<f64>()
        / 2.0
}

/// The similarity that maps a border to the SPEC's normal form: centroid (vertex mean) to
/// the origin, farthest vertex at distance 1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Normalisation {
    pub centroid: Vector3<f64>,
    /// Distance of the farthest vertex from the centroid before scaling.
    pub radius: f64,
}

impl Normalisation {
    /// The normalisation of `points`; errors when every vertex coincides.
    pub fn of(points: &[Point]) -> Result<Self> {
        if points.is_empty() {
            return Err(Error::Empty("border with no vertex".into()));
        }
        let centroid = points.iter().map(|p| p.coords).sum::<Vector3<f64>>() / points.len() as f64;
        let radius = points.iter().map(|p| (p.coords - centroid).norm()).fold(0.0, f64::max);
        if !(radius > 0.0 && radius.is_finite()) {
            return Err(Error::Degenerate("all vertices coincide".into()));
        }
        // A border already at unit size (to 1e-4) is not rescaled: dGLI scales with 1/size,
        // and a rescale by 1 ± 1e-5 would move every value by that much for nothing.
        let radius = if (radius - 1.0).abs() < UNIT_RADIUS_TOLERANCE { 1.0 } else { radius };
        Ok(Normalisation { centroid, radius })
    }

    pub fn apply(&self, p: &Point) -> Point {
        Point::from((p.coords - self.centroid) / self.radius)
    }

    pub fn apply_all(&self, points: &[Point]) -> Vec<Point> {
        points.iter().map(|p| self.apply(p)).collect()
    }
}

/// A validated sample: every frame anticlockwise (by the start frame), same vertex count.
#[derive(Debug, Clone, PartialEq)]
pub struct BorderFrames {
    /// Frames of border vertices, in border order.
    pub frames: Vec<Vec<Point>>,
    /// For each border vertex, its index in the input frames.
    pub border_indices: Vec<usize>,
    /// True when the input was clockwise and was reversed.
    pub reversed: bool,
    /// What was repaired on the way (closing vertex dropped, duplicates merged).
    pub warnings: Vec<String>,
    /// Where the border came from: "border" (given as such) or how a mesh gave it.
    pub source: String,
}

impl BorderFrames {
    pub fn len(&self) -> usize {
        self.border_indices.len()
    }

    pub fn is_empty(&self) -> bool {
        self.border_indices.is_empty()
    }
}

/// Validate raw frames of border positions and bring them to the SPEC's conventions.
///
/// Errors on: no frame, an empty frame, frames of different sizes, non-finite numbers,
/// fewer than [`MIN_VERTICES`] distinct vertices, more than [`MAX_VERTICES`], a start
/// frame whose XY projection has no area. Repairs, with a warning: a closing vertex equal to
/// vertex 0 is dropped; consecutive duplicate vertices of the start frame are merged.
pub fn prepare(raw: Vec<Vec<[f64; 3]>>) -> Result<BorderFrames> {
    let Some(first) = raw.first() else {
        return Err(Error::Empty("the sample has no frame".into()));
    };
    let n_in = first.len();
    if n_in == 0 {
        return Err(Error::Empty("frame 0 has no vertex".into()));
    }
    if raw.len() > MAX_FRAMES {
        return Err(Error::TooLarge(format!("{} frames (at most {MAX_FRAMES})", raw.len())));
    }
    if n_in > MAX_VERTICES + 1 {
        return Err(Error::TooLarge(format!("{n_in} vertices (at most {MAX_VERTICES})")));
    }
    for (f, frame) in raw.iter().enumerate() {
        if frame.len() != n_in {
            return Err(Error::FrameSizeMismatch { frame: f, expected: n_in, got: frame.len() });
        }
        if let Some(v) = frame.iter().position(|p| p.iter().any(|c| !c.is_finite())) {
            return Err(Error::NonFinite { frame: f, vertex: v });
        }
    }
    let start: Vec<Point> = first.iter().map(|p| Point::new(p[0], p[1], p[2])).collect();
    let extent = Normalisation::of(&start)?.radius;
    let same = |a: &Point, b: &Point| (a - b).norm() <= 1e-12 * extent;

    let mut warnings = Vec::new();
    let mut keep: Vec<usize> = (0..n_in).collect();
    if n_in > 1 && same(&start[0], &start[n_in - 1]) {
        keep.pop();
        warnings.push("the last vertex repeats vertex 0: the border was closed already".into());
    }
    let mut merged = Vec::new();
    let mut kept: Vec<usize> = Vec::with_capacity(keep.len());
    for &k in &keep {
        match kept.last() {
            Some(&prev) if same(&start[prev], &start[k]) => merged.push(k),
            _ => kept.push(k),
        }
    }
    if !merged.is_empty() {
        warnings.push(format!("merged {} duplicate consecutive vertices (input indices {:?})", merged.len(), merged));
    }
    if kept.len() < MIN_VERTICES {
        return Err(Error::TooFewVertices { got: kept.len(), min: MIN_VERTICES });
    }
    if kept.len() > MAX_VERTICES {
        return Err(Error::TooLarge(format!("{} vertices (at most {MAX_VERTICES})", kept.len())));
    }

    let start_kept: Vec<Point> = kept.iter().map(|&k| start[k]).collect();
    let area = signed_area_xy(&start_kept);
    if area.abs() <= 1e-9 * extent * extent {
        return Err(Error::Degenerate(
            "the start frame has no area seen from +z (collinear or vertical border)".into(),
        ));
    }
    let reversed = area < 0.0;
    if reversed {
        // Walk the other way round, keeping vertex 0 first.
        kept[1..].reverse();
    }
    let frames = raw
        .iter()
        .map(|frame| kept.iter().map(|&k| Point::new(frame[k][0], frame[k][1], frame[k][2])).collect())
        .collect();
    Ok(BorderFrames { frames, border_indices: kept, reversed, warnings, source: "border".into() })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Vec<[f64; 3]> {
        vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]]
    }

    #[test]
    fn anticlockwise_square_is_kept() {
        let b = prepare(vec![square()]).unwrap();
        assert!(!b.reversed);
        assert_eq!(b.border_indices, vec![0, 1, 2, 3]);
        assert!(b.warnings.is_empty());
    }

    #[test]
    fn closing_vertex_and_duplicates_are_merged() {
        let mut s = square();
        s.insert(2, s[1]);
        s.push(s[0]);
        let b = prepare(vec![s]).unwrap();
        assert_eq!(b.border_indices, vec![0, 1, 3, 4]);
        assert_eq!(b.warnings.len(), 2);
    }

    #[test]
    fn bad_inputs_name_the_problem() {
        assert_eq!(prepare(vec![]).unwrap_err(), Error::Empty("the sample has no frame".into()));
        assert!(matches!(prepare(vec![vec![]]), Err(Error::Empty(_))));
        assert_eq!(prepare(vec![square()[..3].to_vec()]).unwrap_err(), Error::TooFewVertices { got: 3, min: 4 });
        let mut nan = square();
        nan[2][1] = f64::NAN;
        assert_eq!(prepare(vec![square(), nan]).unwrap_err(), Error::NonFinite { frame: 1, vertex: 2 });
        assert_eq!(
            prepare(vec![square(), square()[..3].to_vec()]).unwrap_err(),
            Error::FrameSizeMismatch { frame: 1, expected: 4, got: 3 }
        );
        let line: Vec<[f64; 3]> = (0..6).map(|k| [k as f64, 2.0 * k as f64, 0.0]).collect();
        assert!(matches!(prepare(vec![line]), Err(Error::Degenerate(_))));
        assert!(matches!(prepare(vec![vec![[1.0, 1.0, 1.0]; 8]]), Err(Error::Degenerate(_))));
        let huge = vec![vec![[0.0; 3]; MAX_VERTICES + 10]];
        assert!(matches!(prepare(huge), Err(Error::TooLarge(_))));
    }

    #[test]
    fn point_at_interpolates_cyclically() {
        let pts: Vec<Point> = square().iter().map(|p| Point::new(p[0], p[1], p[2])).collect();
        assert_eq!(point_at(&pts, 0.5), Point::new(0.5, 0.0, 0.0));
        assert_eq!(point_at(&pts, 3.5), Point::new(0.0, 0.5, 0.0));
        assert_eq!(point_at(&pts, -0.5), Point::new(0.0, 0.5, 0.0));
    }

    #[test]
    fn normalisation_puts_farthest_vertex_on_unit_circle() {
        let pts: Vec<Point> = square().iter().map(|p| Point::new(3.0 * p[0] + 5.0, 3.0 * p[1], p[2])).collect();
        let t = Normalisation::of(&pts).unwrap();
        let max = t.apply_all(&pts).iter().map(|p| p.coords.norm()).fold(0.0, f64::max);
        assert!((max - 1.0).abs() < 1e-12);
    }
}
