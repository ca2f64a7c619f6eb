//! What a viewer needs to read values off the pictures: which cell each pixel of a disk
//! picture shows, how the border plot maps data to pixels, and the values of the disks a
//! picture draws.
//!
//! The web app shows the server's pictures and computes no geometry of its own. Which cell
//! is under the pointer it reads off a *cell picture* ([`cell_picture`]): a PNG of the disk
//! picture's size whose pixel holds, as a 24-bit number (red · 2¹⁶ + green · 2⁸ + blue),
//! 1 + the index of the cell the disk picture paints there (0 off the disk), found by the
//! painter's own rule ([`super::disk_picture::sector_at`]). The values come ring by ring
//! ([`rings`]): index (d − 1)·N + a holds the pair of edges (a, a + d mod N), d = 1 at the
//! rim … L = ⌊N/2⌋ at the centre, so a cell's edges, its pair distance and its neighbours
//! follow from its index. To mark a cell's two edges on the border plot a viewer needs that
//! plot's data → pixel map, which plotters works out while it lays out the axes: it is
//! taken from a drawing of the plot at the same size. The values are those of the two
//! frames a step's pictures compare; the diffs follow from them as the pictures compute
//! them (| |end| − |start| | and end − start). Values are sent as `f32`: seven significant
//! digits, more than a readout shows, in half the JSON. A readout of more than
//! [`MAX_VALUES`] values is refused: past N ≈ 1000 a cell is narrower than a pixel of any
//! picture served, and the JSON would weigh tens of megabytes.

use serde::Serialize;

use std::f64::consts::TAU;

use super::disk_picture::{sector_at, Layout};
use super::truth::Truth;
use super::{borders, Canvas, StepSpan, MAX_SIZE, MIN_SIZE};
use crate::error::{Error, Result};
use close_core::analysis::Analysis;
use close_core::border::to_xyz;
use close_core::disk::Disk;

/// Most disk values one readout sends (about 10 MB of JSON): two disks of N = 1000.
pub const MAX_VALUES: usize = 1_000_000;

/// Refuse `disks` disks of `n` edges over [`MAX_VALUES`] (counted ring by ring: N·⌊N/2⌋ each).
pub fn within_limit(disks: usize, n: usize) -> Result<()> {
    let values = disks.saturating_mul(n).saturating_mul(n / 2);
    if values > MAX_VALUES {
        return Err(
            close_core::Error::too_large("disk values in a readout", values, MAX_VALUES).into()
        );
    }
    Ok(())
}

/// Where the disk lies on a square disk picture, in its pixels (y grows downwards): the
/// point (r, θ) of the disk is at (cx + radius·r·cos θ, cy − radius·r·sin θ).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DiskGeometry {
    pub cx: f64,
    pub cy: f64,
    /// Pixel radius of the rim (r = 1).
    pub radius: f64,
}

impl DiskGeometry {
    /// The geometry of a `size`×`size` disk picture (the size clamped as pictures are).
    pub fn of(size: u32) -> DiskGeometry {
        let size = size.clamp(MIN_SIZE, MAX_SIZE);
        let layout = Layout::of(size, size);
        DiskGeometry { cx: layout.cx, cy: layout.cy, radius: layout.radius }
    }
}

/// The border plot's map from data (x, y) to its pixels: pixel x = `x[0]·x + x[1]`, pixel
/// y = `y[0]·y + y[1]` (`y[0] < 0`: pixels grow downwards).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PlotTransform {
    pub x: [f64; 2],
    pub y: [f64; 2],
}

impl PlotTransform {
    /// The map of the border plot of `analysis` over `step` drawn `size`×`size` (clamped as
    /// pictures are), with the `truth` folds it draws (they take legend rows, so they move
    /// the plot).
    pub fn of_borders(
        analysis: &Analysis,
        truth: &Truth,
        step: Option<usize>,
        size: u32,
    ) -> Result<PlotTransform> {
        let mut canvas = Canvas::new(size, size)?;
        let (x, y) = borders::draw(&mut canvas, analysis, truth, step)?.affine();
        Ok(PlotTransform { x, y })
    }
}

/// The values of the disk pictures of one span of an analysis and where to read them.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Readout {
    /// Border vertex (and edge) count: edge i joins vertex i to vertex i + 1 (mod N).
    pub n: usize,
    /// The pictures' side in pixels, as drawn.
    pub size: u32,
    /// The frames compared (sample frame numbers): the start and end disks' frames.
    pub from_frame: usize,
    pub to_frame: usize,
    pub disk: DiskGeometry,
    /// The map of the border plot of the same span.
    pub borders: PlotTransform,
    /// The span's first and last borders (input coordinates, border order), which that plot
    /// draws and a disk cell's edges are marked on.
    pub border_frames: [Vec<[f64; 3]>; 2],
    /// The start disk's values, ring by ring ([`rings`]).
    pub start: Vec<f32>,
    /// The end disk's.
    pub end: Vec<f32>,
}

