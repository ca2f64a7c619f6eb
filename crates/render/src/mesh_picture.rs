//! The mesh picture of a mesh sample: the cloth seen from above, coloured by height, with
//! the border loop found on it drawn over.
//!
//! The analysed start and end frames are drawn side by side (or one above the other, which
//! ever gives the larger drawing) on one scale, so the cloth's size compares between them,
//! and one height scale, shown by the colour bar. Each face (a polygon, cut into a fan of
//! triangles) is filled pixel by pixel: a pixel takes the height z interpolated
//! (barycentrically) in each triangle over it and keeps the highest, so a folded layer hides
//! what lies under it, as seen from above; faces drawn large enough to tell apart show their
//! edges a shade darker. The border loop (the analysis's border: mesh
//! vertex indices, found on frame 0 and followed by vertex) is drawn over each frame with
//! a white halo, vertex 0 marked.
//!
//! ```
//! use close_render::mesh_picture::MeshView;
//! // A unit square of two triangles, lifted at one corner in the end frame.
//! let start = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
//! let mut end = start.clone();
//! end[2][2] = 0.5;
//! let view = MeshView { faces: vec![vec![0, 1, 2], vec![0, 2, 3]], start, end, frames: (0, 1) };
//! assert_eq!(view.heights(), (0.0, 0.5));
//! ```

use plotters::style::text_anchor::{HPos, VPos};

use super::colour::height_colour;
use super::disk_picture::format_value;
use super::{label_size, line_width, note_size, Canvas, INK, MUTED, MUTED_TEXT, PAPER};
use crate::error::{Error, Result};
use close_core::analysis::Analysis;
use close_io::mesh::MeshFrames;

/// What the mesh picture draws of a mesh sample: its faces and the vertex positions of the
/// analysed start and end frames (a copy of two frames, not of the whole sample).
#[derive(Debug, Clone, PartialEq)]
pub struct MeshView {
    /// Polygons of vertex indices.
    pub faces: Vec<Vec<usize>>,
    /// Vertex positions of the analysed start frame.
    pub start: Vec<[f64; 3]>,
    /// Vertex positions of the analysed end frame.
    pub end: Vec<[f64; 3]>,
    /// The sample's numbers of those two frames.
    pub frames: (usize, usize),
}

impl MeshView {
    /// The view of `mesh` for `analysis` (its analysed start and end frames); `None` when
    /// those frames are not in the mesh.
    pub fn of(mesh: &MeshFrames, analysis: &Analysis) -> Option<MeshView> {
        MeshView::new(mesh, (analysis.start_frame, analysis.end_frame))
    }

    /// The view of `mesh` at its frames `(start, end)`; `None` when either is not in the mesh.
    pub fn new(mesh: &MeshFrames, (a, b): (usize, usize)) -> Option<MeshView> {
        Some(MeshView {
            faces: mesh.faces.clone(),
            start: mesh.frames.get(a)?.clone(),
            end: mesh.frames.get(b)?.clone(),
            frames: (a, b),
        })
    }

    /// Bytes the view holds on the heap, for a cache's weight.
    pub fn bytes(&self) -> usize {
        24 * (self.start.len() + self.end.len())
            + self.faces.iter().map(|f| 24 + 8 * f.len()).sum::<usize>()
    }

    /// The lowest and highest z over both frames (0, 0 when there is no vertex).
    pub fn heights(&self) -> (f64, f64) {
        let z = self.start.iter().chain(&self.end).map(|p| p[2]).filter(|z| z.is_finite());
        let (lo, hi) = z.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), z| (a.min(z), b.max(z)));
        if lo > hi {
            (0.0, 0.0)
        } else {
            (lo, hi)
        }
    }

    /// The frames drawn: (sample frame number, positions), one when start and end are the same frame.
    fn panels(&self) -> Vec<(usize, &[[f64; 3]])> {
        let mut panels = vec![(self.frames.0, self.start.as_slice())];
        if self.frames.1 != self.frames.0 {
            panels.push((self.frames.1, self.end.as_slice()));
        }
        panels
    }
}

/// A height's place on the colour scale, t ∈ [0, 1]: the middle when every height is one.
fn height_t(z: f64, (lo, hi): (f64, f64)) -> f64 {
    if hi - lo > 1e-12 * (1.0 + hi.abs()) {
        ((z - lo) / (hi - lo)).clamp(0.0, 1.0)
    } else {
        0.5
    }
}

