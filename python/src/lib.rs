//! `close._close`: the native half of the Python package `close`.
//!
//! A thin layer: every number comes from the `close` library (the same functions as the CLI
//! and the server), nothing is computed here. What this file does is convert — numpy arrays
//! in and out, the library's JSON objects as Python dicts (through `json.loads`, so
//! `Analysis.to_dict()` is exactly what `close analyze --json` prints) — map errors
//! (`close_core::Error` → `close.CloseError` with the CLI's message; a missing file →
//! `FileNotFoundError`), apply the server's input limits ([`Budget::SERVER`]; the readers'
//! and [`close_core::border::prepare`]'s own limits hold everywhere), and release the GIL
//! around the work. A Rust panic unwinds into `pyo3_runtime.PanicException` (the release
//! profile keeps `panic = "unwind"`).

use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{mpsc, Arc, Mutex, OnceLock};
use std::time::Duration;

use close_core::border::BorderFrames;
use close_core::budget::{Budget, Deadline};
use close_core::geometry::{Fold, Folding, Line, Point2, Vector2};
use close_core::{Analysis, FoldMethod, FrameRange, Options};
use close_io::formats::{Sample, MAX_FILE_BYTES};
use numpy::ndarray::{Array1, Array2, Array3};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArray3, PyReadonlyArrayDyn};
use pyo3::exceptions::{PyFileNotFoundError, PyOSError, PyUserWarning, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{IntoPyDict, PyBytes, PyDict, PyList, PyTuple};
use rayon::prelude::*;

pyo3::create_exception!(
    close,
    CloseError,
    PyValueError,
    "Bad input: not parseable, too few vertices, NaN, mismatched frames, degenerate, over a limit, … \
     The message is the one the `close` command line prints."
);

pyo3::create_exception!(
    close,
    CloseWarning,
    PyUserWarning,
    "What an analysis repaired or changed in its input: a clockwise border walked the other way \
     round, a closing vertex dropped, duplicate vertices merged (`Analysis.warnings`)."
);

/// The library's error as `close.CloseError`, with the CLI's message.
fn close_error(e: impl std::error::Error) -> PyErr {
    CloseError::new_err(e.to_string())
}

fn invalid(message: String) -> PyErr {
    close_error(close_core::Error::InvalidArgument(message))
}

/// A JSON value of the library as the Python object `json.loads` makes of it.
fn to_python<'py>(py: Python<'py>, value: &impl serde::Serialize) -> PyResult<Bound<'py, PyAny>> {
    let text =
        serde_json::to_string(value).map_err(|e| invalid(format!("could not write JSON: {e}")))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// A Python object (a dict of a truth, …) as JSON, through `json.dumps`.
fn from_python<T: serde::de::DeserializeOwned>(
    value: &Bound<'_, PyAny>,
    what: &str,
) -> PyResult<T> {
    let text: String = value.py().import("json")?.call_method1("dumps", (value,))?.extract()?;
    serde_json::from_str(&text).map_err(|e| invalid(format!("{what}: {e}")))
}

/// The fold method named `name`: "default", or a name `close analyze --method` takes.
fn method(name: &str) -> PyResult<FoldMethod> {
    if name == "default" {
        return Ok(FoldMethod::default());
    }
    serde_json::from_value(serde_json::Value::String(name.into())).map_err(|_| {
        invalid(format!("unknown method {name:?}: expected \"default\", \"cut\" or \"paper\""))
    })
}

/// A numpy float64 array of anything array-like.
fn float_array<'py>(obj: &Bound<'py, PyAny>) -> PyResult<PyReadonlyArrayDyn<'py, f64>> {
    let numpy = obj.py().import("numpy")?;
    let kwargs = [("dtype", numpy.getattr("float64")?)].into_py_dict(obj.py())?;
    let array = numpy
        .call_method("asarray", (obj,), Some(&kwargs))
        .map_err(|e| invalid(format!("not an array of numbers: {e}")))?;
    array.extract()
}

/// A row of 3 coordinates, or of 2 (x, y on the table: z = 0, as 2-D contour extraction
/// gives them).
fn point(row: numpy::ndarray::ArrayView1<'_, f64>) -> [f64; 3] {
    [row[0], row[1], row.get(2).copied().unwrap_or(0.0)]
}

/// One border state, an (N, 3) array-like of x, y, z, or (N, 2) of x, y (z = 0); `what`
/// names it in errors.
fn points(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<[f64; 3]>> {
    let array = float_array(obj)?;
    let view = array.as_array();
    match view.shape() {
        [_, 2 | 3] => Ok(view.rows().into_iter().map(point).collect()),
        shape => Err(invalid(format!(
            "{what}: expected an (N, 3) array of x, y, z (or (N, 2) of x, y), got shape {shape:?}"
        ))),
    }
}

/// Frames of border positions: an (F, N, 3) array-like, or a list of (N, 3) ones (which
/// may differ in N: the library names the frame that does); (F, N, 2) and (N, 2) ones are
/// x, y with z = 0.
fn frames(obj: &Bound<'_, PyAny>) -> PyResult<Vec<Vec<[f64; 3]>>> {
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        return obj
            .try_iter()?
            .enumerate()
            .map(|(k, frame)| points(&frame?, &format!("frame {k}")))
            .collect();
    }
    let array = float_array(obj)?;
    let view = array.as_array();
    match view.shape() {
        [_, _, 2 | 3] => {
            Ok(view.outer_iter().map(|f| f.rows().into_iter().map(point).collect()).collect())
        }
        shape => Err(invalid(format!(
            "frames: expected an (F, N, 3) array or a list of (N, 3) arrays (or (F, N, 2), (N, 2): z = 0), got shape {shape:?}"
        ))),
    }
}

/// An (F, N, 3) array of frames (N = 0 when there is no frame).
fn frames_array<'py>(
    py: Python<'py>,
    frames: &[Vec<[f64; 3]>],
) -> PyResult<Bound<'py, PyArray3<f64>>> {
    let n = frames.first().map_or(0, Vec::len);
    if let Some(k) = frames.iter().position(|f| f.len() != n) {
        return Err(close_error(close_core::Error::FrameSizeMismatch {
            frame: k,
            expected: n,
            got: frames[k].len(),
        }));
    }
    let flat: Vec<f64> = frames.iter().flatten().flatten().copied().collect();
    let array = Array3::from_shape_vec((frames.len(), n, 3), flat)
        .map_err(|e| invalid(format!("frames: {e}")))?;
    Ok(array.into_pyarray(py))
}

/// A float64 vector for Python.
type Floats<'py> = Bound<'py, PyArray1<f64>>;

fn points_array<'py>(py: Python<'py>, points: &[[f64; 3]]) -> Bound<'py, PyArray2<f64>> {
    Array2::from_shape_fn((points.len(), 3), |(k, c)| points[k][c]).into_pyarray(py)
}

/// A user's file as an OS error of Python's (a missing file is `FileNotFoundError`).
fn os_error(name: &str) -> impl Fn(std::io::Error) -> PyErr + '_ {
    move |e: std::io::Error| match e.kind() {
        std::io::ErrorKind::NotFound => PyFileNotFoundError::new_err((
            e.raw_os_error().unwrap_or(2),
            e.to_string(),
            name.to_string(),
        )),
        _ => PyOSError::new_err((e.raw_os_error().unwrap_or(0), e.to_string(), name.to_string())),
    }
}