/// The readout of the disk pictures of `analysis` for `step` (1-based; `None`: the whole
/// analysis, as [`super::View`] takes it) drawn `size`×`size`, its border plot
/// drawn with the `truth` folds.
pub fn readout(
    analysis: &Analysis,
    truth: &Truth,
    step: Option<usize>,
    size: u32,
) -> Result<Readout> {
    let span = StepSpan::of(analysis, step)?;
    within_limit(2, analysis.n)?;
    let disk_of = |k: usize| {
        analysis.disk(k).ok_or_else(|| Error::Render(format!("analysed frame {k} does not exist")))
    };
    let (start, end) = (disk_of(span.from)?, disk_of(span.to)?);
    Ok(Readout {
        n: start.n(),
        size: size.clamp(MIN_SIZE, MAX_SIZE),
        from_frame: analysis.start_frame + span.from,
        to_frame: analysis.start_frame + span.to,
        disk: DiskGeometry::of(size),
        borders: PlotTransform::of_borders(analysis, truth, step, size)?,
        border_frames: [span.from, span.to]
            .map(|k| analysis.frames[k].iter().map(to_xyz).collect()),
        start: rings(&start),
        end: rings(&end),
    })
}

/// One disk picture's values and where its disk lies (a picture of one border state).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DiskCells {
    pub n: usize,
    pub size: u32,
    pub disk: DiskGeometry,
    /// The values, ring by ring ([`rings`]).
    pub values: Vec<f32>,
}

impl DiskCells {
    /// The cells of `disk` drawn `size`×`size`; refused over [`MAX_VALUES`].
    pub fn of(disk: &Disk, size: u32) -> Result<DiskCells> {
        within_limit(1, disk.n())?;
        Ok(DiskCells {
            n: disk.n(),
            size: size.clamp(MIN_SIZE, MAX_SIZE),
            disk: DiskGeometry::of(size),
            values: rings(disk),
        })
    }
}

/// The values of `disk` ring by ring, as `f32`: index (d − 1)·N + a holds the pair
/// (a, a + d mod N), d = 1 … ⌊N/2⌋, a = 0 … N − 1 (for even N the pairs of the innermost
/// ring come twice, at a and a + N/2, as the picture paints them).
///
/// ```
/// use close_core::disk::Disk;
/// use close_render::readout::rings;
/// let disk = Disk::from_values(4, vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0]).unwrap();
/// // Ring 1: pairs (0,1) (1,2) (2,3) (3,0); ring 2: (0,2) (1,3) (2,0) (3,1).
/// assert_eq!(rings(&disk), [1.0, 4.0, 6.0, 3.0, 2.0, 5.0, 2.0, 5.0]);
/// ```
pub fn rings(disk: &Disk) -> Vec<f32> {
    let n = disk.n();
    (1..=n / 2).flat_map(|d| (0..n).map(move |a| disk.get(a, (a + d) % n) as f32)).collect()
}

/// The cell picture of a `size`×`size` disk picture (clamped as pictures are) of N = `n`:
/// an RGB PNG whose pixel is 1 + the [`rings`] index of the cell the picture paints there
/// (rim pixels, partly painted, included), 0 off the disk.
pub fn cell_picture(n: usize, size: u32) -> Result<Vec<u8>> {
    if !(close_core::border::MIN_VERTICES..=close_core::border::MAX_VERTICES).contains(&n) {
        return Err(Error::invalid(format!(
            "a disk has {} to {} edges, not {n}",
            close_core::border::MIN_VERTICES,
            close_core::border::MAX_VERTICES
        )));
    }
    let mut canvas = Canvas::new(size, size)?;
    let layout = Layout::of(canvas.width, canvas.height);
    let width = canvas.width as usize;
    canvas.rgb.fill(0);
    for (k, pixel) in canvas.rgb.chunks_exact_mut(3).enumerate() {
        let (x, y) = ((k % width) as f64 + 0.5, (k / width) as f64 + 0.5);
        let (dx, dy) = (x - layout.cx, layout.cy - y);
        let dist = dx.hypot(dy);
        // Painted pixels only: the rim's coverage rule of the disk picture.
        if layout.radius + 0.5 - dist <= 0.0 {
            continue;
        }
        let (d, a) = sector_at(n, (dist / layout.radius).min(1.0), dy.atan2(dx).rem_euclid(TAU));
        let code = ((d - 1) * n + a + 1) as u32;
        pixel.copy_from_slice(&code.to_be_bytes()[1..]);
    }
    // Runs of one cell along a row: the Sub filter makes them zeros.
    canvas.png_filter = png::FilterType::Sub;
    canvas.png()
}

