//! The units of `close eval`'s work: everything under the given paths, walked as `close
//! serve --dataset` walks a dataset folder ([`crate::catalog::items`]: each sample file, each
//! folder of frame files, each store inside, an error for what cannot be walked), and each
//! video of a VR-Folding Zarr store among them. One unit is scored on its own
//! ([`Unit::evaluate`]) into the rows [`crate::eval::report`] gathers, so the units can be
//! shared between threads (the CLI) or between the machines of an executor (the Python
//! package's `close.evaluate`): [`units`] lists them in the same order from the same paths
//! wherever it runs, and the report of the rows in that order is the same.

use std::collections::HashSet;
use std::path::{Path, PathBuf};

use crate::catalog::walk::{looks_like_store, Listed};
use crate::catalog::{items, listed_as, read_sample, Item};
use crate::error::{Error, Result};
use crate::eval::{self, SampleResult};
use close_core::budget::Deadline;
use close_core::fold::FoldMethod;

pub use crate::catalog::NO_VRFOLDING;

/// One unit of evaluation work.
pub enum Unit {
    /// One sample's files (one sample file, or a folder of frame files), the name it is
    /// shown under (its path) and the sub-folder it is in: one row (an error row when it
    /// cannot be read).
    Sample { files: Vec<Listed>, name: String, folder: String },
    /// What could not be read or walked (its name, and why): one row with the error.
    Failed(String, String),
    /// A video of a store: a row per fold (`<Category>/fold<k>`).
    #[cfg(feature = "vrfolding")]
    Video(std::sync::Arc<crate::vrfolding::Store>, crate::vrfolding::Video),
}

impl Unit {
    /// The rows of this unit.
    pub fn evaluate(&self, method: FoldMethod) -> Vec<SampleResult> {
        match self {
            Unit::Sample { files, name, folder } => {
                // Read as the catalog reads it: the files listed, regular, through the caps.
                vec![match read_sample(files, &Deadline::default()) {
                    Ok(mut sample) => {
                        (sample.name, sample.category) = listed_as(&sample, files, name, folder);
                        eval::evaluate_with(&sample, method)
                    }
                    Err(e) => SampleResult::unreadable(name, &e.to_string()),
                }]
            }
            Unit::Failed(name, why) => vec![SampleResult::unreadable(name, why)],
            #[cfg(feature = "vrfolding")]
            Unit::Video(store, video) => eval::evaluate_video(store, video, method),
        }
    }
}

/// The units under `paths`, in the order given: a store's videos (each store's in its
/// order, then what of it could not be read), a folder's items ([`items`], a store inside
/// it as a store named alone), a file as one sample. A sample reached twice (a file and
/// the folder it is in) is one unit. A path that does not exist is an error.
pub fn units(paths: &[PathBuf]) -> Result<Vec<Unit>> {
    let mut units = Vec::new();
    let mut seen = HashSet::new();
    for path in paths {
        if looks_like_store(path) {
            units.extend(store_units(path)?);
        } else if path.is_dir() {
            let found =
                items(path).map_err(|e| Error::invalid(format!("{}: {e}", path.display())))?;
            let top =
                path.file_name().map_or("dataset".into(), |n| n.to_string_lossy().to_string());
            let name_of = |at: &Path| at.strip_prefix(path).unwrap_or(at).display().to_string();
            for item in found {
                match item {
                    Item::Sample { files, at, category } => {
                        if files.iter().all(|f| f.id.is_some_and(|id| !seen.insert(id))) {
                            continue;
                        }
                        let folder = if category.is_empty() { top.clone() } else { category };
                        units.push(Unit::Sample { files, name: name_of(&at), folder });
                    }
                    Item::Store(at) => units.extend(store_units(&at).unwrap_or_else(|e| {
                        vec![Unit::Failed(at.display().to_string(), e.to_string())]
                    })),
                    Item::Unreadable { at, why, .. } => {
                        units.push(Unit::Failed(at.display().to_string(), why))
                    }
                }
            }
        } else {
            // A file the user named: a link is followed, as the user asked for that file.
            let meta = std::fs::metadata(path)
                .map_err(|e| Error::invalid(format!("{}: {e}", path.display())))?;
            let id = crate::formats::FileId::of(&meta);
            if id.is_some_and(|id| !seen.insert(id)) {
                continue;
            }
            let real = path.canonicalize().unwrap_or_else(|_| path.clone());
            units.push(Unit::Sample {
                files: vec![Listed { path: real, id }],
                name: path.display().to_string(),
                folder: "uncategorised".into(),
            });
        }
    }
    Ok(units)
}

/// The videos of the VR-Folding store at `path` (a video that cannot be read is a failed
/// unit, the rest of its store kept).
#[cfg(feature = "vrfolding")]
pub fn store_units(path: &Path) -> Result<Vec<Unit>> {
    let store = std::sync::Arc::new(crate::vrfolding::Store::open(path)?);
    let (videos, unreadable) = store.videos()?;
    let mut units: Vec<Unit> = videos.into_iter().map(|v| Unit::Video(store.clone(), v)).collect();
    units.extend(
        unreadable.into_iter().map(|e| Unit::Failed(path.display().to_string(), e.to_string())),
    );
    Ok(units)
}

/// Without the `vrfolding` feature a store is an error.
#[cfg(not(feature = "vrfolding"))]
pub fn store_units(path: &Path) -> Result<Vec<Unit>> {
    Err(Error::invalid(format!("{}: {NO_VRFOLDING}", path.display())))
}
