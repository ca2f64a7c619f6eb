//! The silhouette border of a garment shell, seen from above: how Kamat, Borràs, Torras,
//! "CloSE: A Geometric Shape-Agnostic Cloth State Representation" take the border of a
//! garment mesh that has no single boundary loop.
//!
//! Frame 0 is rendered looking down −z onto a square-celled grid of at most
//! [`GRID`]×[`GRID`] cells over the XY bounding box: a cell is covered when its centre lies
//! in a projected triangle (polygons are fanned), and it remembers the visible surface
//! there — the highest z — through the nearest (in XY) vertex of that triangle. The largest
//! 8-connected covered region is traced with Moore-neighbour tracing (Jacob's stopping
//! rule) into its outer contour; each contour cell gives its visible vertex; an ε-cover
//! then thins the walk: a vertex is kept only when it lies farther than ε (in XY, in units
//! of the mesh's normalised size) from the last kept one and was not kept before, and kept
//! vertices within ε of the first are dropped at the end, so the border closes cleanly.
//!
//! ```
//! use close_io::mesh::silhouette::Silhouette;
//! // A unit square of two triangles: the border visits its four corners.
//! let v = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
//! let s = Silhouette::render(&v, &[vec![0, 1, 2], vec![0, 2, 3]]).unwrap();
//! assert!((s.area() - 1.0).abs() < 0.02);
//! let mut border = s.border(&v, 0.04).unwrap();
//! border.sort();
//! assert_eq!(border, vec![0, 1, 2, 3]);
//! ```

use std::collections::{HashSet, VecDeque};

use close_core::border::{Normalisation, Point};
use close_core::error::{DegenerateReason, Error, MeshError, Result};

/// Cells along the longer side of the bounding box (plus a margin of empty cells).
pub const GRID: usize = 256;
/// The paper's ε of the ε-cover, in normalised units (farthest vertex at distance 1).
pub const EPSILON: f64 = 0.04;
/// Most cell tests one rendering may make (triangles × the cells of their bounding boxes).
/// A polygon of many corners fans into long, thin triangles that each span the grid, so
/// the work is refused up front rather than left to grow with corners × grid area.
pub const MAX_CELL_TESTS: usize = 1 << 25;
/// Empty cells around the box, so every contour is closed inside the grid.
const MARGIN: usize = 2;
const NO_VERTEX: u32 = u32::MAX;

/// A coverage mask of a mesh seen from +z, with the visible vertex of every covered cell.
#[derive(Debug, Clone)]
pub struct Silhouette {
    nx: usize,
    ny: usize,
    cell: f64,
    /// Highest z seen in each cell (−∞ where nothing covers it).
    depth: Vec<f64>,
    /// Visible vertex per cell, `NO_VERTEX` where uncovered.
    visible: Vec<u32>,
}

impl Silhouette {
    /// Rasterise the faces of `vertices` seen from above.
    pub fn render(vertices: &[[f64; 3]], faces: &[Vec<usize>]) -> Result<Silhouette> {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for v in faces.iter().flatten().map(|&k| vertices[k]) {
            for a in 0..2 {
                lo[a] = lo[a].min(v[a]);
                hi[a] = hi[a].max(v[a]);
            }
        }
        let extent = (hi[0] - lo[0]).max(hi[1] - lo[1]);
        // +∞: finite coordinates whose span overflows; −∞: no face at all.
        if extent == f64::INFINITY {
            return Err(Error::Degenerate {
                frame: 0,
                reason: DegenerateReason::TooLargeToNormalise,
            });
        }
        if extent <= 0.0 {
            return Err(MeshError::NoExtent.into());
        }
        let cell = extent / (GRID - 2 * MARGIN) as f64;
        let cells = |a: usize| ((hi[a] - lo[a]) / cell).ceil() as usize + 2 * MARGIN;
        let (nx, ny) = (cells(0), cells(1));
        let origin = [lo[0] - MARGIN as f64 * cell, lo[1] - MARGIN as f64 * cell];
        let mut s = Silhouette {
            nx,
            ny,
            cell,
            depth: vec![f64::NEG_INFINITY; nx * ny],
            visible: vec![NO_VERTEX; nx * ny],
        };
        let triangles = || {
            faces.iter().flat_map(|face| {
                (1..face.len().saturating_sub(1)).map(|k| [face[0], face[k], face[k + 1]])
            })
        };
        let work = triangles().fold(0usize, |sum, tri| {
            let [cols, rows] = s.bounding_cells(&tri.map(|k| vertices[k]), origin);
            sum.saturating_add(cols.count().saturating_mul(rows.count()))
        });
        if work > MAX_CELL_TESTS {
            return Err(Error::too_large(
                "silhouette cell tests (face triangles × cells of their bounding boxes)",
                work,
                MAX_CELL_TESTS,
            ));
        }
        for tri in triangles() {
            s.fill_triangle(tri, vertices, origin);
        }
        if s.visible.iter().all(|&v| v == NO_VERTEX) {
            return Err(MeshError::NoArea.into());
        }
        Ok(s)
    }

