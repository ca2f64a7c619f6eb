//! The CloSE fold circle: the border parameter drawn as the unit circle.
//!
//! A border parameter s sits at angle 2πs/N, vertex 0 at angle 0 (right), anticlockwise.
//! The corners θ_1 < … < θ_n are numbered dots (1-based, numbers left out beyond 20
//! corners, where the cloth counts as circular). Each fold (f1, f2) is the arc from f1
//! anticlockwise to f2 — the folded side — drawn thick and shaded up to the chord f1–f2,
//! which is the fold line. The values are written underneath.
//!
//! ```
//! use close::render::circle::folded_arc;
//! use std::f64::consts::PI;
//! // The arc from 3π/2 to π/2 wraps through 0 and spans half the circle.
//! let arc = folded_arc([1.5 * PI, 0.5 * PI], 5);
//! assert!((arc[2] - 2.0 * PI).abs() < 1e-12);
//! ```

use std::f64::consts::{PI, TAU};

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

use super::disk::outward;
use super::{draw_title, endpoint_name, fold_colour, label_size, line_width, text_style, title_size, Area, Canvas, DrawResult, INK, MUTED};
use crate::analysis::Analysis;
use crate::error::Result;

/// Corners beyond this count are drawn without numbers (SPEC: the cloth is circular).
pub const NUMBERED_CORNERS: usize = 20;

/// `points` angles from f1 anticlockwise to f2 (unwrapped: increasing from f1).
pub fn folded_arc([f1, f2]: [f64; 2], points: usize) -> Vec<f64> {
    let span = (f2 - f1).rem_euclid(TAU);
    let last = points.max(2) - 1;
    (0..=last).map(|k| f1 + span * k as f64 / last as f64).collect()
}

/// The lines of text under the circle: corners, one line per fold, the label sentence.
fn caption(analysis: &Analysis, chars_per_line: usize) -> Vec<(String, RGBColor)> {
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
    lines.extend(wrap(&analysis.label.text, chars_per_line).into_iter().map(|l| (l, MUTED)));
    lines
}

