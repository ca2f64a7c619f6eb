//! The units of `close eval`'s work: each Sample JSON file under the given paths, and each
//! video of a VR-Folding Zarr store among them. One unit is scored on its own
//! ([`Unit::evaluate`]) into the rows [`crate::eval::report`] gathers, so the units can be
//! shared between threads (the CLI) or between the machines of an executor (the Python
//! package's `close.evaluate`): [`units`] lists them in the same order from the same paths
//! wherever it runs, and the report of the rows in that order is the same.

use std::path::PathBuf;

use crate::error::{Error, Result};
use crate::eval::{self, SampleResult};
use crate::fold::FoldMethod;

/// Why a store cannot be read by a build without the `vrfolding` feature.
pub const NO_VRFOLDING: &str = "this close was built without the `vrfolding` feature: it cannot read Zarr stores";

/// One unit of evaluation work.
pub enum Unit {
    /// A Sample JSON file: one row (an error row when it cannot be read).
    File(PathBuf),
    /// A video of a store: a row per fold (`<Category>/fold<k>`).
    #[cfg(feature = "vrfolding")]
    Video(std::sync::Arc<crate::vrfolding::Store>, crate::vrfolding::Video),
}

impl Unit {
    /// The rows of this unit.
    pub fn evaluate(&self, method: FoldMethod) -> Vec<SampleResult> {
        match self {
            Unit::File(path) => {
                let sample = std::fs::read(path)
                    .map_err(|e| format!("{}: {e}", path.display()))
                    .and_then(|bytes| crate::formats::json::parse_sample(&bytes).map_err(|e| e.to_string()));
                vec![match sample {
                    Ok(sample) => eval::evaluate_with(&sample, method),
                    Err(e) => SampleResult::unreadable(&path.display().to_string(), &e),
                }]
            }
            #[cfg(feature = "vrfolding")]
            Unit::Video(store, video) => crate::vrfolding::evaluate(store, video, method),
        }
    }
}

/// The units under `paths`: the videos of every store among them (in the order given, each
/// store's videos in its order), then every `.json` file under the other files and folders,
/// sorted. A path that is neither a folder nor a `.json` file is an error.
pub fn units(paths: &[PathBuf]) -> Result<Vec<Unit>> {
    let (mut units, rest) = store_units(paths)?;
    units.extend(sample_files(&rest)?.into_iter().map(Unit::File));
    Ok(units)
}

/// The videos of every VR-Folding store among `paths`, and the other paths.
#[cfg(feature = "vrfolding")]
pub fn store_units(paths: &[PathBuf]) -> Result<(Vec<Unit>, Vec<PathBuf>)> {
    let (stores, rest): (Vec<PathBuf>, Vec<PathBuf>) = paths.iter().cloned().partition(|p| crate::vrfolding::is_store(p));
    let mut units = Vec::new();
    for path in stores {
        let store = std::sync::Arc::new(crate::vrfolding::Store::open(&path)?);
        let videos = store.videos()?;
        units.extend(videos.into_iter().map(|v| Unit::Video(store.clone(), v)));
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

/// Every `.json` file under the given files and folders, sorted.
fn sample_files(paths: &[PathBuf]) -> Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    let mut stack: Vec<PathBuf> = paths.to_vec();
    while let Some(p) = stack.pop() {
        if p.is_dir() {
            let entries = std::fs::read_dir(&p).map_err(|e| Error::InvalidArgument(format!("{}: {e}", p.display())))?;
            stack.extend(entries.filter_map(|e| e.ok()).map(|e| e.path()));
        } else if p.extension().is_some_and(|e| e == "json") {
            out.push(p);
        } else if paths.contains(&p) {
            return Err(Error::InvalidArgument(format!("{}: not a folder or a Sample JSON file", p.display())));
        }
    }
    out.sort();
    Ok(out)
}
