//! Fitting fold curves (Kamat, Borràs, Torras, "CloSE", Sec. III-C): the paper's 20
//! starting lines, minimised with L-BFGS, with three fixes that make it work in practice.
//!
//! 1. The loss repeats in a1 with period 2πL, so a1 is bounded to [−π, π] (through
//!    a1 = π·sin u, which keeps L-BFGS unconstrained) and minima on the bound are dropped.
//! 2. Minima whose rim coordinates f = a0 + a1 lie within [`CurveParams::merge_edges`] edges of
//!    each other are one curve; the lower loss is kept.
//! 3. The rim coordinate of each kept curve is refined on the rim rings alone (rings
//!    d ≤ [`CurveParams::rim_rings`] near f, a1 = 0) with Brent's method, since the straight line
//!    extrapolated to the rim is biased.

use std::cell::RefCell;
use std::f64::consts::PI;

use argmin::core::{CostFunction, Executor, Gradient, State};
use argmin::solver::brent::BrentOpt;
use argmin::solver::linesearch::MoreThuenteLineSearch;
use argmin::solver::quasinewton::LBFGS;
use nalgebra::Vector2;
use rayon::prelude::*;

use super::loss::{exact_loss, ring_cells, Cell, RingTables};
use super::params::{CurveParams, Params};
use crate::angle::{edge, wrap_pi, wrap_tau, TAU};
use crate::disk::Disk;
use crate::geometry::Fold;

/// Starting curves a0 = 2πm/STARTS, a1 = 0: the paper's 20.
pub const STARTS: usize = 20;
/// Bound on the slope a1: the loss repeats in a1 with period 2πL (fix 1 above).
const A1_BOUND: f64 = PI;

/// A fitted fold curve θ̂ = a0 + a1·r.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Curve {
    /// The curve's angle at the disk's centre, r = 0 (radians).
    pub a0: f64,
    /// Its change of angle from the centre to the rim, r = 1 (radians per disk radius).
    pub a1: f64,
    /// The paper's loss at the minimum (negative for a fold curve).
    pub loss: f64,
    /// Where the curve meets the rim, refined: the fold coordinate, in [0, 2π) (radians).
    pub rim: f64,
}

/// A point of the solver's parameters, the loss there and its gradient.
type Evaluated = ([f64; 2], f64, [f64; 2]);

/// The loss in the solver's parameters (a0, u) with a1 = π·sin u, and its gradient.
struct Problem<'a> {
    tables: &'a RingTables,
    /// The last point evaluated: the line search asks for the cost and then the gradient of
    /// the same point, and one table pass gives both.
    last: RefCell<Option<Evaluated>>,
}

impl Problem<'_> {
    fn at(&self, x: &Vector2<f64>) -> (f64, [f64; 2]) {
        let key = [x[0], x[1]];
        if let Some((at, loss, gradient)) = *self.last.borrow() {
            if at == key {
                return (loss, gradient);
            }
        }
        let (loss, g) = self.tables.loss_and_gradient(x[0], A1_BOUND * x[1].sin());
        let gradient = [g[0], g[1] * A1_BOUND * x[1].cos()];
        *self.last.borrow_mut() = Some((key, loss, gradient));
        (loss, gradient)
    }
}

impl CostFunction for Problem<'_> {
    type Param = Vector2<f64>;
    type Output = f64;
    fn cost(&self, x: &Vector2<f64>) -> Result<f64, argmin::core::Error> {
        Ok(self.at(x).0)
    }
}

impl Gradient for Problem<'_> {
    type Param = Vector2<f64>;
    type Gradient = Vector2<f64>;
    fn gradient(&self, x: &Vector2<f64>) -> Result<Vector2<f64>, argmin::core::Error> {
        Ok(self.at(x).1.into())
    }
}

