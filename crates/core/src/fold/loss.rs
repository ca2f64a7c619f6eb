//! The paper's fold-curve loss and a fast way to evaluate it.
//!
//! Kamat, Borràs, Torras, "CloSE", Sec. III-C (fold coordinates): a fold curve is the line
//! θ̂ = a0 + a1·r on the diff disk, fitted by minimising
//!
//! L(a0, a1) = Σ_i k1·δ_i²·p1(δ_i)·√g_i − k2·p2(δ_i)·g_i,
//! δ_i = wrap_pi(θ_i − θ̂(r_i)) ∈ (−π, π], p1(δ) = exp(−δ²/(2τ²)), p2(δ) = 1/(k3 + δ²),
//!
//! over the cells i of the diff disk (value g_i ≥ 0 at radius r_i, angle θ_i), with
//! k1 = 0.1, k2 = 0.05, k3 = 0.1, τ = π/4.
//!
//! The term is `√g·A(δ) − g·B(δ)`, so on one ring (one radius) the loss of every curve is a
//! circular cross-correlation of the ring's √g and g profiles with the kernels A and B.
//! [`RingTables`] evaluates it once per ring on a grid of angles (S points per edge); a
//! curve then costs one interpolation per ring instead of a pass over all N²/2 cells, which is
//! what makes 20 L-BFGS starts affordable at N = 300.

use std::f64::consts::PI;

use rayon::prelude::*;
use realfft::num_complex::Complex;
use realfft::RealFftPlanner;

use super::params::CurveParams;
use crate::angle::wrap_pi;
use crate::disk::{ring_angle, Disk};

/// The paper's k1, k2, k3 (the weights of the loss's two terms, and p2's width).
const K1: f64 = 0.1;
const K2: f64 = 0.05;
const K3: f64 = 0.1;
/// The paper's τ: the width (standard deviation, radians) of p1's Gaussian, past which a
/// cell's angular offset from the curve stops being penalised. Not [`crate::angle::TAU`].
pub const GAUSSIAN_WIDTH: f64 = PI / 4.0;

/// Kernel of the √g term: k1·δ²·exp(−δ²/2τ²), τ = [`GAUSSIAN_WIDTH`].
#[inline]
pub(crate) fn kernel_sqrt_g(delta: f64) -> f64 {
    K1 * delta * delta * (-delta * delta / (2.0 * GAUSSIAN_WIDTH * GAUSSIAN_WIDTH)).exp()
}

/// Kernel of the g term (with its minus sign taken out): k2/(k3 + δ²).
#[inline]
pub(crate) fn kernel_g(delta: f64) -> f64 {
    K2 / (K3 + delta * delta)
}

/// Loss of one cell of value `g` at angular offset `delta` from the curve.
#[inline]
pub(crate) fn cell_loss(g: f64, delta: f64) -> f64 {
    g.sqrt() * kernel_sqrt_g(delta) - g * kernel_g(delta)
}

/// One cell of the diff disk, as the loss sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cell {
    pub layer: usize,
    pub radius: f64,
    pub angle: f64,
    pub value: f64,
}

/// Every cell of ring `d` of `disk` (N cells; on the centre ring of an even N each pair
/// appears at both of its angles).
pub(crate) fn ring_cells(disk: &Disk, d: usize) -> impl Iterator<Item = Cell> + '_ {
    let n = disk.n();
    let l = disk.layers();
    let radius = (l - d + 1) as f64 / l as f64;
    (0..n).map(move |a| Cell {
        layer: d,
        radius,
        angle: ring_angle(n, d, a),
        value: disk.ring_value(d, a),
    })
}

/// Exact loss of the curve θ̂ = a0 + a1·r over the given cells.
pub(crate) fn exact_loss(cells: &[Cell], a0: f64, a1: f64) -> f64 {
    cells.iter().map(|c| cell_loss(c.value, wrap_pi(c.angle - a0 - a1 * c.radius))).sum()
}

/// The loss of every ring tabulated on an angular grid (see the module doc).
#[derive(Debug, Clone)]
pub struct RingTables {
    /// Grid points on the circle.
    grid: usize,
    /// Grid step, 2π/grid.
    step: f64,
    /// For each ring used: its radius, its weight, and its loss at every grid angle (padded:
    /// entry k is grid point k − 1, cyclically, for k in 0..grid + 3).
    rings: Vec<(f64, f64, Vec<f64>)>,
}

