//! The CloSE representation: corners from the start disk's rim, and fold coordinates.
//!
//! **Corners** θ_1 < … < θ_n are the layer-1 cells (edges i, i+1 meet at vertex i+1) of the
//! START disk whose |value| exceeds a threshold: the population standard deviation of the
//! disk values after dropping those with a z-score of 7 or more (as the reference does).
//! Each is reported as the angle of its vertex, 2π(i+1)/N.
//!
//! **CloSE** = ((θ_1 … θ_n), (f1, f2) per fold), all angles in [0, 2π).
//!
//! ```
//! use close::close::corners;
//! use close::disk::Disk;
//! use close::border::Point;
//! let square: Vec<Point> = (0..16)
//!     .map(|k| {
//!         let (side, t) = (k / 4, (k % 4) as f64 / 4.0);
//!         let (x, y) = [(t, 0.0), (1.0, t), (1.0 - t, 1.0), (0.0, 1.0 - t)][side];
//!         Point::new(x, y, 0.0)
//!     })
//!     .collect();
//! let found = corners(&Disk::of_border(&square));
//! assert_eq!(found.vertices, vec![0, 4, 8, 12]);
//! ```

use std::f64::consts::PI;

use serde::Serialize;

use crate::disk::Disk;

/// z-scores at or beyond this are outliers for the corner threshold.
pub const OUTLIER_Z: f64 = 7.0;

/// Corners found on a disk's rim.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Corners {
    /// Corner vertices, increasing.
    pub vertices: Vec<usize>,
    /// Their angles 2πv/N, increasing, in [0, 2π).
    pub angles: Vec<f64>,
    /// The |value| a rim cell had to exceed.
    pub threshold: f64,
}

fn mean_std(values: impl Iterator<Item = f64> + Clone) -> (f64, f64) {
    let (count, sum) = values.clone().fold((0usize, 0.0), |(c, s), v| (c + 1, s + v));
    if count == 0 {
        return (0.0, 0.0);
    }
    let mean = sum / count as f64;
    let var = values.map(|v| (v - mean).powi(2)).sum::<f64>() / count as f64;
    (mean, var.sqrt())
}

/// The corner threshold of a disk: std of its values without the |z| ≥ 7 outliers.
pub fn corner_threshold(disk: &Disk) -> f64 {
    let values = disk.values();
    let (mean, std) = mean_std(values.iter().copied());
    if std == 0.0 {
        return 0.0;
    }
    mean_std(values.iter().copied().filter(|v| ((v - mean) / std).abs() < OUTLIER_Z)).1
}

/// The corners of a start disk.
pub fn corners(disk: &Disk) -> Corners {
    let n = disk.n();
    let threshold = corner_threshold(disk);
    let vertices: Vec<usize> = (0..n).filter(|&v| disk.get((v + n - 1) % n, v).abs() > threshold && threshold > 0.0).collect();
    let angles = vertices.iter().map(|&v| 2.0 * PI * v as f64 / n as f64).collect();
    Corners { vertices, angles, threshold }
}

/// The CloSE of one state: corners and the folds that led to it, in order.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Close {
    pub corners: Vec<f64>,
    pub folds: Vec<[f64; 2]>,
}
