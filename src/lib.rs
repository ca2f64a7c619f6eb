//! CloSE: a geometric, shape-agnostic cloth state representation.
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
//! The data flows one way, and the modules follow it:
//! [`formats`] (files) → [`mesh`] (a mesh's border) → [`border`] (validation,
//! normalisation) → [`gli`] → [`disk`] (the dGLI disk) → [`fold`] (fold coordinates) →
//! [`close`] (corners, the CloSE value) → [`label`] / [`plan`] / [`interpolate`] →
//! [`analysis`] (the whole pipeline) → [`metrics`] / [`eval`] → [`render`] → [`server`].
//!
//! ```
//! use close::{analyze, FrameRange, Sample};
//! // A square napkin folded in half along its diagonal from vertex 0 to vertex 2.
//! let json = r#"{"name": "napkin", "category": "napkin", "frames": [
//!     [[0,0,0],[1,0,0],[1,1,0],[0,1,0]],
//!     [[0,0,0],[0,1,0.01],[1,1,0],[0,1,0]]]}"#;
//! let sample: Sample = close::formats::json::parse_sample(json.as_bytes())?;
//! let analysis = analyze(&sample.border_frames()?, FrameRange::default())?;
//! assert_eq!(analysis.n, 4);
//! assert_eq!(analysis.close.folds.len(), analysis.folds.len());
//! # Ok::<(), close::Error>(())
//! ```

pub mod analysis;
pub mod batch;
pub mod catalog;
pub mod angle;
pub mod border;
pub mod cache;
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
#[cfg(feature = "vrfolding")]
pub mod vrfolding;

pub use analysis::{analyze, analyze_with, Analysis, FrameRange, Options};
pub use fold::FoldMethod;
pub use error::{Error, Result};
pub use formats::Sample;
