//! Benchmarks: one dGLI disk and a full analysis (two disks + fit + label) at N = 76, 300
//! and 1000. Run with `cargo bench`; `scripts/bench.sh` runs them beside the numpy
//! baseline (`benches/numpy_baseline.py`) and prints the ratios.

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

#[divan::bench(args = [76, 300, 1000])]
fn analyze_fold(bencher: divan::Bencher, n: usize) {
    let frames = prepare(folded_frames(n)).unwrap();
    bencher.bench(|| analyze(divan::black_box(&frames), FrameRange::default()).unwrap());
}
