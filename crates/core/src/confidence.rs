//! A step's confidence: whether the disks' evidence for the fold a step found (or for no
//! fold) is strong, and if not, why.
//!
//! The evidence is what the step reports ([`FoldDetection`], [`Metrics`]); a step is of
//! [`Level::Low`] confidence when any of it passes its limit ([`Limits::DEFAULT`]):
//! - the cut's same-to-cross ratio (0 for an exact fold, about 1 for change with no side to
//!   it; the detector gives up at [`crate::fold::params::DetectParams::max_same_to_cross`])
//!   above 1;
//! - the cut's residual (the share of the change the cut leaves unexplained) above 0.6;
//! - the orientation decided by its tie-break, or its two flip scores closer than a
//!   relative margin of 0.25 (|a − b| / max(a, b); 0 is a tie, 1 one side only);
//! - on a stacked start (no orientation: the line search turned a known side over), the
//!   synthesis leaving more than 60 % of the unfolded state's mismatch unexplained;
//! - the prediction farther than [`CHANGED_RMSE`] (aligned RMSE: once moved rigidly onto
//!   the observed frame, as CloSE does not see a slide) from the frame observed after the
//!   step: the disks can agree with a wrong fold, and the observed frame then says so;
//! - a step without a fold whose observed frame is that far from the unchanged one: the
//!   cloth changed beyond noise, but no fold explains it.
//!
//! The limits were measured on the built-in set (150 fold steps): same-to-cross at most
//! 0.38, residual at most 0.52 (noisy samples, predictions still right), flip margin at
//! least 0.75, no tie-break, aligned RMSE at most 0.073 except one visibly wrong step; on
//! the physics and MuJoCo second folds (stacked starts) the unexplained share is at most
//! 0.49, and 0.73 and more for wrong lines.
//!
//! ```
//! use close_core::confidence::{judge, Level};
//! use close_core::fold::FoldDetection;
//! use close_core::metrics::Metrics;
//! let nothing = FoldDetection {
//!     fold: None, arcs: vec![], curves: vec![], cut: None, orientation: None, synthesis: None,
//! };
//! let still = Metrics { rmse: 0.01, frechet: 0.01, aligned_rmse: 0.01 };
//! assert_eq!(judge(&nothing, &still).level, Level::High);
//! let moved = Metrics { rmse: 0.3, frechet: 0.4, aligned_rmse: 0.3 };
//! let judged = judge(&nothing, &moved);
//! assert_eq!(judged.level, Level::Low);
//! assert!(judged.doubts[0].text.starts_with("changed, but no fold found"));
//! ```

use serde::{Deserialize, Serialize};

use crate::fold::FoldDetection;
use crate::label::CHANGED_RMSE;
use crate::metrics::Metrics;

/// How far a step's evidence may go before it is doubtful.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// Largest same-to-cross ratio of the cut.
    pub same_to_cross: f64,
    /// Largest residual of the cut.
    pub residual: f64,
    /// Smallest relative margin between the two flip scores.
    pub flip_margin: f64,
    /// Largest aligned RMSE of the prediction against the observed frame.
    pub rmse: f64,
    /// Largest share of the unfolded state's mismatch the synthesis may leave.
    pub unexplained: f64,
}

impl Limits {
    /// The limits measured on the built-in set (see the module doc).
    pub const DEFAULT: Limits = Limits {
        same_to_cross: 1.0,
        residual: 0.6,
        flip_margin: 0.25,
        rmse: CHANGED_RMSE,
        unexplained: 0.6,
    };
}

/// High or low confidence.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum Level {
    High,
    Low,
}

/// Which piece of evidence is doubtful.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum Reason {
    /// No fold, but the observed frame is far from the unchanged one.
    ChangedWithoutFold,
    /// The synthesised fold leaves much of the mismatch unexplained.
    Unexplained,
    SameToCross,
    Residual,
    /// The orientation was decided by the tie-break.
    TieBreak,
    /// The two flip scores are close.
    FlipMargin,
    /// The prediction is far from the observed frame.
    Prediction,
}