/// Whether a file may be read: it exists (else `FileNotFoundError`), is within the readers'
/// (and the server's upload) byte limit, and is not a VR-Folding store. Its name, for errors.
#[pyfunction]
fn _check_file(path: PathBuf) -> PyResult<String> {
    let name = path.display().to_string();
    let size = std::fs::metadata(&path).map_err(os_error(&name))?.len();
    if size > MAX_FILE_BYTES as u64 {
        return Err(close_error(
            close_io::error::Error::from(close_core::Error::TooLarge {
                what: "bytes of file",
                got: Some(size),
                limit: MAX_FILE_BYTES as u64,
            })
            .in_file(&name),
        ));
    }
    if close_io::vrfolding::is_store(&path) {
        return Err(invalid(format!(
            "{name} is a VR-Folding Zarr store: open it with close.vrfolding.open"
        )));
    }
    Ok(name)
}

/// A file's bytes for the readers, once [`_check_file`] allows it.
fn read(path: &PathBuf) -> PyResult<(String, Vec<u8>)> {
    let name = _check_file(path.clone())?;
    let bytes = std::fs::read(path).map_err(os_error(&name))?;
    Ok((name, bytes))
}

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
struct PySample {
    sample: Arc<Sample>,
    /// Where the sample came from.
    meta: Meta,
}

/// `Sample.meta`: for a VR-Folding action its video, category and fold; empty otherwise.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
struct Meta {
    #[serde(skip_serializing_if = "Option::is_none")]
    video_id: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    category: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    fold: Option<usize>,
}

impl PySample {
    fn state(&self) -> PyResult<(String, String)> {
        let meta = serde_json::to_string(&self.meta)
            .map_err(|e| invalid(format!("could not write JSON: {e}")))?;
        Ok((close_io::formats::json::to_json(&self.sample), meta))
    }

    /// A sample of the user's, refused here when the analysis would refuse its frames.
    fn checked(sample: Sample, meta: Meta) -> PyResult<Self> {
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
        let mut sample = Sample::from_frames(name, category, crate::frames(frames)?);
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
fn sample_of(obj: &Bound<'_, PyAny>) -> PyResult<Arc<Sample>> {
    match obj.cast::<PySample>() {
        Ok(s) => Ok(s.get().sample.clone()),
        Err(_) => Ok(Arc::new(Sample::from_frames("", "", frames(obj)?))),
    }
}

/// The result of `close.analyze`: the CloSE value of the end state, its label, the predicted
/// end border and its metrics. Angles in radians in [0, 2π), vertex k at 2πk/N; each fold
/// (f1, f2) has its folded side anticlockwise from f1 to f2. `to_dict()` is the object that
/// `close analyze --json` prints, key for key.
#[pyclass(frozen, module = "close", name = "Analysis")]
struct PyAnalysis {
    /// The analysis, whose fields the getters read. One unpickled is read back from its
    /// JSON, which has no frames: `redone` then holds it redone from `redo`.
    analysis: Arc<Analysis>,
    /// How its folds were found, so that it can be redone exactly.
    method: FoldMethod,
    /// An unpickled analysis's border frames as the pickle carried them.
    redo: Option<BorderFrames>,
    /// The unpickled analysis redone from `redo` (with its frames), when first needed.
    redone: OnceLock<Arc<Analysis>>,
}

impl PyAnalysis {
    fn of(analysis: Analysis, method: FoldMethod) -> Self {
        PyAnalysis { analysis: Arc::new(analysis), method, redo: None, redone: OnceLock::new() }
    }

    /// The analysed border frames: its own, or for an unpickled analysis those its pickle
    /// carried (none from a pickle without them).
    fn frames(&self) -> Option<&[Vec<close_core::border::Point>]> {
        if !self.analysis.frames.is_empty() {
            return Some(&self.analysis.frames);
        }
        self.redo.as_ref().map(|r| r.frames.as_slice())
    }

    /// The analysis with its frames, for `close.plan` and `disk`: redone from its frames
    /// when this object was unpickled; it must find the same corners and folds as the JSON
    /// says (another version of the library might not).
    fn analysis(&self, py: Python<'_>) -> PyResult<Arc<Analysis>> {
        if !self.analysis.frames.is_empty() {
            return Ok(self.analysis.clone());
        }
        if let Some(a) = self.redone.get() {
            return Ok(a.clone());
        }
        let redo = self.redo.as_ref().ok_or_else(|| {
            invalid("this Analysis was pickled without its frames: analyse its Sample again".into())
        })?;
        let options = Options { method: self.method, budget: Budget::SERVER, ..Options::default() };
        let again = py.detach(|| close_core::analyze_with(redo, options)).map_err(close_error)?;
        if again.corners != self.analysis.corners || again.folds != self.analysis.folds {
            return Err(invalid(
                "this Analysis could not be redone as it was pickled (another version of close?): analyse its Sample again".into(),
            ));
        }
        Ok(self.redone.get_or_init(|| Arc::new(again)).clone())
    }

    /// Warnings of the analysis for Python's `warnings`: what was repaired, and a clockwise
    /// input reversed.
    fn warnings(&self) -> Vec<String> {
        let mut out = self.analysis.warnings.clone();
        if self.analysis.reversed {
            out.push(
                "the border was given clockwise and was walked the other way round: folds, corners and labels follow that anticlockwise order (Analysis.input_folds gives the folds in your vertex order)".into(),
            );
        }
        out
    }
}

#[pymethods]
impl PyAnalysis {
    /// Border vertex count N.
    #[getter]
    fn n(&self) -> usize {
        self.analysis.n
    }

    /// Corner angles θ_1 < … < θ_n (radians; vertex k at 2πk/N).
    #[getter]
    fn corners(&self) -> Vec<f64> {
        self.analysis.corners.clone()
    }

    /// One (f1, f2) per detected fold, in order; the folded side runs anticlockwise from f1 to f2.
    #[getter]
    fn folds(&self) -> Vec<(f64, f64)> {
        self.analysis.folds.iter().map(|f| (f.f1, f.f2)).collect()
    }

    /// The CloSE value, {"corners": [...], "folds": [[f1, f2], ...]}.
    #[getter]
    fn close<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.analysis.close)
    }

    /// The semantic label as a sentence (the structured fields are in `to_dict()["label"]`).
    #[getter]
    fn label(&self) -> String {
        self.analysis.label.text.clone()
    }

