//! Anti-aliased strokes and text straight into the canvas pixels.
//!
//! plotters 0.3.7 draws wide lines as unsmoothed polygons (ragged arcs) and its `ab_glyph`
//! text drops each glyph's side bearing (uneven letter spacing), so the pictures draw their
//! strokes and text here and keep plotters for charts and fills.
//! - A stroke of width w covers each pixel by clamp(w/2 + 1/2 − dist, 0, 1), dist being
//!   the distance from the pixel centre to the polyline; coverage is the maximum over the
//!   polyline's segments, so joints are not painted twice.
//! - Text is laid out with the font's advances and kerning and rasterised by `ab_glyph`.
//! - Parts drawn alike on many pictures (a disk's rim and ruler, for one size and N) can be
//!   drawn once on a recording canvas (`Canvas::record`) and replayed on each picture
//!   (`Canvas::replay`): the same blends in the same order give the same pixels, at the
//!   cost of the blends alone.
//!
//! ```
//! use close_render::raster::text_width;
//! assert!(text_width("wide text", 20.0) > text_width("text", 20.0));
//! ```

use std::sync::OnceLock;

use ab_glyph::{Font, FontRef, PxScale, ScaleFont};
use plotters::style::text_anchor::{HPos, VPos};

use super::{Canvas, FONT};

/// The embedded font, parsed once.
fn font() -> Option<&'static FontRef<'static>> {
    static PARSED: OnceLock<Option<FontRef<'static>>> = OnceLock::new();
    PARSED.get_or_init(|| FontRef::try_from_slice(FONT).ok()).as_ref()
}

/// Width in pixels of `text` at `size` pixels (0 when the font is unavailable).
pub fn text_width(text: &str, size: f64) -> f64 {
    font().map_or(0.0, |f| layout(f, text, size).1)
}

/// Glyph origins (x, char) of `text` and its total advance.
fn layout(font: &FontRef<'static>, text: &str, size: f64) -> (Vec<(f32, char)>, f64) {
    let scaled = font.as_scaled(PxScale::from(size as f32));
    let mut caret = 0.0f32;
    let mut prev = None;
    let mut glyphs = Vec::with_capacity(text.len());
    for c in text.chars() {
        let id = scaled.glyph_id(c);
        if let Some(p) = prev {
            caret += scaled.kern(p, id);
        }
        glyphs.push((caret, c));
        caret += scaled.h_advance(id);
        prev = Some(id);
    }
    (glyphs, caret as f64)
}

/// The blends strokes and text made on a recording canvas: (x, y, colour, weight in (0, 1]).
#[derive(Debug, Default, PartialEq)]
pub(crate) struct Recording(Vec<(u32, u32, [u8; 3], f64)>);

impl Recording {
    /// Bytes the recording holds.
    pub(crate) fn bytes(&self) -> usize {
        size_of_val(self.0.as_slice())
    }
}

/// `colour` over `pixel` with weight `alpha` (≤ 1).
pub(crate) fn mix(pixel: &mut [u8], colour: [u8; 3], alpha: f64) {
    for (p, c) in pixel.iter_mut().zip(colour) {
        *p = (*p as f64 * (1.0 - alpha) + c as f64 * alpha).round() as u8;
    }
}

impl Canvas {
    /// Blend `colour` into pixel (x, y) with weight `alpha`; pixels off the canvas are skipped.
    pub(crate) fn blend(&mut self, x: i64, y: i64, colour: [u8; 3], alpha: f64) {
        if x < 0 || y < 0 || x >= self.width as i64 || y >= self.height as i64 || alpha <= 0.0 {
            return;
        }
        let (x, y, alpha) = (x as u32, y as u32, alpha.min(1.0));
        match &mut self.recording {
            Some(Recording(blends)) => blends.push((x, y, colour, alpha)),
            None => mix(self.pixel_mut(x, y), colour, alpha),
        }
    }

    /// The blends `draw` makes with strokes and text on a `width`×`height` canvas (a
    /// canvas without pixels: `draw` must not touch them otherwise).
    pub(crate) fn record(width: u32, height: u32, draw: impl FnOnce(&mut Canvas)) -> Recording {
        let mut canvas = Canvas {
            width,
            height,
            rgb: Vec::new(),
            png_filter: png::FilterType::Sub,
            recording: Some(Recording::default()),
            vector: None,
            dpi: None,
        };
        draw(&mut canvas);
        canvas.recording.unwrap_or_default()
    }

