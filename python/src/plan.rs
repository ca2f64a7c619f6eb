//! What to do next and whether it was done: `close.interpolate` (a folding motion),
//! `close.plan`, `close.verify` and `close.distance`, as the server's routes answer them.

use close_core::budget::Budget;
use close_core::geometry::{Fold, Folding, Line, Point2, Vector2};
use numpy::{IntoPyArray, PyArray3};
use pyo3::prelude::*;

use crate::analysis::{analysis_for, PyAnalysis};
use crate::convert::{float_array, frames_array, points, to_python};
use crate::errors::{close_error, invalid};

/// A folding motion (radians, vertex k at 2πk/N) on `border` ((N, 3), the flat border, or a
/// folded state with its flat `reference`): between two folds `from_` (f1, f2) → `to`
/// (g1, g2), each endpoint moving along the border circle; or one fold's `arcs` (an analysis
/// step's `arcs`, [(a, b), ...]) turned over together about `line` (its `line`, a dict
/// {"point": (x, y), "direction": (dx, dy)}; by default through the first arc's start and the
/// last arc's end). `prior`: folds made on the flat `border` first, in order, each a dict
/// with its "arcs" and "line" as an analysis step's `folds` entries give them: the motion
/// starts from the state they leave, so fold k of a sequence plays after folds 1…k−1 (no
/// `reference` then). Returns a (steps, N, 3) array of borders, as `POST /api/interpolate`
/// does.
#[pyfunction]
#[pyo3(signature = (border, from_ = None, to = None, steps = 60, *, reference = None, arcs = None, line = None, prior = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn interpolate<'py>(
    py: Python<'py>,
    border: &Bound<'py, PyAny>,
    from_: Option<(f64, f64)>,
    to: Option<(f64, f64)>,
    steps: usize,
    reference: Option<&Bound<'py, PyAny>>,
    arcs: Option<Vec<[f64; 2]>>,
    line: Option<&Bound<'py, PyAny>>,
    prior: Option<Vec<Bound<'py, PyAny>>>,
) -> PyResult<Bound<'py, PyArray3<f64>>> {
    let border = points(border, "border")?;
    let reference = reference.map(|r| points(r, "reference")).transpose()?;
    let pair = |p: (f64, f64)| Fold::new(p.0, p.1);
    let line = line.map(fold_line).transpose()?;
    let arcs = arcs.map(|arcs| arcs.into_iter().map(close_core::geometry::Arc::from).collect());
    let motion = close_core::interpolate::Motion::of(from_.map(pair), to.map(pair), arcs, line)
        .map_err(close_error)?;
    let prior = prior.unwrap_or_default().iter().map(prior_fold).collect::<PyResult<Vec<_>>>()?;
    Budget::SERVER.interpolation(border.len(), steps).map_err(close_error)?;
    let motion = py
        .detach(|| close_core::interpolate::interpolate(border, reference, &prior, &motion, steps))
        .map_err(close_error)?;
    frames_array(py, &motion.borders)
}

/// A fold made before a motion, given as an analysis step's `folds` entry: a dict with its
/// "arcs" [(a, b), ...] and its "line" (or None).
pub(crate) fn prior_fold(fold: &Bound<'_, PyAny>) -> PyResult<Folding> {
    let expected = "prior: each fold a dict with \"arcs\" [(a, b), ...] and \"line\" (or None)";
    let arcs: Vec<[f64; 2]> =
        fold.get_item("arcs").and_then(|a| a.extract()).map_err(|_| invalid(expected.into()))?;
    let arcs: Vec<close_core::geometry::Arc> = arcs.into_iter().map(Into::into).collect();
    let line = match fold.get_item("line") {
        Ok(line) if !line.is_none() => Some(fold_line(&line)?),
        _ => None,
    };
    Ok(Folding { fold: Fold::span(&arcs).unwrap_or_default(), arcs, line })
}

/// A fold line given as an analysis reports it: {"point": (x, y), "direction": (dx, dy)}.
pub(crate) fn fold_line(line: &Bound<'_, PyAny>) -> PyResult<Line> {
    let pair = |key: &str| -> PyResult<[f64; 2]> {
        line.get_item(key)
            .and_then(|v| v.extract())
            .map_err(|_| invalid(format!("line: expected a dict {{\"point\": (x, y), \"direction\": (dx, dy)}}, without a usable \"{key}\"")))
    };
    let ([x, y], [dx, dy]) = (pair("point")?, pair("direction")?);
    Ok(Line { point: Point2::new(x, y), direction: Vector2::new(dx, dy) })
}

