//! The dGLI disk: the dGLI of every pair of border edges, laid out on concentric rings.
//!
//! Storage is the condensed pair vector of the reference: pairs (i, j), i < j, row-major,
//! index `i·N − i(i+1)/2 + j − i − 1`.
//!
//! Layout (the dGLI disk of Kamat, Borràs, Torras, "CloSE: A Geometric Shape-Agnostic
//! Cloth State Representation"): pair (i, j) has cyclic distance
//! d = min(|i−j|, N−|i−j|), 1 ≤ d ≤ L = ⌊N/2⌋. With a the edge from which walking d edges forward reaches the other, the pair sits on
//! layer d (1 is the rim), radius r = (L − d + 1)/L, angle θ = π(2a + d + 1)/N mod 2π: the
//! midpoint between the two edge midpoints along the shorter arc, with vertex k at 2πk/N.
//! When N is even, a pair with d = N/2 is reached from both ends and sits at both angles.
//!
//! ```
//! use close_core::disk::{condensed_index, Disk};
//! assert_eq!(condensed_index(5, 0, 1), 0);
//! assert_eq!(condensed_index(5, 3, 4), 9);
//! let disk = Disk::from_values(5, vec![0.0; 10]).unwrap();
//! // Edges 4 and 0 meet at vertex 0: layer 1, radius 1, angle 0.
//! let cell = disk.position(4, 0);
//! assert_eq!((cell.layer, cell.radius, cell.angle), (1, 1.0, 0.0));
//! ```

use std::f64::consts::{PI, TAU};

use rayon::prelude::*;

use crate::border::{prepare, Normalisation, Point};
use crate::budget::Deadline;
use crate::error::{Error, Result};
use crate::gli::dgli_each;

/// Index of pair (i, j), i < j, in the condensed vector of an N-edge border.
#[inline]
pub fn condensed_index(n: usize, i: usize, j: usize) -> usize {
    debug_assert!(i < j && j < n);
    i * n - i * (i + 1) / 2 + j - i - 1
}

/// Where one pair of edges sits on the disk.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Position {
    /// Ring, 1 (rim) … ⌊N/2⌋ (centre): the cyclic distance between the edges.
    pub layer: usize,
    /// Outer radius of the ring, (L − d + 1)/L.
    pub radius: f64,
    /// Angle in [0, 2π) of the midpoint of the shorter arc between the edge midpoints.
    pub angle: f64,
    /// The edge from which walking `layer` edges forward reaches the other one.
    pub from_edge: usize,
}

/// A dGLI disk of an N-edge border.
#[derive(Debug, Clone, PartialEq)]
pub struct Disk {
    n: usize,
    values: Vec<f64>,
}

impl Disk {
    /// The dGLI of every edge pair of the closed border `points` (both cores, row by row).
    pub fn of_border(points: &[Point]) -> Disk {
        // A default deadline never expires: every row is computed.
        Disk { n: points.len(), values: pair_values(points, &Deadline::default()) }
    }

    /// [`Disk::of_border`] that gives up with [`Error::Cancelled`] once `deadline` expires,
    /// checked before every row (N dGLI values), so a stopped job frees its core at once.
    pub(crate) fn of_border_until(points: &[Point], deadline: &Deadline) -> Result<Disk> {
        let values = pair_values(points, deadline);
        deadline.check()?;
        Ok(Disk { n: points.len(), values })
    }

    /// A disk from a condensed vector; errors when the length is not N(N−1)/2.
    pub fn from_values(n: usize, values: Vec<f64>) -> Result<Disk> {
        if n < 2 || values.len() != n * (n - 1) / 2 {
            return Err(Error::InvalidArgument(format!(
                "a disk of {n} edges has {} cells, got {}",
                n * n.saturating_sub(1) / 2,
                values.len()
            )));
        }
        Ok(Disk { n, values })
    }

    /// Number of edges (= vertices) of the border.
    pub fn n(&self) -> usize {
        self.n
    }

    /// Number of rings, L = ⌊N/2⌋.
    pub fn layers(&self) -> usize {
        self.n / 2
    }

