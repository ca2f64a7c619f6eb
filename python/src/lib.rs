//! `close._close`: the native half of the Python package `close`.
//!
//! A thin layer: every number comes from the `close` library (the same functions as the CLI
//! and the server), nothing is computed here. What it does is convert — numpy arrays
//! in and out, the library's JSON objects as Python dicts (through `json.loads`, so
//! `Analysis.to_dict()` is exactly what `close analyze --json` prints) — map errors
//! (`close_core::Error` → `close.CloseError` with the CLI's message; a missing file →
//! `FileNotFoundError`), apply the server's input limits ([`close_core::budget::Budget::SERVER`]; the readers'
//! and [`close_core::border::prepare`]'s own limits hold everywhere), and release the GIL
//! around the work. A Rust panic unwinds into `pyo3_runtime.PanicException` (the release
//! profile keeps `panic = "unwind"`).
//!
//! One module an idea: [`errors`] (the exceptions), [`convert`] (numpy and JSON in and out),
//! [`sample`] (`close.Sample`), [`analysis`] (`close.Analysis`, `close.analyze`), [`threads`]
//! (work with the GIL released), [`batch`] (`analyze_many`, `to_arrays`), [`eval`]
//! (`close.evaluate`), [`files`] (the user's files), [`disk`] (the dGLI disk), [`plan`]
//! (interpolate, plan, verify, distance), [`store`] (VR-Folding stores).

mod analysis;
mod batch;
mod convert;
mod disk;
mod errors;
mod eval;
mod files;
mod plan;
mod sample;
mod store;
mod threads;

use pyo3::prelude::*;

#[pymodule]
fn _close(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("CloseError", m.py().get_type::<errors::CloseError>())?;
    m.add("CloseWarning", m.py().get_type::<errors::CloseWarning>())?;
    m.add_class::<sample::PySample>()?;
    m.add_class::<analysis::PyAnalysis>()?;
    m.add_class::<store::PyStore>()?;
    m.add_function(wrap_pyfunction!(analysis::analyze, m)?)?;
    m.add_function(wrap_pyfunction!(batch::analyze_many, m)?)?;
    m.add_function(wrap_pyfunction!(files::load, m)?)?;
    m.add_function(wrap_pyfunction!(disk::dgli_disk, m)?)?;
    m.add_function(wrap_pyfunction!(disk::disk_layout, m)?)?;
    m.add_function(wrap_pyfunction!(plan::interpolate, m)?)?;
    m.add_function(wrap_pyfunction!(plan::plan, m)?)?;
    m.add_function(wrap_pyfunction!(plan::distance, m)?)?;
    m.add_function(wrap_pyfunction!(plan::verify, m)?)?;
    m.add_function(wrap_pyfunction!(store::vrfolding_open, m)?)?;
    m.add_function(wrap_pyfunction!(eval::_eval_units, m)?)?;
    m.add_function(wrap_pyfunction!(eval::_eval_rows, m)?)?;
    m.add_function(wrap_pyfunction!(eval::_eval_sample_rows, m)?)?;
    m.add_function(wrap_pyfunction!(eval::_eval_report, m)?)?;
    m.add_function(wrap_pyfunction!(eval::_eval_table, m)?)?;
    m.add_function(wrap_pyfunction!(eval::_builtin, m)?)?;
    m.add_function(wrap_pyfunction!(plan::_plan_text, m)?)?;
    m.add_function(wrap_pyfunction!(batch::to_arrays, m)?)?;
    m.add_function(wrap_pyfunction!(files::_read_file, m)?)?;
    m.add_function(wrap_pyfunction!(errors::_panic_for_tests, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
