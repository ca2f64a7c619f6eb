//! `close.evaluate`'s native half: `close eval`'s units, rows and report, which the Python
//! side spreads over threads or an executor's workers.

use std::path::PathBuf;
use std::sync::Arc;

use pyo3::prelude::*;

use crate::analysis::method;
use crate::convert::to_python;
use crate::errors::{close_error, invalid};
use crate::files::existing;
use crate::sample::{sample_of, Meta, PySample};
use crate::threads::{run_batch, thread_count};

/// How many units of work (`.json` files, videos of VR-Folding stores) `close eval PATHS`
/// has: what `close.evaluate` partitions over an executor's workers.
#[pyfunction]
pub(crate) fn _eval_units(py: Python<'_>, paths: Vec<PathBuf>) -> PyResult<usize> {
    let paths = existing(paths)?;
    py.detach(|| close_io::batch::units(&paths).map(|u| u.len())).map_err(close_error)
}

/// The rows of units `indices` of `paths` (all when None), each as JSON: one worker's share.
/// `progress`: None or a callable (units done, units).
#[pyfunction]
#[pyo3(signature = (paths, indices = None, *, threads = None, method = "default", progress = None))]
pub(crate) fn _eval_rows(
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
pub(crate) fn _eval_sample_rows(
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
pub(crate) fn rows_json(rows: &[close_io::eval::SampleResult]) -> PyResult<Vec<String>> {
    rows.iter()
        .map(|r| {
            serde_json::to_string(r).map_err(|e| invalid(format!("could not write JSON: {e}")))
        })
        .collect()
}

/// The `close eval --json` report of rows (JSON, in order).
#[pyfunction]
pub(crate) fn _eval_report<'py>(py: Python<'py>, rows: Vec<String>) -> PyResult<Bound<'py, PyAny>> {
    let rows = rows
        .iter()
        .map(|r| serde_json::from_str(r).map_err(|e| invalid(format!("evaluation row: {e}"))))
        .collect::<PyResult<Vec<_>>>()?;
    to_python(py, &close_io::eval::report(rows))
}

/// The `close eval` table (without `--json`) of rows (JSON, in order).
#[pyfunction]
pub(crate) fn _eval_table(rows: Vec<String>) -> PyResult<String> {
    let rows = rows
        .iter()
        .map(|r| serde_json::from_str(r).map_err(|e| invalid(format!("evaluation row: {e}"))))
        .collect::<PyResult<Vec<_>>>()?;
    Ok(close_io::eval::report(rows).table())
}

/// The built-in dataset's samples (`close eval --builtin`), in its order.
#[pyfunction]
pub(crate) fn _builtin(py: Python<'_>) -> PyResult<Vec<PySample>> {
    let dataset = py.detach(close_io::dataset::Dataset::builtin);
    Ok(dataset
        .entries()
        .iter()
        .map(|e| PySample { sample: Arc::new(e.sample.clone()), meta: Meta::default() })
        .collect())
}
