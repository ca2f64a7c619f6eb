//! PLY frames (ASCII, binary little and big endian), read with `ply-rs-bw`.
//!
//! The `vertex` element gives positions from its `x`, `y`, `z` properties (any scalar
//! type); the `face` element gives polygons from its `vertex_indices` (or `vertex_index`)
//! list. Other elements and properties are read past and ignored. Element counts are
//! checked against the file size and the mesh limits before anything is read, so a header
//! announcing billions of vertices is refused without allocating for them.
//!
//! ```
//! use close::formats::ply::parse_frame;
//! let doc = b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
//! element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
//! let m = parse_frame(doc).unwrap();
//! assert_eq!((m.vertices.len(), m.faces.clone()), (3, vec![vec![0, 1, 2]]));
//! assert!(parse_frame(b"obj\n").unwrap_err().to_string().contains("not a PLY file"));
//! ```

use ply_rs_bw::parser::{Parser, Reader};
use ply_rs_bw::ply::{ElementDef, Encoding, Property, PropertyAccess, PropertyAccessResult, PropertyType};

use super::{MeshFrame, MAX_FILE_BYTES};
use crate::error::{Error, Result};
use crate::mesh::{MAX_FACE_CORNERS, MAX_MESH_FACES, MAX_MESH_VERTICES};

/// A scalar property as f64; `None` for lists.
fn scalar(p: &Property) -> Option<f64> {
    Some(match *p {
        Property::Char(v) => v.into(),
        Property::UChar(v) => v.into(),
        Property::Short(v) => v.into(),
        Property::UShort(v) => v.into(),
        Property::Int(v) => v.into(),
        Property::UInt(v) => v.into(),
        Property::Float(v) => v.into(),
        Property::Double(v) => v,
        _ => return None,
    })
}

/// A list property as signed integers; `None` for scalars and float lists.
fn index_list(p: Property) -> Option<Vec<i64>> {
    Some(match p {
        Property::ListChar(v) => v.into_iter().map(i64::from).collect(),
        Property::ListUChar(v) => v.into_iter().map(i64::from).collect(),
        Property::ListShort(v) => v.into_iter().map(i64::from).collect(),
        Property::ListUShort(v) => v.into_iter().map(i64::from).collect(),
        Property::ListInt(v) => v.into_iter().map(i64::from).collect(),
        Property::ListUInt(v) => v.into_iter().map(i64::from).collect(),
        _ => return None,
    })
}

#[derive(Debug, Default)]
struct Vertex([f64; 3]);

impl PropertyAccess for Vertex {
    fn new() -> Self {
        Vertex::default()
    }
    fn set_property(&mut self, name: &str, property: Property) -> PropertyAccessResult {
        let axis = match name {
            "x" => 0,
            "y" => 1,
            "z" => 2,
            _ => return PropertyAccessResult::Ignored,
        };
        match scalar(&property) {
            Some(v) => {
                self.0[axis] = v;
                PropertyAccessResult::Set
            }
            None => PropertyAccessResult::UnsupportedType,
        }
    }
}

#[derive(Debug, Default)]
struct Face(Vec<i64>);

impl PropertyAccess for Face {
    fn new() -> Self {
        Face::default()
    }
    fn set_property(&mut self, name: &str, property: Property) -> PropertyAccessResult {
        if name != "vertex_indices" && name != "vertex_index" {
            return PropertyAccessResult::Ignored;
        }
        match index_list(property) {
            Some(list) => {
                self.0 = list;
                PropertyAccessResult::Set
            }
            None => PropertyAccessResult::UnsupportedType,
        }
    }
}

/// Elements read past.
struct Skip;

impl PropertyAccess for Skip {
    fn new() -> Self {
        Skip
    }
}

fn bad(message: impl ToString) -> Error {
    Error::parse("PLY", message)
}

/// Refuse counts the file cannot hold or the limits forbid, before reading the payload.
fn check_counts(elements: &[&ElementDef], payload_bytes: usize) -> Result<()> {
    for e in elements {
        // Every element with a property takes at least one byte (binary) or one character.
        if !e.properties.is_empty() && e.count > payload_bytes {
            return Err(bad(format!("the header announces {} {} elements but only {payload_bytes} bytes follow (truncated file?)", e.count, e.name)));
        }
        let limit = match e.name.as_str() {
            "vertex" => MAX_MESH_VERTICES,
            "face" => MAX_MESH_FACES,
            _ => continue,
        };
        if e.count > limit {
            return Err(Error::TooLarge(format!("{} {} elements (at most {limit})", e.count, e.name)));
        }
    }
    Ok(())
}

