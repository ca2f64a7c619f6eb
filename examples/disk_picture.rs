//! Time the picture of `POST /api/disk`: the dGLI disk of the load test's body (a square of
//! 76 vertices folded in half, scripts/load.lua) drawn at the default size, many times.
//! Run under `perf record` to see where a picture's time goes.
//!
//!   cargo run --release --example disk_picture [REPEATS] [SIZE] [OUT.png]

use std::time::Instant;

use close::budget::Deadline;
use close::render::{render_disk, Output, DEFAULT_SIZE};

/// The folded square of scripts/load.lua: (folded border, flat reference).
fn load_body() -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
    let per_side = 19;
    let corners = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let (mut flat, mut folded) = (Vec::new(), Vec::new());
    for c in 0..4 {
        let (a, b) = (corners[c], corners[(c + 1) % 4]);
        for k in 0..per_side {
            let t = k as f64 / per_side as f64;
            let (x, y) = (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]));
            flat.push([x, y, 0.0]);
            folded.push(if x > 0.4 { [0.8 - x, y, 0.01] } else { [x, y, 0.0] });
        }
    }
    (folded, flat)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let number =
        |k: usize, default: u32| args.get(k).map_or(default, |a| a.parse().expect("a number"));
    let (repeats, size) = (number(0, 200), number(1, DEFAULT_SIZE));
    let (border, reference) = load_body();
    let disk = close::disk::of_state(border, Some(reference), &Deadline::default()).unwrap();
    let output = Output::png(size);
    let (png, _) = render_disk(&disk, "dGLI disk · current state", None, &output).unwrap();
    if let Some(out) = args.get(2) {
        std::fs::write(out, &png).unwrap();
    }
    let start = Instant::now();
    for _ in 0..repeats {
        std::hint::black_box(
            render_disk(std::hint::black_box(&disk), "dGLI disk · current state", None, &output)
                .unwrap(),
        );
    }
    let per = start.elapsed().as_secs_f64() / repeats as f64;
    println!(
        "N = {}, {size}×{size} px, {} bytes: {:.3} ms per picture ({repeats} pictures)",
        disk.n(),
        png.len(),
        per * 1e3
    );
}
