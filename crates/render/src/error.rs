//! The error type of close-render: a picture or recording that could not be made, beside
//! the library's own errors (an analysis frame or an argument that does not exist).
//!
//! ```
//! use close_render::error::Error;
//! let e = Error::Render("the embedded font could not be loaded".into());
//! assert!(!e.is_input_fault());
//! assert!(Error::invalid("no such picture".into()).is_input_fault());
//! ```

use thiserror::Error;

/// Why a picture or a recording could not be made.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum Error {
    /// The input or the request is wrong (an HTTP layer answers 4xx).
    #[error(transparent)]
    Core(#[from] close_core::Error),
    /// A picture could not be drawn or encoded: a bug, not a bad input.
    #[error("could not draw the picture: {0}")]
    Render(String),
    /// A recording could not be written (feature `rerun`): a bug, not a bad input.
    #[error("recording failed: {0}")]
    Recording(String),
}

/// Shorthand used across the crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

impl Error {
    /// An argument out of range or inconsistent ([`close_core::Error::InvalidArgument`]).
    pub fn invalid(message: String) -> Self {
        Error::Core(close_core::Error::InvalidArgument(message))
    }

    /// True when the input is at fault (a 4xx), false for the crate's own failures.
    pub fn is_input_fault(&self) -> bool {
        matches!(self, Error::Core(_))
    }
}
