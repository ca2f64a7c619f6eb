//! The one error type of the library: every way an input can be wrong, named plainly.

use thiserror::Error;

/// Why an input could not be turned into a CloSE analysis.
///
/// Each variant names the problem so a user can fix the file; none is ever a panic.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum Error {
    /// The file or body could not be parsed in the expected format.
    #[error("could not parse {format}: {message}")]
    Parse { format: &'static str, message: String },
    /// The sample holds no frame, or a frame holds no vertex.
    #[error("empty input: {0}")]
    Empty(String),
    /// Fewer vertices than a closed border needs.
    #[error("too few vertices: a border needs at least {min}, got {got}")]
    TooFewVertices { got: usize, min: usize },
    /// More vertices or frames than the configured limit.
    #[error("input too large: {0}")]
    TooLarge(String),
    /// A coordinate is NaN or infinite.
    #[error("non-finite coordinate in frame {frame}, vertex {vertex}")]
    NonFinite { frame: usize, vertex: usize },
    /// Frames disagree on the vertex count.
    #[error("frame {frame} has {got} vertices but frame 0 has {expected}")]
    FrameSizeMismatch { frame: usize, expected: usize, got: usize },
    /// The border cannot be a cloth outline (collinear, coincident, zero area, …).
    #[error("degenerate border: {0}")]
    Degenerate(String),
    /// A request names something that does not exist or an argument out of range.
    #[error("invalid argument: {0}")]
    InvalidArgument(String),
    /// A mesh could not give a border (no boundary, out-of-range face, …).
    #[error("mesh problem: {0}")]
    Mesh(String),
    /// A recording could not be written (feature `rerun`).
    #[error("recording failed: {0}")]
    Recording(String),
    /// A picture could not be drawn or encoded (a bug, not a bad input).
    #[error("could not draw the picture: {0}")]
    Render(String),
    /// The estimated work is over a [`crate::budget::Budget`] limit (refused before starting).
    #[error("too much work: {what} is {got}, over the limit of {limit}")]
    OverBudget { what: &'static str, got: u64, limit: u64 },
    /// The job was stopped by its [`crate::budget::Deadline`] (time-out or cancelled request).
    #[error("the work was stopped: it ran past its deadline or its request went away")]
    Cancelled,
}

/// Shorthand used across the crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

impl Error {
    pub(crate) fn parse(format: &'static str, message: impl ToString) -> Self {
        Error::Parse { format, message: message.to_string() }
    }
}
