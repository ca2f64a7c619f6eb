//! How far apart two states of one cloth are: a reward for a folding loop.
//!
//! A state is a CloSE value: the cloth's corners and the sequence of folds (f1, f2) that led
//! to it, each in angles of the START border (vertex k of N at 2πk/N). Two values of one
//! cloth share its corners, so the distance is read on the folds; the corners only name
//! the cloth.
//!
//! **Fold distance** (unit: shares of the border, 0 … about the number of folds). Fold
//! points are border parameters, so an angle δ is the share δ/2π of the border, and one
//! edge is 1/N of it (of the perimeter too, where the edges are of one length). Between two
//! sequences A = (a_1 … a_m) and B = (b_1 … b_n), the least total cost of an edit that turns
//! one into the other, in order (Levenshtein's distance with these costs):
//! - a fold kept and moved, a → b, costs c(a, b) = (δ(a1, b1) + δ(a2, b2)) / 2π, δ the
//!   angle between two points on the circle (≤ π): moving one fold point by one edge costs
//!   1/N;
//! - a fold missing or extra costs w(a) = wrap(a2 − a1) / 2π, the share of the border it
//!   folds over (anticlockwise from a1 to a2).
//!
//! The DP `d[i][j] = min(d[i−1][j] + w(a_i), d[i][j−1] + w(b_j), d[i−1][j−1] + c(a_i, b_j))`
//! over (m+1)(n+1) cells gives `D(A, B) = d[m][n]`; `align` also gives the edit that
//! reaches it (which fold matches which, which are missing and extra).
//!
//! Properties (tested below): D(A, A) = 0 and D(A, B) > 0 for A ≠ B; D(A, B) = D(B, A)
//! exactly; D is continuous in every fold point, Lipschitz with constant 1/2π per radian,
//! and moves by 1/N when a fold point moves by one edge (as long as the edit does not
//! change); an extra fold costs its folded share. **The triangle inequality**
//! D(A, C) ≤ D(A, B) + D(B, C) holds whenever w is 1-Lipschitz for c on the folds
//! involved (then the edit costs form a metric on folds and the gap, and so does the edit
//! distance). It does with every fold folding between a quarter and three quarters of the
//! border (every half, diagonal and quarter fold), and fails only where a fold's two points
//! pass each other: then its folded share jumps between almost none and almost all of the
//! border, which an edit of two points by δ each cannot follow (a fold of 2 % and the fold
//! of 98 % with the same points are 4 % apart, but 96 % apart in the cost of folding them
//! from nothing).
//!
//! **Geometric distance** (unit: normalised cloth sizes, the farthest start vertex at 1):
//! the XY RMSE between the two states' predicted borders (the start border with each
//! sequence's folds applied in turn, `fold_state`) once one is moved rigidly onto the
//! other ([`crate::metrics::aligned_rmse_xy`], the analysis's `aligned_rmse`): how far the
//! shapes are, whatever the cloth's slide on the table.
//!
//! As a reward, −D is dense and bounded: a goal of k folds is at most Σ w(g) from the flat
//! cloth, a fold point one edge off costs 1/N, and a fold made the wrong way round costs
//! twice its points' distance to the right ones.
//!
//! ```
//! use close_core::distance::{fold_distance, share};
//! use std::f64::consts::PI;
//! let n = 40.0;
//! let edge = 2.0 * PI / n;
//! let half = [0.0, PI];
//! // One fold point one edge off: one edge's share of the border.
//! assert!((fold_distance(&[half], &[[edge, PI]]) - 1.0 / n).abs() < 1e-12);
//! // A second fold made on top, that the other state lacks: its folded share.
//! let corner = [PI / 4.0, 3.0 * PI / 4.0];
//! assert!((fold_distance(&[half], &[half, corner]) - share(corner)).abs() < 1e-12);
//! assert_eq!(fold_distance(&[half, corner], &[half, corner]), 0.0);
//! ```

use rayon::prelude::*;
use serde::Serialize;

use crate::analysis::Analysis;
use crate::angle::{angle_to_param, distance as circular, wrap_tau, TAU};
use crate::border::{point_at, Normalisation, Point};
use crate::error::{Error, Result};
use crate::fold::apply;
use crate::geometry::{Fold, Folding, Line, Point2, Vector2};
use crate::metrics::aligned_rmse_xy;

