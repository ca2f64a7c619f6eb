//! Sample JSON, the canonical form: `{"name", "category", "frames": [[[x, y, z], …], …]}`,
//! or a `"mesh"` with `"faces"` and `"frames"`, and an optional `"truth"` (JSON itself is
//! RFC 8259).
//!
//! Counts are bounded while the document is read, not after: a list longer than its limit
//! (frames, vertices of a frame, faces, face corners in all) stops the parse at the first
//! element past it, so memory never exceeds what the limits allow, and nesting deeper than
//! [`MAX_NESTING`] (serde_json's recursion limit) is refused anywhere in the document, even
//! inside a key that is skipped ([`check_nesting`]).
//!
//! ```
//! use close_io::formats::json::parse_sample;
//! let s = parse_sample(br#"{"name": "sq", "frames": [[[0,0,0],[1,0,0],[1,1,0],[0,1,0]]]}"#).unwrap();
//! assert_eq!(s.frames[0].len(), 4);
//! assert!(parse_sample(b"{\"frames\": 3}").unwrap_err().to_string().contains("at line 1"));
//! ```

use std::cell::Cell;
use std::fmt;
use std::marker::PhantomData;

use serde::de::{self, DeserializeSeed, Deserializer, SeqAccess, Visitor};
use serde::Deserialize;

use super::{Sample, MAX_FILE_BYTES};
use crate::error::{Error, Format, Result};
use crate::mesh::{MeshFrames, MAX_FACE_CORNERS, MAX_MESH_FACES, MAX_MESH_VERTICES};
use close_core::border::{MAX_FRAMES, MAX_VERTICES};
use close_core::geometry::Fold;
use close_core::Error as CoreError;

/// Deepest nesting of lists and objects a JSON document may have.
pub const MAX_NESTING: usize = 128;

/// Refuse a JSON document nested deeper than [`MAX_NESTING`], wherever the nesting is:
/// serde_json counts depth only for the values it builds, and skips an unknown key's value
/// at any depth. One pass over the bytes, outside strings.
pub fn check_nesting(bytes: &[u8]) -> Result<()> {
    let (mut depth, mut line, mut in_string, mut escaped) = (0usize, 1usize, false, false);
    for &b in bytes {
        match (in_string, b) {
            (true, _) if escaped => escaped = false,
            (true, b'\\') => escaped = true,
            (true, b'"') | (false, b'"') => in_string = !in_string,
            (false, b'[' | b'{') => {
                depth += 1;
                if depth > MAX_NESTING {
                    return Err(Error::parse_at(
                        Format::SampleJson,
                        line,
                        format!("nested deeper than {MAX_NESTING} levels"),
                    ));
                }
            }
            (false, b']' | b'}') => depth = depth.saturating_sub(1),
            (_, b'\n') => line += 1,
            _ => {}
        }
    }
    Ok(())
}

/// Parse a Sample JSON document. Errors name the line serde stopped at; a count over its
/// limit is [`close_core::Error::TooLarge`].
pub fn parse_sample(bytes: &[u8]) -> Result<Sample> {
    if bytes.len() > MAX_FILE_BYTES {
        return Err(Error::too_large("bytes of JSON", bytes.len(), MAX_FILE_BYTES));
    }
    check_nesting(bytes)?;
    if bytes.iter().all(u8::is_ascii_whitespace) {
        return Err(CoreError::Empty { what: "the JSON document is empty" }.into());
    }
    EXCEEDED.set(None);
    let sample: Sample = serde_json::from_slice(bytes).map_err(|e| match EXCEEDED.take() {
        Some((what, Some(got), limit)) => Error::too_large(what, got, limit),
        Some((what, None, limit)) => Error::over_limit(what, limit),
        None => parse_error(&e),
    })?;
    if sample.frames.is_empty() && sample.mesh.is_none() {
        return Err(
            CoreError::Empty { what: "the sample has neither \"frames\" nor \"mesh\"" }.into()
        );
    }
    Ok(sample)
}

/// serde_json's error with its position moved into the typed `line` (the column stays in
/// the reason); line 0 means serde_json knew no position.
fn parse_error(e: &serde_json::Error) -> Error {
    // serde's message may quote a string of the file.
    let message = super::redact(&e.to_string());
    let position = format!(" at line {} column {}", e.line(), e.column());
    match message.strip_suffix(&position) {
        Some(reason) if e.line() > 0 => Error::parse_at(
            Format::SampleJson,
            e.line(),
            format!("{reason} (column {})", e.column()),
        ),
        _ => Error::parse(Format::SampleJson, message),
    }
}

/// Write a sample as compact JSON.
pub fn to_json(sample: &Sample) -> String {
    // A sample is plain data (strings, numbers, lists): serde_json cannot fail on it, and
    // a non-finite coordinate is written as null.
    serde_json::to_string(sample).unwrap_or_default()
}

