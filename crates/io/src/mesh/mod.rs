//! The border of a cloth mesh, found on frame 0 and followed through the frames by vertex.
//!
//! Three ways, tried in this order ([`BorderMethod`]):
//! - **border edges** given by the file (the MATLAB data's `Eb`): chained into one loop;
//! - **boundary loop** of a planar cloth: the edges used by exactly one face, chained into
//!   loops ([`boundary`]); the longest (3D length) is the outline, the others are holes.
//!   It is used when its XY area covers at least [`ENCLOSES`] of the mesh's silhouette area;
//! - **silhouette** of a garment shell (no boundary, or openings — neck, sleeves, waist —
//!   whose loops enclose little of what is seen from above): the paper's method
//!   ([`silhouette`]).
//!
//! However it was found, the border is then walked anticlockwise (seen from +z on frame 0)
//! from its **lowest vertex**: the one with the least y on frame 0, of those within
//! [`LEVEL`] of the least y (a level bottom edge, up to noise), the one with the least x;
//! the bottom-left corner of a napkin. It is a rule of the cloth's shape, not of how the
//! mesh numbers its vertices or lists its faces, and the rule the border forms of the
//! simulated sets and the built-in dataset's outlines follow (anticlockwise from the
//! bottom-left corner), so a mesh and its border form give the same border in the same
//! order, and the same folds. (A round cloth has no such corner: its lowest point is where
//! it starts.)
//!
//! ```
//! use close_io::mesh::{border_of, BorderMethod, MeshFrames};
//! // A 2×1 strip of quads: its outline visits all six vertices.
//! let v = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0], [2.0, 1.0, 0.0]];
//! let mesh = MeshFrames::new(vec![vec![0, 1, 4, 3], vec![1, 2, 5, 4]], vec![v]);
//! let b = border_of(&mesh).unwrap();
//! assert_eq!(b.method, BorderMethod::BoundaryLoop);
//! assert_eq!(b.indices, vec![0, 1, 2, 5, 4, 3]);
//! ```

pub mod boundary;
pub mod silhouette;

use std::collections::HashMap;

use serde::Serialize;

use close_core::border::{signed_area_xy, Point, MAX_FRAMES};
use close_core::error::{Error, MeshError, Result};

/// Most vertices a mesh may have.
pub const MAX_MESH_VERTICES: usize = 2_000_000;
/// Most faces a mesh may have.
pub const MAX_MESH_FACES: usize = 4_000_000;
/// Most vertex corners over all faces (bounds the memory the topology needs).
pub const MAX_FACE_CORNERS: usize = 16_000_000;
/// A boundary loop is the outline when its XY area is at least this part of the silhouette.
pub const ENCLOSES: f64 = 0.8;
/// Vertices this close to the lowest y, as a share of the border's extent (its largest
/// distance from its centroid, the SPEC normalisation's radius), lie at the same height for
/// [`start_lowest`]: simulated cloth keeps a level edge level only to ~10⁻⁵ of its size.
pub const LEVEL: f64 = 1e-4;

/// A triangle (or polygon) mesh followed through frames by vertex index. Serialised as
/// Sample JSON's `"mesh"`; read back through [`crate::formats::json`], whose lists are
/// bounded while reading.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct MeshFrames {
    pub faces: Vec<Vec<usize>>,
    pub frames: Vec<Vec<[f64; 3]>>,
    /// Border edges given by the file (the MATLAB data's `Eb`, 0-based here); when present
    /// they define the border and the faces may be empty.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub border_edges: Vec<[usize; 2]>,
}

impl MeshFrames {
    /// A mesh from faces and frames of vertex positions.
    pub fn new(faces: Vec<Vec<usize>>, frames: Vec<Vec<[f64; 3]>>) -> MeshFrames {
        MeshFrames { faces, frames, border_edges: Vec::new() }
    }
}

/// How a mesh's border was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BorderMethod {
    BorderEdges,
    BoundaryLoop,
    Silhouette,
}

impl BorderMethod {
    /// The name the analysis reports.
    pub fn name(self) -> &'static str {
        match self {
            BorderMethod::BorderEdges => "mesh border edges",
            BorderMethod::BoundaryLoop => "mesh boundary loop",
            BorderMethod::Silhouette => "mesh silhouette",
        }
    }
}

/// A mesh's border: mesh vertex indices in walking order, and how they were found.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshBorder {
    pub indices: Vec<usize>,
    pub method: BorderMethod,
}

