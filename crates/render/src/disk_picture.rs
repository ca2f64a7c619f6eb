//! The dGLI disk picture: one annular sector per edge pair, as the paper draws it.
//!
//! Pair (a, a + d) sits on ring d counted from the rim, between radii (L − d)/L and
//! (L − d + 1)/L (L = ⌊N/2⌋), one edge wide (2π/N) and centred at its angle
//! θ = π(2a + d + 1)/N ([`close_core::disk::position`]); angle 0 points right (+x) and angles grow
//! anticlockwise. Every ring has N sectors, so for even N the d = N/2 pairs show at θ and
//! θ + π. The sectors are rasterised by inverse mapping — each pixel finds its (ring, sector)
//! from its polar coordinates — which is exact, leaves no seams between neighbouring
//! sectors and costs O(pixels) whatever N is; the rim is anti-aliased by pixel coverage.
//! Which cell each pixel shows depends on the canvas size and N alone, as do the rim
//! outline, its angle marks and the ring ruler: they are worked out once per (size, N) and
//! kept (`Template`), so a picture costs a table read per disk pixel, the replayed blends
//! of those guides, the colour bar, a few labels and the PNG encoding.
//! Over a diff disk the fold curves θ̂(r) = a0 + a1·r, r ∈ [1/L, 1], are drawn in polar
//! coordinates, with the fold points marked on the rim: the curves of the fold the step
//! reports, fitted with the paper's loss through its fold points
//! ([`close_core::fold::Evidence::curves`]), and
//! only on the disk of the two frames of that step. Layout and curves follow the disk figures of Kamat, Borràs, Torras, "CloSE: A
//! Geometric Shape-Agnostic Cloth State Representation" (the dGLI disk and the fold-curve
//! fit on the diff disk). A ruler under the disk names the rings by pair distance d; the
//! colour bar says its transform (tanh, see [`super::colour`]) and its scale.
//!
//! ```
//! use close_render::disk_picture::Layout;
//! let layout = Layout::of(480, 480);
//! // The centre of the disk is its own pixel; the rim is `radius` pixels away.
//! let (x, y) = layout.pixel(0.0, 0.0);
//! assert_eq!((x.round(), y.round()), (layout.cx.round(), layout.cy.round()));
//! ```

use std::f64::consts::PI;
use std::sync::{Arc, Mutex};

use plotters::style::text_anchor::{HPos, VPos};

use super::colour::{Ramp, Scale};
use super::raster::Recording;
pub use super::sector_map::sector_at;
use super::sector_map::SectorMap;
use super::{
    endpoint_name, fold_colour, label_size, line_width, note_size, outward, title_size, Canvas,
    INK, MUTED, MUTED_TEXT, PAPER,
};
use crate::error::Result;
use close_core::disk::Disk;
use close_core::fold::Curve;
use close_core::geometry::Fold;
use close_io::cache::Lru;

/// Height of the ring ruler's band under the disk, in label sizes.
const RULER_BAND: f64 = 2.4;

/// Where the disk and its colour bar sit on a canvas, in pixels (y grows downwards).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Layout {
    pub cx: f64,
    pub cy: f64,
    /// Pixel radius of the rim (r = 1).
    pub radius: f64,
    /// Colour bar: left, top, right, bottom.
    pub bar: [i32; 4],
}

impl Layout {
    /// The layout on a `width`×`height` canvas: title on top, colour bar on the right, the
    /// disk as large as fits in the rest with room for labels around the rim.
    pub fn of(width: u32, height: u32) -> Layout {
        let (w, h) = (width as f64, height as f64);
        let unit = w.min(h);
        let label = label_size(unit);
        let top = 1.8 * title_size(unit);
        let bar_width = (0.035 * unit).max(4.0);
        let band = bar_width + 5.5 * label;
        let pad = 1.6 * label;
        // Below the disk: the angle mark, then the ring ruler and its labels.
        let below = pad + RULER_BAND * label;
        let (room_x, room_y) = ((w - band - 2.0 * pad) / 2.0, (h - top - pad - below) / 2.0);
        let radius = room_x.min(room_y).max(4.0);
        // Centred in the room left of the bar, below the title.
        let (cx, cy) = (pad + room_x.max(radius), top + pad + room_y.max(radius));
        let bar_left = (w - band + label) as i32;
        // Room under the bar for the transform, the scale and N.
        let bar = [
            bar_left,
            (cy - 0.85 * radius) as i32,
            bar_left + bar_width as i32,
            (cy + 0.45 * radius) as i32,
        ];
        Layout { cx, cy, radius, bar }
    }

