//! The CloSE fold circle: the border parameter drawn as the unit circle.
//!
//! A border parameter s sits at angle 2πs/N, vertex 0 at angle 0 (right), anticlockwise.
//! The corners θ_1 < … < θ_n are numbered dots (1-based, numbers left out beyond 20
//! corners, where the cloth counts as circular). Each fold (f1, f2) is the arc from f1
//! anticlockwise to f2 — the folded side — drawn thick and shaded up to the chord f1–f2,
//! which is the fold line. The values are written underneath. Drawn for one step of the
//! analysis, the folds that step made keep their colours and the others are faded, so the
//! circle follows the step as the disks and the border plot do.
//!
//! ```
//! use close_core::geometry::Arc;
//! use close_render::circle::folded_arc;
//! use std::f64::consts::PI;
//! // The arc from 3π/2 to π/2 wraps through 0 and spans half the circle.
//! let arc = folded_arc(Arc::new(1.5 * PI, 0.5 * PI), 5);
//! assert!((arc[2] - 2.0 * PI).abs() < 1e-12);
//! ```

use std::f64::consts::TAU;

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

use super::raster::{mix, text_width};
use super::truth::{agreement, true_lines, Truth};
use super::{
    endpoint_name, fold_colour, label_size, line_width, note_size, plot, title_size, Canvas,
    StepSpan, INK, MUTED, MUTED_TEXT, PAPER,
};
use crate::error::Result;
use close_core::analysis::Analysis;
use close_core::geometry::{Arc, Fold};
use std::ops::Range;

/// Corners beyond this count are drawn without numbers (the paper's label calls such a cloth circular).
pub const NUMBERED_CORNERS: usize = 20;

/// Fold `k`'s colour on a circle that shows the folds `shown` (indices into
/// [`Analysis::foldings`]): its own, or mostly paper for a fold of another step.
fn colour_of(k: usize, shown: &Range<usize>) -> [u8; 3] {
    let mut colour = fold_colour(k);
    if !shown.contains(&k) {
        colour = PAPER;
        mix(&mut colour, fold_colour(k), 0.3);
    }
    colour
}

/// `points` angles from f1 anticlockwise to f2 (unwrapped: increasing from f1).
pub fn folded_arc(Arc { a: f1, b: f2 }: Arc, points: usize) -> Vec<f64> {
    let span = (f2 - f1).rem_euclid(TAU);
    let last = points.max(2) - 1;
    (0..=last).map(|k| f1 + span * k as f64 / last as f64).collect()
}