#[cfg(test)]
mod tests {
    use super::super::colour::{Ramp, Scale};
    use super::super::tests::{decode, disk_png, folded_square, png};
    use super::super::Picture;
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn the_values_are_the_step_disks_ring_by_ring() {
        let analysis = folded_square(8, [PI / 4.0, 5.0 * PI / 4.0]);
        let readout = readout(&analysis, &Truth::default(), Some(1), 400).unwrap();
        let (start, end) = (analysis.disk(0).unwrap(), analysis.disk(1).unwrap());
        assert_eq!((readout.n, readout.from_frame, readout.to_frame), (32, 0, 1));
        let n = readout.n;
        assert_eq!(readout.start.len(), n * (n / 2));
        for d in 1..=n / 2 {
            for a in 0..n {
                let k = (d - 1) * n + a;
                for (got, disk) in [(readout.start[k], &start), (readout.end[k], &end)] {
                    let want = disk.get(a, (a + d) % n);
                    assert!((got as f64 - want).abs() <= 1e-6 * want.abs().max(1e-3), "({d}, {a})");
                }
            }
        }
    }

    #[test]
    fn the_cell_picture_names_the_cell_each_pixel_is_painted_with() {
        for (n, size) in [(32, 400), (13, 300), (200, 480)] {
            // Every pair of its own value: a pixel's colour names its cell.
            let disk =
                Disk::from_values(n, (0..n * (n - 1) / 2).map(|k| k as f64).collect()).unwrap();
            let scale = Scale::of(disk.values());
            let (_, _, painted) = decode(&disk_png(&disk, "", (size, size)));
            let (_, _, cells) = decode(&cell_picture(n, size).unwrap());
            let values = rings(&disk);
            let layout = Layout::of(size, size);
            let (mut inside, mut off) = (0, 0);
            for (k, (cell, colour)) in cells.chunks(3).zip(painted.chunks(3)).enumerate() {
                let code = u32::from_be_bytes([0, cell[0], cell[1], cell[2]]) as usize;
                let (x, y) = ((k % size as usize) as f64 + 0.5, (k / size as usize) as f64 + 0.5);
                let dist = (x - layout.cx).hypot(y - layout.cy);
                if dist > layout.radius + 0.5 {
                    assert_eq!(code, 0, "({x}, {y}) off the disk, N = {n}");
                    off += 1;
                    continue;
                }
                assert!(code >= 1 && code <= values.len(), "({x}, {y}): {code}");
                // Inside the rim's anti-aliasing, the colour is the cell's value's.
                if dist < layout.radius - 1.5 {
                    let want = Ramp::Diverging.colour(scale.squash(values[code - 1] as f64));
                    assert_eq!(colour, want, "({x}, {y}), N = {n}, cell {}", code - 1);
                    inside += 1;
                }
            }
            assert!(inside > 1000 && off > 1000, "N = {n}: {inside} inside, {off} off");
        }
        assert!(cell_picture(3, 100).is_err() && cell_picture(5001, 100).is_err());
    }

    #[test]
    fn the_border_transform_puts_vertex_0_on_its_mark() {
        let analysis = folded_square(8, [PI / 4.0, 5.0 * PI / 4.0]);
        let size = 360;
        let t = PlotTransform::of_borders(&analysis, &Truth::default(), None, size).unwrap();
        let (_, _, rgb) = decode(&png(&analysis, Picture::Borders, None, (size, size)).unwrap());
        let p = analysis.start_border()[0];
        let (x, y) = (t.x[0] * p.x + t.x[1], t.y[0] * p.y + t.y[1]);
        assert!(
            t.y[0] < 0.0 && (0.0..size as f64).contains(&x) && (0.0..size as f64).contains(&y),
            "({x}, {y})"
        );
        // Vertex 0 carries a filled disc: ink, not paper.
        let pixel = &rgb[(y as usize * size as usize + x as usize) * 3..][..3];
        assert!(pixel.iter().any(|&c| c < 200), "vertex 0 at ({x}, {y}) is {pixel:?}");
    }

    #[test]
    fn too_many_values_are_refused_before_any_is_written() {
        assert!(within_limit(2, 1000).is_ok());
        assert!(matches!(
            within_limit(2, 1001),
            Err(Error::Core(close_core::Error::TooLarge { got: Some(1_001_000), .. }))
        ));
        assert!(within_limit(1, 1414).is_ok());
    }

    #[test]
    fn a_step_that_does_not_exist_is_refused() {
        let analysis = folded_square(4, [0.0, PI]);
        assert!(matches!(
            readout(&analysis, &Truth::default(), Some(2), 200),
            Err(Error::Core(close_core::Error::InvalidArgument(_)))
        ));
    }
}
