//! Folds nobody tuned for: seeded random convex cloths (square, towel, hexagon, disk) of
//! random vertex counts, folded along random chords, some with noise on the end frame,
//! then rotated, moved and scaled. The representation must find the one fold and predict
//! the folded border.

mod common;

use std::f64::consts::PI;

use close::eval::evaluate;
use close::formats::Truth;
use close::Sample;
use common::fold_frame;

/// splitmix64, uniform in [0, 1).
struct Random(u64);

impl Random {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E3779B97F4A7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58476D1CE4E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D049BB133111EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }

    fn normal(&mut self) -> f64 {
        (-2.0 * self.next().max(1e-300).ln()).sqrt() * (2.0 * PI * self.next()).cos()
    }
}

/// A convex polygon through `corners`, sampled with about `n` vertices, corners kept.
fn outline(corners: &[[f64; 2]], n: usize) -> Vec<[f64; 3]> {
    let sides: Vec<f64> = (0..corners.len())
        .map(|i| {
            let (a, b) = (corners[i], corners[(i + 1) % corners.len()]);
            (b[0] - a[0]).hypot(b[1] - a[1])
        })
        .collect();
    let total: f64 = sides.iter().sum();
    let mut out = Vec::new();
    for (i, len) in sides.iter().enumerate() {
        let (a, b) = (corners[i], corners[(i + 1) % corners.len()]);
        let k = ((n as f64 * len / total).round() as usize).max(1);
        out.extend((0..k).map(|j| {
            let t = j as f64 / k as f64;
            [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), 0.0]
        }));
    }
    out
}

fn random_sample(rng: &mut Random, index: usize) -> Sample {
    let n = [40, 63, 75, 90, 101][(rng.next() * 5.0) as usize];
    let mut start = match index % 4 {
        0 => outline(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]], n),
        1 => outline(&[[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]], n),
        2 => outline(&(0..6).map(|k| [(k as f64 * PI / 3.0).cos(), (k as f64 * PI / 3.0).sin()]).collect::<Vec<_>>(), n),
        _ => (0..n).map(|k| [(2.0 * PI * k as f64 / n as f64).cos(), (2.0 * PI * k as f64 / n as f64).sin(), 0.0]).collect(),
    };
    for p in &mut start {
        p[0] += 1e-5 * rng.normal();
        p[1] += 1e-5 * rng.normal();
    }
    let n = start.len() as f64;
    let f1 = rng.next() * n;
    let f2 = (f1 + (0.15 + 0.45 * rng.next()) * n) % n;
    let mut end = fold_frame(&start, f1, f2);
    if rng.next() < 0.3 {
        for p in &mut end {
            for c in p.iter_mut() {
                *c += 0.003 * rng.normal();
            }
        }
    }
    let (angle, scale) = (2.0 * PI * rng.next(), [0.3, 1.0, 5.0][index % 3]);
    let (c, s) = (angle.cos(), angle.sin());
    let place = |frame: Vec<[f64; 3]>| -> Vec<[f64; 3]> {
        frame.iter().map(|p| [scale * (c * p[0] - s * p[1]) + 2.0, scale * (s * p[0] + c * p[1]) - 1.0, scale * p[2]]).collect()
    };
    let mut sample = Sample::from_frames(format!("unseen_{index}"), "unseen", vec![place(start), place(end)]);
    sample.truth = Some(Truth { folds: vec![[2.0 * PI * f1 / n, 2.0 * PI * f2 / n]], folded_vertices: None });
    sample
}

#[test]
fn random_folds_are_found_and_predicted() {
    let mut rng = Random(2026);
    let results: Vec<_> = (0..40).map(|k| evaluate(&random_sample(&mut rng, k))).collect();
    let one_fold = results.iter().filter(|r| r.folds == 1).count();
    let mean_rmse = results.iter().map(|r| r.rmse.unwrap()).sum::<f64>() / results.len() as f64;
    println!("one fold on {one_fold} of 40, mean RMSE {mean_rmse:.4}");
    assert!(one_fold >= 38, "one fold on {one_fold} of 40");
    assert!(mean_rmse <= 0.03, "mean RMSE {mean_rmse}");
}
