//! CloSE pictures: the pictures of an analysis, drawn with plotters into an in-memory RGB buffer and
//! encoded as PNG.
//!
//! - [`disk_picture`]: a dGLI disk as the paper draws it (annular sectors, diverging map), and the
//!   diff disks with the fitted fold curves over them;
//! - [`circle`]: the CloSE fold circle (corners and folds on the unit circle);
//! - [`borders`]: start, end and predicted end borders in XY, with the fold lines;
//! - [`mesh_picture`]: a mesh sample's cloth from above, coloured by height, under its border loop.
//!
//! Text uses DejaVu Sans embedded in the binary (no system fonts), registered with plotters
//! once before any drawing. Sizes are clamped to [[`MIN_SIZE`], [`MAX_SIZE`]] pixels and
//! every length and font scales with the picture, so 480 px and 1200 px read the same; text
//! is sized for the narrowest width a picture is shown at ([`note_size`]) and darkened to AA
//! contrast on the paper ([`readable`]).
//!
//! Two functions draw them all: [`render`] a picture of an analysis ([`View`]: which picture,
//! of which step) and [`render_disk`] the disk of any one border state, each written as
//! [`Output`] says (size, PNG or SVG, print resolution).
//!
//! ```
//! use close_render::{render_disk, Output, Picture};
//! let disk = close_core::disk::Disk::from_values(4, vec![1.0, -0.5, 0.0, 0.0, 0.2, 2.0]).unwrap();
//! let (png, _) = render_disk(&disk, "a disk", None, &Output { height: 80, ..Output::png(100) }).unwrap();
//! assert_eq!(&png[1..4], b"PNG");
//! assert_eq!(Picture::from_name("signed_diff"), Some(Picture::SignedDiff));
//! ```

pub mod axes;
pub mod borders;
pub mod circle;
pub mod cloth;
pub mod colour;
pub mod disk_picture;
pub mod error;
pub mod mesh_picture;
pub mod raster;
pub mod readout;
#[cfg(feature = "rerun")]
pub mod record;
mod sector_map;
pub mod svg;
pub mod truth;

use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};
use plotters::style::{register_font, FontStyle};
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use close_core::analysis::Analysis;
use colour::{Ramp, Scale};

/// Which picture of an analysis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Picture {
    DiskStart,
    DiskEnd,
    Diff,
    SignedDiff,
    Close,
    Borders,
    /// A small drawing of the borders alone, for lists.
    Thumbnail,
    /// A mesh sample's cloth from above with its border loop ([`mesh_picture`]): listed only for
    /// mesh samples.
    Mesh,
}

impl Picture {
    /// The pictures every analysis lists (its `images`); [`Picture::Thumbnail`] is for
    /// lists, and [`Picture::Mesh`] is listed for mesh samples alone.
    pub const ALL: [Picture; 6] = [
        Picture::DiskStart,
        Picture::DiskEnd,
        Picture::Diff,
        Picture::SignedDiff,
        Picture::Close,
        Picture::Borders,
    ];

    /// The name used in URLs and JSON ("disk_start", …).
    pub fn name(self) -> &'static str {
        match self {
            Picture::DiskStart => "disk_start",
            Picture::DiskEnd => "disk_end",
            Picture::Diff => "diff",
            Picture::SignedDiff => "signed_diff",
            Picture::Close => "close",
            Picture::Borders => "borders",
            Picture::Thumbnail => "thumbnail",
            Picture::Mesh => "mesh",
        }
    }

    /// The picture of that name, if any.
    pub fn from_name(s: &str) -> Option<Picture> {
        Picture::ALL.into_iter().chain([Picture::Thumbnail, Picture::Mesh]).find(|p| p.name() == s)
    }
}

/// Default width and height in pixels.
pub const DEFAULT_SIZE: u32 = 480;
/// Smallest width or height; smaller requests are clamped up.
pub const MIN_SIZE: u32 = 64;
/// Largest width or height; larger requests are clamped down.
pub const MAX_SIZE: u32 = 2048;

/// The file a picture is written as.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Format {
    /// An 8-bit RGB PNG.
    #[default]
    Png,
    /// An SVG document: strokes and text as vectors over the fills' pixels ([`svg`]).
    Svg,
}

impl Format {
    /// The HTTP content type.
    pub fn content_type(self) -> &'static str {
        match self {
            Format::Png => "image/png",
            Format::Svg => "image/svg+xml",
        }
    }
}

/// How a picture is written: its size in pixels (each side clamped to
/// [`MIN_SIZE`]…[`MAX_SIZE`]), its format, and for a PNG the print resolution it states.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Output {
    pub width: u32,
    pub height: u32,
    pub format: Format,
    /// Dots per inch written in a PNG (its `pHYs` chunk: the size it prints at); none by
    /// default. An SVG is sized in pixels.
    pub dpi: Option<u32>,
}

