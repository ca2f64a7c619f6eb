//! The border plot: start, true end and predicted end borders in the XY plane.
//!
//! Borders are closed polylines in the input's coordinates, drawn with equal scales on x
//! and y so shapes are not distorted. Each border's edges are drawn from low z to high z
//! with a thin white halo, so where a folded layer lies over the rest of the cloth it is
//! seen crossing on top. The true end is drawn wide and the prediction thin over it: where
//! they agree, the prediction runs inside the end line. Vertex 0 is marked on each border.
//!
//! ```
//! use close::render::borders::equal_aspect;
//! // A 2×1 box shown in a square plot gets a y range as wide as its x range.
//! let (x, y) = equal_aspect((0.0, 2.0), (0.0, 1.0), (100, 100));
//! assert_eq!((x, y), ((0.0, 2.0), (-0.5, 1.5)));
//! ```

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

use super::{draw_title, label_size, line_width, text_style, title_size, Canvas, DrawResult, INK, MUTED};
use crate::analysis::Analysis;
use crate::error::Result;

/// One border to draw: vertices (x, y, z), colour, line width in pixels, legend name.
struct Trace {
    points: Vec<[f64; 3]>,
    colour: RGBColor,
    width: u32,
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
        points: analysis.start_border.iter().map(array).collect(),
        colour: RGBColor(160, 160, 160),
        width: line_width(unit, 0.004),
        name: "start",
    }];
    if analysis.end_frame > analysis.start_frame {
        traces.push(Trace {
            points: analysis.end_border.iter().map(array).collect(),
            colour: RGBColor(120, 170, 220),
            width: line_width(unit, 0.013),
            name: "end",
        });
    }
    if !analysis.folds.is_empty() {
        traces.push(Trace {
            points: analysis.predicted_end.clone(),
            colour: RGBColor(230, 110, 20),
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

/// Draw the border plot of `analysis`.
pub(crate) fn draw(canvas: &mut Canvas, analysis: &Analysis) -> Result<()> {
    let unit = canvas.unit();
    let traces = traces(analysis, unit);
    let (x, y) = bounds(&traces);
    let label = label_size(unit);
    canvas.draw(|area| {
        draw_title(area, unit, "Borders (XY)")?;
        let body = area.margin((1.8 * title_size(unit)) as i32, (0.6 * label) as i32, (0.6 * label) as i32, (1.2 * label) as i32);
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
            .light_line_style(RGBColor(240, 240, 240))
            .bold_line_style(RGBColor(225, 225, 225))
            .axis_style(MUTED)
            .label_style(text_style(0.85 * label, INK, HPos::Center, VPos::Center))
            .x_labels(6)
            .y_labels(6)
            .draw()?;
        for trace in &traces {
            draw_trace(&mut chart, trace)?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .margin((0.5 * label) as i32)
            .legend_area_size((1.8 * label) as i32)
            .label_font(text_style(0.85 * label, INK, HPos::Left, VPos::Center))
            .background_style(WHITE.mix(0.85))
            .border_style(MUTED)
            .draw()?;
        let note = match &analysis.metrics {
            Some(m) => format!("RMSE {:.3} · Fréchet {:.3} (normalised) · ● vertex 0", m.rmse, m.frechet),
            None => "● vertex 0".to_string(),
        };
        let (w, h) = area.dim_in_pixel();
        area.draw(&Text::new(note, (w as i32 - (0.5 * label) as i32, h as i32 - (0.3 * label) as i32), text_style(0.8 * label, MUTED, HPos::Right, VPos::Bottom)))
    })
}

type Chart<'a, 'b> = ChartContext<'a, BitMapBackend<'b>, Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>>;

/// One border: edges in z order, each with a halo, then its vertex 0 and its legend entry.
fn draw_trace(chart: &mut Chart, trace: &Trace) -> DrawResult {
    let n = trace.points.len();
    let mut edges: Vec<usize> = (0..n).collect();
    edges.sort_by(|&a, &b| {
        let z = |k: usize| trace.points[k][2] + trace.points[(k + 1) % n][2];
        z(a).total_cmp(&z(b))
    });
    let xy = |k: usize| (trace.points[k % n][0], trace.points[k % n][1]);
    for k in edges {
        let segment = vec![xy(k), xy(k + 1)];
        chart.draw_series(std::iter::once(PathElement::new(segment.clone(), WHITE.stroke_width(trace.width + 2))))?;
        chart.draw_series(std::iter::once(PathElement::new(segment, trace.colour.stroke_width(trace.width))))?;
    }
    let dot = (trace.width as i32 + 2).max(3);
    let colour = trace.colour;
    let marker = (n > 0).then(|| Circle::new(xy(0), dot, colour.filled()));
    let legend_width = 3 * dot;
    chart
        .draw_series(marker)?
        .label(trace.name)
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + legend_width * 2, y)], colour.stroke_width(3)));
    Ok(())
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
    fn bounds_of_nothing_is_a_unit_box() {
        assert_eq!(bounds(&[]), ((0.0, 1.0), (0.0, 1.0)));
    }
}
