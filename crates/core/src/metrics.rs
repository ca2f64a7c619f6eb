//! How far a predicted border is from the true one: RMSE and discrete Fréchet distance.
//!
//! Both are measured on the XY (zenithal) projection after the normalisation of the
//! START border (centroid to origin, farthest vertex at distance 1), so they read in
//! unit-circle units whatever the cloth's size.
//!
//! ```
//! use close_core::border::Point;
//! use close_core::metrics::{frechet_xy, rmse_xy};
//! let a = [Point::new(0.0, 0.0, 0.0), Point::new(1.0, 0.0, 0.0), Point::new(1.0, 1.0, 0.0)];
//! let b = [Point::new(0.0, 0.0, 5.0), Point::new(1.0, 0.0, 0.0), Point::new(1.0, 1.0, 0.0)];
//! assert_eq!(rmse_xy(&a, &b), 0.0); // z does not count
//! assert_eq!(frechet_xy(&a, &b), 0.0);
//! ```

use serde::Serialize;

use crate::border::{Normalisation, Point};

/// Error of a predicted end border against the true one.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Metrics {
    pub rmse: f64,
    pub frechet: f64,
}

impl Metrics {
    /// Metrics of `predicted` against `truth`, both normalised by `start`'s transform.
    pub fn measure(norm: &Normalisation, predicted: &[Point], truth: &[Point]) -> Metrics {
        let p = norm.apply_all(predicted);
        let t = norm.apply_all(truth);
        Metrics { rmse: rmse_xy(&p, &t), frechet: frechet_xy(&p, &t) }
    }
}

/// Squared XY distance: the Fréchet recursion only takes maxima and minima, so it runs on
/// squares and takes one root at the end (hypot per cell was most of its cost).
fn dist2_xy(a: &Point, b: &Point) -> f64 {
    (a.x - b.x).powi(2) + (a.y - b.y).powi(2)
}

/// Root mean square of the XY distances between corresponding vertices.
pub fn rmse_xy(a: &[Point], b: &[Point]) -> f64 {
    let n = a.len().min(b.len()).max(1);
    (a.iter().zip(b).map(|(p, q)| dist2_xy(p, q)).sum::<f64>() / n as f64).sqrt()
}

/// Discrete Fréchet distance in XY between two closed vertex sequences, both walked from
/// vertex 0 back to vertex 0. Eiter–Mannila's dynamic programme, one row at a time: a few
/// lines, so no geometry crate is pulled in for it.
pub fn frechet_xy(a: &[Point], b: &[Point]) -> f64 {
    if a.is_empty() || b.is_empty() {
        return 0.0;
    }
    let closed = |s: &[Point]| s.iter().chain(s.first()).copied().collect::<Vec<_>>();
    let (a, b) = (closed(a), closed(b));
    let mut prev = vec![0.0_f64; b.len()];
    let mut cur = vec![0.0_f64; b.len()];
    for (i, p) in a.iter().enumerate() {
        for (j, q) in b.iter().enumerate() {
            let d = dist2_xy(p, q);
            cur[j] = match (i, j) {
                (0, 0) => d,
                (0, _) => cur[j - 1].max(d),
                (_, 0) => prev[0].max(d),
                _ => prev[j].min(prev[j - 1]).min(cur[j - 1]).max(d),
            };
        }
        std::mem::swap(&mut prev, &mut cur);
    }
    prev[b.len() - 1].sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frechet_of_a_shifted_copy_is_the_shift() {
        let a: Vec<Point> = (0..10).map(|k| Point::new(k as f64, 0.0, 0.0)).collect();
        let b: Vec<Point> = a.iter().map(|p| Point::new(p.x, 0.5, 0.0)).collect();
        assert!((frechet_xy(&a, &b) - 0.5).abs() < 1e-12);
        assert!((rmse_xy(&a, &b) - 0.5).abs() < 1e-12);
    }

    #[test]
    fn frechet_sees_order_not_just_positions() {
        let a = [Point::new(0.0, 0.0, 0.0), Point::new(1.0, 0.0, 0.0), Point::new(0.0, 1.0, 0.0)];
        let b = [Point::new(0.0, 0.0, 0.0), Point::new(0.0, 1.0, 0.0), Point::new(1.0, 0.0, 0.0)];
        assert!(frechet_xy(&a, &b) > 0.5);
    }
}
