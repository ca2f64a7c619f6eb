//! The dGLI disk picture: one annular sector per edge pair, as the paper draws it.
//!
//! Pair (a, a + d) sits on ring d counted from the rim, between radii (L − d)/L and
//! (L − d + 1)/L (L = ⌊N/2⌋), one edge wide (2π/N) and centred at its angle
//! θ = π(2a + d + 1)/N ([`crate::disk::position`]); angle 0 points right (+x) and angles grow
//! anticlockwise. Every ring has N sectors, so for even N the d = N/2 pairs show at θ and
//! θ + π. The sectors are rasterised by inverse mapping — each pixel finds its (ring, sector)
//! from its polar coordinates — which is exact, leaves no seams between neighbouring
//! sectors and costs O(pixels) whatever N is; the rim is anti-aliased by pixel coverage.
//! Over a diff disk the fitted fold curves θ̂(r) = a0 + a1·r, r ∈ [1/L, 1], are drawn in polar
//! coordinates, with the fold points marked on the rim.
//!
//! ```
//! use close::render::disk::Layout;
//! let layout = Layout::of(480, 480);
//! // The centre of the disk is its own pixel; the rim is `radius` pixels away.
//! let (x, y) = layout.pixel(0.0, 0.0);
//! assert_eq!((x.round(), y.round()), (layout.cx.round(), layout.cy.round()));
//! ```

use std::f64::consts::{PI, TAU};

use plotters::style::text_anchor::{HPos, VPos};

use super::colour::{Ramp, Scale};
use super::{endpoint_name, fold_colour, label_size, line_width, outward, title_size, Canvas, INK, MUTED, PAPER};
use crate::analysis::Analysis;
use crate::disk::{condensed_index, Disk};
use crate::error::Result;

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
        let (room_x, room_y) = ((w - band - 2.0 * pad) / 2.0, (h - top - 2.0 * pad) / 2.0);
        let radius = room_x.min(room_y).max(4.0);
        // Centred in the room left of the bar, below the title.
        let (cx, cy) = (pad + room_x.max(radius), top + pad + room_y.max(radius));
        let bar_left = (w - band + label) as i32;
        let bar = [bar_left, (cy - 0.75 * radius) as i32, bar_left + bar_width as i32, (cy + 0.75 * radius) as i32];
        Layout { cx, cy, radius, bar }
    }

    /// The pixel of polar point (r, θ) (not rounded).
    pub fn pixel(&self, r: f64, theta: f64) -> (f64, f64) {
        (self.cx + self.radius * r * theta.cos(), self.cy - self.radius * r * theta.sin())
    }

}

/// The (ring d, first edge a) of the sector holding polar point (r ≤ 1, θ) on an N-edge disk.
pub fn sector_at(n: usize, r: f64, theta: f64) -> (usize, usize) {
    let l = n / 2;
    // Ring d spans ((L − d)/L, (L − d + 1)/L]; the centre belongs to the innermost ring.
    let d = (l + 1).saturating_sub((r * l as f64).ceil() as usize).clamp(1, l);
    // θ = π(2a + d + 1)/N, sectors one edge wide around it.
    let a = ((theta * n as f64 / PI - d as f64 - 1.0) / 2.0).round();
    (d, a.rem_euclid(n as f64) as usize % n)
}

/// Draw `disk` with `ramp` under `title`; with `analysis`, its fold curves and points on top.
pub(crate) fn draw(canvas: &mut Canvas, disk: &Disk, title: &str, ramp: Ramp, analysis: Option<&Analysis>) -> Result<()> {
    let layout = Layout::of(canvas.width, canvas.height);
    let scale = Scale::of(disk.values());
    paint_sectors(canvas, disk, ramp, &scale, &layout);
    let t_range = bar_range(ramp, &scale);
    paint_bar(canvas, ramp, t_range, &layout);
    canvas.title(title);
    draw_frame(canvas, &layout, disk.n());
    draw_bar_ticks(canvas, &layout, &scale, t_range);
    if let Some(analysis) = analysis {
        draw_folds(canvas, &layout, analysis, disk.layers());
    }
    Ok(())
}

