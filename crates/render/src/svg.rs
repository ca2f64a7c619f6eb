//! The SVG form of a picture (`?format=svg`), drawn by the same code as its PNG.
//!
//! A picture is drawn twice over: fills (a disk's sectors, its colour bar, the charts plotters
//! draws) into pixels, and strokes and text ([`super::raster`]) anti-aliased on top. An SVG
//! canvas records the strokes and text as vector elements instead of pixels: polylines,
//! circles and text (DejaVu Sans, stretched with `textLength` to the width the PNG's layout
//! gives, so a viewer without the font places every label where the PNG does). The pixels
//! go under them as one embedded PNG of the same size, so the file scales and its text
//! stays text; a picture with no fills (the border plot: its axes are strokes and text too)
//! embeds no pixels at all.
//!
//! ```
//! use close_render::{render, Output, Picture, View};
//! # let analysis = close_core::analyze(&close_core::border::prepare(vec![vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]]; 2]).unwrap(), Default::default()).unwrap();
//! let svg = String::from_utf8(render(&analysis, &View::whole(Picture::Close), &Output::svg(300), Default::default()).unwrap()).unwrap();
//! assert!(svg.starts_with("<svg") && svg.contains("<text"));
//! ```

use std::fmt::Write;

use base64::Engine;

/// Vector elements in drawing order.
#[derive(Debug, Default)]
pub(crate) struct Vector(String);

/// `#rrggbb` of a colour.
fn hex([r, g, b]: [u8; 3]) -> String {
    format!("#{r:02x}{g:02x}{b:02x}")
}

/// `text` escaped for XML character data and attributes.
fn escape(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

impl Vector {
    /// A polyline `width` wide with round joins and caps (a single point: a disc of that
    /// diameter), as the raster stroke covers it.
    pub(crate) fn stroke(&mut self, points: &[(f64, f64)], width: f64, colour: [u8; 3]) {
        match points {
            [] => {}
            [(x, y)] => {
                let _ = write!(
                    self.0,
                    r#"<circle cx="{x:.2}" cy="{y:.2}" r="{:.2}" fill="{}"/>"#,
                    width / 2.0,
                    hex(colour)
                );
            }
            _ => {
                let list: Vec<String> =
                    points.iter().map(|(x, y)| format!("{x:.2},{y:.2}")).collect();
                let _ = write!(
                    self.0,
                    r#"<polyline points="{}" fill="none" stroke="{}" stroke-width="{width:.2}" stroke-linejoin="round" stroke-linecap="round"/>"#,
                    list.join(" "),
                    hex(colour)
                );
            }
        }
    }

    /// `text` of `size` px with its left end at `left` and its baseline at `baseline`,
    /// `width` px long as the PNG lays it out.
    pub(crate) fn text(
        &mut self,
        text: &str,
        (left, baseline): (f64, f64),
        size: f64,
        width: f64,
        colour: [u8; 3],
    ) {
        let _ = write!(
            self.0,
            r#"<text x="{left:.2}" y="{baseline:.2}" font-size="{size:.2}" textLength="{width:.2}" lengthAdjust="spacingAndGlyphs" fill="{}">{}</text>"#,
            hex(colour),
            escape(text)
        );
    }

    /// The SVG document: the pixels (`png`, `width`×`height`) under the vector elements;
    /// without pixels (a picture drawn only in strokes and text), a white background.
    pub(crate) fn document(&self, width: u32, height: u32, png: Option<&[u8]>) -> String {
        let under = match png {
            Some(png) => format!(
                r#"<image width="{width}" height="{height}" href="data:image/png;base64,{}"/>"#,
                base64::engine::general_purpose::STANDARD.encode(png)
            ),
            None => format!(r##"<rect width="{width}" height="{height}" fill="#ffffff"/>"##),
        };
        format!(
            concat!(
                r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="DejaVu Sans, Verdana, sans-serif">"#,
                "{under}{body}</svg>"
            ),
            w = width,
            h = height,
            under = under,
            body = self.0
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn elements_are_escaped_and_coloured() {
        let mut v = Vector::default();
        v.stroke(&[(1.0, 2.0), (3.0, 4.0)], 2.0, [255, 0, 16]);
        v.stroke(&[(5.0, 5.0)], 4.0, [0, 0, 0]);
        v.text("a < b & \"c\"", (0.0, 10.0), 12.0, 40.0, [40, 40, 40]);
        let doc = v.document(10, 20, Some(b"png"));
        assert!(doc.contains(r##"stroke="#ff0010""##) && doc.contains(r#"r="2.00""#), "{doc}");
        assert!(doc.contains("a &lt; b &amp; &quot;c&quot;"), "{doc}");
        assert!(doc.contains(r#"viewBox="0 0 10 20""#) && doc.contains("base64,cG5n"), "{doc}");
        let vector_only = v.document(10, 20, None);
        assert!(!vector_only.contains("<image") && vector_only.contains("<rect"), "{vector_only}");
    }
}