/// Data → pixel map of one panel: equal scales on x and y, y up.
#[derive(Debug, Clone, Copy)]
struct Place {
    /// Pixel of data (x0, y1), the box's top-left corner.
    origin: (f64, f64),
    /// Data's top-left (x0, y1).
    data: (f64, f64),
    /// Pixels per data unit.
    scale: f64,
}

impl Place {
    fn pixel(&self, p: &[f64; 3]) -> (f64, f64) {
        (
            self.origin.0 + (p[0] - self.data.0) * self.scale,
            self.origin.1 + (self.data.1 - p[1]) * self.scale,
        )
    }
}

/// The XY box of `points`: (x0, x1), (y0, y1); a unit box when there is no finite point.
fn xy_box<'a>(points: impl Iterator<Item = &'a [f64; 3]>) -> ((f64, f64), (f64, f64)) {
    let (mut x, mut y) = ((f64::INFINITY, f64::NEG_INFINITY), (f64::INFINITY, f64::NEG_INFINITY));
    for p in points.filter(|p| p[0].is_finite() && p[1].is_finite()) {
        x = (x.0.min(p[0]), x.1.max(p[0]));
        y = (y.0.min(p[1]), y.1.max(p[1]));
    }
    if x.0 > x.1 {
        ((0.0, 1.0), (0.0, 1.0))
    } else {
        (x, y)
    }
}

/// Where the parts of a mesh picture go on a `width`×`height` canvas.
struct Layout {
    /// One per panel of [`MeshView::panels`].
    places: Vec<Place>,
    /// The colour bar: left, top, right, bottom.
    bar: [f64; 4],
}

impl Layout {
    /// Title on top, the colour bar and its values on the right, a note at the bottom, the
    /// panels in the rest.
    fn of(width: u32, height: u32, view: &MeshView) -> Layout {
        let (w, h) = (width as f64, height as f64);
        let unit = w.min(h);
        let (note, label) = (note_size(unit), label_size(unit));
        let top = 1.8 * super::title_size(unit);
        let heights = view.heights();
        let bar_width = (0.035 * unit).max(4.0);
        let values = (0..=2)
            .map(|k| super::raster::text_width(&height_tick(heights, k), note))
            .fold(0.0, f64::max);
        let band = bar_width
            + 0.6 * note
            + values.max(super::raster::text_width("height z", note) - bar_width)
            + label;
        let bottom = h - 1.8 * note;
        let places = lay_out(&view.panels(), (0.5 * label, top, w - band, bottom), 1.6 * note);
        let left = w - band + 0.5 * label;
        Layout { places, bar: [left, top + 1.6 * note, left + bar_width, bottom - note] }
    }
}

/// Draw the mesh picture of `analysis` from `view`.
pub(crate) fn draw(canvas: &mut Canvas, analysis: &Analysis, view: &MeshView) -> Result<()> {
    if analysis.border_indices.iter().any(|&v| v >= view.start.len() || v >= view.end.len()) {
        return Err(Error::Render("the border's vertices are not the mesh's: the mesh picture needs the analysis of that mesh".into()));
    }
    let unit = canvas.unit();
    let h = canvas.height as f64;
    let (note, label) = (note_size(unit), label_size(unit));
    let heights = view.heights();
    let layout = Layout::of(canvas.width, canvas.height, view);
    let panels = view.panels();
    for ((_, points), place) in panels.iter().zip(&layout.places) {
        fill(canvas, &view.faces, points, place, heights);
    }
    canvas.title("Mesh from above, coloured by height");
    let width = line_width(unit, 0.005);
    for ((frame, points), place) in panels.iter().zip(&layout.places) {
        let loop_points: Vec<(f64, f64)> = analysis
            .border_indices
            .iter()
            .chain(analysis.border_indices.first())
            .map(|&v| place.pixel(&points[v]))
            .collect();
        canvas.stroke(&loop_points, width + 3.0, PAPER);
        canvas.stroke(&loop_points, width, INK);
        if let Some(&first) = loop_points.first() {
            canvas.disc(first, width + 2.5, PAPER);
            canvas.disc(first, width + 1.5, INK);
        }
        canvas.text(
            &format!("frame {frame}"),
            (place.origin.0, place.origin.1 - 0.9 * note),
            note,
            INK,
            (HPos::Left, VPos::Center),
        );
    }
    draw_bar(canvas, heights, layout.bar, note);
    let faces = if view.faces.is_empty() { " · the mesh gives no faces" } else { "" };
    let text = format!("black: border loop ({}) · ● vertex 0{faces}", analysis.border_source);
    canvas.text(&text, (0.5 * label, h - 0.8 * note), note, MUTED_TEXT, (HPos::Left, VPos::Center));
    Ok(())
}