    /// The start border with the folds applied in order, (N, 3), input coordinates, in
    /// `border_indices` order.
    #[getter]
    fn predicted_end<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        points_array(py, &self.analysis.predicted_end)
    }

    /// {"rmse", "frechet", "aligned_rmse"} of `predicted_end` against the end frame (XY, normalised
    /// units; `aligned_rmse` once `predicted_end` is moved rigidly onto the end), or None.
    #[getter]
    fn metrics<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.analysis.metrics.as_ref().map(|m| to_python(py, m)).transpose()
    }

    /// For each border vertex, its index in the input frames (a mesh vertex for a mesh).
    #[getter]
    fn border_indices<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        Array1::from_iter(self.analysis.border_indices.iter().map(|&k| k as i64)).into_pyarray(py)
    }

    /// The object `close analyze --json` prints, key for key.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &*self.analysis)
    }

    /// `close analyze --json`'s output.
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string(&*self.analysis)
            .map_err(|e| invalid(format!("could not write JSON: {e}")))
    }

    fn __repr__(&self) -> String {
        format!(
            "Analysis(n={}, corners={}, folds={:?}, label={:?})",
            self.n(),
            self.corners().len(),
            self.folds(),
            self.label()
        )
    }

    /// Pickled as its JSON and what redoes it: the analysed border frames (float64 bytes,
    /// F × N × 3) and the method.
    #[allow(clippy::type_complexity)]
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, (String, Option<(Bound<'py, PyBytes>, usize, String)>))> {
        let py = slf.py();
        let this = slf.get();
        let method = serde_json::to_value(this.method)
            .ok()
            .and_then(|m| m.as_str().map(str::to_string))
            .unwrap_or_default();
        let redo = this.frames().map(|frames| {
            let bytes: Vec<u8> = frames
                .iter()
                .flatten()
                .flat_map(|p| p.coords.iter())
                .flat_map(|c| c.to_le_bytes())
                .collect();
            (PyBytes::new(py, &bytes), frames.len(), method)
        });
        Ok((slf.get_type().getattr("_from_state")?, (this.to_json()?, redo)))
    }

    /// Rebuild a pickled analysis from its JSON and, when given, its frames and method.
    #[classmethod]
    #[pyo3(signature = (json, redo = None))]
    fn _from_state(
        _cls: &Bound<'_, pyo3::types::PyType>,
        json: &str,
        redo: Option<(Vec<u8>, usize, String)>,
    ) -> PyResult<Self> {
        let analysis: Analysis =
            serde_json::from_str(json).map_err(|e| invalid(format!("analysis JSON: {e}")))?;
        let Some((bytes, count, method_name)) = redo else {
            return Ok(PyAnalysis::of(analysis, FoldMethod::default()));
        };
        let n = analysis.border_indices.len();
        if count == 0 || bytes.len() != count * n * 3 * 8 {
            return Err(invalid(format!(
                "analysis state: {} bytes are not {count} frames of {n} vertices",
                bytes.len()
            )));
        }
        let coords: Vec<f64> = bytes
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().unwrap_or_default()))
            .collect();
        let frames = coords
            .chunks_exact(n * 3)
            .map(|f| {
                f.chunks_exact(3)
                    .map(|p| close_core::border::Point::new(p[0], p[1], p[2]))
                    .collect()
            })
            .collect();
        let frames = BorderFrames {
            frames,
            border_indices: analysis.border_indices.clone(),
            reversed: analysis.reversed,
            warnings: analysis.warnings.clone(),
            source: analysis.border_source.clone(),
        };
        Ok(PyAnalysis {
            method: method(&method_name)?,
            redo: Some(frames),
            ..PyAnalysis::of(analysis, FoldMethod::default())
        })
    }

    /// Equal when their `to_dict()`s are: the same numbers, key for key.
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other.cast::<PyAnalysis>().is_ok_and(|o| {
            serde_json::to_value(&*o.get().analysis).ok()
                == serde_json::to_value(&*self.analysis).ok()
        })
    }

    /// What the analysis repaired or changed in its input (a closing vertex dropped,
    /// duplicates merged, a clockwise border reversed), as `close.analyze` warns of it
    /// (`close.CloseWarning`).
    #[getter(warnings)]
    fn warnings_getter(&self) -> Vec<String> {
        self.warnings()
    }

    /// True when the input border was clockwise and the analysis walked it the other way
    /// round: `folds`, `corners` and the label follow the anticlockwise order; see `input_folds`.
    #[getter]
    fn reversed(&self) -> bool {
        self.analysis.reversed
    }

    /// The folds in YOUR vertex order: each fold point at angle 2πt/M of its fractional
    /// input vertex index t (M input vertices, a closing repeat of vertex 0 not counted),
    /// the folded side from the first point to the second in the input's order. Equal to
    /// `folds` for an anticlockwise border; for a clockwise one, mirrored and swapped. None
    /// for a mesh sample (its vertices have no border order of their own).
    #[getter]
    fn input_folds(&self, py: Python<'_>) -> PyResult<Option<Vec<(f64, f64)>>> {
        Ok(self.analysis(py)?.input_folds().map(|f| f.iter().map(|f| (f.f1, f.f2)).collect()))
    }

    /// Border vertex index (0-based) of each corner, in border order: corner k of the label
    /// and the plan ("corner 1", 1-based) is `corners[k - 1]` at vertex `corner_vertices[k - 1]`
    /// (the input's index: `border_indices[corner_vertices[k - 1]]`).
    #[getter]
    fn corner_vertices<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        Array1::from_iter(self.analysis.corner_vertices.iter().map(|&k| k as i64)).into_pyarray(py)
    }

    /// The dGLI disk of analysed frame `k` (0 the start, -1 the end) as `close analyze
    /// --disks` gives it: the condensed pair vector, on the border normalised by the start
    /// frame's transform.
    #[pyo3(signature = (k = 0))]
    fn disk<'py>(&self, py: Python<'py>, k: isize) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let analysis = self.analysis(py)?;
        let count = analysis.frames.len();
        let index = if k < 0 { count.checked_sub(k.unsigned_abs()) } else { Some(k as usize) };
        let disk = index.and_then(|i| analysis.disk(i)).ok_or_else(|| {
            pyo3::exceptions::PyIndexError::new_err(format!(
                "frame {k} of the {count} analysed frames"
            ))
        })?;
        Ok(disk.values().to_vec().into_pyarray(py))
    }
}

/// The library's pipeline on a sample, under the budget of `options` (run with the GIL
/// released).
fn analysis_of(sample: &Sample, options: &Options) -> Result<Analysis, close_core::Error> {
    sample.check_budget(options.frames, &options.budget)?;
    close_core::analyze_with(&sample.border_frames()?, options.clone())
}

/// What `close.analyze` does with the GIL released: the analysis and its JSON.
fn analyze_sample(sample: &Sample, options: &Options) -> Result<PyAnalysis, close_core::Error> {
    analysis_of(sample, options).map(|a| PyAnalysis::of(a, options.method))
}

fn options(
    method_name: &str,
    start: Option<usize>,
    end: Option<usize>,
    max_folds: usize,
) -> PyResult<Options> {
    Ok(Options {
        frames: FrameRange { start, end },
        method: method(method_name)?,
        max_folds,
        budget: Budget::SERVER,
        ..Options::default()
    })
}

/// How often a thread waiting for native work wakes to run Python's signal handlers (so
/// that Ctrl-C stops the work within a fraction of a second) and the progress callback.
const POLL: Duration = Duration::from_millis(50);

/// Run `job` on `pool` (rayon's global pool when None) while this thread waits with the GIL
/// released, waking every [`POLL`] and when the job ends to run Python's signal handlers
/// and report `progress` (the `done` counter, of `total`, to a callable `(done, total)`).
/// A signal handler that raises (Ctrl-C: `KeyboardInterrupt`), or a callback that does,
/// cancels `deadline`, which the job checks between items; this returns that exception once
/// the job has stopped, so no work of this call is left running.
fn wait_for<R: Send>(
    py: Python<'_>,
    pool: Option<&rayon::ThreadPool>,
    deadline: &Deadline,
    progress: Option<(&AtomicUsize, usize, Py<PyAny>)>,
    job: impl FnOnce() -> R + Send,
) -> PyResult<R> {
    py.detach(|| {
        let (ended, end) = mpsc::channel::<()>();
        let result = Mutex::new(None);
        let result_slot = &result;
        let task = move || {
            let r = job();
            *result_slot.lock().unwrap_or_else(|e| e.into_inner()) = Some(r);
            drop(ended);
        };
        let watched = match pool {
            Some(pool) => pool.in_place_scope(|scope| {
                scope.spawn(|_| task());
                supervise(&end, deadline, progress.as_ref())
            }),
            None => rayon::in_place_scope(|scope| {
                scope.spawn(|_| task());
                supervise(&end, deadline, progress.as_ref())
            }),
        };
        watched?;
        result
            .into_inner()
            .unwrap_or_else(|e| e.into_inner())
            .ok_or_else(|| invalid("the work ended without an answer".into()))
    })
}