    /// The pixel of polar point (r, θ) (not rounded).
    pub fn pixel(&self, r: f64, theta: f64) -> (f64, f64) {
        (self.cx + self.radius * r * theta.cos(), self.cy - self.radius * r * theta.sin())
    }
}

/// What is drawn over a diff disk: fold points on the rim and the fold curves.
pub(crate) struct Marks {
    /// (fold number, 0-based, in step order; (f1, f2)) of each fold to mark.
    pub folds: Vec<(usize, Fold)>,
    /// How many folds the analysis has (names are numbered when more than one).
    pub total: usize,
    /// The curves to draw: those of the fold reported.
    pub curves: Vec<Curve>,
    /// A short note shown above the colour bar ("no fold", …).
    pub note: Option<String>,
}

/// Draw `disk` with `ramp` and colour `scale` under `title`; with `marks`, fold points and
/// curves on top.
pub(crate) fn draw(
    canvas: &mut Canvas,
    disk: &Disk,
    title: &str,
    ramp: Ramp,
    scale: &Scale,
    marks: Option<&Marks>,
) -> Result<()> {
    let layout = Layout::of(canvas.width, canvas.height);
    // Most rows of a disk repeat the row above: with the Up filter they encode as runs of
    // zeros, about 30 % faster and 8 % smaller than with Sub (480 px, N = 76).
    canvas.png_filter = png::FilterType::Up;
    let template = Template::of(canvas.width, canvas.height, disk.n());
    let colours: Vec<[u8; 3]> =
        disk.values().iter().map(|&v| ramp.colour(scale.squash(v))).collect();
    template.sectors.paint(canvas, &colours);
    let t_range = bar_range(ramp, scale);
    paint_bar(canvas, ramp, t_range, &layout);
    canvas.title(title);
    if canvas.is_vector() {
        // The recorded guides are pixels: an SVG draws them as vectors.
        draw_guides(canvas, &layout, disk.n());
    } else {
        canvas.replay(&template.guides);
    }
    draw_bar_ticks(canvas, &layout, scale, t_range);
    draw_bar_notes(canvas, &layout, scale, disk.n());
    if let Some(marks) = marks {
        draw_marks(canvas, &layout, marks, disk.layers());
    }
    Ok(())
}

/// The parts of a disk picture that depend on the canvas size and N alone, kept for the
/// next picture of that size and N: an animation or the web app's `/api/disk` draws many.
#[derive(Debug, PartialEq)]
struct Template {
    /// Which cell each disk pixel shows.
    sectors: SectorMap,
    /// The rim outline and its angle marks, and the ring ruler.
    guides: Recording,
}

/// Most templates kept.
const KEPT_TEMPLATES: usize = 16;
/// Most bytes the kept templates weigh in all: a 480 px template weighs about 0.5 MB, a
/// 2048 px one about 7 MB.
const KEPT_BYTES: usize = 32 << 20;

impl Template {
    /// The template of a `width`×`height` canvas for N = `n`, from the kept ones if it is there.
    fn of(width: u32, height: u32, n: usize) -> Arc<Template> {
        static KEPT: Mutex<Option<Lru<Arc<Template>>>> = Mutex::new(None);
        let key = format!("{width}x{height}/{n}");
        let kept = || KEPT.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(template) = kept().as_mut().and_then(|templates| templates.get(&key)) {
            return template;
        }
        // Made outside the lock: two threads may make the same template, neither waits.
        let template = Arc::new(Template::new(width, height, n));
        let bytes = template.sectors.bytes() + template.guides.bytes();
        kept().get_or_insert_with(|| Lru::new(KEPT_TEMPLATES, KEPT_BYTES)).insert(
            key,
            template.clone(),
            bytes,
        );
        template
    }

    fn new(width: u32, height: u32, n: usize) -> Template {
        let layout = Layout::of(width, height);
        let guides = Canvas::record(width, height, |canvas| draw_guides(canvas, &layout, n));
        Template {
            sectors: SectorMap::new(width, height, (layout.cx, layout.cy), layout.radius, n),
            guides,
        }
    }
}

/// The rim outline with its angle marks, and the ring ruler, of a disk of N = `n`.
fn draw_guides(canvas: &mut Canvas, layout: &Layout, n: usize) {
    draw_frame(canvas, layout);
    draw_ring_ruler(canvas, layout, n / 2);
}

