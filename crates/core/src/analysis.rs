//! The whole pipeline of `close analyze`: frames in, CloSE, label, prediction and metrics out.
//!
//! Frames K_start … K_end of a prepared sample are each turned into a dGLI disk, on
//! borders normalised by the START frame's transform (dGLI scales with 1/size). Step k
//! (frame k−1 → k) gives one fold, or, from a flat start whose end disk one fold cannot
//! explain, a sequence of up to [`Options::max_folds`] folds ([`crate::fold::sequence`]).
//! The predicted end applies the folds in order to the start border, in the input's
//! coordinates.

use serde::{Deserialize, Serialize};

use crate::angle::{angle_to_param, param_to_angle, wrap_tau};
use crate::border::{to_xyz, BorderFrames, Normalisation, Point};
use crate::budget::{Budget, Deadline};
use crate::close::{corners, Close, CornerParams};
use crate::confidence::{judge, Confidence};
use crate::disk::Disk;
use crate::error::{Error, Result};
use crate::fold::sequence::{Alternative, ExplainedFold, StepFolds, MAX_FOLDS};
use crate::fold::{apply, read, FoldDetection, FoldMethod, Params, Reading};
use crate::geometry::{Fold, Folding, Line};
use crate::label::{label, Label, CHANGED_RMSE};
use crate::metrics::{Metrics, RigidMotion};

/// Which frames to analyse (defaults: first and last).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct FrameRange {
    pub start: Option<usize>,
    pub end: Option<usize>,
}

/// Folds one step may hold by default ([`Options::max_folds`]).
pub const DEFAULT_MAX_FOLDS: usize = 3;

/// How to analyse: which frames, how fold points are chosen, and what it may cost.
#[derive(Debug, Clone)]
pub struct Options {
    pub frames: FrameRange,
    pub method: FoldMethod,
    /// Most folds one step may hold (1: one fold per step, as the paper reads a step; at most
    /// [`crate::fold::sequence::MAX_FOLDS`]). Default [`DEFAULT_MAX_FOLDS`].
    pub max_folds: usize,
    /// The fold search's knobs; the default is as measured ([`crate::fold::params`]).
    pub fold: Params,
    /// The corner tests' knobs; the default is as measured ([`CornerParams`]).
    pub corners: CornerParams,
    /// Checked while the disks are computed and between steps: once expired, the analysis
    /// stops with [`Error::Cancelled`]. The default never expires.
    pub deadline: Deadline,
    /// Refuses, before any disk is computed, more analysed frames × N² than it allows. The
    /// default is unlimited.
    pub budget: Budget,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            frames: FrameRange::default(),
            method: FoldMethod::default(),
            max_folds: DEFAULT_MAX_FOLDS,
            fold: Params::default(),
            corners: CornerParams::default(),
            deadline: Deadline::default(),
            budget: Budget::default(),
        }
    }
}

/// One step between consecutive frames.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Step {
    pub from_frame: usize,
    pub to_frame: usize,
    /// The one-fold detection and its evidence; its `fold` and `arcs` are the step's first
    /// fold (`folds[0]`), none when the step has no fold.
    #[serde(flatten)]
    pub detection: FoldDetection,
    /// The step's folds in the order made, each with the line it was applied along in
    /// `predicted` and the share of the step's end-disk mismatch it explained: one fold, or
    /// a sequence when one fold left the end disk unexplained.
    pub folds: Vec<ExplainedFold>,
    /// Other fold sequences that explain the step's end disk about as well (two
    /// perpendicular half folds done in either order can land alike), with their shares;
    /// when `unexplained`, the best candidate found.
    pub alternatives: Vec<Alternative>,
    /// Share of the step's end-disk mismatch its folds explain.
    pub explained: f64,
    /// True when the best fold or sequence found left the end disk unexplained: the step
    /// changed, but no fold found explains it, and none is reported.
    pub unexplained: bool,
    /// The line this step's first fold was applied along in `predicted_end` (input
    /// coordinates, XY: a point and a unit direction): through the border points at f1 and
    /// f2 of the predicted state, or, when those coincide (and for every fold of a
    /// sequence), through their midpoint in the direction the disks gave on the observed
    /// frame, turned by the rigid motion that best brings that frame onto the predicted
    /// state (a cloth may turn on the table between folds, which no disk sees). `None`
    /// without a fold.
    pub line: Option<Line>,
    /// The start border with the folds found up to this step applied, against this
    /// step's true end frame.
    pub metrics: Metrics,
    /// That border itself, the state this step predicts for its end frame (input
    /// coordinates, border order): the last step's is `predicted_end`. A frame scrubber
    /// shows it beside the observed frame.
    pub predicted: Vec<[f64; 3]>,
    /// How strong the disks' evidence for this step's fold (or for no fold) is, and why
    /// not, when it is weak ([`crate::confidence`]).
    pub confidence: Confidence,
}

