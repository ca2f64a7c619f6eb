//! The CloSE fold circle: the border parameter drawn as the unit circle.
//!
//! A border parameter s sits at angle 2πs/N, vertex 0 at angle 0 (right), anticlockwise.
//! The corners θ_1 < … < θ_n are numbered dots (1-based, numbers left out beyond 20
//! corners, where the cloth counts as circular). Each fold (f1, f2) is the arc from f1
//! anticlockwise to f2 — the folded side — drawn thick and shaded up to the chord f1–f2,
//! which is the fold line. The values are written underneath.
//!
//! ```
//! use close_render::render::circle::folded_arc;
//! use std::f64::consts::PI;
//! // The arc from 3π/2 to π/2 wraps through 0 and spans half the circle.
//! let arc = folded_arc([1.5 * PI, 0.5 * PI], 5);
//! assert!((arc[2] - 2.0 * PI).abs() < 1e-12);
//! ```

use std::f64::consts::TAU;

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

use super::raster::text_width;
use super::{endpoint_name, fold_colour, label_size, line_width, outward, plot, Canvas, INK, MUTED, PAPER};
use crate::analysis::Analysis;
use crate::angle;
use crate::error::Result;

/// Corners beyond this count are drawn without numbers (the paper's label calls such a cloth circular).
pub const NUMBERED_CORNERS: usize = 20;

/// `points` angles from f1 anticlockwise to f2 (unwrapped: increasing from f1).
pub fn folded_arc([f1, f2]: [f64; 2], points: usize) -> Vec<f64> {
    let span = (f2 - f1).rem_euclid(TAU);
    let last = points.max(2) - 1;
    (0..=last).map(|k| f1 + span * k as f64 / last as f64).collect()
}

/// The lines of text under the circle: corners, one line per fold (and per true fold, with
/// the found fold's angle errors), the label sentence.
fn caption(analysis: &Analysis, truth: &[[f64; 2]], size: f64, width: f64) -> Vec<(String, [u8; 3])> {
    let corners = match analysis.corners.len() {
        0 => "no corners".to_string(),
        1 => "1 corner".to_string(),
        c => format!("{c} corners"),
    };
    let mut lines = vec![(corners, INK)];
    let count = analysis.folds.len();
    for (k, f) in analysis.folds.iter().enumerate() {
        let names = [endpoint_name(k, 0, count), endpoint_name(k, 1, count)];
        lines.push((format!("{} = {:.2} rad, {} = {:.2} rad", names[0], f[0], names[1], f[1]), fold_colour(k)));
    }
    if count == 0 {
        lines.push(("no fold detected".into(), MUTED));
    }
    for (k, t) in truth.iter().enumerate() {
        let error = analysis.folds.get(k).map_or_else(
            || "not found".to_string(),
            |f| format!("found {:.1}°, {:.1}° off", angle::distance(f[0], t[0]).to_degrees(), angle::distance(f[1], t[1]).to_degrees()),
        );
        let name = if truth.len() > 1 { format!("true fold {}", k + 1) } else { "true fold".into() };
        lines.push((format!("{name} (○) = {:.2}, {:.2} rad: {error}", t[0], t[1]), MUTED));
    }
    lines.extend(wrap(&analysis.label.text, |line| text_width(line, size) <= width).into_iter().map(|l| (l, INK)));
    lines
}

