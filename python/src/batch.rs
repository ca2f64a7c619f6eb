//! `close.analyze_many` (its native half) and `close.to_arrays`: many samples at once.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

use close_core::Options;
use close_io::formats::Sample;
use numpy::ndarray::{Array2, Array3};
use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::analysis::{analyze_sample, options, PyAnalysis};
use crate::errors::{invalid, warn, CloseError};
use crate::sample::sample_of;
use crate::threads::{run_batch, thread_count};

/// `close.analyze` of every item: what `close.analyze_many` (the Python function, which
/// turns `progress=True` into a bar) calls. `progress`: None or a callable (done, total).
/// With `errors="return"` a failing item's place holds its `close.CloseError`; with
/// "raise" the first failing item (the lowest index) raises, naming its index.
#[pyfunction]
#[pyo3(signature = (items, *, threads = None, method = "default", progress = None, errors = "raise"))]
pub(crate) fn analyze_many<'py>(
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
pub(crate) fn to_arrays<'py>(
    py: Python<'py>,
    results: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
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
