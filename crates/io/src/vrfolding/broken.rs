//! BiFold's broken-mesh test (Barbany et al., ICRA 2025; the filter the CloSE paper applied
//! to VR-Folding before Table I).
//!
//! Over the edges of every triangle (each triangle gives its three edges, so an interior
//! edge counts twice, as trimesh's `edges` does), the largest length's z-score is
//! z = (max − mean) / std (population std). A frame is broken when z on its world positions
//! divided by z on the canonical (NOCS) positions of the same mesh is ≥ [`RATIO`]: a few
//! torn, stretched edges stand out far more than the mesh's own spread of edge lengths.
//!
//! ```
//! use close_io::vrfolding::broken::{max_edge_zscore, RATIO};
//! let v = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
//! let faces = [[0, 1, 2], [0, 2, 3]];
//! let z = max_edge_zscore(&v, &faces).unwrap();
//! assert!((z - std::f64::consts::SQRT_2).abs() < 1e-9); // 4 sides and 2 diagonals
//! assert!(RATIO == 3.5);
//! ```

/// BiFold's threshold on the z-score ratio.
pub const RATIO: f64 = 3.5;

/// The largest edge length's z-score over every triangle's three edges; `None` when all
/// edges have the same length (no spread: the z-score is undefined).
pub fn max_edge_zscore(vertices: &[[f64; 3]], faces: &[[usize; 3]]) -> Option<f64> {
    let length = |a: usize, b: usize| {
        let (p, q) = (vertices[a], vertices[b]);
        ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
    };
    let (mut sum, mut sum2, mut max) = (0.0, 0.0, 0.0_f64);
    for &[a, b, c] in faces {
        for l in [length(a, b), length(b, c), length(c, a)] {
            sum += l;
            sum2 += l * l;
            max = max.max(l);
        }
    }
    let count = 3.0 * faces.len() as f64;
    let mean = sum / count;
    let std = (sum2 / count - mean * mean).max(0.0).sqrt();
    (std > 1e-12 * mean.max(1e-300) && std.is_finite()).then(|| (max - mean) / std)
}

/// BiFold's verdict: the frame's z-score over the canonical mesh's is ≥ [`RATIO`]. A frame
/// whose edges all have the same length is not broken; a canonical mesh with no spread
/// makes any spread in the frame count as broken.
pub fn is_broken(frame_zscore: Option<f64>, canonical_zscore: Option<f64>) -> bool {
    match (frame_zscore, canonical_zscore) {
        (None, _) => false,
        (Some(_), None) => true,
        (Some(z), Some(zc)) => z / zc >= RATIO,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(n: usize) -> (Vec<[f64; 3]>, Vec<[usize; 3]>) {
        let v = (0..=n).flat_map(|j| (0..=n).map(move |i| [i as f64, j as f64, 0.0])).collect();
        let id = |i: usize, j: usize| j * (n + 1) + i;
        let f = (0..n)
            .flat_map(|j| {
                (0..n).flat_map(move |i| {
                    [
                        [id(i, j), id(i + 1, j), id(i + 1, j + 1)],
                        [id(i, j), id(i + 1, j + 1), id(i, j + 1)],
                    ]
                })
            })
            .collect();
        (v, f)
    }

    #[test]
    fn a_thrown_vertex_breaks_the_mesh_and_a_rigid_move_does_not() {
        let (rest, faces) = grid(10);
        let canonical = max_edge_zscore(&rest, &faces);
        let moved: Vec<[f64; 3]> = rest.iter().map(|p| [3.0 - p[1], p[0] + 7.0, 0.5]).collect();
        assert!(!is_broken(max_edge_zscore(&moved, &faces), canonical));
        let mut torn = rest.clone();
        torn[60][2] += 8.0;
        let z = max_edge_zscore(&torn, &faces).unwrap();
        assert!(z / canonical.unwrap() >= RATIO, "ratio {}", z / canonical.unwrap());
        assert!(is_broken(Some(z), canonical));
    }

    #[test]
    fn equal_edges_have_no_zscore() {
        let v = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.5, 3f64.sqrt() / 2.0, 0.0]];
        assert_eq!(max_edge_zscore(&v, &[[0, 1, 2]]), None);
        assert!(!is_broken(None, Some(1.0)));
        assert!(is_broken(Some(2.0), None));
    }

    #[test]
    fn matches_the_population_formula() {
        let (v, f) = grid(3);
        let lengths: Vec<f64> = f
            .iter()
            .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
            .map(|(a, b)| ((v[a][0] - v[b][0]).powi(2) + (v[a][1] - v[b][1]).powi(2)).sqrt())
            .collect();
        let mean = lengths.iter().sum::<f64>() / lengths.len() as f64;
        let std =
            (lengths.iter().map(|l| (l - mean).powi(2)).sum::<f64>() / lengths.len() as f64).sqrt();
        let max = lengths.iter().cloned().fold(0.0, f64::max);
        assert!((max_edge_zscore(&v, &f).unwrap() - (max - mean) / std).abs() < 1e-9);
    }
}