thread_local! {
    /// The limit the parse on this thread stopped at: serde only carries a message, so the
    /// typed cause waits here for [`parse_sample`] to pick it up.
    static EXCEEDED: Cell<Option<(&'static str, Option<usize>, usize)>> = const { Cell::new(None) };
}

/// The error for `got` (or, when uncounted, more than `limit`) of `what`.
fn exceeded<E: de::Error>(what: &'static str, got: Option<usize>, limit: usize) -> E {
    EXCEEDED.set(Some((what, got, limit)));
    E::custom(format_args!("too many {what} (at most {limit})"))
}

/// A JSON array of at most `limit` items, each read by `item`.
#[derive(Clone, Copy)]
struct Bounded<S> {
    what: &'static str,
    limit: usize,
    item: S,
}

impl<'de, S: DeserializeSeed<'de> + Copy> DeserializeSeed<'de> for Bounded<S> {
    type Value = Vec<S::Value>;

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<Self::Value, D::Error> {
        d.deserialize_seq(self)
    }
}

impl<'de, S: DeserializeSeed<'de> + Copy> Visitor<'de> for Bounded<S> {
    type Value = Vec<S::Value>;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(f, "a list of at most {} {}", self.limit, self.what)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
        let mut out = Vec::new();
        while let Some(item) = seq.next_element_seed(self.item)? {
            if out.len() == self.limit {
                // Count the rest without keeping it, so the message gives the true count.
                let mut got = self.limit + 1;
                while seq.next_element::<de::IgnoredAny>()?.is_some() {
                    got += 1;
                }
                return Err(exceeded(self.what, Some(got), self.limit));
            }
            out.push(item);
        }
        Ok(out)
    }
}

/// One face corner, counted against a budget shared by all faces.
#[derive(Clone, Copy)]
struct Corner<'a>(&'a Cell<usize>);

impl<'de> DeserializeSeed<'de> for Corner<'_> {
    type Value = usize;

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<usize, D::Error> {
        let used = self.0.get() + 1;
        if used > MAX_FACE_CORNERS {
            return Err(exceeded("face corners", None, MAX_FACE_CORNERS));
        }
        self.0.set(used);
        usize::deserialize(d)
    }
}

/// Frames of at most `per_frame` points each.
fn frames<'de, D: Deserializer<'de>>(
    d: D,
    per_frame: usize,
    what: &'static str,
) -> Result<Vec<Vec<[f64; 3]>>, D::Error> {
    let frame = Bounded { what, limit: per_frame, item: PhantomData::<[f64; 3]> };
    Bounded { what: "frames", limit: MAX_FRAMES, item: frame }.deserialize(d)
}

/// `"frames"` of a border sample (a closing vertex may repeat vertex 0).
pub(super) fn border_frames<'de, D: Deserializer<'de>>(
    d: D,
) -> Result<Vec<Vec<[f64; 3]>>, D::Error> {
    frames(d, MAX_VERTICES + 1, "vertices in one border frame")
}

/// `"mesh"`: read through [`MeshJson`], whose every list is bounded.
pub(super) fn mesh<'de, D: Deserializer<'de>>(d: D) -> Result<Option<MeshFrames>, D::Error> {
    Ok(Option::<MeshJson>::deserialize(d)?.map(|m| MeshFrames {
        faces: m.faces,
        frames: m.frames,
        border_edges: m.border_edges,
    }))
}

/// [`MeshFrames`] as JSON gives it, with bounded lists.
#[derive(Deserialize)]
struct MeshJson {
    #[serde(default, deserialize_with = "faces")]
    faces: Vec<Vec<usize>>,
    #[serde(deserialize_with = "mesh_frames")]
    frames: Vec<Vec<[f64; 3]>>,
    #[serde(default, deserialize_with = "border_edges")]
    border_edges: Vec<[usize; 2]>,
}

fn faces<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<Vec<usize>>, D::Error> {
    let corners = Cell::new(0);
    let face =
        Bounded { what: "corners in one face", limit: MAX_FACE_CORNERS, item: Corner(&corners) };
    Bounded { what: "faces", limit: MAX_MESH_FACES, item: face }.deserialize(d)
}

fn mesh_frames<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<Vec<[f64; 3]>>, D::Error> {
    frames(d, MAX_MESH_VERTICES, "vertices in one mesh frame")
}

/// `truth.folds`: at most one fold per step between frames.
pub(super) fn truth_folds<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<Fold>, D::Error> {
    Bounded { what: "true folds", limit: MAX_FRAMES, item: PhantomData::<Fold> }.deserialize(d)
}

/// A list of vertices, at most one entry per mesh vertex.
struct Vertices(Vec<usize>);

impl<'de> Deserialize<'de> for Vertices {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        Bounded { what: "folded vertices", limit: MAX_MESH_VERTICES, item: PhantomData::<usize> }
            .deserialize(d)
            .map(Vertices)
    }
}