/// Where each panel goes in `area` (left, top, right, bottom, pixels), each with room for
/// its caption (`caption` pixels) above: side by side or one above the other, whichever
/// draws larger, on one scale.
fn lay_out(
    panels: &[(usize, &[[f64; 3]])],
    (left, top, right, bottom): (f64, f64, f64, f64),
    caption: f64,
) -> Vec<Place> {
    let ((x0, x1), (y0, y1)) = xy_box(panels.iter().flat_map(|(_, p)| p.iter()));
    let (dx, dy) = ((x1 - x0).max(1e-12), (y1 - y0).max(1e-12));
    let count = panels.len().max(1) as f64;
    let gap = caption;
    let (room_w, room_h) = ((right - left).max(1.0), (bottom - top).max(1.0));
    // Pixels per data unit with the panels in a row, and in a column.
    let in_row = ((room_w - gap * (count - 1.0)) / count / dx).min((room_h - caption) / dy);
    let in_column =
        (room_w / dx).min((room_h - count * caption - gap * (count - 1.0)) / count / dy);
    let (row, scale) = if in_row >= in_column { (true, in_row) } else { (false, in_column) };
    let scale = scale.max(1e-9);
    let (pw, ph) = (dx * scale, dy * scale);
    (0..panels.len())
        .map(|k| {
            let k = k as f64;
            let origin = if row {
                let spare = room_w - count * pw - gap * (count - 1.0);
                (left + spare / 2.0 + k * (pw + gap), top + caption + (room_h - caption - ph) / 2.0)
            } else {
                let spare = room_h - count * (ph + caption) - gap * (count - 1.0);
                (left + (room_w - pw) / 2.0, top + spare / 2.0 + caption + k * (ph + caption + gap))
            };
            Place { origin, data: (x0, y1), scale }
        })
        .collect()
}

/// Faces drawn at least this many pixels across (the root of their mean area) show their
/// edges; smaller ones would be all edge.
const EDGES_FROM: f64 = 8.0;

/// An edge pixel's colour: its face's, darkened by this factor.
const EDGE_SHADE: f64 = 0.8;

/// The colour of a face's edge over a face of `colour`.
fn edge_colour(colour: [u8; 3]) -> [u8; 3] {
    colour.map(|c| (c as f64 * EDGE_SHADE).round() as u8)
}