    /// The columns and rows of the cells whose centres lie in the triangle's bounding box.
    fn bounding_cells(&self, p: &[[f64; 3]; 3], origin: [f64; 2]) -> [std::ops::Range<usize>; 2] {
        [(0, self.nx), (1, self.ny)].map(|(a, n)| {
            let lo = p.iter().map(|v| v[a]).fold(f64::INFINITY, f64::min);
            let hi = p.iter().map(|v| v[a]).fold(f64::NEG_INFINITY, f64::max);
            let first = ((lo - origin[a]) / self.cell - 0.5).ceil().max(0.0) as usize;
            let last = (((hi - origin[a]) / self.cell - 0.5).floor().max(0.0) as usize).min(n - 1);
            first..last + 1
        })
    }

    fn fill_triangle(&mut self, tri: [usize; 3], vertices: &[[f64; 3]], origin: [f64; 2]) {
        let p = tri.map(|k| vertices[k]);
        let det =
            (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
        if det.abs() <= f64::EPSILON * self.cell * self.cell {
            return; // seen edge-on: covers nothing
        }
        let [cols, rows] = self.bounding_cells(&p, origin);
        // Centres exactly on a shared edge count for both triangles, so no gap opens.
        let tolerance = -1e-9;
        for j in rows {
            let y = origin[1] + (j as f64 + 0.5) * self.cell;
            for i in cols.clone() {
                let x = origin[0] + (i as f64 + 0.5) * self.cell;
                let b1 = ((x - p[0][0]) * (p[2][1] - p[0][1])
                    - (p[2][0] - p[0][0]) * (y - p[0][1]))
                    / det;
                let b2 = ((p[1][0] - p[0][0]) * (y - p[0][1])
                    - (x - p[0][0]) * (p[1][1] - p[0][1]))
                    / det;
                let b0 = 1.0 - b1 - b2;
                if b0 < tolerance || b1 < tolerance || b2 < tolerance {
                    continue;
                }
                let z = b0 * p[0][2] + b1 * p[1][2] + b2 * p[2][2];
                let c = j * self.nx + i;
                if z > self.depth[c] {
                    self.depth[c] = z;
                    let d2 = |v: &[f64; 3]| (v[0] - x).powi(2) + (v[1] - y).powi(2);
                    let nearest =
                        (0..3).min_by(|&a, &b| d2(&p[a]).total_cmp(&d2(&p[b]))).unwrap_or(0);
                    self.visible[c] = tri[nearest] as u32;
                }
            }
        }
    }

    fn covered(&self, i: isize, j: isize) -> bool {
        i >= 0
            && j >= 0
            && (i as usize) < self.nx
            && (j as usize) < self.ny
            && self.visible[j as usize * self.nx + i as usize] != NO_VERTEX
    }

    /// Covered area, in the mesh's units squared.
    pub fn area(&self) -> f64 {
        self.visible.iter().filter(|&&v| v != NO_VERTEX).count() as f64 * self.cell * self.cell
    }

    /// The cells of the largest 8-connected covered region.
    fn largest_region(&self) -> HashSet<(isize, isize)> {
        let mut seen = vec![false; self.nx * self.ny];
        let mut best: HashSet<(isize, isize)> = HashSet::new();
        for start in 0..self.nx * self.ny {
            if seen[start] || self.visible[start] == NO_VERTEX {
                continue;
            }
            seen[start] = true;
            let mut region = HashSet::new();
            let mut queue =
                VecDeque::from([((start % self.nx) as isize, (start / self.nx) as isize)]);
            while let Some((i, j)) = queue.pop_front() {
                region.insert((i, j));
                for (di, dj) in NEIGHBOURS {
                    let (a, b) = (i + di, j + dj);
                    if self.covered(a, b)
                        && !std::mem::replace(&mut seen[b as usize * self.nx + a as usize], true)
                    {
                        queue.push_back((a, b));
                    }
                }
            }
            if region.len() > best.len() {
                best = region;
            }
        }
        best
    }

    /// Outer contour of the largest region, as cells in walking order.
    fn contour(&self) -> Vec<(isize, isize)> {
        let region = self.largest_region();
        let inside = |c: (isize, isize)| region.contains(&c);
        let step = |p: (isize, isize), d: usize| (p.0 + NEIGHBOURS[d].0, p.1 + NEIGHBOURS[d].1);
        // First cell in raster order: its west neighbour is outside, so tracing starts there.
        let Some(&start) = region.iter().min_by_key(|&&(i, j)| (j, i)) else {
            return Vec::new();
        };
        let mut contour = vec![start];
        // `back`: direction (index in NEIGHBOURS) of the outside cell we arrived from.
        let (mut p, mut back) = (start, 0usize);
        let mut first_move = None;
        for _ in 0..4 * region.len() + 8 {
            // Sweep p's neighbours clockwise from the one after `back`.
            let Some(d) = (1..=8).map(|k| (back + k) % 8).find(|&d| inside(step(p, d))) else {
                break; // an isolated cell
            };
            let q = step(p, d);
            // Stop when the first move repeats (the trace has gone round once).
            if first_move == Some((p, q)) {
                break;
            }
            first_move.get_or_insert((p, q));
            // The new backtrack: the cell checked just before q, seen from q.
            let b = step(p, (d + 7) % 8);
            back = NEIGHBOURS.iter().position(|&(di, dj)| (q.0 + di, q.1 + dj) == b).unwrap_or(0);
            p = q;
            contour.push(p);
        }
        // The walk ends back at the start cell; it is listed once.
        if contour.len() > 1 && contour.last() == Some(&start) {
            contour.pop();
        }
        contour
    }

    /// The closed border: contour cells → visible vertices → ε-cover (ε in normalised units).
    pub fn border(&self, vertices: &[[f64; 3]], epsilon: f64) -> Result<Vec<usize>> {
        let points: Vec<Point> = vertices.iter().map(|v| Point::new(v[0], v[1], v[2])).collect();
        let reach = epsilon * Normalisation::of(&points)?.radius;
        let far = |a: usize, b: usize| {
            (vertices[a][0] - vertices[b][0]).hypot(vertices[a][1] - vertices[b][1]) > reach
        };
        let mut kept: Vec<usize> = Vec::new();
        let mut used = HashSet::new();
        for (i, j) in self.contour() {
            let v = self.visible[j as usize * self.nx + i as usize] as usize;
            if kept.last().is_none_or(|&last| far(last, v)) && used.insert(v) {
                kept.push(v);
            }
        }
        while kept.len() > 1 && !far(kept[kept.len() - 1], kept[0]) {
            kept.pop();
        }
        Ok(kept)
    }
}

/// The 8 neighbours clockwise (x right, y up) starting west.
const NEIGHBOURS: [(isize, isize); 8] =
    [(-1, 0), (-1, 1), (0, 1), (1, 1), (1, 0), (1, -1), (0, -1), (-1, -1)];

#[cfg(test)]
mod tests {
    use super::*;