    /// The condensed pair vector.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// Value of the pair of edges i and j (any order, i ≠ j).
    #[inline]
    pub fn get(&self, i: usize, j: usize) -> f64 {
        let (i, j) = if i < j { (i, j) } else { (j, i) };
        self.values[condensed_index(self.n, i, j)]
    }

    /// Value of the pair of edge `a` and edge `a + d` (cyclic): ring d, angle of [`Self::position`].
    #[inline]
    pub fn ring_value(&self, d: usize, a: usize) -> f64 {
        self.get(a % self.n, (a + d) % self.n)
    }

    /// Where pair (i, j) sits. For d = N/2 this gives the angle reached from the lower edge.
    pub fn position(&self, i: usize, j: usize) -> Position {
        position(self.n, i, j)
    }

    /// Elementwise map of two disks of the same size.
    fn zip_with(&self, other: &Disk, f: impl Fn(f64, f64) -> f64) -> Disk {
        assert_eq!(self.n, other.n, "disks of different sizes");
        Disk {
            n: self.n,
            values: self.values.iter().zip(&other.values).map(|(&a, &b)| f(a, b)).collect(),
        }
    }

    /// The abs diff disk | |end| − |start| | (shows the fold curve). `self` is the start.
    pub fn abs_diff(&self, end: &Disk) -> Disk {
        self.zip_with(end, |s, e| (e.abs() - s.abs()).abs())
    }

    /// The signed diff disk Δ = end − start (shows which side folded). `self` is the start.
    pub fn signed_diff(&self, end: &Disk) -> Disk {
        self.zip_with(end, |s, e| e - s)
    }
}

/// The condensed pair vector of `points`, rows in parallel; rows started after `deadline`
/// expired are left at zero (the caller checks the deadline).
fn pair_values(points: &[Point], deadline: &Deadline) -> Vec<f64> {
    let n = points.len();
    let mut values = vec![0.0; n * n.saturating_sub(1) / 2];
    let mut rows: Vec<(usize, &mut [f64])> = Vec::with_capacity(n);
    let mut rest = values.as_mut_slice();
    for i in 0..n.saturating_sub(1) {
        let (row, tail) = rest.split_at_mut(n - 1 - i);
        rows.push((i, row));
        rest = tail;
    }
    rows.into_par_iter().with_min_len(4).for_each(|(i, row)| {
        if deadline.expired() {
            return;
        }
        let (a, b) = (&points[i], &points[(i + 1) % n]);
        let mut slots = row.iter_mut();
        dgli_each((i + 1..n).map(|j| [a, b, &points[j], &points[(j + 1) % n]]), |v| {
            if let Some(slot) = slots.next() {
                *slot = v;
            }
        });
    });
    values
}

/// The dGLI disk of one border state, as an analysis computes its frames' disks: `border`
/// and its `reference` (the flat start frame whose normalisation and orientation apply,
/// since dGLI scales with 1/size; by default `border` itself) are validated together by
/// [`prepare`], then `border` is normalised by the reference's transform.
///
/// ```
/// use close_core::{budget::Deadline, disk};
/// let square = vec![[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 2.0, 0.0], [0.0, 2.0, 0.0]];
/// let d = disk::of_state(square.clone(), None, &Deadline::default()).unwrap();
/// assert_eq!(d.n(), 4);
/// assert!(disk::of_state(vec![[0.0; 3]; 4], None, &Deadline::default()).is_err());
/// ```
pub fn of_state(
    border: Vec<[f64; 3]>,
    reference: Option<Vec<[f64; 3]>>,
    deadline: &Deadline,
) -> Result<Disk> {
    let frames = match reference {
        Some(reference) => vec![reference, border],
        None => vec![border],
    };
    let prepared = prepare(frames)?;
    // prepare gives one frame per frame given: the reference first, the state last.
    let start = prepared.frames.first().map_or(&[][..], Vec::as_slice);
    let now = prepared.frames.last().map_or(&[][..], Vec::as_slice);
    Disk::of_border_until(&Normalisation::of(start)?.apply_all(now), deadline)
}