/// Check sizes, frames and faces: every face has ≥ 3 distinct in-range vertices, every
/// frame the same vertex count and finite coordinates, no edge has more than two faces.
pub fn validate(mesh: &MeshFrames) -> Result<()> {
    let Some(first) = mesh.frames.first() else {
        return Err(Error::Empty { what: "the mesh has no frame" });
    };
    let n = first.len();
    if n == 0 {
        return Err(Error::Empty { what: "frame 0 of the mesh has no vertex" });
    }
    if n > MAX_MESH_VERTICES {
        return Err(Error::too_large("mesh vertices", n, MAX_MESH_VERTICES));
    }
    if mesh.frames.len() > MAX_FRAMES {
        return Err(Error::too_large("frames", mesh.frames.len(), MAX_FRAMES));
    }
    for (f, frame) in mesh.frames.iter().enumerate() {
        if frame.len() != n {
            return Err(Error::FrameSizeMismatch { frame: f, expected: n, got: frame.len() });
        }
        if let Some(v) = frame.iter().position(|p| p.iter().any(|c| !c.is_finite())) {
            return Err(Error::NonFinite { frame: f, vertex: v });
        }
    }
    if mesh.faces.len() > MAX_MESH_FACES {
        return Err(Error::too_large("mesh faces", mesh.faces.len(), MAX_MESH_FACES));
    }
    let corners = mesh.faces.iter().map(Vec::len).sum::<usize>();
    if corners > MAX_FACE_CORNERS {
        return Err(Error::too_large("face corners", corners, MAX_FACE_CORNERS));
    }
    // One buffer for all faces: a face's repeated vertex is found sorted, O(K log K).
    let mut sorted = Vec::new();
    for (k, face) in mesh.faces.iter().enumerate() {
        if face.len() < 3 {
            return Err(MeshError::FaceTooSmall { face: k, corners: face.len() }.into());
        }
        if let Some(&v) = face.iter().find(|&&v| v >= n) {
            return Err(MeshError::VertexOutOfRange { face: k, vertex: v, vertices: n }.into());
        }
        sorted.clear();
        sorted.extend_from_slice(face);
        sorted.sort_unstable();
        if let Some(w) = sorted.windows(2).find(|w| w[0] == w[1]) {
            return Err(MeshError::RepeatedVertex { face: k, vertex: w[0] }.into());
        }
    }
    for &[a, b] in &mesh.border_edges {
        if a.max(b) >= n {
            return Err(MeshError::BorderEdgeOutOfRange { a, b, vertices: n }.into());
        }
    }
    edge_faces(&mesh.faces).map(|_| ())
}

/// How many faces use each undirected edge (key: smaller vertex first); an error names the
/// first edge used by more than two faces.
pub fn edge_faces(faces: &[Vec<usize>]) -> Result<HashMap<[usize; 2], u8>> {
    let mut count: HashMap<[usize; 2], u8> = HashMap::new();
    for face in faces {
        for k in 0..face.len() {
            let (a, b) = (face[k], face[(k + 1) % face.len()]);
            let c = count.entry([a.min(b), a.max(b)]).or_default();
            *c += 1;
            if *c > 2 {
                return Err(MeshError::NonManifoldEdge { a: a.min(b), b: a.max(b) }.into());
            }
        }
    }
    Ok(count)
}

/// The boundary loops (edges with exactly one face), each from its lowest vertex.
pub fn boundary_loops(faces: &[Vec<usize>]) -> Result<Vec<Vec<usize>>> {
    let mut edges: Vec<[usize; 2]> =
        edge_faces(faces)?.into_iter().filter(|&(_, c)| c == 1).map(|(e, _)| e).collect();
    edges.sort_unstable();
    boundary::chain_loops(&edges)
}

fn loop_length(vertices: &[[f64; 3]], cycle: &[usize]) -> f64 {
    let p = |k: usize| Point::from(vertices[cycle[k % cycle.len()]]);
    (0..cycle.len()).map(|k| (p(k + 1) - p(k)).norm()).sum()
}

/// The border loop `indices` (mesh vertices, in walking order) walked anticlockwise in XY
/// from its lowest vertex on `vertices` (frame 0; see the module doc).
pub fn start_lowest(mut indices: Vec<usize>, vertices: &[[f64; 3]]) -> Vec<usize> {
    let points: Vec<Point> = indices.iter().map(|&k| Point::from(vertices[k])).collect();
    let n = points.len() as f64;
    let centre = points.iter().fold([0.0, 0.0], |c, p| [c[0] + p.x / n, c[1] + p.y / n]);
    let extent =
        points.iter().map(|p| (p.x - centre[0]).hypot(p.y - centre[1])).fold(0.0, f64::max);
    let bottom = points.iter().map(|p| p.y).fold(f64::INFINITY, f64::min);
    let level = |k: &usize| points[*k].y <= bottom + LEVEL * extent;
    let lowest = (0..points.len())
        .filter(level)
        .min_by(|&a, &b| points[a].x.total_cmp(&points[b].x))
        .unwrap_or(0);
    indices.rotate_left(lowest);
    if signed_area_xy(&points) < 0.0 {
        indices[1..].reverse();
    }
    indices
}