/// The waiting of [`wait_for`]: until `end` says the job ended, every [`POLL`] run the
/// signal handlers and report progress, with the GIL held only for that.
fn supervise(
    end: &mpsc::Receiver<()>,
    deadline: &Deadline,
    progress: Option<&(&AtomicUsize, usize, Py<PyAny>)>,
) -> PyResult<()> {
    let mut reported = None;
    loop {
        // Disconnected: the job ended (or panicked: the scope passes the panic on).
        let finished = !matches!(end.recv_timeout(POLL), Err(mpsc::RecvTimeoutError::Timeout));
        let checked = Python::attach(|py| -> PyResult<()> {
            py.check_signals()?;
            if let Some((done, total, callback)) = progress {
                let now = done.load(Ordering::Relaxed);
                if reported != Some(now) {
                    callback.call1(py, (now, *total))?;
                    reported = Some(now);
                }
            }
            Ok(())
        });
        if let Err(e) = checked {
            deadline.cancel();
            return Err(e);
        }
        if finished {
            return Ok(());
        }
    }
}

/// `work(k, deadline)` for every k < `total` on `threads` native threads (None: one per
/// core) in a pool of this call's own, whose threads have exited when it returns, under
/// [`wait_for`]: Ctrl-C stops the batch between items (and inside an analysis, at its
/// deadline checks) with `KeyboardInterrupt`; `progress` is called with (items done, total).
fn run_batch<T: Send>(
    py: Python<'_>,
    threads: Option<usize>,
    total: usize,
    progress: Option<&Bound<'_, PyAny>>,
    work: impl Fn(usize, &Deadline) -> T + Sync,
) -> PyResult<Vec<T>> {
    let deadline = Deadline::default();
    let done = AtomicUsize::new(0);
    let progress = progress.map(|p| (&done, total, p.clone().unbind()));
    let batch = || -> Vec<Option<T>> {
        (0..total)
            .into_par_iter()
            .map(|k| {
                if deadline.expired() {
                    return None;
                }
                let out = work(k, &deadline);
                done.fetch_add(1, Ordering::Relaxed);
                Some(out)
            })
            .collect()
    };
    // The pool's threads, joined (not only told to stop) before this returns.
    let handles = Mutex::new(Vec::new());
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .spawn_handler(|thread| {
            let handle = std::thread::Builder::new()
                .name(format!("close-{}", thread.index()))
                .spawn(move || thread.run())?;
            handles.lock().unwrap_or_else(|e| e.into_inner()).push(handle);
            Ok(())
        })
        .build()
        .map_err(|e| invalid(format!("could not start threads: {e}")))?;
    let results = wait_for(py, Some(&pool), &deadline, progress, batch);
    drop(pool);
    let handles = handles.into_inner().unwrap_or_else(|e| e.into_inner());
    py.detach(|| handles.into_iter().for_each(|h| drop(h.join())));
    results?
        .into_iter()
        .collect::<Option<Vec<T>>>()
        .ok_or_else(|| invalid("the batch was cancelled".into()))
}

/// The number of threads asked for: None (one per core) or at least 1.
fn thread_count(threads: Option<i64>) -> PyResult<Option<usize>> {
    match threads {
        None => Ok(None),
        Some(t) if t >= 1 => Ok(Some(usize::try_from(t).unwrap_or(usize::MAX))),
        Some(t) => {
            Err(invalid(format!("threads must be at least 1 (or None: one per core), not {t}")))
        }
    }
}

/// Issue `warnings` (each with the items it concerns, when given) as `close.CloseWarning`s,
/// `stacklevel` frames up from the native call.
fn warn(py: Python<'_>, warnings: &[(String, Vec<usize>)], stacklevel: i32) -> PyResult<()> {
    let category = py.get_type::<CloseWarning>();
    for (message, items) in warnings {
        let text = match items.as_slice() {
            [] => message.clone(),
            [k] => format!("item {k}: {message}"),
            many => {
                let shown: Vec<String> = many.iter().take(10).map(usize::to_string).collect();
                let more = if many.len() > 10 {
                    format!(" and {} more", many.len() - 10)
                } else {
                    String::new()
                };
                format!("items {}{more}: {message}", shown.join(", "))
            }
        };
        let text = std::ffi::CString::new(text.replace('\0', " ")).unwrap_or_default();
        PyErr::warn(py, &category, &text, stacklevel)?;
    }
    Ok(())
}

// `close.analyze`'s `max_folds` default is a literal, so that `inspect.signature` shows it
// (a path shows as `...`); the assertion keeps it the library's.
const _: () = assert!(close_core::DEFAULT_MAX_FOLDS == 3);

/// Analyse frames `start` → `end` (default: first → last) of a sample, one fold per step
/// between consecutive frames, exactly as `close analyze --json` does.
///
/// `frames`: an (F, N, 3) array, a list of (N, 3) arrays, or a `close.Sample`; (F, N, 2)
/// arrays and lists of (N, 2) ones are x, y on the table (z = 0). The border is a closed
/// polyline listed anticlockwise seen from +z (z up, the table the XY plane); a clockwise
/// one is reversed (`Analysis.input_folds` gives its folds in your vertex order).
/// Conventions: angles in radians in [0, 2π); vertex k sits at angle 2πk/N (a fractional
/// vertex index s at 2πs/N); each fold (f1, f2) has its folded side anticlockwise from f1 to
/// f2. `method`: "default" (= "cut") or "paper".
///
/// What the analysis repaired or changed (a clockwise border reversed, a closing vertex
/// dropped, duplicate vertices merged) is issued as a `close.CloseWarning` through Python's
/// `warnings` (and kept in `Analysis.warnings`). Ctrl-C stops a long analysis. `max_folds`:
/// most folds one step may hold (1 to 4, as `close analyze --max-folds`): a step whose end
/// one fold cannot explain is read as a sequence of folds (`steps[k].folds`).
///
/// Raises `close.CloseError` (a ValueError) with the CLI's message on bad input, and on
/// inputs over the server's limits (frames × N² dGLI cells).
#[pyfunction]
#[pyo3(signature = (frames, *, method = "default", start = None, end = None, max_folds = 3))]
fn analyze(
    py: Python<'_>,
    frames: &Bound<'_, PyAny>,
    method: &str,
    start: Option<usize>,
    end: Option<usize>,
    max_folds: usize,
) -> PyResult<PyAnalysis> {
    let deadline = Deadline::default();
    let options = Options { deadline: deadline.clone(), ..options(method, start, end, max_folds)? };
    let sample = sample_of(frames)?;
    let analysis = wait_for(py, None, &deadline, None, || analyze_sample(&sample, &options))?
        .map_err(close_error)?;
    let warnings: Vec<(String, Vec<usize>)> =
        analysis.warnings().into_iter().map(|w| (w, Vec::new())).collect();
    warn(py, &warnings, 1)?;
    Ok(analysis)
}