/// Where pair (i, j) of an N-edge border sits on the disk (see the module doc).
pub fn position(n: usize, i: usize, j: usize) -> Position {
    let (lo, hi) = if i < j { (i, j) } else { (j, i) };
    let forward = hi - lo;
    let (from_edge, layer) = if 2 * forward <= n { (lo, forward) } else { (hi, n - forward) };
    let l = n / 2;
    let angle = (PI * (2 * from_edge + layer + 1) as f64 / n as f64).rem_euclid(TAU);
    Position { layer, radius: (l - layer + 1) as f64 / l as f64, angle, from_edge }
}

/// Angle of ring `d`'s cell that starts at edge `a`: π(2a + d + 1)/N.
#[inline]
pub(crate) fn ring_angle(n: usize, d: usize, a: usize) -> f64 {
    (PI * (2 * a + d + 1) as f64 / n as f64).rem_euclid(TAU)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn condensed_index_walks_rows_in_order() {
        let n = 7;
        let mut k = 0;
        for i in 0..n {
            for j in i + 1..n {
                assert_eq!(condensed_index(n, i, j), k);
                k += 1;
            }
        }
    }

    #[test]
    fn positions_follow_the_spec() {
        let n = 8;
        // Adjacent edges 2 and 3 meet at vertex 3.
        let p = position(n, 2, 3);
        assert_eq!((p.layer, p.radius), (1, 1.0));
        assert!((p.angle - TAU * 3.0 / 8.0).abs() < 1e-12);
        // Edges 7 and 1 are two apart through vertex 0: midpoint at vertex 0.5.
        let p = position(n, 1, 7);
        assert_eq!((p.layer, p.from_edge), (2, 7));
        assert!((p.angle - TAU * 0.5 / 8.0).abs() < 1e-12);
        // Centre ring.
        assert!((position(n, 0, 4).radius - 0.25).abs() < 1e-12);
        // The reference's angle is half an edge earlier.
        let p = position(n, 1, 5);
        let reference = (1 + 5) as f64 * PI / n as f64;
        assert!((p.angle - PI / n as f64 - reference).abs() < 1e-12);
    }

    #[test]
    fn a_cancelled_disk_stops_with_an_error() {
        let ring: Vec<Point> = (0..40)
            .map(|k| Point::new((k as f64 * 0.157).cos(), (k as f64 * 0.157).sin(), 0.0))
            .collect();
        let full = Disk::of_border_until(&ring, &Deadline::default()).unwrap();
        assert_eq!(full, Disk::of_border(&ring));
        let stopped = Deadline::default();
        stopped.cancel();
        assert_eq!(Disk::of_border_until(&ring, &stopped), Err(Error::Cancelled));
    }

    #[test]
    fn a_state_is_normalised_by_its_reference() {
        let square = |s: f64, dx: f64| {
            vec![[dx, 0.0, 0.0], [dx + s, 0.0, 0.0], [dx + s, s, 0.0], [dx, s, 0.0]]
        };
        let never = Deadline::default();
        // Position and size of the reference do not matter when the state is the reference.
        let a = of_state(square(1.0, 0.0), None, &never).unwrap();
        assert_eq!(a, of_state(square(1.0, 0.0), Some(square(1.0, 0.0)), &never).unwrap());
        let b = of_state(square(3.0, 5.0), None, &never).unwrap();
        assert!(a.values().iter().zip(b.values()).all(|(x, y)| (x - y).abs() < 1e-9));
        // A small state against a large reference is a different disk: dGLI scales with 1/size.
        let small = of_state(square(1.0, 0.0), Some(square(3.0, 0.0)), &never).unwrap();
        assert_ne!(small, a);
        assert!(matches!(
            of_state(square(1.0, 0.0)[..3].to_vec(), None, &never),
            Err(Error::TooFewVertices { .. })
        ));
    }

    #[test]
    fn diff_disks() {
        let start = Disk::from_values(3, vec![1.0, -2.0, 0.5]).unwrap();
        let end = Disk::from_values(3, vec![-1.0, 3.0, 0.0]).unwrap();
        assert_eq!(start.abs_diff(&end).values(), &[0.0, 1.0, 0.5]);
        assert_eq!(start.signed_diff(&end).values(), &[-2.0, 5.0, -0.5]);
    }
}
