//! The border plot: start, true end and predicted end borders in the XY plane.
//!
//! Borders are closed polylines in the input's coordinates, drawn with equal scales on x
//! and y so shapes are not distorted. Each border's edges are drawn from low z to high z
//! with a thin white halo, so where a folded layer lies over the rest of the cloth it is
//! seen crossing on top. The true end is drawn wide and the prediction thin over it: where
//! they agree, the prediction runs inside the end line. Vertex 0 is marked on each border.
//! Each fold found is drawn as its line across the cloth (in the state it was made on: the
//! start with the folds before it applied), in its fold's colour; where the sample's true
//! folds are known, each is drawn dashed beside it, and the legend gives the found fold's
//! angle errors |f1 − t1|, |f2 − t2| (on the circle).
//!
//! ```
//! use close_render::borders::equal_aspect;
//! // A 2×1 box shown in a square plot gets a y range as wide as its x range.
//! let (x, y) = equal_aspect((0.0, 2.0), (0.0, 1.0), (100, 100));
//! assert_eq!((x, y), ((0.0, 2.0), (-0.5, 1.5)));
//! ```

use plotters::style::text_anchor::{HPos, VPos};

use super::axes::{self, Frame};
use super::cloth::{across, layers, make};
use super::raster::text_width;
use super::truth::{agreement, true_lines, Truth};
use super::{fold_colour, label_size, line_width, note_size, Canvas, INK, MUTED_TEXT, PAPER};
use crate::error::Result;
use crate::StepSpan;
use close_core::analysis::Analysis;
use std::ops::Range;

/// One border to draw: vertices (x, y, z), colour, line width in pixels, legend name.
struct Trace {
    points: Vec<[f64; 3]>,
    colour: [u8; 3],
    width: f64,
    name: &'static str,
}

/// A fold line to draw: its two ends (input XY), whether it is a true fold (dashed), which
/// fold (0-based), its colour and legend text (for a true fold, how the found one agrees).
struct FoldMark {
    ends: [[f64; 2]; 2],
    truth: bool,
    fold: usize,
    colour: [u8; 3],
    name: String,
}

