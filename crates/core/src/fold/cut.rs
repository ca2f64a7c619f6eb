//! Fold points as the cut of the border that leaves no change within either side.
//!
//! (Kamat, Borràs, Torras, "CloSE", Sec. III-C reads fold coordinates from the diff disk;
//! this reads them from the same disk by its structure rather than by fitting curves.)
//!
//! A fold reflects the folded arc A in a vertical plane and lifts it. For a pair of edges
//! that both lie on A, the dGLI only changes sign (reflection reverses linking, and a
//! vertical lift commutes with it); for a pair that both lie off A it does not change at
//! all. So the abs diff disk g = | |end| − |start| | is zero on every "same side" pair and
//! the change lives on the pairs that straddle the fold. We look for the two cut points
//! (p1, p2) on the half-edge grid — p an integer is a cut through vertex p, p = k + ½ a cut
//! through edge k, whose pairs are left out — that minimise the same-side mass
//! `S(p1, p2) = Σ_{i<j both inside} g_ij + Σ_{i<j both outside} g_ij`.
//! With the change of every run of consecutive edges tabulated, every candidate costs O(1),
//! so all 2N² of them cost O(N²).
//!
//! Several neighbouring cuts can tie; each cut point is then the middle of its tie range.
//! The lifted layer tilts the edge that leaves the fold point, so even a fold through a
//! vertex shows as a cut through an edge: the cut locates each fold point within half an
//! edge, and the synthesis ([`super::synth`]) places it inside that edge.

use rayon::prelude::*;

use super::params::CutParams;
use crate::disk::{condensed_index, Disk};

/// Relative tolerance of a tie in S: a rounding tolerance of the sums, not a knob.
const TIE: f64 = 1e-7;

/// The best cut found: positions in vertex units on the half-edge grid, both in [0, N).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Cut {
    pub p1: f64,
    pub p2: f64,
    /// Same-side mass of the cut as a share of all the change (0 for an exact fold).
    pub residual: f64,
    /// Mean change per same-side pair over mean change per straddling pair: 0 for an exact
    /// fold, near 1 when the change is noise with no side to it.
    pub same_to_cross: f64,
    /// True when the cut point lies strictly inside an edge (it is refinable within it).
    pub inside_edge: [bool; 2],
}

/// The change within every run of consecutive edges: `runs[len][a]` is Σ g over the
/// unordered pairs of the `len` edges starting at edge `a` (cyclic). Stored by length, so
/// the search, which pairs runs of two fixed lengths at every start, reads memory in order.
struct RunSums {
    n: usize,
    runs: Vec<f64>,
}

impl RunSums {
    /// By inclusion–exclusion on runs: run(a, len) = run(a, len − 1) + run(a + 1, len − 1)
    /// − run(a + 1, len − 2) + g(a, a + len − 1). O(N²).
    fn new(g: &Disk) -> RunSums {
        let n = g.n();
        let mut runs = vec![0.0; (n + 1) * n];
        // First each pair's value where its run's recurrence adds it, for both of its orders:
        // g(i, j) at [j − i + 1][i] and at [n − (j − i) + 1][j]. Read in storage order, a block
        // of rows at a time, so that the scattered writes stay in cache (reading the disk
        // ring by ring instead misses the cache on every cell).
        const BLOCK: usize = 64;
        for first in (0..n).step_by(BLOCK) {
            // The last edge has no pair of its own in storage order.
            for i in first..(first + BLOCK).min(n - 1) {
                let row = &g.values()[condensed_index(n, i, i + 1)..][..n - i - 1];
                for (d, &value) in (1..).zip(row) {
                    runs[(d + 1) * n + i] = value;
                    runs[(n - d + 1) * n + i + d] = value;
                }
            }
        }
        for len in 2..=n {
            let (done, row) = runs.split_at_mut(len * n);
            let (shorter, shortest) = (&done[(len - 1) * n..], &done[(len - 2) * n..(len - 1) * n]);
            for (a, slot) in row[..n].iter_mut().enumerate() {
                let next = (a + 1) % n;
                *slot += shorter[a] + shorter[next] - shortest[next];
            }
        }
        RunSums { n, runs }
    }

    /// The row of runs of `len` edges, by start edge.
    fn of_length(&self, len: usize) -> &[f64] {
        &self.runs[len * self.n..(len + 1) * self.n]
    }

    /// Σ g over unordered pairs of the `len` edges starting at edge `a` (cyclic).
    fn within(&self, (a, len): (usize, usize)) -> f64 {
        self.of_length(len)[a % self.n]
    }
}