/// Greedy word wrap: each line as long as `fits` allows (a longer word gets its own line).
fn wrap(text: &str, fits: impl Fn(&str) -> bool) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for word in text.split_whitespace() {
        match lines.last_mut() {
            Some(line) if fits(&format!("{line} {word}")) => {
                line.push(' ');
                line.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines
}

/// Where the circle sits: centre and radius in pixels.
struct Frame {
    cx: f64,
    cy: f64,
    radius: f64,
}

impl Frame {
    /// The pixel of polar point (r, θ), y down.
    fn at(&self, r: f64, theta: f64) -> (f64, f64) {
        (self.cx + self.radius * r * theta.cos(), self.cy - self.radius * r * theta.sin())
    }
}

/// Draw the fold circle of `analysis`, with the `truth` folds (when known) as hollow
/// markers joined by a thin chord beside the found ones.
pub(crate) fn draw(canvas: &mut Canvas, analysis: &Analysis, truth: &[[f64; 2]]) -> Result<()> {
    let unit = canvas.unit();
    let (w, h) = (canvas.width as f64, canvas.height as f64);
    let label = label_size(unit);
    let lines = caption(analysis, truth, label, w - label);
    let line_height = 1.35 * label;
    let top = canvas.title_band();
    let text_top = h - line_height * lines.len() as f64 - 0.4 * label;
    // Room outside the circle for corner numbers and fold names.
    let pad = 4.4 * label;
    let radius = ((w - 2.0 * pad) / 2.0).min((text_top - top - 2.0 * pad) / 2.0).max(4.0);
    let frame = Frame { cx: w / 2.0, cy: top + pad + radius, radius };
    shade_folded_sides(canvas, analysis, &frame)?;
    canvas.title("CloSE fold circle");
    canvas.ring((frame.cx, frame.cy), radius, line_width(unit, 0.004), INK);
    let tick = 0.4 * label / radius;
    canvas.stroke(&[frame.at(1.0, 0.0), frame.at(1.0 - tick, 0.0)], line_width(unit, 0.003), INK);
    canvas.text("0", frame.at(1.0 - 1.5 * tick, 0.0), 0.8 * label, MUTED, (HPos::Right, VPos::Center));
    let mut taken = draw_corners(canvas, &analysis.corners, &frame);
    draw_truth(canvas, truth, &frame);
    draw_folds(canvas, analysis, &frame, &mut taken);
    for (k, (text, colour)) in lines.iter().enumerate() {
        let y = text_top + line_height * (k as f64 + 0.5);
        canvas.text(text, (0.5 * label, y), label, *colour, (HPos::Left, VPos::Center));
    }
    Ok(())
}

/// The folded side of each fold, between each of its arcs and its chord, lightly shaded.
fn shade_folded_sides(canvas: &mut Canvas, analysis: &Analysis, frame: &Frame) -> Result<()> {
    canvas.draw(|area| {
        for (k, arcs) in analysis.fold_arcs().into_iter().enumerate() {
            for &fold in arcs {
                let arc: Vec<(i32, i32)> = folded_arc(fold, 361)
                    .into_iter()
                    .map(|t| frame.at(1.0, t))
                    .map(|(x, y)| (x.round() as i32, y.round() as i32))
                    .collect();
                area.draw(&Polygon::new(arc, plot(fold_colour(k)).mix(0.14).filled()))?;
            }
        }
        Ok(())
    })
}

/// The pixel box [x0, y0, x1, y1] of `text` of `size` at `at` anchored `outward(theta)`.
fn text_box(text: &str, at: (f64, f64), size: f64, theta: f64) -> [f64; 4] {
    let (w, h) = (text_width(text, size), 0.8 * size);
    let (hp, vp) = outward(theta);
    let x0 = match hp {
        HPos::Left => at.0,
        HPos::Center => at.0 - w / 2.0,
        HPos::Right => at.0 - w,
    };
    let y0 = match vp {
        VPos::Top => at.1,
        VPos::Center => at.1 - h / 2.0,
        VPos::Bottom => at.1 - h,
    };
    [x0, y0, x0 + w, y0 + h]
}

/// True when two boxes overlap (with a small gap).
fn overlaps(a: &[f64; 4], b: &[f64; 4], gap: f64) -> bool {
    a[0] < b[2] + gap && b[0] < a[2] + gap && a[1] < b[3] + gap && b[1] < a[3] + gap
}

/// Corner dots, numbered 1… outside the circle when there are at most [`NUMBERED_CORNERS`];
/// gives the boxes the numbers take.
fn draw_corners(canvas: &mut Canvas, corners: &[f64], frame: &Frame) -> Vec<[f64; 4]> {
    let unit = canvas.unit();
    let dot = (unit * 0.012).max(2.0);
    let size = label_size(unit);
    let mut taken = Vec::new();
    for (k, &theta) in corners.iter().enumerate() {
        canvas.disc(frame.at(1.0, theta), dot + 1.5, PAPER);
        canvas.disc(frame.at(1.0, theta), dot, INK);
        if corners.len() <= NUMBERED_CORNERS {
            let (at, text) = (frame.at(1.0 + 1.8 * dot / frame.radius, theta), (k + 1).to_string());
            canvas.text(&text, at, size, INK, outward(theta));
            taken.push(text_box(&text, at, size, theta));
        }
    }
    taken
}

/// Each true fold: its chord thin, its two points as hollow rings in its fold's colour.
fn draw_truth(canvas: &mut Canvas, truth: &[[f64; 2]], frame: &Frame) {
    let unit = canvas.unit();
    let marker = (unit * 0.022).max(4.0);
    for (k, t) in truth.iter().enumerate() {
        let colour = fold_colour(k);
        canvas.stroke(&[frame.at(1.0, t[0]), frame.at(1.0, t[1])], line_width(unit, 0.003), MUTED);
        for &a in t {
            canvas.ring(frame.at(1.0, a), marker, line_width(unit, 0.004), colour);
        }
    }
}

/// Each fold: its arcs (the folded side: one, or several for a multi-arc fold), the chord of
/// each (the fold line) and the named endpoints of the pair that spans them, each name moved
/// outwards until it clears the corner numbers and the names before it.
fn draw_folds(canvas: &mut Canvas, analysis: &Analysis, frame: &Frame, taken: &mut Vec<[f64; 4]>) {
    let unit = canvas.unit();
    let count = analysis.folds.len();
    let size = label_size(unit);
    let marker = (unit * 0.016).max(3.0);
    for (k, (&fold, arcs)) in analysis.folds.iter().zip(analysis.fold_arcs()).enumerate() {
        let colour = fold_colour(k);
        for &[a, b] in arcs {
            let arc: Vec<(f64, f64)> = folded_arc([a, b], 361).into_iter().map(|t| frame.at(1.0, t)).collect();
            canvas.stroke(&arc, line_width(unit, 0.014), colour);
            canvas.stroke(&[frame.at(1.0, a), frame.at(1.0, b)], line_width(unit, 0.005), colour);
        }
        for (e, &f) in fold.iter().enumerate() {
            canvas.disc(frame.at(1.0, f), marker + 1.5, PAPER);
            canvas.disc(frame.at(1.0, f), marker, colour);
            let name = endpoint_name(k, e, count);
            let place = |step: f64| {
                let at = frame.at(1.0 + (1.0 + 1.1 * step) * size / frame.radius, f);
                (at, text_box(&name, at, size, f))
            };
            let (at, bounds) = (0..4)
                .map(|step| place(step as f64))
                .find(|(_, b)| !taken.iter().any(|t| overlaps(t, b, 0.15 * size)))
                .unwrap_or_else(|| place(3.0));
            canvas.text(&name, at, size, colour, outward(f));
            taken.push(bounds);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn folded_arc_runs_anticlockwise_from_f1_to_f2() {
        let arc = folded_arc([1.0, 0.5], 3);
        assert_eq!(arc[0], 1.0);
        assert!((arc[2] - (0.5 + TAU)).abs() < 1e-12);
        assert!(arc.windows(2).all(|w| w[1] >= w[0]));
    }

    #[test]
    fn boxes_overlap_only_when_they_meet() {
        let a = [0.0, 0.0, 10.0, 10.0];
        assert!(overlaps(&a, &[5.0, 5.0, 15.0, 15.0], 0.0));
        assert!(!overlaps(&a, &[11.0, 0.0, 20.0, 10.0], 0.5));
        assert!(overlaps(&a, &[10.2, 0.0, 20.0, 10.0], 0.5));
        // A label anchored right of a point on the right of the circle starts at the point.
        let b = text_box("12", (100.0, 50.0), 10.0, 0.0);
        assert_eq!(b[0], 100.0);
        assert!(b[2] > 100.0 && b[1] < 50.0 && b[3] > 50.0);
    }

    #[test]
    fn wrap_keeps_words_and_width() {
        let fits = |line: &str| line.chars().count() <= 16;
        let lines = wrap("one fold along the diagonal, corners 2 and 3 folded", fits);
        assert!(lines.iter().all(|l| fits(l)), "{lines:?}");
        assert!(lines.len() >= 3);
        assert_eq!(lines.join(" "), "one fold along the diagonal, corners 2 and 3 folded");
        assert_eq!(wrap("", fits), Vec::<String>::new());
    }
}