/// The distance between two states of one cloth.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Distance {
    /// [`fold_distance`]: shares of the border.
    pub folds: f64,
    /// [`geometric_distance`]: aligned XY RMSE of the predicted borders, in normalised
    /// units; `None` where a state's borders are unknown.
    pub geometric: Option<f64>,
}

/// The angle between two points of the circle, the same bits whichever comes first (so
/// that the distance is exactly symmetric).
fn delta(a: f64, b: f64) -> f64 {
    if a <= b {
        circular(b, a)
    } else {
        circular(a, b)
    }
}

/// c(a, b): the cost of moving fold `a` to fold `b`, shares of the border.
pub fn moved(a: [f64; 2], b: [f64; 2]) -> f64 {
    (delta(a[0], b[0]) + delta(a[1], b[1])) / TAU
}

/// w(f): the cost of a fold missing or extra, the share of the border it folds over
/// (anticlockwise from f1 to f2).
pub fn share(fold: [f64; 2]) -> f64 {
    wrap_tau(fold[1] - fold[0]) / TAU
}

/// One step of the edit that turns sequence A into sequence B.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(tag = "edit", rename_all = "snake_case")]
pub enum Edit {
    /// Fold `a` of A is fold `b` of B, moved (0-based indices).
    Matched { a: usize, b: usize },
    /// Fold `a` of A has no counterpart in B.
    OnlyA { a: usize },
    /// Fold `b` of B has no counterpart in A.
    OnlyB { b: usize },
}

/// The least-cost edit from A to B, in sequence order, and its cost.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Alignment {
    pub distance: f64,
    pub edits: Vec<Edit>,
}

/// D(A, B) and the edit that reaches it: the full DP table, traced back from (m, n). On a
/// tie a match is preferred, then a fold of A missing.
pub(crate) fn align(a: &[[f64; 2]], b: &[[f64; 2]]) -> Alignment {
    let (m, n) = (a.len(), b.len());
    let width = n + 1;
    let mut d = vec![0.0; (m + 1) * width];
    for j in 1..=n {
        d[j] = d[j - 1] + share(b[j - 1]);
    }
    for i in 1..=m {
        d[i * width] = d[(i - 1) * width] + share(a[i - 1]);
        for j in 1..=n {
            d[i * width + j] = step(
                d[(i - 1) * width + j - 1],
                d[(i - 1) * width + j],
                d[i * width + j - 1],
                (a[i - 1], b[j - 1]),
            );
        }
    }
    let mut edits = Vec::with_capacity(m.max(n));
    let (mut i, mut j) = (m, n);
    while i > 0 || j > 0 {
        let here = d[i * width + j];
        if i > 0 && j > 0 && here == d[(i - 1) * width + j - 1] + moved(a[i - 1], b[j - 1]) {
            edits.push(Edit::Matched { a: i - 1, b: j - 1 });
            (i, j) = (i - 1, j - 1);
        } else if i > 0 && (j == 0 || here == d[(i - 1) * width + j] + share(a[i - 1])) {
            edits.push(Edit::OnlyA { a: i - 1 });
            i -= 1;
        } else {
            edits.push(Edit::OnlyB { b: j - 1 });
            j -= 1;
        }
    }
    edits.reverse();
    Alignment { distance: d[m * width + n], edits }
}

/// One cell of the DP from its three neighbours: diagonal, above (a fold of A dropped),
/// left (a fold of B dropped).
#[inline]
fn step(diagonal: f64, above: f64, left: f64, (a, b): ([f64; 2], [f64; 2])) -> f64 {
    (diagonal + moved(a, b)).min(above + share(a)).min(left + share(b))
}

/// Sequences up to this long run the DP in a row on the stack.
const STACK_ROW: usize = 15;

/// D(A, B), the fold distance between two fold sequences of one cloth (angles of the start
/// border), in shares of the border: see the module's doc. One row of the DP at a time.
pub fn fold_distance(a: &[[f64; 2]], b: &[[f64; 2]]) -> f64 {
    let mut stack = [0.0; STACK_ROW + 1];
    let mut heap = Vec::new();
    let row: &mut [f64] = if b.len() <= STACK_ROW {
        &mut stack[..=b.len()]
    } else {
        heap.resize(b.len() + 1, 0.0);
        &mut heap
    };
    for j in 1..row.len() {
        row[j] = row[j - 1] + share(b[j - 1]);
    }
    for &fa in a {
        let mut diagonal = row[0];
        row[0] += share(fa);
        for j in 1..row.len() {
            let above = row[j];
            row[j] = step(diagonal, above, row[j - 1], (fa, b[j - 1]));
            diagonal = above;
        }
    }
    row[row.len() - 1]
}