/// `close.analyze` of every item: what `close.analyze_many` (the Python function, which
/// turns `progress=True` into a bar) calls. `progress`: None or a callable (done, total).
/// With `errors="return"` a failing item's place holds its `close.CloseError`; with
/// "raise" the first failing item (the lowest index) raises, naming its index.
#[pyfunction]
#[pyo3(signature = (items, *, threads = None, method = "default", progress = None, errors = "raise"))]
fn analyze_many<'py>(
    py: Python<'py>,
    items: &Bound<'py, PyAny>,
    threads: Option<i64>,
    method: &str,
    progress: Option<&Bound<'py, PyAny>>,
    errors: &str,
) -> PyResult<Vec<Bound<'py, PyAny>>> {
    let keep_errors = match errors {
        "raise" => false,
        "return" => true,
        other => {
            return Err(invalid(format!("errors must be \"raise\" or \"return\", not {other:?}")))
        }
    };
    let threads = thread_count(threads)?;
    let options = options(method, None, None, close_core::DEFAULT_MAX_FOLDS)?;
    let at = |k: usize, e: &dyn std::fmt::Display| CloseError::new_err(format!("item {k}: {e}"));
    // Items that are not samples fail here, before any work; in "raise" mode the first of
    // them bounds the work (nothing after it runs).
    let mut inputs = Vec::new();
    for (k, item) in items.try_iter()?.enumerate() {
        inputs.push(item.and_then(|item| sample_of(&item)).map_err(|e| at(k, &e.value(py))));
    }
    let first_failed = AtomicUsize::new(if keep_errors {
        usize::MAX
    } else {
        inputs.iter().position(Result::is_err).unwrap_or(usize::MAX)
    });
    let samples: Vec<Option<Arc<Sample>>> =
        inputs.iter().map(|r| r.as_ref().ok().cloned()).collect();
    let outcomes = run_batch(py, threads, samples.len(), progress, |k, deadline| {
        let sample = samples[k].as_ref()?;
        if k > first_failed.load(Ordering::Relaxed) {
            return None;
        }
        let options = Options { deadline: deadline.clone(), ..options.clone() };
        let outcome = analyze_sample(sample, &options);
        if outcome.is_err() && !keep_errors {
            first_failed.fetch_min(k, Ordering::Relaxed);
        }
        Some(outcome)
    })?;
    let mut results = Vec::with_capacity(outcomes.len());
    let mut warnings: Vec<(String, Vec<usize>)> = Vec::new();
    for (k, (outcome, input)) in outcomes.into_iter().zip(inputs).enumerate() {
        let result = match (outcome, input) {
            (Some(Ok(analysis)), _) => {
                for w in analysis.warnings() {
                    match warnings.iter_mut().find(|(m, _)| *m == w) {
                        Some((_, items)) => items.push(k),
                        None => warnings.push((w, vec![k])),
                    }
                }
                Ok(Bound::new(py, analysis)?.into_any())
            }
            (Some(Err(e)), _) => Err(at(k, &e)),
            (None, Err(e)) => Err(e),
            // Skipped: an item before it failed, and that one is raised.
            (None, Ok(_)) => continue,
        };
        match result {
            Ok(done) => results.push(done),
            Err(e) if keep_errors => results.push(e.into_value(py).into_bound(py).into_any()),
            Err(e) => return Err(e),
        }
    }
    warn(py, &warnings, 2)?;
    Ok(results)
}

/// A batch's results as numpy arrays, ready for pandas: `results` is what
/// `close.analyze_many` returns (with `errors="return"`, a `CloseError` in a failed item's
/// place). Returns a dict of arrays, one row per item in order:
///
/// - `n`, `corner_count`, `fold_count`: int64 (B,) (0 for a failed item);
/// - `corners`: (B, C) float64, each item's corner angles NaN-padded to the most corners C;
/// - `folds`: (B, F, 2) float64, each item's folds NaN-padded to the most folds F;
/// - `rmse`, `frechet`, `aligned_rmse`: float64 (B,), NaN without an end frame or on failure
///   (normalised units: the start frame's farthest-vertex radius is 1);
/// - `error`: list of the failed items' messages (None where the item succeeded).
///
/// The one-dimensional entries are columns: `pandas.DataFrame({k: v for k, v in
/// arrays.items() if numpy.ndim(v) == 1})`.
#[pyfunction]
fn to_arrays<'py>(py: Python<'py>, results: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyDict>> {
    let mut rows: Vec<Option<Bound<'py, PyAnalysis>>> = Vec::new();
    let mut messages: Vec<Option<String>> = Vec::new();
    for (k, item) in results.try_iter()?.enumerate() {
        let item = item?;
        if let Ok(a) = item.cast::<PyAnalysis>() {
            rows.push(Some(a.clone()));
            messages.push(None);
        } else if item.is_instance_of::<pyo3::exceptions::PyBaseException>() {
            rows.push(None);
            messages.push(Some(item.str()?.to_string()));
        } else {
            return Err(pyo3::exceptions::PyTypeError::new_err(format!(
                "item {k}: expected a close.Analysis or an exception (analyze_many(..., errors=\"return\")), got {}",
                item.get_type().name()?
            )));
        }
    }
    let analyses: Vec<Option<&PyAnalysis>> =
        rows.iter().map(|r| r.as_ref().map(Bound::get)).collect();
    let b = analyses.len();
    let corners: Vec<Vec<f64>> =
        analyses.iter().map(|a| a.map(PyAnalysis::corners).unwrap_or_default()).collect();
    let folds: Vec<Vec<(f64, f64)>> =
        analyses.iter().map(|a| a.map(PyAnalysis::folds).unwrap_or_default()).collect();
    let most_corners = corners.iter().map(Vec::len).max().unwrap_or(0);
    let most_folds = folds.iter().map(Vec::len).max().unwrap_or(0);
    let corner_array = Array2::from_shape_fn((b, most_corners), |(i, j)| {
        corners[i].get(j).copied().unwrap_or(f64::NAN)
    });
    let fold_array = Array3::from_shape_fn((b, most_folds, 2), |(i, j, e)| {
        folds[i].get(j).map_or(f64::NAN, |f| if e == 0 { f.0 } else { f.1 })
    });
    let count = |f: &dyn Fn(&PyAnalysis) -> usize| -> Vec<i64> {
        analyses.iter().map(|a| a.map_or(0, |a| f(a) as i64)).collect()
    };
    let metric = |of: fn(&close_core::metrics::Metrics) -> f64| -> Vec<f64> {
        analyses
            .iter()
            .map(|a| a.and_then(|a| a.analysis.metrics.as_ref()).map_or(f64::NAN, of))
            .collect()
    };
    let out = PyDict::new(py);
    out.set_item("n", count(&PyAnalysis::n).into_pyarray(py))?;
    out.set_item("corner_count", count(&|a| a.corners().len()).into_pyarray(py))?;
    out.set_item("fold_count", count(&|a| a.folds().len()).into_pyarray(py))?;
    out.set_item("corners", corner_array.into_pyarray(py))?;
    out.set_item("folds", fold_array.into_pyarray(py))?;
    out.set_item("rmse", metric(|m| m.rmse).into_pyarray(py))?;
    out.set_item("frechet", metric(|m| m.frechet).into_pyarray(py))?;
    out.set_item("aligned_rmse", metric(|m| m.aligned_rmse).into_pyarray(py))?;
    out.set_item("error", messages)?;
    Ok(out)
}