impl Step {
    /// The folds this step found, as they were made in `predicted`, in order.
    pub fn foldings(&self) -> impl Iterator<Item = &Folding> {
        self.folds.iter().map(|f| &f.folding)
    }
}

/// Everything `close analyze` reports.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Analysis {
    /// Border vertex count.
    pub n: usize,
    /// Corner angles (radians, increasing).
    pub corners: Vec<f64>,
    pub corner_vertices: Vec<usize>,
    pub corner_threshold: f64,
    /// One [f1, f2] per detected fold, in order, in [0, 2π) (radians).
    pub folds: Vec<Fold>,
    /// The CloSE value of the end state: the corners and the folds that led to it.
    pub close: Close,
    pub label: Label,
    pub border_indices: Vec<usize>,
    /// Where the border came from ("border", "mesh boundary loop", "mesh silhouette", …).
    pub border_source: String,
    /// True when the input was clockwise and was walked the other way.
    pub reversed: bool,
    pub warnings: Vec<String>,
    pub start_frame: usize,
    pub end_frame: usize,
    pub steps: Vec<Step>,
    /// The start border with the folds applied, input coordinates, border order.
    pub predicted_end: Vec<[f64; 3]>,
    pub metrics: Option<Metrics>,
    /// The analysed frames `start_frame ..= end_frame` (input coordinates, border order),
    /// for drawing: their disks are recomputed on demand ([`Analysis::disk`]) rather than
    /// kept, so an analysis holds O(frames·N) memory, not O(frames·N²).
    #[serde(skip)]
    pub frames: Vec<Vec<Point>>,
    /// The start frame's normalisation, which every disk of this analysis uses.
    #[serde(skip)]
    pub normalisation: Normalisation,
}

impl Analysis {
    /// The start border (input coordinates, border order).
    pub fn start_border(&self) -> &[Point] {
        &self.frames[0]
    }

    /// The end border (input coordinates, border order).
    pub fn end_border(&self) -> &[Point] {
        &self.frames[self.frames.len() - 1]
    }

    /// Each fold of [`Analysis::folds`] as it was made ([`Step::foldings`] of every step),
    /// in fold order: its arcs and the line of `predicted_end`.
    pub fn foldings(&self) -> Vec<Folding> {
        self.steps.iter().flat_map(Step::foldings).cloned().collect()
    }

