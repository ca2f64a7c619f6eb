//! The cloth border: a closed polyline listed anticlockwise seen from +z.
//!
//! Convention (Kamat, Borràs, Torras, "CloSE: A Geometric Shape-Agnostic Cloth State
//! Representation", the border and its dGLI disk): vertices P_0 … P_{N−1}, z the zenithal
//! axis, edge k joins P_k and P_{k+1 mod N}, and a border parameter `s` (fractional vertex
//! index) sits at angle 2πs/N. [`prepare`] validates every frame, closes and merges
//! duplicates, and orients the border anticlockwise by the sign of the start frame's XY
//! area (shoelace formula, A = ½ Σ x_k y_{k+1} − x_{k+1} y_k), all on coordinates
//! normalised by the start frame ([`Normalisation`]).
//!
//! ```
//! use close_core::border::prepare;
//! // A unit square listed clockwise is reversed, keeping vertex 0 first.
//! let cw = vec![vec![[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0], [1.0, 0.0, 0.0]]];
//! let b = prepare(cw).unwrap();
//! assert!(b.reversed);
//! assert_eq!(b.border_indices, vec![0, 3, 2, 1]);
//! ```

use nalgebra::{Point3, Vector3};

use crate::error::{DegenerateReason, Error, Result};

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
/// Farthest a later frame's vertex may lie from the start frame's centroid, in start-frame
/// radii: beyond it the dGLI's lift (1e-5) is lost to rounding in the coordinates.
pub const MAX_NORMALISED_DISTANCE: f64 = 1e6;
/// A later frame whose vertices all lie within this many start-frame radii of their
/// centroid has collapsed to one point.
pub const COLLAPSE_TOLERANCE: f64 = 1e-9;

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

/// The similarity that maps a border to its normal form: centroid (vertex mean) to the
/// origin, farthest vertex at distance 1. The dGLI is a derivative along an absolute lift,
/// so its values scale with 1/size: every disk of a sample is computed on frames normalised
/// by the START frame's transform, and the paper's error metrics are read in these units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Normalisation {
    pub centroid: Vector3<f64>,
    /// Distance of the farthest vertex from the centroid before scaling.
    pub radius: f64,
}

impl Default for Normalisation {
    /// The identity: no shift, no scale.
    fn default() -> Self {
        Normalisation { centroid: Vector3::zeros(), radius: 1.0 }
    }
}

impl Normalisation {
    /// The normalisation of `points`, taken as a start frame (errors name frame 0):
    /// degenerate when every vertex coincides or the coordinates overflow.
    pub fn of(points: &[Point]) -> Result<Self> {
        if points.is_empty() {
            return Err(Error::Empty { what: "border with no vertex" });
        }
        Self::measure(points).map_err(|reason| Error::Degenerate { frame: 0, reason })
    }

    /// Centroid and radius of a non-empty frame, or why there are none.
    fn measure(points: &[Point]) -> Result<Self, DegenerateReason> {
        let centroid = points.iter().map(|p| p.coords).sum::<Vector3<f64>>() / points.len() as f64;
        let radius = points.iter().map(|p| (p.coords - centroid).norm()).fold(0.0, f64::max);
        // Overflow first: an infinite radius is not "no radius".
        if !(centroid.iter().all(|c| c.is_finite()) && radius.is_finite()) {
            return Err(DegenerateReason::TooLargeToNormalise);
        }
        if radius <= 0.0 {
            return Err(DegenerateReason::Coincident);
        }
        // A border already at unit size (to 1e-4) is not rescaled: dGLI scales with 1/size,
        // and a rescale by 1 ± 1e-5 would move every value by that much for nothing.
        let radius = if (radius - 1.0).abs() < UNIT_RADIUS_TOLERANCE { 1.0 } else { radius };
        Ok(Normalisation { centroid, radius })
    }

    /// `p` in normalised coordinates: moved by −centroid, scaled by 1/radius.
    pub fn apply(&self, p: &Point) -> Point {
        Point::from((p.coords - self.centroid) / self.radius)
    }

    /// Every point of `points` normalised ([`Normalisation::apply`]).
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
    /// Border vertices N of every frame.
    pub fn len(&self) -> usize {
        self.border_indices.len()
    }

    /// True when the border has no vertex.
    pub fn is_empty(&self) -> bool {
        self.border_indices.is_empty()
    }
}

