//! The border plot: start, true end and predicted end borders in the XY plane.
//!
//! Borders are closed polylines in the input's coordinates, drawn with equal scales on x
//! and y so shapes are not distorted. Each border's edges are drawn from low z to high z
//! with a thin white halo, so where a folded layer lies over the rest of the cloth it is
//! seen crossing on top. The true end is drawn wide and the prediction thin over it: where
//! they agree, the prediction runs inside the end line. Vertex 0 is marked on each border.
//!
//! ```
//! use close_render::render::borders::equal_aspect;
//! // A 2×1 box shown in a square plot gets a y range as wide as its x range.
//! let (x, y) = equal_aspect((0.0, 2.0), (0.0, 1.0), (100, 100));
//! assert_eq!((x, y), ((0.0, 2.0), (-0.5, 1.5)));
//! ```

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

use super::{label_size, line_width, plot, text_style, Canvas, INK, MUTED, PAPER};
use crate::analysis::Analysis;
use crate::error::Result;

/// One border to draw: vertices (x, y, z), colour, line width in pixels, legend name.
struct Trace {
    points: Vec<[f64; 3]>,
    colour: [u8; 3],
    width: f64,
    name: &'static str,
}

/// Grow the x or y range about its centre so one data unit spans as many pixels on both
/// axes of a `pixels` (width, height) plot.
pub fn equal_aspect(x: (f64, f64), y: (f64, f64), pixels: (u32, u32)) -> ((f64, f64), (f64, f64)) {
    let (dx, dy) = ((x.1 - x.0).max(f64::MIN_POSITIVE), (y.1 - y.0).max(f64::MIN_POSITIVE));
    let (pw, ph) = (pixels.0.max(1) as f64, pixels.1.max(1) as f64);
    let per_unit = (pw / dx).min(ph / dy);
    let (half_x, half_y) = (pw / per_unit / 2.0, ph / per_unit / 2.0);
    let (mx, my) = ((x.0 + x.1) / 2.0, (y.0 + y.1) / 2.0);
    ((mx - half_x, mx + half_x), (my - half_y, my + half_y))
}

/// The borders of `analysis` that exist, bottom to top.
fn traces(analysis: &Analysis, unit: f64) -> Vec<Trace> {
    let array = |p: &crate::border::Point| [p.x, p.y, p.z];
    let mut traces = vec![Trace {
        points: analysis.start_border().iter().map(array).collect(),
        colour: [160, 160, 160],
        width: line_width(unit, 0.004),
        name: "start",
    }];
    if analysis.end_frame > analysis.start_frame {
        traces.push(Trace {
            points: analysis.end_border().iter().map(array).collect(),
            colour: [120, 170, 220],
            width: line_width(unit, 0.016),
            name: "end",
        });
    }
    if !analysis.folds.is_empty() {
        traces.push(Trace {
            points: analysis.predicted_end.clone(),
            colour: [230, 110, 20],
            width: line_width(unit, 0.005),
            name: "predicted end",
        });
    }
    traces
}

/// The smallest box holding every point of `traces`, padded by 6 %; a unit box when empty.
fn bounds(traces: &[Trace]) -> ((f64, f64), (f64, f64)) {
    let points = traces.iter().flat_map(|t| &t.points).filter(|p| p[0].is_finite() && p[1].is_finite());
    let (mut x, mut y) = ((f64::INFINITY, f64::NEG_INFINITY), (f64::INFINITY, f64::NEG_INFINITY));
    for p in points {
        x = (x.0.min(p[0]), x.1.max(p[0]));
        y = (y.0.min(p[1]), y.1.max(p[1]));
    }
    if x.0 > x.1 {
        return ((0.0, 1.0), (0.0, 1.0));
    }
    let pad = 0.06 * (x.1 - x.0).max(y.1 - y.0).max(1e-9);
    ((x.0 - pad, x.1 + pad), (y.0 - pad, y.1 + pad))
}

/// Maps data (x, y) to pixels (y down) in the plotting area.
pub(crate) struct Mapping {
    x: (f64, f64),
    y: (f64, f64),
    px: (f64, f64),
    py: (f64, f64),
}

