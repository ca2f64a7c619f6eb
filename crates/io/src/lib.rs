//! CloSE readers: the files a user brings, the built-in dataset and the evaluation table,
//! over [`close_core`] (named by its own paths: nothing is re-exported).
//!
//! [`formats`] (Sample JSON, text/CSV, OBJ, PLY, MATLAB v5) → [`mesh`] (a mesh's border) →
//! [`dataset`] (the built-in samples) → [`eval`] (the evaluation table) → [`vrfolding`]
//! (VR-Folding Zarr stores, feature `vrfolding`: Blosc is C) → [`catalog`] (the user's
//! datasets) → [`batch`] (the units of `close eval`'s work); [`cache`] is a bounded LRU.

pub mod batch;
pub mod cache;
pub mod catalog;
pub mod dataset;
pub mod error;
pub mod eval;
pub mod formats;
pub mod mesh;
#[cfg(feature = "vrfolding")]
pub mod vrfolding;

pub use formats::Sample;