/// Fill the faces of one frame: each pixel the colour of the highest height over it, and,
/// when the faces are large enough to tell apart, their edges (the polygons', not those of
/// the fans they are cut into) a shade darker.
fn fill(
    canvas: &mut Canvas,
    faces: &[Vec<usize>],
    points: &[[f64; 3]],
    place: &Place,
    heights: (f64, f64),
) {
    let (w, h) = (canvas.width as usize, canvas.height as usize);
    // The highest height over each pixel, and whether the pixel is on its face's edge.
    let mut top = vec![(f64::NEG_INFINITY, false); w * h];
    let (mut across, mut drawn) = (0.0, 0usize);
    // Each triangle of a face's fan, with which of its sides are the face's: the side
    // opposite corner 0 always, the others at the ends of the fan.
    let triangles = faces.iter().flat_map(|f| {
        let last = f.len().saturating_sub(1);
        (1..last).map(move |k| ([f[0], f[k], f[k + 1]], [true, k + 1 == last, k == 1]))
    });
    for (triangle, outer) in triangles {
        let Some(corners) = triangle.iter().map(|&v| points.get(v)).collect::<Option<Vec<_>>>()
        else {
            continue;
        };
        let p: Vec<(f64, f64)> = corners.iter().map(|c| place.pixel(c)).collect();
        let z = [corners[0][2], corners[1][2], corners[2][2]];
        let area = (p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[2].0 - p[0].0) * (p[1].1 - p[0].1);
        if !area.is_finite() || area.abs() < 1e-12 {
            continue;
        }
        across += area.abs().sqrt();
        drawn += 1;
        // The triangle's height over the side opposite each corner, in pixels.
        let side = |a: (f64, f64), b: (f64, f64)| (b.0 - a.0).hypot(b.1 - a.1).max(1e-12);
        let heights_over = [
            area.abs() / side(p[1], p[2]),
            area.abs() / side(p[2], p[0]),
            area.abs() / side(p[0], p[1]),
        ];
        let x0 = p.iter().map(|q| q.0).fold(f64::INFINITY, f64::min).floor().max(0.0) as usize;
        let x1 = (p.iter().map(|q| q.0).fold(f64::NEG_INFINITY, f64::max).ceil().max(0.0) as usize)
            .min(w);
        let y0 = p.iter().map(|q| q.1).fold(f64::INFINITY, f64::min).floor().max(0.0) as usize;
        let y1 = (p.iter().map(|q| q.1).fold(f64::NEG_INFINITY, f64::max).ceil().max(0.0) as usize)
            .min(h);
        for y in y0..y1 {
            for x in x0..x1 {
                let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
                // Barycentric weights of the pixel centre; inside when all are ≥ 0.
                let weight = |a: (f64, f64), b: (f64, f64)| {
                    ((b.0 - a.0) * (py - a.1) - (px - a.0) * (b.1 - a.1)) / area
                };
                let weights = [weight(p[1], p[2]), weight(p[2], p[0]), weight(p[0], p[1])];
                if weights.iter().all(|&l| l >= -1e-9) {
                    let at = weights[0] * z[0] + weights[1] * z[1] + weights[2] * z[2];
                    let k = y * w + x;
                    if at > top[k].0 {
                        // Within 0.4 px of one of the face's own sides (a line about a pixel wide).
                        let edge = (0..3).any(|i| outer[i] && weights[i] * heights_over[i] < 0.4);
                        top[k] = (at, edge);
                    }
                }
            }
        }
    }
    let edges = drawn > 0 && across / drawn as f64 >= EDGES_FROM;
    for (k, &(z, edge)) in top.iter().enumerate() {
        if z > f64::NEG_INFINITY {
            let colour = height_colour(height_t(z, heights));
            let colour = if edge && edges { edge_colour(colour) } else { colour };
            canvas.pixel_mut((k % w) as u32, (k / w) as u32).copy_from_slice(&colour);
        }
    }
}

/// The value of colour-bar tick k (0: lowest, 1: middle, 2: highest).
fn height_tick((lo, hi): (f64, f64), k: usize) -> String {
    format_value(lo + (hi - lo) * k as f64 / 2.0)
}

