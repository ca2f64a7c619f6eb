//! The sample list: built-in samples and the user's datasets ([`close_io::catalog`], `close
//! serve --dataset PATH`) as one list of typed rows.
//!
//! `GET /api/samples?category=&q=&offset=&limit=` filters the rows of every source alike
//! and pages the result; without `limit` it is the whole list. Each row has the same fields
//! ([`SampleRow`]): `source` is `"builtin"` or the dataset's folder or store, `error` says
//! why a dataset entry cannot be read. Every listed id is answered, pictured and planned by
//! the same handlers (`routes::sample_analysis`).
//!
//! The work is bounded and counted: the list is built once, each row's JSON written then
//! with its lower-case text; a query is checked against its caps first
//! ([`close_io::catalog::Filter::new`]: 400 past them), the rows are filtered on a worker
//! under the request's deadline, and the answer's size, known from the rows chosen, is
//! taken from the memory budget before the answer is put together (on a worker too).

use std::sync::Arc;

use axum::extract::State;
use axum::response::{IntoResponse, Response};
use serde::Deserialize;

use super::answer::SampleRow;
use super::listing::Listing;
use super::routes::JsonBytes;
use super::state::Lane;
use super::{ApiError, AppQuery, AppState};
use close_io::catalog;

/// The listing, built once (a mesh's border vertex count takes finding its border: a
/// worker's job).
pub(super) async fn listing(state: &AppState) -> Result<Arc<Listing>, ApiError> {
    if let Some(listing) = state.0.sample_list.get() {
        return Ok(listing.clone());
    }
    let job = state.clone();
    let listing = state
        .run_cpu(Lane::Light, move |_| {
            let builtin = job.entries().iter().map(SampleRow::builtin);
            let rows: Vec<SampleRow> =
                builtin.chain(job.catalog().entries().iter().map(SampleRow::dataset)).collect();
            Listing::of(&rows)
                .map_err(|e| ApiError::Internal(format!("could not write the sample list: {e}")))
        })
        .await?;
    Ok(state.0.sample_list.get_or_init(|| Arc::new(listing)).clone())
}

/// Filtering and paging of the list (`?category=&q=&offset=&limit=`).
#[derive(Debug, Default, Deserialize)]
pub struct SampleQuery {
    /// Exact category.
    category: Option<String>,
    /// Words (separated by white space), each found case-insensitively in the name, id or
    /// category: at most [`catalog::MAX_QUERY_CHARS`] characters and
    /// [`catalog::MAX_QUERY_TERMS`] words.
    q: Option<String>,
    #[serde(default)]
    offset: usize,
    limit: Option<usize>,
}

pub async fn samples(
    State(state): State<AppState>,
    AppQuery(query): AppQuery<SampleQuery>,
) -> Result<Response, ApiError> {
    let filter = catalog::Filter::new(query.category.as_deref(), query.q.as_deref())?;
    let (offset, limit) = (query.offset, query.limit);
    let listing = listing(&state).await?;
    let job = listing.clone();
    let selection = state
        .run_cpu(Lane::Light, move |deadline| Ok(job.select(&filter, offset, limit, deadline)?))
        .await?;
    // Counted before it is built: many large lists at once wait for the budget.
    let reserved = state.0.memory.reserve(selection.bytes).await?;
    let answer =
        state.run_cpu(Lane::Light, move |_| Ok(listing.answer(&selection, offset, limit))).await?;
    let mut response = JsonBytes(answer).into_response();
    response.extensions_mut().insert(reserved);
    Ok(response)
}
