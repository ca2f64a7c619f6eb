//! The user's files: `close.load`, and the paths other calls are given (a missing file
//! is `FileNotFoundError`, as Python's own calls raise it).

use std::path::PathBuf;

use close_io::formats::MAX_FILE_BYTES;
use pyo3::exceptions::{PyFileNotFoundError, PyOSError};
use pyo3::prelude::*;

use crate::errors::{close_error, invalid};
use crate::sample::{Meta, PySample};

/// A user's file as an OS error of Python's (a missing file is `FileNotFoundError`).
pub(crate) fn os_error(name: &str) -> impl Fn(std::io::Error) -> PyErr + '_ {
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
pub(crate) fn _check_file(path: PathBuf) -> PyResult<String> {
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
pub(crate) fn read(path: &PathBuf) -> PyResult<(String, Vec<u8>)> {
    let name = _check_file(path.clone())?;
    let bytes = std::fs::read(path).map_err(os_error(&name))?;
    Ok((name, bytes))
}

/// Read a sample from files, as `close analyze FILE...` does: one Sample JSON or MATLAB .mat
/// file, one text/CSV file per frame, or one OBJ/PLY mesh per frame. A missing file raises
/// FileNotFoundError; a file that cannot be parsed, `close.CloseError`.
#[pyfunction]
#[pyo3(signature = (*paths))]
pub(crate) fn load(paths: Vec<PathBuf>) -> PyResult<PySample> {
    let files = paths.iter().map(read).collect::<PyResult<Vec<_>>>()?;
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
