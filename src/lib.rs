//! CloSE: a geometric, shape-agnostic cloth state representation.
//!
//! From a cloth's border before and after a fold this crate computes the dGLI disks
//! ([`disk`]), the corners and fold coordinates ([`close`], [`fold`]), a plain-words label
//! ([`label`]), the predicted folded border and its error ([`metrics`]); [`analysis`] runs
//! the whole pipeline.

pub mod analysis;
pub mod angle;
pub mod border;
pub mod budget;
pub mod close;
pub mod dataset;
pub mod disk;
pub mod error;
pub mod eval;
pub mod fold;
pub mod formats;
pub mod gli;
pub mod interpolate;
pub mod label;
pub mod mesh;
pub mod metrics;
pub mod plan;
#[cfg(feature = "rerun")]
pub mod record;
pub mod render;
pub mod rng;
pub mod server;

pub use analysis::{analyze, analyze_with, Analysis, FrameRange, Options};
pub use fold::FoldMethod;
pub use error::{Error, Result};
pub use formats::Sample;
