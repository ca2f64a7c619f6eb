//! Files a user brings, all read into one [`Sample`] type.
//!
//! - Sample JSON ([`json`]): `{"name", "category", "frames": [[[x,y,z], …], …]}`, or a
//!   `"mesh"` with faces and frames; optional `"truth"`.
//! - Plain text / CSV ([`text`]): one vertex `x,y,z` (or `x y z`) per line, one file per frame.

pub mod json;
pub mod text;

use serde::{Deserialize, Serialize};

use crate::border::{prepare, BorderFrames};
use crate::error::{Error, Result};

/// Largest input file the readers accept.
pub const MAX_FILE_BYTES: usize = 64 * 1024 * 1024;

/// Known fold of a sample (ground truth), angles in the SPEC convention (2πf/N).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct Truth {
    #[serde(default)]
    pub folds: Vec<[f64; 2]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub folded_vertices: Option<Vec<usize>>,
}

/// A triangle (or polygon) mesh followed through frames by vertex index.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MeshFrames {
    pub faces: Vec<Vec<usize>>,
    pub frames: Vec<Vec<[f64; 3]>>,
}

/// One cloth sample: border frames (or a mesh), frame 0 the flat start.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Sample {
    #[serde(default)]
    pub name: String,
    #[serde(default)]
    pub category: String,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub frames: Vec<Vec<[f64; 3]>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mesh: Option<MeshFrames>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub truth: Option<Truth>,
}

impl Sample {
    /// A border sample from frames.
    pub fn from_frames(name: impl Into<String>, category: impl Into<String>, frames: Vec<Vec<[f64; 3]>>) -> Sample {
        Sample { name: name.into(), category: category.into(), frames, mesh: None, truth: None }
    }

    /// Validate and orient the border frames (SPEC §1, Border).
    pub fn border_frames(&self) -> Result<BorderFrames> {
        match (&self.mesh, self.frames.is_empty()) {
            (Some(_), false) => Err(Error::parse("sample JSON", "give either \"frames\" or \"mesh\", not both")),
            (Some(_), true) => Err(Error::Mesh("mesh samples are not supported yet: give border frames".into())),
            (None, _) => prepare(self.frames.clone()),
        }
    }
}

/// The kind of file a name announces.
fn extension(name: &str) -> String {
    name.rsplit_once('.').map(|(_, e)| e.to_ascii_lowercase()).unwrap_or_default()
}

/// Read a sample from named files: one Sample JSON, or text/CSV files with one frame each
/// (in the order given).
pub fn read_files(files: &[(String, Vec<u8>)]) -> Result<Sample> {
    let Some((first, _)) = files.first() else {
        return Err(Error::Empty("no file given".into()));
    };
    match extension(first).as_str() {
        "json" => {
            if files.len() > 1 {
                return Err(Error::InvalidArgument("give one Sample JSON file, or one text file per frame".into()));
            }
            json::parse_sample(&files[0].1)
        }
        "txt" | "csv" | "xyz" | "dat" | "" => {
            let frames = files
                .iter()
                .map(|(name, bytes)| {
                    let text = std::str::from_utf8(bytes).map_err(|_| Error::parse("text", format!("{name} is not UTF-8 text")))?;
                    text::parse_frame(text).map_err(|e| match e {
                        Error::Parse { format, message } => Error::Parse { format, message: format!("{name}: {message}") },
                        other => other,
                    })
                })
                .collect::<Result<Vec<_>>>()?;
            let name = first.rsplit('/').next().unwrap_or(first).to_string();
            Ok(Sample::from_frames(name, "upload", frames))
        }
        other => Err(Error::InvalidArgument(format!(
            "unknown file type .{other}: expected .json (Sample JSON) or .txt/.csv (one vertex per line)"
        ))),
    }
}
