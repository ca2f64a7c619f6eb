//! Evaluation over many samples, per category and overall (the paper's Table I).
//!
//! For each sample: analyse first → last frame, count folds, measure RMSE and Fréchet of
//! the predicted end (the paper's metrics: XY RMSE and discrete Fréchet distance after normalisation), and, where `truth` is given, the angular error of f1
//! and f2 against the true fold. Samples with several steps (a fold, then a second fold)
//! are also scored step by step, so first and second folds get rows of their own.
//! [`evaluate_steps`] scores a sequence fold by fold into rows `<category>/fold<k>` (the
//! VR-Folding rows of Table I), and a fold that could not be scored (a broken mesh) is
//! counted as dropped ([`SampleResult::dropped`]), apart from the errors; [`evaluate_video`]
//! gives those rows for a video of a VR-Folding store.
//!
//! Units ([`Units`], in every report): angles in radians (the text table prints degrees and
//! says so, °), lengths in the START border's normalised units
//! ([`close_core::metrics`]: centroid at the origin, farthest vertex at distance 1).

use std::collections::BTreeMap;
use std::f64::consts::PI;

use serde::{Deserialize, Serialize};

use crate::formats::Sample;
#[cfg(feature = "vrfolding")]
use crate::vrfolding::{Store, Video, FOLDS};
use close_core::analysis::{analyze_with, Analysis, Options};
use close_core::angle;
use close_core::error::Error;
use close_core::fold::FoldMethod;
use close_core::geometry::Fold;

/// The outcome for one sample. Rows scored elsewhere (another process, another machine)
/// come back as JSON and are reported as they were.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct SampleResult {
    pub name: String,
    pub category: String,
    pub folds: usize,
    /// Folds the sample should have (truth, else one per step).
    pub expected_folds: usize,
    /// XY RMSE of the predicted end border against the true one (normalised units).
    pub rmse: Option<f64>,
    /// Discrete Fréchet distance of the same (normalised units).
    pub frechet: Option<f64>,
    /// The RMSE once the prediction is moved rigidly onto the truth
    /// ([`close_core::metrics::aligned_rmse_xy`]): what is left when the cloth's slide across
    /// the table, which the disks cannot see, is taken out (normalised units). Absent from
    /// rows scored before it was measured.
    #[serde(default)]
    pub aligned_rmse: Option<f64>,
    /// Angular error of f1 and f2 against the true first fold (radians).
    pub angle_error: Option<[f64; 2]>,
    pub error: Option<String>,
    /// Why the sample was left out of the scores (e.g. a broken mesh), when it was.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dropped: Option<String>,
    /// Step k (frame k → k+1): the prediction with the folds found so far.
    pub steps: Vec<StepResult>,
}

/// How one step of a sample went.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct StepResult {
    pub fold_found: bool,
    /// As [`SampleResult::rmse`], for this step's end (normalised units).
    pub rmse: f64,
    /// As [`SampleResult::frechet`] (normalised units).
    pub frechet: f64,
    /// As [`SampleResult::aligned_rmse`] (normalised units).
    #[serde(default)]
    pub aligned_rmse: Option<f64>,
    /// Angular error of f1 and f2 against the step's true fold, when known (radians).
    pub angle_error: Option<[f64; 2]>,
}

impl SampleResult {
    /// The result of a sample that could not be read.
    pub fn unreadable(name: &str, error: &str) -> SampleResult {
        SampleResult { error: Some(error.to_string()), ..SampleResult::empty(name, "unreadable") }
    }

    /// A sample left out of the scores on purpose (`reason`), counted as dropped in its row.
    pub fn dropped(name: &str, category: &str, reason: &str) -> SampleResult {
        SampleResult { dropped: Some(reason.to_string()), ..SampleResult::empty(name, category) }
    }

    fn empty(name: &str, category: &str) -> SampleResult {
        SampleResult {
            name: name.to_string(),
            category: category.to_string(),
            folds: 0,
            expected_folds: 0,
            rmse: None,
            frechet: None,
            aligned_rmse: None,
            angle_error: None,
            error: None,
            dropped: None,
            steps: Vec::new(),
        }
    }
}

