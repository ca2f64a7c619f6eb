//! What a viewer needs to read values off the pictures: where the disk lies on a disk
//! picture, how the border plot maps data to pixels, and the values of the disks a picture
//! draws.
//!
//! The web app shows the server's PNGs. To say which cell is under the pointer it needs the
//! disk's centre and rim radius in the picture's pixels ([`super::disk_picture::Layout`]); the cell
//! of a point then follows from its polar coordinates ([`super::disk_picture::sector_at`]: ring d
//! from the radius, first edge a from the angle). To mark a cell's two edges on the border
//! plot it needs that plot's data → pixel map, which plotters works out while it lays out
//! the axes: it is taken from a drawing of the plot at the same size. The values are the
//! condensed pair vectors (pairs (i, j), i < j, row-major, [`close_core::disk::condensed_index`])
//! of the two frames a step's pictures compare; the diffs follow from them as the pictures
//! compute them (| |end| − |start| | and end − start). Values are sent as `f32`: seven
//! significant digits, more than a readout shows, in half the JSON.
//! A readout of more than [`MAX_VALUES`] values is refused: past N ≈ 1000 a cell is
//! narrower than a pixel of any picture served, and the JSON would weigh tens of megabytes.

use serde::Serialize;

use super::disk_picture::Layout;
use super::{borders, Canvas, StepSpan, MAX_SIZE, MIN_SIZE};
use close_core::analysis::Analysis;
use close_core::disk::Disk;
use close_core::error::{Error, Result};
use close_core::geometry::Fold;

/// Most disk values one readout sends (about 10 MB of JSON): two disks of N = 1000.
pub const MAX_VALUES: usize = 1_000_000;

/// Refuse `disks` disks of `n` edges over [`MAX_VALUES`].
pub fn within_limit(disks: usize, n: usize) -> Result<()> {
    let values = disks * n * n.saturating_sub(1) / 2;
    if values > MAX_VALUES {
        return Err(Error::too_large("disk values in a readout", values, MAX_VALUES));
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

/// The border plot's map from data (x, y) to its pixels: pixel x = x[0]·x + x[1], pixel
/// y = y[0]·y + y[1] (y[0] < 0: pixels grow downwards).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PlotTransform {
    pub x: [f64; 2],
    pub y: [f64; 2],
}

impl PlotTransform {
    /// The map of the border plot of `analysis` drawn `size`×`size` (clamped as pictures are),
    /// with the `truth` folds it draws (they take legend rows, so they move the plot).
    pub fn of_borders(analysis: &Analysis, truth: &[Fold], size: u32) -> Result<PlotTransform> {
        let mut canvas = Canvas::new(size, size)?;
        let (x, y) = borders::draw(&mut canvas, analysis, truth)?.affine();
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
    /// The border plot's map (the plot shows the whole analysis, whatever the span).
    pub borders: PlotTransform,
    /// The start disk's condensed pair vector.
    pub start: Vec<f32>,
    /// The end disk's.
    pub end: Vec<f32>,
}

/// The readout of the disk pictures of `analysis` for `step` (1-based; `None`: the whole
/// analysis, as [`super::render_step`] takes it) drawn `size`×`size`, its border plot
/// drawn with the `truth` folds.
pub fn readout(
    analysis: &Analysis,
    truth: &[Fold],
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
        borders: PlotTransform::of_borders(analysis, truth, size)?,
        start: single(&start),
        end: single(&end),
    })
}

/// One disk picture's values and where its disk lies (a picture of one border state).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DiskCells {
    pub n: usize,
    pub size: u32,
    pub disk: DiskGeometry,
    /// The condensed pair vector.
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
            values: single(disk),
        })
    }
}

/// The values of `disk` as `f32` (see the module doc).
fn single(disk: &Disk) -> Vec<f32> {
    disk.values().iter().map(|&v| v as f32).collect()
}

#[cfg(test)]
mod tests {
    use super::super::colour::{Ramp, Scale};
    use super::super::tests::{decode, folded_square};
    use super::super::{render_png, render_step_png, Picture};
    use super::*;
    use close_core::disk::{condensed_index, position};
    use std::f64::consts::PI;

    #[test]
    fn the_values_are_the_step_disks_and_each_cell_is_where_the_picture_paints_it() {
        let analysis = folded_square(8, [PI / 4.0, 5.0 * PI / 4.0]);
        let size = 400;
        let readout = readout(&analysis, &[], Some(1), size).unwrap();
        let (start, end) = (analysis.disk(0).unwrap(), analysis.disk(1).unwrap());
        assert_eq!((readout.n, readout.from_frame, readout.to_frame), (32, 0, 1));
        let close = |a: &[f32], b: &[f64]| {
            a.len() == b.len()
                && a.iter().zip(b).all(|(&x, &y)| (x as f64 - y).abs() <= 1e-6 * y.abs().max(1e-3))
        };
        assert!(close(&readout.start, start.values()) && close(&readout.end, end.values()));
        // The signed diff's picture paints the cell of the largest |Δ| in that value's colour
        // at the point the geometry gives for the middle of that cell.
        let n = readout.n;
        let (mut best, mut at) = (0.0, (0, 1));
        for i in 0..n {
            for j in i + 1..n {
                let delta = (end.get(i, j) - start.get(i, j)).abs();
                if delta > best {
                    (best, at) = (delta, (i, j));
                }
            }
        }
        let cell = position(n, at.0, at.1);
        let r = cell.radius - 0.5 / (n / 2) as f64;
        let g = readout.disk;
        let (x, y) =
            (g.cx + g.radius * r * cell.angle.cos(), g.cy - g.radius * r * cell.angle.sin());
        let (_, _, rgb) =
            decode(&render_step_png(&analysis, Picture::SignedDiff, Some(1), size, size).unwrap());
        let pixel = &rgb[(y as usize * size as usize + x as usize) * 3..][..3];
        let diff = start.signed_diff(&end);
        let want = Ramp::Diverging
            .colour(Scale::of(diff.values()).squash(diff.values()[condensed_index(n, at.0, at.1)]));
        assert_eq!(pixel, want, "cell {at:?}");
    }

    #[test]
    fn the_border_transform_puts_vertex_0_on_its_mark() {
        let analysis = folded_square(8, [PI / 4.0, 5.0 * PI / 4.0]);
        let size = 360;
        let t = PlotTransform::of_borders(&analysis, &[], size).unwrap();
        let (_, _, rgb) = decode(&render_png(&analysis, Picture::Borders, size, size).unwrap());
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
        assert!(matches!(within_limit(2, 1001), Err(Error::TooLarge { got: Some(1_001_000), .. })));
        assert!(within_limit(1, 1414).is_ok());
    }

    #[test]
    fn a_step_that_does_not_exist_is_refused() {
        let analysis = folded_square(4, [0.0, PI]);
        assert!(matches!(readout(&analysis, &[], Some(2), 200), Err(Error::InvalidArgument(_))));
    }
}