impl Output {
    /// A square PNG of `size` pixels.
    pub fn png(size: u32) -> Output {
        Output { width: size, height: size, format: Format::Png, dpi: None }
    }

    /// A square SVG of `size` pixels.
    pub fn svg(size: u32) -> Output {
        Output { format: Format::Svg, ..Output::png(size) }
    }
}

/// Which picture of an analysis, of which part of it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    pub picture: Picture,
    /// With `Some(k)` (1-based: step k goes from analysed frame k − 1 to frame k), the disk
    /// pictures of that step alone (its two disks and its diffs, with the fold curves
    /// fitted on that step); `None`, the whole analysis, start frame → end frame.
    pub step: Option<usize>,
}

impl View {
    /// `picture` of the whole analysis.
    pub fn whole(picture: Picture) -> View {
        View { picture, step: None }
    }

    /// `picture` of step `k` alone.
    pub fn step(picture: Picture, k: usize) -> View {
        View { picture, step: Some(k) }
    }
}

/// What is known of a sample beyond its analysis, for the pictures that draw it.
#[derive(Debug, Clone, Copy)]
pub struct Known<'a> {
    /// The sample's true folds (may be empty), drawn beside the found ones on the fold
    /// circle and the borders, with how each found fold agrees ([`truth`]).
    pub truth: &'a truth::Truth,
    /// A mesh sample's mesh, which [`Picture::Mesh`] draws.
    pub mesh: Option<&'a mesh_picture::MeshView>,
}

impl Default for Known<'_> {
    /// Nothing known beyond the analysis.
    fn default() -> Self {
        static NOTHING: truth::Truth = truth::Truth { folds: Vec::new(), folded: Vec::new() };
        Known { truth: &NOTHING, mesh: None }
    }
}

/// Draw picture `view` of `analysis` as `output` says, with what is `known` of the sample.
/// The start and end disks of a picture pair share one colour scale, so a colour means one
/// value in both panels; a PNG and an SVG are the same drawing.
///
/// ```
/// use close_render::{render, Output, Picture, View};
/// # let analysis = close_core::analyze(&close_core::border::prepare(vec![vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]]; 2]).unwrap(), Default::default()).unwrap();
/// let png = render(&analysis, &View::whole(Picture::Close), &Output::png(200), Default::default()).unwrap();
/// assert_eq!(&png[1..4], b"PNG");
/// ```
pub fn render(analysis: &Analysis, view: &View, output: &Output, known: Known) -> Result<Vec<u8>> {
    let (picture, step) = (view.picture, view.step);
    let mut canvas = Canvas::new(output.width, output.height)?;
    canvas.dpi = output.dpi;
    if output.format == Format::Svg {
        canvas.vector = Some(svg::Vector::default());
    }
    match picture {
        Picture::Thumbnail | Picture::Mesh if step.is_some() => {
            return Err(Error::invalid(format!(
                "the {} picture shows the whole analysis: it takes no step",
                picture.name()
            )));
        }
        Picture::Close => circle::draw(&mut canvas, analysis, known.truth, step)?,
        Picture::Borders => {
            borders::draw(&mut canvas, analysis, known.truth, step)?;
        }
        Picture::Thumbnail => borders::draw_thumbnail(&mut canvas, analysis),
        Picture::Mesh => {
            match known.mesh {
                Some(view) => mesh_picture::draw(&mut canvas, analysis, view)?,
                None => return Err(Error::invalid(
                    "the mesh picture is drawn for mesh samples only: this sample gives borders"
                        .into(),
                )),
            }
        }
        _ => {
            let span = StepSpan::of(analysis, step)?;
            let disk_of = |k: usize| {
                analysis
                    .disk(k)
                    .ok_or_else(|| Error::Render(format!("analysed frame {k} does not exist")))
            };
            let (start, end) = (disk_of(span.from)?, disk_of(span.to)?);
            let frame = |k: usize| analysis.start_frame + k;
            match picture {
                Picture::DiskStart | Picture::DiskEnd => {
                    let shared = Scale::of_all(&[start.values(), end.values()]);
                    let (disk, k) = if picture == Picture::DiskStart {
                        (&start, span.from)
                    } else {
                        (&end, span.to)
                    };
                    let title = format!("dGLI disk · frame {}", frame(k));
                    disk_picture::draw(&mut canvas, disk, &title, Ramp::Diverging, &shared, None)?
                }
                _ => {
                    // The curves were fitted on |diff|, and are drawn over either diff.
                    let marks = span.marks(analysis);
                    let (diff, ramp, what) = if picture == Picture::Diff {
                        (start.abs_diff(&end), Ramp::Sequential, "| |end| − |start| |")
                    } else {
                        (start.signed_diff(&end), Ramp::Diverging, "Δ = end − start")
                    };
                    let title = format!("{what} · frames {}→{}", frame(span.from), frame(span.to));
                    disk_picture::draw(
                        &mut canvas,
                        &diff,
                        &title,
                        ramp,
                        &Scale::of(diff.values()),
                        Some(&marks),
                    )?
                }
            }
        }
    }
    canvas.encode()
}