/// Minimise the tabulated loss from one starting line; `None` when the solver fails.
fn minimise(tables: &RingTables, a0: f64) -> Option<(f64, f64, f64)> {
    let solver = LBFGS::new(MoreThuenteLineSearch::new(), 7)
        .with_tolerance_grad(1e-9)
        .ok()?
        .with_tolerance_cost(1e-12)
        .ok()?;
    let result = Executor::new(Problem { tables, last: RefCell::new(None) }, solver)
        .configure(|state| state.param(Vector2::new(a0, 0.0)).max_iters(200))
        .timer(false)
        .run()
        .ok()?;
    let state = result.state();
    let x = state.get_best_param()?;
    Some((wrap_tau(x[0]), A1_BOUND * x[1].sin(), state.get_best_cost()))
}

/// Every distinct local minimum with negative loss of the diff disk `g` (tabulated in
/// `tables`), lowest loss first, rim coordinates refined: the paper's free fit, with the
/// knobs of `params` ([`Params::curves`], and [`super::params::DetectParams::flat_diff`]
/// for a rim cell that changed).
pub fn fit_curves(g: &Disk, tables: &RingTables, params: &Params) -> Vec<Curve> {
    let curves = &params.curves;
    let n = g.n();
    let mut minima: Vec<(f64, f64, f64)> = (0..STARTS)
        .into_par_iter()
        .filter_map(|m| minimise(tables, TAU * m as f64 / STARTS as f64))
        .filter(|&(_, a1, loss)| loss < 0.0 && a1.abs() < A1_BOUND * (1.0 - 1e-3))
        .collect();
    minima.sort_by(|a, b| a.2.total_cmp(&b.2));
    let merge = curves.merge_edges * edge(n);
    let mut kept: Vec<(f64, f64, f64)> = Vec::new();
    for m in minima {
        let rim = m.0 + m.1;
        if kept.iter().all(|k| wrap_pi(k.0 + k.1 - rim).abs() > merge) {
            kept.push(m);
        }
    }
    let rim_cells = rim_cells(g, curves);
    let reach = curves.rim_search_edges * edge(n);
    kept.into_iter()
        .map(|(a0, a1, loss)| {
            let rim = wrap_tau(a0 + a1);
            // A refinement that runs to the edge of its range found no minimum near the line.
            let window = (rim - reach, rim + reach);
            let refined = rim_minimum(&rim_cells, n, rim, window, params)
                .filter(|r| (wrap_pi(r - rim).abs() - reach).abs() > 1e-3 * reach)
                .unwrap_or(rim);
            Curve { a0, a1, loss, rim: refined }
        })
        .collect()
}

/// Slopes a1 tried per fold point before the best is refined by golden section: half a
/// cell apart (π/N), which resolves a cell on the inner rings, and at most one every half
/// degree of [−π, π], the bound the paper's fit keeps a1 in.
fn slopes(n: usize) -> usize {
    (2 * n + 1).min(721)
}

/// The curves of a fold found some other way (the cut and synthesis), over the step's diff
/// disk (tabulated in `tables`, N = `n`): for each fold point f, the paper's curve
/// θ̂ = a0 + a1·r whose rim end is f (a0 = f − a1), the slope a1 ∈ [−π, π] minimising the
/// paper's loss. A free curve may end several edges from the fold point or be missing, so
/// the curves of the fold are fitted through its points: each ends where the fold is
/// reported. A fold point whose best curve has no negative loss (no change along any line
/// through it) gets none.
pub fn curves_through(tables: &RingTables, n: usize, fold: Fold) -> Vec<Curve> {
    let slopes = slopes(n);
    let step = 2.0 * A1_BOUND / (slopes - 1) as f64;
    // The two points in parallel: this runs after the fold is found, with nothing beside it.
    [fold.f1, fold.f2]
        .par_iter()
        .filter_map(|&rim| {
            let scan: Vec<(f64, f64)> =
                (0..slopes).map(|k| -A1_BOUND + k as f64 * step).map(|a1| (rim - a1, a1)).collect();
            let best =
                scan.iter().zip(tables.losses(&scan)).min_by(|a, b| a.1.total_cmp(&b.1))?.0 .1;
            // Brent's method within a grid step either side of the best slope.
            let solver = BrentOpt::new((best - step).max(-A1_BOUND), (best + step).min(A1_BOUND));
            let a1 = Executor::new(SlopeProblem { tables, rim }, solver)
                .configure(|state| state.max_iters(100))
                .timer(false)
                .run()
                .ok()
                .and_then(|r| r.state().get_best_param().copied())
                .unwrap_or(best);
            let loss = SlopeProblem { tables, rim }.loss(a1);
            (loss < 0.0).then_some(Curve { a0: rim - a1, a1, loss, rim })
        })
        .collect()
}

