//! The error type of close-core: every way an input can be wrong for the analysis, named
//! plainly. Reading files is close-io's (its error wraps this one), drawing close-render's.
//!
//! Variants carry typed fields (frame and vertex numbers, limits, a reason enum) so a
//! caller can act on the cause — the HTTP layer maps them to status codes — and their
//! messages name the problem so a user can fix the input. Nothing here is ever a panic.
//!
//! ```
//! use close_core::error::{DegenerateReason, Error};
//! let e = Error::Degenerate { frame: 2, reason: DegenerateReason::Coincident };
//! assert_eq!(e.to_string(), "degenerate border in frame 2: all vertices coincide");
//! let e = Error::too_large("frames", 1200, 1000);
//! assert_eq!(e.to_string(), "input too large: 1200 frames (at most 1000)");
//! ```

use std::fmt;

use thiserror::Error;

/// Why an input could not be turned into a CloSE analysis. Every variant is an input fault
/// (the input or the request is wrong: an HTTP layer answers 4xx).
#[derive(Debug, Error, Clone, PartialEq)]
pub enum Error {
    /// The sample holds no frame, a frame holds no vertex, no file was given, …
    #[error("{what}")]
    Empty { what: &'static str },
    /// Fewer vertices than a closed border needs.
    #[error("too few vertices: a border needs at least {min}, got {got}")]
    TooFewVertices { got: usize, min: usize },
    /// More of something (bytes, frames, vertices, …) than the limit: refused before the
    /// work or the memory it would take. `got` is `None` when the reader stopped counting
    /// at the limit.
    #[error("input too large: {}", Over { what, got: *.got, limit: *.limit })]
    TooLarge { what: &'static str, got: Option<u64>, limit: u64 },
    /// A coordinate is NaN or infinite.
    #[error("non-finite coordinate in frame {frame}, vertex {vertex}")]
    NonFinite { frame: usize, vertex: usize },
    /// Frames disagree on the vertex count.
    #[error("frame {frame} has {got} vertices but frame 0 has {expected}")]
    FrameSizeMismatch { frame: usize, expected: usize, got: usize },
    /// A frame cannot be a cloth outline.
    #[error("degenerate border in frame {frame}: {reason}")]
    Degenerate { frame: usize, reason: DegenerateReason },
    /// An argument out of range or inconsistent (a frame that does not exist, a bad fold
    /// specification, a file type the readers do not know, …).
    #[error("{0}")]
    InvalidArgument(String),
    /// A mesh could not give a border.
    #[error("mesh problem: {0}")]
    Mesh(#[from] MeshError),
    /// A synthetic fold (the built-in dataset's generator) that cannot be made.
    #[error("fold ({f1}, {f2}) cannot be made: {problem}")]
    InvalidFold { f1: f64, f2: f64, problem: FoldProblem },
    /// The estimated work is over a [`crate::budget::Budget`] limit (refused before starting).
    #[error("too much work: {what} is {got}, over the limit of {limit}")]
    OverBudget { what: &'static str, got: u64, limit: u64 },
    /// The job was stopped by its [`crate::budget::Deadline`] (time-out or cancelled request).
    #[error("the work was stopped: it ran past its deadline or its request went away")]
    Cancelled,
}

/// Why a synthetic fold along border parameters (f1, f2) cannot be made.
#[derive(Debug, Error, Clone, Copy, PartialEq, Eq)]
pub enum FoldProblem {
    #[error("a parameter or the thickness is not finite")]
    NotFinite,
    #[error("the border has fewer than 3 vertices")]
    TooFewVertices,
    #[error("the two fold points coincide")]
    PointsCoincide,
    #[error("no vertex lies on the folded arc")]
    EmptyArc,
    #[error("the folded arc is not on one side of the fold line")]
    ArcCrossesLine,
    #[error("the fold line leaves the cloth")]
    LeavesCloth,
}

/// Shorthand used across the crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Why a frame cannot be a cloth outline.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DegenerateReason {
    /// Every vertex at one point (to a relative 1e-9 of the start frame's size).
    Coincident,
    /// The start frame's XY projection encloses no area (collinear or vertical border).
    NoArea,
    /// Coordinates so large that the centroid or the radius overflows.
    TooLargeToNormalise,
    /// A later frame lies farther than `limit` start-frame radii from the start frame's
    /// centroid: the normalised coordinates would lose the dGLI's lift to rounding.
    FarFromStart { limit: f64 },
}

impl fmt::Display for DegenerateReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DegenerateReason::Coincident => f.write_str("all vertices coincide"),
            DegenerateReason::NoArea => {
                f.write_str("no area seen from +z (collinear or vertical border)")
            }
            DegenerateReason::TooLargeToNormalise => {
                f.write_str("coordinates too large to normalise")
            }
            DegenerateReason::FarFromStart { limit } => {
                write!(f, "vertices lie more than {limit:e} start-frame radii from the start frame's centre (coordinates too large to normalise)")
            }
        }
    }
}