/// Mean and population variance, in the unit of what they are of (the variance in its
/// square).
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Stat {
    pub mean: f64,
    pub var: f64,
}

impl Stat {
    fn of(values: &[f64]) -> Option<Stat> {
        if values.is_empty() {
            return None;
        }
        let mean = values.iter().sum::<f64>() / values.len() as f64;
        let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / values.len() as f64;
        Some(Stat { mean, var })
    }
}

/// One row of the table.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Summary {
    pub category: String,
    pub count: usize,
    /// Of [`SampleResult::rmse`] (normalised units).
    pub rmse: Option<Stat>,
    /// Of [`SampleResult::frechet`] (normalised units).
    pub frechet: Option<Stat>,
    /// Of [`SampleResult::aligned_rmse`] (normalised units).
    #[serde(default)]
    pub aligned_rmse: Option<Stat>,
    /// Samples whose fold count differs from what they should have.
    pub fold_count_misses: usize,
    pub errors: usize,
    /// Samples left out of the scores (not in `count`), e.g. folds with a broken mesh.
    pub dropped: usize,
    /// Of the error of f1 ([`SampleResult::angle_error`]): radians (its variance in
    /// radians²).
    pub f1_error: Option<Stat>,
    /// Of the error of f2: radians (its variance in radians²).
    pub f2_error: Option<Stat>,
    /// For categories with multi-step samples: fold 1, fold 2, … scored apart.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub by_fold: Vec<FoldSummary>,
}

/// The k-th fold of every multi-step sample of a category.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct FoldSummary {
    pub fold: usize,
    pub count: usize,
    pub found: usize,
    /// Of [`StepResult::rmse`] (normalised units).
    pub rmse: Option<Stat>,
    /// Of [`StepResult::frechet`] (normalised units).
    pub frechet: Option<Stat>,
    /// Of [`StepResult::aligned_rmse`] (normalised units).
    #[serde(default)]
    pub aligned_rmse: Option<Stat>,
    /// Of the error of this fold's f1 ([`StepResult::angle_error`]): radians (its variance
    /// in radians²).
    pub f1_error: Option<Stat>,
    /// Of the error of its f2: radians (its variance in radians²).
    pub f2_error: Option<Stat>,
}

/// The whole evaluation.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Report {
    /// The units of its numbers.
    #[serde(default)]
    pub units: Units,
    pub categories: Vec<Summary>,
    pub overall: Summary,
    pub samples: Vec<SampleResult>,
}

/// The units of a report's numbers, said in the report itself so that its field names need
/// not (`f1_error` is read by people): the same in every report.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Units {
    pub angle: AngleUnit,
    pub length: LengthUnit,
}

/// The unit of every angle of a report.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub enum AngleUnit {
    /// Radians.
    #[default]
    #[serde(rename = "rad")]
    Radian,
}

/// The unit of every length of a report (RMSE, Fréchet distance).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub enum LengthUnit {
    /// The START border's normalised units: centroid at the origin, farthest vertex at
    /// distance 1 ([`close_core::metrics`]).
    #[default]
    #[serde(rename = "normalised")]
    Normalised,
}

/// Evaluate one sample with the default fold method.
///
/// ```
/// use close_io::dataset::Dataset;
/// use close_io::eval::{evaluate, report};
/// let data = Dataset::builtin();
/// let result = evaluate(&data.get("napkin__half_vertical").expect("a built-in sample").sample);
/// assert_eq!((result.folds, result.expected_folds), (1, 1));
/// assert!(result.rmse.expect("an end frame to compare with") < 0.02);
/// assert_eq!(report(vec![result]).overall.count, 1);
/// ```
pub fn evaluate(sample: &Sample) -> SampleResult {
    evaluate_with(sample, FoldMethod::default())
}

/// Evaluate one sample, choosing fold points with `method`.
pub fn evaluate_with(sample: &Sample, method: FoldMethod) -> SampleResult {
    let analysis = sample
        .border_frames()
        .and_then(|b| analyze_with(&b, Options { method, ..Options::default() }));
    score(sample, analysis.as_ref())
}