/// The frames a disk picture (or a border plot) compares, and the step they are, if one.
struct StepSpan {
    from: usize,
    to: usize,
    step: Option<usize>,
}

impl StepSpan {
    fn of(analysis: &Analysis, step: Option<usize>) -> Result<StepSpan> {
        let steps = analysis.steps.len();
        match step {
            None => Ok(StepSpan { from: 0, to: analysis.frames.len() - 1, step: None }),
            Some(k) if (1..=steps).contains(&k) => {
                Ok(StepSpan { from: k - 1, to: k, step: Some(k) })
            }
            Some(k) if steps == 0 => Err(Error::invalid(format!(
                "step {k} does not exist: the analysis has one frame, no step"
            ))),
            Some(k) if steps == 1 => Err(Error::invalid(format!(
                "step {k} does not exist: the analysis has one step, step=1"
            ))),
            Some(k) => Err(Error::invalid(format!(
                "step {k} does not exist: the analysis has steps 1…{steps}"
            ))),
        }
    }

    /// The indices (in [`Analysis::foldings`] order) of the folds this span holds.
    fn folds(&self, analysis: &Analysis) -> std::ops::Range<usize> {
        match self.step {
            Some(k) => {
                let before: usize = analysis.steps[..k - 1].iter().map(|s| s.folds.len()).sum();
                before..before + analysis.steps[k - 1].folds.len()
            }
            None => 0..analysis.steps.iter().map(|s| s.folds.len()).sum(),
        }
    }

    /// What to draw over this span's diff: the fold points of the folds it holds, and, for
    /// a single step, the curves of its fold, fitted on that step's own |diff| (a curve fitted
    /// on another pair of frames would be drawn on a disk it was not read from).
    fn marks(&self, analysis: &Analysis) -> disk_picture::Marks {
        let total = analysis.folds.len();
        // Fold number of each step's fold: folds are numbered in step order.
        let numbered = analysis.steps.iter().scan(0, |count, s| {
            let k = *count;
            *count += usize::from(s.detection.fold.is_some());
            Some((k, s))
        });
        let one_step = self.step.or((analysis.steps.len() == 1).then_some(1));
        let mut marks =
            disk_picture::Marks { folds: Vec::new(), total, curves: Vec::new(), note: None };
        for (k, (fold_number, step)) in numbered.enumerate() {
            let shown = self.step.is_none_or(|s| s == k + 1);
            if let (true, Some(fold)) = (shown, step.detection.fold) {
                marks.folds.push((fold_number, fold));
            }
            if one_step == Some(k + 1) {
                // The curves ending at the reported fold points (all of them with the default
                // method; the paper's free fit also finds others).
                let at_fold = |c: &&close_core::fold::Curve| {
                    step.detection.fold.is_some_and(|f| {
                        [f.f1, f.f2].iter().any(|&f| close_core::angle::distance(c.rim, f) < 1e-9)
                    })
                };
                marks.curves = step.detection.curves.iter().filter(at_fold).copied().collect();
            }
        }
        if one_step.is_none() {
            marks.note = Some("fold curves: see each step".into());
        } else if marks.folds.is_empty() {
            marks.note = Some("no fold".into());
        }
        marks
    }
}

/// Draw a dGLI disk alone (diverging map, colour bar, `title`) as `output` says, with a colour
/// `scale` (its own when `None`); gives the file and the scale used, so a caller can keep one
/// scale through an animation.
///
/// ```
/// use close_render::{render_disk, Output};
/// let disk = close_core::disk::Disk::from_values(4, vec![1.0, -0.5, 0.0, 0.0, 0.2, 2.0]).unwrap();
/// let (png, scale) = render_disk(&disk, "a disk", None, &Output::png(100)).unwrap();
/// assert_eq!(&png[1..4], b"PNG");
/// assert_eq!(scale.max, 2.0);
/// ```
pub fn render_disk(
    disk: &close_core::disk::Disk,
    title: &str,
    scale: Option<Scale>,
    output: &Output,
) -> Result<(Vec<u8>, Scale)> {
    let mut canvas = Canvas::new(output.width, output.height)?;
    canvas.dpi = output.dpi;
    if output.format == Format::Svg {
        canvas.vector = Some(svg::Vector::default());
    }
    let scale = scale.unwrap_or_else(|| Scale::of(disk.values()));
    disk_picture::draw(&mut canvas, disk, title, Ramp::Diverging, &scale, None)?;
    Ok((canvas.encode()?, scale))
}

