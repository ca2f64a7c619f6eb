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

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

use super::colour::{Ramp, Scale};
use super::{
    draw_title, endpoint_name, fold_colour, label_size, line_width, text_style, title_size, Area, Canvas, DrawResult,
    INK, MUTED,
};
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
        let radius = ((w - band - 2.0 * pad) / 2.0).min((h - top - 2.0 * pad) / 2.0).max(4.0);
        let cx = pad + radius + ((w - band - 2.0 * pad) / 2.0 - radius).max(0.0);
        let cy = top + pad + radius;
        let bar_left = (w - band + label) as i32;
        let bar = [bar_left, (cy - 0.75 * radius) as i32, bar_left + bar_width as i32, (cy + 0.75 * radius) as i32];
        Layout { cx, cy, radius, bar }
    }

    /// The pixel of polar point (r, θ) (not rounded).
    pub fn pixel(&self, r: f64, theta: f64) -> (f64, f64) {
        (self.cx + self.radius * r * theta.cos(), self.cy - self.radius * r * theta.sin())
    }

    /// [`Self::pixel`] rounded for plotters.
    fn at(&self, r: f64, theta: f64) -> (i32, i32) {
        let (x, y) = self.pixel(r, theta);
        (x.round() as i32, y.round() as i32)
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
    let unit = canvas.unit();
    canvas.draw(|area| {
        draw_title(area, unit, title)?;
        draw_frame(area, unit, &layout, disk.n())?;
        draw_bar_ticks(area, unit, &layout, &scale, t_range)?;
        match analysis {
            Some(analysis) => draw_folds(area, unit, &layout, analysis, disk.layers()),
            None => Ok(()),
        }
    })
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
            blend(canvas.pixel_mut(x, y), colour_of(d, a), coverage);
        }
    }
}

