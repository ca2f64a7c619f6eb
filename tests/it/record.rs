//! Rerun recordings (feature `rerun`): `close::record` reads back with every entity, and
//! `close record` writes an .rrd file or says plainly why not. (Here rather than beside the
//! module, so that CI's `rerun` run needs no second build of the library's unit tests.)
#![cfg(feature = "rerun")]

use std::collections::BTreeSet;
use std::process::Command;

use close::disk::Disk;
use close::record::{polar_image, record};
use close::{analyze, FrameRange};
use rerun::external::re_log_encoding::DecoderApp;
use rerun::log::{Chunk, LogMsg};

/// Entity paths and the number of chunks of the recording, decoded back from the bytes.
fn entities(rrd: &[u8]) -> BTreeSet<String> {
    DecoderApp::decode_eager(rrd)
        .expect("an RRD stream")
        .filter_map(|msg| match msg.expect("a decodable message") {
            LogMsg::ArrowMsg(_, arrow) => {
                Some(Chunk::from_arrow_msg(&arrow).expect("a chunk").entity_path().to_string())
            }
            _ => None,
        })
        .collect()
}

#[test]
fn a_recording_reads_back_with_every_entity() {
    let dataset = close::dataset::Dataset::builtin();
    let entry = dataset.get("napkin__half_vertical").expect("a built-in sample");
    let frames = entry.sample.border_frames().unwrap();
    let analysis = analyze(&frames, FrameRange::default()).unwrap();
    assert_eq!(analysis.folds.len(), 1, "the detector finds this fold");
    let paths = entities(&record(&analysis, &frames).unwrap());
    for expected in [
        "/border",
        "/predicted_end",
        "/fold/1/points",
        "/fold/1/line",
        "/close/f1",
        "/close/f2",
        "/close/corners",
        "/close/label",
        "/disk/start",
        "/disk/end",
        "/disk/diff",
        "/disk/signed_diff",
    ] {
        assert!(paths.contains(expected), "{expected} missing from {paths:?}");
    }
}

#[test]
fn the_polar_image_places_each_cell_by_its_angle() {
    // 6 edges, 3 rings: pair (i, j) holds 10·i + j so each cell names itself.
    let n = 6;
    let values = (0..n).flat_map(|i| (i + 1..n).map(move |j| (10 * i + j) as f64)).collect();
    let disk = Disk::from_values(n, values).unwrap();
    let (rows, cols, image) = polar_image(&disk);
    assert_eq!((rows, cols), (3, 12));
    // Ring 1, edges 0–1: angle π(0 + 1 + 1)/6 = 2 columns of π/6 → columns 1 and 2.
    assert_eq!(&image[1..3], &[1.0, 1.0]);
    // Ring 2, edges 5–1 (a = 5): columns 12 and 13 wrap to 0 and 1.
    assert_eq!((image[12], image[13]), (15.0, 15.0));
}

const SQUARE: &str = "tests/fixtures/plan/square_cw_diagonal.json";

#[test]
fn record_writes_an_rrd_file() {
    let out_path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("square_cw_diagonal.rrd");
    let _ = std::fs::remove_file(&out_path);
    let out = Command::new(env!("CARGO_BIN_EXE_close"))
        .args(["record", SQUARE, "--out"])
        .arg(&out_path)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let bytes = std::fs::read(&out_path).unwrap();
    // RRD files start with the magic "RRF2"; the entities are checked above.
    assert_eq!(&bytes[..4], b"RRF2");
}

#[test]
fn record_to_a_missing_folder_fails_plainly() {
    let out = Command::new(env!("CARGO_BIN_EXE_close"))
        .args(["record", SQUARE, "--out", "/nonexistent/folder/x.rrd"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("/nonexistent/folder/x.rrd"));
}