/// The entries of `row` from `start` on, cyclically.
fn cyclic_from(row: &[f64], start: usize) -> impl Iterator<Item = &f64> {
    row[start..].iter().chain(&row[..start])
}

/// Edges lying wholly on the arc from half-grid position h1 to h2 (anticlockwise):
/// (first edge, count).
fn arc_edges(n: usize, h1: usize, h2: usize) -> (usize, usize) {
    let span = (h2 + 2 * n - h1) % (2 * n);
    let first = h1.div_ceil(2);
    let end = (h1 + span) / 2;
    (first % n, end.saturating_sub(first))
}

/// The cut of least same-side mass of the diff disk `g`; `None` when g holds no change.
pub fn find_cut(g: &Disk) -> Option<Cut> {
    let n = g.n();
    let sums = RunSums::new(g);
    let total = sums.within((0, n));
    if total <= 0.0 {
        return None;
    }
    let same_side = |h1: usize, h2: usize| {
        sums.within(arc_edges(n, h1, h2)) + sums.within(arc_edges(n, h2, h1))
    };
    let grid = 2 * n;
    // Every cut {h1, h2 = h1 + span}: for one span and one parity of h1 both arcs keep their
    // lengths and their starts advance by one edge per step, so each reads two rows in order.
    // Ties go to the least (lower, higher) end, as a scan in that order would find.
    let mut best = (f64::INFINITY, 0, 0);
    for span in 1..=n {
        for parity in 0..2 {
            let (a0, la) = arc_edges(n, parity, parity + span);
            let (b0, lb) = arc_edges(n, (parity + span) % grid, parity);
            let (inside, outside) = (sums.of_length(la), sums.of_length(lb));
            for (k, s) in cyclic_from(inside, a0)
                .zip(cyclic_from(outside, b0))
                .map(|(i, o)| i + o)
                .enumerate()
            {
                if s <= best.0 {
                    let h1 = 2 * k + parity;
                    let h2 = (h1 + span) % grid;
                    let ends = (h1.min(h2), h1.max(h2));
                    if s < best.0 || ends < (best.1, best.2) {
                        best = (s, ends.0, ends.1);
                    }
                }
            }
        }
    }
    let (s_min, h1, h2) = best;
    let tie = s_min + TIE * total;
    // Middle of the run of tying positions around `h`, moving one end with the other fixed.
    let middle = |h: usize, other: usize, first: bool| -> f64 {
        let score =
            |x: usize| if first { same_side(x % grid, other) } else { same_side(other, x % grid) };
        let ok = |x: usize| x % grid != other && score(x) <= tie;
        let (mut lo, mut hi) = (0, 0);
        while lo < grid && ok(h + grid - lo - 1) {
            lo += 1;
        }
        while hi < grid && ok(h + hi + 1) {
            hi += 1;
        }
        ((h + grid) as f64 + (hi as f64 - lo as f64) / 2.0) / 2.0 % n as f64
    };
    let (p1, p2) = (middle(h1, h2, true), middle(h2, h1, false));
    let inside = |p: f64| (p - p.round()).abs() > 0.25;
    let (arc_in, arc_out) = (arc_edges(n, h1, h2), arc_edges(n, h2, h1));
    let pairs = |len: usize| (len * len.saturating_sub(1) / 2) as f64;
    let same_mean = s_min / (pairs(arc_in.1) + pairs(arc_out.1)).max(1.0);
    let edges = |(start, len): (usize, usize)| (start..start + len).map(move |e| e % n);
    let between: f64 =
        edges(arc_in).map(|i| edges(arc_out).map(|j| g.get(i, j)).sum::<f64>()).sum();
    let cross_mean = between / ((arc_in.1 * arc_out.1) as f64).max(1.0);
    let same_to_cross = if cross_mean > 0.0 { same_mean / cross_mean } else { f64::INFINITY };
    Some(Cut {
        p1,
        p2,
        residual: s_min / total,
        same_to_cross,
        inside_edge: [inside(p1), inside(p2)],
    })
}