/// Checks a fold sequence: finite angles, two points more than `min_apart` apart (a fold
/// whose points meet folds nothing, or everything). `what` names the sequence.
pub fn check_folds(what: &str, folds: &[[f64; 2]], min_apart: f64) -> Result<()> {
    for (k, f) in folds.iter().enumerate() {
        if !(f[0].is_finite() && f[1].is_finite()) {
            return Err(Error::InvalidArgument(format!(
                "{what}, fold {}: ({}, {}) is not finite",
                k + 1,
                f[0],
                f[1]
            )));
        }
        if delta(f[0], f[1]) <= min_apart {
            return Err(Error::InvalidArgument(format!(
                "{what}, fold {}: ({:.4}, {:.4}): its two points must be more than {min_apart:.4} rad apart",
                k + 1,
                f[0],
                f[1]
            )));
        }
    }
    Ok(())
}

/// Most folds a sequence of a [`FoldBatch`] may hold (the DP is quadratic in it).
pub const MAX_BATCH_FOLDS: usize = 64;

/// Many fold sequences in one array, for a learning loop: `count` sequences of at most
/// `width` folds, row-major (count, width, 2); a sequence shorter than `width` ends with
/// rows of two NaN.
#[derive(Debug, Clone)]
pub struct FoldBatch<'a> {
    folds: &'a [[f64; 2]],
    width: usize,
    /// Each sequence's length (its rows before the NaN ones).
    lengths: Vec<usize>,
}

impl<'a> FoldBatch<'a> {
    /// The batch of `values` (count × width × 2 numbers), checked: finite folds, padding
    /// only at the end of a sequence, both angles of a padding row NaN.
    pub fn new(values: &'a [f64], count: usize, width: usize) -> Result<FoldBatch<'a>> {
        if width > MAX_BATCH_FOLDS {
            return Err(Error::too_large("folds per sequence", width, MAX_BATCH_FOLDS));
        }
        let (folds, _) = values.as_chunks::<2>();
        if count.checked_mul(2 * width) != Some(values.len()) {
            return Err(Error::InvalidArgument(format!(
                "a batch of {count} fold sequences of {width} is {count} × {width} × 2 numbers, not {}",
                values.len()
            )));
        }
        let lengths = (0..count)
            .map(|s| {
                let rows = &folds[s * width..(s + 1) * width];
                let length = rows.iter().take_while(|f| !f[0].is_nan() || !f[1].is_nan()).count();
                if let Some(k) =
                    rows[length..].iter().position(|f| !(f[0].is_nan() && f[1].is_nan()))
                {
                    return Err(Error::InvalidArgument(format!(
                        "sequence {s}, row {}: a fold after the padding (rows of NaN end a sequence)",
                        length + k
                    )));
                }
                check_folds(&format!("sequence {s}"), &rows[..length], 0.0)?;
                Ok(length)
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(FoldBatch { folds, width, lengths })
    }

    /// How many sequences.
    pub fn len(&self) -> usize {
        self.lengths.len()
    }

    /// True when it holds no sequence.
    pub fn is_empty(&self) -> bool {
        self.lengths.is_empty()
    }

    /// Sequence `k`, without its padding.
    pub fn get(&self, k: usize) -> &'a [[f64; 2]] {
        &self.folds[k * self.width..k * self.width + self.lengths[k]]
    }

    /// The pairs of `self` and `other`, sequence k with sequence k; a batch of one is paired
    /// with every sequence of the other.
    fn pairs<'b>(&'b self, other: &'b FoldBatch<'a>) -> Result<Pairs<'a, 'b>> {
        let count = match (self.len(), other.len()) {
            (a, b) if a == b => a,
            (1, b) => b,
            (a, 1) => a,
            (a, b) => {
                return Err(Error::InvalidArgument(format!(
                "batches of {a} and {b} fold sequences: pair them one to one, or give one sequence"
            )))
            }
        };
        Ok(Pairs { a: self, b: other, count })
    }
}

struct Pairs<'a, 'b> {
    a: &'b FoldBatch<'a>,
    b: &'b FoldBatch<'a>,
    count: usize,
}

impl<'a> Pairs<'a, '_> {
    fn get(&self, k: usize) -> (&'a [[f64; 2]], &'a [[f64; 2]]) {
        let pick = |batch: &FoldBatch<'a>| batch.get(if batch.len() == 1 { 0 } else { k });
        (pick(self.a), pick(self.b))
    }
}

