//! Fold coordinates from the dGLI disks (Kamat, Borràs, Torras, "CloSE", Sec. III-C), read
//! by one search ([`read`]).
//!
//! A step (start state → end state) is seeded with the one fold its abs diff disk
//! g = | |end| − |start| | points to: on a flat start the cut of least same-side change
//! (`cut`) says which edges turned over, to half an edge, the signed diff Δ = end − start
//! orders its points (`orientation`), and analysis by synthesis on the disks (`synth`)
//! places each fold point within its edge; on a stacked start (an earlier fold) the cut
//! loses its footing and a line search tries lines instead; [`FoldMethod::Paper`] keeps the
//! paper's free fit of fold curves (`loss`, `fit`). When that fold leaves the end disk
//! unexplained, fold sequences are searched ([`sequence`]), each made on the synthesised
//! state of the step's start ([`state`]) and refined alike. A step whose diff disk is flat,
//! whose change has no side to it, or that no candidate fold explains, has no fold. The
//! search's knobs are [`params`].
//!
//! Honesty rule: the fold is read from the disks only. The step's start border is used to
//! synthesise the disks of candidate folds; the end border's coordinates are never read.

mod cut;
mod fit;
#[cfg(test)]
mod fixtures;
mod line_search;
mod loss;
mod orientation;
pub mod params;
mod probe;
mod read;
mod refine;
mod reflect;
mod seed;
pub mod sequence;
pub mod state;
mod synth;

pub use cut::Cut;
pub use fit::Curve;
pub use orientation::Orientation;
pub use params::Params;
pub use read::{read, Reading};
pub use reflect::apply;
pub use seed::{Evidence, FoldDetection, FoldMethod};
pub use synth::Synthesis;