/// How much the change of the edges on either side of half-grid position `h` differs,
/// against every edge away from both: Σ_e |c(a, e) − c(b, e)|, with c = asinh g (`squashed`,
/// so that the few large values of pairs near a crease do not outweigh the rest) and a, b
/// the edges before and after the vertex `h / 2` (h even) or either side of the edge
/// `(h − 1) / 2` (h odd). The edges of one piece move together, so their rows of g vary
/// smoothly along it and jump where a crease separates them.
fn row_jump(squashed: &Disk, h: usize) -> f64 {
    let n = squashed.n();
    let (a, b) = (((h + 2 * n - 1) / 2 - h % 2) % n, (h / 2 + h % 2) % n);
    // The edges from a − 1 to b + 1 are left out: their pairs with a or b are neighbours'.
    let beside = (b + n - a) % n + 3;
    (0..n.saturating_sub(beside))
        .map(|k| (b + 2 + k) % n)
        .map(|e| (squashed.get(a, e) - squashed.get(b, e)).abs())
        .sum()
}

/// The border split into arcs whose own pairs hold the least change: the cut of a fold
/// sequence ([`find_cuts`]).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Cuts {
    /// Cut points in vertex units on the half-edge grid, increasing, in [0, N).
    pub points: Vec<f64>,
    /// Change within the arcs as a share of all the change.
    pub residual: f64,
}