/// DejaVu Sans (Bitstream Vera licence, see `assets/DejaVuSans-LICENSE.txt`).
static FONT: &[u8] = include_bytes!("../../../assets/DejaVuSans.ttf");
/// The family name every text style of this module uses.
const FAMILY: &str = "sans-serif";

/// Register the embedded font with plotters, once; drawing text without it panics.
fn ensure_font() -> Result<()> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    if *REGISTERED.get_or_init(|| register_font(FAMILY, FontStyle::Normal, FONT).is_ok()) {
        Ok(())
    } else {
        Err(Error::Render("the embedded font could not be loaded".into()))
    }
}

/// What plotters drawing on the canvas returns.
type DrawResult<T = ()> = std::result::Result<
    T,
    DrawingAreaErrorKind<<BitMapBackend<'static> as DrawingBackend>::ErrorType>,
>;
/// A plotters drawing area over the whole canvas, in pixel coordinates.
type Area<'a> = DrawingArea<BitMapBackend<'a>, Shift>;

/// An RGB picture being drawn: raw pixels first (the disk raster), then plotters on top.
pub(crate) struct Canvas {
    width: u32,
    height: u32,
    rgb: Vec<u8>,
    /// The PNG row filter: Sub suits line drawings; a disk picture sets Up.
    png_filter: png::FilterType,
    /// On a recording canvas ([`Canvas::record`]), the blends made so far instead of pixels.
    recording: Option<raster::Recording>,
    /// On an SVG canvas, strokes and text as vector elements instead of pixels.
    vector: Option<svg::Vector>,
    /// The print resolution a PNG states, if any.
    dpi: Option<u32>,
}

impl Canvas {
    /// A white canvas of the clamped size; also makes sure the font is registered.
    fn new(width: u32, height: u32) -> Result<Canvas> {
        ensure_font()?;
        let (width, height) = (width.clamp(MIN_SIZE, MAX_SIZE), height.clamp(MIN_SIZE, MAX_SIZE));
        Ok(Canvas {
            width,
            height,
            rgb: vec![255; width as usize * height as usize * 3],
            png_filter: png::FilterType::Sub,
            recording: None,
            vector: None,
            dpi: None,
        })
    }

    /// The unit every length and font is scaled from: the shorter side in pixels.
    fn unit(&self) -> f64 {
        self.width.min(self.height) as f64
    }

    /// Mutable pixel (x, y) as RGB.
    fn pixel_mut(&mut self, x: u32, y: u32) -> &mut [u8] {
        let k = (y as usize * self.width as usize + x as usize) * 3;
        &mut self.rgb[k..k + 3]
    }

    /// Draw with plotters over the current pixels.
    fn draw<T>(&mut self, f: impl FnOnce(&Area) -> DrawResult<T>) -> Result<T> {
        let area = BitMapBackend::with_buffer(&mut self.rgb, (self.width, self.height))
            .into_drawing_area();
        let out = f(&area).map_err(|e| Error::Render(e.to_string()))?;
        area.present().map_err(|e| Error::Render(e.to_string()))?;
        Ok(out)
    }

    /// The finished picture: its PNG, or on an SVG canvas the SVG document.
    fn encode(&self) -> Result<Vec<u8>> {
        Ok(match &self.vector {
            // Nothing but paper under the vectors: no pixels to embed.
            Some(vector) if self.rgb.iter().all(|&c| c == 255) => {
                vector.document(self.width, self.height, None).into_bytes()
            }
            Some(vector) => {
                vector.document(self.width, self.height, Some(&self.png()?)).into_bytes()
            }
            None => self.png()?,
        })
    }

    /// Whether strokes and text are written as vectors (an SVG canvas).
    fn is_vector(&self) -> bool {
        self.vector.is_some()
    }

    /// Encode as an 8-bit RGB PNG with `png_filter`, at the fast setting (fdeflate: run
    /// lengths and a fixed Huffman code, ten times faster than the default level).
    fn png(&self) -> Result<Vec<u8>> {
        let fail = |e: png::EncodingError| Error::Render(format!("PNG encoding failed: {e}"));
        let mut out = Vec::new();
        let mut encoder = png::Encoder::new(&mut out, self.width, self.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::Fast);
        encoder.set_filter(self.png_filter);
        if let Some(dpi) = self.dpi {
            // pHYs counts pixels per metre.
            let per_metre = (f64::from(dpi) / 0.0254).round() as u32;
            encoder.set_pixel_dims(Some(png::PixelDimensions {
                xppu: per_metre,
                yppu: per_metre,
                unit: png::Unit::Meter,
            }));
        }
        let mut writer = encoder.write_header().map_err(fail)?;
        writer.write_image_data(&self.rgb).map_err(fail)?;
        writer.finish().map_err(fail)?;
        Ok(out)
    }
}

