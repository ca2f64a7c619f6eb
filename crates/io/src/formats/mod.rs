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
//!
//! A file's bytes are read bounded by [`read_file`] (a file a walk listed, [`read_listed`]), and
//! written whole or not at all by [`write_atomic`].

pub mod json;
pub mod mat;
pub mod obj;
pub mod ply;
pub mod text;

mod files;
pub use files::{read_file, read_file_io, read_listed, write_atomic, FileId, ReadError};

use serde::{Deserialize, Serialize};

use crate::error::{Error, Format, Result};
use close_core::border::{prepare, BorderFrames, MAX_FRAMES};
use close_core::error::MeshError;
use close_core::geometry::Fold;
use close_core::Error as CoreError;
// Mesh frames belong to `mesh` (formats reads files into them); re-exported for callers.
pub use crate::mesh::MeshFrames;

/// Largest input file the readers accept.
pub const MAX_FILE_BYTES: usize = 64 * 1024 * 1024;
/// Most characters of a library's message (about the user's file) an error keeps.
pub const MESSAGE_CHARS: usize = 200;

/// The name a file's own header gives (a PLY element, a MATLAB variable) as an error may
/// name it: a word of at most 32 ASCII letters, digits and `_`; anything else is not quoted.
pub(crate) fn identifier(name: &str) -> Option<&str> {
    let plain = name.len() <= 32 && name.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_');
    (plain && !name.is_empty()).then_some(name)
}

/// A library's message about a user's file, made safe to show: at most [`MESSAGE_CHARS`]
/// characters of its first line, and nothing it quotes of the file. A parser's message may
/// quote the text it could not read (serde's `invalid type: string "…"`, a PLY line in
/// `'…'`); errors name where and what is wrong, never the file's contents, so a file that
/// is not what it seems (a link to `/etc/passwd` in a dataset folder) leaks nothing.
///
/// ```
/// # use close_io::formats::redact;
/// assert_eq!(redact(r#"invalid type: string "root:x:0", expected a number at line 1"#),
///            r#"invalid type: string "…", expected a number at line 1"#);
/// assert_eq!(redact("Couldn't parse 'v 1 2' here.\n\tString: 'secret'"),
///            "Couldn't parse '…' here.");
/// ```
pub fn redact(message: &str) -> String {
    let line = message.lines().next().unwrap_or_default();
    let mut out = String::new();
    let mut chars = line.chars().peekable();
    let mut before = ' ';
    while let Some(c) = chars.next() {
        // An apostrophe inside a word ("couldn't") opens no quote.
        let opens = c == '"' || (c == '\'' && (before.is_whitespace() || "([{:=".contains(before)));
        before = c;
        if !opens {
            out.push(c);
            continue;
        }
        out.push(c);
        out.push('…');
        while let Some(q) = chars.next() {
            match q {
                '\\' => {
                    chars.next();
                }
                q if q == c => break,
                _ => {}
            }
        }
        out.push(c);
    }
    match out.char_indices().nth(MESSAGE_CHARS) {
        Some((cut, _)) => format!("{}…", &out[..cut]),
        None => out,
    }
}

/// Known fold of a sample (ground truth), angles in the border convention (vertex k at 2πk/N).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Truth {
    /// The known folds, each (f1, f2) in [0, 2π) (radians).
    #[serde(default, deserialize_with = "json::truth_folds")]
    pub folds: Vec<Fold>,
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "json::folded_vertices"
    )]
    pub folded_vertices: Option<Vec<usize>>,
    /// Per fold, the vertices it turned over (a fold of several arcs is known by them).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "json::folded_vertices_per_fold"
    )]
    pub folded_vertices_per_fold: Option<Vec<Vec<usize>>>,
}

/// One mesh file: a frame's vertex positions and its faces (polygons of vertex indices).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MeshFrame {
    pub vertices: Vec<[f64; 3]>,
    pub faces: Vec<Vec<usize>>,
}

