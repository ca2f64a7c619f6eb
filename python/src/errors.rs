//! The package's exceptions and warnings: `close.CloseError` with the CLI's message,
//! `close.CloseWarning` for what an analysis repaired, and a panic that stays an exception.

use pyo3::exceptions::{PyUserWarning, PyValueError};
use pyo3::prelude::*;

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
pub(crate) fn close_error(e: impl std::error::Error) -> PyErr {
    CloseError::new_err(e.to_string())
}

pub(crate) fn invalid(message: String) -> PyErr {
    close_error(close_core::Error::InvalidArgument(message))
}

/// Issue `warnings` (each with the items it concerns, when given) as `close.CloseWarning`s,
/// `stacklevel` frames up from the native call.
pub(crate) fn warn(
    py: Python<'_>,
    warnings: &[(String, Vec<usize>)],
    stacklevel: i32,
) -> PyResult<()> {
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

/// Panics, for the test that a Rust panic becomes a Python exception (no abort).
#[pyfunction]
pub(crate) fn _panic_for_tests() {
    panic!("a panic raised on purpose by close._close._panic_for_tests");
}
