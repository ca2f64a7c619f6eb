//! Which cell of an N-edge dGLI disk each pixel of a canvas shows.
//!
//! The disk is painted by inverse mapping (see [`super::disk`]): a pixel's polar coordinates
//! give its (ring, sector) through [`sector_at`]. That costs a `hypot`, an `atan2` and a few
//! roundings per pixel, and profiling `POST /api/disk` (480 px, N = 76) put about 80 % of a
//! picture's time there. Which cell a pixel shows, and how much of the pixel lies inside the
//! rim, depend on the canvas size and N alone, not on the values: a [`SectorMap`] records
//! them once (the disk pictures keep it per size and N), so painting is one table read and
//! one copy per pixel. A 480 px map weighs about 0.35 MB, a 2048 px one about 6.5 MB.

use std::f64::consts::{PI, TAU};

use super::Canvas;
use close_core::disk::condensed_index;

/// The (ring d, first edge a) of the sector holding polar point (r ≤ 1, θ) on an N-edge disk.
pub fn sector_at(n: usize, r: f64, theta: f64) -> (usize, usize) {
    let l = n / 2;
    // Ring d spans ((L − d)/L, (L − d + 1)/L]; the centre belongs to the innermost ring.
    let d = (l + 1).saturating_sub((r * l as f64).ceil() as usize).clamp(1, l);
    // θ = π(2a + d + 1)/N, sectors one edge wide around it.
    let a = ((theta * n as f64 / PI - d as f64 - 1.0) / 2.0).round();
    (d, a.rem_euclid(n as f64) as usize % n)
}

/// The cell of every disk pixel of a `width`×`height` canvas, the disk centred at pixel
/// point (cx, cy) with rim radius `radius` (as [`super::disk_picture::Layout`] places it), for N
/// edges.
#[derive(Debug, PartialEq)]
pub(crate) struct SectorMap {
    /// Runs of consecutive pixels wholly inside the rim: (index of the first pixel, row-major,
    /// and the run's length).
    runs: Vec<(u32, u32)>,
    /// Condensed index ([`condensed_index`]) of the cell of each pixel of `runs`, in order.
    cells: Vec<u32>,
    /// Pixels the rim crosses.
    rim: Vec<RimPixel>,
}

/// A pixel partly inside the rim.
#[derive(Debug, PartialEq)]
struct RimPixel {
    x: u32,
    y: u32,
    cell: u32,
    /// Fraction of the pixel inside the rim, in (0, 1).
    coverage: f64,
}

impl SectorMap {
    /// Classify every pixel of the disk's bounding box by [`sector_at`]; the rim covers a
    /// pixel by clamp(radius + 1/2 − distance of its centre, 0, 1), a smooth edge.
    pub(crate) fn new(
        width: u32,
        height: u32,
        (cx, cy): (f64, f64),
        radius: f64,
        n: usize,
    ) -> SectorMap {
        let mut map = SectorMap { runs: Vec::new(), cells: Vec::new(), rim: Vec::new() };
        let y_range =
            ((cy - radius - 1.0).max(0.0) as u32)..((cy + radius + 2.0).min(height as f64) as u32);
        let x_range =
            ((cx - radius - 1.0).max(0.0) as u32)..((cx + radius + 2.0).min(width as f64) as u32);
        for y in y_range {
            for x in x_range.clone() {
                let (dx, dy) = (x as f64 + 0.5 - cx, cy - (y as f64 + 0.5));
                let dist = dx.hypot(dy);
                let coverage = (radius + 0.5 - dist).clamp(0.0, 1.0);
                if coverage == 0.0 {
                    continue;
                }
                let (d, a) = sector_at(n, (dist / radius).min(1.0), dy.atan2(dx).rem_euclid(TAU));
                let (i, j) = (a, (a + d) % n);
                // N² / 2 cells fit in u32 for any N whose values fit in memory.
                let cell = condensed_index(n, i.min(j), i.max(j)) as u32;
                if coverage < 1.0 {
                    map.rim.push(RimPixel { x, y, cell, coverage });
                    continue;
                }
                let pixel = y * width + x;
                match map.runs.last_mut() {
                    Some((start, len)) if *start + *len == pixel => *len += 1,
                    _ => map.runs.push((pixel, 1)),
                }
                map.cells.push(cell);
            }
        }
        map
    }

