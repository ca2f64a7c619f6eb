//! Wavefront OBJ frames: `v x y z` vertices and `f a b c …` polygons (1-based, `a/t/n`
//! forms and negative, relative indices allowed); every other statement is skipped
//! (format: Wavefront's "Object Files (.obj)", Advanced Visualizer manual, Appendix B).
//! Vertex and corner counts are bounded while reading ([`MAX_MESH_VERTICES`],
//! [`MAX_FACE_CORNERS`]).
//!
//! Read directly rather than with `tobj`: tobj renumbers vertices in the order faces first
//! use them and drops unused ones (and reads `f32` unless a feature is on), while a
//! sample's frames are matched by the file's own vertex order and `border_indices` must be
//! the file's vertex numbers.
//!
//! ```
//! use close_io::formats::obj::parse_frame;
//! let m = parse_frame(b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1/1/1 2/2/2 3/3/3 -1\n").unwrap();
//! assert_eq!(m.faces, vec![vec![0, 1, 2, 3]]);
//! assert!(parse_frame(b"v 0 0 0\nf 1 2 3\n").unwrap_err().to_string().contains("vertex 2"));
//! ```

use super::{MeshFrame, MAX_FILE_BYTES};
use crate::error::{Error, Format, Result};
use crate::mesh::{MAX_FACE_CORNERS, MAX_MESH_VERTICES};
use close_core::error::MeshError;
use close_core::Error as CoreError;

fn bad(line: usize, message: impl ToString) -> Error {
    Error::parse_at(Format::Obj, line, message)
}

/// Parse one OBJ file.
pub fn parse_frame(bytes: &[u8]) -> Result<MeshFrame> {
    if bytes.len() > MAX_FILE_BYTES {
        return Err(Error::too_large("bytes of OBJ", bytes.len(), MAX_FILE_BYTES));
    }
    let text = std::str::from_utf8(bytes)
        .map_err(|e| Error::parse(Format::Obj, format!("not UTF-8 text ({e})")))?;
    let mut mesh = MeshFrame::default();
    let mut corners = 0usize;
    for (k, line) in text.lines().enumerate() {
        let line_no = k + 1;
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                if mesh.vertices.len() >= MAX_MESH_VERTICES {
                    return Err(Error::over_limit("mesh vertices", MAX_MESH_VERTICES));
                }
                let mut xyz = [0.0; 3];
                for (c, axis) in xyz.iter_mut().zip(["x", "y", "z"]) {
                    let word = words.next().ok_or_else(|| bad(line_no, "a vertex needs x y z"))?;
                    *c = word.parse().map_err(|_| {
                        bad(line_no, format!("the vertex's {axis} is not a number"))
                    })?;
                }
                mesh.vertices.push(xyz);
            }
            Some("f") => {
                let face = words
                    .map(|w| corner(w, mesh.vertices.len(), line_no))
                    .collect::<Result<Vec<_>>>()?;
                if face.len() < 3 {
                    return Err(bad(
                        line_no,
                        format!("a face needs at least 3 vertices, got {}", face.len()),
                    ));
                }
                corners += face.len();
                if corners > MAX_FACE_CORNERS {
                    return Err(Error::over_limit("face corners", MAX_FACE_CORNERS));
                }
                mesh.faces.push(face);
            }
            _ => {}
        }
    }
    if mesh.vertices.is_empty() {
        return Err(CoreError::Empty { what: "the OBJ file holds no vertex" }.into());
    }
    let n = mesh.vertices.len();
    if let Some((k, &v)) =
        mesh.faces.iter().enumerate().find_map(|(k, f)| f.iter().find(|&&v| v >= n).map(|v| (k, v)))
    {
        // OBJ counts vertices from 1: name the vertex as the file does.
        return Err(MeshError::VertexOutOfRange { face: k, vertex: v + 1, vertices: n }.into());
    }
    Ok(mesh)
}

/// One face corner `v`, `v/t`, `v//n` or `v/t/n` → 0-based vertex index.
fn corner(word: &str, defined: usize, line: usize) -> Result<usize> {
    let v = word.split('/').next().unwrap_or(word);
    let index: i64 = v.parse().map_err(|_| bad(line, "a face corner is not a vertex index"))?;
    match index {
        0 => Err(bad(line, "vertex index 0 (OBJ counts from 1)")),
        // Negative indices count back from the last vertex defined so far.
        i if i < 0 => usize::try_from(defined as i64 + i)
            .map_err(|_| bad(line, format!("relative index {i} reaches before the first vertex"))),
        i => {
            usize::try_from(i - 1).map_err(|_| bad(line, format!("vertex index {i} is too large")))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn skips_other_statements_and_keeps_vertex_order() {
        let m = parse_frame(b"# c\nmtllib x.mtl\no a\nv 3 0 0\nvn 0 0 1\nv 0 3 0\nvt 0 0\nv 0 0 3\ns off\nf 3//1 1//1 2//1\n").unwrap();
        assert_eq!(m.vertices[0], [3.0, 0.0, 0.0]);
        assert_eq!(m.faces, vec![vec![2, 0, 1]]);
    }

    #[test]
    fn bad_lines_are_named() {
        for (doc, what) in [
            (&b""[..], "no vertex"),
            (b"v 1 2\n", "line 1"),
            (b"v 0 0 0\nv 1 x 0\n", "line 2"),
            (b"v 0 0 0\nf 1 1\n", "at least 3"),
            (b"v 0 0 0\nf 0 1 1\n", "index 0"),
            (b"v 0 0 0\nf -2 1 1\n", "before the first"),
            (b"\xff\xfe", "UTF-8"),
        ] {
            let err = parse_frame(doc).unwrap_err().to_string();
            assert!(err.contains(what), "{err}");
        }
    }
}