    /// The folds in the caller's own vertex order: each fold point as the angle 2πt/M of
    /// its fractional INPUT vertex index t (M input vertices, a closing repeat of vertex 0
    /// not counted), the folded side running from the first to the second in the input's
    /// order. For an anticlockwise input without merged duplicates these are
    /// [`Analysis::folds`]; a clockwise input was walked the other way round, so its
    /// points are mirrored and swapped. `None` for a mesh, whose vertices have no border
    /// order of their own.
    ///
    /// ```
    /// use close_core::{analyze, border, FrameRange};
    /// # let square: Vec<[f64; 3]> = (0..40)
    /// #     .map(|k| { let t = (k % 10) as f64 / 10.0; [[t, 0.0], [1.0, t], [1.0 - t, 1.0], [0.0, 1.0 - t]][k / 10] })
    /// #     .map(|[x, y]| [x, y, 0.0]).collect();
    /// # let folded: Vec<[f64; 3]> = square.iter().map(|&[x, y, z]| if x > 0.5 { [1.0 - x, y, 0.01] } else { [x, y, z] }).collect();
    /// // The same folded square, its vertices listed clockwise from vertex 0.
    /// let clockwise = |f: &[[f64; 3]]| (0..40).map(|i| f[(40 - i) % 40]).collect::<Vec<_>>();
    /// let frames = border::prepare(vec![clockwise(&square), clockwise(&folded)])?;
    /// let analysis = analyze(&frames, FrameRange::default())?;
    /// let [f1, f2] = analysis.folds[0].ends();
    /// let [g1, g2] = analysis.input_folds().unwrap()[0].ends();
    /// // Border vertex k is input vertex 40 − k: angle f is 2π − f in the input's order.
    /// let tau = std::f64::consts::TAU;
    /// assert!((g1 - (tau - f2)).abs() < 1e-9 && (g2 - (tau - f1)).abs() < 1e-9);
    /// # Ok::<(), close_core::Error>(())
    /// ```
    pub fn input_folds(&self) -> Option<Vec<Fold>> {
        if self.border_source != "border" {
            return None;
        }
        let m = self.border_indices.iter().max().map_or(0, |&v| v + 1);
        let input = |f: f64| input_angle(&self.border_indices, self.reversed, m, f);
        let mapped = |f: &Fold| {
            let [g1, g2] = [input(f.f1), input(f.f2)];
            if self.reversed {
                Fold::new(g2, g1)
            } else {
                Fold::new(g1, g2)
            }
        };
        Some(self.folds.iter().map(mapped).collect())
    }

    /// The dGLI disk of analysed frame `k` (0 = the start frame), on the border normalised
    /// by the start frame's transform, as the analysis computed it; `None` past the end.
    pub fn disk(&self, k: usize) -> Option<Disk> {
        self.frames.get(k).map(|frame| Disk::of_border(&self.normalisation.apply_all(frame)))
    }
}

/// The angle 2πt/m, in the input's own order, of border angle `f`: t runs from input
/// vertex `indices[k]` to `indices[k + 1]` as the border parameter runs from k to k + 1,
/// one step of the walk (forwards through the input, or backwards when it was `reversed`;
/// a merged duplicate makes the step longer).
fn input_angle(indices: &[usize], reversed: bool, m: usize, f: f64) -> f64 {
    let n = indices.len();
    let s = angle_to_param(f, n);
    let k = (s.floor() as usize).min(n - 1);
    let (a, b) = (indices[k] as f64, indices[(k + 1) % n] as f64);
    let mf = m as f64;
    let step = if reversed { -(a - b).rem_euclid(mf) } else { (b - a).rem_euclid(mf) };
    wrap_tau(param_to_angle((a + (s - k as f64) * step).rem_euclid(mf), m))
}

/// Analyse frames `range` of a prepared sample.
///
/// ```
/// use close_core::{analyze, border, FrameRange};
/// // A square of 40 vertices, its right half folded over onto the left along x = 0.5.
/// let square: Vec<[f64; 3]> = (0..40)
///     .map(|k| {
///         let t = (k % 10) as f64 / 10.0;
///         [[t, 0.0], [1.0, t], [1.0 - t, 1.0], [0.0, 1.0 - t]][k / 10]
///     })
///     .map(|[x, y]| [x, y, 0.0])
///     .collect();
/// let folded = square.iter().map(|&[x, y, z]| if x > 0.5 { [1.0 - x, y, 0.01] } else { [x, y, z] }).collect();
/// let analysis = analyze(&border::prepare(vec![square, folded])?, FrameRange::default())?;
/// assert_eq!(analysis.folds.len(), 1);
/// assert_eq!(analysis.close.corners.len(), 4);
/// # Ok::<(), close_core::Error>(())
/// ```
pub fn analyze(sample: &BorderFrames, range: FrameRange) -> Result<Analysis> {
    analyze_with(sample, Options { frames: range, ..Options::default() })
}