/// One cloth sample: border frames (or a mesh), frame 0 the flat start.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Sample {
    #[serde(default)]
    pub name: String,
    #[serde(default)]
    pub category: String,
    #[serde(
        default,
        skip_serializing_if = "Vec::is_empty",
        deserialize_with = "json::border_frames"
    )]
    pub frames: Vec<Vec<[f64; 3]>>,
    #[serde(default, skip_serializing_if = "Option::is_none", deserialize_with = "json::mesh")]
    pub mesh: Option<MeshFrames>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub truth: Option<Truth>,
}

impl Sample {
    /// A border sample from frames.
    pub fn from_frames(
        name: impl Into<String>,
        category: impl Into<String>,
        frames: Vec<Vec<[f64; 3]>>,
    ) -> Sample {
        Sample { name: name.into(), category: category.into(), frames, mesh: None, truth: None }
    }

    /// Bytes the sample holds on the heap: its positions (24 bytes a vertex a frame), and a
    /// mesh's faces (a list each: its 24-byte header and 8 bytes a corner) and border edges;
    /// what a cache of samples must count.
    pub fn weight(&self) -> usize {
        let positions = |frames: &[Vec<[f64; 3]>]| 24 * frames.iter().map(Vec::len).sum::<usize>();
        let mesh = self.mesh.as_ref().map_or(0, |m| {
            positions(&m.frames)
                + m.faces.iter().map(|f| 24 + 8 * f.len()).sum::<usize>()
                + 16 * m.border_edges.len()
        });
        positions(&self.frames) + mesh
    }

    /// Refuse the analysis of frames `range` over `budget` before its border is prepared
    /// (a copy of every frame), when that is known from the sample alone: every frame of a
    /// border sample. A frame range or a mesh (whose border is shorter than its vertex
    /// list) is checked by the analysis once its border is known.
    ///
    /// ```
    /// use close_core::{budget::Budget, FrameRange};
    /// let square = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
    /// let sample = close_io::Sample::from_frames("", "", vec![square; 3]);
    /// let tight = Budget { max_cells: 40, ..Budget::default() }; // 3 frames × 4² = 48 cells
    /// assert!(sample.check_budget(FrameRange::default(), &tight).is_err());
    /// let two = FrameRange { start: Some(1), end: None };
    /// assert!(sample.check_budget(two, &tight).is_ok()); // checked once its border is known
    /// ```
    pub fn check_budget(
        &self,
        range: close_core::FrameRange,
        budget: &close_core::budget::Budget,
    ) -> close_core::Result<()> {
        match (self.frames.first(), range) {
            (Some(first), close_core::FrameRange { start: None, end: None }) => {
                budget.analysis(self.frames.len(), first.len())
            }
            _ => Ok(()),
        }
    }

    /// Validate and orient the border frames ([`prepare`]). For a mesh, the border is
    /// found on frame 0 and `border_indices` are mesh vertex indices.
    pub fn border_frames(&self) -> close_core::Result<BorderFrames> {
        match (&self.mesh, self.frames.is_empty()) {
            (Some(_), false) => Err(CoreError::InvalidArgument(
                "give either \"frames\" or \"mesh\", not both".into(),
            )),
            (Some(mesh), true) => {
                let found = crate::mesh::border_of(mesh)?;
                let raw = mesh
                    .frames
                    .iter()
                    .map(|frame| found.indices.iter().map(|&k| frame[k]).collect())
                    .collect();
                let mut border = prepare(raw)?;
                // prepare's indices point into the gathered border; map them to the mesh.
                border.border_indices =
                    border.border_indices.iter().map(|&k| found.indices[k]).collect();
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
        return Err(CoreError::Empty { what: "no file given" }.into());
    };
    let single = |what: &str| {
        if files.len() > 1 {
            return Err(Error::invalid(format!(
                "give one {what} file, or one text or mesh file per frame"
            )));
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
        other => Err(Error::invalid(format!(
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
            other => {
                Err(Error::invalid(format!("a mesh sample takes .obj or .ply files, not .{other}")))
            }
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
    Ok(Sample {
        name,
        category: "upload".into(),
        frames: Vec::new(),
        mesh: Some(MeshFrames::new(faces, frames)),
        truth: None,
    })
}