/// The height colour bar in `[left, top, right, bottom]` (pixels), high at the top, with
/// its three values and its name.
fn draw_bar(
    canvas: &mut Canvas,
    heights: (f64, f64),
    [left, top, right, bottom]: [f64; 4],
    size: f64,
) {
    let flat = height_t(heights.1, heights) == 0.5;
    for y in top.max(0.0) as u32..(bottom.min(canvas.height as f64)) as u32 {
        let t = if flat { 0.5 } else { 1.0 - (y as f64 - top) / (bottom - top).max(1.0) };
        for x in left.max(0.0) as u32..(right.min(canvas.width as f64)) as u32 {
            canvas.pixel_mut(x, y).copy_from_slice(&height_colour(t));
        }
    }
    canvas.stroke(
        &[(left, top), (right, top), (right, bottom), (left, bottom), (left, top)],
        1.0,
        MUTED,
    );
    canvas.text("height z", (left, top - 0.9 * size), size, INK, (HPos::Left, VPos::Center));
    let ticks = if flat {
        vec![(0.5, height_tick(heights, 0))]
    } else {
        (0..=2).map(|k| (1.0 - k as f64 / 2.0, height_tick(heights, k))).collect()
    };
    for (f, text) in ticks {
        let y = top + f * (bottom - top);
        canvas.stroke(&[(right, y), (right + 0.4 * size, y)], 1.0, INK);
        canvas.text(&text, (right + 0.6 * size, y), size, INK, (HPos::Left, VPos::Center));
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::{decode, preview};
    use super::super::{render, Known, Output, Picture, View};
    use super::*;

    /// The analysis of a built-in mesh sample and its view.
    fn mesh_sample(id: &str) -> (Analysis, MeshView) {
        let entry = close_io::dataset::Dataset::builtin().get(id).unwrap().clone();
        let analysis = close_core::analyze(
            &entry.sample.border_frames().unwrap(),
            close_core::FrameRange::default(),
        )
        .unwrap();
        let view = MeshView::of(entry.sample.mesh.as_ref().unwrap(), &analysis).unwrap();
        (analysis, view)
    }

    /// The id of the first built-in mesh sample.
    fn first_mesh_id() -> String {
        close_io::dataset::Dataset::builtin()
            .entries()
            .iter()
            .find(|e| e.sample.mesh.is_some())
            .unwrap()
            .id
            .clone()
    }

    #[test]
    fn the_mesh_is_inked_inside_its_border_in_height_colours() {
        let (analysis, view) = mesh_sample(&first_mesh_id());
        let size = 480;
        let known = Known { mesh: Some(&view), ..Known::default() };
        let png =
            render(&analysis, &View::whole(Picture::Mesh), &Output::png(size), known).unwrap();
        preview("mesh.png", &png);
        let (_, _, rgb) = decode(&png);
        let colour_at = |(x, y): (f64, f64)| {
            let k = (y as usize * size as usize + x as usize) * 3;
            [rgb[k], rgb[k + 1], rgb[k + 2]]
        };
        let layout = Layout::of(size, size, &view);
        assert_eq!(layout.places.len(), 2, "start and end frames");
        // The start frame lies flat at the lowest height: inside its border (a napkin or a
        // towel: a rectangle), the pixels are that height's colour, or a shade darker on the
        // edges of its faces, drawn at this size.
        let (lo, hi) = view.heights();
        assert!(hi > lo, "the folded mesh has no height");
        assert!(view.start.iter().all(|p| p[2] == lo), "the start frame is flat");
        let ((x0, x1), (y0, y1)) = xy_box(view.start.iter());
        let (a, b) =
            (layout.places[0].pixel(&[x0, y1, 0.0]), layout.places[0].pixel(&[x1, y0, 0.0]));
        let (face, edge) = (height_colour(0.0), edge_colour(height_colour(0.0)));
        let (mut faces, mut edges) = (0, 0);
        let inset = 0.1 * (b.0 - a.0).min(b.1 - a.1);
        for y in (a.1 + inset) as u32..(b.1 - inset) as u32 {
            for x in (a.0 + inset) as u32..(b.0 - inset) as u32 {
                match colour_at((x as f64, y as f64)) {
                    c if c == face => faces += 1,
                    c if c == edge => edges += 1,
                    c => panic!("pixel ({x}, {y}) inside the start frame is {c:?}"),
                }
            }
        }
        assert!(faces > 2 * edges && edges > 0, "{faces} face pixels, {edges} edge pixels");
        // The end frame shows the folded layer, high, in the scale's top colours.
        let near = |a: &[u8], b: [u8; 3]| a.iter().zip(b).all(|(&x, y)| x.abs_diff(y) <= 6);
        assert!(
            rgb.chunks(3).filter(|p| near(p, height_colour(1.0))).count() > 100,
            "no folded layer drawn"
        );
        assert!(
            rgb.chunks(3).filter(|p| near(p, height_colour(0.0))).count()
                > (size * size / 20) as usize,
            "little cloth drawn"
        );
        // The border loop is drawn in ink over both frames, through the border's vertices.
        let n = analysis.border_indices.len() as f64;
        for (place, frame) in layout.places.iter().zip([&view.start, &view.end]) {
            let on_loop = analysis
                .border_indices
                .iter()
                .filter(|&&v| near(&colour_at(place.pixel(&frame[v])), INK))
                .count();
            assert!(on_loop as f64 > 0.9 * n, "{on_loop} of {n} border vertices in ink");
        }
    }

    #[test]
    fn a_mesh_picture_needs_the_mesh_of_its_analysis() {
        let (analysis, mut view) = mesh_sample(&first_mesh_id());
        view.start.truncate(3);
        let known = Known { mesh: Some(&view), ..Known::default() };
        assert!(matches!(
            render(&analysis, &View::whole(Picture::Mesh), &Output::png(200), known),
            Err(Error::Render(_))
        ));
        let none = Known::default();
        assert!(matches!(
            render(&analysis, &View::whole(Picture::Mesh), &Output::png(200), none),
            Err(Error::Core(close_core::Error::InvalidArgument(_)))
        ));
    }
}