/// Analyse with explicit [`Options`].
///
/// The disks are computed as a stream, one step at a time: at most two are alive at once,
/// whatever the number of frames.
pub fn analyze_with(sample: &BorderFrames, options: Options) -> Result<Analysis> {
    let range = options.frames;
    let Some(last) = sample.frames.len().checked_sub(1) else {
        return Err(Error::Empty { what: "the sample has no frame" });
    };
    let start = range.start.unwrap_or(0);
    let end = range.end.unwrap_or(last);
    if start > last || end > last {
        return Err(Error::InvalidArgument(format!(
            "frame {} does not exist (the sample has frames 0…{last})",
            start.max(end)
        )));
    }
    if end < start {
        return Err(Error::InvalidArgument(format!(
            "end frame {end} comes before start frame {start}"
        )));
    }
    if !(1..=MAX_FOLDS).contains(&options.max_folds) {
        return Err(Error::InvalidArgument(format!(
            "max_folds {} is out of range: a step holds 1 to {MAX_FOLDS} folds",
            options.max_folds
        )));
    }
    options.fold.check()?;
    let frames = &sample.frames[start..=end];
    options.budget.analysis(frames.len(), sample.len())?;
    let norm = Normalisation::of(&frames[0])?;
    let start_border = norm.apply_all(&frames[0]);
    let start_disk = Disk::of_border_until(&start_border, &options.deadline)?;
    // The corners need only the start state: found while the steps are analysed.
    let (found, steps) = rayon::join(
        || corners(&start_disk, &start_border, &options.corners),
        || analyse_steps(frames, start, &norm, (&start_border, &start_disk), &options),
    );
    let (steps, predicted) = steps?;
    let foldings: Vec<Folding> = steps.iter().flat_map(Step::foldings).cloned().collect();
    let folds: Vec<Fold> = foldings.iter().map(|f| f.fold).collect();
    let metrics = steps.last().map(|s| s.metrics);
    let n = sample.len();
    let mut label = label(&frames[0], &found.vertices, &foldings);
    // A cloth only moved across the table is in the same state: the aligned error decides.
    let changed: Vec<usize> = steps
        .iter()
        .enumerate()
        .filter(|(_, s)| {
            s.unexplained || (s.folds.is_empty() && s.metrics.aligned_rmse > CHANGED_RMSE)
        })
        .map(|(k, _)| k + 1)
        .collect();
    label.changed_without_fold(&changed);
    Ok(Analysis {
        n,
        close: Close { corners: found.angles.clone(), folds: folds.clone() },
        corners: found.angles,
        corner_vertices: found.vertices,
        corner_threshold: found.threshold,
        folds,
        label,
        border_indices: sample.border_indices.clone(),
        border_source: sample.source.clone(),
        reversed: sample.reversed,
        warnings: sample.warnings.clone(),
        start_frame: start,
        end_frame: end,
        steps,
        predicted_end: predicted.iter().map(to_xyz).collect(),
        metrics,
        frames: frames.to_vec(),
        normalisation: norm,
    })
}

