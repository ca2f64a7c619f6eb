//! The user's files: read as the CLI reads them (`close.load`, and numpy's files through
//! `_read_file`), and the paths other calls are given; a missing file is
//! `FileNotFoundError`, as Python's own calls raise it.

use std::path::{Path, PathBuf};

use close_io::formats::ReadError;
use pyo3::exceptions::{PyFileNotFoundError, PyOSError};
use pyo3::prelude::*;
use pyo3::types::PyBytes;

use crate::errors::{close_error, invalid};
use crate::sample::{Meta, PySample};

/// The system's error about a user's file as Python's own `OSError` would be: the subclass
/// its errno gives (`FileNotFoundError`, `IsADirectoryError`, `PermissionError`, …, as
/// `OSError(errno, strerror, filename)` picks it), with the file's name.
fn os_error(name: &str, e: &std::io::Error) -> PyErr {
    let args = (e.raw_os_error().unwrap_or(0), e.to_string(), name.to_string());
    match e.kind() {
        // Without an errno (not from the system), still the subclass of a missing file.
        std::io::ErrorKind::NotFound => PyFileNotFoundError::new_err(args),
        _ => PyOSError::new_err(args),
    }
}

/// A user's file's bytes, read as the CLI reads them ([`close_io::formats::read_file`]: a
/// regular file only, opened non-blocking, never more than the readers' byte cap). A missing
/// file, a folder or one without permission is the matching `OSError`; a VR-Folding store,
/// a FIFO, a device or a file over the cap is `close.CloseError` with the CLI's message.
/// Its name, for errors, and its bytes.
pub(crate) fn read(path: &Path) -> PyResult<(String, Vec<u8>)> {
    let name = path.display().to_string();
    if close_io::vrfolding::is_store(path) {
        return Err(invalid(format!(
            "{name} is a VR-Folding Zarr store: open it with close.vrfolding.open"
        )));
    }
    match close_io::formats::read_file_io(path) {
        Ok(bytes) => Ok((name, bytes)),
        Err(ReadError::Os { path, error }) => Err(os_error(&path, &error)),
        Err(ReadError::Refused(e)) => Err(close_error(e)),
    }
}

/// A user's file's bytes as [`read`] reads them, for the Python side's own readers (numpy's).
#[pyfunction]
pub(crate) fn _read_file(py: Python<'_>, path: PathBuf) -> PyResult<Bound<'_, PyBytes>> {
    let (_, bytes) = py.detach(|| read(&path))?;
    Ok(PyBytes::new(py, &bytes))
}

/// Read a sample from files, as `close analyze FILE...` does: one Sample JSON or MATLAB .mat
/// file, one text/CSV file per frame, or one OBJ/PLY mesh per frame. A missing file raises
/// FileNotFoundError; a file that cannot be parsed, `close.CloseError`.
#[pyfunction]
#[pyo3(signature = (*paths))]
pub(crate) fn load(py: Python<'_>, paths: Vec<PathBuf>) -> PyResult<PySample> {
    let files = py.detach(|| paths.iter().map(|p| read(p)).collect::<PyResult<Vec<_>>>())?;
    let sample = close_io::formats::read_files(&files).map_err(close_error)?;
    PySample::checked(sample, Meta::default())
}

/// The paths of `close.evaluate`, each of which must exist.
pub(crate) fn existing(paths: Vec<PathBuf>) -> PyResult<Vec<PathBuf>> {
    match paths.iter().find(|p| !p.exists()) {
        Some(p) => Err(PyFileNotFoundError::new_err((
            2,
            "No such file or directory",
            p.display().to_string(),
        ))),
        None => Ok(paths),
    }
}
