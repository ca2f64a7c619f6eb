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
//! ([`close_io::catalog::Query::filter`]: 400 past them), the rows are filtered on a worker
//! under the request's deadline, and the answer's size, known from the rows chosen, is
//! taken from the memory budget before the answer is put together (on a worker too).

use std::sync::Arc;

use axum::body::Bytes;
use axum::extract::State;
use axum::response::{IntoResponse, Response};
use serde::Serialize;

use super::routes::{to_json, JsonBytes, SampleRow};
use super::{ApiError, AppQuery, AppState, Lane};
use close_core::budget::Deadline;
use close_io::catalog::{self, Filter};

/// A category and how many rows of the whole list it holds.
#[derive(Serialize)]
struct Category<'a> {
    name: &'a str,
    count: usize,
}

/// One row of the list, ready to filter and to write.
struct Row {
    category: String,
    /// [`Filter::text`] of the row.
    text: String,
    /// The row's JSON.
    json: Bytes,
}

/// Every row of the sample list, built-in samples first, and the categories of them all
/// (`[{name, count}]` in first-seen order) as JSON.
pub(super) struct Listing {
    rows: Vec<Row>,
    categories: Bytes,
}

/// Rows filtered between deadline checks.
const ROWS_BETWEEN_CHECKS: usize = 4096;
/// Bytes of an answer besides its rows and categories: the brackets, commas and numbers.
const ANSWER_FRAME: usize = 128;

impl Listing {
    fn of(rows: &[SampleRow]) -> Result<Listing, ApiError> {
        let mut categories: Vec<Category> = Vec::new();
        for row in rows {
            match categories.iter_mut().find(|c| c.name == row.entry.category) {
                Some(c) => c.count += 1,
                None => categories.push(Category { name: &row.entry.category, count: 1 }),
            }
        }
        Ok(Listing {
            categories: to_json(&categories)?,
            rows: rows
                .iter()
                .map(|r| {
                    let e = &r.entry;
                    Ok(Row {
                        category: e.category.clone(),
                        text: Filter::text(&e.id, &e.name, &e.category),
                        json: to_json(r)?,
                    })
                })
                .collect::<Result<_, ApiError>>()?,
        })
    }

    /// The rows on the page asked for among those that pass `filter` (their indices), how
    /// many pass, and the answer's size at most; stops at `deadline`.
    fn select(
        &self,
        filter: &Filter,
        offset: usize,
        limit: Option<usize>,
        deadline: &Deadline,
    ) -> Result<Selection, ApiError> {
        let mut page = Vec::new();
        let mut total = 0usize;
        let mut bytes = ANSWER_FRAME + self.categories.len();
        for (k, row) in self.rows.iter().enumerate() {
            if k % ROWS_BETWEEN_CHECKS == 0 {
                deadline.check()?;
            }
            if !filter.matches(&row.category, &row.text) {
                continue;
            }
            if total >= offset && limit.is_none_or(|l| page.len() < l) {
                page.push(k);
                bytes += row.json.len() + 1;
            }
            total += 1;
        }
        Ok(Selection { page, total, bytes })
    }

    /// The answer of `selection`, `{samples, total, offset, limit, categories}`.
    fn answer(&self, selection: &Selection, offset: usize, limit: Option<usize>) -> Bytes {
        let mut out = Vec::with_capacity(selection.bytes);
        out.extend_from_slice(b"{\"samples\":[");
        for (n, &k) in selection.page.iter().enumerate() {
            if n > 0 {
                out.push(b',');
            }
            out.extend_from_slice(&self.rows[k].json);
        }
        let limit = limit.map_or("null".to_string(), |l| l.to_string());
        out.extend_from_slice(
            format!(
                "],\"total\":{},\"offset\":{offset},\"limit\":{limit},\"categories\":",
                selection.total
            )
            .as_bytes(),
        );
        out.extend_from_slice(&self.categories);
        out.push(b'}');
        out.into()
    }
}

/// What a query chose: the page's rows, how many rows pass, the answer's size at most.
struct Selection {
    page: Vec<usize>,
    total: usize,
    bytes: usize,
}

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
        })
        .await?;
    Ok(state.0.sample_list.get_or_init(|| Arc::new(listing)).clone())
}

pub async fn samples(
    State(state): State<AppState>,
    AppQuery(query): AppQuery<catalog::Query>,
) -> Result<Response, ApiError> {
    let filter = query.filter()?;
    let (offset, limit) = (query.offset, query.limit);
    let listing = listing(&state).await?;
    let job = listing.clone();
    let selection = state
        .run_cpu(Lane::Light, move |deadline| job.select(&filter, offset, limit, deadline))
        .await?;
    // Counted before it is built: many large lists at once wait for the budget.
    let reserved = state.0.memory.reserve(selection.bytes).await?;
    let answer =
        state.run_cpu(Lane::Light, move |_| Ok(listing.answer(&selection, offset, limit))).await?;
    let mut response = JsonBytes(answer).into_response();
    response.extensions_mut().insert(reserved);
    Ok(response)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn listing(rows: usize) -> Listing {
        let entry = |k: usize| close_io::catalog::Entry {
            id: format!("d0-row{k}"),
            name: format!("row {k}"),
            category: if k.is_multiple_of(2) { "even" } else { "odd" }.into(),
            n: Some(4),
            frames: 2,
            mesh: false,
            source: "test".into(),
            error: None,
        };
        let rows: Vec<SampleRow> = (0..rows).map(|k| SampleRow::dataset(&entry(k))).collect();
        Listing::of(&rows).unwrap()
    }

    #[test]
    fn a_page_is_written_as_its_size_said_and_as_serde_would() {
        let listing = listing(10);
        let query = catalog::Query { q: Some("ROW".into()), ..Default::default() };
        let filter = query.filter().unwrap();
        let selection = listing.select(&filter, 3, Some(4), &Deadline::default()).unwrap();
        assert_eq!((selection.page.clone(), selection.total), (vec![3, 4, 5, 6], 10));
        let answer = listing.answer(&selection, 3, Some(4));
        assert!(answer.len() <= selection.bytes, "{} > {}", answer.len(), selection.bytes);
        let v: serde_json::Value = serde_json::from_slice(&answer).unwrap();
        assert_eq!(v["samples"].as_array().unwrap().len(), 4);
        assert_eq!(
            (v["total"].as_u64(), v["offset"].as_u64(), v["limit"].as_u64()),
            (Some(10), Some(3), Some(4))
        );
        assert_eq!(
            v["categories"],
            serde_json::json!([{"name": "even", "count": 5}, {"name": "odd", "count": 5}])
        );
        assert_eq!(v["samples"][0]["name"], "row 3");
        let odd = catalog::Query { category: Some("odd".into()), ..Default::default() };
        let selection =
            listing.select(&odd.filter().unwrap(), 0, None, &Deadline::default()).unwrap();
        assert_eq!(selection.total, 5);
        let v: serde_json::Value =
            serde_json::from_slice(&listing.answer(&selection, 0, None)).unwrap();
        assert!(v["limit"].is_null());
    }

    #[test]
    fn filtering_stops_at_the_deadline() {
        let listing = listing(10);
        let expired = Deadline::default();
        expired.cancel();
        let filter = catalog::Query::default().filter().unwrap();
        assert!(matches!(
            listing.select(&filter, 0, None, &expired),
            Err(ApiError::Input(close_core::error::Error::Cancelled))
        ));
    }
}
