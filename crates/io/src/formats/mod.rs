//! Files a user brings, all read into one [`Sample`] type.
//!
//! - Sample JSON ([`json`]): `{"name", "category", "frames": [[[x,y,z], …], …]}`, or a
//!   `"mesh"` with faces and frames; optional `"truth"`.
//! - Plain text / CSV ([`text`]): one vertex `x,y,z` (or `x y z`) per line, one file per frame.
//! - Wavefront OBJ ([`obj`]) and PLY ([`ply`], ASCII and binary): one mesh file per frame,
//!   same vertices in the same order; the faces come from the first file.
//! - MATLAB v5 `.mat` ([`mat`]): the paper's `phiPositions` (positions per frame) and `Eb`
//!   (border edges).
//!
//! A mesh sample's border is found by [`crate::mesh::border_of`] and followed by vertex index.

pub mod json;
pub mod mat;
pub mod obj;
pub mod ply;
pub mod text;

use serde::{Deserialize, Serialize};

use crate::border::{prepare, BorderFrames, MAX_FRAMES};
use crate::error::{Error, Format, MeshError, Result};
// Mesh frames belong to `mesh` (formats reads files into them); re-exported for callers.
pub use crate::mesh::MeshFrames;

/// Largest input file the readers accept.
pub const MAX_FILE_BYTES: usize = 64 * 1024 * 1024;

/// Known fold of a sample (ground truth), angles in the border convention (vertex k at 2πk/N).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct Truth {
    #[serde(default, deserialize_with = "json::truth_folds")]
    pub folds: Vec<[f64; 2]>,
    #[serde(default, skip_serializing_if = "Option::is_none", deserialize_with = "json::folded_vertices")]
    pub folded_vertices: Option<Vec<usize>>,
}

/// One mesh file: a frame's vertex positions and its faces (polygons of vertex indices).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MeshFrame {
    pub vertices: Vec<[f64; 3]>,
    pub faces: Vec<Vec<usize>>,
}

/// One cloth sample: border frames (or a mesh), frame 0 the flat start.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Sample {
    #[serde(default)]
    pub name: String,
    #[serde(default)]
    pub category: String,
    #[serde(default, skip_serializing_if = "Vec::is_empty", deserialize_with = "json::border_frames")]
    pub frames: Vec<Vec<[f64; 3]>>,
    #[serde(default, skip_serializing_if = "Option::is_none", deserialize_with = "json::mesh")]
    pub mesh: Option<MeshFrames>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub truth: Option<Truth>,
}

impl Sample {
    /// A border sample from frames.
    pub fn from_frames(name: impl Into<String>, category: impl Into<String>, frames: Vec<Vec<[f64; 3]>>) -> Sample {
        Sample { name: name.into(), category: category.into(), frames, mesh: None, truth: None }
    }

    /// Validate and orient the border frames ([`prepare`]). For a mesh, the border is
    /// found on frame 0 and `border_indices` are mesh vertex indices.
    pub fn border_frames(&self) -> Result<BorderFrames> {
        match (&self.mesh, self.frames.is_empty()) {
            (Some(_), false) => Err(Error::parse(Format::SampleJson, "give either \"frames\" or \"mesh\", not both")),
            (Some(mesh), true) => {
                let found = crate::mesh::border_of(mesh)?;
                let raw = mesh.frames.iter().map(|frame| found.indices.iter().map(|&k| frame[k]).collect()).collect();
                let mut border = prepare(raw)?;
                // prepare's indices point into the gathered border; map them to the mesh.
                border.border_indices = border.border_indices.iter().map(|&k| found.indices[k]).collect();
                border.source = found.method.name().into();
                Ok(border)
            }
            (None, _) => prepare(self.frames.clone()),
        }
    }
}

/// The kind of file a name announces.
fn extension(name: &str) -> String {
    name.rsplit_once('.').map(|(_, e)| e.to_ascii_lowercase()).unwrap_or_default()
}

/// The file name without folders.
fn base_name(path: &str) -> &str {
    path.rsplit(['/', '\\']).next().unwrap_or(path)
}

/// Read a sample from named files: one Sample JSON or `.mat` file, text/CSV files with
/// one frame each, or OBJ/PLY mesh files with one frame each (in the order given).
pub fn read_files(files: &[(String, Vec<u8>)]) -> Result<Sample> {
    let Some((first, _)) = files.first() else {
        return Err(Error::Empty { what: "no file given" });
    };
    let single = |what: &str| {
        if files.len() > 1 {
            return Err(Error::InvalidArgument(format!("give one {what} file, or one text or mesh file per frame")));
        }
        Ok(&files[0].1)
    };
    let name = base_name(first).to_string();
    match extension(first).as_str() {
        "json" => json::parse_sample(single("Sample JSON")?).map_err(|e| e.in_file(first)),
        "mat" => mat::parse_sample(single("MATLAB .mat")?, &name).map_err(|e| e.in_file(first)),
        "obj" | "ply" => read_mesh_files(files, name),
        "txt" | "csv" | "xyz" | "dat" | "" => {
            let frames = files
                .iter()
                .map(|(name, bytes)| {
                    let text = std::str::from_utf8(bytes).map_err(|_| Error::parse(Format::Text, "not UTF-8 text").in_file(name))?;
                    text::parse_frame(text).map_err(|e| e.in_file(name))
                })
                .collect::<Result<Vec<_>>>()?;
            Ok(Sample::from_frames(name, "upload", frames))
        }
        other => Err(Error::InvalidArgument(format!(
            "unknown file type .{other}: expected .json (Sample JSON), .txt/.csv (one vertex per line), .obj/.ply (one mesh per frame) or .mat"
        ))),
    }
}

/// OBJ/PLY files, one frame each: faces from the first, the same vertex count in all.
fn read_mesh_files(files: &[(String, Vec<u8>)], name: String) -> Result<Sample> {
    let mut faces = Vec::new();
    if files.len() > MAX_FRAMES {
        return Err(Error::too_large("frame files", files.len(), MAX_FRAMES));
    }
    let mut frames: Vec<Vec<[f64; 3]>> = Vec::with_capacity(files.len());
    for (k, (file, bytes)) in files.iter().enumerate() {
        let frame = match extension(file).as_str() {
            "obj" => obj::parse_frame(bytes),
            "ply" => ply::parse_frame(bytes),
            other => Err(Error::InvalidArgument(format!("a mesh sample takes .obj or .ply files, not .{other}"))),
        }
        .map_err(|e| e.in_file(file))?;
        if let Some(expected) = frames.first().map(Vec::len) {
            if frame.vertices.len() != expected {
                return Err(MeshError::FrameFileMismatch {
                    file: base_name(file).into(),
                    got: frame.vertices.len(),
                    first: base_name(&files[0].0).into(),
                    expected,
                }
                .into());
            }
        }
        if k == 0 {
            faces = frame.faces;
        }
        frames.push(frame.vertices);
    }
    if faces.is_empty() {
        return Err(Error::from(MeshError::NoFaces).in_file(&name));
    }
    Ok(Sample { name, category: "upload".into(), frames: Vec::new(), mesh: Some(MeshFrames::new(faces, frames)), truth: None })
}
