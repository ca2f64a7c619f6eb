//! PLACEHOLDER (the render branch replaces this): a blank PNG of the asked size.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Picture {
    DiskStart,
    DiskEnd,
    Diff,
    SignedDiff,
    Close,
    Borders,
}

impl Picture {
    pub const ALL: [Picture; 6] = [Picture::DiskStart, Picture::DiskEnd, Picture::Diff, Picture::SignedDiff, Picture::Close, Picture::Borders];

    pub fn name(self) -> &'static str {
        match self {
            Picture::DiskStart => "disk_start",
            Picture::DiskEnd => "disk_end",
            Picture::Diff => "diff",
            Picture::SignedDiff => "signed_diff",
            Picture::Close => "close",
            Picture::Borders => "borders",
        }
    }

    pub fn from_name(name: &str) -> Option<Picture> {
        Picture::ALL.into_iter().find(|p| p.name() == name)
    }
}

pub const DEFAULT_SIZE: u32 = 480;

pub fn render_png(_analysis: &crate::Analysis, _picture: Picture, width: u32, height: u32) -> Result<Vec<u8>> {
    let (w, h) = (width.clamp(64, 2048), height.clamp(64, 2048));
    let mut out = Vec::new();
    let mut enc = png::Encoder::new(&mut out, w, h);
    enc.set_color(png::ColorType::Grayscale);
    let mut writer = enc.write_header().map_err(|e| Error::InvalidArgument(e.to_string()))?;
    writer.write_image_data(&vec![200u8; (w * h) as usize]).map_err(|e| Error::InvalidArgument(e.to_string()))?;
    writer.finish().map_err(|e| Error::InvalidArgument(e.to_string()))?;
    Ok(out)
}
