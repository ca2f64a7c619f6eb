//! `close.Sample`: a cloth sample checked when it is made, its getters, JSON and pickling.

use std::sync::Arc;

use close_io::formats::Sample;
use numpy::PyArray3;
use pyo3::prelude::*;

use crate::convert::{self, frames_array, from_python, to_python};
use crate::errors::{close_error, invalid};

/// A cloth sample: border frames (or a mesh), frame 0 the flat start.
///
/// `Sample(frames, *, name="", category="", truth=None)`: `frames` an (F, N, 3) array or a list
/// of (N, 3) arrays of border vertices, anticlockwise seen from +z (a clockwise border is
/// reversed by the analysis); (F, N, 2) and (N, 2) arrays are x, y with z = 0. `truth` a dict
/// {"folds": [[f1, f2]], "folded_vertices": [...]} in radians, vertex k at 2πk/N. The frames
/// are checked when the sample is made (a NaN, too few vertices, mismatched frames, a
/// degenerate border raise `close.CloseError` here, not at `analyze`). `close.load` reads one
/// from files, `Sample.from_json` from Sample JSON text.
#[pyclass(frozen, module = "close", name = "Sample")]
pub(crate) struct PySample {
    pub(crate) sample: Arc<Sample>,
    /// Where the sample came from.
    pub(crate) meta: Meta,
}

/// `Sample.meta`: for a VR-Folding action its video, category and fold; empty otherwise.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub(crate) struct Meta {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) video_id: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) category: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) fold: Option<usize>,
}

impl PySample {
    fn state(&self) -> PyResult<(String, String)> {
        let meta = serde_json::to_string(&self.meta)
            .map_err(|e| invalid(format!("could not write JSON: {e}")))?;
        Ok((close_io::formats::json::to_json(&self.sample), meta))
    }

    /// A sample of the user's, refused here when the analysis would refuse its frames.
    pub(crate) fn checked(sample: Sample, meta: Meta) -> PyResult<Self> {
        sample.border_frames().map_err(close_error)?;
        Ok(PySample { sample: Arc::new(sample), meta })
    }
}

#[pymethods]
impl PySample {
    #[new]
    #[pyo3(signature = (frames, *, name = "", category = "", truth = None))]
    #[pyo3(text_signature = "(frames, *, name='', category='', truth=None)")]
    fn new(
        frames: &Bound<'_, PyAny>,
        name: &str,
        category: &str,
        truth: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let mut sample = Sample::from_frames(name, category, convert::frames(frames)?);
        sample.truth = truth.map(|t| from_python(t, "truth")).transpose()?;
        Self::checked(sample, Meta::default())
    }

    /// A sample from Sample JSON text (str or bytes: the file format `close analyze` reads,
    /// what `Sample.to_json()` writes), checked as `Sample(...)` checks its frames.
    #[classmethod]
    fn from_json(_cls: &Bound<'_, pyo3::types::PyType>, text: &Bound<'_, PyAny>) -> PyResult<Self> {
        let bytes: Vec<u8> = match text.extract::<String>() {
            Ok(text) => text.into_bytes(),
            Err(_) => {
                text.extract().map_err(|_| invalid("Sample JSON: expected str or bytes".into()))?
            }
        };
        let sample = close_io::formats::json::parse_sample(&bytes).map_err(close_error)?;
        Self::checked(sample, Meta::default())
    }

    #[getter]
    fn name(&self) -> &str {
        &self.sample.name
    }

    #[getter]
    fn category(&self) -> &str {
        &self.sample.category
    }

    /// Vertex positions per frame, an (F, N, 3) float64 array: the border frames, or for a
    /// mesh sample the mesh's vertex frames.
    #[getter]
    fn frames<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f64>>> {
        match &self.sample.mesh {
            Some(mesh) => frames_array(py, &mesh.frames),
            None => frames_array(py, &self.sample.frames),
        }
    }

    /// The known folds, {"folds": [[f1, f2], ...], "folded_vertices": [...]}, or None.
    #[getter]
    fn truth<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.sample.truth.as_ref().map(|t| to_python(py, t)).transpose()
    }

    /// {"faces": list of vertex-index lists, "frames": (F, V, 3) array} for a mesh sample, else None.
    #[getter]
    fn mesh<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        let Some(mesh) = &self.sample.mesh else { return Ok(None) };
        let dict = pyo3::types::PyDict::new(py);
        dict.set_item("faces", mesh.faces.clone())?;
        dict.set_item("frames", frames_array(py, &mesh.frames)?)?;
        Ok(Some(dict.into_any()))
    }

    /// Where the sample came from: for a VR-Folding action {"video_id", "category", "fold"}.
    #[getter]
    fn meta<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.meta)
    }

    /// The sample as Sample JSON (the file format `close analyze` reads).
    fn to_json(&self) -> String {
        close_io::formats::json::to_json(&self.sample)
    }

    fn __repr__(&self) -> String {
        let (frames, n) = match &self.sample.mesh {
            Some(mesh) => (mesh.frames.len(), mesh.frames.first().map_or(0, Vec::len)),
            None => (self.sample.frames.len(), self.sample.frames.first().map_or(0, Vec::len)),
        };
        format!(
            "Sample(name={:?}, category={:?}, frames={frames}, vertices={n})",
            self.sample.name, self.sample.category
        )
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, (String, String))> {
        Ok((slf.get_type().getattr("_from_state")?, slf.get().state()?))
    }

    /// Equal when name, category, frames (or mesh), truth and meta are.
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other.cast::<PySample>().is_ok_and(|o| {
            let that = o.get();
            that.meta == self.meta
                && close_io::formats::json::to_json(&that.sample)
                    == close_io::formats::json::to_json(&self.sample)
        })
    }

    /// Rebuild a pickled sample from its Sample JSON and meta JSON.
    #[classmethod]
    fn _from_state(
        _cls: &Bound<'_, pyo3::types::PyType>,
        json: &str,
        meta: &str,
    ) -> PyResult<Self> {
        let sample = close_io::formats::json::parse_sample(json.as_bytes()).map_err(close_error)?;
        let meta = serde_json::from_str(meta).map_err(|e| invalid(format!("sample meta: {e}")))?;
        Ok(PySample { sample: Arc::new(sample), meta })
    }
}

/// The sample of `obj`: a `close.Sample`, or frames (an (F, N, 3) array, a list of (N, 3) arrays).
pub(crate) fn sample_of(obj: &Bound<'_, PyAny>) -> PyResult<Arc<Sample>> {
    match obj.cast::<PySample>() {
        Ok(s) => Ok(s.get().sample.clone()),
        Err(_) => Ok(Arc::new(Sample::from_frames("", "", convert::frames(obj)?))),
    }
}
