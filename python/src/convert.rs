//! Python values in and out: numpy arrays ↔ border points and frames, and the library's
//! JSON objects ↔ Python objects (through `json`, so a dict is what the CLI prints).

use numpy::ndarray::{Array2, Array3};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArray3, PyReadonlyArrayDyn};
use pyo3::prelude::*;
use pyo3::types::{IntoPyDict, PyList, PyTuple};

use crate::errors::{close_error, invalid};

/// A JSON value of the library as the Python object `json.loads` makes of it.
pub(crate) fn to_python<'py>(
    py: Python<'py>,
    value: &impl serde::Serialize,
) -> PyResult<Bound<'py, PyAny>> {
    let text =
        serde_json::to_string(value).map_err(|e| invalid(format!("could not write JSON: {e}")))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// A Python object (a dict of a truth, …) as JSON, through `json.dumps`.
pub(crate) fn from_python<T: serde::de::DeserializeOwned>(
    value: &Bound<'_, PyAny>,
    what: &str,
) -> PyResult<T> {
    let text: String = value.py().import("json")?.call_method1("dumps", (value,))?.extract()?;
    serde_json::from_str(&text).map_err(|e| invalid(format!("{what}: {e}")))
}

/// A numpy float64 array of anything array-like.
pub(crate) fn float_array<'py>(obj: &Bound<'py, PyAny>) -> PyResult<PyReadonlyArrayDyn<'py, f64>> {
    let numpy = obj.py().import("numpy")?;
    let kwargs = [("dtype", numpy.getattr("float64")?)].into_py_dict(obj.py())?;
    let array = numpy
        .call_method("asarray", (obj,), Some(&kwargs))
        .map_err(|e| invalid(format!("not an array of numbers: {e}")))?;
    array.extract()
}

/// A row of 3 coordinates, or of 2 (x, y on the table: z = 0, as 2-D contour extraction
/// gives them).
pub(crate) fn point(row: numpy::ndarray::ArrayView1<'_, f64>) -> [f64; 3] {
    [row[0], row[1], row.get(2).copied().unwrap_or(0.0)]
}

/// One border state, an (N, 3) array-like of x, y, z, or (N, 2) of x, y (z = 0); `what`
/// names it in errors.
pub(crate) fn points(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<[f64; 3]>> {
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
pub(crate) fn frames(obj: &Bound<'_, PyAny>) -> PyResult<Vec<Vec<[f64; 3]>>> {
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
pub(crate) fn frames_array<'py>(
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
pub(crate) type Floats<'py> = Bound<'py, PyArray1<f64>>;

pub(crate) fn points_array<'py>(py: Python<'py>, points: &[[f64; 3]]) -> Bound<'py, PyArray2<f64>> {
    Array2::from_shape_fn((points.len(), 3), |(k, c)| points[k][c]).into_pyarray(py)
}