/// Pairs per rayon task: a distance costs tens of nanoseconds, so they go in chunks.
const CHUNK: usize = 4096;

/// [`fold_distance`] of every pair of two batches (sequence k of `a` with sequence k of `b`;
/// a batch of one sequence is paired with every sequence of the other), on every core.
pub fn fold_distances(a: &FoldBatch<'_>, b: &FoldBatch<'_>) -> Result<Vec<f64>> {
    let pairs = a.pairs(b)?;
    let mut out = vec![0.0; pairs.count];
    out.par_chunks_mut(CHUNK).enumerate().for_each(|(c, chunk)| {
        for (k, d) in chunk.iter_mut().enumerate() {
            let (x, y) = pairs.get(c * CHUNK + k);
            *d = fold_distance(x, y);
        }
    });
    Ok(out)
}

/// Two fold points closer than this share of the mean edge length lie on top of each other
/// (a fold through stacked layers): the line through them is no guide. (Not the fold
/// search's [`crate::fold::params::SynthesisParams::coincide_edges`]: this one only tells a
/// line through two points from none.)
const ON_TOP_EDGES: f64 = 0.5;

/// How the line of a fold is found in the state before it.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum LineOf {
    /// Through its two fold points (unless they lie on top of each other).
    #[default]
    Points,
    /// Through the midpoint of its two fold points in this XY direction (a fold through
    /// stacked layers, whose direction the disks gave).
    Direction([f64; 2]),
    /// This line.
    Given(Line),
}

/// The line fold `fold` of state `before` is made along (see [`LineOf`]); `None` when its
/// two points lie on top of each other and no direction is given.
pub fn fold_line(before: &[Point], fold: [f64; 2], how: LineOf) -> Option<Line> {
    let n = before.len();
    let at = |f: f64| point_at(before, angle_to_param(f, n));
    let (p, q) = (at(fold[0]), at(fold[1]));
    match how {
        LineOf::Given(line) => Some(line),
        LineOf::Direction([x, y]) => {
            let length = x.hypot(y);
            (length > 0.0 && length.is_finite()).then(|| Line {
                point: Point2::new((p.x + q.x) / 2.0, (p.y + q.y) / 2.0),
                direction: Vector2::new(x / length, y / length),
            })
        }
        LineOf::Points => {
            let perimeter: f64 =
                (0..n).map(|k| (before[(k + 1) % n].xy() - before[k].xy()).norm()).sum();
            ((q.xy() - p.xy()).norm() > ON_TOP_EDGES * perimeter / n as f64)
                .then(|| Line::through(&p, &q))
                .flatten()
        }
    }
}

/// The predicted state of `folds` (angles of the start border) made in turn on the start
/// border `flat`: each fold's arc reflected across its line in the state before it
/// ([`fold_line`] as `lines[k]` says; through its points where `lines` has no entry), z
/// kept. An error names a fold whose two points lie on top of each other in the state
/// before it when no direction is given for it.
pub(crate) fn fold_state(
    flat: &[Point],
    folds: &[[f64; 2]],
    lines: &[LineOf],
) -> Result<Vec<Point>> {
    let mut state = flat.to_vec();
    for (k, &fold) in folds.iter().enumerate() {
        let Some(line) = fold_line(&state, fold, lines.get(k).copied().unwrap_or_default()) else {
            return Err(Error::InvalidArgument(format!(
                "fold {} ({:.4}, {:.4}): its two points lie on top of each other in the state before it, so they do not give its line: give the line",
                k + 1,
                fold[0],
                fold[1]
            )));
        };
        let fold = Fold::from(fold);
        state = apply(&state, &Folding { fold, arcs: vec![fold.arc()], line: Some(line) });
    }
    Ok(state)
}