/// Read a sample from files, as `close analyze FILE...` does: one Sample JSON or MATLAB .mat
/// file, one text/CSV file per frame, or one OBJ/PLY mesh per frame. A missing file raises
/// FileNotFoundError; a file that cannot be parsed, `close.CloseError`.
#[pyfunction]
#[pyo3(signature = (*paths))]
fn load(paths: Vec<PathBuf>) -> PyResult<PySample> {
    let files = paths.iter().map(read).collect::<PyResult<Vec<_>>>()?;
    let sample = close_io::formats::read_files(&files).map_err(close_error)?;
    PySample::checked(sample, Meta::default())
}

/// The dGLI disk of one border state ((N, 3) array) as the condensed pair vector of
/// `close analyze --disks`: pairs (i, j), i < j, row-major (index i·N − i(i+1)/2 + j − i − 1),
/// N(N−1)/2 values. Computed on the border normalised by `reference` (the flat start frame,
/// whose normalisation and orientation apply, as in an analysis; default: the border itself).
/// `close.disk_layout(N)` gives each pair's place on the disk.
#[pyfunction]
#[pyo3(signature = (border, *, reference = None))]
fn dgli_disk<'py>(
    py: Python<'py>,
    border: &Bound<'py, PyAny>,
    reference: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let border = points(border, "border")?;
    let reference = reference.map(|r| points(r, "reference")).transpose()?;
    Budget::SERVER.analysis(1, border.len()).map_err(close_error)?;
    let disk = py
        .detach(|| close_core::disk::of_state(border, reference, &Default::default()))
        .map_err(close_error)?;
    Ok(disk.values().to_vec().into_pyarray(py))
}

/// Where each pair of `dgli_disk`'s vector sits on the disk of an N-edge border: radius
/// (L − d + 1)/L for cyclic distance d (the rim is 1) and angle π(2a + d + 1)/N (radians),
/// two (N(N−1)/2,) arrays in the same order. For `matplotlib`'s polar axes.
#[pyfunction]
fn disk_layout(py: Python<'_>, n: usize) -> PyResult<(Floats<'_>, Floats<'_>)> {
    if !(close_core::border::MIN_VERTICES..=close_core::border::MAX_VERTICES).contains(&n) {
        return Err(invalid(format!(
            "a disk has {} to {} edges, not {n}",
            close_core::border::MIN_VERTICES,
            close_core::border::MAX_VERTICES
        )));
    }
    let (radius, angle): (Vec<f64>, Vec<f64>) = (0..n)
        .flat_map(|i| (i + 1..n).map(move |j| close_core::disk::position(n, i, j)))
        .map(|p| (p.radius, p.angle))
        .unzip();
    Ok((radius.into_pyarray(py), angle.into_pyarray(py)))
}

/// A folding motion (radians, vertex k at 2πk/N) on `border` ((N, 3), the flat border, or a
/// folded state with its flat `reference`): between two folds `from_` (f1, f2) → `to`
/// (g1, g2), each endpoint moving along the border circle; or one fold's `arcs` (an analysis
/// step's `arcs`, [(a, b), ...]) turned over together about `line` (its `line`, a dict
/// {"point": (x, y), "direction": (dx, dy)}; by default through the first arc's start and the
/// last arc's end). `prior`: folds made on the flat `border` first, in order, each a dict
/// with its "arcs" and "line" as an analysis step's `folds` entries give them: the motion
/// starts from the state they leave, so fold k of a sequence plays after folds 1…k−1 (no
/// `reference` then). Returns a (steps, N, 3) array of borders, as `POST /api/interpolate`
/// does.
#[pyfunction]
#[pyo3(signature = (border, from_ = None, to = None, steps = 60, *, reference = None, arcs = None, line = None, prior = None))]
#[allow(clippy::too_many_arguments)]
fn interpolate<'py>(
    py: Python<'py>,
    border: &Bound<'py, PyAny>,
    from_: Option<(f64, f64)>,
    to: Option<(f64, f64)>,
    steps: usize,
    reference: Option<&Bound<'py, PyAny>>,
    arcs: Option<Vec<[f64; 2]>>,
    line: Option<&Bound<'py, PyAny>>,
    prior: Option<Vec<Bound<'py, PyAny>>>,
) -> PyResult<Bound<'py, PyArray3<f64>>> {
    let border = points(border, "border")?;
    let reference = reference.map(|r| points(r, "reference")).transpose()?;
    let pair = |p: (f64, f64)| Fold::new(p.0, p.1);
    let line = line.map(fold_line).transpose()?;
    let arcs = arcs.map(|arcs| arcs.into_iter().map(close_core::geometry::Arc::from).collect());
    let motion = close_core::interpolate::Motion::of(from_.map(pair), to.map(pair), arcs, line)
        .map_err(close_error)?;
    let prior = prior.unwrap_or_default().iter().map(prior_fold).collect::<PyResult<Vec<_>>>()?;
    Budget::SERVER.interpolation(border.len(), steps).map_err(close_error)?;
    let motion = py
        .detach(|| close_core::interpolate::interpolate(border, reference, &prior, &motion, steps))
        .map_err(close_error)?;
    frames_array(py, &motion.borders)
}

/// A fold made before a motion, given as an analysis step's `folds` entry: a dict with its
/// "arcs" [(a, b), ...] and its "line" (or None).
fn prior_fold(fold: &Bound<'_, PyAny>) -> PyResult<Folding> {
    let expected = "prior: each fold a dict with \"arcs\" [(a, b), ...] and \"line\" (or None)";
    let arcs: Vec<[f64; 2]> =
        fold.get_item("arcs").and_then(|a| a.extract()).map_err(|_| invalid(expected.into()))?;
    let arcs: Vec<close_core::geometry::Arc> = arcs.into_iter().map(Into::into).collect();
    let line = match fold.get_item("line") {
        Ok(line) if !line.is_none() => Some(fold_line(&line)?),
        _ => None,
    };
    Ok(Folding { fold: Fold::span(&arcs).unwrap_or_default(), arcs, line })
}

/// A fold line given as an analysis reports it: {"point": (x, y), "direction": (dx, dy)}.
fn fold_line(line: &Bound<'_, PyAny>) -> PyResult<Line> {
    let pair = |key: &str| -> PyResult<[f64; 2]> {
        line.get_item(key)
            .and_then(|v| v.extract())
            .map_err(|_| invalid(format!("line: expected a dict {{\"point\": (x, y), \"direction\": (dx, dy)}}, without a usable \"{key}\"")))
    };
    let ([x, y], [dx, dy]) = (pair("point")?, pair("direction")?);
    Ok(Line { point: Point2::new(x, y), direction: Vector2::new(dx, dy) })
}

/// The analysis of `obj`: a `close.Analysis` (an unpickled one is redone from its frames),
/// or a `close.Sample` (or frames) analysed first → last, with the GIL released.
fn analysis_for(py: Python<'_>, obj: &Bound<'_, PyAny>) -> PyResult<Arc<Analysis>> {
    match obj.cast::<PyAnalysis>() {
        Ok(a) => a.get().analysis(py),
        Err(_) => {
            let sample = sample_of(obj)?;
            let options = options("default", None, None, close_core::DEFAULT_MAX_FOLDS)?;
            py.detach(|| analysis_of(&sample, &options)).map(Arc::new).map_err(close_error)
        }
    }
}

