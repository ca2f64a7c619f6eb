//! `close record` (feature `rerun`): writes an .rrd file, or says plainly why not.
#![cfg(feature = "rerun")]

use std::process::Command;

const SQUARE: &str = "tests/fixtures/plan/square_cw_diagonal.json";

#[test]
fn record_writes_an_rrd_file() {
    let out_path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("square_cw_diagonal.rrd");
    let _ = std::fs::remove_file(&out_path);
    let out = Command::new(env!("CARGO_BIN_EXE_close")).args(["record", SQUARE, "--out"]).arg(&out_path).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let bytes = std::fs::read(&out_path).unwrap();
    // RRD files start with the magic "RRF2"; the entities are checked in `close::record`'s tests.
    assert_eq!(&bytes[..4], b"RRF2");
}

#[test]
fn record_to_a_missing_folder_fails_plainly() {
    let out = Command::new(env!("CARGO_BIN_EXE_close")).args(["record", SQUARE, "--out", "/nonexistent/folder/x.rrd"]).output().unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("/nonexistent/folder/x.rrd"));
}