/// The geometric distance between fold sequences `a` and `b` made on the start border
/// `flat`: the aligned XY RMSE of their predicted states (`fold_state`, lines through the
/// fold points), normalised by the start border's transform.
pub fn geometric_distance(flat: &[Point], a: &[[f64; 2]], b: &[[f64; 2]]) -> Result<f64> {
    let norm = Normalisation::of(flat)?;
    let flat = norm.apply_all(flat);
    Ok(aligned_rmse_xy(&fold_state(&flat, a, &[])?, &fold_state(&flat, b, &[])?))
}

/// [`geometric_distance`] of every pair of two batches (paired as in [`fold_distances`]),
/// on every core.
pub fn geometric_distances(
    flat: &[Point],
    a: &FoldBatch<'_>,
    b: &FoldBatch<'_>,
) -> Result<Vec<f64>> {
    let pairs = a.pairs(b)?;
    let norm = Normalisation::of(flat)?;
    let flat = norm.apply_all(flat);
    (0..pairs.count)
        .into_par_iter()
        .map(|k| {
            let (x, y) = pairs.get(k);
            Ok(aligned_rmse_xy(&fold_state(&flat, x, &[])?, &fold_state(&flat, y, &[])?))
        })
        .collect()
}

/// Folds as the `[f1, f2]` pairs this module computes on.
pub(crate) fn pairs(folds: &[Fold]) -> Vec<[f64; 2]> {
    folds.iter().map(|&f| f.into()).collect()
}