/// One doubt: the evidence, its value, the limit it passed and a sentence saying so.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Doubt {
    pub reason: Reason,
    pub value: f64,
    pub limit: f64,
    pub text: String,
}

/// A step's confidence and the doubts that lower it (none when high).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Confidence {
    pub level: Level,
    pub doubts: Vec<Doubt>,
}

/// The relative gap between two flip scores: 0 for a tie, 1 when one side alone flipped.
pub(crate) fn flip_margin(forward: f64, backward: f64) -> f64 {
    let (a, b) = (forward.abs(), backward.abs());
    (a - b).abs() / a.max(b).max(1e-12)
}

/// The confidence of a step that found `detection`, its prediction measured by `metrics`,
/// with [`Limits::DEFAULT`].
pub fn judge(detection: &FoldDetection, metrics: &Metrics) -> Confidence {
    judge_with(detection, metrics, &Limits::DEFAULT)
}

/// [`judge`] with other `limits`.
pub(crate) fn judge_with(
    detection: &FoldDetection,
    metrics: &Metrics,
    limits: &Limits,
) -> Confidence {
    let mut doubts = Vec::new();
    let mut doubt = |reason, value: f64, limit: f64, text: String| {
        doubts.push(Doubt { reason, value, limit, text });
    };
    let shape = metrics.aligned_rmse;
    if detection.fold.is_none() {
        if shape > limits.rmse {
            doubt(
                Reason::ChangedWithoutFold,
                shape,
                limits.rmse,
                format!(
                    "changed, but no fold found (the observed frame is {shape:.3} RMSE from the \
                     unchanged one once moved onto it, > {})",
                    limits.rmse
                ),
            );
        }
    } else {
        if let (Some(s), None) = (&detection.synthesis, &detection.orientation) {
            if s.unfolded_mismatch > 0.0 {
                let ratio = s.mismatch / s.unfolded_mismatch;
                if ratio > limits.unexplained {
                    doubt(
                        Reason::Unexplained,
                        ratio,
                        limits.unexplained,
                        format!(
                            "the synthesised fold leaves {:.0}% of the disks' mismatch unexplained (> {:.0}%)",
                            100.0 * ratio,
                            100.0 * limits.unexplained
                        ),
                    );
                }
            }
        }
        if let Some(cut) = &detection.cut {
            if cut.same_to_cross > limits.same_to_cross {
                doubt(
                    Reason::SameToCross,
                    cut.same_to_cross,
                    limits.same_to_cross,
                    format!(
                        "same-to-cross ratio {:.2} > {}",
                        cut.same_to_cross, limits.same_to_cross
                    ),
                );
            }
            if cut.residual > limits.residual {
                doubt(
                    Reason::Residual,
                    cut.residual,
                    limits.residual,
                    format!("cut residual {:.2} > {}", cut.residual, limits.residual),
                );
            }
        }
        if let Some(o) = &detection.orientation {
            let margin = flip_margin(o.flip_forward, o.flip_backward);
            if o.tie_break {
                doubt(
                    Reason::TieBreak,
                    margin,
                    limits.flip_margin,
                    "orientation decided by the tie-break".into(),
                );
            } else if margin < limits.flip_margin {
                doubt(
                    Reason::FlipMargin,
                    margin,
                    limits.flip_margin,
                    format!(
                        "orientation scores close (margin {margin:.2} < {})",
                        limits.flip_margin
                    ),
                );
            }
        }
        if shape > limits.rmse {
            doubt(
                Reason::Prediction,
                shape,
                limits.rmse,
                format!(
                    "prediction {shape:.3} RMSE from the frame observed after the step, once \
                     moved onto it (> {})",
                    limits.rmse
                ),
            );
        }
    }
    let level = if doubts.is_empty() { Level::High } else { Level::Low };
    Confidence { level, doubts }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fold::{Cut, Orientation, Synthesis};

    fn found(cut: Cut, orientation: Option<Orientation>) -> FoldDetection {
        FoldDetection {
            fold: Some(crate::geometry::Fold::new(0.0, 3.0)),
            arcs: vec![crate::geometry::Arc::new(0.0, 3.0)],
            curves: vec![],
            cut: Some(cut),
            orientation,
            synthesis: None,
        }
    }

    fn cut(residual: f64, same_to_cross: f64) -> Cut {
        Cut { p1: 0.0, p2: 3.0, residual, same_to_cross, inside_edge: [false; 2] }
    }

    fn oriented(forward: f64, backward: f64, tie_break: bool) -> Option<Orientation> {
        Some(Orientation {
            flip_forward: forward,
            flip_backward: backward,
            tie_break,
            swapped: false,
        })
    }

    const GOOD: Metrics = Metrics { rmse: 0.02, frechet: 0.03, aligned_rmse: 0.02 };

    #[test]
    fn strong_evidence_is_high_and_each_weakness_is_named() {
        let strong = found(cut(0.1, 0.2), oriented(5.0, 0.5, false));
        assert_eq!(judge(&strong, &GOOD), Confidence { level: Level::High, doubts: vec![] });
        let reasons = |d: &FoldDetection, m: &Metrics| -> Vec<Reason> {
            judge(d, m).doubts.iter().map(|d| d.reason).collect()
        };
        assert_eq!(
            reasons(&found(cut(0.7, 0.2), oriented(5.0, 0.5, false)), &GOOD),
            [Reason::Residual]
        );
        assert_eq!(
            reasons(&found(cut(0.1, 1.5), oriented(5.0, 0.5, false)), &GOOD),
            [Reason::SameToCross]
        );
        assert_eq!(
            reasons(&found(cut(0.1, 0.2), oriented(5.0, 4.5, false)), &GOOD),
            [Reason::FlipMargin]
        );
        assert_eq!(
            reasons(&found(cut(0.1, 0.2), oriented(5.0, 5.0, true)), &GOOD),
            [Reason::TieBreak]
        );
        let far = Metrics { aligned_rmse: 0.2, ..GOOD };
        let judged = judge(&strong, &far);
        assert_eq!(judged.level, Level::Low);
        assert_eq!(judged.doubts[0].reason, Reason::Prediction);
        assert_eq!((judged.doubts[0].value, judged.doubts[0].limit), (0.2, CHANGED_RMSE));
        // A slide is no evidence against the fold: only the aligned error counts.
        let slid = Metrics { rmse: 0.5, frechet: 0.6, aligned_rmse: 0.02 };
        assert_eq!(judge(&strong, &slid).level, Level::High);
    }

    #[test]
    fn a_stacked_start_is_judged_by_what_its_synthesis_explains() {
        let synthesis = |mismatch| Synthesis {
            s: [0.0, 3.0],
            arcs: vec![[0.0, 3.0]],
            direction: None,
            mismatch,
            unfolded_mismatch: 1.0,
        };
        let mut d = found(cut(0.1, 0.2), None);
        d.synthesis = Some(synthesis(0.4));
        assert_eq!(judge(&d, &GOOD).level, Level::High);
        d.synthesis = Some(synthesis(0.8));
        let judged = judge(&d, &GOOD);
        assert_eq!(judged.doubts[0].reason, Reason::Unexplained);
        assert!(judged.doubts[0].text.contains("80%"), "{}", judged.doubts[0].text);
    }

    #[test]
    fn flip_margin_is_zero_for_a_tie_and_one_for_one_side() {
        assert_eq!(flip_margin(2.0, 2.0), 0.0);
        assert_eq!(flip_margin(2.0, 0.0), 1.0);
        assert_eq!(flip_margin(0.0, 0.0), 0.0);
    }
}