/// The t interval the colour bar shows: the data's, from −max (or 0) to max.
fn bar_range(ramp: Ramp, scale: &Scale) -> (f64, f64) {
    let top = scale.squash(scale.max).max(1e-3);
    match ramp {
        Ramp::Diverging => (-top, top),
        Ramp::Sequential => (0.0, top),
    }
}

/// Paint the colour bar, t growing upwards.
fn paint_bar(canvas: &mut Canvas, ramp: Ramp, (lo, hi): (f64, f64), layout: &Layout) {
    let [left, top, right, bottom] = layout.bar;
    for y in top.max(0)..bottom.min(canvas.height as i32) {
        let t = hi - (hi - lo) * (y - top) as f64 / (bottom - top).max(1) as f64;
        let colour = ramp.colour(t);
        for x in left.max(0)..right.min(canvas.width as i32) {
            canvas.pixel_mut(x as u32, y as u32).copy_from_slice(&colour);
        }
    }
}

/// Rim outline and angle marks 0, π/2, π, 3π/2.
fn draw_frame(canvas: &mut Canvas, layout: &Layout) {
    let size = note_size(canvas.unit());
    canvas.ring((layout.cx, layout.cy), layout.radius, 1.0, MUTED);
    let gap = 0.3 * size / layout.radius;
    for (k, name) in ["0", "π/2", "π", "3π/2"].iter().enumerate() {
        let theta = k as f64 * PI / 2.0;
        canvas.stroke(&[layout.pixel(1.0, theta), layout.pixel(1.0 + gap, theta)], 1.0, MUTED);
        canvas.text(name, layout.pixel(1.0 + 2.0 * gap, theta), size, MUTED_TEXT, outward(theta));
    }
}

/// Outline, ticks and value labels of the colour bar (see [`bar_labels`]).
fn draw_bar_ticks(canvas: &mut Canvas, layout: &Layout, scale: &Scale, range: (f64, f64)) {
    let [left, top, right, bottom] = layout.bar.map(|v| v as f64);
    canvas.stroke(
        &[(left, top), (right, top), (right, bottom), (left, bottom), (left, top)],
        1.0,
        MUTED,
    );
    let size = label_size(canvas.unit());
    for label in bar_labels(scale, range, (top, bottom), size) {
        // The tick at its value, a leader to its label when the label had to move.
        canvas.stroke(
            &[
                (right, label.tick),
                (right + 0.4 * size, label.tick),
                (right + 0.6 * size, label.at),
            ],
            1.0,
            INK,
        );
        canvas.text(
            &format_value(label.value),
            (right + 0.7 * size, label.at),
            size,
            INK,
            (HPos::Left, VPos::Center),
        );
    }
}

/// A colour-bar value: where its tick is (pixel y), where its label is, and the value.
#[derive(Debug, Clone, Copy, PartialEq)]
struct BarLabel {
    tick: f64,
    at: f64,
    value: f64,
}

/// The colour bar's labelled values, on a bar from pixel `top` to `bottom` showing t in
/// `(lo, hi)`: ±max, 0, ±s and ±2s (the colour saturates near 2s, so that is where a reader
/// needs values), each tick where its value is and each label moved apart from the others by
/// at least a line (`size`), within the bar; ±2s dropped when there is no room for all.
fn bar_labels(
    scale: &Scale,
    (lo, hi): (f64, f64),
    (top, bottom): (f64, f64),
    size: f64,
) -> Vec<BarLabel> {
    let y_of = |t: f64| top + (hi - t) / (hi - lo) * (bottom - top);
    let gap = 1.05 * size;
    let signs: &[f64] = if lo < 0.0 { &[1.0, -1.0] } else { &[1.0] };
    let mut wanted: Vec<(f64, f64)> = vec![(0.0, 0.0)];
    for &sign in signs {
        wanted.push((sign * hi.abs().max(lo.abs()), sign * scale.max));
    }
    let inside = |t: f64| t > lo && t < hi;
    for multiple in [1.0, 2.0] {
        let before = wanted.len();
        for &sign in signs {
            let value = sign * multiple * scale.s;
            let t = scale.squash(value);
            // Only below the largest value shown, and clear of its tick.
            if inside(t) && value.abs() < scale.max && (y_of(t) - y_of(sign * hi.abs())).abs() > 1.0
            {
                wanted.push((t, value));
            }
        }
        if wanted.len() as f64 * gap > bottom - top + gap && multiple > 1.0 {
            wanted.truncate(before);
        }
    }
    let mut labels: Vec<BarLabel> =
        wanted.iter().map(|&(t, value)| BarLabel { tick: y_of(t), at: y_of(t), value }).collect();
    labels.sort_by(|a, b| a.tick.total_cmp(&b.tick));
    // Apart downwards from the top, then upwards from the bottom, within the bar.
    for k in 0..labels.len() {
        let floor = if k == 0 { top } else { labels[k - 1].at + gap };
        labels[k].at = labels[k].at.max(floor);
    }
    for k in (0..labels.len()).rev() {
        let ceiling = if k + 1 == labels.len() { bottom } else { labels[k + 1].at - gap };
        labels[k].at = labels[k].at.min(ceiling);
    }
    labels
}