/// The `arcs` cut points (`arcs` ≥ 2) that split the border into arcs holding the least change
/// within themselves: Σ over the arcs of the change g of the pairs of edges both on the arc. A
/// sequence of folds of a flat cloth moves each piece between its creases rigidly, so every pair
/// inside a piece keeps |dGLI| and a border arc inside one piece holds no change; the cut points
/// are where the creases meet the border ([`find_cut`] is the case of two arcs). The search is a
/// dynamic programme over a grid of at most [`CutParams::coarse_grid`] positions (O(arcs · grid³)),
/// each point then moved along the half-edge grid while that lowers the change. `None` when g holds
/// no change or the border has too few edges.
///
/// Ties: a crease meeting a straight side square to it changes no pair of that side (its edges stay
/// on one line), so the side splits anywhere at the same change. Of splits that tie, the one whose
/// points lie where the rows of g jump most is taken: at a point between edges a and b, Σ_e |asinh
/// g(a, e) − asinh g(b, e)| over the edges e away from both, the largest within
/// [`CutParams::jump_reach_half_edges`] only. Each point's change is lowered by at most a tenth of
/// the tie tolerance over the number of arcs, so a split of more change wins only within a tenth of
/// the tolerance.
pub fn find_cuts(g: &Disk, arcs: usize, params: &CutParams) -> Option<Cuts> {
    let n = g.n();
    let grid = 2 * n;
    if arcs < 2 || arcs > n {
        return None;
    }
    let sums = RunSums::new(g);
    let total: f64 = g.values().iter().map(|v| v.abs()).sum();
    if total <= 0.0 {
        return None;
    }
    let within = |h1: usize, h2: usize| sums.within(arc_edges(n, h1 % grid, h2 % grid));
    let stride = grid.div_ceil(params.coarse_grid);
    let coarse: Vec<usize> = (0..grid).step_by(stride).collect();
    let m = coarse.len();
    // A crease shows as a jump at its own position and smaller ones beside it: only the
    // largest within a few edges counts, so that ties are not split beside a crease already
    // cut. Each coarse position takes the grid positions nearest it.
    let squashed = Disk::from_values(n, g.values().iter().map(|v| v.asinh()).collect()).ok()?;
    let fine: Vec<f64> = (0..grid).map(|h| row_jump(&squashed, h)).collect();
    let peaks: Vec<f64> = (0..grid)
        .map(|h| {
            let top = (1..=params.jump_reach_half_edges)
                .flat_map(|d| [(h + d) % grid, (h + grid - d) % grid])
                .all(|k| fine[k] <= fine[h]);
            if top {
                fine[h]
            } else {
                0.0
            }
        })
        .collect();
    let jumps: Vec<f64> = coarse
        .iter()
        .map(|&c| {
            (0..stride).map(|d| peaks[(c + grid + d - stride / 2) % grid]).fold(0.0, f64::max)
        })
        .collect();
    let most = jumps.iter().copied().fold(0.0, f64::max);
    let per_jump = if most > 0.0 { TIE * total / (10.0 * arcs as f64 * most) } else { 0.0 };
    let bonus = |b: usize| per_jump * jumps[b];
    // The change of every arc between two coarse positions, less its end point's bonus (so
    // a closed partition counts each point's once), once: the programme reads each many
    // times.
    let arc_changes: Vec<f64> =
        (0..m * m).map(|k| within(coarse[k / m], coarse[k % m]) - bonus(k % m)).collect();
    let arc = |a: usize, b: usize| arc_changes[a * m + b];
    // For each first cut point, the least change of `arcs` arcs: best[j][b] is the least
    // change of j arcs from the first point to coarse position b (unrolled, b > first).
    let solve = |first: usize| -> (f64, Vec<usize>) {
        let mut best = vec![vec![(f64::INFINITY, usize::MAX); m]; arcs];
        for (b, slot) in best[1].iter_mut().enumerate().skip(first + 1) {
            *slot = (arc(first, b), first);
        }
        for j in 2..arcs {
            let (done, rest) = best.split_at_mut(j);
            let previous = &done[j - 1];
            for (b, slot) in rest[0].iter_mut().enumerate().skip(first + j) {
                *slot = (first + j - 1..b).fold((f64::INFINITY, usize::MAX), |least, a| {
                    let v = previous[a].0 + arc(a, b);
                    if v < least.0 {
                        (v, a)
                    } else {
                        least
                    }
                });
            }
        }
        let last = best[arcs - 1].iter().enumerate().skip(first + arcs - 1).fold(
            (f64::INFINITY, usize::MAX),
            |last, (b, &(change, _))| {
                let v = change + arc(b, first);
                if v < last.0 {
                    (v, b)
                } else {
                    last
                }
            },
        );
        if last.1 == usize::MAX {
            return (f64::INFINITY, Vec::new());
        }
        let mut points = vec![last.1];
        for j in (2..arcs).rev() {
            points.push(best[j][points[points.len() - 1]].1);
        }
        points.push(first);
        points.reverse();
        (last.0, points.into_iter().map(|b| coarse[b]).collect())
    };
    // A cyclic partition has a point in the first 1/arcs of the grid.
    let firsts: Vec<usize> = (0..m.div_ceil(arcs)).collect();
    let (_, mut points) = firsts
        .par_iter()
        .map(|&f| solve(f))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .filter(|(v, _)| v.is_finite())?;
    // Each point along the full grid, between its neighbours, while the change drops.
    let change = |points: &[usize]| {
        (0..points.len()).map(|k| within(points[k], points[(k + 1) % points.len()])).sum::<f64>()
    };
    let mut current = change(&points);
    loop {
        let mut moved = false;
        for k in 0..points.len() {
            for delta in [1, grid - 1] {
                let mut trial = points.clone();
                trial[k] = (trial[k] + delta) % grid;
                if trial.iter().filter(|&&h| h == trial[k]).count() > 1 {
                    continue;
                }
                trial.sort_unstable();
                if trial != points && change(&trial) < current - TIE * total {
                    current = change(&trial);
                    points = trial;
                    moved = true;
                }
            }
        }
        if !moved {
            break;
        }
    }
    Some(Cuts {
        points: points.iter().map(|&h| h as f64 / 2.0).collect(),
        residual: current / total,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::angle::param_to_angle;
    use crate::border::Point;
    use crate::fold::reflect::apply;
    use crate::geometry::{Fold, Folding};

    fn square(per_side: usize) -> Vec<Point> {
        let s = per_side as f64;
        (0..4 * per_side)
            .map(|k| {
                let t = (k % per_side) as f64 / s;
                let (x, y) = [(t, 0.0), (1.0, t), (1.0 - t, 1.0), (0.0, 1.0 - t)][k / per_side];
                Point::new(
                    x - 0.5 + 1e-6 * (k as f64).sin(),
                    y - 0.5 + 1e-6 * (k as f64).cos(),
                    0.0,
                )
            })
            .collect()
    }

    fn cut_of(points: &[Point], f: [f64; 2]) -> Cut {
        let n = points.len();
        let fold = Fold::new(param_to_angle(f[0], n), param_to_angle(f[1], n));
        let mut end = apply(points, &Folding::new(fold));
        for (e, s) in end.iter_mut().zip(points) {
            if e != s {
                e.z = 0.01;
            }
        }
        let g = Disk::of_border(points).abs_diff(&Disk::of_border(&end));
        find_cut(&g).unwrap()
    }

    fn assert_within_half_an_edge(c: &Cut, truth: [f64; 2]) {
        let mut got = [c.p1, c.p2];
        got.sort_by(f64::total_cmp);
        for (g, t) in got.iter().zip(truth) {
            assert!((g - t).abs() <= 0.5, "{got:?} vs {truth:?}");
        }
        assert!(c.residual < 1e-6);
    }

    #[test]
    fn a_fold_through_vertices_is_found_within_half_an_edge() {
        // The lifted layer tilts the edge leaving the on-line vertex, so it counts as cut.
        assert_within_half_an_edge(&cut_of(&square(8), [4.0, 20.0]), [4.0, 20.0]);
    }

    #[test]
    fn a_fold_through_edges_is_found_within_half_an_edge() {
        let c = cut_of(&square(8), [29.3, 5.6]);
        assert_within_half_an_edge(&c, [5.6, 29.3]);
        assert_eq!(c.inside_edge, [true, true]);
    }

    #[test]
    fn creases_square_to_straight_sides_are_cut_where_they_meet_them() {
        // A towel 1.5 × 1 folded in thirds, the left third over, then the right one over it
        // with the first flap's tip: three creases, each meeting the long sides square,
        // where no pair of a side changes. Without the tie-break the first crease's two
        // points slide along the sides to beside the tip's.
        let corners = [[-0.75, -0.5], [0.75, -0.5], [0.75, 0.5], [-0.75, 0.5]];
        let towel: Vec<Point> = (0..4)
            .flat_map(|k| {
                let (a, b): ([f64; 2], [f64; 2]) = (corners[k], corners[(k + 1) % 4]);
                let steps = (30.0 * (b[0] - a[0]).abs().max((b[1] - a[1]).abs())) as usize;
                (0..steps).map(move |i| {
                    let t = i as f64 / steps as f64;
                    Point::new(a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), 0.0)
                })
            })
            .collect();
        // Every vertex beyond x = `crease` on the side `sign` reflected and laid on top.
        let fold = |state: &[Point], crease: f64, sign: f64| -> Vec<Point> {
            let top = state.iter().map(|p| p.z).fold(0.0, f64::max);
            let over = |p: &Point| Point::new(2.0 * crease - p.x, p.y, 2.0 * top + 0.01 - p.z);
            state.iter().map(|p| if sign * (p.x - crease) > 0.0 { over(p) } else { *p }).collect()
        };
        let folded = fold(&fold(&towel, -0.237, -1.0), 0.237, 1.0);
        // Offset as the sequence search offsets it, else a split at the corners costs nothing.
        let start = Disk::of_border(&towel);
        let g = start.abs_diff(&Disk::of_border(&folded));
        let offset = g
            .values()
            .iter()
            .zip(start.values())
            .map(|(c, s)| c - CutParams::default().start_share * s.abs());
        let offset = Disk::from_values(g.n(), offset.collect()).unwrap();
        let cuts = find_cuts(&offset, 6, &CutParams::default()).unwrap();
        // The creases at x = −0.711 (the tip's), −0.237 and 0.237 meet the bottom side in
        // edges 1, 15 and 29, the top one in 90, 104 and 118.
        for (got, truth) in cuts.points.iter().zip([1.5, 15.5, 29.5, 90.5, 104.5, 118.5]) {
            assert!((got - truth).abs() <= 0.5, "{:?}", cuts.points);
        }
    }

    #[test]
    fn no_change_has_no_cut() {
        let g = Disk::from_values(6, vec![0.0; 15]).unwrap();
        assert!(find_cut(&g).is_none());
    }

    #[test]
    fn a_cut_between_two_runs_of_unchanged_pairs_is_found_there() {
        // Six edges; only the pairs across a cut between edges {0, 1, 2} and {3, 4, 5} changed.
        let n = 6;
        let values = (0..n)
            .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
            .map(|(i, j)| if (i < 3) != (j < 3) { 1.0 } else { 0.0 })
            .collect();
        let cut = find_cut(&Disk::from_values(n, values).unwrap()).unwrap();
        assert_eq!(cut.residual, 0.0);
        let mut points = [cut.p1, cut.p2];
        points.sort_by(f64::total_cmp);
        assert_eq!(points, [0.0, 3.0]);
    }

    #[test]
    fn four_runs_of_unchanged_pairs_are_cut_between_them() {
        // Twelve edges in four runs of three whose own pairs did not change.
        let n = 12;
        let values = (0..n)
            .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
            .map(|(i, j)| if i / 3 == j / 3 { 0.0 } else { 1.0 })
            .collect();
        let cuts =
            find_cuts(&Disk::from_values(n, values).unwrap(), 4, &CutParams::default()).unwrap();
        assert_eq!(cuts.residual, 0.0);
        // Each cut between two runs, within the half edge that holds no pair of its own.
        assert!(cuts.points.iter().zip([0.0, 3.0, 6.0, 9.0]).all(|(p, q)| (p - q).abs() <= 0.5));
    }
}
