//! The built-in dataset: exact synthetic folds of cloth outlines, generated in memory, and
//! physics-simulated folds of real-looking cloth.
//!
//! Kamat, Borràs, Torras, "CloSE: A Geometric Shape-Agnostic Cloth State Representation"
//! evaluate the representation on cloths folded once or twice; this dataset gives such
//! samples for every shape the app shows, each with its truth.
//! - [`shapes`]: the outlines (napkin, towel, circular towel, T-shirt, top, trousers,
//!   skirt), anticlockwise and normalised;
//! - [`spec`]: the folds, as points along the outline's sides, made at seeded random
//!   points a fraction of an edge from them (never on a vertex or half-edge);
//! - [`corpus`]: a seeded random corpus of fold sequences, for rates on unseen cloths;
//! - [`exact_fold`]: the exact fold that makes the end frames, independent of [`close_core::fold`];
//! - [`variants`]: noise, rigid motion, start jitter and relabelling of a clean fold;
//! - [`grid`]: the napkin and towel as grid meshes (category `mesh`);
//! - [`physics`]: twenty simulated folds (categories `physics`, `physics_second_fold`).
//!
//! **Truth** (the paper's convention): the folds [f1, f2] in angles 2πf/N, one per step,
//! and the vertices that moved between the first and the last frame (input indices; of a
//! mesh, interior ones too). Sample names are `<shape>__<fold>[__<variant>]`,
//! `<shape>__<first>_then_<second>` (category `<shape>_second_fold`),
//! `<shape>_mesh__<fold>` and `physics__<file>`; the id is the name.
//!
//! ```
//! use close_io::dataset::Dataset;
//! let data = Dataset::builtin();
//! let diagonal = data.get("napkin__diagonal").unwrap();
//! assert_eq!(diagonal.sample.category, "napkin");
//! assert_eq!(diagonal.sample.frames.len(), 2);
//! assert!(data.entries().iter().any(|e| e.sample.category == "physics"));
//! assert!(data.get("no such sample").is_none());
//! ```

pub mod corpus;
pub mod exact_fold;
pub mod grid;
pub mod physics;
pub mod shapes;
pub mod spec;
pub mod variants;

use crate::error::Result;
use crate::formats::{MeshFrames, Sample, Truth};
use close_core::angle::param_to_angle;
use close_core::border::{to_xyz, Point};
use close_core::geometry::Fold;

use exact_fold::fold_border;
use grid::grid_mesh;
use shapes::{outline, Shape};
use spec::{fold_off_grid, second_folds, single_folds};
use variants::{Variant, Varied};

/// Cloth thickness: the height a folded layer gains.
pub const THICKNESS: f64 = 0.01;

/// One sample of the built-in dataset.
#[derive(Debug, Clone, PartialEq)]
pub struct BuiltinSample {
    /// Stable identifier (the sample name).
    pub id: String,
    pub sample: Sample,
}

/// The built-in samples, in a fixed order: single folds shape by shape, second folds,
/// meshes, physics.
#[derive(Debug, Clone, PartialEq)]
pub struct Dataset {
    entries: Vec<BuiltinSample>,
}

impl Dataset {
    /// Generate the synthetic samples and read the embedded physics ones. Errors only if a
    /// fold specification or an embedded file is wrong (a bug the tests catch).
    pub fn generate() -> Result<Dataset> {
        let mut samples = single_fold_samples()?;
        samples.extend(second_fold_samples()?);
        samples.extend(mesh_samples()?);
        samples.extend(physics::physics_samples()?);
        Ok(Dataset {
            entries: samples
                .into_iter()
                .map(|sample| BuiltinSample { id: sample.name.clone(), sample })
                .collect(),
        })
    }

    /// The built-in dataset. Its specifications and files are constants that the tests
    /// generate, so a failure here is a bug in this module, not a user's input.
    pub fn builtin() -> Dataset {
        Self::generate().expect("the built-in fold specifications and physics files are valid")
    }

    /// Every sample, in the dataset's order.
    pub fn entries(&self) -> &[BuiltinSample] {
        &self.entries
    }

    /// The sample with this id.
    pub fn get(&self, id: &str) -> Option<&BuiltinSample> {
        self.entries.iter().find(|e| e.id == id)
    }
}

/// Vertices whose position changed between two frames.
fn moved(start: &[Point], end: &[Point]) -> Vec<usize> {
    (0..start.len()).filter(|&v| start[v] != end[v]).collect()
}

fn to_arrays(points: &[Point]) -> Vec<[f64; 3]> {
    points.iter().map(to_xyz).collect()
}

