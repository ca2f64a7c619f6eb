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
    #[serde(default)]
    pub faces: Vec<Vec<usize>>,
    pub frames: Vec<Vec<[f64; 3]>>,
    /// Border edges given by the file (the MATLAB data's `Eb`, 0-based here); when present
    /// they define the border and the faces may be empty.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub border_edges: Vec<[usize; 2]>,
}

impl MeshFrames {
    /// A mesh from faces and frames of vertex positions.
    pub fn new(faces: Vec<Vec<usize>>, frames: Vec<Vec<[f64; 3]>>) -> MeshFrames {
        MeshFrames { faces, frames, border_edges: Vec::new() }
    }
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

    /// Validate and orient the border frames (SPEC §1, Border). For a mesh, the border is
    /// found on frame 0 and `border_indices` are mesh vertex indices.
    pub fn border_frames(&self) -> Result<BorderFrames> {
        match (&self.mesh, self.frames.is_empty()) {
            (Some(_), false) => Err(Error::parse("sample JSON", "give either \"frames\" or \"mesh\", not both")),
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

/// Put the file's name in front of an error's message, so a user knows which file is bad.
fn in_file(name: &str, error: Error) -> Error {
    let name = base_name(name);
    match error {
        Error::Parse { format, message } => Error::Parse { format, message: format!("{name}: {message}") },
        Error::Empty(m) => Error::Empty(format!("{name}: {m}")),
        Error::TooLarge(m) => Error::TooLarge(format!("{name}: {m}")),
        Error::Mesh(m) => Error::Mesh(format!("{name}: {m}")),
        other => other,
    }
}

/// Read a sample from named files: one Sample JSON or `.mat` file, text/CSV files with
/// one frame each, or OBJ/PLY mesh files with one frame each (in the order given).
pub fn read_files(files: &[(String, Vec<u8>)]) -> Result<Sample> {
    let Some((first, _)) = files.first() else {
        return Err(Error::Empty("no file given".into()));
    };
    let single = |what: &str| {
        if files.len() > 1 {
            return Err(Error::InvalidArgument(format!("give one {what} file, or one text or mesh file per frame")));
        }
        Ok(&files[0].1)
    };
    let name = base_name(first).to_string();
    match extension(first).as_str() {
        "json" => json::parse_sample(single("Sample JSON")?),
        "mat" => mat::parse_sample(single("MATLAB .mat")?, &name).map_err(|e| in_file(first, e)),
        "obj" | "ply" => read_mesh_files(files, name),
        "txt" | "csv" | "xyz" | "dat" | "" => {
            let frames = files
                .iter()
                .map(|(name, bytes)| {
                    let text = std::str::from_utf8(bytes).map_err(|_| Error::parse("text", format!("{name} is not UTF-8 text")))?;
                    text::parse_frame(text).map_err(|e| in_file(name, e))
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
    let mut frames: Vec<Vec<[f64; 3]>> = Vec::with_capacity(files.len().min(crate::border::MAX_FRAMES));
    if files.len() > crate::border::MAX_FRAMES {
        return Err(Error::TooLarge(format!("{} frame files (at most {})", files.len(), crate::border::MAX_FRAMES)));
    }
    for (k, (file, bytes)) in files.iter().enumerate() {
        let frame = match extension(file).as_str() {
            "obj" => obj::parse_frame(bytes),
            "ply" => ply::parse_frame(bytes),
            other => Err(Error::InvalidArgument(format!("a mesh sample takes .obj or .ply files, not .{other}"))),
        }
        .map_err(|e| in_file(file, e))?;
        if let Some(expected) = frames.first().map(Vec::len) {
            if frame.vertices.len() != expected {
                return Err(Error::Mesh(format!(
                    "{} has {} vertices but {} has {expected}: every frame file must list the same vertices in the same order",
                    base_name(file),
                    frame.vertices.len(),
                    base_name(&files[0].0)
                )));
            }
        }
        if k == 0 {
            faces = frame.faces;
        }
        frames.push(frame.vertices);
    }
    if faces.is_empty() {
        return Err(Error::Mesh(format!("{name} has no face: a mesh sample needs the faces in its first file")));
    }
    Ok(Sample { name, category: "upload".into(), frames: Vec::new(), mesh: Some(MeshFrames::new(faces, frames)), truth: None })
}
