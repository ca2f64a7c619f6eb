//! Variants of a clean synthetic fold: what a real capture changes and a cloth state
//! representation must not care about.
//!
//! Kamat, Borràs, Torras, "CloSE: A Geometric Shape-Agnostic Cloth State Representation"
//! build the representation from the dGLI, which is invariant to rigid motions, and read
//! fold coordinates in the border's own parametrisation. The variants test exactly that:
//! - **noisy**: Gaussian noise (sd [`END_NOISE`]) on every coordinate of the end frame only;
//! - **rotated**: one rotation about z and one XY translation of every frame (rigid);
//! - **jitter**: in-plane Gaussian jitter (sd [`START_JITTER`]) of the start before folding;
//! - **shifted**: a cyclic relabelling of the vertices (new vertex i is old vertex i + s),
//!   which moves the true fold parameters back by s.
//!
//! Randomness comes from [`SplitMix64::from_name`] seeded with the sample's name, so one
//! sample's draws do not depend on the others and two builds are identical.
//!
//! ```
//! use close_core::border::Point;
//! use close_io::dataset::variants::{Variant, Varied};
//! let square = vec![Point::new(0.0, 0.0, 0.0), Point::new(1.0, 0.0, 0.0), Point::new(1.0, 1.0, 0.0), Point::new(0.0, 1.0, 0.0)];
//! let clean = Varied { frames: vec![square.clone(), square], folds: vec![[0.0, 2.0]], folded: vec![1] };
//! let shifted = Variant::Shifted.apply(clean.clone(), "example");
//! // The same cloth, relabelled: the fold started at vertex 0 and still starts there.
//! let i = shifted.folds[0][0] as usize;
//! assert_ne!(i, 0);
//! assert_eq!(shifted.frames[0][i], clean.frames[0][0]);
//! ```

use nalgebra::{Rotation3, Vector3};

use close_core::angle::TAU;
use close_core::border::Point;
use close_core::rng::SplitMix64;

/// Standard deviation of the noise added to a noisy sample's end frame.
pub const END_NOISE: f64 = 0.005;
/// Standard deviation of the in-plane jitter of a jittered sample's start frame.
pub const START_JITTER: f64 = 1e-5;

/// How a clean fold sample is varied.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Variant {
    Clean,
    Noisy,
    Rotated,
    Jitter,
    Shifted,
}

/// A sample's frames and truth as border parameters: the folds and the vertices that moved.
#[derive(Debug, Clone, PartialEq)]
pub struct Varied {
    pub frames: Vec<Vec<Point>>,
    /// Fold endpoints as border parameters (fractional vertex indices), one pair a step.
    pub folds: Vec<[f64; 2]>,
    /// Vertices that moved between the first and the last frame, increasing.
    pub folded: Vec<usize>,
}

