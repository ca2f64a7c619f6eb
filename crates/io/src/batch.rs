//! The units of `close eval`'s work: each Sample JSON file under the given paths, and each
//! video of a VR-Folding Zarr store among them. One unit is scored on its own
//! ([`Unit::evaluate`]) into the rows [`crate::eval::report`] gathers, so the units can be
//! shared between threads (the CLI) or between the machines of an executor (the Python
//! package's `close.evaluate`): [`units`] lists them in the same order from the same paths
//! wherever it runs, and the report of the rows in that order is the same.

use std::path::{Path, PathBuf};

use crate::eval::{self, SampleResult};
use close_core::error::{Error, Result};
use close_core::fold::FoldMethod;

/// Why a store cannot be read by a build without the `vrfolding` feature.
pub const NO_VRFOLDING: &str =
    "this close was built without the `vrfolding` feature: it cannot read Zarr stores";

/// One unit of evaluation work.
pub enum Unit {
    /// A Sample JSON file: one row (an error row when it cannot be read).
    File(PathBuf),
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
            Unit::File(path) => {
                // Read as a user's file is: a regular file, through the readers' byte cap.
                let sample = crate::formats::read_file(path)
                    .and_then(|bytes| crate::formats::json::parse_sample(&bytes));
                vec![match sample {
                    Ok(sample) => eval::evaluate_with(&sample, method),
                    Err(e) => SampleResult::unreadable(&path.display().to_string(), &e.to_string()),
                }]
            }
            Unit::Failed(name, why) => vec![SampleResult::unreadable(name, why)],
            #[cfg(feature = "vrfolding")]
            Unit::Video(store, video) => eval::evaluate_video(store, video, method),
        }
    }
}

/// The units under `paths`: the videos of every store among them (in the order given, each
/// store's videos in its order, then what of the store could not be read), then every
/// `.json` file under the other files and folders, sorted, and what could not be walked. A
/// path that is neither a folder nor a `.json` file is an error.
pub fn units(paths: &[PathBuf]) -> Result<Vec<Unit>> {
    let (mut units, rest) = store_units(paths)?;
    units.extend(sample_files(&rest)?);
    Ok(units)
}

/// The videos of every VR-Folding store among `paths` (a video that cannot be read is a
/// failed unit, the rest of its store kept), and the other paths.
#[cfg(feature = "vrfolding")]
pub fn store_units(paths: &[PathBuf]) -> Result<(Vec<Unit>, Vec<PathBuf>)> {
    let (stores, rest): (Vec<PathBuf>, Vec<PathBuf>) =
        paths.iter().cloned().partition(|p| crate::vrfolding::is_store(p));
    let mut units = Vec::new();
    for path in stores {
        let store = std::sync::Arc::new(crate::vrfolding::Store::open(&path)?);
        let (videos, unreadable) = store.videos()?;
        units.extend(videos.into_iter().map(|v| Unit::Video(store.clone(), v)));
        units.extend(
            unreadable.into_iter().map(|e| Unit::Failed(path.display().to_string(), e.to_string())),
        );
    }
    Ok((units, rest))
}

/// Without the `vrfolding` feature a store among `paths` is an error.
#[cfg(not(feature = "vrfolding"))]
pub fn store_units(paths: &[PathBuf]) -> Result<(Vec<Unit>, Vec<PathBuf>)> {
    match paths.iter().find(|p| p.join(".zgroup").is_file()) {
        Some(p) => Err(Error::InvalidArgument(format!("{}: {NO_VRFOLDING}", p.display()))),
        None => Ok((Vec::new(), paths.to_vec())),
    }
}

/// Every `.json` file under the given files and folders, each once and sorted, walked as a
/// dataset folder is ([`crate::catalog::walk`]: no loops, not out of the folder); what
/// cannot be walked is a failed unit.
fn sample_files(paths: &[PathBuf]) -> Result<Vec<Unit>> {
    let json = |p: &Path| p.extension().is_some_and(|e| e == "json");
    let (mut files, mut failed) = (Vec::new(), Vec::new());
    for p in paths {
        if p.is_dir() {
            let tree = crate::catalog::walk::walk(p, &json)
                .map_err(|e| Error::InvalidArgument(format!("{}: {e}", p.display())))?;
            files.extend(tree.files().cloned());
            failed.extend(
                tree.unreadable()
                    .map(|(path, why)| Unit::Failed(path.display().to_string(), why.clone())),
            );
        } else if json(p) {
            files.push(p.clone());
        } else {
            return Err(Error::InvalidArgument(format!(
                "{}: not a folder or a Sample JSON file",
                p.display()
            )));
        }
    }
    files.sort();
    files.dedup();
    Ok(files.into_iter().map(Unit::File).chain(failed).collect())
}