/// A border sample from its frames and truth (folds as border parameters).
fn border_sample(name: String, category: &str, varied: Varied) -> Sample {
    let n = varied.frames.first().map_or(0, Vec::len);
    Sample {
        name,
        category: category.to_string(),
        frames: varied.frames.iter().map(|f| to_arrays(f)).collect(),
        mesh: None,
        truth: Some(Truth {
            folds: varied
                .folds
                .iter()
                .map(|f| Fold::from(f.map(|s| param_to_angle(s, n))))
                .collect(),
            folded_vertices: Some(varied.folded),
            folded_vertices_per_fold: None,
        }),
    }
}

/// Every single fold of every shape, clean and in its variants.
fn single_fold_samples() -> Result<Vec<Sample>> {
    let mut samples = Vec::new();
    for kind in Shape::ALL {
        let outline = outline(kind);
        let n = outline.points.len();
        for (k, spec) in single_folds(kind).iter().enumerate() {
            // The clean fold and its variants share the fold's draw.
            let fold_name = format!("{}__{}", kind.name(), spec.name);
            let ([[f1, f2]], _) =
                fold_off_grid(&fold_name, n, [spec.params(&outline)], |[[f1, f2]]| {
                    fold_border(&outline.points, f1, f2, THICKNESS)
                })?;
            for &variant in std::iter::once(&Variant::Clean).chain(Variant::of_fold(k)) {
                let name = format!("{fold_name}{}", variant.suffix());
                let start = variant.start(&outline.points, &name);
                let end = fold_border(&start, f1, f2, THICKNESS)?;
                let folded = moved(&start, &end);
                let varied = variant.apply(
                    Varied { frames: vec![start, end], folds: vec![[f1, f2]], folded },
                    &name,
                );
                samples.push(border_sample(name, kind.name(), varied));
            }
        }
    }
    Ok(samples)
}

/// A fold, then a fold of the folded cloth: three frames.
fn second_fold_samples() -> Result<Vec<Sample>> {
    second_folds()
        .iter()
        .map(|spec| {
            let outline = outline(spec.shape);
            let name = format!("{}__{}", spec.shape.name(), spec.name);
            let nominal = spec.params(&outline);
            let start = outline.points;
            let ([f, g], (once, twice)) = fold_off_grid(&name, start.len(), nominal, |[f, g]| {
                let once = fold_border(&start, f[0], f[1], THICKNESS)?;
                let twice = fold_border(&once, g[0], g[1], THICKNESS)?;
                Ok((once, twice))
            })?;
            let folded = moved(&start, &twice);
            let category = format!("{}_second_fold", spec.shape.name());
            Ok(border_sample(
                name,
                &category,
                Varied { frames: vec![start, once, twice], folds: vec![f, g], folded },
            ))
        })
        .collect()
}

/// The folds marked `mesh` of the shapes that have a grid, as mesh samples.
fn mesh_samples() -> Result<Vec<Sample>> {
    let mut samples = Vec::new();
    for kind in Shape::ALL {
        let Some(grid) = grid_mesh(kind) else { continue };
        let outline = outline(kind);
        for spec in single_folds(kind).iter().filter(|s| s.mesh) {
            let n = grid.ring().len();
            // Drawn as its border twin `<shape>__<fold>` is, so both fold at the same points.
            let twin = format!("{}__{}", kind.name(), spec.name);
            let ([[f1, f2]], folded) =
                fold_off_grid(&twin, n, [spec.params(&outline)], |[[f1, f2]]| {
                    grid.fold(f1, f2, THICKNESS)
                })?;
            samples.push(Sample {
                name: format!("{}_mesh__{}", kind.name(), spec.name),
                category: "mesh".into(),
                frames: Vec::new(),
                truth: Some(Truth {
                    folds: vec![Fold::new(param_to_angle(f1, n), param_to_angle(f2, n))],
                    folded_vertices: Some(moved(grid.vertices(), &folded)),
                    folded_vertices_per_fold: None,
                }),
                mesh: Some(MeshFrames::new(
                    grid.faces().to_vec(),
                    vec![to_arrays(grid.vertices()), to_arrays(&folded)],
                )),
            });
        }
    }
    Ok(samples)
}

#[cfg(test)]
mod tests {
    use super::*;
    use close_core::fold::apply;
    use close_core::geometry::Folding;
    use std::collections::HashSet;

    /// Frames of a border sample or of a mesh sample.
    fn frame_count(e: &BuiltinSample) -> usize {
        e.sample.mesh.as_ref().map_or(e.sample.frames.len(), |m| m.frames.len())
    }

    #[test]
    fn generation_is_deterministic() {
        let (a, b) = (Dataset::generate().unwrap(), Dataset::generate().unwrap());
        assert_eq!(a, b);
        assert!(a.entries().iter().all(|e| e.id == e.sample.name));
        let ids: HashSet<&str> = a.entries().iter().map(|e| e.id.as_str()).collect();
        assert_eq!(ids.len(), a.entries().len());
    }