impl RingTables {
    /// Tabulate the loss of the diff disk `g`, on at most [`CurveParams::max_rings`] rings
    /// (beyond it every k-th ring stands for k rings) of at most [`CurveParams::max_grid`]
    /// grid angles.
    ///
    /// Each ring's table is the circular convolution of its √g and g profiles with the
    /// kernels, computed by FFT: O(grid·log grid) per ring instead of O(N·grid).
    pub fn new(g: &Disk, params: &CurveParams) -> RingTables {
        let n = g.n();
        // Half-edge cell angles fall on the grid exactly up to `max_grid` points; beyond it,
        // cells share grid points (their weights add), which bounds the work for huge N.
        let per_edge = if n <= 128 { 4 } else { 2 };
        let grid = (per_edge * n).min(params.max_grid);
        let step = crate::angle::TAU / grid as f64;
        let mut planner = RealFftPlanner::<f64>::new();
        let (forward, inverse) = (planner.plan_fft_forward(grid), planner.plan_fft_inverse(grid));
        // Kernel spectra; kernels are indexed by (q − p) mod grid, i.e. at δ = −(q − p)·step.
        let spectrum = |f: fn(f64) -> f64| -> Vec<Complex<f64>> {
            let mut kernel: Vec<f64> = (0..grid).map(|t| f(wrap_pi(-(t as f64) * step))).collect();
            let mut out = forward.make_output_vec();
            forward.process(&mut kernel, &mut out).expect("buffers sized by the plan");
            out
        };
        let (ka, kb) = (spectrum(kernel_sqrt_g), spectrum(kernel_g));
        let l = g.layers();
        let stride = l.div_ceil(params.max_rings).max(1);
        let rings = (1..=l)
            .step_by(stride)
            .collect::<Vec<_>>()
            .into_par_iter()
            .map(|d| {
                // The ring's √g and g profiles on the grid.
                let (mut sqrt_g, mut plain_g) = (vec![0.0; grid], vec![0.0; grid]);
                for a in 0..n {
                    let value = g.ring_value(d, a);
                    if value > 0.0 {
                        let p = (ring_angle(n, d, a) / step).round() as usize % grid;
                        sqrt_g[p] += value.sqrt();
                        plain_g[p] += value;
                    }
                }
                let (mut s, mut p) = (forward.make_output_vec(), forward.make_output_vec());
                forward.process(&mut sqrt_g, &mut s).expect("buffers sized by the plan");
                forward.process(&mut plain_g, &mut p).expect("buffers sized by the plan");
                let mut product: Vec<Complex<f64>> = s
                    .iter()
                    .zip(&p)
                    .zip(ka.iter().zip(&kb))
                    .map(|((s, p), (a, b))| s * a - p * b)
                    .collect();
                // The spectrum of a real signal: its DC and Nyquist terms are real.
                product[0].im = 0.0;
                if let Some(last) = product.last_mut().filter(|_| grid.is_multiple_of(2)) {
                    last.im = 0.0;
                }
                let mut table = inverse.make_output_vec();
                inverse.process(&mut product, &mut table).expect("buffers sized by the plan");
                // Padded by one point before and two after, so an interpolation reads four
                // consecutive entries without wrapping.
                let padded =
                    (0..grid + 3).map(|k| table[(k + grid - 1) % grid] / grid as f64).collect();
                ((l - d + 1) as f64 / l as f64, stride as f64, padded)
            })
            .collect();
        RingTables { grid, step, rings }
    }

    /// Loss of the curve θ̂ = a0 + a1·r and its gradient (∂/∂a0, ∂/∂a1), by periodic
    /// Catmull–Rom interpolation of each ring's table.
    pub(crate) fn loss_and_gradient(&self, a0: f64, a1: f64) -> (f64, [f64; 2]) {
        let mut loss = 0.0;
        let mut grad = [0.0; 2];
        for (radius, weight, table) in &self.rings {
            let (segment, t) = self.segment(table, a0 + a1 * radius);
            let slope = segment.slope(t) / self.step;
            loss += weight * segment.value(t);
            grad[0] += weight * slope;
            grad[1] += weight * slope * radius;
        }
        (loss, grad)
    }

    /// The loss of every curve (a0, a1) of `curves`, equal to [`RingTables::loss_and_gradient`]'s;
    /// ring by ring, so a scan of many curves reads each ring's table in one sweep instead of
    /// jumping between tables.
    pub(crate) fn losses(&self, curves: &[(f64, f64)]) -> Vec<f64> {
        let mut losses = vec![0.0; curves.len()];
        for (radius, weight, table) in &self.rings {
            for (loss, &(a0, a1)) in losses.iter_mut().zip(curves) {
                let (segment, t) = self.segment(table, a0 + a1 * radius);
                *loss += weight * segment.value(t);
            }
        }
        losses
    }

