//! `close`: the CloSE cloth-state representation as one library, the facade over the
//! workspace's crates, which the `close` binary, the tests and the benchmarks use.
//!
//! - [`close_core`]: the maths (border, geometry, gli, disk, fold, close, label, plan,
//!   interpolate, metrics, analysis, distance, verify), with no web, async, plotting or C dependency;
//! - [`close_io`]: the readers, the built-in dataset, the evaluation, VR-Folding stores;
//! - [`close_render`]: the pictures and Rerun recordings;
//! - [`close_server`]: the web app.
//!
//! This facade re-exports their modules by name, so every module is reachable here under one
//! name: `close::fold` (close-core), `close::formats` (close-io), `close::render` (the
//! close-render crate), `close::server` (the close-server crate).
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
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub use close_core::{
    analysis, analyze, analyze_with, angle, border, budget, close, disk, distance, error, fold,
    geometry, gli, interpolate, label, metrics, plan, rng, verify, Analysis, Arc, Error, Fold,
    FoldMethod, Folding, FrameRange, Line, Options, Result, DEFAULT_MAX_FOLDS,
};
/// What reading files, datasets and stores fails with ([`close_io::error`]).
pub use close_io::error as io_error;
#[cfg(feature = "vrfolding")]
pub use close_io::vrfolding;
pub use close_io::{batch, cache, catalog, dataset, eval, formats, mesh, Sample};
pub use close_render as render;
#[cfg(feature = "rerun")]
pub use close_render::record;
pub use close_server as server;
