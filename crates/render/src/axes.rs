//! Chart axes drawn as strokes and text: a light grid, the left and bottom axis lines and
//! their tick labels, so an SVG picture keeps them as vector elements (no embedded bitmap).
//!
//! Ticks are "nice" numbers: multiples of 1, 2 or 5 × 10^k, about `count` of them across
//! the range. Labels carry as many decimals as the step needs and never read "-0".
//!
//! ```
//! use close_render::axes::ticks;
//! assert_eq!(ticks((-0.83, 1.71), 5), vec![-0.5, 0.0, 0.5, 1.0, 1.5]);
//! assert_eq!(close_render::axes::tick_label(-1e-17, 0.5), "0.0");
//! ```

use plotters::style::text_anchor::{HPos, VPos};

use super::{Canvas, INK, MUTED};

/// Grid lines between ticks.
const GRID: [u8; 3] = [226, 226, 226];

/// The tick step of a range `span` wide: 1, 2 or 5 × 10^k, the one giving closest to
/// `count` ticks (at least one).
fn step(span: f64, count: usize) -> f64 {
    let rough = span / count.max(1) as f64;
    let power = 10f64.powf(rough.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * power)
        .min_by(|a, b| {
            ((span / a) - count as f64).abs().total_cmp(&((span / b) - count as f64).abs())
        })
        .unwrap_or(power)
}

/// The tick values inside `range` (low, high), a nice step apart.
pub fn ticks(range: (f64, f64), count: usize) -> Vec<f64> {
    let span = range.1 - range.0;
    if !(span.is_finite() && span > 0.0) {
        return Vec::new();
    }
    let step = step(span, count);
    let first = (range.0 / step).ceil() as i64;
    let last = (range.1 / step).floor() as i64;
    // Multiples of the step, not repeated additions, so 0 is exactly 0.
    (first..=last).map(|k| k as f64 * step).collect()
}

/// A tick's label: the decimals the step needs, and a value that rounds to zero as "0".
pub fn tick_label(value: f64, step: f64) -> String {
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    let text = format!("{value:.decimals$}");
    // "-0.0" is a rounding artefact, not a sign.
    if text.trim_start_matches('-').chars().all(|c| c == '0' || c == '.') {
        text.trim_start_matches('-').to_string()
    } else {
        text
    }
}

/// A rectangle of the picture in pixels (y down).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Frame {
    pub(crate) left: f64,
    pub(crate) right: f64,
    pub(crate) top: f64,
    pub(crate) bottom: f64,
}

/// Draw the grid, axis lines and tick labels of data ranges `x` and `y` shown in `frame`,
/// labels in text of `size` pixels.
pub(crate) fn draw(canvas: &mut Canvas, frame: Frame, x: (f64, f64), y: (f64, f64), size: f64) {
    let to_x = |v: f64| frame.left + (v - x.0) / (x.1 - x.0) * (frame.right - frame.left);
    let to_y = |v: f64| frame.bottom - (v - y.0) / (y.1 - y.0) * (frame.bottom - frame.top);
    let (xs, ys) = (ticks(x, 5), ticks(y, 5));
    for &v in &xs {
        canvas.stroke(&[(to_x(v), frame.top), (to_x(v), frame.bottom)], 1.0, GRID);
    }
    for &v in &ys {
        canvas.stroke(&[(frame.left, to_y(v)), (frame.right, to_y(v))], 1.0, GRID);
    }
    let axes = [(frame.left, frame.top), (frame.left, frame.bottom), (frame.right, frame.bottom)];
    canvas.stroke(&axes, 1.0, MUTED);
    let tick = 0.35 * size;
    let gap = |values: &[f64]| match values {
        [a, b, ..] => b - a,
        _ => 1.0,
    };
    for &v in &xs {
        let at = to_x(v);
        canvas.stroke(&[(at, frame.bottom), (at, frame.bottom + tick)], 1.0, MUTED);
        let label = tick_label(v, gap(&xs));
        canvas.text(&label, (at, frame.bottom + 1.4 * tick), size, INK, (HPos::Center, VPos::Top));
    }
    for &v in &ys {
        let at = to_y(v);
        canvas.stroke(&[(frame.left - tick, at), (frame.left, at)], 1.0, MUTED);
        let label = tick_label(v, gap(&ys));
        canvas.text(&label, (frame.left - 1.4 * tick, at), size, INK, (HPos::Right, VPos::Center));
    }
}

/// The part of segment `a`–`b` inside `frame` (Liang–Barsky), or `None` when it misses.
pub(crate) fn clip([a, b]: [(f64, f64); 2], frame: Frame) -> Option<[(f64, f64); 2]> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-dx, a.0 - frame.left),
        (dx, frame.right - a.0),
        (-dy, a.1 - frame.top),
        (dy, frame.bottom - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else if p < 0.0 {
            t0 = t0.max(q / p);
        } else {
            t1 = t1.min(q / p);
        }
    }
    (t0 <= t1).then_some([(a.0 + t0 * dx, a.1 + t0 * dy), (a.0 + t1 * dx, a.1 + t1 * dy)])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_nice_and_inside() {
        assert_eq!(ticks((0.0, 10.0), 5), vec![0.0, 2.0, 4.0, 6.0, 8.0, 10.0]);
        assert_eq!(ticks((-2.3, 2.3), 5), vec![-2.0, -1.0, 0.0, 1.0, 2.0]);
        assert_eq!(ticks((0.0, 0.0), 5), Vec::<f64>::new());
        assert_eq!(ticks((f64::NAN, 1.0), 5), Vec::<f64>::new());
        let small = ticks((0.0012, 0.0049), 5);
        assert!(small.len() >= 3 && small.iter().all(|v| (0.0012..=0.0049).contains(v)));
    }

    #[test]
    fn labels_never_read_minus_zero() {
        assert_eq!(tick_label(-0.0, 0.5), "0.0");
        assert_eq!(tick_label(-0.04, 0.5), "0.0");
        assert_eq!(tick_label(-0.5, 0.5), "-0.5");
        assert_eq!(tick_label(20.0, 10.0), "20");
        assert_eq!(tick_label(0.002, 0.001), "0.002");
    }

    #[test]
    fn segments_are_clipped_to_the_frame() {
        let frame = Frame { left: 0.0, right: 10.0, top: 0.0, bottom: 10.0 };
        assert_eq!(clip([(-5.0, 5.0), (15.0, 5.0)], frame), Some([(0.0, 5.0), (10.0, 5.0)]));
        assert_eq!(clip([(2.0, 2.0), (3.0, 3.0)], frame), Some([(2.0, 2.0), (3.0, 3.0)]));
        assert_eq!(clip([(-5.0, -5.0), (-1.0, 20.0)], frame), None);
        assert_eq!(clip([(11.0, 0.0), (11.0, 5.0)], frame), None);
    }
}