/// Find the border of a validated mesh on frame 0 (see the module doc for the choice), walked
/// by [`start_lowest`].
pub fn border_of(mesh: &MeshFrames) -> Result<MeshBorder> {
    let found = find_border(mesh)?;
    Ok(MeshBorder { indices: start_lowest(found.indices, &mesh.frames[0]), ..found })
}

/// The border loop as its method finds it (its start and direction are those of the search).
fn find_border(mesh: &MeshFrames) -> Result<MeshBorder> {
    validate(mesh)?;
    let vertices = &mesh.frames[0];
    if !mesh.border_edges.is_empty() {
        return Ok(MeshBorder {
            indices: boundary::single_loop(&mesh.border_edges)?,
            method: BorderMethod::BorderEdges,
        });
    }
    if mesh.faces.is_empty() {
        return Err(MeshError::NoFaces.into());
    }
    let seen = silhouette::Silhouette::render(vertices, &mesh.faces)?;
    // Touching boundary loops cannot give an outline; the silhouette still can.
    let outline = boundary_loops(&mesh.faces).ok().and_then(|loops| {
        loops
            .into_iter()
            .max_by(|a, b| loop_length(vertices, a).total_cmp(&loop_length(vertices, b)))
    });
    if let Some(outline) = outline {
        let points: Vec<Point> = outline.iter().map(|&k| Point::from(vertices[k])).collect();
        if signed_area_xy(&points).abs() >= ENCLOSES * seen.area() {
            return Ok(MeshBorder { indices: outline, method: BorderMethod::BoundaryLoop });
        }
    }
    let indices = seen.border(vertices, silhouette::EPSILON)?;
    if indices.len() < close_core::border::MIN_VERTICES {
        return Err(MeshError::SilhouetteTooSmall { vertices: indices.len() }.into());
    }
    Ok(MeshBorder { indices, method: BorderMethod::Silhouette })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square_grid(n: usize) -> MeshFrames {
        let v: Vec<[f64; 3]> =
            (0..=n).flat_map(|j| (0..=n).map(move |i| [i as f64, j as f64, 0.0])).collect();
        let id = |i: usize, j: usize| j * (n + 1) + i;
        let f = (0..n)
            .flat_map(|j| {
                (0..n).map(move |i| vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)])
            })
            .collect();
        MeshFrames::new(f, vec![v])
    }

    #[test]
    fn bad_meshes_name_the_problem() {
        let mut m = square_grid(2);
        m.faces.push(vec![0, 1, 99]);
        assert!(validate(&m).unwrap_err().to_string().contains("vertex 99"));
        let mut m = square_grid(2);
        m.faces.extend([vec![0, 1, 5], vec![1, 0, 6]]);
        assert!(validate(&m).unwrap_err().to_string().contains("edge [0, 1]"));
        let mut m = square_grid(2);
        m.faces.push(vec![0, 1]);
        assert!(validate(&m).unwrap_err().to_string().contains("at least 3"));
        let mut m = square_grid(2);
        m.faces[0] = vec![0, 1, 1];
        assert!(validate(&m).unwrap_err().to_string().contains("repeats"));
        let mut m = square_grid(2);
        m.frames.push(vec![[0.0; 3]; 3]);
        assert!(matches!(validate(&m), Err(Error::FrameSizeMismatch { frame: 1, .. })));
        let mut m = square_grid(2);
        m.frames[0][4][2] = f64::NAN;
        assert_eq!(validate(&m), Err(Error::NonFinite { frame: 0, vertex: 4 }));
    }

    /// The border's positions on frame 0, in walking order.
    fn walked(mesh: &MeshFrames) -> Vec<[f64; 3]> {
        border_of(mesh).unwrap().indices.iter().map(|&k| mesh.frames[0][k]).collect()
    }

    #[test]
    fn the_border_starts_at_its_lowest_vertex_however_the_mesh_is_numbered() {
        let grid = square_grid(3);
        let expected = walked(&grid);
        assert_eq!(expected[..3], [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]]);
        // Renumber the vertices (a fixed shuffle), list the faces backwards, each one clockwise.
        let n = grid.frames[0].len();
        let new_id: Vec<usize> = (0..n).map(|k| (7 * k + 5) % n).collect();
        let mut frame = vec![[0.0; 3]; n];
        for (k, p) in grid.frames[0].iter().enumerate() {
            frame[new_id[k]] = *p;
        }
        let faces =
            grid.faces.iter().rev().map(|f| f.iter().rev().map(|&k| new_id[k]).collect()).collect();
        assert_eq!(walked(&MeshFrames::new(faces, vec![frame])), expected);
        // Given border edges, walked clockwise from the top-right corner, give it too.
        let mut ring = grid.clone();
        let id = |i: usize, j: usize| j * 4 + i;
        let outline = [
            id(3, 3),
            id(3, 2),
            id(3, 1),
            id(3, 0),
            id(2, 0),
            id(1, 0),
            id(0, 0),
            id(0, 1),
            id(0, 2),
            id(0, 3),
            id(1, 3),
            id(2, 3),
        ];
        ring.border_edges = (0..12).map(|k| [outline[k], outline[(k + 1) % 12]]).collect();
        assert_eq!(walked(&ring), expected);
    }

    #[test]
    fn a_bottom_edge_level_up_to_noise_starts_at_its_left_end() {
        // The bottom row a little uneven (10⁻⁶ of the size): still its left corner first.
        let mut grid = square_grid(3);
        for (i, dy) in [(0, 2e-6), (1, -1e-6), (2, 0.0), (3, -2e-6)] {
            grid.frames[0][i][1] += dy;
        }
        assert_eq!(walked(&grid)[0], grid.frames[0][0]);
        // Tilted for real (a tenth of a cell over the width), the lowest end wins.
        let mut tilted = square_grid(3);
        for v in tilted.frames[0].iter_mut() {
            v[1] += 0.1 * (3.0 - v[0]) / 3.0;
        }
        assert_eq!(walked(&tilted)[0], tilted.frames[0][3]);
    }

    #[test]
    fn a_hole_does_not_become_the_outline() {
        // A 3×3 grid without its middle quad: the outline (12 vertices) and a hole (4).
        let mut m = square_grid(3);
        m.faces.remove(4);
        assert_eq!(boundary_loops(&m.faces).unwrap().len(), 2);
        let b = border_of(&m).unwrap();
        assert_eq!(b.method, BorderMethod::BoundaryLoop);
        assert_eq!(b.indices.len(), 12);
        assert_eq!(b.indices[0], 0);
    }

    #[test]
    fn a_closed_surface_uses_the_silhouette() {
        // A pillow: 8 equator vertices round a 2×2 square, an apex above and one below.
        let ring = [
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 0.0],
            [2.0, 1.0],
            [2.0, 2.0],
            [1.0, 2.0],
            [0.0, 2.0],
            [0.0, 1.0],
        ];
        let mut v: Vec<[f64; 3]> = ring.iter().map(|p| [p[0], p[1], 0.0]).collect();
        v.extend([[1.0, 1.0, 0.5], [1.0, 1.0, -0.5]]);
        let faces =
            (0..8).flat_map(|k| [vec![k, (k + 1) % 8, 8], vec![(k + 1) % 8, k, 9]]).collect();
        let m = MeshFrames::new(faces, vec![v]);
        assert!(boundary_loops(&m.faces).unwrap().is_empty());
        let b = border_of(&m).unwrap();
        assert_eq!(b.method, BorderMethod::Silhouette);
        assert_eq!(b.indices[0], 0);
        let mut sorted = b.indices.clone();
        sorted.sort();
        assert_eq!(sorted, (0..8).collect::<Vec<_>>());
    }

    #[test]
    fn a_mesh_seen_edge_on_has_no_border() {
        let v = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 0.0, 1.0], [0.0, 0.0, 1.0]];
        let m = MeshFrames::new(vec![vec![0, 1, 2, 3]], vec![v]);
        assert!(border_of(&m).unwrap_err().to_string().contains("no area"));
    }

    #[test]
    fn given_border_edges_win() {
        let mut m = square_grid(1);
        m.border_edges = vec![[0, 1], [1, 3], [3, 2], [2, 0]];
        let b = border_of(&m).unwrap();
        assert_eq!((b.method, b.indices), (BorderMethod::BorderEdges, vec![0, 1, 3, 2]));
        m.border_edges.push([0, 3]);
        assert!(border_of(&m).is_err());
    }
}
