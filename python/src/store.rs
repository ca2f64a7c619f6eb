//! `close.vrfolding.open`: a VR-Folding Zarr store read into `close.Sample`s, one a fold action.

use std::path::PathBuf;
use std::sync::Arc;

use pyo3::prelude::*;
use pyo3::types::PyList;
use rayon::prelude::*;

use crate::errors::close_error;
use crate::files::existing;
use crate::sample::{Meta, PySample};

/// An open VR-Folding Zarr store (or one category of it): its usable fold actions as
/// `close.Sample`s (frames: the border at the start of action 1 and at the end of each action
/// up to this one; `meta`: video_id, category, fold). `len(store)` actions; `store.dropped`
/// folds left out because a mesh they use is broken; `store.errors` videos that could not be read.
#[pyclass(frozen, module = "close.vrfolding", name = "Store")]
pub(crate) struct PyStore {
    path: String,
    actions: Vec<Py<PySample>>,
    dropped: usize,
    errors: Vec<String>,
}

#[pymethods]
impl PyStore {
    fn __len__(&self) -> usize {
        self.actions.len()
    }

    /// Action `k`, counted from the end when negative (as a list's); out of range is IndexError.
    fn __getitem__(&self, py: Python<'_>, k: isize) -> PyResult<Py<PySample>> {
        let count = self.actions.len();
        let index =
            if k < 0 { count.checked_sub(k.unsigned_abs()) } else { Some(k.unsigned_abs()) };
        index.and_then(|i| self.actions.get(i)).map(|s| s.clone_ref(py)).ok_or_else(|| {
            pyo3::exceptions::PyIndexError::new_err(format!("action {k} of {count}"))
        })
    }

    fn __iter__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        PyList::new(py, self.actions.iter().map(|s| s.clone_ref(py)))?
            .into_any()
            .try_iter()
            .map(Bound::into_any)
    }

    #[getter]
    fn path(&self) -> &str {
        &self.path
    }

    #[getter]
    fn dropped(&self) -> usize {
        self.dropped
    }

    #[getter]
    fn errors(&self) -> Vec<String> {
        self.errors.clone()
    }

    fn __repr__(&self) -> String {
        format!("Store({:?}, actions={}, dropped={})", self.path, self.actions.len(), self.dropped)
    }
}

/// Open a VR-Folding store (or one category of it) and read every video: a `close.vrfolding.Store`.
#[pyfunction]
pub(crate) fn vrfolding_open(py: Python<'_>, store: PathBuf) -> PyResult<PyStore> {
    let store = existing(vec![store])?.remove(0);
    let (read, errors) = py
        .detach(|| -> Result<_, close_io::error::Error> {
            let opened = close_io::vrfolding::Store::open(&store)?;
            // Videos that cannot be read are errors of their own; the rest of the store is kept.
            let (videos, unreadable) = opened.videos()?;
            let folds: Vec<_> = videos.par_iter().map(|v| opened.folds(v)).collect();
            let mut read = Vec::new();
            let mut errors: Vec<String> = unreadable.iter().map(|e| e.to_string()).collect();
            for (video, folds) in videos.iter().zip(folds) {
                match folds {
                    Ok(folds) => read.push((video.clone(), folds)),
                    Err(e) => errors.push(e.to_string()),
                }
            }
            Ok((read, errors))
        })
        .map_err(close_error)?;
    let mut actions = Vec::new();
    for (video, folds) in &read {
        for k in 1..=folds.usable() {
            let Some(sample) = folds.sample(video, k) else { continue };
            let meta = Meta {
                video_id: Some(video.id.clone()),
                category: Some(video.category.clone()),
                fold: Some(k),
            };
            actions.push(Py::new(py, PySample { sample: Arc::new(sample), meta })?);
        }
    }
    let dropped = read.iter().map(|(_, f)| f.dropped()).sum();
    Ok(PyStore { path: store.display().to_string(), actions, dropped, errors })
}
