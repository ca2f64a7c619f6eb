//! Benchmarks: one dGLI disk and a full analysis (two disks + fit + label) at N = 76, 300
//! and 1000. Run with `cargo bench`; `scripts/bench.sh` runs them beside the numpy
//! baseline (`benches/numpy_baseline.py`) and prints the ratios.
//!
//! The reward of a learning loop: `close::distance::fold_distances` on 10⁵ pairs of fold
//! sequences (1–3 folds each), beside the plainest distance one could take instead (the
//! sum of the circular distances of the padded fold angles, the same pairs, one core): the
//! ratio is what the edit distance's matching of missing and extra folds costs.
//!
//! Fold sequences in one step (issue 26): `analyze_quarters` is a napkin folded in
//! quarters seen flat and folded (the sequence search runs), beside `analyze_fold` of one
//! fold of the same napkin at the same N = 152: the ratio is what the search costs.

use std::f64::consts::PI;

use close::border::{prepare, Point};
use close::disk::Disk;
use close::fold::apply;
use close::{analyze, Fold, Folding, FrameRange};

fn main() {
    divan::main();
}

/// A square napkin of n vertices (n divisible by 4), slightly jittered.
fn napkin(n: usize) -> Vec<Point> {
    let per_side = n / 4;
    (0..n)
        .map(|k| {
            let t = (k % per_side) as f64 / per_side as f64;
            let (x, y) = [(t, 0.0), (1.0, t), (1.0 - t, 1.0), (0.0, 1.0 - t)][k / per_side];
            Point::new(
                x - 0.5 + 1e-5 * (7.0 * k as f64).sin(),
                y - 0.5 + 1e-5 * (3.0 * k as f64).cos(),
                0.0,
            )
        })
        .collect()
}

fn folded_frames(n: usize) -> Vec<Vec<[f64; 3]>> {
    let start = napkin(n);
    let fold = Fold::new(2.0 * PI * 0.07, 2.0 * PI * 0.59);
    let end = apply(&start, &Folding::new(fold));
    let lift = |p: &Point, s: &Point| [p.x, p.y, if p == s { p.z } else { p.z + 0.01 }];
    vec![
        start.iter().map(|p| lift(p, p)).collect(),
        end.iter().zip(&start).map(|(p, s)| lift(p, s)).collect(),
    ]
}

#[divan::bench(args = [76, 300, 1000])]
fn dgli_disk(bencher: divan::Bencher, n: usize) {
    let border = napkin(n);
    bencher.bench(|| Disk::of_border(divan::black_box(&border)));
}

#[divan::bench(args = [76, 152, 300, 1000])]
fn analyze_fold(bencher: divan::Bencher, n: usize) {
    let frames = prepare(folded_frames(n)).unwrap();
    bencher.bench(|| analyze(divan::black_box(&frames), FrameRange::default()).unwrap());
}

/// `state` with every vertex left of the line through `a` at `angle` reflected across it
/// and laid on top (every layer there turns).
fn fold_left_of(state: &[[f64; 3]], a: [f64; 2], angle: f64) -> Vec<[f64; 3]> {
    let (ux, uy) = (angle.cos(), angle.sin());
    let top = state.iter().map(|p| p[2]).fold(f64::NEG_INFINITY, f64::max);
    state
        .iter()
        .map(|p| {
            let (dx, dy) = (p[0] - a[0], p[1] - a[1]);
            if ux * dy - uy * dx <= 0.0 {
                return *p;
            }
            let t = dx * ux + dy * uy;
            [a[0] + 2.0 * t * ux - dx, a[1] + 2.0 * t * uy - dy, 2.0 * top + 0.004 - p[2]]
        })
        .collect()
}

#[divan::bench(args = [152, 300])]
fn analyze_quarters(bencher: divan::Bencher, n: usize) {
    let start: Vec<[f64; 3]> = napkin(n).iter().map(|p| [p.x, p.y, p.z]).collect();
    let half = fold_left_of(&start, [0.013, 0.0], PI / 2.0);
    let quarters = fold_left_of(&half, [0.0, 0.013], 0.0);
    let frames = prepare(vec![start, quarters]).unwrap();
    bencher.bench(|| analyze(divan::black_box(&frames), FrameRange::default()).unwrap());
}

/// 10⁵ pairs of seeded fold sequences of 1–3 folds, as (count, 3, 2) arrays padded with NaN.
fn fold_batches() -> (Vec<f64>, Vec<f64>) {
    let mut rng = close::rng::SplitMix64::new(30);
    let mut batch = || -> Vec<f64> {
        (0..100_000)
            .flat_map(|_| {
                let k = 1 + rng.below(3);
                let mut rows = [f64::NAN; 6];
                for f in rows.chunks_mut(2).take(k) {
                    let f1 = rng.range(0.0, 2.0 * PI);
                    f[0] = f1;
                    f[1] = (f1 + rng.range(0.3, 5.9)) % (2.0 * PI);
                }
                rows
            })
            .collect()
    };
    (batch(), batch())
}

#[divan::bench]
fn fold_distances_100k(bencher: divan::Bencher) {
    use close::distance::{fold_distances, FoldBatch};
    let (a, b) = fold_batches();
    let (a, b) = (FoldBatch::new(&a, 100_000, 3).unwrap(), FoldBatch::new(&b, 100_000, 3).unwrap());
    bencher.bench(|| fold_distances(divan::black_box(&a), divan::black_box(&b)).unwrap());
}

/// The baseline: Σ circular distances of the six padded angles (NaN rows count as 0), one
/// core, no matching of folds.
#[divan::bench]
fn padded_angle_distances_100k(bencher: divan::Bencher) {
    let (a, b) = fold_batches();
    bencher.bench(|| {
        divan::black_box(&a)
            .chunks(6)
            .zip(divan::black_box(&b).chunks(6))
            .map(|(x, y)| {
                x.iter()
                    .zip(y)
                    .map(|(p, q)| {
                        let d = (p - q).abs() % (2.0 * PI);
                        if d.is_nan() {
                            0.0
                        } else {
                            d.min(2.0 * PI - d)
                        }
                    })
                    .sum::<f64>()
                    / (2.0 * PI)
            })
            .collect::<Vec<f64>>()
    });
}