/// Under the colour bar: the transform that maps a value to a colour (tanh, so the ticks
/// are not evenly spaced), its scale s, and the vertex count.
fn draw_bar_notes(canvas: &mut Canvas, layout: &Layout, scale: &Scale, n: usize) {
    let size = note_size(canvas.unit());
    let [left, _, _, bottom] = layout.bar.map(|v| v as f64);
    let lines = [
        "colour =".to_string(),
        "tanh(v/s)".to_string(),
        format!("s = {}", format_value(scale.s)),
        format!("N = {n}"),
    ];
    for (k, line) in lines.iter().enumerate() {
        let y = bottom + (1.6 + 1.4 * k as f64) * size;
        canvas.text(
            line,
            (left - 0.3 * size, y),
            size,
            if k < 2 { INK } else { MUTED_TEXT },
            (HPos::Left, VPos::Center),
        );
    }
}

/// A ruler under the disk, from the rim to the centre, naming the rings by the cyclic
/// distance d of their edge pairs (d = 1 at the rim, d = L at the centre).
fn draw_ring_ruler(canvas: &mut Canvas, layout: &Layout, layers: usize) {
    let size = note_size(canvas.unit());
    let l = layers.max(1);
    let y = layout.cy + layout.radius + 1.6 * label_size(canvas.unit()) + 0.4 * size;
    let x_of = |d: usize| {
        layout.cx - layout.radius * (l - d) as f64 / l as f64 - 0.5 * layout.radius / l as f64
    };
    canvas.stroke(&[(layout.cx - layout.radius, y), (layout.cx, y)], 1.0, MUTED);
    // Ticks at d = 1, L and round steps between, no closer than four labels' width.
    let room = (layout.radius / (3.0 * size)).max(1.0);
    let step = [1, 2, 5, 10, 20, 50, 100, 200, 500, 1000]
        .into_iter()
        .find(|&s| (l / s) as f64 <= room)
        .unwrap_or(l);
    let mut ticks: Vec<usize> =
        (0..=l).step_by(step).filter(|&d| d > 1 && d + step / 2 < l).collect();
    ticks.insert(0, 1);
    if l > 1 {
        ticks.push(l);
    }
    for d in ticks {
        let x = x_of(d);
        canvas.stroke(&[(x, y - 0.3 * size), (x, y + 0.3 * size)], 1.0, MUTED);
        canvas.text(&d.to_string(), (x, y + 0.5 * size), size, INK, (HPos::Center, VPos::Top));
    }
    canvas.text(
        "← ring: pair distance",
        (layout.cx + 0.4 * size, y),
        size,
        MUTED_TEXT,
        (HPos::Left, VPos::Center),
    );
}

/// A value with about three significant digits.
pub(crate) fn format_value(v: f64) -> String {
    let a = v.abs();
    match a {
        _ if a == 0.0 => "0".into(),
        _ if !(1e-3..1000.0).contains(&a) => format!("{v:.1e}"),
        _ if a >= 100.0 => format!("{v:.0}"),
        _ if a >= 10.0 => format!("{v:.1}"),
        _ if a >= 1.0 => format!("{v:.2}"),
        _ => format!("{v:.3}"),
    }
}

