//! Helpers shared by the integration tests: fixture loading and synthetic folds.
//!
//! The folds here are written independently of `close::fold`, so that a fault shared by
//! the generator and the predictor cannot cancel out.
use std::f64::consts::TAU;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use rayon::prelude::*;

use close::dataset::Dataset;
use close::eval::{report, score, Report};
use close::formats::{json::parse_sample, Sample};
use close::{analyze, Analysis, Error, FrameRange};

/// The repository's root (the `close` crate's folder).
pub fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Whether this run rewrites the checked-in snapshots and schemas (`UPDATE_SNAPSHOTS=1`).
pub fn updating() -> bool {
    std::env::var_os("UPDATE_SNAPSHOTS").is_some_and(|v| !v.is_empty() && v != "0")
}

/// The built-in dataset with every sample's analysis and the evaluation they make (what
/// `close eval --builtin` prints), computed once for every test of the binary.
pub struct Builtin {
    pub data: Dataset,
    /// One per entry, in the dataset's order.
    pub analyses: Vec<Result<Analysis, Error>>,
    pub report: Report,
}

pub fn builtin() -> &'static Builtin {
    static BUILTIN: OnceLock<Builtin> = OnceLock::new();
    BUILTIN.get_or_init(|| {
        let data = Dataset::builtin();
        let analyses: Vec<Result<Analysis, Error>> = data
            .entries()
            .par_iter()
            .map(|e| e.sample.border_frames().and_then(|b| analyze(&b, FrameRange::default())))
            .collect();
        let results = data
            .entries()
            .iter()
            .zip(&analyses)
            .map(|(e, a)| score(&e.sample, a.as_ref()))
            .collect();
        let report = report(results);
        Builtin { data, analyses, report }
    })
}

impl Builtin {
    /// Built-in sample `id` and its analysis.
    pub fn analysed(&self, id: &str) -> (&close::dataset::BuiltinSample, &Analysis) {
        let k = self.data.entries().iter().position(|e| e.id == id).expect("a built-in sample");
        (&self.data.entries()[k], self.analyses[k].as_ref().expect("analysed"))
    }
}

pub fn fixture(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures").join(path)
}

/// Every sample of a fixture folder, sorted by file name.
pub fn samples_in(dir: &str) -> Vec<Sample> {
    let mut files: Vec<PathBuf> =
        std::fs::read_dir(fixture(dir)).unwrap().map(|e| e.unwrap().path()).collect();
    files.sort();
    files.iter().map(|f| parse_sample(&std::fs::read(f).unwrap()).unwrap()).collect()
}

/// The reference samples (95 folded + 1 without a fold).
pub fn reference_samples() -> Vec<Sample> {
    let mut all = samples_in("reference/folded");
    all.extend(samples_in("reference/nofold"));
    all
}

/// A square napkin of `per_side` segments a side, anticlockwise from a corner, with a
/// little in-plane jitter so no two sides are exactly collinear.
pub fn napkin(per_side: usize) -> Vec<[f64; 3]> {
    let s = per_side as f64;
    (0..4 * per_side)
        .map(|k| {
            let t = (k % per_side) as f64 / s;
            let (x, y) = [(t, 0.0), (1.0, t), (1.0 - t, 1.0), (0.0, 1.0 - t)][k / per_side];
            [x - 0.5 + 1e-5 * (7.0 * k as f64).sin(), y - 0.5 + 1e-5 * (3.0 * k as f64).cos(), 0.0]
        })
        .collect()
}

/// Fold `start` along border parameters (f1, f2) (fractional vertex indices) as the
/// reference generator does: the vertices strictly inside the anticlockwise arc from f1 to
/// f2 are reflected, in XY, across the line through the border points at f1 and f2, and
/// lifted by the cloth thickness 0.01.
pub fn fold_frame(start: &[[f64; 3]], f1: f64, f2: f64) -> Vec<[f64; 3]> {
    let n = start.len();
    let nf = n as f64;
    let at = |s: f64| {
        let s = s.rem_euclid(nf);
        let (k, t) = (s.floor() as usize % n, s - s.floor());
        let (a, b) = (start[k], start[(k + 1) % n]);
        [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
    };
    let (a, b) = (at(f1), at(f2));
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = dx * dx + dy * dy;
    let span = (f2 - f1).rem_euclid(nf);
    start
        .iter()
        .enumerate()
        .map(|(v, p)| {
            let offset = (v as f64 - f1).rem_euclid(nf);
            if offset <= 1e-9 || offset >= span - 1e-9 {
                return *p;
            }
            let t = ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2;
            let (fx, fy) = (a[0] + t * dx, a[1] + t * dy);
            [2.0 * fx - p[0], 2.0 * fy - p[1], p[2] + 0.01]
        })
        .collect()
}

pub fn angle_diff(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(TAU);
    d.min(TAU - d)
}

/// The larger angular error of a found fold's two points against the truth, in edges of
/// an `n`-vertex border.
pub fn error_in_edges(found: close::Fold, truth: close::Fold, n: usize) -> f64 {
    angle_diff(found.f1, truth.f1).max(angle_diff(found.f2, truth.f2)) * n as f64 / TAU
}

/// A scratch folder under target/ that is removed afterwards (no tempfile crate needed).
pub struct TempDir(pub PathBuf);

impl TempDir {
    /// A new empty folder `name` (each test its own name: tests run in parallel).
    pub fn new(name: &str) -> TempDir {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        TempDir(dir)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Copy the folder `from` to `to`, recursively.
pub fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.file_type().unwrap().is_dir() {
            copy_dir(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), target).unwrap();
        }
    }
}
