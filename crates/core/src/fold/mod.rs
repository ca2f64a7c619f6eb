//! Fold coordinates from the dGLI disks (Kamat, Borràs, Torras, "CloSE", Sec. III-C).
//!
//! One step (start state → end state) is read from the abs diff disk
//! g = | |end| − |start| |. The paper fits fold curves with its loss ([`loss`], [`fit`]);
//! its free fit is kept as [`FoldMethod::Paper`], and the curves of every fold found are
//! fitted through its points, for drawing. By default, on a flat start the
//! cut of least same-side change ([`cut`]) says which edges turned over, to half an edge,
//! the signed diff Δ = end − start orders its points ([`orientation`]), and analysis by
//! synthesis on the disks ([`synth`]) places each fold point within its edge. On a stacked
//! start (an earlier fold) the cut loses its footing and `synth::search_line` tries lines
//! instead. A step whose diff disk is flat, whose change has no side to it, or that no
//! candidate fold explains, has no fold.
//!
//! Honesty rule: the fold is read from the disks only. The step's start border is used to
//! synthesise the disks of candidate folds; the end border's coordinates are never read.

pub mod cut;
pub mod fit;
pub mod loss;
pub mod orientation;
pub mod params;
mod read;
mod refine;
pub mod reflect;
mod seed;
pub mod sequence;
pub mod state;
pub mod synth;

pub use cut::Cut;
pub use fit::Curve;
pub use orientation::Orientation;
pub use params::Params;
pub use read::{read, Reading};
pub use reflect::apply;
pub use seed::{Evidence, FoldDetection, FoldMethod};
pub use synth::Synthesis;