    /// Bytes the map holds.
    pub(crate) fn bytes(&self) -> usize {
        size_of_val(self.runs.as_slice())
            + size_of_val(self.cells.as_slice())
            + size_of_val(self.rim.as_slice())
    }

    /// Paint each disk pixel of `canvas` (white, of the map's size) with its cell's colour,
    /// `colours` being indexed like the disk's values.
    pub(crate) fn paint(&self, canvas: &mut Canvas, colours: &[[u8; 3]]) {
        let mut cells = self.cells.as_slice();
        for &(start, len) in &self.runs {
            let (start, len) = (start as usize, len as usize);
            let (run, rest) = cells.split_at(len);
            for (pixel, &cell) in
                canvas.rgb[3 * start..3 * (start + len)].chunks_exact_mut(3).zip(run)
            {
                pixel.copy_from_slice(&colours[cell as usize]);
            }
            cells = rest;
        }
        for p in &self.rim {
            canvas.blend(p.x as i64, p.y as i64, colours[p.cell as usize], p.coverage);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every pixel of the map: (x, y, cell, coverage).
    fn pixels(map: &SectorMap, width: u32) -> Vec<(u32, u32, u32, f64)> {
        let mut cells = map.cells.iter();
        let inside = map.runs.iter().flat_map(|&(start, len)| start..start + len);
        let mut all: Vec<_> =
            inside.map(|p| (p % width, p / width, *cells.next().unwrap(), 1.0)).collect();
        assert!(cells.next().is_none(), "one cell per pixel of the runs");
        all.extend(map.rim.iter().map(|p| (p.x, p.y, p.cell, p.coverage)));
        all
    }

    #[test]
    fn the_map_agrees_with_sector_at_on_every_pixel() {
        // Disks inside their canvas, and one whose rim runs off it.
        for (width, height, (cx, cy), radius, n) in [
            (120, 100, (52.5, 55.0), 40.0, 8),
            (100, 140, (50.0, 61.3), 33.7, 13),
            (64, 64, (30.0, 34.0), 20.0, 4),
            (90, 90, (45.0, 45.0), 50.0, 1000),
        ] {
            let map = SectorMap::new(width, height, (cx, cy), radius, n);
            let mut seen = vec![false; (width * height) as usize];
            for (x, y, cell, coverage) in pixels(&map, width) {
                assert!(
                    !std::mem::replace(&mut seen[(y * width + x) as usize], true),
                    "pixel ({x}, {y}) twice"
                );
                let (dx, dy) = (x as f64 + 0.5 - cx, cy - (y as f64 + 0.5));
                let dist = dx.hypot(dy);
                let (d, a) = sector_at(n, (dist / radius).min(1.0), dy.atan2(dx).rem_euclid(TAU));
                let pair = (a.min((a + d) % n), a.max((a + d) % n));
                assert_eq!(
                    cell as usize,
                    condensed_index(n, pair.0, pair.1),
                    "({x}, {y}), N = {n}"
                );
                assert!(coverage > 0.0);
                assert_eq!(coverage, (radius + 0.5 - dist).min(1.0), "({x}, {y})");
            }
            // The pixels left out lie outside the rim.
            for (k, _) in seen.iter().enumerate().filter(|(_, &s)| !s) {
                let (x, y) = (k as f64 % width as f64 + 0.5, (k / width as usize) as f64 + 0.5);
                assert!((x - cx).hypot(y - cy) >= radius + 0.5, "({x}, {y}) left out");
            }
        }
    }
}