    /// An L-shaped plate of unit squares, for contour checks.
    fn l_shape() -> (Vec<[f64; 3]>, Vec<Vec<usize>>) {
        let v = vec![
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
            [1.0, 2.0, 0.0],
            [0.0, 2.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let f = vec![vec![0, 1, 2, 3, 6], vec![6, 3, 4, 5]];
        (v, f)
    }

    #[test]
    fn a_polygon_of_many_corners_is_refused_before_rendering() {
        // 20 000 corners on a circle fan into triangles that each span the grid.
        let k = 20_000;
        let v: Vec<[f64; 3]> = (0..k)
            .map(|i| (i as f64 / k as f64 * std::f64::consts::TAU).sin_cos())
            .map(|(s, c)| [c, s, 0.0])
            .collect();
        let err = Silhouette::render(&v, &[(0..k).collect()]).unwrap_err();
        assert!(
            matches!(err, Error::TooLarge { limit, .. } if limit == MAX_CELL_TESTS as u64),
            "{err}"
        );
        // The same circle as a fan of 64 corners renders.
        let v: Vec<[f64; 3]> = (0..64)
            .map(|i| (i as f64 / 64.0 * std::f64::consts::TAU).sin_cos())
            .map(|(s, c)| [c, s, 0.0])
            .collect();
        let s = Silhouette::render(&v, &[(0..64).collect()]).unwrap();
        assert!((s.area() - std::f64::consts::PI).abs() < 0.05, "{}", s.area());
    }

    #[test]
    fn contour_walks_the_outline_once_in_order() {
        let (v, f) = l_shape();
        let s = Silhouette::render(&v, &f).unwrap();
        assert!((s.area() - 3.0).abs() < 0.05, "{}", s.area());
        let border = s.border(&v, EPSILON).unwrap();
        // Vertex 6 sits on the outline too (the left side's midpoint).
        let mut sorted = border.clone();
        sorted.sort();
        assert_eq!(sorted, vec![0, 1, 2, 3, 4, 5, 6]);
        // Consecutive in the polygon's cyclic order (either direction).
        let ring = [0, 1, 2, 3, 4, 5, 6];
        let pos = |v: usize| ring.iter().position(|&r| r == v).unwrap() as isize;
        let steps: Vec<isize> =
            (0..7).map(|k| (pos(border[(k + 1) % 7]) - pos(border[k])).rem_euclid(7)).collect();
        assert!(steps.iter().all(|&s| s == 1) || steps.iter().all(|&s| s == 6), "{border:?}");
    }

    #[test]
    fn the_top_layer_is_the_visible_one() {
        // Two coincident squares; the upper one (z = 1) owns vertices 4..8.
        let mut v: Vec<[f64; 3]> = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
            .iter()
            .map(|p| [p[0], p[1], 0.0])
            .collect();
        v.extend(v.clone().iter().map(|p| [p[0], p[1], 1.0]));
        let f = vec![vec![0, 1, 2, 3], vec![4, 5, 6, 7]];
        let mut b = Silhouette::render(&v, &f).unwrap().border(&v, EPSILON).unwrap();
        b.sort();
        assert_eq!(b, vec![4, 5, 6, 7]);
    }

    #[test]
    fn no_area_is_an_error() {
        let v = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 0.0, 1.0]];
        assert!(Silhouette::render(&v, &[vec![0, 1, 2]])
            .unwrap_err()
            .to_string()
            .contains("no area"));
        let p = [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, 2.0]];
        assert!(Silhouette::render(&p, &[vec![0, 1, 2]])
            .unwrap_err()
            .to_string()
            .contains("no extent"));
    }

    #[test]
    fn epsilon_cover_thins_a_fine_outline() {
        // A 40×40 grid of a unit square: 160 outline vertices 0.025 apart.
        let n = 40;
        let v: Vec<[f64; 3]> = (0..=n)
            .flat_map(|j| (0..=n).map(move |i| [i as f64 / n as f64, j as f64 / n as f64, 0.0]))
            .collect();
        let id = |i: usize, j: usize| j * (n + 1) + i;
        let f: Vec<Vec<usize>> = (0..n)
            .flat_map(|j| {
                (0..n).map(move |i| vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)])
            })
            .collect();
        let b = Silhouette::render(&v, &f).unwrap().border(&v, EPSILON).unwrap();
        // Normalised radius is √2/2, so ε = 0.04 reaches 0.028: every second outline vertex.
        assert!((70..=90).contains(&b.len()), "{}", b.len());
        let on_outline = |k: usize| {
            let p = v[k];
            p[0] == 0.0 || p[0] == 1.0 || p[1] == 0.0 || p[1] == 1.0
        };
        assert!(b.iter().all(|&k| on_outline(k)));
        let unique: HashSet<_> = b.iter().collect();
        assert_eq!(unique.len(), b.len());
    }
}