    /// Make the blends of `recording` (recorded at this canvas's size) again, in order.
    pub(crate) fn replay(&mut self, recording: &Recording) {
        for &(x, y, colour, alpha) in &recording.0 {
            mix(self.pixel_mut(x, y), colour, alpha);
        }
    }

    /// An anti-aliased polyline through `points` (pixel coordinates), `width` pixels wide.
    pub(crate) fn stroke(&mut self, points: &[(f64, f64)], width: f64, colour: [u8; 3]) {
        if let Some(vector) = &mut self.vector {
            return vector.stroke(points, width, colour);
        }
        let Some(&first) = points.first() else { return };
        let half = width / 2.0;
        let reach = half + 1.0;
        let (mut x0, mut y0, mut x1, mut y1) = (first.0, first.1, first.0, first.1);
        for &(x, y) in points {
            (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
        }
        let clip = |v: f64, hi: u32| (v.floor().max(0.0) as i64).min(hi as i64);
        let (bx0, by0) = (clip(x0 - reach, self.width), clip(y0 - reach, self.height));
        let (bx1, by1) = (clip(x1 + reach + 1.0, self.width), clip(y1 + reach + 1.0, self.height));
        if bx1 <= bx0 || by1 <= by0 {
            return;
        }
        let stride = (bx1 - bx0) as usize;
        let mut coverage = vec![0.0f64; stride * (by1 - by0) as usize];
        // The pixels some segment reaches, each once: a ring reaches a few thousand of the
        // hundred thousand in its bounding box, so only these are blended.
        let mut reached = Vec::new();
        let segments = points
            .windows(2)
            .map(|w| (w[0], w[1]))
            .chain((points.len() == 1).then_some((first, first)));
        for (a, b) in segments {
            let sx0 = clip(a.0.min(b.0) - reach, self.width).max(bx0);
            let sx1 = clip(a.0.max(b.0) + reach + 1.0, self.width).min(bx1);
            let sy0 = clip(a.1.min(b.1) - reach, self.height).max(by0);
            let sy1 = clip(a.1.max(b.1) + reach + 1.0, self.height).min(by1);
            for y in sy0..sy1 {
                for x in sx0..sx1 {
                    let c = (half + 0.5
                        - distance_to_segment((x as f64 + 0.5, y as f64 + 0.5), a, b))
                    .clamp(0.0, 1.0);
                    let k = (y - by0) as usize * stride + (x - bx0) as usize;
                    if c > coverage[k] {
                        if coverage[k] == 0.0 {
                            reached.push(k);
                        }
                        coverage[k] = c;
                    }
                }
            }
        }
        for k in reached {
            self.blend(bx0 + (k % stride) as i64, by0 + (k / stride) as i64, colour, coverage[k]);
        }
    }

    /// A filled anti-aliased disc.
    pub(crate) fn disc(&mut self, centre: (f64, f64), radius: f64, colour: [u8; 3]) {
        self.stroke(&[centre], 2.0 * radius, colour);
    }

    /// A circle outline.
    pub(crate) fn ring(&mut self, centre: (f64, f64), radius: f64, width: f64, colour: [u8; 3]) {
        let steps = (radius * 0.8).clamp(24.0, 720.0) as usize;
        let points: Vec<(f64, f64)> = (0..=steps)
            .map(|k| std::f64::consts::TAU * k as f64 / steps as f64)
            .map(|t| (centre.0 + radius * t.cos(), centre.1 - radius * t.sin()))
            .collect();
        self.stroke(&points, width, colour);
    }

    /// `text` of `size` pixels anchored at `at` by (`h`, `v`); `VPos::Center` centres the
    /// capital height, which is what looks centred. Text lies on the paper: `colour` is
    /// darkened as far as AA contrast needs ([`super::readable`]).
    pub(crate) fn text(
        &mut self,
        text: &str,
        at: (f64, f64),
        size: f64,
        colour: [u8; 3],
        (h, v): (HPos, VPos),
    ) {
        let Some(font) = font() else { return };
        let colour = super::readable(colour);
        let scaled = font.as_scaled(PxScale::from(size as f32));
        let (glyphs, width) = layout(font, text, size);
        let (ascent, descent) = (scaled.ascent() as f64, scaled.descent() as f64);
        let left = at.0
            - match h {
                HPos::Left => 0.0,
                HPos::Center => width / 2.0,
                HPos::Right => width,
            };
        // DejaVu Sans: cap height 0.73 em, ascent − descent 1.16 em.
        let cap = 0.63 * (ascent - descent);
        let baseline = at.1
            + match v {
                VPos::Top => ascent,
                VPos::Center => cap / 2.0,
                VPos::Bottom => descent,
            };
        if let Some(vector) = &mut self.vector {
            return vector.text(text, (left, baseline), size, width, colour);
        }
        for (x, c) in glyphs {
            let glyph = scaled.scaled_glyph(c);
            let glyph = ab_glyph::Glyph {
                position: ab_glyph::point(left as f32 + x, baseline as f32),
                ..glyph
            };
            if let Some(outline) = scaled.outline_glyph(glyph) {
                let bounds = outline.px_bounds();
                let mut ink = Vec::new();
                outline.draw(|gx, gy, c| ink.push((gx, gy, c)));
                for (gx, gy, c) in ink {
                    self.blend(
                        bounds.min.x as i64 + gx as i64,
                        bounds.min.y as i64 + gy as i64,
                        colour,
                        c as f64,
                    );
                }
            }
        }
    }
}

/// Distance from `p` to the segment `a`–`b`.
fn distance_to_segment(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p.0 - a.0 - t * dx).hypot(p.1 - a.1 - t * dy)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pixel(canvas: &mut Canvas, x: u32, y: u32) -> [u8; 3] {
        let p = canvas.pixel_mut(x, y);
        [p[0], p[1], p[2]]
    }