/// Parse one PLY file.
pub fn parse_frame(bytes: &[u8]) -> Result<MeshFrame> {
    if bytes.len() > MAX_FILE_BYTES {
        return Err(Error::TooLarge(format!("{} bytes of PLY (at most {MAX_FILE_BYTES})", bytes.len())));
    }
    if !(bytes.starts_with(b"ply\n") || bytes.starts_with(b"ply\r\n")) {
        return Err(bad("not a PLY file (it must start with the line \"ply\")"));
    }
    let mut reader = Reader::new(bytes);
    let header = Parser::<Skip>::new().read_header(&mut reader).map_err(|e| bad(format!("header: {e}")))?;
    let elements: Vec<&ElementDef> = header.elements.values().collect();
    let header_end = bytes.windows(10).position(|w| w == b"end_header").unwrap_or(0);
    check_counts(&elements, bytes.len().saturating_sub(header_end + 10))?;
    let Some(vertex) = header.elements.get("vertex") else {
        return Err(bad("no \"vertex\" element"));
    };
    for axis in ["x", "y", "z"] {
        match vertex.properties.get(axis).map(|p| &p.data_type) {
            Some(PropertyType::Scalar(_)) => {}
            Some(PropertyType::List(..)) => return Err(bad(format!("vertex property {axis} is a list, not a number"))),
            None => return Err(bad(format!("the vertex element has no {axis} property"))),
        }
    }
    let mut frame = MeshFrame::default();
    for e in elements {
        let read_error = |err: ply_rs_bw::parser::ParseError| {
            let encoding = match header.encoding {
                Encoding::Ascii => "ASCII",
                Encoding::BinaryLittleEndian => "binary little endian",
                Encoding::BinaryBigEndian => "binary big endian",
            };
            bad(format!("{encoding} {} data: {err}", e.name))
        };
        match e.name.as_str() {
            "vertex" => {
                let read = Parser::<Vertex>::new().read_payload_for_element(&mut reader, e, &header).map_err(read_error)?;
                frame.vertices = read.into_iter().map(|v| v.0).collect();
            }
            "face" => {
                let read = Parser::<Face>::new().read_payload_for_element(&mut reader, e, &header).map_err(read_error)?;
                frame.faces = faces(read, e.count)?;
            }
            _ => {
                Parser::<Skip>::new().read_payload_for_element(&mut reader, e, &header).map_err(read_error)?;
            }
        }
    }
    if frame.vertices.is_empty() {
        return Err(Error::Empty("the PLY file holds no vertex".into()));
    }
    let n = frame.vertices.len();
    if let Some((k, &v)) = frame.faces.iter().enumerate().find_map(|(k, f)| f.iter().find(|&&v| v >= n).map(|v| (k, v))) {
        return Err(Error::Mesh(format!("face {k} uses vertex {v} but the file has {n} vertices")));
    }
    Ok(frame)
}

fn faces(read: Vec<Face>, count: usize) -> Result<Vec<Vec<usize>>> {
    if read.iter().map(|f| f.0.len()).sum::<usize>() > MAX_FACE_CORNERS {
        return Err(Error::TooLarge(format!("more than {MAX_FACE_CORNERS} face corners")));
    }
    debug_assert_eq!(read.len(), count);
    read.into_iter()
        .enumerate()
        .map(|(k, f)| {
            f.0.into_iter()
                .map(|v| usize::try_from(v).map_err(|_| Error::Mesh(format!("face {k} uses the negative vertex index {v}"))))
                .collect()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEAD: &str = "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n";

    #[test]
    fn quads_and_extra_elements() {
        let doc = format!(
            "{HEAD}property uchar red\nelement face 1\nproperty list uchar uint vertex_index\nelement edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n0 0 0 9\n1 0 0 9\n1 1 0 9\n0 1 0 9\n4 0 1 2 3\n0 1\n"
        );
        let m = parse_frame(doc.as_bytes()).unwrap();
        assert_eq!(m.faces, vec![vec![0, 1, 2, 3]]);
        assert_eq!(m.vertices[2], [1.0, 1.0, 0.0]);
    }

    #[test]
    fn bad_files_are_named() {
        let faces = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
        let body = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n";
        for (doc, what) in [
            (format!("{HEAD}{faces}{body}3 0 1 7\n"), "vertex 7"),
            (format!("{HEAD}{faces}{body}3 0 1 -1\n"), "negative"),
            (format!("{HEAD}{faces}0 0 0\n1 0"), "vertex data"),
            (format!("{HEAD}{faces}{body}"), "face data"),
            ("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n1\n".into(), "no y"),
            ("ply\nformat ascii 1.0\nelement vertex 99999999999\nproperty float x\nend_header\n".into(), "99999999999"),
            ("ply\nformat ascii 1.0\nend_header\n".into(), "no \"vertex\""),
            ("ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n\0\0\0\0\0\0".into(), "binary little endian vertex data"),
        ] {
            let err = parse_frame(doc.as_bytes()).unwrap_err().to_string();
            assert!(err.contains(what), "{what}: {err}");
        }
    }
}