/// A palette colour for plotters.
fn plot([r, g, b]: [u8; 3]) -> RGBColor {
    RGBColor(r, g, b)
}

/// Ink for text and outlines.
const INK: [u8; 3] = [40, 40, 40];
/// Guides (rims, axes, ticks): lines, never text.
const MUTED: [u8; 3] = [130, 130, 130];
/// Secondary text: 6.4:1 on the paper (WCAG AA asks 4.5:1).
const MUTED_TEXT: [u8; 3] = [86, 96, 113];
/// Background, and halos that keep lines readable over colour.
const PAPER: [u8; 3] = [255, 255, 255];

/// One colour per fold, shared by every picture so fold k looks the same everywhere.
const FOLD_COLOURS: [[u8; 3]; 4] = [[214, 39, 40], [44, 160, 44], [148, 103, 189], [23, 190, 207]];

/// Colour of fold `k` (0-based).
fn fold_colour(k: usize) -> [u8; 3] {
    FOLD_COLOURS[k % FOLD_COLOURS.len()]
}

/// Name of fold `k`'s endpoint `e` (0 or 1): "f1"/"f2", numbered when there are several folds.
fn endpoint_name(k: usize, e: usize, folds: usize) -> String {
    if folds > 1 {
        format!("f{}·{}", e + 1, k + 1)
    } else {
        format!("f{}", e + 1)
    }
}

/// Text anchor that puts a label outside a circle at angle `theta` (y up).
fn outward(theta: f64) -> (HPos, VPos) {
    let (c, s) = (theta.cos(), theta.sin());
    let h = if c > 0.38 {
        HPos::Left
    } else if c < -0.38 {
        HPos::Right
    } else {
        HPos::Center
    };
    let v = if s > 0.38 {
        VPos::Bottom
    } else if s < -0.38 {
        VPos::Top
    } else {
        VPos::Center
    };
    (h, v)
}

impl Canvas {
    /// The title, centred at the top.
    fn title(&mut self, title: &str) {
        let unit = self.unit();
        let size = title_size(unit);
        let (text, fitted) = fit_title(title, unit, self.width as f64);
        self.text(
            &text,
            (self.width as f64 / 2.0, 0.9 * size),
            fitted,
            INK,
            (HPos::Center, VPos::Center),
        );
    }

    /// Height of the title band.
    fn title_band(&self) -> f64 {
        1.8 * title_size(self.unit())
    }
}

/// `title` as drawn across a picture `width` wide: at the title size when it fits, else
/// smaller (down to the notes' size), and cut short with "…" when even that does not fit, so
/// a long name never runs off the picture.
fn fit_title(title: &str, unit: f64, width: f64) -> (String, f64) {
    let room = 0.96 * width;
    let size = title_size(unit);
    let wide = raster::text_width(title, size);
    if wide <= room {
        return (title.to_string(), size);
    }
    let size = (size * room / wide).max(note_size(unit));
    let mut chars: Vec<char> = title.chars().collect();
    let mut text = title.to_string();
    while raster::text_width(&text, size) > room && !chars.is_empty() {
        chars.pop();
        text = format!("{}…", chars.iter().collect::<String>().trim_end());
    }
    (text, size)
}

/// The narrowest a picture is shown, in CSS px per its shorter side: the web app's figures
/// are a grid column at least 22 rem wide (a rem is at least 14 px), less padding — about
/// 330 px at a 420 px viewport, more when wider; the lightbox shows more still.
pub const SHOWN_WIDTH: f64 = 320.0;
/// The smallest text, in CSS px, when the picture is shown [`SHOWN_WIDTH`] wide (12 px is
/// the floor a reader asks for; the half pixel is rounding's margin).
pub const MIN_TEXT_CSS: f64 = 12.5;

/// Font size, in picture pixels, of the smallest text (ticks, notes, legends): text
/// scales with the picture, so shown `SHOWN_WIDTH` CSS px wide (or wider) it is at least
/// `MIN_TEXT_CSS` CSS px; a picture smaller than that is shown at its own size, where
/// the same floor holds in pixels.
pub fn note_size(unit: f64) -> f64 {
    MIN_TEXT_CSS * (unit / SHOWN_WIDTH).max(1.0)
}

/// Font size of labels (corner numbers, fold names, colour-bar values).
pub fn label_size(unit: f64) -> f64 {
    1.1 * note_size(unit)
}

/// Font size of titles.
pub fn title_size(unit: f64) -> f64 {
    1.25 * note_size(unit)
}

