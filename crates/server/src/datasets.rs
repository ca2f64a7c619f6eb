//! The sample list: built-in samples and the user's datasets ([`close_io::catalog`], `close
//! serve --dataset PATH`) as one list of typed rows.
//!
//! `GET /api/samples?category=&q=&offset=&limit=` filters the rows of every source alike
//! and pages the result; without `limit` it is the whole list. Each row has the same fields
//! ([`SampleRow`]): `source` is `"builtin"` or the dataset's folder or store, `error` says
//! why a dataset entry cannot be read. Every listed id is answered, pictured and planned by
//! the same handlers (`routes::sample_analysis`).

use axum::extract::State;
use serde::Serialize;

use super::answer::SampleRow;
use super::routes::{sample_rows, JsonBytes};
use super::{ApiError, AppQuery, AppState};
use close_io::catalog;

/// A category and how many rows of the whole list it holds.
#[derive(Serialize)]
struct Category<'a> {
    name: &'a str,
    count: usize,
}

/// The answer of `GET /api/samples`.
#[derive(Serialize)]
struct SampleList<'a> {
    samples: Vec<&'a SampleRow>,
    /// Rows that pass the filters (before paging).
    total: usize,
    offset: usize,
    limit: Option<usize>,
    /// Every category of the whole list, in first-seen order.
    categories: Vec<Category<'a>>,
}

/// Categories of `rows` with their counts, in first-seen order.
fn categories(rows: &[SampleRow]) -> Vec<Category<'_>> {
    let mut out: Vec<Category> = Vec::new();
    for row in rows {
        match out.iter_mut().find(|c| c.name == row.entry.category) {
            Some(c) => c.count += 1,
            None => out.push(Category { name: &row.entry.category, count: 1 }),
        }
    }
    out
}

pub async fn samples(
    State(state): State<AppState>,
    AppQuery(query): AppQuery<catalog::Query>,
) -> Result<JsonBytes, ApiError> {
    let rows = sample_rows(&state).await?;
    let matching: Vec<&SampleRow> = rows
        .iter()
        .filter(|r| query.matches(&r.entry.id, &r.entry.name, &r.entry.category))
        .collect();
    let total = matching.len();
    let page =
        matching.into_iter().skip(query.offset).take(query.limit.unwrap_or(usize::MAX)).collect();
    let list = SampleList {
        samples: page,
        total,
        offset: query.offset,
        limit: query.limit,
        categories: categories(&rows),
    };
    let body = serde_json::to_vec(&list)
        .map_err(|e| ApiError::Internal(format!("could not write the answer: {e}")))?;
    Ok(JsonBytes(body.into()))
}