/// The steps between consecutive `frames` (the first is the sample's frame `first`), each
/// from the state before it, and the start border with the folds found applied.
fn analyse_steps(
    frames: &[Vec<Point>],
    first: usize,
    norm: &Normalisation,
    start: (&[Point], &Disk),
    options: &Options,
) -> Result<(Vec<Step>, Vec<Point>)> {
    let mut predicted = frames[0].clone();
    // The vertices no fold found so far has moved: where the predicted state and the observed
    // one differ only by how the cloth lies on the table.
    let mut unmoved = vec![true; predicted.len()];
    let mut steps = Vec::with_capacity(frames.len() - 1);
    let mut previous: Option<(Vec<Point>, Disk)> = None;
    for (k, frame) in frames.iter().enumerate().skip(1) {
        let after_border = norm.apply_all(frame);
        let after = Disk::of_border_until(&after_border, &options.deadline)?;
        let (before_border, before) =
            previous.as_ref().map_or(start, |(border, disk)| (border.as_slice(), disk));
        let Reading { evidence, folds: found } = read(
            before_border,
            before,
            &after,
            options.method,
            options.max_folds,
            &options.fold,
            &options.deadline,
        )?;
        options.deadline.check()?;
        let StepFolds { folds: explained_folds, alternatives, explained, unexplained } = found;
        // A sequence's folds all carry their direction; one fold, only when its points
        // coincide (its line otherwise runs through them, on the predicted state as on the
        // observed one).
        let single_direction = evidence.synthesis.as_ref().and_then(|s| s.direction);
        let sequence = explained_folds.len() > 1;
        let turn = placement(before_border, &norm.apply_all(&predicted), &unmoved);
        let mut folds = Vec::with_capacity(explained_folds.len());
        for step_fold in explained_folds {
            let Folding { fold, arcs, line } = step_fold.folding;
            // A direction read on the observed frame turns with the predicted state, which may
            // lie rotated from it (a cloth that slid as it folded).
            let direction = if sequence { line.map(|l| l.direction) } else { single_direction };
            let Some(line) = fold.line_on(&predicted, direction.map(|d| turn.rotate(d))) else {
                continue;
            };
            let folding = Folding { fold, arcs, line: Some(line) };
            predicted = apply(&predicted, &folding);
            for arc in &folding.arcs {
                for v in arc.folded_vertices(predicted.len()) {
                    unmoved[v] = false;
                }
            }
            folds.push(ExplainedFold { folding, explained: step_fold.explained });
        }
        let detection = FoldDetection::of(evidence, folds.first().map(|f| &f.folding));
        let line = folds.first().and_then(|f| f.folding.line);
        let metrics = Metrics::measure(norm, &predicted, frame);
        let confidence = judge(&detection, &metrics);
        steps.push(Step {
            from_frame: first + k - 1,
            to_frame: first + k,
            detection,
            folds,
            alternatives,
            explained,
            unexplained,
            line,
            metrics,
            predicted: predicted.iter().map(to_xyz).collect(),
            confidence,
        });
        previous = Some((after_border, after));
    }
    Ok((steps, predicted))
}