/// Why a mesh gives no border. Vertex and face numbers are 0-based unless a field says
/// otherwise.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum MeshError {
    #[error("face {face} has {corners} vertices (a face needs at least 3)")]
    FaceTooSmall { face: usize, corners: usize },
    /// `vertex` as the file numbers it (1-based in OBJ).
    #[error("face {face} uses vertex {vertex}, but the mesh has {vertices} vertices")]
    VertexOutOfRange { face: usize, vertex: usize, vertices: usize },
    #[error("face {face} uses the negative vertex index {index}")]
    NegativeIndex { face: usize, index: i64 },
    #[error("face {face} repeats vertex {vertex}")]
    RepeatedVertex { face: usize, vertex: usize },
    #[error("non-manifold mesh: edge [{a}, {b}] is shared by 3 or more faces")]
    NonManifoldEdge { a: usize, b: usize },
    #[error("border edge [{vertex}, {vertex}] joins a vertex to itself")]
    SelfEdge { vertex: usize },
    #[error("border edge [{a}, {b}] uses a vertex beyond the mesh's {vertices}")]
    BorderEdgeOutOfRange { a: usize, b: usize, vertices: usize },
    #[error("vertex {vertex} has {edges} border edge(s), not 2: the border edges do not close up")]
    OpenBorder { vertex: usize, edges: usize },
    #[error("vertex {vertex} has {edges} border edges, not 2: border loops touch there")]
    TouchingLoops { vertex: usize, edges: usize },
    #[error("vertex {vertex} is reached twice while chaining border edges")]
    ReachedTwice { vertex: usize },
    #[error("no border edge given")]
    NoBorderEdges,
    #[error("the border edges form {loops} separate loops, not one")]
    SeveralLoops { loops: usize },
    #[error("the mesh has no face and no border edge")]
    NoFaces,
    #[error("the mesh has no extent seen from +z: no silhouette")]
    NoExtent,
    #[error("the mesh covers no area seen from +z: no silhouette")]
    NoArea,
    #[error("the silhouette seen from +z gives only {vertices} border vertices: no usable border")]
    SilhouetteTooSmall { vertices: usize },
    /// Two frame files disagree on the vertex count.
    #[error("{file} has {got} vertices but {first} has {expected}: every frame file must list the same vertices in the same order")]
    FrameFileMismatch { file: String, got: usize, first: String, expected: usize },
}

/// "N things (at most L)", or "more than L things" when the count stopped at the limit.
struct Over<'a> {
    what: &'a str,
    got: Option<u64>,
    limit: u64,
}

impl fmt::Display for Over<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (limit, what) = (quantity(self.limit, self.what), self.what);
        match self.got {
            Some(got) if what == "bytes" => write!(f, "{} (at most {limit})", quantity(got, what)),
            Some(got) => write!(f, "{got} {what} (at most {limit})"),
            None if what == "bytes" => write!(f, "more than {limit}"),
            None => write!(f, "more than {limit} {what}"),
        }
    }
}

/// `n` as a person reads it: a byte count in B, KiB, MiB or GiB (one decimal when not
/// whole), any other count as the number.
fn quantity(n: u64, what: &str) -> String {
    if what != "bytes" {
        return n.to_string();
    }
    let units = [("GiB", 1u64 << 30), ("MiB", 1 << 20), ("KiB", 1 << 10)];
    match units.iter().find(|(_, size)| n >= *size) {
        Some((unit, size)) if n.is_multiple_of(*size) => format!("{} {unit}", n / size),
        Some((unit, size)) => format!("{:.1} {unit}", n as f64 / *size as f64),
        None => format!("{n} B"),
    }
}

impl Error {
    /// Too many of `what`: `got` of them, `limit` allowed.
    pub fn too_large(what: &'static str, got: usize, limit: usize) -> Self {
        Error::TooLarge { what, got: Some(got as u64), limit: limit as u64 }
    }

    /// More than `limit` of `what` (the reader stopped counting there).
    pub fn over_limit(what: &'static str, limit: usize) -> Self {
        Error::TooLarge { what, got: None, limit: limit as u64 }
    }
}
