//! CloSE: a geometric, shape-agnostic cloth state representation — the maths.
//!
//! This crate implements the representation of
//! Kamat, Borràs and Torras, *"CloSE: A Geometric Shape-Agnostic Cloth State
//! Representation"*: a cloth is described by its border, a closed polyline listed
//! anticlockwise seen from above. The dGLI (the derivative of Levitt's Gauss linking
//! integral of two border edges under a vertical lift) of every pair of edges is laid out on
//! a disk; the disk's rim holds the corners, and the change between the disks before and
//! after a fold shows where the fold is. The CloSE value of a state is its corner angles and
//! one pair of fold coordinates (f1, f2) per fold, all angles on the border circle (vertex k
//! of N at 2πk/N).
//!
//! It depends on nothing async, nothing web, no plotting and no C code: the readers
//! (`close-io`), the pictures (`close-render`), the web app (`close-server`) and the `close`
//! binary are crates of their own above it.
//!
//! The modules import one way; each uses only those to its left: [`border`] (validation,
//! normalisation) → [`geometry`] (fold, arc, line) → [`gli`] → [`disk`] (the dGLI disk) → [`fold`] (fold coordinates, a fold
//! applied) → [`close`] (corners, the CloSE value) / [`label`] / [`metrics`] / [`confidence`] /
//! [`interpolate`] → [`analysis`] (the whole pipeline) → [`plan`]. Below them all: [`angle`],
//! [`error`], [`budget`], [`rng`].
//! `tests/it/modules.rs` keeps the imports inside this crate one-way.
//!
//! ```
//! use close_core::{analyze, border, FrameRange};
//! // A square napkin folded in half along its diagonal from vertex 0 to vertex 2.
//! let start = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
//! let end = vec![[0.0, 0.0, 0.0], [0.0, 1.0, 0.01], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
//! // Validated as every route validates a border: finite, matching frames, not degenerate.
//! let frames = border::prepare(vec![start, end])?;
//! let analysis = analyze(&frames, FrameRange::default())?;
//! assert_eq!(analysis.n, 4);
//! assert_eq!(analysis.close.folds.len(), analysis.folds.len());
//! # Ok::<(), close_core::Error>(())
//! ```

pub mod analysis;
pub mod angle;
pub mod border;
pub mod budget;
pub mod close;
pub mod confidence;
pub mod disk;
pub mod distance;
pub mod error;
pub mod fold;
pub mod geometry;
pub mod gli;
pub mod interpolate;
pub mod label;
pub mod metrics;
pub mod plan;
pub mod rng;
pub mod verify;

pub use analysis::{analyze, analyze_with, Analysis, FrameRange, Options, DEFAULT_MAX_FOLDS};
pub use error::{Error, Result};
pub use fold::FoldMethod;
pub use geometry::{Arc, Fold, Folding, Line};
