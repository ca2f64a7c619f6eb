//! The error type of close-io: what reading files, datasets and stores adds to the
//! library's own errors (a border the analysis refuses is still [`close_core::Error`]).
//!
//! ```
//! use close_io::error::{Error, Format};
//! let e = Error::parse_at(Format::Text, 3, "expected 3 numbers").in_file("dir/a.txt");
//! assert_eq!(e.to_string(), "a.txt: could not parse text at line 3: expected 3 numbers");
//! assert!(matches!(e.cause(), Error::Parse { line: Some(3), .. }));
//! ```

use std::fmt;

use thiserror::Error;

/// Why a sample, a dataset entry or a store could not be read. Every variant is an input
/// fault: the file, the store or the id asked for is wrong.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum Error {
    /// The input reads but is not a usable sample (too large, degenerate, …).
    #[error(transparent)]
    Core(#[from] close_core::Error),
    /// The file or body could not be parsed in the expected format.
    #[error("could not parse {format}{}: {reason}", AtLine(*.line))]
    Parse { format: Format, line: Option<usize>, reason: String },
    /// A dataset entry asked for by id does not exist.
    #[error("no sample {id:?} in the datasets")]
    UnknownSample { id: String },
    /// A VR-Folding Zarr store (or one of its groups or arrays) is missing, malformed or
    /// unreadable; `path` is the group or array inside the store.
    #[error("VR-Folding store {store}, {path}: {problem}")]
    Store { store: String, path: String, problem: String },
    /// One of several files is at fault: its name, then the cause.
    #[error("{file}: {error}")]
    InFile { file: String, error: Box<Error> },
}

/// Shorthand used across the crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// The file formats the readers parse.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    SampleJson,
    Text,
    Obj,
    Ply,
    Mat,
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Format::SampleJson => "sample JSON",
            Format::Text => "text",
            Format::Obj => "OBJ",
            Format::Ply => "PLY",
            Format::Mat => "MATLAB .mat",
        })
    }
}

/// " at line N" when the line is known.
struct AtLine(Option<usize>);

impl fmt::Display for AtLine {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            Some(line) => write!(f, " at line {line}"),
            None => Ok(()),
        }
    }
}

impl From<close_core::error::MeshError> for Error {
    fn from(e: close_core::error::MeshError) -> Self {
        Error::Core(e.into())
    }
}

impl Error {
    /// An argument out of range or inconsistent ([`close_core::Error::InvalidArgument`]).
    pub fn invalid(message: String) -> Self {
        Error::Core(close_core::Error::InvalidArgument(message))
    }

    /// Too many of `what` ([`close_core::Error::too_large`]).
    pub fn too_large(what: &'static str, got: usize, limit: usize) -> Self {
        Error::Core(close_core::Error::too_large(what, got, limit))
    }

    /// More than `limit` of `what` ([`close_core::Error::over_limit`]).
    pub fn over_limit(what: &'static str, limit: usize) -> Self {
        Error::Core(close_core::Error::over_limit(what, limit))
    }

    /// A parse error with no line number.
    pub fn parse(format: Format, reason: impl ToString) -> Self {
        Error::Parse { format, line: None, reason: reason.to_string() }
    }

    /// A parse error at a 1-based line.
    pub fn parse_at(format: Format, line: usize, reason: impl ToString) -> Self {
        Error::Parse { format, line: Some(line), reason: reason.to_string() }
    }

    /// This error, said to come from file `path` (its name without folders). A cause
    /// that already names a file keeps it.
    pub fn in_file(self, path: &str) -> Self {
        match self {
            already @ Error::InFile { .. } => already,
            error => {
                let file = path.rsplit(['/', '\\']).next().unwrap_or(path).to_string();
                Error::InFile { file, error: Box::new(error) }
            }
        }
    }

    /// The cause, through any [`Error::InFile`] wrapping.
    pub fn cause(&self) -> &Error {
        match self {
            Error::InFile { error, .. } => error.cause(),
            other => other,
        }
    }
}
