//! Fitting fold curves: the paper's 20 starting lines, minimised with L-BFGS, with the
//! SPEC's three fixes.
//!
//! 1. The loss repeats in a1 with period 2πL, so a1 is bounded to [−π, π] (through
//!    a1 = π·sin u, which keeps L-BFGS unconstrained) and minima on the bound are dropped.
//! 2. Minima whose rim coordinates f = a0 + a1 lie within [`MERGE_EDGES`] edges of each other
//!    are one curve; the lower loss is kept.
//! 3. The rim coordinate of each kept curve is refined on the rim rings alone (rings
//!    d ≤ [`RIM_RINGS`] near f, a1 = 0) with Brent's method, since the straight line
//!    extrapolated to the rim is biased.

use std::f64::consts::PI;

use argmin::core::{CostFunction, Executor, Gradient, State};
use argmin::solver::brent::BrentOpt;
use argmin::solver::linesearch::MoreThuenteLineSearch;
use argmin::solver::quasinewton::LBFGS;

use super::loss::{exact_loss, ring_cells, wrap, Cell, RingTables};
use crate::disk::Disk;

/// Starting curves a0 = 2πm/STARTS, a1 = 0.
pub const STARTS: usize = 20;
/// Minima closer than this many edges at the rim are one curve.
pub const MERGE_EDGES: f64 = 4.0;
/// Rings used to refine a curve's rim coordinate.
pub const RIM_RINGS: usize = 4;
/// Half-width, in edges, of the rim window the refinement reads.
const RIM_WINDOW_EDGES: f64 = 6.0;
/// How far, in edges, the refinement may move a rim coordinate.
const RIM_SEARCH_EDGES: f64 = 2.0;
/// Bound on the slope a1.
const A1_BOUND: f64 = PI;

/// A fitted fold curve θ̂ = a0 + a1·r.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Curve {
    pub a0: f64,
    pub a1: f64,
    /// The paper's loss at the minimum (negative for a fold curve).
    pub loss: f64,
    /// Where the curve meets the rim, refined: the fold coordinate, in [0, 2π).
    pub rim: f64,
}

struct Problem<'a>(&'a RingTables);

impl CostFunction for Problem<'_> {
    type Param = Vec<f64>;
    type Output = f64;
    fn cost(&self, x: &Vec<f64>) -> Result<f64, argmin::core::Error> {
        Ok(self.0.loss_and_gradient(x[0], A1_BOUND * x[1].sin()).0)
    }
}

impl Gradient for Problem<'_> {
    type Param = Vec<f64>;
    type Gradient = Vec<f64>;
    fn gradient(&self, x: &Vec<f64>) -> Result<Vec<f64>, argmin::core::Error> {
        let (_, g) = self.0.loss_and_gradient(x[0], A1_BOUND * x[1].sin());
        Ok(vec![g[0], g[1] * A1_BOUND * x[1].cos()])
    }
}

/// Minimise the tabulated loss from one starting line; `None` when the solver fails.
fn minimise(tables: &RingTables, a0: f64) -> Option<(f64, f64, f64)> {
    let solver = LBFGS::new(MoreThuenteLineSearch::new(), 7).with_tolerance_grad(1e-9).ok()?.with_tolerance_cost(1e-12).ok()?;
    let result = Executor::new(Problem(tables), solver)
        .configure(|state| state.param(vec![a0, 0.0]).max_iters(200))
        .timer(false)
        .run()
        .ok()?;
    let state = result.state();
    let x = state.get_best_param()?;
    Some((x[0].rem_euclid(2.0 * PI), A1_BOUND * x[1].sin(), state.get_best_cost()))
}

/// Every distinct local minimum with negative loss, lowest loss first, rim coordinates refined.
pub fn fit_curves(g: &Disk) -> Vec<Curve> {
    let n = g.n();
    let tables = RingTables::new(g);
    let mut minima: Vec<(f64, f64, f64)> = (0..STARTS)
        .filter_map(|m| minimise(&tables, 2.0 * PI * m as f64 / STARTS as f64))
        .filter(|&(_, a1, loss)| loss < 0.0 && a1.abs() < A1_BOUND * (1.0 - 1e-3))
        .collect();
    minima.sort_by(|a, b| a.2.total_cmp(&b.2));
    let merge = MERGE_EDGES * 2.0 * PI / n as f64;
    let mut kept: Vec<(f64, f64, f64)> = Vec::new();
    for m in minima {
        let rim = m.0 + m.1;
        if kept.iter().all(|k| wrap(k.0 + k.1 - rim).abs() > merge) {
            kept.push(m);
        }
    }
    let rim_cells = rim_cells(g);
    let reach = RIM_SEARCH_EDGES * 2.0 * PI / n as f64;
    kept.into_iter()
        .map(|(a0, a1, loss)| {
            let rim = (a0 + a1).rem_euclid(2.0 * PI);
            // A refinement that runs to the edge of its range found no minimum near the line.
            let refined = refine_rim(&rim_cells, n, rim, rim - reach, rim + reach)
                .filter(|r| (wrap(r - rim).abs() - reach).abs() > 1e-3 * reach)
                .unwrap_or(rim);
            Curve { a0, a1, loss, rim: refined }
        })
        .collect()
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
pub fn rim_cells(g: &Disk) -> Vec<Cell> {
    (1..=RIM_RINGS.min(g.layers())).flat_map(|d| ring_cells(g, d)).collect()
}

/// Refine a rim coordinate on the rim rings near it, with the curve held radial, searching
/// angles in [lo, hi]. `None` when the rim holds no change there or the solver fails.
pub fn refine_rim(rim_cells: &[Cell], n: usize, rim: f64, lo: f64, hi: f64) -> Option<f64> {
    let edge = 2.0 * PI / n as f64;
    let near: Vec<Cell> = rim_cells
        .iter()
        .filter(|c| wrap(c.angle - rim).abs() <= RIM_WINDOW_EDGES * edge)
        .map(|c| Cell { angle: rim + wrap(c.angle - rim), ..*c })
        .collect();
    let (lo, hi) = (rim + wrap(lo - rim), rim + wrap(hi - rim));
    // Only a changed rim cell (a vertex) within the searched angles says where the fold is;
    // change elsewhere (pairs reaching a nearby corner) would pull the minimum to a bound.
    let tiny = 1e-9 * edge;
    let informative =
        near.iter().any(|c| c.layer == 1 && c.angle >= lo - tiny && c.angle <= hi + tiny && c.value > super::FLAT_DIFF);
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
        .map(|a| a.rem_euclid(2.0 * PI))
}