/// The rigid motion that brings the `observed` state onto the `predicted` one, fitted on the
/// vertices no fold has moved (on them the two differ only by a slide across the table;
/// on the flaps, also by the folds' own errors), or on all when fewer than three are left.
fn placement(observed: &[Point], predicted: &[Point], unmoved: &[bool]) -> RigidMotion {
    let (observed_base, predicted_base): (Vec<Point>, Vec<Point>) = observed
        .iter()
        .zip(predicted)
        .zip(unmoved)
        .filter(|(_, &keep)| keep)
        .map(|(pair, _)| pair)
        .unzip();
    if observed_base.len() < 3 {
        RigidMotion::fit_xy(observed, predicted)
    } else {
        RigidMotion::fit_xy(&observed_base, &predicted_base)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::TAU;

    #[test]
    fn a_sample_without_frames_is_an_error_not_a_panic() {
        let empty = BorderFrames {
            frames: Vec::new(),
            border_indices: Vec::new(),
            source: "border".into(),
            reversed: false,
            warnings: Vec::new(),
        };
        assert!(matches!(analyze(&empty, FrameRange::default()), Err(Error::Empty { .. })));
    }

    #[test]
    fn border_angles_map_to_the_inputs_own_order() {
        let at = |indices: &[usize], reversed: bool, m: usize, s: f64| {
            let n = indices.len();
            input_angle(indices, reversed, m, param_to_angle(s, n)) * m as f64 / TAU
        };
        let near = |a: f64, b: f64| (a - b).abs() < 1e-9;
        // Reversed (vertex 0 kept first): border k is input 10 − k.
        let reversed = [0, 9, 8, 7, 6, 5, 4, 3, 2, 1];
        assert!(near(at(&reversed, true, 10, 2.5), 7.5));
        assert!(near(at(&reversed, true, 10, 0.5), 9.5));
        assert!(near(at(&reversed, true, 10, 9.5), 0.5));
        // Input vertex 5 merged into 4: the border's edge 4 spans two input edges.
        let merged = [0, 1, 2, 3, 4, 6, 7, 8, 9, 10];
        assert!(near(at(&merged, false, 11, 4.5), 5.0));
        assert!(near(at(&merged, false, 11, 9.5), 10.5));
        assert!(near(at(&merged, false, 11, 3.0), 3.0));
    }

    fn square_frames(frames: usize) -> BorderFrames {
        let square: Vec<Point> = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
            .iter()
            .map(|p| Point::new(p[0], p[1], 0.0))
            .collect();
        BorderFrames {
            frames: vec![square; frames],
            border_indices: (0..4).collect(),
            source: "border".into(),
            reversed: false,
            warnings: Vec::new(),
        }
    }

    #[test]
    fn the_budget_is_checked_before_any_disk() {
        let budget = Budget { max_cells: 2 * 16, ..Budget::default() };
        let over = analyze_with(&square_frames(3), Options { budget, ..Options::default() });
        assert!(matches!(over, Err(Error::OverBudget { got: 48, limit: 32, .. })));
        // Only the analysed frames count.
        let range = FrameRange { start: Some(1), end: Some(2) };
        assert!(analyze_with(
            &square_frames(3),
            Options { budget, frames: range, ..Options::default() }
        )
        .is_ok());
    }

    #[test]
    fn each_step_carries_the_border_it_predicts() {
        // A square of 40 vertices, its right half folded onto the left, then left alone.
        let square: Vec<[f64; 3]> = (0..40)
            .map(|k| {
                let t = (k % 10) as f64 / 10.0;
                let [x, y] = [[t, 0.0], [1.0, t], [1.0 - t, 1.0], [0.0, 1.0 - t]][k / 10];
                [x, y, 0.0]
            })
            .collect();
        let folded: Vec<[f64; 3]> = square
            .iter()
            .map(|&[x, y, z]| if x > 0.5 { [1.0 - x, y, 0.01] } else { [x, y, z] })
            .collect();
        let analysis = analyze(
            &crate::border::prepare(vec![square.clone(), folded.clone(), folded]).unwrap(),
            FrameRange::default(),
        )
        .unwrap();
        assert_eq!(
            analysis.steps.iter().map(|s| s.detection.fold.is_some()).collect::<Vec<_>>(),
            [true, false]
        );
        // Step 1 folds the start; step 2 finds nothing and predicts the same state.
        let moved = |p: &[[f64; 3]]| {
            p.iter().zip(&square).map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1])).fold(0.0, f64::max)
        };
        assert!(moved(&analysis.steps[0].predicted) > 0.3);
        assert_eq!(analysis.steps[0].predicted, analysis.steps[1].predicted);
        assert_eq!(analysis.steps[1].predicted, analysis.predicted_end);
    }

    #[test]
    fn the_fold_search_reads_its_knobs_from_the_options() {
        // The square of 40 vertices folded in half: one fold as measured; none when no cut
        // may have a side to it; an error naming a knob the search cannot run with.
        let square: Vec<[f64; 3]> = (0..40)
            .map(|k| {
                let t = (k % 10) as f64 / 10.0;
                let [x, y] = [[t, 0.0], [1.0, t], [1.0 - t, 1.0], [0.0, 1.0 - t]][k / 10];
                [x, y, 0.0]
            })
            .collect();
        let folded = square
            .iter()
            .map(|&[x, y, z]| if x > 0.5 { [1.0 - x, y, 0.01] } else { [x, y, z] })
            .collect();
        let sample = crate::border::prepare(vec![square, folded]).unwrap();
        let with = |fold: Params| analyze_with(&sample, Options { fold, ..Options::default() });
        assert_eq!(with(Params::default()).unwrap().folds.len(), 1);
        let mut sideless = Params::default();
        sideless.detect.max_same_to_cross = -1.0;
        assert!(with(sideless).unwrap().folds.is_empty());
        let mut broken = Params::default();
        broken.synthesis.samples = 0;
        assert!(matches!(with(broken), Err(Error::InvalidArgument(m)) if m.contains("samples")));
    }

    #[test]
    fn an_expired_deadline_stops_the_analysis() {
        let deadline = Deadline::default();
        deadline.cancel();
        assert_eq!(
            analyze_with(&square_frames(2), Options { deadline, ..Options::default() }),
            Err(Error::Cancelled)
        );
    }
}