impl Variant {
    /// The suffix of a varied sample's name.
    pub fn suffix(self) -> &'static str {
        match self {
            Variant::Clean => "",
            Variant::Noisy => "__noisy",
            Variant::Rotated => "__rotated",
            Variant::Jitter => "__jitter",
            Variant::Shifted => "__shifted",
        }
    }

    /// Which variants a shape's k-th fold gets beyond the clean one: a few of each per shape.
    pub fn of_fold(k: usize) -> &'static [Variant] {
        match k {
            0 => &[Variant::Noisy, Variant::Rotated],
            1 => &[Variant::Noisy, Variant::Jitter],
            2 => &[Variant::Shifted],
            4 => &[Variant::Noisy, Variant::Jitter],
            6 => &[Variant::Rotated, Variant::Shifted],
            _ => &[],
        }
    }

    /// The start border of this variant of sample `name`: `flat`, jittered in plane for
    /// [`Variant::Jitter`] (the fold is then made on the jittered border).
    pub fn start(self, flat: &[Point], name: &str) -> Vec<Point> {
        let mut start = flat.to_vec();
        if self == Variant::Jitter {
            let mut rng = SplitMix64::from_name(&format!("{name}/start"));
            for p in start.iter_mut() {
                p.x += START_JITTER * rng.gaussian();
                p.y += START_JITTER * rng.gaussian();
            }
        }
        start
    }

    /// This variant of the folded sample `name` (noise, rigid motion or relabelling; the
    /// jitter is in [`Variant::start`]).
    pub fn apply(self, sample: Varied, name: &str) -> Varied {
        let mut rng = SplitMix64::from_name(name);
        let Varied { mut frames, mut folds, mut folded } = sample;
        match self {
            Variant::Clean | Variant::Jitter => {}
            Variant::Noisy => {
                for p in frames.last_mut().into_iter().flatten() {
                    *p += Vector3::new(rng.gaussian(), rng.gaussian(), rng.gaussian()) * END_NOISE;
                }
            }
            Variant::Rotated => {
                let rotation = Rotation3::from_axis_angle(&Vector3::z_axis(), TAU * rng.uniform());
                let offset = Vector3::new(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0), 0.0);
                for p in frames.iter_mut().flatten() {
                    *p = rotation * *p + offset;
                }
            }
            Variant::Shifted => {
                let n = frames.first().map_or(0, Vec::len);
                if n > 1 {
                    // New vertex i is old vertex (i + shift) mod N: parameters move back by shift.
                    let shift = 1 + (rng.next_u64() % (n as u64 - 1)) as usize;
                    for f in folds.iter_mut().flatten() {
                        *f = (*f - shift as f64).rem_euclid(n as f64);
                    }
                    for v in folded.iter_mut() {
                        *v = (*v + n - shift) % n;
                    }
                    folded.sort_unstable();
                    for frame in frames.iter_mut() {
                        frame.rotate_left(shift);
                    }
                }
            }
        }
        Varied { frames, folds, folded }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dataset::exact_fold::fold_border;
    use crate::dataset::shapes::{shape, Shape};

    /// The napkin's half fold, clean.
    fn half_fold() -> Varied {
        let start = shape(Shape::Napkin);
        let end = fold_border(&start, 9.5, 47.5, 0.01).unwrap();
        let folded = (0..start.len()).filter(|&v| start[v] != end[v]).collect();
        Varied { frames: vec![start, end], folds: vec![[9.5, 47.5]], folded }
    }

    fn distances(frame: &[Point]) -> Vec<f64> {
        frame.iter().flat_map(|p| frame.iter().map(move |q| (p - q).norm())).collect()
    }

    #[test]
    fn clean_and_jitter_leave_the_folded_frames() {
        let clean = half_fold();
        assert_eq!(Variant::Clean.apply(clean.clone(), "a"), clean);
        assert_eq!(Variant::Jitter.apply(clean.clone(), "a"), clean);
        assert_eq!(Variant::Clean.start(&clean.frames[0], "a"), clean.frames[0]);
    }

    #[test]
    fn rotated_is_a_rigid_motion_about_z() {
        let clean = half_fold();
        let rotated = Variant::Rotated.apply(clean.clone(), "napkin__half_vertical__rotated");
        assert_eq!((&rotated.folds, &rotated.folded), (&clean.folds, &clean.folded));
        for (r, c) in rotated.frames.iter().zip(&clean.frames) {
            assert!(r != c, "the frame moved");
            let worst = distances(r)
                .iter()
                .zip(distances(c))
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(worst < 1e-12, "distances change by {worst}");
            // Heights are kept.
            assert!(r.iter().zip(c).all(|(p, q)| (p.z - q.z).abs() < 1e-15));
        }
        // One motion for every frame: vertex 0 and 1 move alike in both frames.
        let d = |f: usize, v: usize| rotated.frames[f][v] - clean.frames[f][v];
        assert!((d(0, 0) - d(1, 0)).norm() < 1e-12);
    }

    #[test]
    fn shifted_relabels_the_same_cloth_and_its_truth() {
        let clean = half_fold();
        let n = clean.frames[0].len();
        let shifted = Variant::Shifted.apply(clean.clone(), "napkin__half_horizontal__shifted");
        let s = (clean.folds[0][0] - shifted.folds[0][0]).rem_euclid(n as f64).round() as usize;
        assert!(s > 0 && s < n);
        assert_eq!(
            (clean.folds[0][1] - shifted.folds[0][1]).rem_euclid(n as f64).round() as usize,
            s
        );
        for (new, old) in shifted.frames.iter().zip(&clean.frames) {
            assert!((0..n).all(|i| new[i] == old[(i + s) % n]));
        }
        let mut expected: Vec<usize> = clean.folded.iter().map(|&v| (v + n - s) % n).collect();
        expected.sort_unstable();
        assert_eq!(shifted.folded, expected);
    }

    #[test]
    fn noise_touches_the_end_frame_only() {
        let clean = half_fold();
        let noisy = Variant::Noisy.apply(clean.clone(), "napkin__half_vertical__noisy");
        assert_eq!(noisy.frames[0], clean.frames[0]);
        let offsets: Vec<f64> = noisy.frames[1]
            .iter()
            .zip(&clean.frames[1])
            .flat_map(|(p, q)| (p - q).iter().copied().collect::<Vec<_>>())
            .collect();
        let sd = (offsets.iter().map(|x| x * x).sum::<f64>() / offsets.len() as f64).sqrt();
        assert!(sd > 0.5 * END_NOISE && sd < 1.5 * END_NOISE, "noise sd {sd}");
        // Seeded by name: the same name draws the same noise, another name other noise.
        assert_eq!(Variant::Noisy.apply(clean.clone(), "napkin__half_vertical__noisy"), noisy);
        assert_ne!(Variant::Noisy.apply(clean, "other"), noisy);
    }

    #[test]
    fn jitter_moves_the_start_in_plane_by_a_little() {
        let flat = shape(Shape::Towel);
        let start = Variant::Jitter.start(&flat, "towel__half_short_wrap__jitter");
        let worst = start.iter().zip(&flat).map(|(p, q)| (p - q).norm()).fold(0.0, f64::max);
        assert!(worst > 0.0 && worst < 6.0 * START_JITTER, "{worst}");
        assert!(start.iter().all(|p| p.z == 0.0));
    }
}