impl Mapping {
    /// The affine map of each axis, pixel = a·value + b, as ([a, b] for x, [a, b] for y).
    pub(crate) fn affine(&self) -> ([f64; 2], [f64; 2]) {
        let ax = (self.px.1 - self.px.0) / (self.x.1 - self.x.0);
        let ay = -(self.py.1 - self.py.0) / (self.y.1 - self.y.0);
        ([ax, self.px.0 - ax * self.x.0], [ay, self.py.1 - ay * self.y.0])
    }

    fn pixel(&self, p: &[f64; 3]) -> (f64, f64) {
        let fx = (p[0] - self.x.0) / (self.x.1 - self.x.0);
        let fy = (p[1] - self.y.0) / (self.y.1 - self.y.0);
        (self.px.0 + fx * (self.px.1 - self.px.0), self.py.1 - fy * (self.py.1 - self.py.0))
    }
}

/// Draw the border plot of `analysis`; gives how it mapped data to pixels.
pub(crate) fn draw(canvas: &mut Canvas, analysis: &Analysis) -> Result<Mapping> {
    let unit = canvas.unit();
    let traces = traces(analysis, unit);
    let (x, y) = bounds(&traces);
    let label = label_size(unit);
    let top = canvas.title_band();
    let mapping = canvas.draw(|area| {
        // The bottom margin holds the legend and the note, outside the data.
        let body = area.margin(top as i32, (3.2 * label) as i32, (0.6 * label) as i32, (1.2 * label) as i32);
        let builder = || {
            let mut b = ChartBuilder::on(&body);
            b.x_label_area_size((2.0 * label) as u32).y_label_area_size((3.6 * label) as u32);
            b
        };
        // The plot's pixel size is known only once built: build once to measure, then for real.
        let pixels = builder().build_cartesian_2d(x.0..x.1, y.0..y.1)?.plotting_area().dim_in_pixel();
        let (x, y) = equal_aspect(x, y, pixels);
        let mut chart = builder().build_cartesian_2d(x.0..x.1, y.0..y.1)?;
        chart
            .configure_mesh()
            .light_line_style(RGBColor(242, 242, 242))
            .bold_line_style(RGBColor(226, 226, 226))
            .axis_style(plot(MUTED))
            .label_style(text_style(0.85 * label, INK))
            .x_labels(6)
            .y_labels(6)
            .draw()?;
        let (px, py) = chart.plotting_area().get_pixel_range();
        Ok(Mapping { x, y, px: (px.start as f64, px.end as f64), py: (py.start as f64, py.end as f64) })
    })?;
    canvas.title("Borders (XY)");
    for trace in &traces {
        draw_trace(canvas, trace, &mapping);
    }
    draw_legend(canvas, &traces, (mapping.px.0, canvas.height as f64 - 2.1 * label));
    let note = match &analysis.metrics {
        Some(m) => format!("RMSE {:.3} · Fréchet {:.3} (normalised)   ● vertex 0", m.rmse, m.frechet),
        None => "● vertex 0".to_string(),
    };
    let (w, h) = (canvas.width as f64, canvas.height as f64);
    canvas.text(&note, (w - 0.5 * label, h - 0.6 * label), 0.8 * label, MUTED, (HPos::Right, VPos::Center));
    Ok(mapping)
}

/// A mini drawing for a list of samples: the start border thin grey, the end border thick
/// blue over it, as large as the picture allows; no text, axes or legend, which would be
/// unreadable at this size.
pub(crate) fn draw_thumbnail(canvas: &mut Canvas, analysis: &Analysis) {
    let unit = canvas.unit();
    let mut traces = traces(analysis, unit);
    // Only the data: the prediction is for the full plot.
    traces.retain(|t| t.name != "predicted end");
    for t in &mut traces {
        t.width = if t.name == "start" { line_width(unit, 0.012) } else { line_width(unit, 0.03) };
        if t.name == "end" {
            t.colour = [31, 111, 235];
        }
    }
    let (x, y) = bounds(&traces);
    let pad = 0.04 * unit;
    let (w, h) = (canvas.width as f64, canvas.height as f64);
    let (x, y) = equal_aspect(x, y, ((w - 2.0 * pad) as u32, (h - 2.0 * pad) as u32));
    let mapping = Mapping { x, y, px: (pad, w - pad), py: (pad, h - pad) };
    for trace in &traces {
        draw_trace(canvas, trace, &mapping);
    }
}