/// The fold curves and fold points of `marks`.
fn draw_marks(canvas: &mut Canvas, layout: &Layout, marks: &Marks, layers: usize) {
    let unit = canvas.unit();
    let width = line_width(unit, 0.005);
    let inner = 1.0 / layers.max(1) as f64;
    for curve in &marks.curves {
        let points: Vec<(f64, f64)> = (0..=96)
            .map(|k| inner + (1.0 - inner) * k as f64 / 96.0)
            .map(|r| layout.pixel(r, curve.a0 + curve.a1 * r))
            .collect();
        // A white halo keeps the curve visible on dark and light cells alike.
        canvas.stroke(&points, width + 2.0, PAPER);
        canvas.stroke(&points, width, INK);
    }
    let marker = (unit * 0.014).max(3.0);
    let size = label_size(unit);
    for &(k, fold) in &marks.folds {
        for (e, f) in [fold.f1, fold.f2].into_iter().enumerate() {
            let colour = fold_colour(k);
            canvas.disc(layout.pixel(1.0, f), marker + 1.5, PAPER);
            canvas.disc(layout.pixel(1.0, f), marker, colour);
            let at = layout.pixel(1.0 + 1.6 * marker / layout.radius, f);
            canvas.text(&endpoint_name(k, e, marks.total), at, size, colour, outward(f));
        }
    }
    if let Some(note) = &marks.note {
        // The top-left corner, outside the disk.
        let y = layout.cy - layout.radius + 0.2 * size;
        canvas.text(note, (0.5 * size, y), note_size(unit), MUTED_TEXT, (HPos::Left, VPos::Center));
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::{colours, decode, disk_png, folded_square, png, preview};
    use super::super::Picture;
    use super::*;

    #[test]
    fn the_colour_bar_reads_values_at_s_and_2s_and_its_labels_keep_apart() {
        let scale = Scale { s: 3.76, max: 132.0 };
        let size = 20.0;
        for (range, count) in
            [(bar_range(Ramp::Diverging, &scale), 7), (bar_range(Ramp::Sequential, &scale), 4)]
        {
            let labels = bar_labels(&scale, range, (100.0, 300.0), size);
            let values: Vec<f64> = labels.iter().map(|l| l.value).collect();
            assert_eq!(labels.len(), count, "{values:?}");
            for v in [3.76, 7.52, 132.0, 0.0] {
                assert!(values.contains(&v), "{v} not labelled: {values:?}");
            }
            for pair in labels.windows(2) {
                assert!(pair[1].at - pair[0].at >= 1.05 * size - 1e-9, "{labels:?}");
            }
            assert!(labels.iter().all(|l| (100.0..=300.0).contains(&l.at)));
            // Each tick of ±s, ±2s and 0 is where its value's colour is.
            let (lo, hi) = range;
            for l in labels.iter().filter(|l| l.value.abs() < scale.max) {
                let y = 100.0 + (hi - scale.squash(l.value)) / (hi - lo) * 200.0;
                assert!((l.tick - y).abs() < 1e-9, "{l:?}");
            }
        }
        // A short bar keeps ±max, 0 and ±s, and drops ±2s.
        let short = bar_labels(&scale, bar_range(Ramp::Diverging, &scale), (100.0, 200.0), size);
        assert_eq!(short.len(), 5, "{short:?}");
    }
    use close_core::disk::{condensed_index, position};

    /// The colour of the pixel at polar point (r, θ) of a decoded picture.
    fn sample(rgb: &[u8], width: u32, layout: &Layout, r: f64, theta: f64) -> [u8; 3] {
        let (x, y) = layout.pixel(r, theta);
        let k = (y as usize * width as usize + x as usize) * 3;
        [rgb[k], rgb[k + 1], rgb[k + 2]]
    }

    /// The middle of pair (i, j)'s sector.
    fn sector_middle(n: usize, i: usize, j: usize) -> (f64, f64) {
        let p = position(n, i, j);
        (p.radius - 0.5 / (n / 2) as f64, p.angle)
    }

    fn is_whiteish(c: [u8; 3]) -> bool {
        c.iter().all(|&v| v >= 245)
    }

    fn is_strong(c: [u8; 3]) -> bool {
        c.iter().max().unwrap() - c.iter().min().unwrap() > 80
    }

    #[test]
    fn templates_are_kept_and_shared() {
        let a = Template::of(77, 66, 10);
        assert!(
            Arc::ptr_eq(&a, &Template::of(77, 66, 10)),
            "the second call finds the first template"
        );
        assert_eq!(*a, Template::new(77, 66, 10));
        assert!(!Arc::ptr_eq(&a, &Template::of(77, 66, 12)));
        // The largest canvas's template fits in the budget, so every template can be kept.
        let largest = Template::new(super::super::MAX_SIZE, super::super::MAX_SIZE, 4);
        assert!(largest.sectors.bytes() + largest.guides.bytes() < KEPT_BYTES / 2);
    }

    #[test]
    fn sector_at_inverts_position() {
        for n in [4, 5, 8, 13, 100] {
            for i in 0..n {
                for j in i + 1..n {
                    let (r, theta) = sector_middle(n, i, j);
                    let (d, a) = sector_at(n, r, theta);
                    let pair = (a.min((a + d) % n), a.max((a + d) % n));
                    assert_eq!(pair, (i, j), "n = {n}");
                }
            }
        }
    }

    #[test]
    fn zero_cells_are_white_and_large_cells_coloured() {
        let analysis =
            folded_square(8, [std::f64::consts::FRAC_PI_4, 5.0 * std::f64::consts::FRAC_PI_4]);
        let disk = &analysis.disk(0).unwrap();
        let n = disk.n();
        let (w, h) = (400, 360);
        let (_, _, rgb) = decode(&disk_png(disk, "start", (w, h)));
        let layout = Layout::of(w, h);
        let scale = Scale::of(disk.values());
        let (mut white, mut strong) = (0, 0);
        for i in 0..n {
            let j = (i + 1) % n;
            let v = disk.get(i, j);
            let (r, theta) = sector_middle(n, i, j);
            let c = sample(&rgb, w, &layout, r, theta);
            if v.abs() < 1e-9 {
                assert!(is_whiteish(c), "zero cell ({i}, {j}) drawn {c:?}");
                white += 1;
            } else if v.abs() >= scale.s {
                assert!(is_strong(c), "cell ({i}, {j}) = {v} drawn {c:?}");
                strong += 1;
            }
        }
        // A square has straight sides (zero cells) and four corners (large cells).
        assert!(white > 0 && strong >= 4, "white {white}, strong {strong}");
    }

    #[test]
    fn sign_picks_the_side_of_the_map() {
        let mut values = vec![0.0; 28];
        values[condensed_index(8, 0, 1)] = 1.0;
        values[condensed_index(8, 2, 3)] = -1.0;
        let disk = Disk::from_values(8, values).unwrap();
        let (_, _, rgb) = decode(&disk_png(&disk, "signs", (300, 300)));
        let layout = Layout::of(300, 300);
        let [r, _, b] = sample(&rgb, 300, &layout, 0.9, position(8, 0, 1).angle);
        assert!(r > 150 && b < 100, "positive should be orange, got {r}, {b}");
        let [r, _, b] = sample(&rgb, 300, &layout, 0.9, position(8, 2, 3).angle);
        assert!(b > 100 && r < 100, "negative should be blue, got {r}, {b}");
        assert!(is_whiteish(sample(&rgb, 300, &layout, 0.9, position(8, 4, 5).angle)));
    }

    #[test]
    fn odd_disks_never_panic() {
        let zeros = Disk::from_values(50, vec![0.0; 50 * 49 / 2]).unwrap();
        let (_, _, rgb) = decode(&disk_png(&zeros, "zeros", (120, 100)));
        let layout = Layout::of(120, 100);
        assert!(is_whiteish(sample(&rgb, 120, &layout, 0.5, 1.0)));
        let four = Disk::from_values(4, vec![1.0, -1.0, 0.5, 0.0, 2.0, f64::NAN]).unwrap();
        decode(&disk_png(&four, "", (64, 64)));
        let big: Vec<f64> = (0..1000 * 999 / 2).map(|k| ((k % 97) as f64 - 48.0) / 10.0).collect();
        let big = Disk::from_values(1000, big).unwrap();
        decode(&disk_png(&big, "N = 1000", (160, 160)));
    }

    #[test]
    fn large_pictures_are_drawn_at_their_size_and_the_diff_differs_from_the_disk() {
        let analysis = folded_square(10, [0.3, 0.3 + std::f64::consts::PI]);
        for picture in Picture::ALL {
            let png = png(&analysis, picture, None, (1200, 900)).unwrap();
            let (w, h, rgb) = decode(&png);
            assert_eq!((w, h), (1200, 900), "{picture:?}");
            assert!(colours(&rgb) > 10, "{picture:?} is (nearly) one flat colour");
            preview(&format!("large_{}.png", picture.name()), &png);
        }
        let big = folded_square(25, [1.0, 4.0]);
        let (start, diff) = (
            png(&big, Picture::DiskStart, None, (480, 480)).unwrap(),
            png(&big, Picture::Diff, None, (480, 480)).unwrap(),
        );
        assert_ne!(
            decode(&start).2,
            decode(&diff).2,
            "the diff disk of a fold is not its start disk"
        );
        preview("n100_disk_start.png", &start);
        preview("n100_diff.png", &diff);
    }
}