/// WCAG relative luminance of an sRGB colour.
fn luminance(colour: [u8; 3]) -> f64 {
    let linear = |c: u8| {
        let c = c as f64 / 255.0;
        if c <= 0.040_45 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    };
    let [r, g, b] = colour.map(linear);
    0.2126 * r + 0.7152 * g + 0.0722 * b
}

/// WCAG contrast ratio of two colours (1 to 21).
pub fn contrast(a: [u8; 3], b: [u8; 3]) -> f64 {
    let (la, lb) = (luminance(a), luminance(b));
    (la.max(lb) + 0.05) / (la.min(lb) + 0.05)
}

/// Text contrast WCAG AA asks of normal text.
pub const TEXT_CONTRAST: f64 = 4.5;

/// `colour` for text on the paper: itself when it contrasts [`TEXT_CONTRAST`]:1 or more,
/// else darkened (each channel scaled by the same factor, so the hue stays) until it does.
pub fn readable(colour: [u8; 3]) -> [u8; 3] {
    let mut out = colour;
    let mut k = 1.0;
    while contrast(out, PAPER) < TEXT_CONTRAST && k > 0.0 {
        k -= 0.02;
        out = colour.map(|c| (c as f64 * k).round() as u8);
    }
    out
}

/// Line width for `fraction` of the unit, at least one pixel.
fn line_width(unit: f64, fraction: f64) -> f64 {
    (unit * fraction).max(1.0)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use close_core::border::prepare;
    use close_core::fold::apply;
    use close_core::geometry::{Fold, Folding};
    use close_core::{analyze, FrameRange};
    use std::f64::consts::PI;

    #[test]
    fn a_long_title_fits_its_picture() {
        let short = fit_title("dGLI disk", 480.0, 480.0);
        assert_eq!(short, ("dGLI disk".to_string(), title_size(480.0)));
        let long = "napkin__half_then_half · after step 1 of 2 (frame 1) · a long name";
        let (text, size) = fit_title(long, 480.0, 480.0);
        assert!(size < title_size(480.0) && size >= note_size(480.0));
        assert!(raster::text_width(&text, size) <= 0.96 * 480.0, "{text} at {size}");
        let cut = fit_title(&long.repeat(3), 480.0, 480.0).0;
        assert!(cut.ends_with('…') && cut.len() < 3 * long.len(), "{cut}");
    }

    /// A square of `per_side` vertices per side, folded along `fold` with the folded arc
    /// lifted a little (as a real fold lies on top), analysed.
    pub(crate) fn folded_square(per_side: usize, fold: [f64; 2]) -> Analysis {
        let n = 4 * per_side;
        let corners = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let flat: Vec<close_core::border::Point> = (0..n)
            .map(|k| {
                let (side, t) = (k / per_side, (k % per_side) as f64 / per_side as f64);
                let (a, b) = (corners[side], corners[(side + 1) % 4]);
                close_core::border::Point::new(
                    a[0] + t * (b[0] - a[0]),
                    a[1] + t * (b[1] - a[1]),
                    0.0,
                )
            })
            .collect();
        let fold = Fold::from(fold);
        let mut folded = apply(&flat, &Folding::new(fold));
        for v in fold.arc().folded_vertices(n) {
            folded[v].z = 0.02;
        }
        let raw =
            [flat, folded].iter().map(|f| f.iter().map(|p| [p.x, p.y, p.z]).collect()).collect();
        analyze(&prepare(raw).unwrap(), FrameRange::default()).unwrap()
    }

    /// Picture `picture` of `analysis` (step `step`) as a `w`×`h` PNG.
    pub(crate) fn png(
        analysis: &Analysis,
        picture: Picture,
        step: Option<usize>,
        (w, h): (u32, u32),
    ) -> Result<Vec<u8>> {
        let output = Output { width: w, height: h, ..Output::png(w) };
        render(analysis, &View { picture, step }, &output, Known::default())
    }

    /// A disk alone as a `w`×`h` PNG, on its own colour scale.
    pub(crate) fn disk_png(
        disk: &close_core::disk::Disk,
        title: &str,
        (w, h): (u32, u32),
    ) -> Vec<u8> {
        render_disk(disk, title, None, &Output { width: w, height: h, ..Output::png(w) }).unwrap().0
    }

    /// Decode a PNG into (width, height, RGB pixels).
    pub(crate) fn decode(png_bytes: &[u8]) -> (u32, u32, Vec<u8>) {
        let decoder = png::Decoder::new(png_bytes);
        let mut reader = decoder.read_info().expect("a PNG header");
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).expect("PNG data");
        assert_eq!((info.color_type, info.bit_depth), (png::ColorType::Rgb, png::BitDepth::Eight));
        buf.truncate(info.buffer_size());
        (info.width, info.height, buf)
    }

    /// Number of distinct colours in an RGB buffer.
    pub(crate) fn colours(rgb: &[u8]) -> usize {
        rgb.chunks(3).map(|c| (c[0], c[1], c[2])).collect::<std::collections::HashSet<_>>().len()
    }

    /// Write a preview for a person to look at (`target/render-preview/`).
    pub(crate) fn preview(name: &str, png_bytes: &[u8]) {
        let dir = std::path::Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../target/render-preview"
        ));
        std::fs::create_dir_all(dir).unwrap();
        std::fs::write(dir.join(name), png_bytes).unwrap();
    }

    #[test]
    fn picture_names_round_trip() {
        for p in Picture::ALL.into_iter().chain([Picture::Thumbnail, Picture::Mesh]) {
            assert_eq!(Picture::from_name(p.name()), Some(p));
            assert_eq!(serde_json::to_string(&p).unwrap(), format!("\"{}\"", p.name()));
        }
        assert_eq!(Picture::from_name("thumbnail"), Some(Picture::Thumbnail));
        assert_eq!(Picture::from_name("disk"), None);
    }

    #[test]
    fn every_picture_is_a_png_of_the_requested_size() {
        let analysis = folded_square(6, [PI / 4.0, 5.0 * PI / 4.0]);
        assert_eq!(analysis.folds.len(), 1, "the test square should show one fold");
        for picture in Picture::ALL.into_iter().chain([Picture::Thumbnail]) {
            for (w, h) in [(200, 150), (DEFAULT_SIZE, DEFAULT_SIZE)] {
                let png_bytes = png(&analysis, picture, None, (w, h)).unwrap();
                let (dw, dh, rgb) = decode(&png_bytes);
                assert_eq!((dw, dh), (w, h), "{picture:?}");
                assert!(colours(&rgb) > 10, "{picture:?} is (nearly) one flat colour");
                if w == DEFAULT_SIZE {
                    preview(&format!("{}.png", picture.name()), &png_bytes);
                }
            }
        }
    }

    /// The analysis of a built-in sample.
    fn builtin(id: &str) -> Analysis {
        let entry = close_io::dataset::Dataset::builtin().get(id).unwrap().clone();
        analyze(&entry.sample.border_frames().unwrap(), FrameRange::default()).unwrap()
    }

    #[test]
    fn second_folds_have_pictures_per_step() {
        let analysis = builtin("napkin__half_then_half");
        assert_eq!(analysis.steps.len(), 2);
        for picture in [Picture::DiskStart, Picture::DiskEnd, Picture::Diff, Picture::SignedDiff] {
            let whole = png(&analysis, picture, None, (240, 240)).unwrap();
            let steps: Vec<Vec<u8>> =
                (1..=2).map(|k| png(&analysis, picture, Some(k), (240, 240)).unwrap()).collect();
            // Step 2's start disk is frame 1's, a disk the whole-analysis pictures never show.
            assert_ne!(steps[0], steps[1], "{picture:?}");
            assert_ne!(whole, steps[1], "{picture:?}");
            preview(&format!("step2_{}.png", picture.name()), &steps[1]);
        }
        for bad in [0, 3] {
            let err = png(&analysis, Picture::Diff, Some(bad), (100, 100)).unwrap_err();
            assert!(matches!(err, Error::Core(close_core::Error::InvalidArgument(_))), "{err}");
        }
        // The fold circle follows the step: its other step's fold faded.
        let circles: Vec<Vec<u8>> = [None, Some(1), Some(2)]
            .into_iter()
            .map(|step| png(&analysis, Picture::Close, step, (240, 240)).unwrap())
            .collect();
        assert!(circles[0] != circles[1] && circles[1] != circles[2] && circles[0] != circles[2]);
        preview("step2_close.png", &circles[2]);
        assert!(matches!(
            png(&analysis, Picture::Thumbnail, Some(1), (100, 100)),
            Err(Error::Core(close_core::Error::InvalidArgument(_)))
        ));
    }

    #[test]
    fn start_and_end_disks_share_one_colour_scale() {
        // The first fold of a second-fold sample: the end disk holds far larger values.
        let analysis = builtin("napkin__half_then_half");
        let (start, end) = (analysis.disk(0).unwrap(), analysis.disk(2).unwrap());
        assert!(
            Scale::of(end.values()).s > 1.5 * Scale::of(start.values()).s,
            "the test needs panels of different ranges"
        );
        let size = 400;
        let layout = disk_picture::Layout::of(size, size);
        let pictures = [Picture::DiskStart, Picture::DiskEnd]
            .map(|p| decode(&png(&analysis, p, None, (size, size)).unwrap()).2);
        // Cells of equal value in both frames get the same colour in both panels.
        let n = start.n();
        let mut compared = 0;
        for i in 0..n {
            let j = (i + 1) % n;
            let (a, b) = (start.get(i, j), end.get(i, j));
            if (a - b).abs() > 1e-9 * a.abs().max(1.0) || a.abs() < 1e-6 {
                continue;
            }
            let p = close_core::disk::position(n, i.min(j), i.max(j));
            let (x, y) = layout.pixel(p.radius - 0.5 / (n / 2) as f64, p.angle);
            let k = (y as usize * size as usize + x as usize) * 3;
            assert_eq!(pictures[0][k..k + 3], pictures[1][k..k + 3], "cell ({i}, {j}) = {a}");
            compared += 1;
        }
        assert!(compared > 0, "no cell kept its value");
    }

    #[test]
    fn text_sizes_follow_the_shown_width() {
        for unit in [64.0, 200.0, SHOWN_WIDTH, 480.0, 1400.0, 2048.0] {
            // Shown 320 CSS px wide (the narrowest figure), 336 (a 420 px window), 400
            // (the lightbox at 420 px), 800 (the lightbox at 1400 px).
            for shown in [SHOWN_WIDTH, 336.0, 400.0, 800.0] {
                let css = note_size(unit) * shown / unit;
                assert!(css >= 12.0, "{unit} px shown at {shown} CSS px: text {css} CSS px");
            }
            assert!(label_size(unit) >= note_size(unit) && title_size(unit) >= label_size(unit));
        }
    }

    #[test]
    fn readable_colours_reach_aa_contrast() {
        assert!((contrast([0, 0, 0], PAPER) - 21.0).abs() < 1e-9);
        assert!(contrast(MUTED_TEXT, PAPER) >= TEXT_CONTRAST);
        // The old light grey did not.
        assert!(contrast(MUTED, PAPER) < TEXT_CONTRAST);
        for colour in FOLD_COLOURS.into_iter().chain([MUTED, [255, 255, 0], PAPER]) {
            let text = readable(colour);
            assert!(contrast(text, PAPER) >= TEXT_CONTRAST, "{colour:?} → {text:?}");
        }
        // A colour dark enough is kept.
        assert_eq!(readable(INK), INK);
    }

    /// Every `name="…"` attribute value of the `<text>` elements of an SVG.
    fn text_attributes<'a>(svg: &'a str, name: &str) -> Vec<&'a str> {
        let key = format!(" {name}=\"");
        svg.split("<text")
            .skip(1)
            .filter_map(|t| {
                t.split_once(&key).and_then(|(_, rest)| rest.split_once('"')).map(|(v, _)| v)
            })
            .collect()
    }

    #[test]
    fn every_text_drawn_is_large_enough_and_dark_enough() {
        let entry = close_io::dataset::Dataset::builtin()
            .entries()
            .iter()
            .find(|e| e.sample.mesh.is_some())
            .unwrap()
            .clone();
        let mesh_analysis =
            analyze(&entry.sample.border_frames().unwrap(), FrameRange::default()).unwrap();
        let view = mesh_picture::MeshView::of(entry.sample.mesh.as_ref().unwrap(), &mesh_analysis)
            .unwrap();
        let truth = truth::Truth::of(entry.sample.truth.as_ref().unwrap());
        let known = Known { truth: &truth, mesh: Some(&view) };
        for size in [420, 480, 1400] {
            let mut texts = 0;
            for picture in Picture::ALL.into_iter().chain([Picture::Mesh]) {
                let svg = String::from_utf8(
                    render(&mesh_analysis, &View::whole(picture), &Output::svg(size), known)
                        .unwrap(),
                )
                .unwrap();
                for px in text_attributes(&svg, "font-size") {
                    let px: f64 = px.parse().unwrap();
                    assert!(
                        px >= note_size(size as f64) - 0.01,
                        "{picture:?} at {size}: text of {px} px"
                    );
                    texts += 1;
                }
                for fill in text_attributes(&svg, "fill") {
                    let rgb: Vec<u8> = (0..3)
                        .map(|k| u8::from_str_radix(&fill[1 + 2 * k..3 + 2 * k], 16).unwrap())
                        .collect();
                    let ratio = contrast([rgb[0], rgb[1], rgb[2]], PAPER);
                    assert!(
                        ratio >= TEXT_CONTRAST,
                        "{picture:?}: text in {fill} has contrast {ratio:.2}"
                    );
                }
            }
            assert!(texts > 30, "only {texts} texts");
        }
    }

    #[test]
    fn sizes_are_clamped() {
        let analysis = folded_square(3, [0.0, PI]);
        for ((w, h), want) in [((1, 10_000), (MIN_SIZE, MAX_SIZE)), ((0, 0), (MIN_SIZE, MIN_SIZE))]
        {
            let (dw, dh, _) = decode(&png(&analysis, Picture::Close, None, (w, h)).unwrap());
            assert_eq!((dw, dh), want);
        }
    }
}
