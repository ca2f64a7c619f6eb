//! The server's own answers, typed: what `POST /api/analyze` and `GET /api/samples/{id}`
//! add to the library's analysis, and the error body every failure carries. The analysis,
//! plan, interpolation and evaluation themselves are the library's types, serialised as the
//! CLI and Python serialise them; `schema/*.json` is generated from all of them.

use std::collections::BTreeMap;

use serde::Serialize;

use close_core::analysis::Analysis;
use close_io::formats::{Sample, Truth};

/// `POST /api/analyze` and `GET /api/samples/{id}`: the CLI's analysis JSON plus what the
/// app draws.
#[derive(Debug, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct AnalyzeAnswer<'a> {
    /// The key the answer's pictures and plans are found by (an upload's content hash, or
    /// `sample:{id}`).
    pub key: &'a str,
    pub name: &'a str,
    pub category: &'a str,
    /// Frames of the sample (all of them, not only the analysed range).
    pub frames: usize,
    #[serde(flatten)]
    pub analysis: &'a Analysis,
    /// The analysed start and end frames (input coordinates, border order).
    pub start_border: Vec<[f64; 3]>,
    pub end_border: Vec<[f64; 3]>,
    /// Picture name → URL of its PNG.
    pub images: BTreeMap<&'static str, String>,
    /// Provenance: `"builtin"`, the dataset's folder or store, or `"upload"`.
    pub source: &'a str,
    /// The sample's known folds, when it carries them (any source, uploads too).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub truth: Option<&'a Truth>,
    /// A listed sample's id, the sample itself and its recording's URL.
    #[serde(flatten)]
    pub listed: Option<ListedFields<'a>>,
}

/// What a listed sample's analysis adds: its id, the sample itself, and where its
/// recording is (built-in samples with the `rerun` feature).
#[derive(Debug, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct ListedFields<'a> {
    pub id: &'a str,
    pub sample: &'a Sample,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub recording: Option<String>,
}

/// `POST /api/plan`: the plan ([`close_core::plan::Answer`], as the CLI and Python give
/// it) and the states it goes through as the web app draws them
/// ([`close_render::cloth::plan_states`]).
#[derive(Debug, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct PlanAnswer {
    #[serde(flatten)]
    pub answer: close_core::plan::Answer,
    pub states: Vec<close_render::cloth::Pictured>,
}

/// The body of every failure: a 4xx (or, for a fault of the server, 5xx) status and
/// `{"error": "..."}`, the message naming the problem.
#[derive(Debug, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct ErrorBody {
    pub error: String,
}

/// `GET /api/samples`: the page of rows asked for, how many rows pass the filters, the page
/// (`offset`, `limit`), and every category of the whole list with its row count, in
/// first-seen order. The server writes it from rows serialised once (`listing.rs`), byte
/// for byte as this type serialises (a test holds them together).
#[derive(Debug, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct SampleList<'a> {
    pub samples: Vec<&'a SampleRow>,
    pub total: usize,
    pub offset: usize,
    pub limit: Option<usize>,
    pub categories: Vec<Category<'a>>,
}

/// A category and how many rows of the whole list it holds.
#[derive(Debug, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Category<'a> {
    pub name: &'a str,
    pub count: usize,
}

/// One row of `GET /api/samples`: the same fields for a built-in sample and a dataset's (a
/// catalog entry, `source` `"builtin"` for the built-in ones), and its thumbnail's URL.
#[derive(Debug, Clone, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct SampleRow {
    #[serde(flatten)]
    pub entry: close_io::catalog::Entry,
    /// URL of its small borders picture.
    pub thumbnail: String,
}
