//! `close.Analysis` and `close.analyze`: the library's analysis of a sample, its getters,
//! JSON and pickling (an unpickled one redone from its frames when needed).

use std::sync::{Arc, OnceLock};

use close_core::border::BorderFrames;
use close_core::budget::{Budget, Deadline};
use close_core::{Analysis, FoldMethod, FrameRange, Options};
use close_io::formats::Sample;
use numpy::ndarray::Array1;
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyBytes;

use crate::convert::{points_array, to_python};
use crate::errors::{close_error, invalid, warn};
use crate::sample::sample_of;
use crate::threads::wait_for;

/// The result of `close.analyze`: the CloSE value of the end state, its label, the predicted
/// end border and its metrics. Angles in radians in [0, 2π), vertex k at 2πk/N; each fold
/// (f1, f2) has its folded side anticlockwise from f1 to f2. `to_dict()` is the object that
/// `close analyze --json` prints, key for key.
#[pyclass(frozen, module = "close", name = "Analysis")]
pub(crate) struct PyAnalysis {
    /// The analysis, whose fields the getters read. One unpickled is read back from its
    /// JSON, which has no frames: `redone` then holds it redone from `redo`.
    pub(crate) analysis: Arc<Analysis>,
    /// How its folds were found, so that it can be redone exactly.
    method: FoldMethod,
    /// An unpickled analysis's border frames as the pickle carried them.
    redo: Option<BorderFrames>,
    /// The unpickled analysis redone from `redo` (with its frames), when first needed.
    redone: OnceLock<Arc<Analysis>>,
}

impl PyAnalysis {
    pub(crate) fn of(analysis: Analysis, method: FoldMethod) -> Self {
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
    pub(crate) fn analysis(&self, py: Python<'_>) -> PyResult<Arc<Analysis>> {
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
    pub(crate) fn warnings(&self) -> Vec<String> {
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
    pub(crate) fn n(&self) -> usize {
        self.analysis.n
    }

    /// Corner angles θ_1 < … < θ_n (radians; vertex k at 2πk/N).
    #[getter]
    pub(crate) fn corners(&self) -> Vec<f64> {
        self.analysis.corners.clone()
    }

    /// One (f1, f2) per detected fold, in order; the folded side runs anticlockwise from f1 to f2.
    #[getter]
    pub(crate) fn folds(&self) -> Vec<(f64, f64)> {
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
pub(crate) fn analysis_of(
    sample: &Sample,
    options: &Options,
) -> Result<Analysis, close_core::Error> {
    sample.check_budget(options.frames, &options.budget)?;
    close_core::analyze_with(&sample.border_frames()?, options.clone())
}

/// What `close.analyze` does with the GIL released: the analysis and its JSON.
pub(crate) fn analyze_sample(
    sample: &Sample,
    options: &Options,
) -> Result<PyAnalysis, close_core::Error> {
    analysis_of(sample, options).map(|a| PyAnalysis::of(a, options.method))
}

pub(crate) fn options(
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

/// The fold method named `name`: "default", or a name `close analyze --method` takes.
pub(crate) fn method(name: &str) -> PyResult<FoldMethod> {
    if name == "default" {
        return Ok(FoldMethod::default());
    }
    serde_json::from_value(serde_json::Value::String(name.into())).map_err(|_| {
        invalid(format!("unknown method {name:?}: expected \"default\", \"cut\" or \"paper\""))
    })
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
pub(crate) fn analyze(
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

/// The analysis of `obj`: a `close.Analysis` (an unpickled one is redone from its frames),
/// or a `close.Sample` (or frames) analysed first → last, with the GIL released.
pub(crate) fn analysis_for(py: Python<'_>, obj: &Bound<'_, PyAny>) -> PyResult<Arc<Analysis>> {
    match obj.cast::<PyAnalysis>() {
        Ok(a) => a.get().analysis(py),
        Err(_) => {
            let sample = sample_of(obj)?;
            let options = options("default", None, None, close_core::DEFAULT_MAX_FOLDS)?;
            py.detach(|| analysis_of(&sample, &options)).map(Arc::new).map_err(close_error)
        }
    }
}