/// The lines of text under the circle, one per fold: its values and, where the truth is
/// known, the found fold's angle errors against the true one (drawn as ○); a true fold not
/// found gets its own line. Each line is wrapped to `width` (the corners and folds are named
/// on the circle; the label sentence is the page's).
fn caption(
    analysis: &Analysis,
    truth: &Truth,
    shown: &Range<usize>,
    size: f64,
    width: f64,
) -> Vec<(String, [u8; 3])> {
    let mut lines = Vec::new();
    let count = analysis.folds.len();
    let true_lines = true_lines(analysis, truth);
    for (k, f) in analysis.folds.iter().enumerate() {
        let names = [endpoint_name(k, 0, count), endpoint_name(k, 1, count)];
        // Compared by its points, or for a fold of several arcs by its line and folded set.
        let line = true_lines.get(k).and_then(|(line, _)| line.as_ref());
        let error =
            agreement(analysis, truth, k, line).map_or_else(String::new, |a| format!(" · ○ {a}"));
        lines.push((
            format!("{} = {:.2}, {} = {:.2} rad{error}", names[0], f.f1, names[1], f.f2),
            colour_of(k, shown),
        ));
    }
    if count == 0 {
        lines.push(("no fold detected".into(), MUTED_TEXT));
    }
    for (k, t) in truth.folds.iter().enumerate().skip(count) {
        lines.push((
            format!("○ true fold {} = {:.2}, {:.2} rad: not found", k + 1, t.f1, t.f2),
            colour_of(k, shown),
        ));
    }
    let fits = |line: &str| text_width(line, size) <= width;
    lines
        .into_iter()
        .flat_map(|(text, colour)| wrap(&text, fits).into_iter().map(move |l| (l, colour)))
        .collect()
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
#[derive(Debug, Clone, Copy)]
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

/// A label that names a point of the circle: its text, colour and the angle of its point.
#[derive(Debug, Clone)]
struct Label {
    text: String,
    colour: [u8; 3],
    theta: f64,
}

/// A label placed: its box [x0, y0, x1, y1] in pixels, and whether it left its own angle
/// or ring (then a leader line joins it to its point).
#[derive(Debug, Clone)]
struct Placed {
    label: Label,
    bounds: [f64; 4],
    moved: bool,
}

/// Everything the fold circle draws, and where.
struct Layout {
    frame: Frame,
    /// Font size of the labels round the circle.
    size: f64,
    /// Font size of the caption.
    note: f64,
    /// Radius (pixels) of the ring the labels start on, just outside the markers.
    ring: f64,
    labels: Vec<Placed>,
    /// Caption lines, their colour and baseline centre y.
    caption: Vec<(String, [u8; 3], f64)>,
}

/// The box of a label of `width`×`height` pixels centred on the ray at angle `theta` from
/// the centre of `frame`, just beyond the tangent to the circle of radius `rho` pixels there
/// (so wholly outside that circle).
fn label_box(frame: &Frame, rho: f64, theta: f64, (width, height): (f64, f64)) -> [f64; 4] {
    let (c, s) = (theta.cos(), theta.sin());
    // The box's half extent along the ray: the box lies beyond the tangent at `rho`.
    let reach = (c.abs() * width + s.abs() * height) / 2.0;
    let (x, y) = (frame.cx + (rho + reach) * c, frame.cy - (rho + reach) * s);
    [x - width / 2.0, y - height / 2.0, x + width / 2.0, y + height / 2.0]
}

/// Place `labels` (most important first) outside the circle: each at the free place
/// nearest its own (on the first ring at its angle; else nudged along the circle or out to
/// a further ring, the least displacement first); a place must keep off the boxes placed
/// before it and inside `bounds` [x0, y0, x1, y1]. With no free place, it takes the least
/// crowded one.
fn place_labels(
    labels: Vec<Label>,
    frame: &Frame,
    ring: f64,
    size: f64,
    bounds: [f64; 4],
) -> Vec<Placed> {
    let gap = 0.25 * size;
    let height = 0.8 * size;
    // Nudges (ring r, angle step k) by the distance they move a label, nearest first.
    let (along, out) = (0.4 * size, 1.2 * height);
    let mut nudges: Vec<(usize, i32)> =
        (0..4).flat_map(|r| (-24..=24).map(move |k| (r, k))).collect();
    nudges.sort_by(|a, b| {
        (a.0 as f64 * out)
            .hypot(a.1 as f64 * along)
            .total_cmp(&(b.0 as f64 * out).hypot(b.1 as f64 * along))
    });
    let mut placed: Vec<Placed> = Vec::new();
    for label in labels {
        let dims = (text_width(&label.text, size), height);
        let mut best: Option<(f64, [f64; 4], bool)> = None;
        for &(r, k) in &nudges {
            let rho = ring + r as f64 * out;
            let b = label_box(frame, rho, label.theta + k as f64 * along / rho.max(1.0), dims);
            let inside =
                b[0] >= bounds[0] && b[1] >= bounds[1] && b[2] <= bounds[2] && b[3] <= bounds[3];
            if !inside {
                continue;
            }
            let crowding: f64 = placed.iter().map(|p| overlap_area(&p.bounds, &b, gap)).sum();
            let moved = (r, k) != (0, 0);
            if crowding == 0.0 {
                best = Some((0.0, b, moved));
                break;
            }
            if best.is_none_or(|(c, _, _)| crowding < c) {
                best = Some((crowding, b, moved));
            }
        }
        let (_, bounds_of, moved) =
            best.unwrap_or((0.0, label_box(frame, ring, label.theta, dims), false));
        placed.push(Placed { label, bounds: bounds_of, moved });
    }
    placed
}

/// Area two boxes share once each is grown by `gap` on every side (0 when apart).
fn overlap_area(a: &[f64; 4], b: &[f64; 4], gap: f64) -> f64 {
    let w = (a[2].min(b[2]) - a[0].max(b[0]) + 2.0 * gap).max(0.0);
    let h = (a[3].min(b[3]) - a[1].max(b[1]) + 2.0 * gap).max(0.0);
    w * h
}

impl Layout {
    /// The fold circle of `analysis` with `truth` and the folds `shown` on a `width`×`height`
    /// canvas: the title, the caption at the bottom, the circle as large as the rest allows
    /// with a margin for the labels, which are placed round it without overlapping.
    fn of(
        width: u32,
        height: u32,
        analysis: &Analysis,
        truth: &Truth,
        shown: &Range<usize>,
    ) -> Layout {
        let (w, h) = (width as f64, height as f64);
        let unit = w.min(h);
        let size = label_size(unit);
        let line_height = 1.35 * note_size(unit);
        let lines = caption(analysis, truth, shown, note_size(unit), w - size);
        let top = 1.8 * title_size(unit);
        let text_top = h - line_height * lines.len() as f64 - 0.3 * size;
        let labels = labels(analysis, shown);
        let widest = labels.iter().map(|l| text_width(&l.text, size)).fold(0.0, f64::max);
        let marker = (unit * 0.022).max(4.0);
        // Room for a ring of labels and a half above and below, a label and a nudge on the sides.
        let (pad_x, pad_y) = (
            marker + 0.4 * size + widest + 0.3 * size,
            marker + 0.4 * size + 1.5 * 1.2 * 0.8 * size,
        );
        let radius = ((w - 2.0 * pad_x) / 2.0).min((text_top - top - 2.0 * pad_y) / 2.0).max(4.0);
        let frame = Frame {
            cx: w / 2.0,
            cy: top + pad_y + radius + ((text_top - top - 2.0 * pad_y) / 2.0 - radius).max(0.0),
            radius,
        };
        let ring = radius + marker + 0.3 * size;
        let placed = place_labels(labels, &frame, ring, size, [0.0, top, w, text_top]);
        let caption = lines
            .into_iter()
            .enumerate()
            .map(|(k, (text, colour))| (text, colour, text_top + line_height * (k as f64 + 0.5)))
            .collect();
        Layout { frame, size, note: note_size(unit), ring, labels: placed, caption }
    }
}

/// The labels round the circle, most important first: the fold endpoints' names, the
/// corner numbers (at most [`NUMBERED_CORNERS`] corners), then "0 rad" where angles start.
fn labels(analysis: &Analysis, shown: &Range<usize>) -> Vec<Label> {
    let count = analysis.folds.len();
    let folds = analysis.folds.iter().enumerate().flat_map(|(k, fold)| {
        [fold.f1, fold.f2].into_iter().enumerate().map(move |(e, f)| Label {
            text: endpoint_name(k, e, count),
            colour: colour_of(k, shown),
            theta: f,
        })
    });
    let numbered = analysis.corners.len() <= NUMBERED_CORNERS;
    let corners = analysis
        .corners
        .iter()
        .enumerate()
        .filter(|_| numbered)
        .map(|(k, &theta)| Label { text: (k + 1).to_string(), colour: INK, theta });
    folds
        .chain(corners)
        .chain([Label { text: "0 rad".into(), colour: MUTED_TEXT, theta: 0.0 }])
        .collect()
}

/// Draw the fold circle of `analysis`, with the `truth` folds (when known) as hollow
/// markers joined by a thin chord beside the found ones; for `step` (1-based; `None`: the
/// whole analysis), the folds that step made are drawn in their colours, the others faded.
pub(crate) fn draw(
    canvas: &mut Canvas,
    analysis: &Analysis,
    truth: &Truth,
    step: Option<usize>,
) -> Result<()> {
    let unit = canvas.unit();
    let shown = &StepSpan::of(analysis, step)?.folds(analysis);
    let layout = Layout::of(canvas.width, canvas.height, analysis, truth, shown);
    let frame = layout.frame;
    shade_folded_sides(canvas, analysis, shown, &frame)?;
    match step {
        Some(k) => canvas.title(&format!("CloSE fold circle · step {k}")),
        None => canvas.title("CloSE fold circle"),
    }
    canvas.ring((frame.cx, frame.cy), frame.radius, line_width(unit, 0.004), INK);
    // The tick where angles start, outwards.
    canvas.stroke(
        &[frame.at(1.0, 0.0), (frame.cx + layout.ring, frame.cy)],
        line_width(unit, 0.003),
        INK,
    );
    draw_corners(canvas, &analysis.corners, &frame);
    draw_truth(canvas, &truth.folds, shown, &frame);
    draw_folds(canvas, analysis, shown, &frame);
    for placed in &layout.labels {
        let [x0, y0, x1, y1] = placed.bounds;
        let centre = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
        if placed.moved {
            // A leader from just outside the point's marker to the nearest point of the label.
            let from = frame.at(layout.ring / frame.radius, placed.label.theta);
            canvas.stroke(&[from, (from.0.clamp(x0, x1), from.1.clamp(y0, y1))], 1.0, MUTED);
        }
        canvas.text(
            &placed.label.text,
            centre,
            layout.size,
            placed.label.colour,
            (HPos::Center, VPos::Center),
        );
    }
    for (text, colour, y) in &layout.caption {
        canvas.text(
            text,
            (0.5 * layout.size, *y),
            layout.note,
            *colour,
            (HPos::Left, VPos::Center),
        );
    }
    Ok(())
}

/// The folded side of each fold, between each of its arcs and its chord, lightly shaded.
fn shade_folded_sides(
    canvas: &mut Canvas,
    analysis: &Analysis,
    shown: &Range<usize>,
    frame: &Frame,
) -> Result<()> {
    canvas.draw(|area| {
        for (k, folding) in analysis.foldings().iter().enumerate() {
            for &fold in &folding.arcs {
                let arc: Vec<(i32, i32)> = folded_arc(fold, 361)
                    .into_iter()
                    .map(|t| frame.at(1.0, t))
                    .map(|(x, y)| (x.round() as i32, y.round() as i32))
                    .collect();
                area.draw(&Polygon::new(arc, plot(colour_of(k, shown)).mix(0.14).filled()))?;
            }
        }
        Ok(())
    })
}

/// Corner dots on the circle.
fn draw_corners(canvas: &mut Canvas, corners: &[f64], frame: &Frame) {
    let dot = (canvas.unit() * 0.012).max(2.0);
    for &theta in corners {
        canvas.disc(frame.at(1.0, theta), dot + 1.5, PAPER);
        canvas.disc(frame.at(1.0, theta), dot, INK);
    }
}

/// Each true fold: its chord thin, its two points as hollow rings in its fold's colour.
fn draw_truth(canvas: &mut Canvas, truth: &[Fold], shown: &Range<usize>, frame: &Frame) {
    let unit = canvas.unit();
    let marker = (unit * 0.022).max(4.0);
    for (k, t) in truth.iter().enumerate() {
        let colour = colour_of(k, shown);
        canvas.stroke(&[frame.at(1.0, t.f1), frame.at(1.0, t.f2)], line_width(unit, 0.003), MUTED);
        for a in [t.f1, t.f2] {
            canvas.ring(frame.at(1.0, a), marker, line_width(unit, 0.004), colour);
        }
    }
}

/// Each fold: its arcs (the folded side: one, or several for a multi-arc fold), the chord of
/// each (the fold line) and its two endpoints.
fn draw_folds(canvas: &mut Canvas, analysis: &Analysis, shown: &Range<usize>, frame: &Frame) {
    let unit = canvas.unit();
    let marker = (unit * 0.016).max(3.0);
    for (k, folding) in analysis.foldings().iter().enumerate() {
        let (colour, fold) = (colour_of(k, shown), folding.fold);
        for &arc in &folding.arcs {
            let Arc { a, b } = arc;
            let arc: Vec<(f64, f64)> =
                folded_arc(arc, 361).into_iter().map(|t| frame.at(1.0, t)).collect();
            canvas.stroke(&arc, line_width(unit, 0.014), colour);
            canvas.stroke(&[frame.at(1.0, a), frame.at(1.0, b)], line_width(unit, 0.005), colour);
        }
        for f in [fold.f1, fold.f2] {
            canvas.disc(frame.at(1.0, f), marker + 1.5, PAPER);
            canvas.disc(frame.at(1.0, f), marker, colour);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn folded_arc_runs_anticlockwise_from_f1_to_f2() {
        let arc = folded_arc(Arc::new(1.0, 0.5), 3);
        assert_eq!(arc[0], 1.0);
        assert!((arc[2] - (0.5 + TAU)).abs() < 1e-12);
        assert!(arc.windows(2).all(|w| w[1] >= w[0]));
    }

    #[test]
    fn boxes_overlap_only_when_they_meet() {
        let a = [0.0, 0.0, 10.0, 10.0];
        assert!(overlap_area(&a, &[5.0, 5.0, 15.0, 15.0], 0.0) > 0.0);
        assert_eq!(overlap_area(&a, &[11.0, 0.0, 20.0, 10.0], 0.5), 0.0);
        assert!(overlap_area(&a, &[10.2, 0.0, 20.0, 10.0], 0.5) > 0.0);
        // A label right of the circle starts past the tangent; one above ends under nothing.
        let frame = Frame { cx: 100.0, cy: 100.0, radius: 50.0 };
        let right = label_box(&frame, 60.0, 0.0, (20.0, 8.0));
        assert!((right[0] - 160.0).abs() < 1e-9 && (right[1] - 96.0).abs() < 1e-9);
        let up = label_box(&frame, 60.0, std::f64::consts::FRAC_PI_2, (20.0, 8.0));
        assert!((up[3] - 40.0).abs() < 1e-9);
    }

    /// The analysis of a built-in sample and its true folds.
    fn builtin(id: &str) -> (Analysis, Truth) {
        let entry = close_io::dataset::Dataset::builtin().get(id).unwrap().clone();
        let analysis = close_core::analyze(
            &entry.sample.border_frames().unwrap(),
            close_core::FrameRange::default(),
        )
        .unwrap();
        (analysis, entry.sample.truth.as_ref().map(Truth::of).unwrap_or_default())
    }

    #[test]
    fn labels_keep_apart_off_the_circle_and_inside_the_picture() {
        for (id, size) in [
            ("tshirt__half_then_sleeve", 480),
            ("tshirt__half_then_sleeve", 1400),
            ("napkin__diagonal", 480),
            ("trousers__legs_up_then_half", 320),
        ] {
            let (analysis, truth) = builtin(id);
            let all = 0..analysis.folds.len();
            let layout = Layout::of(size, size, &analysis, &truth, &all);
            let known = super::super::Known { truth: &truth, mesh: None };
            let png = super::super::render(
                &analysis,
                &super::super::View::whole(super::super::Picture::Close),
                &super::super::Output::png(size),
                known,
            )
            .unwrap();
            super::super::tests::preview(&format!("circle_{id}_{size}.png"), &png);
            let labels = &layout.labels;
            assert!(
                labels.len() > analysis.corners.len().min(NUMBERED_CORNERS),
                "{id}: every corner is named"
            );
            for (k, a) in labels.iter().enumerate() {
                let [x0, y0, x1, y1] = a.bounds;
                assert!(
                    x0 >= 0.0 && y0 >= 0.0 && x1 <= size as f64 && y1 <= size as f64,
                    "{id}: {:?} leaves the picture",
                    a.label.text
                );
                // Wholly outside the circle and its markers.
                let (dx, dy) = (
                    ((x0 + x1) / 2.0 - layout.frame.cx).abs(),
                    ((y0 + y1) / 2.0 - layout.frame.cy).abs(),
                );
                let nearest =
                    ((dx - (x1 - x0) / 2.0).max(0.0)).hypot((dy - (y1 - y0) / 2.0).max(0.0));
                assert!(nearest >= layout.ring - 1e-9, "{id}: {:?} is on the circle", a.label.text);
                for b in &labels[k + 1..] {
                    assert_eq!(
                        overlap_area(&a.bounds, &b.bounds, 0.0),
                        0.0,
                        "{id} at {size}: {:?} and {:?} overlap",
                        a.label.text,
                        b.label.text
                    );
                }
            }
            // The caption starts under the lowest label.
            let lowest = labels.iter().map(|p| p.bounds[3]).fold(0.0, f64::max);
            let first = layout.caption.first().map_or(f64::INFINITY, |c| c.2 - 0.5 * layout.note);
            assert!(lowest <= first, "{id}: labels run into the caption");
            // The circle has most of the picture.
            assert!(
                layout.frame.radius >= 0.2 * size as f64,
                "{id} at {size}: radius {}",
                layout.frame.radius
            );
        }
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