/// Mix `colour` into `pixel` with weight `alpha`.
fn blend(pixel: &mut [u8], colour: [u8; 3], alpha: f64) {
    for (p, c) in pixel.iter_mut().zip(colour) {
        *p = (*p as f64 * (1.0 - alpha) + c as f64 * alpha).round() as u8;
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

/// Rim outline and angle marks 0, π/2, π, 3π/2 (with the vertex count).
fn draw_frame(area: &Area, unit: f64, layout: &Layout, n: usize) -> DrawResult {
    let (cx, cy) = (layout.cx.round() as i32, layout.cy.round() as i32);
    area.draw(&Circle::new((cx, cy), layout.radius.round() as i32, MUTED.stroke_width(1)))?;
    let size = label_size(unit) * 0.85;
    let gap = 0.25 * size / layout.radius;
    for (k, name) in ["0", "π/2", "π", "3π/2"].iter().enumerate() {
        let theta = k as f64 * PI / 2.0;
        area.draw(&PathElement::new(vec![layout.at(1.0, theta), layout.at(1.0 + gap, theta)], MUTED.stroke_width(1)))?;
        let (h, v) = outward(theta);
        area.draw(&Text::new(name.to_string(), layout.at(1.0 + 2.0 * gap, theta), text_style(size, MUTED, h, v)))?;
    }
    let note = format!("N = {n}");
    let (_, height) = area.dim_in_pixel();
    area.draw(&Text::new(note, ((0.4 * size) as i32, height as i32 - (0.4 * size) as i32), text_style(size, MUTED, HPos::Left, VPos::Bottom)))
}

/// Text anchor that puts a label outside a circle at `theta`.
pub(crate) fn outward(theta: f64) -> (HPos, VPos) {
    let (c, s) = (theta.cos(), theta.sin());
    let h = if c > 0.38 { HPos::Left } else if c < -0.38 { HPos::Right } else { HPos::Center };
    let v = if s > 0.38 { VPos::Bottom } else if s < -0.38 { VPos::Top } else { VPos::Center };
    (h, v)
}

/// Outline, ticks and value labels of the colour bar: 0, ±s (the robust scale) and ±max.
fn draw_bar_ticks(area: &Area, unit: f64, layout: &Layout, scale: &Scale, (lo, hi): (f64, f64)) -> DrawResult {
    let [left, top, right, bottom] = layout.bar;
    area.draw(&Rectangle::new([(left, top), (right, bottom)], MUTED.stroke_width(1)))?;
    let size = label_size(unit) * 0.85;
    let y_of = |t: f64| top + ((hi - t) / (hi - lo) * (bottom - top) as f64).round() as i32;
    let mut ticks = vec![(hi, scale.max)];
    if lo < 0.0 {
        ticks.push((lo, -scale.max));
    }
    ticks.push((0.0, 0.0));
    for t in [scale.squash(scale.s), -scale.squash(scale.s)] {
        let clear = ticks.iter().all(|&(u, _)| (y_of(u) - y_of(t)).abs() as f64 > 1.3 * size);
        if clear && t >= lo && t <= hi {
            ticks.push((t, scale.unsquash(t)));
        }
    }
    for (t, value) in ticks {
        let y = y_of(t);
        area.draw(&PathElement::new(vec![(right, y), (right + (0.4 * size) as i32, y)], INK.stroke_width(1)))?;
        area.draw(&Text::new(format_value(value), (right + (0.6 * size) as i32, y), text_style(size, INK, HPos::Left, VPos::Center)))?;
    }
    Ok(())
}

/// A value with about three significant digits.
pub(crate) fn format_value(v: f64) -> String {
    let a = v.abs();
    match a {
        _ if a == 0.0 => "0".into(),
        _ if a >= 1000.0 || a < 1e-3 => format!("{v:.1e}"),
        _ if a >= 100.0 => format!("{v:.0}"),
        _ if a >= 10.0 => format!("{v:.1}"),
        _ if a >= 1.0 => format!("{v:.2}"),
        _ => format!("{v:.3}"),
    }
}

/// Every fitted fold curve of every step, and the fold points on the rim.
fn draw_folds(area: &Area, unit: f64, layout: &Layout, analysis: &Analysis, layers: usize) -> DrawResult {
    let width = line_width(unit, 0.006);
    let inner = 1.0 / layers.max(1) as f64;
    for curve in analysis.steps.iter().flat_map(|s| &s.detection.curves) {
        let points: Vec<(i32, i32)> = (0..=64)
            .map(|k| inner + (1.0 - inner) * k as f64 / 64.0)
            .map(|r| layout.at(r, curve.a0 + curve.a1 * r))
            .collect();
        // A white halo keeps the curve visible on dark and light cells alike.
        area.draw(&PathElement::new(points.clone(), WHITE.stroke_width(width + 2)))?;
        area.draw(&PathElement::new(points, INK.stroke_width(width)))?;
        area.draw(&Circle::new(layout.at(1.0, curve.rim), (2 * width + 1) as i32, INK.stroke_width(width)))?;
    }
    let marker = (unit * 0.014).max(3.0) as i32;
    let size = label_size(unit);
    for (k, fold) in analysis.folds.iter().enumerate() {
        for (e, &f) in fold.iter().enumerate() {
            let colour = fold_colour(k);
            area.draw(&Circle::new(layout.at(1.0, f), marker + 1, WHITE.filled()))?;
            area.draw(&Circle::new(layout.at(1.0, f), marker, colour.filled()))?;
            let (h, v) = outward(f);
            let text = endpoint_name(k, e, analysis.folds.len());
            area.draw(&Text::new(text, layout.at(1.0 + 1.3 * marker as f64 / layout.radius, f), text_style(size, colour, h, v)))?;
        }
    }
    if analysis.folds.is_empty() {
        let (w, h) = area.dim_in_pixel();
        let at = (w as i32 - (0.4 * size) as i32, h as i32 - (0.4 * size) as i32);
        area.draw(&Text::new("no fold detected", at, text_style(size * 0.85, MUTED, HPos::Right, VPos::Bottom)))?;
    }
    Ok(())
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
        let disk = &analysis.disk_start;
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
