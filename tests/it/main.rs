//! The integration tests, one binary (as ripgrep does): one link instead of one per file,
//! and one shared evaluation of the built-in set ([`common::builtin`]) for every test that
//! reads it. Each module is one area; `cargo test --test it MODULE::` runs one of them.
//!
//! `browser` needs Chromium and chromedriver, so its test is ignored by default:
//! `cargo test -- --ignored` runs it (`.ci/run` does).

mod common;

mod abuse;
mod browser;
mod cli;
mod cli_plan;
mod corpus;
mod dataset;
mod dataset_hostile;
mod formats;
mod http;
mod invariance;
mod modules;
mod mujoco;
mod physics;
mod pictures;
mod plan;
mod properties;
mod readme;
mod record;
mod reference;
mod schema;
mod sequences;
mod unseen;
mod verify;
mod vrfolding;