/// Greedy word wrap to at most `width` characters a line (a longer word gets its own line).
fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for word in text.split_whitespace() {
        match lines.last_mut() {
            Some(line) if line.chars().count() + 1 + word.chars().count() <= width => {
                line.push(' ');
                line.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines
}

/// Draw the fold circle of `analysis`.
pub(crate) fn draw(canvas: &mut Canvas, analysis: &Analysis) -> Result<()> {
    let unit = canvas.unit();
    let (w, h) = (canvas.width as f64, canvas.height as f64);
    let label = label_size(unit);
    // DejaVu Sans averages about 0.55 em a character.
    let lines = caption(analysis, ((w - label) / (0.55 * label)).max(8.0) as usize);
    let line_height = 1.3 * label;
    let top = 1.8 * title_size(unit);
    let text_top = h - line_height * lines.len() as f64 - 0.5 * label;
    let pad = 2.2 * label;
    let radius = ((w - 2.0 * pad) / 2.0).min((text_top - top - 2.0 * pad) / 2.0).max(4.0);
    let (cx, cy) = (w / 2.0, top + pad + radius);
    let at = |r: f64, theta: f64| ((cx + radius * r * theta.cos()).round() as i32, (cy - radius * r * theta.sin()).round() as i32);
    canvas.draw(|area| {
        draw_title(area, unit, "CloSE fold circle")?;
        draw_folds(area, unit, analysis, &at)?;
        area.draw(&Circle::new(at(0.0, 0.0), radius.round() as i32, INK.stroke_width(line_width(unit, 0.004))))?;
        draw_angle_marks(area, unit, radius, &at)?;
        draw_corners(area, unit, radius, &analysis.corners, &at)?;
        for (k, (text, colour)) in lines.into_iter().enumerate() {
            let y = (text_top + line_height * (k as f64 + 0.5)) as i32;
            area.draw(&Text::new(text, ((0.5 * label) as i32, y), text_style(label, colour, HPos::Left, VPos::Center)))?;
        }
        Ok(())
    })
}

/// Ticks and names of the quarter angles, inside the circle so the corner numbers outside stay clear.
fn draw_angle_marks(area: &Area, unit: f64, radius: f64, at: &impl Fn(f64, f64) -> (i32, i32)) -> DrawResult {
    let size = label_size(unit) * 0.8;
    let tick = 0.3 * size / radius;
    for (k, name) in ["0", "π/2", "π", "3π/2"].iter().enumerate() {
        let theta = k as f64 * PI / 2.0;
        area.draw(&PathElement::new(vec![at(1.0, theta), at(1.0 - tick, theta)], MUTED.stroke_width(1)))?;
        let (h, v) = outward(theta + PI);
        area.draw(&Text::new(name.to_string(), at(1.0 - 2.0 * tick, theta), text_style(size, MUTED, h, v)))?;
    }
    Ok(())
}

/// Corner dots, numbered 1… outside the circle when there are at most [`NUMBERED_CORNERS`].
fn draw_corners(area: &Area, unit: f64, radius: f64, corners: &[f64], at: &impl Fn(f64, f64) -> (i32, i32)) -> DrawResult {
    let dot = (unit * 0.012).max(2.0) as i32;
    let size = label_size(unit);
    for (k, &theta) in corners.iter().enumerate() {
        area.draw(&Circle::new(at(1.0, theta), dot + 1, WHITE.filled()))?;
        area.draw(&Circle::new(at(1.0, theta), dot, INK.filled()))?;
        if corners.len() <= NUMBERED_CORNERS {
            let (h, v) = outward(theta);
            let r = 1.0 + 1.6 * dot as f64 / radius;
            area.draw(&Text::new((k + 1).to_string(), at(r, theta), text_style(size, INK, h, v)))?;
        }
    }
    Ok(())
}

/// Each fold: the shaded folded side, its arc, the chord and the named endpoints.
fn draw_folds(area: &Area, unit: f64, analysis: &Analysis, at: &impl Fn(f64, f64) -> (i32, i32)) -> DrawResult {
    let count = analysis.folds.len();
    let size = label_size(unit);
    for (k, &fold) in analysis.folds.iter().enumerate() {
        let colour = fold_colour(k);
        let arc: Vec<(i32, i32)> = folded_arc(fold, 181).into_iter().map(|t| at(1.0, t)).collect();
        area.draw(&Polygon::new(arc.clone(), colour.mix(0.14).filled()))?;
        area.draw(&PathElement::new(arc, colour.stroke_width(line_width(unit, 0.014))))?;
        area.draw(&PathElement::new(vec![at(1.0, fold[0]), at(1.0, fold[1])], colour.stroke_width(line_width(unit, 0.004))))?;
        let marker = (unit * 0.016).max(3.0) as i32;
        for (e, &f) in fold.iter().enumerate() {
            area.draw(&Circle::new(at(1.0, f), marker, colour.filled()))?;
            area.draw(&Circle::new(at(1.0, f), marker, WHITE.stroke_width(1)))?;
            // Endpoint names go inside, clear of the corner numbers outside.
            let (h, v) = outward(f + PI);
            let r = 1.0 - 0.09;
            area.draw(&Text::new(endpoint_name(k, e, count), at(r, f), text_style(size, colour, h, v)))?;
        }
    }
    Ok(())
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
    fn wrap_keeps_words_and_width() {
        let lines = wrap("one fold along the diagonal, corners 2 and 3 folded", 16);
        assert!(lines.iter().all(|l| l.chars().count() <= 16), "{lines:?}");
        assert_eq!(lines.join(" "), "one fold along the diagonal, corners 2 and 3 folded");
        assert_eq!(wrap("", 10), Vec::<String>::new());
    }
}
