//! CloSE pictures: the dGLI disks, borders and fold circles drawn with plotters (PNG and
//! SVG), and Rerun recordings (feature `rerun`), over [`close_io`] (re-exported whole).

pub use close_io::*;

pub mod render;
#[cfg(feature = "rerun")]
pub mod record;
