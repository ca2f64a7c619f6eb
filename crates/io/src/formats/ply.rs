//! PLY frames (ASCII, binary little and big endian), read with `ply-rs-bw`.
//!
//! The `vertex` element gives positions from its `x`, `y`, `z` properties (any scalar
//! type); the `face` element gives polygons from its `vertex_indices` (or `vertex_index`)
//! list. Other elements and properties are read past and ignored. Element counts are
//! checked against the mesh limits and against the bytes the payload holds (each element
//! takes at least a known number of bytes) before anything is read, so a header
//! announcing billions of elements is refused without allocating or looping for them.
//! Format: Greg Turk's "The PLY Polygon File Format" (ASCII, binary little/big endian).
//!
//! ```
//! use close_io::formats::ply::parse_frame;
//! let doc = b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
//! element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
//! let m = parse_frame(doc).unwrap();
//! assert_eq!((m.vertices.len(), m.faces.clone()), (3, vec![vec![0, 1, 2]]));
//! assert!(parse_frame(b"obj\n").unwrap_err().to_string().contains("not a PLY file"));
//! ```

use ply_rs_bw::parser::{Parser, Reader};
use ply_rs_bw::ply::{
    ElementDef, Encoding, Property, PropertyAccess, PropertyAccessResult, PropertyType, ScalarType,
};

use super::{MeshFrame, MAX_FILE_BYTES};
use crate::error::{Error, Format, Result};
use crate::mesh::{MAX_FACE_CORNERS, MAX_MESH_FACES, MAX_MESH_VERTICES};
use close_core::error::MeshError;
use close_core::Error as CoreError;

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
    Error::parse(Format::Ply, message)
}

/// Size in bytes of one binary scalar.
fn scalar_size(t: &ScalarType) -> usize {
    match t {
        ScalarType::Char | ScalarType::UChar => 1,
        ScalarType::Short | ScalarType::UShort => 2,
        ScalarType::Int | ScalarType::UInt | ScalarType::Float => 4,
        ScalarType::Double => 8,
    }
}

/// Payload bytes one element is counted for: at least what it takes, and at least one.
/// Binary: its scalars plus each list's count (a list may be empty). ASCII: its own line,
/// with at least a digit and a separator per property (a property-less element still takes
/// its newline). A binary property-less element takes no byte at all: it is counted as
/// one all the same, so an absurd count is refused rather than trusted.
fn min_element_bytes(e: &ElementDef, encoding: Encoding) -> usize {
    let bytes = match encoding {
        Encoding::Ascii => 2 * e.properties.len(),
        _ => e
            .properties
            .values()
            .map(|p| match &p.data_type {
                PropertyType::Scalar(t) | PropertyType::List(t, _) => scalar_size(t),
            })
            .sum(),
    };
    bytes.max(1)
}

/// Refuse counts the limits forbid or the file cannot hold, before reading the payload:
/// every element, property-less ones included, must fit in the bytes that follow the
/// header, so no read loop can run on a count without consuming input. (A binary
/// property-less element is not read at all: see [`parse_frame`].)
fn check_counts(elements: &[&ElementDef], encoding: Encoding, payload_bytes: usize) -> Result<()> {
    let mut needed = 0usize;
    for e in elements {
        let limit = match e.name.as_str() {
            "vertex" => MAX_MESH_VERTICES,
            "face" => MAX_MESH_FACES,
            _ => usize::MAX,
        };
        if e.count > limit {
            return Err(Error::too_large(
                if e.name == "vertex" { "mesh vertices" } else { "mesh faces" },
                e.count,
                limit,
            ));
        }
        needed = e
            .count
            .checked_mul(min_element_bytes(e, encoding))
            .and_then(|b| needed.checked_add(b))
            .unwrap_or(usize::MAX);
        if needed > payload_bytes {
            return Err(bad(format!(
                "the header announces {} {} elements, which with those before take at least {needed} bytes, but only {payload_bytes} bytes follow (truncated file?)",
                e.count, element_name(&e.name)
            )));
        }
    }
    Ok(())
}

/// An element's name as an error names it: a word ([`super::identifier`]), else not quoted.
fn element_name(name: &str) -> &str {
    super::identifier(name).unwrap_or("(unnamed)")
}