    #[test]
    fn strokes_cover_their_width_and_nothing_else() {
        let mut canvas = Canvas::new(100, 100).unwrap();
        canvas.stroke(&[(10.0, 50.0), (90.0, 50.0)], 6.0, [0, 0, 0]);
        assert_eq!(pixel(&mut canvas, 50, 49), [0, 0, 0]);
        assert_eq!(pixel(&mut canvas, 50, 52), [0, 0, 0]);
        assert_eq!(pixel(&mut canvas, 50, 55), [255, 255, 255]);
        // A stroke leaving the canvas is clipped, not a panic.
        canvas.stroke(&[(-50.0, -50.0), (500.0, 20.0)], 3.0, [0, 0, 0]);
        canvas.disc((99.0, 99.0), 10.0, [255, 0, 0]);
        assert_eq!(pixel(&mut canvas, 95, 95), [255, 0, 0]);
    }

    #[test]
    fn a_replayed_recording_gives_the_pixels_drawn() {
        let guides = |canvas: &mut Canvas| {
            canvas.ring((50.0, 40.0), 30.0, 1.5, [90, 90, 90]);
            canvas.stroke(&[(0.0, 0.0), (99.0, 79.0), (99.0, 0.0)], 2.0, [200, 0, 0]);
            canvas.text("π/2", (50.0, 40.0), 14.0, [0, 0, 0], (HPos::Center, VPos::Center));
        };
        let under = |canvas: &mut Canvas| {
            for y in 0..80 {
                for x in 0..100 {
                    canvas.pixel_mut(x, y).copy_from_slice(&[(x * 2) as u8, (y * 3) as u8, 128]);
                }
            }
        };
        let (mut drawn, mut replayed) =
            (Canvas::new(100, 80).unwrap(), Canvas::new(100, 80).unwrap());
        under(&mut drawn);
        guides(&mut drawn);
        under(&mut replayed);
        let recording = Canvas::record(100, 80, guides);
        assert!(recording.bytes() > 0);
        replayed.replay(&recording);
        assert!(drawn.rgb == replayed.rgb, "replaying differs from drawing");
    }

    #[test]
    fn text_leaves_ink_where_anchored() {
        let mut canvas = Canvas::new(200, 60).unwrap();
        canvas.text("Hello", (100.0, 30.0), 20.0, [0, 0, 0], (HPos::Center, VPos::Center));
        let inked: Vec<(u32, u32)> = (0..60)
            .flat_map(|y| (0..200).map(move |x| (x, y)))
            .filter(|&(x, y)| pixel(&mut canvas, x, y)[0] < 128)
            .collect();
        let (xs, ys): (Vec<u32>, Vec<u32>) = inked.into_iter().unzip();
        let mid = |v: &[u32]| (v.iter().min().unwrap() + v.iter().max().unwrap()) as f64 / 2.0;
        assert!(
            (mid(&xs) - 100.0).abs() < 3.0 && (mid(&ys) - 30.0).abs() < 3.0,
            "{} {}",
            mid(&xs),
            mid(&ys)
        );
    }
}
