//! Physics-simulated folds: real-looking cloth next to the exact synthetic folds.
//!
//! Twenty first and second folds of flat cloths (napkin, towel, circular towel, pentagon,
//! T-shirt, trousers) simulated with clothilde-sim (F. Coltraro et al., Apache-2.0), copied
//! unchanged into `assets/physics/` (see its README for the credit) and embedded in the
//! binary. Each file is a Sample JSON border: [start, end] or [start, after fold 1, after
//! fold 2], with one true fold [f1, f2] per step in the convention of Kamat, Borràs,
//! Torras, "CloSE: A Geometric Shape-Agnostic Cloth State Representation" (vertex k at
//! angle 2πk/N, anticlockwise from f1 to f2 is the side that folds).
//!
//! Real cloth is no exact reflection: the crease is a rounded loop, the flap lands a few
//! millimetres off the commanded line, outlines are staircases of a masked grid, and a
//! second fold slides the layers underneath. Single folds form the category `physics`,
//! sequences `physics_second_fold`; ids are `physics__<file name>`.
//!
//! ```
//! use close_io::dataset::physics::physics_samples;
//! let samples = physics_samples().unwrap();
//! assert_eq!(samples.len(), 20);
//! assert!(samples.iter().any(|s| s.name == "physics__q3_napkin_half_then_quarter_31x31"));
//! ```

use crate::error::Result;
use crate::formats::json::parse_sample;
use crate::formats::Sample;

/// Embeds each named file of `assets/physics/` as (name, JSON text).
macro_rules! physics_files {
    ($($id:literal),* $(,)?) => {
        [$(($id, include_str!(concat!("../../../../assets/physics/", $id, ".json")))),*]
    };
}

/// The physics folds, by file name.
const FILES: [(&str, &str); 20] = physics_files!(
    "disk_f1_half_bottom_up",
    "disk_f3_cap_right",
    "h1_half_left_onto_right_31x31",
    "h3_towel_half_top_down_26x41",
    "pentagon_f1_half_axis",
    "pentagon_f3_askew_17deg",
    "q3_napkin_half_then_quarter_31x31",
    "q5_towel_half_then_half_26x41",
    "r1_random_napkin_31x31",
    "r2_random_napkin_31x31",
    "r6_random_towel_26x41",
    "r7_random_towel_26x41",
    "trousers_f1_half_left_onto_right",
    "trousers_f3_cuff_corner",
    "trousers_f5_left_side_in",
    "tshirt_f1_half_left_onto_right",
    "tshirt_f3_left_sleeve_over_body",
    "tshirt_f5_corner_hem_right",
    "tshirt_f6_left_side_in",
    "tshirt_q1_left_sleeve_then_half",
);

/// The category of the single physics folds.
pub const CATEGORY: &str = "physics";
/// The category of the physics fold sequences.
pub const SEQUENCE_CATEGORY: &str = "physics_second_fold";

/// The physics samples, named `physics__<file name>`, with their truth.
pub fn physics_samples() -> Result<Vec<Sample>> {
    FILES
        .iter()
        .map(|(id, text)| {
            let mut sample = parse_sample(text.as_bytes())?;
            sample.name = format!("physics__{id}");
            sample.category =
                if sample.frames.len() > 2 { SEQUENCE_CATEGORY } else { CATEGORY }.to_string();
            Ok(sample)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use close_core::angle::TAU;

    #[test]
    fn twenty_folds_with_one_true_fold_a_step() {
        let samples = physics_samples().unwrap();
        let sequences: Vec<&str> = samples
            .iter()
            .filter(|s| s.category == SEQUENCE_CATEGORY)
            .map(|s| s.name.as_str())
            .collect();
        assert_eq!(
            sequences,
            [
                "physics__q3_napkin_half_then_quarter_31x31",
                "physics__q5_towel_half_then_half_26x41",
                "physics__tshirt_q1_left_sleeve_then_half"
            ]
        );
        for s in &samples {
            let truth = s.truth.as_ref().unwrap_or_else(|| panic!("{}: no truth", s.name));
            assert_eq!(truth.folds.len() + 1, s.frames.len(), "{}", s.name);
            assert!(
                truth.folds.iter().flat_map(|f| [f.f1, f.f2]).all(|f| (0.0..TAU).contains(&f)),
                "{}",
                s.name
            );
            let b = s.border_frames().unwrap_or_else(|e| panic!("{}: {e}", s.name));
            // Given anticlockwise and clean: nothing to repair.
            assert!(!b.reversed && b.warnings.is_empty(), "{}: {:?}", s.name, b.warnings);
            let n = b.len();
            let folded = truth.folded_vertices.as_deref().unwrap_or_default();
            assert!(!folded.is_empty() && folded.iter().all(|&v| v < n), "{}", s.name);
            // The cloth lies on the table at the start, and a fold lifts part of it.
            assert!(s.frames[0].iter().all(|p| p[2].abs() < 1e-3), "{}", s.name);
            assert!(s.frames.last().into_iter().flatten().any(|p| p[2] > 1e-3), "{}", s.name);
        }
    }
}