/// Fill every pixel of the disk with its sector's colour.
fn paint_sectors(canvas: &mut Canvas, disk: &Disk, ramp: Ramp, scale: &Scale, layout: &Layout) {
    let n = disk.n();
    let cell_colours: Vec<[u8; 3]> = disk.values().iter().map(|&v| ramp.colour(scale.squash(v))).collect();
    let colour_of = |d: usize, a: usize| {
        let (i, j) = (a, (a + d) % n);
        cell_colours[condensed_index(n, i.min(j), i.max(j))]
    };
    let Layout { cx, cy, radius, .. } = *layout;
    let y_range = ((cy - radius - 1.0).max(0.0) as u32)..((cy + radius + 2.0).min(canvas.height as f64) as u32);
    let x_range = ((cx - radius - 1.0).max(0.0) as u32)..((cx + radius + 2.0).min(canvas.width as f64) as u32);
    for y in y_range {
        for x in x_range.clone() {
            let (dx, dy) = (x as f64 + 0.5 - cx, cy - (y as f64 + 0.5));
            let dist = dx.hypot(dy);
            // Fraction of the pixel inside the rim, for a smooth edge.
            let coverage = (radius + 0.5 - dist).clamp(0.0, 1.0);
            if coverage == 0.0 {
                continue;
            }
            let (d, a) = sector_at(n, (dist / radius).min(1.0), dy.atan2(dx).rem_euclid(TAU));
            canvas.blend(x as i64, y as i64, colour_of(d, a), coverage);
        }
    }
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

/// Rim outline, angle marks 0, π/2, π, 3π/2, and the vertex count under the colour bar.
fn draw_frame(canvas: &mut Canvas, layout: &Layout, n: usize) {
    let size = label_size(canvas.unit()) * 0.85;
    canvas.ring((layout.cx, layout.cy), layout.radius, 1.0, MUTED);
    let gap = 0.3 * size / layout.radius;
    for (k, name) in ["0", "π/2", "π", "3π/2"].iter().enumerate() {
        let theta = k as f64 * PI / 2.0;
        canvas.stroke(&[layout.pixel(1.0, theta), layout.pixel(1.0 + gap, theta)], 1.0, MUTED);
        canvas.text(name, layout.pixel(1.0 + 2.0 * gap, theta), size, MUTED, outward(theta));
    }
    let [left, _, _, bottom] = layout.bar;
    canvas.text(&format!("N = {n}"), (left as f64, bottom as f64 + 1.8 * size), size, MUTED, (HPos::Left, VPos::Center));
}

/// Outline, ticks and value labels of the colour bar: 0, ±s (the robust scale) and ±max.
fn draw_bar_ticks(canvas: &mut Canvas, layout: &Layout, scale: &Scale, (lo, hi): (f64, f64)) {
    let [left, top, right, bottom] = layout.bar.map(|v| v as f64);
    canvas.stroke(&[(left, top), (right, top), (right, bottom), (left, bottom), (left, top)], 1.0, MUTED);
    let size = label_size(canvas.unit()) * 0.85;
    let y_of = |t: f64| top + (hi - t) / (hi - lo) * (bottom - top);
    let mut ticks = vec![(hi, scale.max)];
    if lo < 0.0 {
        ticks.push((lo, -scale.max));
    }
    ticks.push((0.0, 0.0));
    for t in [scale.squash(scale.s), -scale.squash(scale.s)] {
        let clear = ticks.iter().all(|&(u, _)| (y_of(u) - y_of(t)).abs() > 1.3 * size);
        if clear && t >= lo && t <= hi {
            ticks.push((t, scale.unsquash(t)));
        }
    }
    for (t, value) in ticks {
        let y = y_of(t);
        canvas.stroke(&[(right, y), (right + 0.4 * size, y)], 1.0, INK);
        canvas.text(&format_value(value), (right + 0.6 * size, y), size, INK, (HPos::Left, VPos::Center));
    }
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

/// Every fitted fold curve of every step, and the fold points on the rim.
fn draw_folds(canvas: &mut Canvas, layout: &Layout, analysis: &Analysis, layers: usize) {
    let unit = canvas.unit();
    let width = line_width(unit, 0.005);
    let inner = 1.0 / layers.max(1) as f64;
    for curve in analysis.steps.iter().flat_map(|s| &s.detection.curves) {
        let points: Vec<(f64, f64)> = (0..=96)
            .map(|k| inner + (1.0 - inner) * k as f64 / 96.0)
            .map(|r| layout.pixel(r, curve.a0 + curve.a1 * r))
            .collect();
        // A white halo keeps the curve visible on dark and light cells alike.
        canvas.stroke(&points, width + 2.0, PAPER);
        canvas.stroke(&points, width, INK);
        canvas.ring(layout.pixel(1.0, curve.rim), 1.5 * width + 1.0, width, INK);
    }
    let marker = (unit * 0.014).max(3.0);
    let size = label_size(unit);
    for (k, fold) in analysis.folds.iter().enumerate() {
        for (e, &f) in fold.iter().enumerate() {
            let colour = fold_colour(k);
            canvas.disc(layout.pixel(1.0, f), marker + 1.5, PAPER);
            canvas.disc(layout.pixel(1.0, f), marker, colour);
            let at = layout.pixel(1.0 + 1.6 * marker / layout.radius, f);
            canvas.text(&endpoint_name(k, e, analysis.folds.len()), at, size, colour, outward(f));
        }
    }
    if analysis.folds.is_empty() {
        let [left, top, ..] = layout.bar;
        canvas.text("no fold", (left as f64, top as f64 - 1.2 * size), 0.85 * size, MUTED, (HPos::Left, VPos::Center));
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::{decode, folded_square, preview};
    use super::super::{disk_png, render_png, Picture};
    use super::*;
    use crate::disk::position;

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
        let analysis = folded_square(8, [std::f64::consts::FRAC_PI_4, 5.0 * std::f64::consts::FRAC_PI_4]);
        let disk = &analysis.disk(0).unwrap();
        let n = disk.n();
        let (w, h) = (400, 360);
        let (_, _, rgb) = decode(&disk_png(disk, "start", w, h).unwrap());
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
        let (_, _, rgb) = decode(&disk_png(&disk, "signs", 300, 300).unwrap());
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
        let (_, _, rgb) = decode(&disk_png(&zeros, "zeros", 120, 100).unwrap());
        let layout = Layout::of(120, 100);
        assert!(is_whiteish(sample(&rgb, 120, &layout, 0.5, 1.0)));
        let four = Disk::from_values(4, vec![1.0, -1.0, 0.5, 0.0, 2.0, f64::NAN]).unwrap();
        decode(&disk_png(&four, "", 64, 64).unwrap());
        let big: Vec<f64> = (0..1000 * 999 / 2).map(|k| ((k % 97) as f64 - 48.0) / 10.0).collect();
        let big = Disk::from_values(1000, big).unwrap();
        decode(&disk_png(&big, "N = 1000", 160, 160).unwrap());
    }

    #[test]
    fn diff_pictures_show_the_fold() {
        let analysis = folded_square(10, [0.3, 0.3 + std::f64::consts::PI]);
        for picture in Picture::ALL {
            let png = render_png(&analysis, picture, 1200, 900).unwrap();
            preview(&format!("large_{}.png", picture.name()), &png);
        }
        let big = folded_square(25, [1.0, 4.0]);
        preview("n100_disk_start.png", &render_png(&big, Picture::DiskStart, 480, 480).unwrap());
        preview("n100_diff.png", &render_png(&big, Picture::Diff, 480, 480).unwrap());
    }
}