/// Score `sample` against its truth, given its analysis or the error that stopped it: what
/// [`evaluate_with`] does after analysing, for a caller that has the analysis already.
pub fn score(sample: &Sample, analysis: std::result::Result<&Analysis, &Error>) -> SampleResult {
    let truth_folds = sample.truth.as_ref().map(|t| t.folds.clone());
    let mut result = SampleResult {
        expected_folds: truth_folds
            .as_ref()
            .map_or(sample.frames.len().saturating_sub(1), Vec::len),
        ..SampleResult::empty(&sample.name, category_of(sample))
    };
    match analysis {
        Ok(a) => {
            result.folds = a.folds.len();
            result.rmse = a.metrics.map(|m| m.rmse);
            result.frechet = a.metrics.map(|m| m.frechet);
            result.aligned_rmse = a.metrics.map(|m| m.aligned_rmse);
            let error = |found: &Fold, truth: &Fold| {
                [angle::distance(found.f1, truth.f1), angle::distance(found.f2, truth.f2)]
            };
            if let (Some(found), Some(truth)) =
                (a.folds.first(), truth_folds.as_ref().and_then(|t| t.first()))
            {
                result.angle_error = Some(error(found, truth));
            }
            result.steps = a
                .steps
                .iter()
                .enumerate()
                .map(|(k, step)| StepResult {
                    fold_found: step.detection.fold.is_some(),
                    rmse: step.metrics.rmse,
                    frechet: step.metrics.frechet,
                    aligned_rmse: Some(step.metrics.aligned_rmse),
                    angle_error: step
                        .detection
                        .fold
                        .zip(truth_folds.as_ref().and_then(|t| t.get(k)))
                        .map(|(f, t)| error(&f, t)),
                })
                .collect();
        }
        Err(e) => result.error = Some(e.to_string()),
    }
    result
}

fn category_of(sample: &Sample) -> &str {
    if sample.category.is_empty() {
        "uncategorised"
    } else {
        &sample.category
    }
}

/// Score a sequence fold by fold: one analysis of all its frames, and for each step k one
/// result named `<name>/fold<k>` in category `<category>/fold<k>`, scored on that step alone
/// (the folds found before it applied, as the analysis does): one fold expected per step.
pub fn evaluate_steps(sample: &Sample, method: FoldMethod) -> Vec<SampleResult> {
    let rows = sample.frames.len().saturating_sub(1);
    let row = |k: usize| SampleResult {
        expected_folds: 1,
        ..SampleResult::empty(
            &format!("{}/fold{k}", sample.name),
            &format!("{}/fold{k}", category_of(sample)),
        )
    };
    match sample
        .border_frames()
        .and_then(|b| analyze_with(&b, Options { method, ..Options::default() }))
    {
        Ok(a) => a
            .steps
            .iter()
            .enumerate()
            .map(|(k, step)| {
                let found = step.detection.fold.is_some();
                SampleResult {
                    folds: usize::from(found),
                    rmse: Some(step.metrics.rmse),
                    frechet: Some(step.metrics.frechet),
                    aligned_rmse: Some(step.metrics.aligned_rmse),
                    steps: vec![StepResult {
                        fold_found: found,
                        rmse: step.metrics.rmse,
                        frechet: step.metrics.frechet,
                        aligned_rmse: Some(step.metrics.aligned_rmse),
                        angle_error: None,
                    }],
                    ..row(k + 1)
                }
            })
            .collect(),
        Err(e) => (1..=rows.max(1))
            .map(|k| SampleResult { error: Some(e.to_string()), ..row(k) })
            .collect(),
    }
}