/// The folds of a plan's goal: one fold (g1, g2), or folds in order as a (K, 2) array-like
/// (empty: the flat cloth).
fn goal_folds(goal: &Bound<'_, PyAny>) -> PyResult<Vec<Fold>> {
    if let Ok((g1, g2)) = goal.extract::<(f64, f64)>() {
        return Ok(vec![Fold::new(g1, g2)]);
    }
    let array = float_array(goal)?;
    let view = array.as_array();
    match *view.shape() {
        // No fold: the flat cloth.
        [0] => Ok(Vec::new()),
        [2] => Ok(vec![Fold::new(view[0], view[1])]),
        [_, 2] => Ok(view.rows().into_iter().map(|r| Fold::new(r[0], r[1])).collect()),
        ref shape => Err(invalid(format!(
            "goal: expected one fold (g1, g2) or folds in order as a (K, 2) array, got shape {shape:?}"
        ))),
    }
}

/// How to reach the goal from the state a sample ends in: the answer of `POST /api/plan`
/// ({"case", "steps": [{"action", "fold", "corners", "picks", "line"}], ...}). `goal` is one
/// fold (g1, g2) in radians, or folds made in order as a (K, 2) array-like (each on the
/// state the ones before it left). Takes a `close.Sample` (or frames: analysed first →
/// last) or a `close.Analysis` (an unpickled one too: it is redone from the frames its
/// pickle carries). Each step's `corners` are 1-based corner numbers (corner k is
/// `Analysis.corners[k - 1]`), with the vertex of each beside them in `corner_vertices`;
/// picks and `corner_vertices` are the input's vertex indices (through `border_indices`).
#[pyfunction]
fn plan<'py>(
    py: Python<'py>,
    sample_or_analysis: &Bound<'py, PyAny>,
    goal: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let goal = goal_folds(goal)?;
    let analysis = analysis_for(py, sample_or_analysis)?;
    let answer = close_core::plan::answer(&analysis, &goal).map_err(close_error)?;
    to_python(py, &answer)
}

/// `close plan FILES --goal G1,G2`'s text (without `--json`): the plan from a sample, or
/// frames, or an analysis.
#[pyfunction]
fn _plan_text(
    py: Python<'_>,
    sample_or_analysis: &Bound<'_, PyAny>,
    goal: &Bound<'_, PyAny>,
) -> PyResult<String> {
    let goal = goal_folds(goal)?;
    let analysis = analysis_for(py, sample_or_analysis)?;
    let plan = close_core::plan::plan_for(&analysis, &goal).map_err(close_error)?;
    Ok(plan.text())
}

/// Fold sequences given to `close.distance` / `close.verify`: a `close.Analysis` (its folds),
/// a dict with "folds" (a CloSE value, `Analysis.close`), or an array-like of folds: (K, 2)
/// for one sequence, (B, K, 2) for a batch whose shorter sequences end in rows of NaN.
/// Returns the numbers (row-major), the sequence count (`None`: one sequence, not a batch)
/// and the width K.
fn fold_rows(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<(Vec<f64>, Option<usize>, usize)> {
    if let Ok(a) = obj.cast::<PyAnalysis>() {
        let folds = a.get().folds();
        let width = folds.len();
        return Ok((folds.into_iter().flat_map(|(f1, f2)| [f1, f2]).collect(), None, width));
    }
    let folds = match obj.cast::<pyo3::types::PyDict>() {
        Ok(dict) => dict
            .get_item("folds")?
            .ok_or_else(|| invalid(format!("{what}: a dict needs \"folds\" (a CloSE value)")))?,
        Err(_) => obj.clone(),
    };
    let array = float_array(&folds)?;
    let view = array.as_array();
    let values = || view.iter().copied().collect::<Vec<f64>>();
    match *view.shape() {
        // An empty list: the flat cloth.
        [0] => Ok((Vec::new(), None, 0)),
        [k, 2] => Ok((values(), None, k)),
        [count, k, 2] => Ok((values(), Some(count), k)),
        ref shape => Err(invalid(format!(
            "{what}: expected folds as a (K, 2) array or a batch (B, K, 2), got shape {shape:?}"
        ))),
    }
}

/// The distance between two states of one cloth (see `close_core::distance`): by default
/// the fold distance, in shares of the border (moving one fold point by one edge costs 1/N,
/// a missing or extra fold its folded share); `kind="geometric"`, the aligned XY RMSE of the
/// two predicted borders in normalised units (needs `border`, the flat start, or two
/// Analyses). `a`, `b`: Analyses, CloSE dicts, (K, 2) arrays of folds, or (B, K, 2) batches
/// (NaN rows pad shorter sequences; a single sequence is paired with every one of a batch):
/// a float for two states, a (B,) array for a batch.
#[pyfunction]
#[pyo3(signature = (a, b, *, kind = "folds", border = None))]
fn distance<'py>(
    py: Python<'py>,
    a: &Bound<'py, PyAny>,
    b: &Bound<'py, PyAny>,
    kind: &str,
    border: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    use close_core::distance::{between, fold_distances, geometric_distances, FoldBatch};
    let geometric = match kind {
        "folds" => false,
        "geometric" => true,
        _ => return Err(invalid(format!("kind {kind:?}: expected \"folds\" or \"geometric\""))),
    };
    if let (true, None, Ok(x), Ok(y)) =
        (geometric, border, a.cast::<PyAnalysis>(), b.cast::<PyAnalysis>())
    {
        let (x, y) = (x.get().analysis(py)?, y.get().analysis(py)?);
        let d = between(&x, &y).map_err(close_error)?;
        return Ok(d.geometric.unwrap_or(f64::NAN).into_pyobject(py)?.into_any());
    }
    let flat = match (geometric, border) {
        (true, None) => {
            return Err(invalid(
                "kind=\"geometric\" needs the flat `border` (or two Analyses)".into(),
            ))
        }
        (true, Some(border)) => {
            let prepared = close_core::border::prepare(vec![points(border, "border")?])
                .map_err(close_error)?;
            prepared.frames.into_iter().next()
        }
        (false, _) => None,
    };
    let ((xa, ca, wa), (xb, cb, wb)) = (fold_rows(a, "a")?, fold_rows(b, "b")?);
    let batch = ca.is_some() || cb.is_some();
    let out = py
        .detach(|| {
            let x = FoldBatch::new(&xa, ca.unwrap_or(1), wa)?;
            let y = FoldBatch::new(&xb, cb.unwrap_or(1), wb)?;
            match &flat {
                Some(flat) => geometric_distances(flat, &x, &y),
                None => fold_distances(&x, &y),
            }
        })
        .map_err(close_error)?;
    match out[..] {
        [one] if !batch => Ok(one.into_pyobject(py)?.into_any()),
        _ => Ok(out.into_pyarray(py).into_any()),
    }
}

/// Did the state a sample ends in reach the goal folds? The answer of `POST /api/verify`
/// ({"reached", "text", "distance", "folds", "extra", "plan", ...}). `observed`: a
/// `close.Sample` (or frames, analysed first → last) or a `close.Analysis`; `goal`: folds
/// (g1, g2) in order, as a list, a (K, 2) array, a CloSE dict or an Analysis.
#[pyfunction]
#[pyo3(signature = (observed, goal, *, tolerance_edges = 1.5, tolerance_rmse = 0.03))]
fn verify<'py>(
    py: Python<'py>,
    observed: &Bound<'py, PyAny>,
    goal: &Bound<'py, PyAny>,
    tolerance_edges: f64,
    tolerance_rmse: f64,
) -> PyResult<Bound<'py, PyAny>> {
    use close_core::verify::{check_goal, Goal, Tolerance};
    let (values, count, _) = fold_rows(goal, "goal")?;
    if count.is_some() {
        return Err(invalid("goal: one sequence of folds, (K, 2), not a batch".into()));
    }
    let goal = Goal::folds(values.chunks(2).map(|f| [f[0], f[1]]));
    // A bad goal is refused before the sample is analysed.
    check_goal(&goal, None).map_err(close_error)?;
    let analysis = analysis_for(py, observed)?;
    let tolerance = Tolerance { edges: tolerance_edges, aligned_rmse: tolerance_rmse };
    let answer = py
        .detach(|| close_core::verify::verify(&analysis, &goal, tolerance))
        .map_err(close_error)?;
    to_python(py, &answer)
}