/// Validate raw frames of border positions and bring them to the paper's conventions: the
/// one validation of the crate, used alike for a sample to analyse, one border state to
/// draw the disk of, and a border to interpolate folds on.
///
/// Errors on: no frame, an empty frame, frames of different sizes, non-finite numbers,
/// fewer than [`MIN_VERTICES`] distinct vertices, more than [`MAX_VERTICES`] or
/// [`MAX_FRAMES`]; and, as [`Error::Degenerate`] naming the frame, a start frame whose
/// coordinates overflow ([`DegenerateReason::TooLargeToNormalise`]), whose vertices all
/// coincide, or whose XY projection has no area; any later frame that lies farther than
/// [`MAX_NORMALISED_DISTANCE`] start radii from the start centroid (its normalised
/// coordinates would be useless) or that collapsed to one point (within
/// [`COLLAPSE_TOLERANCE`] start radii). Later frames may have no XY area: a cloth can be
/// held up vertically. Repairs, with a warning: a closing vertex equal to vertex 0 is
/// dropped; consecutive duplicate vertices of the start frame are merged.
pub fn prepare(raw: Vec<Vec<[f64; 3]>>) -> Result<BorderFrames> {
    let Some(first) = raw.first() else {
        return Err(Error::Empty { what: "the sample has no frame" });
    };
    let n_in = first.len();
    if n_in == 0 {
        return Err(Error::Empty { what: "frame 0 has no vertex" });
    }
    if raw.len() > MAX_FRAMES {
        return Err(Error::too_large("frames", raw.len(), MAX_FRAMES));
    }
    if n_in > MAX_VERTICES + 1 {
        return Err(Error::too_large("border vertices", n_in, MAX_VERTICES));
    }
    for (f, frame) in raw.iter().enumerate() {
        if frame.len() != n_in {
            return Err(Error::FrameSizeMismatch { frame: f, expected: n_in, got: frame.len() });
        }
        if let Some(v) = frame.iter().position(|p| p.iter().any(|c| !c.is_finite())) {
            return Err(Error::NonFinite { frame: f, vertex: v });
        }
    }
    let degenerate = |frame: usize| move |reason| Error::Degenerate { frame, reason };
    let start: Vec<Point> = first.iter().map(from_xyz).collect();
    let norm = Normalisation::measure(&start).map_err(degenerate(0))?;
    // Every test below runs on normalised coordinates: no product can overflow, and the
    // tolerances are relative to the start frame's size.
    let unit = norm.apply_all(&start);
    let same = |a: usize, b: usize| (unit[a] - unit[b]).norm() <= 1e-12;

    let mut warnings = Vec::new();
    let mut keep: Vec<usize> = (0..n_in).collect();
    if n_in > 1 && same(0, n_in - 1) {
        keep.pop();
        warnings.push("the last vertex repeats vertex 0: the border was closed already".into());
    }
    let mut merged = Vec::new();
    let mut kept: Vec<usize> = Vec::with_capacity(keep.len());
    for &k in &keep {
        match kept.last() {
            Some(&prev) if same(prev, k) => merged.push(k),
            _ => kept.push(k),
        }
    }
    if !merged.is_empty() {
        warnings.push(format!(
            "merged {} duplicate consecutive vertices (input indices {:?})",
            merged.len(),
            merged
        ));
    }
    if kept.len() < MIN_VERTICES {
        return Err(Error::TooFewVertices { got: kept.len(), min: MIN_VERTICES });
    }
    if kept.len() > MAX_VERTICES {
        return Err(Error::too_large("border vertices", kept.len(), MAX_VERTICES));
    }

    let unit_kept: Vec<Point> = kept.iter().map(|&k| unit[k]).collect();
    let area = signed_area_xy(&unit_kept);
    if area.abs() <= 1e-9 {
        return Err(degenerate(0)(DegenerateReason::NoArea));
    }
    let reversed = area < 0.0;
    if reversed {
        // Walk the other way round, keeping vertex 0 first.
        kept[1..].reverse();
    }
    let frames: Vec<Vec<Point>> =
        raw.iter().map(|frame| kept.iter().map(|&k| from_xyz(&frame[k])).collect()).collect();
    for (f, frame) in frames.iter().enumerate().skip(1) {
        check_later_frame(&norm, frame).map_err(degenerate(f))?;
    }
    Ok(BorderFrames { frames, border_indices: kept, reversed, warnings, source: "border".into() })
}