/// The Table I rows of one VR-Folding video: `<Category>/fold1`, `<Category>/fold2` from one analysis of
/// (start, end of action 1, end of action 2); a fold with a broken mesh is dropped; a video
/// whose meshes cannot be read is an error row for each fold its grips cut it into, as the
/// server lists them (one, fold 1's, when its grips cannot be read either).
#[cfg(feature = "vrfolding")]
pub fn evaluate_video(store: &Store, video: &Video, method: FoldMethod) -> Vec<SampleResult> {
    let name = |k: usize| format!("{}/fold{k}", video.id);
    let category = |k: usize| format!("{}/fold{k}", video.category);
    let folds = match store.folds(video) {
        Ok(folds) => folds,
        Err(e) => {
            // A row per fold the server lists (its grips cut it), so none is dropped unseen.
            let listed = store.cut(video).map_or(1, |cut| cut.actions.len().clamp(1, FOLDS));
            return (1..=listed)
                .map(|k| SampleResult {
                    category: category(k),
                    ..SampleResult::unreadable(&name(k), &e.to_string())
                })
                .collect();
        }
    };
    let usable = folds.usable();
    let mut rows = if usable == 0 {
        Vec::new()
    } else {
        evaluate_steps(
            &Sample::from_frames(video.id.clone(), video.category.clone(), folds.frames.clone()),
            method,
        )
    };
    for k in usable + 1..=folds.broken.len() {
        let culprit = folds.broken.iter().position(|&b| b).map_or(k, |a| a + 1);
        rows.push(SampleResult::dropped(
            &name(k),
            &category(k),
            &format!("broken mesh at the start or end of action {culprit}"),
        ));
    }
    rows
}

fn stat_of<T>(items: &[T], f: impl Fn(&T) -> Option<f64>) -> Option<Stat> {
    Stat::of(&items.iter().filter_map(f).collect::<Vec<_>>())
}

fn by_fold(results: &[&SampleResult]) -> Vec<FoldSummary> {
    let multi: Vec<&SampleResult> = results.iter().copied().filter(|r| r.steps.len() > 1).collect();
    let most = multi.iter().map(|r| r.steps.len()).max().unwrap_or(0);
    (0..most)
        .map(|k| {
            let steps: Vec<&StepResult> = multi.iter().filter_map(|r| r.steps.get(k)).collect();
            FoldSummary {
                fold: k + 1,
                count: steps.len(),
                found: steps.iter().filter(|s| s.fold_found).count(),
                rmse: stat_of(&steps, |s| Some(s.rmse)),
                frechet: stat_of(&steps, |s| Some(s.frechet)),
                aligned_rmse: stat_of(&steps, |s| s.aligned_rmse),
                f1_error: stat_of(&steps, |s| s.angle_error.map(|a| a[0])),
                f2_error: stat_of(&steps, |s| s.angle_error.map(|a| a[1])),
            }
        })
        .collect()
}

fn summarise(category: &str, all: &[&SampleResult]) -> Summary {
    let results: Vec<&SampleResult> = all.iter().copied().filter(|r| r.dropped.is_none()).collect();
    let results = results.as_slice();
    let pick = |f: &dyn Fn(&SampleResult) -> Option<f64>| stat_of(results, |r| f(r));
    Summary {
        category: category.to_string(),
        count: results.len(),
        rmse: pick(&|r| r.rmse),
        frechet: pick(&|r| r.frechet),
        aligned_rmse: pick(&|r| r.aligned_rmse),
        fold_count_misses: results
            .iter()
            .filter(|r| r.error.is_none() && r.folds != r.expected_folds)
            .count(),
        errors: results.iter().filter(|r| r.error.is_some()).count(),
        dropped: all.len() - results.len(),
        f1_error: pick(&|r| r.angle_error.map(|a| a[0])),
        f2_error: pick(&|r| r.angle_error.map(|a| a[1])),
        by_fold: by_fold(results),
    }
}

/// Build the report from per-sample results.
pub fn report(samples: Vec<SampleResult>) -> Report {
    let mut by_category: BTreeMap<&str, Vec<&SampleResult>> = BTreeMap::new();
    for r in &samples {
        by_category.entry(r.category.as_str()).or_default().push(r);
    }
    let categories = by_category.iter().map(|(c, rs)| summarise(c, rs)).collect();
    let overall = summarise("overall", &samples.iter().collect::<Vec<_>>());
    Report { units: Units::default(), categories, overall, samples }
}