/// The paper's loss of the curve through the rim point `rim` as a function of its slope a1.
struct SlopeProblem<'a> {
    tables: &'a RingTables,
    rim: f64,
}

impl SlopeProblem<'_> {
    fn loss(&self, a1: f64) -> f64 {
        self.tables.loss_and_gradient(self.rim - a1, a1).0
    }
}

impl CostFunction for SlopeProblem<'_> {
    type Param = f64;
    type Output = f64;
    fn cost(&self, a1: &f64) -> Result<f64, argmin::core::Error> {
        Ok(self.loss(*a1))
    }
}

struct RimProblem<'a> {
    cells: &'a [Cell],
}

impl CostFunction for RimProblem<'_> {
    type Param = f64;
    type Output = f64;
    fn cost(&self, a0: &f64) -> Result<f64, argmin::core::Error> {
        Ok(exact_loss(self.cells, *a0, 0.0))
    }
}

/// The cells of the rim rings, which the refinement reads.
pub(crate) fn rim_cells(g: &Disk, params: &CurveParams) -> Vec<Cell> {
    (1..=params.rim_rings.min(g.layers())).flat_map(|d| ring_cells(g, d)).collect()
}

/// Refine a rim coordinate on the rim rings near it, with the curve held radial, searching
/// angles in [lo, hi]. `None` when the rim holds no change there or the solver fails.
pub(crate) fn rim_minimum(
    rim_cells: &[Cell],
    n: usize,
    rim: f64,
    (lo, hi): (f64, f64),
    params: &Params,
) -> Option<f64> {
    let edge = edge(n);
    let near: Vec<Cell> = rim_cells
        .iter()
        .filter(|c| wrap_pi(c.angle - rim).abs() <= params.curves.rim_window_edges * edge)
        .map(|c| Cell { angle: rim + wrap_pi(c.angle - rim), ..*c })
        .collect();
    let (lo, hi) = (rim + wrap_pi(lo - rim), rim + wrap_pi(hi - rim));
    // Only a changed rim cell (a vertex) within the searched angles says where the fold is;
    // change elsewhere (pairs reaching a nearby corner) would pull the minimum to a bound.
    let tiny = 1e-9 * edge;
    let informative = near.iter().any(|c| {
        c.layer == 1
            && c.angle >= lo - tiny
            && c.angle <= hi + tiny
            && c.value > params.detect.flat_diff
    });
    if !informative {
        return None;
    }
    let solver = BrentOpt::new(lo, hi);
    Executor::new(RimProblem { cells: &near }, solver)
        .configure(|state| state.max_iters(100))
        .timer(false)
        .run()
        .ok()
        .and_then(|r| r.state().get_best_param().copied())
        .map(wrap_tau)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::disk::position;

    /// A diff disk with a ridge of change along each curve θ = rim + a1·(r − 1) of `ridges`.
    fn ridged(n: usize, ridges: &[(f64, f64)]) -> Disk {
        let values = (0..n)
            .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
            .map(|(i, j)| {
                let p = position(n, i, j);
                ridges
                    .iter()
                    .map(|&(rim, a1)| {
                        (-(wrap_pi(p.angle - rim - a1 * (p.radius - 1.0)) * 8.0).powi(2)).exp()
                    })
                    .sum()
            })
            .collect();
        Disk::from_values(n, values).unwrap()
    }

    fn fit(g: &Disk) -> Vec<Curve> {
        let params = Params::default();
        fit_curves(g, &RingTables::new(g, &params.curves), &params)
    }

    #[test]
    fn the_curves_of_a_fold_end_at_its_points() {
        let n = 40;
        let g = ridged(n, &[(1.0, 0.0), (4.0, 0.5)]);
        // The fold points sit a little off the ridges' rim ends, as a cut's may: the curves
        // still end at the fold points, and follow the ridges' slopes.
        let tables = |g: &Disk| RingTables::new(g, &CurveParams::default());
        let curves = curves_through(&tables(&g), n, Fold::new(1.05, 3.95));
        assert_eq!(curves.len(), 2);
        for (curve, (f, slope)) in curves.iter().zip([(1.05, 0.0), (3.95, 0.5)]) {
            assert!((curve.a0 + curve.a1 - f).abs() < 1e-12 && curve.rim == f, "{curve:?}");
            assert!((curve.a1 - slope).abs() < 0.15 && curve.loss < 0.0, "{curve:?}");
        }
        // No change at all: no line through a fold point has negative loss, no curve.
        assert!(curves_through(&tables(&ridged(n, &[])), n, Fold::new(1.05, 3.95)).is_empty());
    }

    #[test]
    fn two_ridges_give_two_curves_at_their_angles() {
        let n = 60;
        let curves = fit(&ridged(n, &[(1.0, 0.0), (4.0, 0.0)]));
        assert!(curves.len() >= 2, "{curves:?}");
        let mut rims = [curves[0].rim, curves[1].rim];
        rims.sort_by(f64::total_cmp);
        assert!((rims[0] - 1.0).abs() < edge(n) && (rims[1] - 4.0).abs() < edge(n), "{rims:?}");
        assert!(curves.iter().all(|c| c.loss < 0.0 && c.a1.abs() < A1_BOUND));
    }

    #[test]
    fn minima_closer_than_the_merge_distance_are_one_curve() {
        let n = 60;
        let curves = fit(&ridged(n, &[(2.0, 0.0)]));
        let near: Vec<_> = curves
            .iter()
            .filter(|c| wrap_pi(c.rim - 2.0).abs() < CurveParams::default().merge_edges * edge(n))
            .collect();
        assert_eq!(near.len(), 1, "{curves:?}");
    }

    #[test]
    fn no_change_gives_no_curve() {
        assert!(fit(&Disk::from_values(20, vec![0.0; 190]).unwrap()).is_empty());
    }

    #[test]
    fn the_free_fit_finds_a_radial_ridge() {
        // A diff disk whose change runs along the radial line at 1 rad.
        let n = 40;
        let values = (0..n)
            .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
            .map(|(i, j)| {
                (-(crate::angle::wrap_pi(position(n, i, j).angle - 1.0) * 8.0).powi(2)).exp()
            })
            .collect();
        let g = Disk::from_values(n, values).unwrap();
        let params = crate::fold::Params::default();
        let curves =
            fit_curves(&g, &crate::fold::loss::RingTables::new(&g, &params.curves), &params);
        assert!(crate::angle::distance(curves[0].rim, 1.0) < crate::angle::edge(n));
    }

    #[test]
    fn each_fold_point_gets_the_radial_curve_ending_there() {
        // A diff disk whose change runs along the radial lines at 1 rad and 4 rad.
        let n = 40;
        let ridge =
            |angle: f64, at: f64| (-(crate::angle::wrap_pi(angle - at) * 8.0).powi(2)).exp();
        let values = (0..n)
            .flat_map(|i| (i + 1..n).map(move |j| position(n, i, j).angle))
            .map(|angle| ridge(angle, 1.0) + ridge(angle, 4.0))
            .collect();
        let g = Disk::from_values(n, values).unwrap();
        let tables = RingTables::new(&g, &crate::fold::params::CurveParams::default());
        let curves = curves_through(&tables, n, crate::geometry::Fold::new(1.0, 4.0));
        // Each fold point gets the radial curve ending there.
        assert_eq!(curves.iter().map(|c| c.rim).collect::<Vec<_>>(), vec![1.0, 4.0]);
        assert!(curves.iter().all(|c| c.a1.abs() < 0.1 && c.loss < 0.0));
    }
}