/// A later frame, seen through the start frame's normalisation: near enough to be
/// normalised usefully, and not collapsed to one point.
fn check_later_frame(start: &Normalisation, frame: &[Point]) -> Result<(), DegenerateReason> {
    let unit = start.apply_all(frame);
    let farthest = unit.iter().map(|p| p.coords.norm()).fold(0.0, f64::max);
    // Finite inputs give no NaN here; an overflow is +∞, which is beyond the limit.
    if farthest > MAX_NORMALISED_DISTANCE {
        return Err(DegenerateReason::FarFromStart { limit: MAX_NORMALISED_DISTANCE });
    }
    match Normalisation::measure(&unit) {
        Ok(own) if own.radius > COLLAPSE_TOLERANCE => Ok(()),
        Ok(_) | Err(DegenerateReason::Coincident) => Err(DegenerateReason::Coincident),
        Err(other) => Err(other),
    }
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
        assert_eq!(prepare(vec![]).unwrap_err(), Error::Empty { what: "the sample has no frame" });
        assert!(matches!(prepare(vec![vec![]]), Err(Error::Empty { .. })));
        assert_eq!(
            prepare(vec![square()[..3].to_vec()]).unwrap_err(),
            Error::TooFewVertices { got: 3, min: 4 }
        );
        let mut nan = square();
        nan[2][1] = f64::NAN;
        assert_eq!(
            prepare(vec![square(), nan]).unwrap_err(),
            Error::NonFinite { frame: 1, vertex: 2 }
        );
        assert_eq!(
            prepare(vec![square(), square()[..3].to_vec()]).unwrap_err(),
            Error::FrameSizeMismatch { frame: 1, expected: 4, got: 3 }
        );
        let line: Vec<[f64; 3]> = (0..6).map(|k| [k as f64, 2.0 * k as f64, 0.0]).collect();
        assert_eq!(
            prepare(vec![line]).unwrap_err(),
            Error::Degenerate { frame: 0, reason: DegenerateReason::NoArea }
        );
        assert_eq!(
            prepare(vec![vec![[1.0, 1.0, 1.0]; 8]]).unwrap_err(),
            Error::Degenerate { frame: 0, reason: DegenerateReason::Coincident }
        );
        let huge = vec![vec![[0.0; 3]; MAX_VERTICES + 10]];
        assert!(matches!(
            prepare(huge),
            Err(Error::TooLarge { what: "border vertices", limit: 5000, .. })
        ));
    }

    /// A start frame and `end` made from it point by point.
    fn with_end(end: impl Fn([f64; 3]) -> [f64; 3]) -> Vec<Vec<[f64; 3]>> {
        vec![square(), square().into_iter().map(end).collect()]
    }

    #[test]
    fn degenerate_end_frames_are_refused_naming_the_frame() {
        let collapsed = with_end(|_| [0.3, 0.3, 0.0]);
        assert_eq!(
            prepare(collapsed).unwrap_err(),
            Error::Degenerate { frame: 1, reason: DegenerateReason::Coincident }
        );
        // Shrunk to a speck (1e-12 of the start's size): collapsed too, not a tiny cloth.
        let speck = with_end(|p| p.map(|c| c * 1e-12));
        assert_eq!(
            prepare(speck).unwrap_err(),
            Error::Degenerate { frame: 1, reason: DegenerateReason::Coincident }
        );
        // Scaled by 1e300: finite, but nothing the dGLI can be computed on.
        let far = with_end(|p| p.map(|c| c * 1e300));
        let err = prepare(far).unwrap_err();
        assert!(
            matches!(
                err,
                Error::Degenerate { frame: 1, reason: DegenerateReason::FarFromStart { .. } }
            ),
            "{err}"
        );
        assert!(err.to_string().contains("too large to normalise"), "{err}");
        // A middle frame is checked as well as the end.
        let mut three = with_end(|p| p);
        three.insert(1, vec![[2.0, 2.0, 2.0]; 4]);
        assert_eq!(
            prepare(three).unwrap_err(),
            Error::Degenerate { frame: 1, reason: DegenerateReason::Coincident }
        );
    }

    #[test]
    fn later_frames_may_be_moved_held_up_or_small() {
        // Translated far (1000 sizes away), held up vertically (no XY area), a tenth the size.
        for end in [
            with_end(|p| [p[0] + 1000.0, p[1], p[2]]),
            with_end(|p| [p[0], 0.0, p[1]]),
            with_end(|p| p.map(|c| c * 0.1)),
        ] {
            assert_eq!(prepare(end).unwrap().frames.len(), 2);
        }
    }

    #[test]
    fn huge_coordinates_are_too_large_to_normalise_not_coincident() {
        let big: Vec<[f64; 3]> = square().iter().map(|p| p.map(|c| c * 1e300)).collect();
        let err = prepare(vec![big]).unwrap_err();
        assert_eq!(
            err,
            Error::Degenerate { frame: 0, reason: DegenerateReason::TooLargeToNormalise }
        );
        assert!(err.to_string().contains("coordinates too large to normalise"), "{err}");
        // Near 1e300 but a unit apart: the centroid overflows, the spread does not.
        let offset: Vec<[f64; 3]> = square().iter().map(|p| [p[0] + 1.7e308, p[1], 0.0]).collect();
        assert!(matches!(prepare(vec![offset]), Err(Error::Degenerate { frame: 0, .. })));
        // Large but sound coordinates (1e100 apart) still work: the tests run normalised.
        let wide: Vec<[f64; 3]> = square().iter().map(|p| p.map(|c| c * 1e100)).collect();
        assert!(prepare(vec![wide.clone(), wide]).is_ok());
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
        let pts: Vec<Point> =
            square().iter().map(|p| Point::new(3.0 * p[0] + 5.0, 3.0 * p[1], p[2])).collect();
        let t = Normalisation::of(&pts).unwrap();
        let max = t.apply_all(&pts).iter().map(|p| p.coords.norm()).fold(0.0, f64::max);
        assert!((max - 1.0).abs() < 1e-12);
    }
}