impl Report {
    /// The table as aligned text.
    pub fn table(&self) -> String {
        let mut out = row([
            "category", "count", "RMSE", "RMSE var", "Fréchet", "Fr. var", "aligned", "misses",
            "errors", "dropped", "f1 err°", "f2 err°",
        ]
        .map(String::from));
        for s in self.categories.iter().chain(std::iter::once(&self.overall)) {
            let counts = [s.errors, s.dropped].map(|c| c.to_string());
            out.push_str(&stats_row(
                &s.category,
                s.count,
                [s.rmse, s.frechet, s.aligned_rmse, s.f1_error, s.f2_error],
                s.fold_count_misses,
                counts,
            ));
            for f in &s.by_fold {
                let label = format!("  fold {}", f.fold);
                out.push_str(&stats_row(
                    &label,
                    f.count,
                    [f.rmse, f.frechet, f.aligned_rmse, f.f1_error, f.f2_error],
                    f.count - f.found,
                    [String::new(), String::new()],
                ));
            }
        }
        out
    }
}

/// One aligned line of the table.
fn row(cells: [String; 12]) -> String {
    let [c0, c1, c2, c3, c4, c5, c6, c7, c8, c9, c10, c11] = cells;
    format!("{c0:<20} {c1:>5} {c2:>9} {c3:>9} {c4:>9} {c5:>9} {c6:>9} {c7:>7} {c8:>6} {c9:>7} {c10:>9} {c11:>9}\n")
}

/// A row from statistics: RMSE and Fréchet with their variances, the aligned RMSE, angle
/// errors in degrees.
fn stats_row(
    label: &str,
    count: usize,
    [rmse, frechet, aligned, f1, f2]: [Option<Stat>; 5],
    misses: usize,
    [errors, dropped]: [String; 2],
) -> String {
    let mean = |s: Option<Stat>, scale: f64| {
        s.map_or("-".to_string(), |s| format!("{:.4}", s.mean * scale))
    };
    let var = |s: Option<Stat>| s.map_or("-".to_string(), |s| format!("{:.5}", s.var));
    let degrees = 180.0 / PI;
    row([
        label.to_string(),
        count.to_string(),
        mean(rmse, 1.0),
        var(rmse),
        mean(frechet, 1.0),
        var(frechet),
        mean(aligned, 1.0),
        misses.to_string(),
        errors,
        dropped,
        mean(f1, degrees),
        mean(f2, degrees),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scored(name: &str, category: &str, rmse: f64, folds: usize) -> SampleResult {
        SampleResult {
            rmse: Some(rmse),
            frechet: Some(2.0 * rmse),
            folds,
            expected_folds: 1,
            ..SampleResult::empty(name, category)
        }
    }

    #[test]
    fn rows_per_category_with_mean_variance_misses_errors_and_drops() {
        let results = vec![
            scored("a1", "a", 0.1, 1),
            scored("a2", "a", 0.3, 2),
            scored("b1", "b", 0.5, 1),
            SampleResult::unreadable("x.json", "could not parse JSON"),
            SampleResult::dropped("b2", "b", "broken mesh"),
        ];
        let r = report(results);
        let row = |c: &str| {
            r.categories.iter().find(|s| s.category == c).unwrap_or_else(|| panic!("no row {c}"))
        };
        let a = row("a");
        assert_eq!((a.count, a.fold_count_misses, a.errors, a.dropped), (2, 1, 0, 0));
        let rmse = a.rmse.expect("scored samples");
        assert!((rmse.mean - 0.2).abs() < 1e-12 && (rmse.var - 0.01).abs() < 1e-12, "{rmse:?}");
        let b = row("b");
        assert_eq!((b.count, b.dropped), (1, 1));
        assert_eq!(row("unreadable").errors, 1);
        assert!(r.table().contains("overall") && r.table().contains("f1 err°"));
        let json = serde_json::to_value(&r).unwrap();
        assert_eq!(json["units"], serde_json::json!({"angle": "rad", "length": "normalised"}));
    }
}