/// The paths of `close.evaluate`, each of which must exist.
fn existing(paths: Vec<PathBuf>) -> PyResult<Vec<PathBuf>> {
    match paths.iter().find(|p| !p.exists()) {
        Some(p) => Err(PyFileNotFoundError::new_err((
            2,
            "No such file or directory",
            p.display().to_string(),
        ))),
        None => Ok(paths),
    }
}

/// How many units of work (`.json` files, videos of VR-Folding stores) `close eval PATHS`
/// has: what `close.evaluate` partitions over an executor's workers.
#[pyfunction]
fn _eval_units(py: Python<'_>, paths: Vec<PathBuf>) -> PyResult<usize> {
    let paths = existing(paths)?;
    py.detach(|| close_io::batch::units(&paths).map(|u| u.len())).map_err(close_error)
}

/// The rows of units `indices` of `paths` (all when None), each as JSON: one worker's share.
/// `progress`: None or a callable (units done, units).
#[pyfunction]
#[pyo3(signature = (paths, indices = None, *, threads = None, method = "default", progress = None))]
fn _eval_rows(
    py: Python<'_>,
    paths: Vec<PathBuf>,
    indices: Option<Vec<usize>>,
    threads: Option<i64>,
    method: &str,
    progress: Option<&Bound<'_, PyAny>>,
) -> PyResult<Vec<String>> {
    let paths = existing(paths)?;
    let method = self::method(method)?;
    let threads = thread_count(threads)?;
    let units = py.detach(|| close_io::batch::units(&paths)).map_err(close_error)?;
    let chosen: Vec<&close_io::batch::Unit> = match indices {
        Some(indices) => indices
            .iter()
            .map(|&k| {
                units.get(k).ok_or_else(|| {
                    invalid(format!("unit {k} does not exist ({} found)", units.len()))
                })
            })
            .collect::<PyResult<_>>()?,
        None => units.iter().collect(),
    };
    let rows = run_batch(py, threads, chosen.len(), progress, |k, _| chosen[k].evaluate(method))?;
    rows_json(&rows.into_iter().flatten().collect::<Vec<_>>())
}

/// The rows of samples (or frames) `items`, each as JSON. `progress`: None or a callable
/// (items done, items).
#[pyfunction]
#[pyo3(signature = (items, *, threads = None, method = "default", progress = None))]
fn _eval_sample_rows(
    py: Python<'_>,
    items: &Bound<'_, PyAny>,
    threads: Option<i64>,
    method: &str,
    progress: Option<&Bound<'_, PyAny>>,
) -> PyResult<Vec<String>> {
    let method = self::method(method)?;
    let threads = thread_count(threads)?;
    let samples = items.try_iter()?.map(|item| sample_of(&item?)).collect::<PyResult<Vec<_>>>()?;
    let rows = run_batch(py, threads, samples.len(), progress, |k, _| {
        close_io::eval::evaluate_with(&samples[k], method)
    })?;
    rows_json(&rows)
}

/// Evaluation rows as JSON, to travel between processes.
fn rows_json(rows: &[close_io::eval::SampleResult]) -> PyResult<Vec<String>> {
    rows.iter()
        .map(|r| {
            serde_json::to_string(r).map_err(|e| invalid(format!("could not write JSON: {e}")))
        })
        .collect()
}

/// The `close eval --json` report of rows (JSON, in order).
#[pyfunction]
fn _eval_report<'py>(py: Python<'py>, rows: Vec<String>) -> PyResult<Bound<'py, PyAny>> {
    let rows = rows
        .iter()
        .map(|r| serde_json::from_str(r).map_err(|e| invalid(format!("evaluation row: {e}"))))
        .collect::<PyResult<Vec<_>>>()?;
    to_python(py, &close_io::eval::report(rows))
}

/// The `close eval` table (without `--json`) of rows (JSON, in order).
#[pyfunction]
fn _eval_table(rows: Vec<String>) -> PyResult<String> {
    let rows = rows
        .iter()
        .map(|r| serde_json::from_str(r).map_err(|e| invalid(format!("evaluation row: {e}"))))
        .collect::<PyResult<Vec<_>>>()?;
    Ok(close_io::eval::report(rows).table())
}

/// The built-in dataset's samples (`close eval --builtin`), in its order.
#[pyfunction]
fn _builtin(py: Python<'_>) -> PyResult<Vec<PySample>> {
    let dataset = py.detach(close_io::dataset::Dataset::builtin);
    Ok(dataset
        .entries()
        .iter()
        .map(|e| PySample { sample: Arc::new(e.sample.clone()), meta: Meta::default() })
        .collect())
}

/// An open VR-Folding Zarr store (or one category of it): its usable fold actions as
/// `close.Sample`s (frames: the border at the start of action 1 and at the end of each action
/// up to this one; `meta`: video_id, category, fold). `len(store)` actions; `store.dropped`
/// folds left out because a mesh they use is broken; `store.errors` videos that could not be read.
#[pyclass(frozen, module = "close.vrfolding", name = "Store")]
struct PyStore {
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
fn vrfolding_open(py: Python<'_>, store: PathBuf) -> PyResult<PyStore> {
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

/// Panics, for the test that a Rust panic becomes a Python exception (no abort).
#[pyfunction]
fn _panic_for_tests() {
    panic!("a panic raised on purpose by close._close._panic_for_tests");
}

#[pymodule]
fn _close(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("CloseError", m.py().get_type::<CloseError>())?;
    m.add("CloseWarning", m.py().get_type::<CloseWarning>())?;
    m.add_class::<PySample>()?;
    m.add_class::<PyAnalysis>()?;
    m.add_class::<PyStore>()?;
    m.add_function(wrap_pyfunction!(analyze, m)?)?;
    m.add_function(wrap_pyfunction!(analyze_many, m)?)?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(dgli_disk, m)?)?;
    m.add_function(wrap_pyfunction!(disk_layout, m)?)?;
    m.add_function(wrap_pyfunction!(interpolate, m)?)?;
    m.add_function(wrap_pyfunction!(plan, m)?)?;
    m.add_function(wrap_pyfunction!(distance, m)?)?;
    m.add_function(wrap_pyfunction!(verify, m)?)?;
    m.add_function(wrap_pyfunction!(vrfolding_open, m)?)?;
    m.add_function(wrap_pyfunction!(_eval_units, m)?)?;
    m.add_function(wrap_pyfunction!(_eval_rows, m)?)?;
    m.add_function(wrap_pyfunction!(_eval_sample_rows, m)?)?;
    m.add_function(wrap_pyfunction!(_eval_report, m)?)?;
    m.add_function(wrap_pyfunction!(_eval_table, m)?)?;
    m.add_function(wrap_pyfunction!(_builtin, m)?)?;
    m.add_function(wrap_pyfunction!(_plan_text, m)?)?;
    m.add_function(wrap_pyfunction!(to_arrays, m)?)?;
    m.add_function(wrap_pyfunction!(_check_file, m)?)?;
    m.add_function(wrap_pyfunction!(_panic_for_tests, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