/// Parse one PLY file.
pub fn parse_frame(bytes: &[u8]) -> Result<MeshFrame> {
    if bytes.len() > MAX_FILE_BYTES {
        return Err(Error::too_large("bytes of PLY", bytes.len(), MAX_FILE_BYTES));
    }
    if !(bytes.starts_with(b"ply\n") || bytes.starts_with(b"ply\r\n")) {
        return Err(bad("not a PLY file (it must start with the line \"ply\")"));
    }
    let mut reader = Reader::new(bytes);
    let header = Parser::<Skip>::new()
        .read_header(&mut reader)
        .map_err(|e| bad(format!("header: {}", super::redact(&e.to_string()))))?;
    let elements: Vec<&ElementDef> = header.elements.values().collect();
    // The payload starts after the line "end_header" (its newline counted as payload: one
    // byte of slack for an ASCII file whose last line has none).
    let payload_start =
        bytes.windows(11).position(|w| w == b"\nend_header").map_or(bytes.len(), |k| k + 11);
    check_counts(&elements, header.encoding, bytes.len() - payload_start)?;
    let Some(vertex) = header.elements.get("vertex") else {
        return Err(bad("no \"vertex\" element"));
    };
    for axis in ["x", "y", "z"] {
        match vertex.properties.get(axis).map(|p| &p.data_type) {
            Some(PropertyType::Scalar(_)) => {}
            Some(PropertyType::List(..)) => {
                return Err(bad(format!("vertex property {axis} is a list, not a number")))
            }
            None => return Err(bad(format!("the vertex element has no {axis} property"))),
        }
    }
    let mut frame = MeshFrame::default();
    for e in elements {
        if e.properties.is_empty() && header.encoding != Encoding::Ascii {
            continue; // holds no byte: nothing to read, however large its count
        }
        let read_error = |err: ply_rs_bw::parser::ParseError| {
            let encoding = match header.encoding {
                Encoding::Ascii => "ASCII",
                Encoding::BinaryLittleEndian => "binary little endian",
                Encoding::BinaryBigEndian => "binary big endian",
            };
            // The parser's message may quote a whole line of the file.
            bad(format!(
                "{encoding} {} data: {}",
                element_name(&e.name),
                super::redact(&err.to_string())
            ))
        };
        match e.name.as_str() {
            "vertex" => {
                let read = Parser::<Vertex>::new()
                    .read_payload_for_element(&mut reader, e, &header)
                    .map_err(read_error)?;
                frame.vertices = read.into_iter().map(|v| v.0).collect();
            }
            "face" => {
                let read = Parser::<Face>::new()
                    .read_payload_for_element(&mut reader, e, &header)
                    .map_err(read_error)?;
                frame.faces = faces(read, e.count)?;
            }
            _ => {
                Parser::<Skip>::new()
                    .read_payload_for_element(&mut reader, e, &header)
                    .map_err(read_error)?;
            }
        }
    }
    if frame.vertices.is_empty() {
        return Err(CoreError::Empty { what: "the PLY file holds no vertex" }.into());
    }
    let n = frame.vertices.len();
    if let Some((k, &v)) = frame
        .faces
        .iter()
        .enumerate()
        .find_map(|(k, f)| f.iter().find(|&&v| v >= n).map(|v| (k, v)))
    {
        return Err(MeshError::VertexOutOfRange { face: k, vertex: v, vertices: n }.into());
    }
    Ok(frame)
}

fn faces(read: Vec<Face>, count: usize) -> Result<Vec<Vec<usize>>> {
    if read.iter().map(|f| f.0.len()).sum::<usize>() > MAX_FACE_CORNERS {
        return Err(Error::over_limit("face corners", MAX_FACE_CORNERS));
    }
    debug_assert_eq!(read.len(), count);
    read.into_iter()
        .enumerate()
        .map(|(k, f)| {
            f.0.into_iter()
                .map(|v| {
                    usize::try_from(v)
                        .map_err(|_| MeshError::NegativeIndex { face: k, index: v }.into())
                })
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
            // Too short for the counts: refused before reading.
            (format!("{HEAD}{faces}0 0 0\n1 0"), "4 vertex elements"),
            (format!("{HEAD}{faces}{body}"), "1 face elements"),
            // Long enough, but not numbers: refused while reading, naming the element.
            (format!("{HEAD}{faces}a b c\n{body}"), "ASCII vertex data"),
            (format!("{HEAD}{faces}{body}3 0 x 2\n"), "ASCII face data"),
            ("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n1\n".into(), "no y"),
            ("ply\nformat ascii 1.0\nelement vertex 99999999999\nproperty float x\nend_header\n".into(), "99999999999"),
            ("ply\nformat ascii 1.0\nend_header\n".into(), "no \"vertex\""),
            ("ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n\0\0\0\0\0\0".into(), "2 vertex elements"),
        ] {
            let err = parse_frame(doc.as_bytes()).unwrap_err().to_string();
            assert!(err.contains(what), "{what}: {err}");
        }
    }

    #[test]
    fn property_less_elements_are_counted_and_never_looped_over() {
        let junk = |format: &str, count: &str, after: &str| {
            format!("ply\nformat {format} 1.0\nelement vertex 1\nproperty uchar x\nproperty uchar y\nproperty uchar z\nelement junk {count}\nend_header\n{after}")
        };
        // 2^62 of them cannot fit in what follows, in either encoding.
        for format in ["binary_little_endian", "ascii"] {
            let err = parse_frame(junk(format, "4611686018427387904", "1 2 3\n\n").as_bytes())
                .unwrap_err()
                .to_string();
            assert!(err.contains("4611686018427387904 junk elements"), "{err}");
        }
        // Counts that fit: binary ones hold no byte and are skipped; ASCII ones are lines.
        let m = parse_frame(junk("binary_little_endian", "1", "\x01\x02\x03").as_bytes()).unwrap();
        assert_eq!(m.vertices, vec![[1.0, 2.0, 3.0]]);
        assert_eq!(
            parse_frame(junk("ascii", "2", "1 2 3\n\n\n").as_bytes()).unwrap().vertices.len(),
            1
        );
    }
}