    #[test]
    fn every_category_is_there_with_its_frames_and_truth() {
        let data = Dataset::builtin();
        let count = |category: &str| {
            data.entries().iter().filter(|e| e.sample.category == category).count()
        };
        for kind in Shape::ALL {
            assert!(count(kind.name()) >= single_folds(kind).len(), "{kind:?}");
        }
        assert_eq!(count("mesh"), 3);
        assert_eq!(count("physics"), 17);
        assert_eq!(count("physics_second_fold"), 3);
        let seconds =
            data.entries().iter().filter(|e| e.sample.category.ends_with("_second_fold")).count();
        assert_eq!(seconds, second_folds().len() + 3);
        for e in data.entries() {
            let truth = e.sample.truth.as_ref().unwrap_or_else(|| panic!("{}: no truth", e.id));
            assert_eq!(truth.folds.len() + 1, frame_count(e), "{}", e.id);
        }
        assert_eq!(
            data.get("napkin__half_vertical__noisy").map(|e| e.sample.category.as_str()),
            Some("napkin")
        );
    }

    /// The generator's own mirror against the predictor's `apply`: two independent
    /// implementations of the fold must agree on every synthetic sample.
    #[test]
    fn truth_folds_reproduce_the_end_frames() {
        for e in Dataset::builtin().entries().iter().filter(|e| !e.id.starts_with("physics__")) {
            let truth = e.sample.truth.as_ref().unwrap();
            // The border as the analysis sees it (a mesh's boundary, in border order).
            let b = e.sample.border_frames().unwrap();
            let start = &b.frames[0];
            let predicted =
                truth.folds.iter().fold(start.clone(), |b, &f| apply(&b, &Folding::new(f)));
            let end = &b.frames[b.frames.len() - 1];
            let worst = predicted
                .iter()
                .zip(end)
                .map(|(p, q)| (p.xy() - q.xy()).norm())
                .fold(0.0, f64::max);
            let tolerance =
                if e.id.ends_with("__noisy") { 6.0 * variants::END_NOISE } else { 1e-9 };
            assert!(worst < tolerance, "{}: worst XY error {worst}", e.id);
            // The truth lists input vertices: of a mesh, interior ones too.
            let mut moved: Vec<usize> = (0..start.len())
                .filter(|&v| (predicted[v] - start[v]).norm() > 0.0)
                .map(|v| b.border_indices[v])
                .collect();
            moved.sort_unstable();
            let on_border: HashSet<usize> = b.border_indices.iter().copied().collect();
            let listed: Vec<usize> = truth
                .folded_vertices
                .iter()
                .flatten()
                .copied()
                .filter(|v| on_border.contains(v))
                .collect();
            assert_eq!(listed, moved, "{}", e.id);
        }
    }

    #[test]
    fn every_sample_prepares_without_repair() {
        for e in Dataset::builtin().entries() {
            let b = e.sample.border_frames().unwrap_or_else(|err| panic!("{}: {err}", e.id));
            assert!(!b.reversed && b.warnings.is_empty(), "{}: {:?}", e.id, b.warnings);
            match &e.sample.mesh {
                Some(_) => assert_eq!(b.source, "mesh boundary loop", "{}", e.id),
                None => assert_eq!(b.len(), e.sample.frames[0].len(), "{}", e.id),
            }
        }
    }

    #[test]
    fn mesh_samples_have_the_border_of_their_border_twins() {
        let data = Dataset::builtin();
        let meshes: Vec<&BuiltinSample> =
            data.entries().iter().filter(|e| e.sample.mesh.is_some()).collect();
        assert_eq!(meshes.len(), 3);
        for e in meshes {
            let twin = data
                .get(&e.id.replace("_mesh__", "__"))
                .unwrap_or_else(|| panic!("{}: no border twin", e.id));
            let (mesh, border) =
                (e.sample.border_frames().unwrap(), twin.sample.border_frames().unwrap());
            assert_eq!(mesh.len(), border.len(), "{}", e.id);
            for (m, b) in mesh.frames.iter().zip(&border.frames) {
                let worst = m.iter().zip(b).map(|(p, q)| (p - q).norm()).fold(0.0, f64::max);
                assert!(worst < 1e-12, "{}: frames differ by {worst}", e.id);
            }
            assert_eq!(
                e.sample.truth.as_ref().map(|t| &t.folds),
                twin.sample.truth.as_ref().map(|t| &t.folds)
            );
            // Interior vertices fold too: more moved than the border's share.
            let moved = e
                .sample
                .truth
                .as_ref()
                .and_then(|t| t.folded_vertices.as_ref())
                .map_or(0, Vec::len);
            let moved_on_border = twin
                .sample
                .truth
                .as_ref()
                .and_then(|t| t.folded_vertices.as_ref())
                .map_or(0, Vec::len);
            assert!(moved > moved_on_border, "{}: {moved} mesh vertices moved", e.id);
        }
    }
}