/// The folds of a plan's goal: one fold (g1, g2), or folds in order as a (K, 2) array-like
/// (empty: the flat cloth).
pub(crate) fn goal_folds(goal: &Bound<'_, PyAny>) -> PyResult<Vec<Fold>> {
    if let Ok((g1, g2)) = goal.extract::<(f64, f64)>() {
        return Ok(vec![Fold::new(g1, g2)]);
    }
    let array = float_array(goal)?;
    let view = array.as_array();
    match *view.shape() {
        // No fold: the flat cloth.
        [0] => Ok(Vec::new()),
        [2] => Ok(vec![Fold::new(view[0], view[1])]),
        [_, 2] => Ok(view.rows().into_iter().map(|r| Fold::new(r[0], r[1])).collect()),
        ref shape => Err(invalid(format!(
            "goal: expected one fold (g1, g2) or folds in order as a (K, 2) array, got shape {shape:?}"
        ))),
    }
}

/// How to reach the goal from the state a sample ends in: the answer of `POST /api/plan`
/// ({"case", "steps": [{"action", "fold", "corners", "picks", "line"}], ...}). `goal` is one
/// fold (g1, g2) in radians, or folds made in order as a (K, 2) array-like (each on the
/// state the ones before it left). Takes a `close.Sample` (or frames: analysed first →
/// last) or a `close.Analysis` (an unpickled one too: it is redone from the frames its
/// pickle carries). Each step's `corners` are 1-based corner numbers (corner k is
/// `Analysis.corners[k - 1]`), with the vertex of each beside them in `corner_vertices`;
/// picks and `corner_vertices` are the input's vertex indices (through `border_indices`).
#[pyfunction]
pub(crate) fn plan<'py>(
    py: Python<'py>,
    sample_or_analysis: &Bound<'py, PyAny>,
    goal: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let goal = goal_folds(goal)?;
    let analysis = analysis_for(py, sample_or_analysis)?;
    let answer = close_core::plan::answer(&analysis, &goal).map_err(close_error)?;
    to_python(py, &answer)
}

/// `close plan FILES --goal G1,G2`'s text (without `--json`): the plan from a sample, or
/// frames, or an analysis.
#[pyfunction]
pub(crate) fn _plan_text(
    py: Python<'_>,
    sample_or_analysis: &Bound<'_, PyAny>,
    goal: &Bound<'_, PyAny>,
) -> PyResult<String> {
    let goal = goal_folds(goal)?;
    let analysis = analysis_for(py, sample_or_analysis)?;
    let plan = close_core::plan::plan_for(&analysis, &goal).map_err(close_error)?;
    Ok(plan.text())
}

/// Fold sequences given to `close.distance` / `close.verify`: a `close.Analysis` (its folds),
/// a dict with "folds" (a CloSE value, `Analysis.close`), or an array-like of folds: (K, 2)
/// for one sequence, (B, K, 2) for a batch whose shorter sequences end in rows of NaN.
/// Returns the numbers (row-major), the sequence count (`None`: one sequence, not a batch)
/// and the width K.
pub(crate) fn fold_rows(
    obj: &Bound<'_, PyAny>,
    what: &str,
) -> PyResult<(Vec<f64>, Option<usize>, usize)> {
    if let Ok(a) = obj.cast::<PyAnalysis>() {
        let folds = a.get().folds();
        let width = folds.len();
        return Ok((folds.into_iter().flat_map(|(f1, f2)| [f1, f2]).collect(), None, width));
    }
    let folds = match obj.cast::<pyo3::types::PyDict>() {
        Ok(dict) => dict
            .get_item("folds")?
            .ok_or_else(|| invalid(format!("{what}: a dict needs \"folds\" (a CloSE value)")))?,
        Err(_) => obj.clone(),
    };
    let array = float_array(&folds)?;
    let view = array.as_array();
    let values = || view.iter().copied().collect::<Vec<f64>>();
    match *view.shape() {
        // An empty list: the flat cloth.
        [0] => Ok((Vec::new(), None, 0)),
        [k, 2] => Ok((values(), None, k)),
        [count, k, 2] => Ok((values(), Some(count), k)),
        ref shape => Err(invalid(format!(
            "{what}: expected folds as a (K, 2) array or a batch (B, K, 2), got shape {shape:?}"
        ))),
    }
}