/// The found folds' lines, and the true folds' beside them with how each found fold agrees
/// ([`super::truth`]: by its points, or for a fold of several arcs by its line and folded set).
fn fold_marks(analysis: &Analysis, truth: &Truth, shown: &Range<usize>) -> Vec<FoldMark> {
    let numbered = |what: &str, k: usize, count: usize| {
        if count > 1 {
            format!("{what} {}", k + 1)
        } else {
            what.to_string()
        }
    };
    // Each found fold's line across the state it folded, as the analysis made it.
    let found: Vec<Option<[[f64; 2]; 2]>> =
        match make(analysis.start_border(), &analysis.foldings()) {
            Ok((_, made)) => {
                layers(analysis.start_border(), &made, 1.0).lines.into_iter().map(Some).collect()
            }
            Err(_) => Vec::new(),
        };
    let true_lines = true_lines(analysis, truth);
    let true_segments: Vec<Option<[[f64; 2]; 2]>> =
        true_lines.iter().map(|(line, state)| line.as_ref().map(|l| across(state, l))).collect();
    let mut marks = Vec::new();
    for (k, segment) in found.into_iter().enumerate().filter(|(k, _)| shown.contains(k)) {
        if let Some(ends) = segment {
            marks.push(FoldMark {
                ends,
                truth: false,
                fold: k,
                colour: fold_colour(k),
                name: numbered("fold", k, analysis.folds.len()),
            });
        }
    }
    for (k, segment) in true_segments.into_iter().enumerate().filter(|(k, _)| shown.contains(k)) {
        let error = agreement(analysis, truth, k, true_lines[k].0.as_ref())
            .map_or_else(|| "not found".to_string(), |a| a.to_string());
        if let Some(ends) = segment {
            marks.push(FoldMark {
                ends,
                truth: true,
                fold: k,
                colour: fold_colour(k),
                name: format!("{} ({error})", numbered("true fold", k, truth.folds.len())),
            });
        }
    }
    marks
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

/// The borders of `analysis` over `span` that exist, bottom to top: its first and last
/// frames and what its folds predict for the last.
fn traces(analysis: &Analysis, unit: f64, span: &StepSpan) -> Vec<Trace> {
    let array = |p: &close_core::border::Point| [p.x, p.y, p.z];
    let (predicted, folds) = match span.step {
        Some(k) => (&analysis.steps[k - 1].predicted, analysis.steps[k - 1].folds.len()),
        None => (&analysis.predicted_end, analysis.folds.len()),
    };
    let mut traces = vec![Trace {
        points: analysis.frames[span.from].iter().map(array).collect(),
        colour: [160, 160, 160],
        width: line_width(unit, 0.004),
        name: "start",
    }];
    if span.to > span.from {
        traces.push(Trace {
            points: analysis.frames[span.to].iter().map(array).collect(),
            colour: [120, 170, 220],
            width: line_width(unit, 0.016),
            name: "end",
        });
    }
    if folds > 0 {
        traces.push(Trace {
            points: predicted.clone(),
            colour: [230, 110, 20],
            width: line_width(unit, 0.005),
            name: "predicted end",
        });
    }
    traces
}

/// The smallest box holding every point of `traces`, padded by 6 %; a unit box when empty.
fn bounds(traces: &[Trace]) -> ((f64, f64), (f64, f64)) {
    let points =
        traces.iter().flat_map(|t| &t.points).filter(|p| p[0].is_finite() && p[1].is_finite());
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

    /// The plotting area in pixels.
    fn frame(&self) -> Frame {
        Frame { left: self.px.0, right: self.px.1, top: self.py.0, bottom: self.py.1 }
    }

    fn pixel(&self, p: &[f64; 3]) -> (f64, f64) {
        let fx = (p[0] - self.x.0) / (self.x.1 - self.x.0);
        let fy = (p[1] - self.y.0) / (self.y.1 - self.y.0);
        (self.px.0 + fx * (self.px.1 - self.px.0), self.py.1 - fy * (self.py.1 - self.py.0))
    }
}

/// Draw the border plot of `analysis` over `step` (1-based; `None`: the whole analysis): the
/// span's first and last frames, the prediction and the folds of the span, with the `truth`
/// folds (when known) beside the found ones; gives how it mapped data to pixels.
pub(crate) fn draw(
    canvas: &mut Canvas,
    analysis: &Analysis,
    truth: &Truth,
    step: Option<usize>,
) -> Result<Mapping> {
    let unit = canvas.unit();
    let span = StepSpan::of(analysis, step)?;
    let traces = traces(analysis, unit, &span);
    let marks = fold_marks(analysis, truth, &span.folds(analysis));
    let (x, y) = bounds(&traces);
    let label = label_size(unit);
    let note = note_size(unit);
    let top = canvas.title_band();
    let (w, h) = (canvas.width as f64, canvas.height as f64);
    let entries = legend_entries(&traces, &marks, unit);
    // The metrics and the vertex-0 key: one line where it fits, else two.
    let metrics = match span.step {
        Some(k) => Some(&analysis.steps[k - 1].metrics),
        None => analysis.metrics.as_ref(),
    };
    let notes = match metrics {
        Some(m) => vec![
            format!(
                "RMSE {:.3} · Fréchet {:.3} · aligned {:.3} (normalised)",
                m.rmse, m.frechet, m.aligned_rmse
            ),
            "● vertex 0".to_string(),
        ],
        None => vec!["● vertex 0".to_string()],
    };
    let joined = notes.join(" · ");
    let notes = if text_width(&joined, note) <= w - label { vec![joined] } else { notes };
    let legend = Legend::lay_out(&entries, note, (0.5 * label, w - 0.5 * label));
    // The bottom margin holds the legend rows and the metrics line, outside the data.
    let row = 1.5 * note;
    let bottom = row * (legend.rows + notes.len()) as f64 + 0.6 * note;
    let mapping = plot_area(
        (x, y),
        |y| y_label_room(y, note),
        Frame { left: 0.6 * label, right: w - 1.2 * label, top, bottom: h - bottom - 1.9 * note },
    );
    axes::draw(canvas, mapping.frame(), mapping.x, mapping.y, note);
    canvas.title(&match span.step {
        Some(k) => format!("Borders (XY) · step {k}"),
        None => "Borders (XY)".to_string(),
    });
    for trace in &traces {
        draw_trace(canvas, trace, &mapping);
    }
    for mark in &marks {
        let ends = mark.ends.map(|[x, y]| mapping.pixel(&[x, y, 0.0]));
        if let Some(ends) = axes::clip(ends, mapping.frame()) {
            draw_line(canvas, ends, fold_width(unit, mark.truth), mark.colour, mark.truth);
        }
    }
    let first_row = h - bottom + 0.5 * row;
    legend.draw(canvas, &entries, note, first_row, row);
    for (k, text) in notes.iter().enumerate() {
        let y = first_row + (legend.rows + k) as f64 * row;
        canvas.text(text, (w - 0.5 * label, y), note, MUTED_TEXT, (HPos::Right, VPos::Center));
    }
    Ok(mapping)
}

/// Pixels the y tick labels of range `y` and their ticks take left of the axis.
fn y_label_room(y: (f64, f64), size: f64) -> f64 {
    let values = axes::ticks(y, 5);
    let step = match values.as_slice() {
        [a, b, ..] => b - a,
        _ => 1.0,
    };
    let widest =
        values.iter().map(|&v| text_width(&axes::tick_label(v, step), size)).fold(0.0, f64::max);
    widest + 0.8 * size
}

/// The mapping of data ranges (`x`, `y`) onto `room` (the plot with its y labels, whose
/// width `y_labels` gives for a y range): the plot takes what the labels leave and shows the
/// data at equal scales, centred.
fn plot_area(
    (x, y): ((f64, f64), (f64, f64)),
    y_labels: impl Fn((f64, f64)) -> f64,
    room: Frame,
) -> Mapping {
    // The labels depend on the y range shown, which depends on the room they leave: settle
    // it from the data's own range, then once more from the range shown.
    let mut left = room.left + y_labels(y);
    let mut shown = (x, y);
    for _ in 0..2 {
        let pixels =
            ((room.right - left).max(1.0) as u32, (room.bottom - room.top).max(1.0) as u32);
        shown = equal_aspect(x, y, pixels);
        left = room.left + y_labels(shown.1);
    }
    Mapping { x: shown.0, y: shown.1, px: (left, room.right), py: (room.top, room.bottom) }
}

/// Line width of a fold line: the found one solid and wide, a true one dashed and thinner,
/// so where the two agree the true one's dashes run inside the found one.
fn fold_width(unit: f64, truth: bool) -> f64 {
    line_width(unit, if truth { 0.004 } else { 0.009 })
}

/// A line from `ends[0]` to `ends[1]` (pixels): solid with a white halo, or dashed (dashes
/// and gaps of four widths) in `colour` darkened, without a halo, so a line under it shows
/// between the dashes.
fn draw_line(
    canvas: &mut Canvas,
    [a, b]: [(f64, f64); 2],
    width: f64,
    colour: [u8; 3],
    dashed: bool,
) {
    if dashed {
        let length = (b.0 - a.0).hypot(b.1 - a.1).max(1e-9);
        let period = 8.0 * width.max(1.5);
        let at = |t: f64| {
            (a.0 + (b.0 - a.0) * t.min(length) / length, a.1 + (b.1 - a.1) * t.min(length) / length)
        };
        let dark = colour.map(|c| (c as f64 * 0.55).round() as u8);
        for t in (0..(length / period).ceil() as usize).map(|k| k as f64 * period) {
            canvas.stroke(&[at(t), at(t + period / 2.0)], width, dark);
        }
    } else {
        canvas.stroke(&[a, b], width + 3.0, PAPER);
        canvas.stroke(&[a, b], width, colour);
    }
}

/// A legend's line sample: solid or dashed.
struct Swatch {
    colour: [u8; 3],
    width: f64,
    dashed: bool,
}

/// One legend entry: its swatches side by side and its text.
struct Entry {
    swatches: Vec<Swatch>,
    text: String,
}

/// The legend: one entry per border, and one per fold with its true fold's dashed swatch
/// beside it and how the two agree ("fold 1 (true: 0.3°, 0.1° off)"), so a fold and its truth
/// take one place; a true fold nothing was found for has its own entry.
fn legend_entries(traces: &[Trace], marks: &[FoldMark], unit: f64) -> Vec<Entry> {
    let swatch = |m: &FoldMark| Swatch {
        colour: m.colour,
        width: fold_width(unit, m.truth),
        dashed: m.truth,
    };
    let mut entries: Vec<Entry> = traces
        .iter()
        .map(|t| Entry {
            swatches: vec![Swatch { colour: t.colour, width: t.width, dashed: false }],
            text: t.name.to_string(),
        })
        .collect();
    let found = marks.iter().filter(|m| !m.truth);
    for mark in found.clone() {
        let true_mark = marks.iter().find(|t| t.truth && t.fold == mark.fold);
        let mut entry = Entry { swatches: vec![swatch(mark)], text: mark.name.clone() };
        if let Some(t) = true_mark {
            entry.swatches.push(swatch(t));
            // "true fold 1 (0.3°, 0.1° off)" → "fold 1 (true: 0.3°, 0.1° off)".
            let agreement = t.name.split_once(" (").map_or("", |(_, rest)| rest);
            entry.text = format!("{} (true: {agreement}", mark.name);
        }
        entries.push(entry);
    }
    let unmatched = marks.iter().filter(|t| t.truth && !found.clone().any(|m| m.fold == t.fold));
    entries.extend(unmatched.map(|t| Entry { swatches: vec![swatch(t)], text: t.name.clone() }));
    entries
}

/// Where each legend entry goes: entries flow left to right and wrap to a new row at the
/// right edge; an entry too long for a row of its own is broken into lines between words,
/// and takes as many rows.
struct Legend {
    /// (row, left x) of each entry.
    places: Vec<(usize, f64)>,
    /// Each entry's text, line by line.
    lines: Vec<Vec<String>>,
    rows: usize,
}

impl Legend {
    /// Swatch length in text sizes.
    const SWATCH: f64 = 2.2;

    /// Lay `entries` out in text of `size` between `left` and `right` (pixels).
    fn lay_out(entries: &[Entry], size: f64, (left, right): (f64, f64)) -> Legend {
        let (mut places, mut lines) = (Vec::new(), Vec::new());
        let (mut row, mut x, mut tall) = (0, left, 1);
        for entry in entries {
            let lead = Self::swatches_width(entry, size) + 0.4 * size;
            let text = wrap(&entry.text, size, right - left - lead);
            let wide = lead + text.iter().map(|l| text_width(l, size)).fold(0.0, f64::max);
            if x > left && (x + wide > right || text.len() > 1 || tall > 1) {
                (row, x) = (row + tall, left);
                tall = 1;
            }
            places.push((row, x));
            tall = tall.max(text.len());
            lines.push(text);
            x += wide + 1.2 * size;
        }
        let rows = if places.is_empty() { 0 } else { row + tall };
        Legend { places, lines, rows }
    }

    /// Pixels the swatches of `entry` take, side by side a third of a text size apart.
    fn swatches_width(entry: &Entry, size: f64) -> f64 {
        let each = entry.swatches.iter().map(|w| Self::SWATCH * size + w.width.max(2.0));
        each.sum::<f64>() + 0.3 * size * entry.swatches.len().saturating_sub(1) as f64
    }

    /// Draw the entries, the first row's centre at `top`, rows `row` apart.
    fn draw(&self, canvas: &mut Canvas, entries: &[Entry], size: f64, top: f64, row: f64) {
        for ((entry, &(r, x)), text) in entries.iter().zip(&self.places).zip(&self.lines) {
            let y = top + r as f64 * row;
            let mut left = x;
            for swatch in &entry.swatches {
                // A wide line's round caps reach half its width past its ends.
                let cap = swatch.width.max(2.0) / 2.0;
                let ends = [(left + cap, y), (left + cap + Self::SWATCH * size, y)];
                draw_line(canvas, ends, swatch.width.max(2.0), swatch.colour, swatch.dashed);
                left += Self::SWATCH * size + 2.0 * cap + 0.3 * size;
            }
            let text_x = x + Self::swatches_width(entry, size) + 0.4 * size;
            for (k, line) in text.iter().enumerate() {
                let at = (text_x, y + k as f64 * row);
                canvas.text(line, at, size, INK, (HPos::Left, VPos::Center));
            }
        }
    }
}

/// `text` in lines at most `width` pixels wide in text of `size`, broken between words (a
/// word wider than that alone on its line).
fn wrap(text: &str, size: f64, width: f64) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for word in text.split(' ') {
        match lines.last_mut() {
            Some(line) if text_width(&format!("{line} {word}"), size) <= width => {
                line.push(' ');
                line.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines
}

/// A mini drawing for a list of samples: the start border thin grey, the end border thick
/// blue over it, as large as the picture allows; no text, axes or legend, which would be
/// unreadable at this size.
pub(crate) fn draw_thumbnail(canvas: &mut Canvas, analysis: &Analysis) {
    let unit = canvas.unit();
    let mut traces = match StepSpan::of(analysis, None) {
        Ok(whole) => traces(analysis, unit, &whole),
        Err(_) => return,
    };
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
    let (lo, hi) =
        (0..n).map(z).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
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
    fn true_folds_are_drawn_beside_the_found_ones_with_their_errors() {
        let entry =
            close_io::dataset::Dataset::builtin().get("napkin__half_then_half").unwrap().clone();
        let analysis = close_core::analyze(
            &entry.sample.border_frames().unwrap(),
            close_core::FrameRange::default(),
        )
        .unwrap();
        let truth = Truth::of(entry.sample.truth.as_ref().unwrap());
        assert_eq!((analysis.folds.len(), truth.folds.len()), (2, 2));
        let whole = StepSpan::of(&analysis, None).unwrap();
        let marks = fold_marks(&analysis, &truth, &whole.folds(&analysis));
        let (found, true_ones): (Vec<&FoldMark>, Vec<&FoldMark>) =
            marks.iter().partition(|m| !m.truth);
        assert_eq!((found.len(), true_ones.len()), (2, 2));
        let size = bounds(&traces(&analysis, 480.0, &whole)).0;
        let size = size.1 - size.0;
        for (k, (f, t)) in found.iter().zip(&true_ones).enumerate() {
            let off = |e: usize| {
                let pair = |f: close_core::geometry::Fold| [f.f1, f.f2];
                close_core::angle::distance(pair(analysis.folds[k])[e], pair(truth.folds[k])[e])
                    .to_degrees()
            };
            let errors = format!("{:.1}°, {:.1}° off", off(0), off(1));
            assert!(t.name.contains(&errors), "{} lacks {errors}", t.name);
            assert_eq!(f.colour, t.colour, "fold {k} and its truth share a colour");
            // Found right, so each true line runs where the found one does (either way round).
            let d = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]);
            let apart = (d(f.ends[0], t.ends[0]) + d(f.ends[1], t.ends[1]))
                .min(d(f.ends[0], t.ends[1]) + d(f.ends[1], t.ends[0]));
            assert!(apart < 0.1 * size, "fold {k}: the true line is {apart} away");
        }
        let picture = |truth: &Truth| {
            let known = super::super::Known { truth, mesh: None };
            super::super::render(
                &analysis,
                &super::super::View::whole(super::super::Picture::Borders),
                &super::super::Output::png(480),
                known,
            )
            .unwrap()
        };
        let (with, without) = (picture(&truth), picture(&Truth::default()));
        assert_ne!(with, without, "the truth draws nothing");
        super::super::tests::preview("borders_truth.png", &with);
    }

    #[test]
    fn long_legend_texts_break_between_words() {
        let text = "fold (true: line 0.1° and 0.001 apart, 19% of its folded vertices shared)";
        let lines = wrap(text, 12.0, 150.0);
        assert!(lines.len() > 1 && lines.join(" ") == text, "{lines:?}");
        assert!(lines.iter().all(|l| text_width(l, 12.0) <= 150.0 || !l.contains(' ')));
        assert_eq!(wrap("fold 1", 12.0, 150.0), vec!["fold 1"]);
    }

    #[test]
    fn bounds_of_nothing_is_a_unit_box() {
        assert_eq!(bounds(&[]), ((0.0, 1.0), (0.0, 1.0)));
    }
}