/// `truth.folded_vertices`: at most one entry per mesh vertex.
pub(super) fn folded_vertices<'de, D: Deserializer<'de>>(
    d: D,
) -> Result<Option<Vec<usize>>, D::Error> {
    Ok(Option::<Vertices>::deserialize(d)?.map(|v| v.0))
}

/// `truth.folded_vertices_per_fold`: at most one list per frame, each as `folded_vertices`.
pub(super) fn folded_vertices_per_fold<'de, D: Deserializer<'de>>(
    d: D,
) -> Result<Option<Vec<Vec<usize>>>, D::Error> {
    /// The bounded lists, as a type `Option` can wrap (null stays `None`).
    struct PerFold(Vec<Vertices>);
    impl<'de> Deserialize<'de> for PerFold {
        fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
            Bounded {
                what: "folds' folded vertices",
                limit: MAX_FRAMES,
                item: PhantomData::<Vertices>,
            }
            .deserialize(d)
            .map(PerFold)
        }
    }
    Ok(Option::<PerFold>::deserialize(d)?.map(|p| p.0.into_iter().map(|v| v.0).collect()))
}

fn border_edges<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<[usize; 2]>, D::Error> {
    Bounded { what: "border edges", limit: MAX_MESH_VERTICES, item: PhantomData::<[usize; 2]> }
        .deserialize(d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn malformed_documents_are_named() {
        for (doc, what) in [
            (&b""[..], "empty"),
            (b"not json", "parse"),
            (b"{\"frames\": [[[0, 0]]]}", "parse"),
            (b"{\"name\": \"x\"}", "neither \"frames\" nor \"mesh\""),
            (b"{\"frames\": [[[0, 0, \"a\"]]]}", "parse"),
        ] {
            let err = parse_sample(doc).unwrap_err().to_string();
            assert!(err.contains(what) || err.to_lowercase().contains(what), "{err}");
        }
    }

    #[test]
    fn round_trip() {
        let s = Sample::from_frames("a", "napkin", vec![vec![[0.0, 1.0, 2.0]; 4]]);
        assert_eq!(parse_sample(to_json(&s).as_bytes()).unwrap(), s);
        let mesh = Sample {
            mesh: Some(MeshFrames::new(vec![vec![0, 1, 2]], vec![vec![[0.0; 3]; 3]])),
            ..Sample::from_frames("m", "", vec![])
        };
        assert_eq!(parse_sample(to_json(&mesh).as_bytes()).unwrap(), mesh);
    }

    #[test]
    fn counts_over_the_limits_are_too_large() {
        let frames = format!("{{\"frames\": [{}[]]}}", "[],".repeat(MAX_FRAMES));
        assert_eq!(
            parse_sample(frames.as_bytes()).unwrap_err(),
            Error::too_large("frames", MAX_FRAMES + 1, MAX_FRAMES)
        );
        let vertices =
            format!("{{\"frames\": [[{}[0,0,0]]]}}", "[0,0,0],".repeat(MAX_VERTICES + 5));
        let err = parse_sample(vertices.as_bytes()).unwrap_err();
        assert_eq!(
            err.to_string(),
            format!(
                "input too large: {} vertices in one border frame (at most {})",
                MAX_VERTICES + 6,
                MAX_VERTICES + 1
            )
        );
        // A later, well-formed parse on the same thread is not confused by the last one.
        assert!(matches!(parse_sample(b"{\"frames\": [[1]]}"), Err(Error::Parse { .. })));
    }

    #[test]
    fn truth_is_bounded_and_may_be_null() {
        let doc = |truth: &str| format!("{{\"frames\": [[[0,0,0]]], \"truth\": {truth}}}");
        let s = parse_sample(doc(r#"{"folds": [[1, 2]], "folded_vertices": null}"#).as_bytes())
            .unwrap();
        assert_eq!(
            s.truth,
            Some(crate::formats::Truth {
                folds: vec![Fold::new(1.0, 2.0)],
                folded_vertices: None,
                folded_vertices_per_fold: None
            })
        );
        let s = parse_sample(doc(r#"{"folded_vertices": [3, 4]}"#).as_bytes()).unwrap();
        assert_eq!(s.truth.and_then(|t| t.folded_vertices), Some(vec![3, 4]));
        let many = doc(&format!("{{\"folds\": [{}[0, 1]]}}", "[0, 1],".repeat(MAX_FRAMES)));
        assert_eq!(
            parse_sample(many.as_bytes()).unwrap_err(),
            Error::too_large("true folds", MAX_FRAMES + 1, MAX_FRAMES)
        );
    }

    #[test]
    fn the_position_is_said_once() {
        let err = parse_sample(b"{\"frames\":\n [[[0, 0, 0]]],\n \"name\": 3}").unwrap_err();
        assert_eq!(err.to_string(), "could not parse sample JSON at line 3: invalid type: integer `3`, expected a string (column 10)");
    }
}