/// One border: its lower edges, then its raised edges (a folded layer) with a halo so they
/// cross on top, then its vertex 0.
fn draw_trace(canvas: &mut Canvas, trace: &Trace, mapping: &Mapping) {
    let n = trace.points.len();
    let z = |k: usize| (trace.points[k][2] + trace.points[(k + 1) % n][2]) / 2.0;
    let (lo, hi) = (0..n).map(z).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
    let raised = |k: usize| hi - lo > 1e-9 * (1.0 + hi.abs()) && z(k) > (lo + hi) / 2.0;
    let at = |v: usize| mapping.pixel(&trace.points[v % n]);
    for run in runs(n, |k| !raised(k)) {
        canvas.stroke(&run.iter().map(|&v| at(v)).collect::<Vec<_>>(), trace.width, trace.colour);
    }
    for run in runs(n, raised) {
        let points: Vec<(f64, f64)> = run.iter().map(|&v| at(v)).collect();
        canvas.stroke(&points, trace.width + 3.0, PAPER);
        canvas.stroke(&points, trace.width, trace.colour);
    }
    if n > 0 {
        canvas.disc(at(0), trace.width + 2.5, PAPER);
        canvas.disc(at(0), trace.width + 1.5, trace.colour);
    }
}

/// The maximal runs of consecutive edges k (k → k+1, cyclic) of a closed n-gon with
/// `keep(k)`, each as its vertex indices (not reduced mod n, so a run may pass n).
fn runs(n: usize, keep: impl Fn(usize) -> bool) -> Vec<Vec<usize>> {
    if (0..n).all(&keep) {
        return vec![(0..=n).collect()];
    }
    (0..n)
        .filter(|&k| keep(k) && !keep((k + n - 1) % n))
        .map(|k| {
            let len = (k..k + n).take_while(|&e| keep(e % n)).count();
            (k..=k + len).collect()
        })
        .collect()
}

/// The legend in one row under the plot, starting at `start` (left end, vertical centre).
fn draw_legend(canvas: &mut Canvas, traces: &[Trace], start: (f64, f64)) {
    let size = 0.85 * label_size(canvas.unit());
    let swatch = 2.2 * size;
    let (mut x, y) = start;
    for trace in traces {
        // A wide line's round caps reach half its width past its ends.
        let cap = trace.width.max(2.0) / 2.0;
        canvas.stroke(&[(x + cap, y), (x + cap + swatch, y)], trace.width.max(2.0), trace.colour);
        x += swatch + 2.0 * cap + 0.4 * size;
        canvas.text(trace.name, (x, y), size, INK, (HPos::Left, VPos::Center));
        x += super::raster::text_width(trace.name, size) + 1.2 * size;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equal_aspect_keeps_the_data_inside_and_scales_equal() {
        let ((x0, x1), (y0, y1)) = equal_aspect((-1.0, 3.0), (0.0, 1.0), (300, 200));
        assert!(x0 <= -1.0 && x1 >= 3.0 && y0 <= 0.0 && y1 >= 1.0);
        assert!(((x1 - x0) / 300.0 - (y1 - y0) / 200.0).abs() < 1e-12);
    }

    #[test]
    fn runs_split_a_closed_border_at_the_changes() {
        // Edges 5, 0, 1 kept on a hexagon: one run through vertex 0.
        assert_eq!(runs(6, |k| k == 5 || k <= 1), vec![vec![5, 6, 7, 8]]);
        assert_eq!(runs(4, |_| true), vec![vec![0, 1, 2, 3, 4]]);
        assert_eq!(runs(4, |k| k % 2 == 0), vec![vec![0, 1], vec![2, 3]]);
        assert!(runs(4, |_| false).is_empty());
    }

    #[test]
    fn bounds_of_nothing_is_a_unit_box() {
        assert_eq!(bounds(&[]), ((0.0, 1.0), (0.0, 1.0)));
    }
}
