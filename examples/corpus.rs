//! Rates of the fold-sequence search on a seeded random corpus it was never tuned on
//! ([`close::dataset::corpus`]): each sequence analysed from its start and end frames alone,
//! with `close analyze`'s defaults.
//!
//! ```text
//! cargo run --release --example corpus [-- --count 300 --seed 2026 --out DIR]
//! ```
//!
//! Per outline kind and fold count, and overall: the share with the right fold count, with
//! the end where it lies (RMSE ≤ 0.01 in the start's normalised units, as `endscheck.py
//! --placed-rmse`), with the right shape wherever it lies (aligned RMSE ≤ 0.01), and the
//! sequences read with another count whose end lands all the same (a second sequence with
//! the observed end: counted apart). `--out DIR` also writes every sequence as a Sample
//! JSON with all its frames and truth, which `../shared/tools/endscheck.py` reads.
//! Exits 1 when the rates are below issue 44's targets (right count ≥ 95 %, placed ≥ 90 %
//! of the rest), 2 on a usage error.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::process::ExitCode;

use rayon::prelude::*;

use close::dataset::corpus::{corpus, CorpusParams, CorpusSequence};
use close::{analyze, FrameRange};

/// Where a sequence's end is within this RMSE (normalised units), it lies where observed.
const PLACED_RMSE: f64 = 0.01;
const TARGET_COUNT: f64 = 0.95;
const TARGET_PLACED: f64 = 0.90;

/// What one sequence's analysis got.
#[derive(Debug, Clone, Copy, Default)]
struct Outcome {
    right_count: bool,
    placed: bool,
    aligned: bool,
    /// Another count, but the end where it lies.
    other_count_same_end: bool,
    failed: bool,
}

fn outcome(s: &CorpusSequence) -> Outcome {
    let two = s.start_and_end();
    let analysis = two.border_frames().and_then(|frames| analyze(&frames, FrameRange::default()));
    let Ok(analysis) = analysis else {
        return Outcome { failed: true, ..Outcome::default() };
    };
    let right_count = analysis.folds.len() == s.folds();
    let (placed, aligned) = analysis
        .metrics
        .map_or((false, false), |m| (m.rmse <= PLACED_RMSE, m.aligned_rmse <= PLACED_RMSE));
    Outcome {
        right_count,
        placed,
        aligned,
        other_count_same_end: !right_count && placed,
        failed: false,
    }
}

#[derive(Debug, Default)]
struct Tally {
    n: usize,
    right_count: usize,
    placed: usize,
    aligned: usize,
    other_count_same_end: usize,
    failed: usize,
}

impl Tally {
    fn add(&mut self, o: Outcome) {
        self.n += 1;
        self.right_count += o.right_count as usize;
        self.placed += o.placed as usize;
        self.aligned += o.aligned as usize;
        self.other_count_same_end += o.other_count_same_end as usize;
        self.failed += o.failed as usize;
    }

    fn share(count: usize, of: usize) -> f64 {
        if of == 0 {
            f64::NAN
        } else {
            count as f64 / of as f64
        }
    }

    fn row(&self, name: &str) -> String {
        let pct = |c: usize| format!("{:5.1} %", 100.0 * Tally::share(c, self.n));
        format!(
            "{name:24} {:>4} {:>8} {:>8} {:>8} {:>6} {:>6}",
            self.n,
            pct(self.right_count),
            pct(self.placed),
            pct(self.aligned),
            self.other_count_same_end,
            self.failed
        )
    }
}

struct Args {
    params: CorpusParams,
    out: Option<PathBuf>,
}

fn args() -> Result<Args, String> {
    let mut params = CorpusParams::default();
    let mut out = None;
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let mut value = || it.next().ok_or(format!("{flag} needs a value"));
        match flag.as_str() {
            "--count" => params.count = value()?.parse().map_err(|e| format!("--count: {e}"))?,
            "--seed" => params.seed = value()?.parse().map_err(|e| format!("--seed: {e}"))?,
            "--out" => out = Some(PathBuf::from(value()?)),
            other => {
                return Err(format!("unknown argument {other:?} (--count N, --seed S, --out DIR)"))
            }
        }
    }
    Ok(Args { params, out })
}

fn main() -> ExitCode {
    let args = match args() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("corpus: {e}");
            return ExitCode::from(2);
        }
    };
    let sequences = corpus(&args.params);
    if let Some(dir) = &args.out {
        if let Err(e) = write_all(dir, &sequences) {
            eprintln!("corpus: {}: {e}", dir.display());
            return ExitCode::from(2);
        }
    }
    let outcomes: Vec<Outcome> = sequences.par_iter().map(outcome).collect();
    let mut by_kind: BTreeMap<String, Tally> = BTreeMap::new();
    let mut total = Tally::default();
    for (s, &o) in sequences.iter().zip(&outcomes) {
        by_kind.entry(format!("{} k={}", s.outline.name(), s.folds())).or_default().add(o);
        total.add(o);
    }
    println!(
        "corpus: {} sequences, seed {}, [start, end] only",
        args.params.count, args.params.seed
    );
    println!(
        "{:24} {:>4} {:>8} {:>8} {:>8} {:>6} {:>6}",
        "kind", "n", "count", "placed", "aligned", "other", "error"
    );
    for (kind, tally) in &by_kind {
        println!("{}", tally.row(kind));
    }
    println!("{}", total.row("all"));
    // Sequences read with another count that land the observed end are a second sequence
    // with that end: the targets are on the rest.
    let rest = total.n - total.other_count_same_end;
    let count_rate = Tally::share(total.right_count, rest);
    let placed_rate = Tally::share(total.placed - total.other_count_same_end, rest);
    let ok = count_rate >= TARGET_COUNT && placed_rate >= TARGET_PLACED;
    println!(
        "{}: right count {:.1} % (target {:.0} %), placed {:.1} % (target {:.0} %) of {rest}",
        if ok { "PASS" } else { "BELOW TARGET" },
        100.0 * count_rate,
        100.0 * TARGET_COUNT,
        100.0 * placed_rate,
        100.0 * TARGET_PLACED
    );
    if ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

fn write_all(dir: &std::path::Path, sequences: &[CorpusSequence]) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    for s in sequences {
        let json = serde_json::to_vec(&s.sample).map_err(std::io::Error::other)?;
        std::fs::write(dir.join(format!("{}.json", s.name)), json)?;
    }
    Ok(())
}
