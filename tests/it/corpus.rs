//! The fixed-seed subset of the random corpus (`close::dataset::corpus`, made without the
//! method): its first 40 sequences, each read from its start and end frames alone with the
//! defaults, as `examples/corpus.rs` reads all 300.
//!
//! The floors are the rates measured on 8b39e1f (26 of 40 with the right fold count, 22 of
//! 40 the right shape wherever it lies, 8 of 40 where it lies): a change may raise them, and
//! must not lower them. Issue 44's targets (95 % right count, 90 % placed) are the corpus
//! script's, which reports how far off they are.

use rayon::prelude::*;

use close::dataset::corpus::{corpus, CorpusParams};
use close::{analyze, FrameRange};

/// An end within this RMSE of the observed one (normalised units) lies where observed.
const PLACED_RMSE: f64 = 0.01;

#[test]
fn the_fixed_seed_corpus_holds_its_measured_rates() {
    let sequences = corpus(&CorpusParams { count: 40, ..CorpusParams::default() });
    let outcomes: Vec<(bool, bool, bool)> = sequences
        .par_iter()
        .map(|s| {
            let frames = s.start_and_end().border_frames().expect("a generated sample is valid");
            let a = analyze(&frames, FrameRange::default()).expect("analysed");
            let m = a.metrics.expect("an end frame is scored");
            (a.folds.len() == s.folds(), m.rmse <= PLACED_RMSE, m.aligned_rmse <= PLACED_RMSE)
        })
        .collect();
    let count = |pick: fn(&(bool, bool, bool)) -> bool| outcomes.iter().filter(|o| pick(o)).count();
    let (right, placed, aligned) = (count(|o| o.0), count(|o| o.1), count(|o| o.2));
    eprintln!("corpus subset: right count {right}/40, placed {placed}/40, aligned {aligned}/40");
    assert!(right >= 26, "right fold count on {right} of 40 (measured 26)");
    assert!(aligned >= 22, "right shape on {aligned} of 40 (measured 22)");
    assert!(placed >= 8, "placed on {placed} of 40 (measured 8)");
}
