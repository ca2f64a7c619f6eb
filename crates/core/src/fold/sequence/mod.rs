//! Fold sequences in one step: the folds that took a flat cloth to a state whose disk alone
//! is seen.
//!
//! Our extension of CloSE, after the paper's "Multi-folds" section (Kamat, Borràs, Torras,
//! "CloSE"): the diff disk of two folds seen at once holds the lines of both. A cloth folded
//! k times, seen flat and folded with no frame between, is read as a sequence of folds, each
//! made on the state the ones before it left: later folds cross stacked layers and may turn
//! several arcs of the border at once.
//!
//! **Where the creases meet the border.** Folds of a flat cloth move each piece between the creases
//! rigidly, so a pair of edges of one piece keeps |dGLI|: a border arc inside one piece holds no
//! change of the abs diff disk g. The border split into m arcs of least change within themselves
//! (`super::cut::find_cuts`) puts its m cut points where the creases meet the border. Straight
//! sides hold no change at all (collinear edges have dGLI 0 before and after), so a split at a
//! corner would cost nothing: each pair's change is offset by
//! [`CutParams::start_share`](crate::fold::params::CutParams::start_share) times its start |dGLI|,
//! which favours arcs whose pairs could have shown a change.
//!
//! **Analysis by synthesis.** Each fold of a candidate sequence is a line on the state it is
//! made on, through two cut points where they lie on that state, or through one in a
//! searched direction where two coincide (stacked layers) or, for the first fold, through
//! one alone (a crease can meet a straight side where no cut shows it), directions taken
//! in the cloth's frame, and the arcs of the border left
//! of it that turn over: all of them, or the one holding a given vertex (a fold of the top
//! layer only). The folds are made in turn (`super::synth`: each flap rotated by π about
//! its line, laid above the stack), and the synthesised state's dGLI on probe pairs is
//! compared with the measured end disk (`asinh`-compressed, mean absolute difference). A
//! beam search builds the sequences a fold at a time on a screen of strided pairs; besides
//! the best, the best sequence through each set of cut points is carried on (a sequence's
//! first folds can explain the end disk less than the flat cloth does); the best are
//! refined, all their folds together, by a pattern search over each fold's two parameters,
//! and judged on a larger probe, each at the flap height that fits it best (the cloth's
//! thickness, which sets how far apart its layers lie, shows in the disk).
//!
//! **Layer order.** Two perpendicular half folds done in either order land alike on the table, but
//! for a rigid motion, which no disk sees: what tells them apart is the order of their layers. A
//! sequence whose end lands like the best one's (within
//! [`LayerOrderParams::congruent`](crate::fold::params::LayerOrderParams::congruent)) is compared
//! with it on the order alone: each one's outline with each one's heights. Lines are refined and
//! layers ordered on a truncated loss
//! ([`LayerOrderParams::capped_mismatch`](crate::fold::params::LayerOrderParams::capped_mismatch)),
//! as a few pairs of nearly collinear or stacked edges turn measurement noise into large
//! mismatches.
//!
//! **Model selection.** k folds are reported only when they explain markedly more of the end disk
//! than fewer ([`SelectionParams`](crate::fold::params::SelectionParams)): more than the answer so
//! far (the best of fewer folds accepted), and more than any k − 1 of their own (else those are the
//! answer so far, if better); each length is tried in turn; the search runs only when the step's
//! one fold leaves more than
//! [`SelectionParams::explained_by_one_share`](crate::fold::params::SelectionParams::explained_by_one_share)
//! of it unexplained. The search's own best single fold is weighed alike: it replaces the step's
//! fold when it explains markedly more (a fold of several arcs on a flat start, which the step's
//! one-fold search does not make), and sequences are then weighed against it. A fold or sequence
//! that leaves more than
//! [`SelectionParams::unexplained_share`](crate::fold::params::SelectionParams::unexplained_share)
//! unexplained is not a confident fold.
//!
//! The end border's coordinates are never read: only its disk.

mod beam;
mod candidate;
mod layer_order;
mod selection;

pub use candidate::MAX_FOLDS;
pub(crate) use selection::explain;
pub use selection::{Alternative, ExplainedFold, StepFolds};