/// The distance between two states of one cloth (see `close_core::distance`): by default
/// the fold distance, in shares of the border (moving one fold point by one edge costs 1/N,
/// a missing or extra fold its folded share); `kind="geometric"`, the aligned XY RMSE of the
/// two predicted borders in normalised units (needs `border`, the flat start, or two
/// Analyses). `a`, `b`: Analyses, CloSE dicts, (K, 2) arrays of folds, or (B, K, 2) batches
/// (NaN rows pad shorter sequences; a single sequence is paired with every one of a batch):
/// a float for two states, a (B,) array for a batch.
#[pyfunction]
#[pyo3(signature = (a, b, *, kind = "folds", border = None))]
pub(crate) fn distance<'py>(
    py: Python<'py>,
    a: &Bound<'py, PyAny>,
    b: &Bound<'py, PyAny>,
    kind: &str,
    border: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    use close_core::distance::{between, fold_distances, geometric_distances, FoldBatch};
    let geometric = match kind {
        "folds" => false,
        "geometric" => true,
        _ => return Err(invalid(format!("kind {kind:?}: expected \"folds\" or \"geometric\""))),
    };
    if let (true, None, Ok(x), Ok(y)) =
        (geometric, border, a.cast::<PyAnalysis>(), b.cast::<PyAnalysis>())
    {
        let (x, y) = (x.get().analysis(py)?, y.get().analysis(py)?);
        let d = between(&x, &y).map_err(close_error)?;
        return Ok(d.geometric.unwrap_or(f64::NAN).into_pyobject(py)?.into_any());
    }
    let flat = match (geometric, border) {
        (true, None) => {
            return Err(invalid(
                "kind=\"geometric\" needs the flat `border` (or two Analyses)".into(),
            ))
        }
        (true, Some(border)) => {
            let prepared = close_core::border::prepare(vec![points(border, "border")?])
                .map_err(close_error)?;
            prepared.frames.into_iter().next()
        }
        (false, _) => None,
    };
    let ((xa, ca, wa), (xb, cb, wb)) = (fold_rows(a, "a")?, fold_rows(b, "b")?);
    let batch = ca.is_some() || cb.is_some();
    let out = py
        .detach(|| {
            let x = FoldBatch::new(&xa, ca.unwrap_or(1), wa)?;
            let y = FoldBatch::new(&xb, cb.unwrap_or(1), wb)?;
            match &flat {
                Some(flat) => geometric_distances(flat, &x, &y),
                None => fold_distances(&x, &y),
            }
        })
        .map_err(close_error)?;
    match out[..] {
        [one] if !batch => Ok(one.into_pyobject(py)?.into_any()),
        _ => Ok(out.into_pyarray(py).into_any()),
    }
}

/// Did the state a sample ends in reach the goal folds? The answer of `POST /api/verify`
/// ({"reached", "text", "distance", "folds", "extra", "plan", ...}). `observed`: a
/// `close.Sample` (or frames, analysed first → last) or a `close.Analysis`; `goal`: folds
/// (g1, g2) in order, as a list, a (K, 2) array, a CloSE dict or an Analysis.
#[pyfunction]
#[pyo3(signature = (observed, goal, *, tolerance_edges = 1.5, tolerance_rmse = 0.03))]
pub(crate) fn verify<'py>(
    py: Python<'py>,
    observed: &Bound<'py, PyAny>,
    goal: &Bound<'py, PyAny>,
    tolerance_edges: f64,
    tolerance_rmse: f64,
) -> PyResult<Bound<'py, PyAny>> {
    use close_core::verify::{check_goal, Goal, Tolerance};
    let (values, count, _) = fold_rows(goal, "goal")?;
    if count.is_some() {
        return Err(invalid("goal: one sequence of folds, (K, 2), not a batch".into()));
    }
    let goal = Goal::folds(values.chunks(2).map(|f| [f[0], f[1]]));
    // A bad goal is refused before the sample is analysed.
    check_goal(&goal, None).map_err(close_error)?;
    let analysis = analysis_for(py, observed)?;
    let tolerance = Tolerance { edges: tolerance_edges, aligned_rmse: tolerance_rmse };
    let answer = py
        .detach(|| close_core::verify::verify(&analysis, &goal, tolerance))
        .map_err(close_error)?;
    to_python(py, &answer)
}
