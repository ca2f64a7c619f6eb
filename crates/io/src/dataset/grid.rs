//! Grid meshes of the rectangular shapes, and their folds.
//!
//! Kamat, Borràs, Torras, "CloSE: A Geometric Shape-Agnostic Cloth State Representation"
//! need only the cloth's border, which a mesh gives as its boundary loop. A napkin or towel
//! here is a grid of (w+1)×(h+1) vertices, id = j·(w+1) + i, with quad faces, w segments
//! along the bottom and h up the side as its outline has ([`outline`]), and normalised as
//! the outline is (a grid and its outline share the centre and the farthest vertex), so its
//! boundary loop is exactly the outline. A fold mirrors every vertex on the folded arc's
//! side of the line (interior ones too), as [`fold_border`](super::exact_fold::fold_border)
//! does to the border.
//!
//! ```
//! use close_io::dataset::grid::grid_mesh;
//! use close_io::dataset::shapes::{outline, Shape};
//! let grid = grid_mesh(Shape::Napkin).unwrap();
//! assert_eq!(grid.vertices().len(), 20 * 20);
//! assert_eq!(grid.ring().len(), outline(Shape::Napkin).points.len());
//! assert!(grid_mesh(Shape::Skirt).is_none());
//! ```

use super::exact_fold::{scale_of, top, Fold, EPS};
use super::shapes::{normalise, outline, Shape};
use close_core::border::Point;
use close_core::error::Result;

/// A flat grid mesh and its boundary (built by [`grid_mesh`] only, so indices are valid).
#[derive(Debug, Clone, PartialEq)]
pub struct GridMesh {
    vertices: Vec<Point>,
    faces: Vec<Vec<usize>>,
    ring: Vec<usize>,
}

impl GridMesh {
    pub fn vertices(&self) -> &[Point] {
        &self.vertices
    }

    /// Quads of vertex indices, anticlockwise.
    pub fn faces(&self) -> &[Vec<usize>] {
        &self.faces
    }

    /// The boundary vertices in the outline's order: anticlockwise from the bottom-left
    /// corner, as the mesh's border is found.
    pub fn ring(&self) -> &[usize] {
        &self.ring
    }

    /// The mesh folded along border parameters `f1`, `f2` of its boundary ring: every vertex
    /// on the folded arc's side of the line mirrored and stacked `thickness` above the
    /// cloth. Errors as [`fold_border`](super::exact_fold::fold_border) does.
    pub fn fold(&self, f1: f64, f2: f64, thickness: f64) -> Result<Vec<Point>> {
        let boundary: Vec<Point> = self.ring.iter().map(|&k| self.vertices[k]).collect();
        let fold = Fold::of(&boundary, f1, f2, thickness)?;
        let top = top(&self.vertices);
        let tolerance = EPS * scale_of(&self.vertices);
        Ok(self
            .vertices
            .iter()
            .map(|p| {
                if fold.side * fold.mirror.side(p) > tolerance {
                    fold.turn_over(p, top)
                } else {
                    *p
                }
            })
            .collect())
    }
}

/// The grid mesh of a rectangular shape (see the module doc); `None` for a shape that is
/// no axis-aligned rectangle.
pub fn grid_mesh(kind: Shape) -> Option<GridMesh> {
    let &[[0.0, 0.0], [width, 0.0], [_, height], [0.0, _]] = kind.polygon() else {
        return None;
    };
    let o = outline(kind);
    let (w, h) = (o.side_starts[1] - o.side_starts[0], o.side_starts[2] - o.side_starts[1]);
    let id = |i: usize, j: usize| j * (w + 1) + i;
    let raw: Vec<Point> = (0..=h)
        .flat_map(|j| {
            (0..=w).map(move |i| {
                Point::new(i as f64 / w as f64 * width, j as f64 / h as f64 * height, 0.0)
            })
        })
        .collect();
    let faces = (0..h)
        .flat_map(|j| {
            (0..w).map(move |i| vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)])
        })
        .collect();
    let ring = (0..w)
        .map(|i| id(i, 0))
        .chain((0..h).map(|j| id(w, j)))
        .chain((0..w).map(|i| id(w - i, h)))
        .chain((0..h).map(|j| id(0, h - j)))
        .collect();
    Some(GridMesh { vertices: normalise(&raw), faces, ring })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dataset::exact_fold::fold_border;
    use close_core::error::{Error, FoldProblem};

    fn worst(a: &[Point], b: &[Point]) -> f64 {
        a.iter().zip(b).map(|(p, q)| (p - q).norm()).fold(0.0, f64::max)
    }

    #[test]
    fn the_boundary_ring_is_the_outline() {
        for kind in [Shape::Napkin, Shape::Towel] {
            let grid = grid_mesh(kind).unwrap();
            let o = outline(kind);
            let ring: Vec<Point> = grid.ring().iter().map(|&k| grid.vertices()[k]).collect();
            assert!(worst(&ring, &o.points) < 1e-12, "{kind:?}");
            let (w, h) = (o.side_starts[1], o.side_starts[2] - o.side_starts[1]);
            assert_eq!(grid.vertices().len(), (w + 1) * (h + 1));
            assert_eq!(grid.faces().len(), w * h);
            assert!(grid.faces().iter().flatten().all(|&k| k < grid.vertices().len()));
        }
        for kind in [Shape::CircularTowel, Shape::TShirt, Shape::Top, Shape::Trousers, Shape::Skirt]
        {
            assert!(grid_mesh(kind).is_none(), "{kind:?}");
        }
    }

    #[test]
    fn a_mesh_folds_as_its_border_and_its_inside_follows() {
        let grid = grid_mesh(Shape::Napkin).unwrap();
        let o = outline(Shape::Napkin);
        for [f1, f2] in [[9.5, 47.5], [0.0, 38.0], [12.0, 25.0]] {
            let folded = grid.fold(f1, f2, 0.01).unwrap();
            let ring: Vec<Point> = grid.ring().iter().map(|&k| folded[k]).collect();
            assert!(
                worst(&ring, &fold_border(&o.points, f1, f2, 0.01).unwrap()) < 1e-12,
                "({f1}, {f2})"
            );
            let moved = grid.vertices().iter().zip(&folded).filter(|(p, q)| p != q).count();
            let moved_on_border =
                grid.ring().iter().filter(|&&k| folded[k] != grid.vertices()[k]).count();
            assert!(moved > moved_on_border, "({f1}, {f2}): {moved} moved");
            // Folded vertices lie on one layer's height, the rest on the table.
            assert!(folded.iter().all(|p| p.z == 0.0 || p.z == 0.01));
        }
        assert!(matches!(
            grid.fold(5.0, 5.5, 0.01),
            Err(Error::InvalidFold { problem: FoldProblem::EmptyArc, .. })
        ));
        assert!(matches!(
            grid.fold(9.5, 47.5, f64::NAN),
            Err(Error::InvalidFold { problem: FoldProblem::NotFinite, .. })
        ));
    }
}