    /// The interpolating cubic of `table` around the angle `theta`, and where in it θ falls.
    #[inline(always)]
    fn segment(&self, table: &[f64], theta: f64) -> (CatmullRom, f64) {
        let x = theta / self.step;
        // floor(x) by truncation, and wrapped onto the grid without a division where it is
        // at most a turn off: on the x86-64 baseline `f64::floor` is a libm call, and these
        // two were most of the cost of a ring.
        let grid = self.grid as i64;
        let truncated = x as i64;
        let floor = truncated - i64::from((truncated as f64) > x);
        let i = match floor {
            k if (0..grid).contains(&k) => k,
            k if (-grid..0).contains(&k) => k + grid,
            k if (grid..2 * grid).contains(&k) => k - grid,
            k => k.rem_euclid(grid),
        } as usize;
        let [p0, p1, p2, p3] = [table[i], table[i + 1], table[i + 2], table[i + 3]];
        let segment = CatmullRom {
            p1,
            c1: -p0 + p2,
            c2: 2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3,
            c3: -p0 + 3.0 * p1 - 3.0 * p2 + p3,
        };
        (segment, x - floor as f64)
    }
}

/// A Catmull–Rom segment between grid points p1 and p2 (its coefficients, twice over).
struct CatmullRom {
    p1: f64,
    c1: f64,
    c2: f64,
    c3: f64,
}

impl CatmullRom {
    /// The value at t ∈ [0, 1).
    #[inline(always)]
    fn value(&self, t: f64) -> f64 {
        0.5 * (2.0 * self.p1 + t * (self.c1 + t * (self.c2 + t * self.c3)))
    }

    /// The derivative in t.
    #[inline(always)]
    fn slope(&self, t: f64) -> f64 {
        0.5 * (self.c1 + t * (2.0 * self.c2 + 3.0 * t * self.c3))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::disk::position;

    fn synthetic_diff(n: usize, fold_angle: f64) -> Disk {
        // A ridge of change along the radial line θ = fold_angle, fading away from it.
        let mut values = Vec::new();
        for i in 0..n {
            for j in i + 1..n {
                let p = position(n, i, j);
                values.push((-(wrap_pi(p.angle - fold_angle) * n as f64 / 6.0).powi(2)).exp());
            }
        }
        Disk::from_values(n, values).unwrap()
    }

    #[test]
    fn tables_match_the_exact_loss() {
        let n = 40;
        let g = synthetic_diff(n, 1.0);
        let tables = RingTables::new(&g, &CurveParams::default());
        let cells: Vec<Cell> = (1..=n / 2).flat_map(|d| ring_cells(&g, d)).collect();
        for &(a0, a1) in &[(1.0, 0.0), (0.7, 0.3), (5.0, -1.2), (3.1, 2.0)] {
            let exact = exact_loss(&cells, a0, a1);
            let (approx, grad) = tables.loss_and_gradient(a0, a1);
            assert!(
                (exact - approx).abs() < 2e-3 * (1.0 + exact.abs()),
                "{a0} {a1}: {exact} vs {approx}"
            );
            // The gradient is the derivative of the interpolant: check by central difference.
            let h = 1e-6;
            let num0 = (tables.loss_and_gradient(a0 + h, a1).0
                - tables.loss_and_gradient(a0 - h, a1).0)
                / (2.0 * h);
            let num1 = (tables.loss_and_gradient(a0, a1 + h).0
                - tables.loss_and_gradient(a0, a1 - h).0)
                / (2.0 * h);
            assert!((num0 - grad[0]).abs() < 1e-4 * (1.0 + num0.abs()));
            assert!((num1 - grad[1]).abs() < 1e-4 * (1.0 + num1.abs()));
        }
    }

    #[test]
    fn many_curves_at_once_are_each_the_same() {
        let tables = RingTables::new(&synthetic_diff(50, 2.5), &CurveParams::default());
        let curves: Vec<(f64, f64)> =
            (0..200).map(|k| (-7.0 + 0.07 * k as f64, -3.0 + 0.03 * k as f64)).collect();
        for (loss, &(a0, a1)) in tables.losses(&curves).iter().zip(&curves) {
            assert_eq!(loss.to_bits(), tables.loss_and_gradient(a0, a1).0.to_bits(), "{a0} {a1}");
        }
    }

    #[test]
    fn the_loss_is_lowest_on_the_ridge() {
        let g = synthetic_diff(60, 2.0);
        let tables = RingTables::new(&g, &CurveParams::default());
        let on = tables.loss_and_gradient(2.0, 0.0).0;
        assert!(on < 0.0);
        assert!(on < tables.loss_and_gradient(2.5, 0.0).0);
        assert!(on < tables.loss_and_gradient(2.0, 0.5).0);
    }
}