/// Both distances between two analyses of one cloth (the same border vertex count): their
/// folds, and their predicted end borders (each normalised by its own start border).
pub fn between(a: &Analysis, b: &Analysis) -> Result<Distance> {
    if a.n != b.n {
        return Err(Error::InvalidArgument(format!(
            "not one cloth: the states have borders of {} and {} vertices",
            a.n, b.n
        )));
    }
    let predicted = |x: &Analysis| -> Vec<Point> {
        let points: Vec<Point> = x.predicted_end.iter().map(crate::border::from_xyz).collect();
        x.normalisation.apply_all(&points)
    };
    Ok(Distance {
        folds: fold_distance(&pairs(&a.folds), &pairs(&b.folds)),
        geometric: Some(aligned_rmse_xy(&predicted(a), &predicted(b))),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64 as Rng;
    use std::f64::consts::PI;

    fn edge(n: usize) -> f64 {
        TAU / n as f64
    }

    /// A random fold whose folded share lies in [lo, hi].
    fn random_fold(rng: &mut Rng, lo: f64, hi: f64) -> [f64; 2] {
        let f1 = rng.range(0.0, TAU);
        [f1, wrap_tau(f1 + TAU * rng.range(lo, hi))]
    }

    fn random_sequence(rng: &mut Rng, lo: f64, hi: f64) -> Vec<[f64; 2]> {
        let k = rng.below(4);
        (0..k).map(|_| random_fold(rng, lo, hi)).collect()
    }

    #[test]
    fn the_same_state_is_at_zero_and_another_is_not() {
        let mut rng = Rng::new(1);
        for _ in 0..500 {
            let a = random_sequence(&mut rng, 0.05, 0.95);
            assert_eq!(fold_distance(&a, &a), 0.0);
            let mut b = a.clone();
            if let Some(f) = b.first_mut() {
                f[1] = wrap_tau(f[1] + 1e-6);
                assert!(fold_distance(&a, &b) > 0.0);
            }
        }
        // One state angles a turn apart is the same state.
        assert!(fold_distance(&[[0.5, 3.5]], &[[0.5 + TAU, 3.5 - TAU]]) < 1e-15);
    }

    #[test]
    fn it_is_exactly_symmetric() {
        let mut rng = Rng::new(2);
        for _ in 0..2000 {
            let (a, b) =
                (random_sequence(&mut rng, 0.02, 0.98), random_sequence(&mut rng, 0.02, 0.98));
            assert_eq!(fold_distance(&a, &b), fold_distance(&b, &a), "{a:?} {b:?}");
            assert_eq!(align(&a, &b).distance, fold_distance(&a, &b));
        }
    }

    #[test]
    fn one_edge_of_one_point_is_one_edge_share() {
        for n in [40, 76, 180] {
            let e = edge(n);
            let goal = [[3.0 * e, 3.0 * e + PI], [PI / 2.0, 3.0 * PI / 2.0]];
            for k in 0..2 {
                for p in 0..2 {
                    for sign in [-1.0, 1.0] {
                        let mut moved = goal;
                        moved[k][p] += sign * e;
                        let d = fold_distance(&goal, &moved);
                        assert!(
                            (d - 1.0 / n as f64).abs() < 1e-12,
                            "N {n}, fold {k} point {p}: {d}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn it_is_continuous_in_the_fold_points() {
        // Walk one fold point round the circle in small steps: the distance never jumps by
        // more than the step's share (1/2π per radian), through every change of the edit.
        let goal = [[0.3, 2.9], [4.0, 1.0]];
        let h = 1e-3;
        let mut previous: Option<f64> = None;
        for k in 0..(TAU / h) as usize {
            let state = [[0.3, 2.9], [4.0, wrap_tau(1.0 + k as f64 * h)]];
            let d = fold_distance(&goal, &state);
            if let Some(p) = previous {
                assert!((d - p).abs() <= h / TAU + 1e-12, "step {k}: {p} → {d}");
            }
            previous = Some(d);
        }
    }

    #[test]
    fn an_extra_or_missing_fold_costs_its_share() {
        let mut rng = Rng::new(3);
        for _ in 0..300 {
            let a = random_sequence(&mut rng, 0.05, 0.95);
            let extra = random_fold(&mut rng, 0.05, 0.95);
            for at in 0..=a.len() {
                let mut b = a.clone();
                b.insert(at, extra);
                let d = fold_distance(&a, &b);
                // At most its share (the edit that drops it); less only if another edit is cheaper.
                assert!(d <= share(extra) + 1e-12, "{d} > {}", share(extra));
            }
            // From the flat cloth, every fold costs its share.
            let total: f64 = a.iter().map(|&f| share(f)).sum();
            assert!((fold_distance(&[], &a) - total).abs() < 1e-12);
        }
        // A quarter fold added on top of a half fold, far from it: exactly its share.
        let half = [0.0, PI];
        let quarter = [PI / 2.0, PI];
        assert!((fold_distance(&[half], &[half, quarter]) - 0.25).abs() < 1e-12);
        let aligned = align(&[half], &[half, quarter]);
        assert_eq!(aligned.edits, vec![Edit::Matched { a: 0, b: 0 }, Edit::OnlyB { b: 1 }]);
    }

    #[test]
    fn the_triangle_inequality_holds_for_folds_of_a_quarter_to_three_quarters() {
        let mut rng = Rng::new(4);
        for _ in 0..20_000 {
            let [a, b, c] = [0; 3].map(|_| random_sequence(&mut rng, 0.25, 0.75));
            let (ab, bc, ac) =
                (fold_distance(&a, &b), fold_distance(&b, &c), fold_distance(&a, &c));
            assert!(ac <= ab + bc + 1e-12, "{a:?} {b:?} {c:?}: {ac} > {ab} + {bc}");
        }
    }

    #[test]
    fn the_triangle_inequality_fails_where_a_folds_points_pass_each_other() {
        // A fold of 2 % and the fold of 98 % between the same two points (swapped): 4 % apart
        // as folds, but the flat cloth is 2 % from one and 98 % from the other.
        let small = [0.0, 0.02 * TAU];
        let large = [0.02 * TAU, 0.0];
        let (flat_small, small_large, flat_large) = (
            fold_distance(&[], &[small]),
            fold_distance(&[small], &[large]),
            fold_distance(&[], &[large]),
        );
        assert!((small_large - 0.04).abs() < 1e-12);
        assert!(
            flat_large > flat_small + small_large + 0.9,
            "{flat_large} {flat_small} {small_large}"
        );
    }

    #[test]
    fn the_alignment_names_what_is_missing_extra_and_moved() {
        let e = edge(40);
        let goal = [[0.0, PI], [PI / 2.0, PI]];
        // The first fold 2 edges off, the second never made, a corner fold added.
        let observed = [[2.0 * e, PI], [1.5 * PI, 1.7 * PI]];
        let aligned = align(&goal, &observed);
        let cost: f64 = aligned
            .edits
            .iter()
            .map(|edit| match *edit {
                Edit::Matched { a, b } => moved(goal[a], observed[b]),
                Edit::OnlyA { a } => share(goal[a]),
                Edit::OnlyB { b } => share(observed[b]),
            })
            .sum();
        assert!((cost - aligned.distance).abs() < 1e-12);
        assert_eq!(aligned.edits[0], Edit::Matched { a: 0, b: 0 });
        assert_eq!(aligned.edits.len(), 3, "{:?}", aligned.edits);
    }

    #[test]
    fn a_batch_is_the_pairs_one_by_one() {
        let mut rng = Rng::new(5);
        let width = 3;
        let seqs: Vec<Vec<[f64; 2]>> =
            (0..1000).map(|_| random_sequence(&mut rng, 0.05, 0.95)).collect();
        let flat: Vec<f64> = seqs
            .iter()
            .flat_map(|s| (0..width).flat_map(|k| s.get(k).copied().unwrap_or([f64::NAN; 2])))
            .collect();
        let batch = FoldBatch::new(&flat, 1000, width).unwrap();
        assert_eq!(batch.len(), 1000);
        let goal = [0.1, 3.0, f64::NAN, f64::NAN];
        let one = FoldBatch::new(&goal, 1, 2).unwrap();
        let d = fold_distances(&batch, &one).unwrap();
        for (k, s) in seqs.iter().enumerate() {
            assert_eq!(d[k], fold_distance(s, &[[0.1, 3.0]]));
        }
        let rolled: Vec<f64> =
            flat[2 * width..].iter().chain(&flat[..2 * width]).copied().collect();
        let other = FoldBatch::new(&rolled, 1000, width).unwrap();
        let d = fold_distances(&batch, &other).unwrap();
        assert_eq!(d[0], fold_distance(&seqs[0], &seqs[1]));
    }

    #[test]
    fn bad_batches_are_named() {
        let message = |values: &[f64], width: usize| {
            let count = values.len() / (2 * width).max(1);
            FoldBatch::new(values, count, width).unwrap_err().to_string()
        };
        assert!(message(&[0.0, 1.0, 2.0], 1).contains("not 3"));
        assert!(message(&[f64::NAN, f64::NAN, 0.0, 1.0], 2).contains("after the padding"));
        assert!(message(&[f64::NAN, 1.0], 1).contains("not finite"));
        assert!(message(&[f64::INFINITY, 1.0], 1).contains("not finite"));
        assert!(message(&vec![0.0; 2 * 65], 65).contains("too large"));
        let (a, b) = (
            FoldBatch::new(&[0.0, 1.0, 0.0, 2.0], 2, 1).unwrap(),
            FoldBatch::new(&[0.0, 1.0, 0.0, 2.0, 0.0, 3.0], 3, 1).unwrap(),
        );
        assert!(fold_distances(&a, &b).unwrap_err().to_string().contains("2 and 3"));
        // Empty batches are empty answers; one empty sequence (the flat cloth) is a sequence.
        let none = FoldBatch::new(&[], 0, 2).unwrap();
        assert!(fold_distances(&none, &none).unwrap().is_empty());
        let flat = FoldBatch::new(&[], 1, 0).unwrap();
        assert_eq!(fold_distances(&flat, &b).unwrap(), vec![1.0 / TAU, 2.0 / TAU, 3.0 / TAU]);
    }

    /// A square of `4·per_side` vertices, side 1, centred.
    fn square(per_side: usize) -> Vec<Point> {
        (0..4 * per_side)
            .map(|k| {
                let t = (k % per_side) as f64 / per_side as f64;
                let (x, y) = [(t, 0.0), (1.0, t), (1.0 - t, 1.0), (0.0, 1.0 - t)][k / per_side];
                Point::new(x - 0.5, y - 0.5, 0.0)
            })
            .collect()
    }

    #[test]
    fn the_geometric_distance_of_exact_folds() {
        let sq = square(10);
        let n = sq.len();
        let at = |s: f64| crate::angle::param_to_angle(s, n);
        // Right half over (x = 0 from vertex 5 to 25) against the same: zero.
        let half = [at(5.0), at(25.0)];
        assert!(geometric_distance(&sq, &[half], &[half]).unwrap() < 1e-12);
        // The same half fold against the flat cloth: the right half's 21 vertices (5…25, the
        // two on the line staying) moved; by hand, in units of the half diagonal.
        let by_hand = {
            let moved: f64 = sq.iter().filter(|p| p.x > 1e-9).map(|p| (2.0 * p.x).powi(2)).sum();
            (moved / n as f64).sqrt() / (0.5f64.sqrt())
        };
        let d = geometric_distance(&sq, &[], &[half]).unwrap();
        // Aligned: the flat cloth may move to lower it, so at most the raw RMSE.
        assert!(d <= by_hand + 1e-12 && d > 0.5 * by_hand, "{d} vs {by_hand}");
        // Moved and scaled cloth: the same numbers.
        let moved: Vec<Point> =
            sq.iter().map(|p| Point::new(3.0 * p.x + 7.0, 3.0 * p.y - 2.0, 0.0)).collect();
        assert!((geometric_distance(&moved, &[], &[half]).unwrap() - d).abs() < 1e-12);
        // Symmetric.
        let other = [at(3.0), at(27.0)];
        let (x, y) = (
            geometric_distance(&sq, &[half], &[other]).unwrap(),
            geometric_distance(&sq, &[other], &[half]).unwrap(),
        );
        assert!((x - y).abs() < 1e-12 && x > 0.0);
    }

    #[test]
    fn a_stacked_fold_needs_its_line() {
        let sq = square(10);
        let n = sq.len();
        let at = |s: f64| crate::angle::param_to_angle(s, n);
        // Right half over, then the stack's top half down: the second fold's points (the
        // middles of the right and left sides) meet at (−0.5, 0) in the folded state.
        let quarters = [[at(5.0), at(25.0)], [at(15.0), at(35.0)]];
        let error = fold_state(&sq, &quarters, &[]).unwrap_err().to_string();
        assert!(error.contains("fold 2") && error.contains("give the line"), "{error}");
        let line = Line { point: Point2::new(-0.5, 0.0), direction: Vector2::new(1.0, 0.0) };
        let state = fold_state(&sq, &quarters, &[LineOf::Points, LineOf::Given(line)]).unwrap();
        // Every vertex ends in the bottom-left quarter.
        assert!(state.iter().all(|p| p.x <= 1e-9 && p.y <= 1e-9), "{state:?}");
        // A direction alone is enough: the line runs through the points.
        let by_direction =
            fold_state(&sq, &quarters, &[LineOf::Points, LineOf::Direction([-2.0, 0.0])]).unwrap();
        assert!(state.iter().zip(&by_direction).all(|(p, q)| (p - q).norm() < 1e-12));
    }

    #[test]
    fn analyses_of_one_cloth_are_compared_and_of_two_refused() {
        use crate::{analyze, border::prepare, FrameRange};
        let sq = square(10);
        let xyz = |s: &[Point]| s.iter().map(|p| [p.x, p.y, p.z]).collect::<Vec<_>>();
        let lifted = |s: &[Point]| {
            s.iter()
                .zip(&sq)
                .map(|(p, q)| [p.x, p.y, if p == q { 0.0 } else { 0.01 }])
                .collect::<Vec<_>>()
        };
        let n = sq.len();
        let at = |s: f64| crate::angle::param_to_angle(s, n);
        let fold_a = fold_state(&sq, &[[at(5.0), at(25.0)]], &[]).unwrap();
        let fold_b = fold_state(&sq, &[[at(0.0), at(20.0)]], &[]).unwrap();
        let a = analyze(&prepare(vec![xyz(&sq), lifted(&fold_a)]).unwrap(), FrameRange::default())
            .unwrap();
        let b = analyze(&prepare(vec![xyz(&sq), lifted(&fold_b)]).unwrap(), FrameRange::default())
            .unwrap();
        let same = between(&a, &a).unwrap();
        assert_eq!(same.folds, 0.0);
        assert!(same.geometric.unwrap() < 1e-12);
        let d = between(&a, &b).unwrap();
        assert_eq!(d.folds, between(&b, &a).unwrap().folds);
        assert!(d.folds > 0.0 && d.geometric.unwrap() > 0.05, "{d:?}");
        let small =
            analyze(&prepare(vec![xyz(&square(5))]).unwrap(), FrameRange::default()).unwrap();
        assert!(between(&a, &small).unwrap_err().to_string().contains("not one cloth"));
    }
}
