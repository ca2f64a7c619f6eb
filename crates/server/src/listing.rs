//! The sample list of `GET /api/samples`, serialised once: each row's JSON written with
//! its lower-case text ([`Filter::text`]), then filtered and paged per query under a
//! deadline, the answer's size known before it is put together.

use axum::body::Bytes;

use crate::answer::{Category, SampleRow};
use close_core::budget::Deadline;
use close_io::catalog::Filter;

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
pub(crate) struct Listing {
    rows: Vec<Row>,
    categories: Bytes,
}

/// Rows filtered between deadline checks.
const ROWS_BETWEEN_CHECKS: usize = 4096;
/// Bytes of an answer besides its rows and categories: the brackets, commas and numbers.
const ANSWER_FRAME: usize = 128;

impl Listing {
    pub(crate) fn of(rows: &[SampleRow]) -> serde_json::Result<Listing> {
        let mut categories: Vec<Category> = Vec::new();
        for row in rows {
            match categories.iter_mut().find(|c| c.name == row.entry.category) {
                Some(c) => c.count += 1,
                None => categories.push(Category { name: &row.entry.category, count: 1 }),
            }
        }
        Ok(Listing {
            categories: Bytes::from(serde_json::to_vec(&categories)?),
            rows: rows
                .iter()
                .map(|r| {
                    let e = &r.entry;
                    Ok(Row {
                        category: e.category.clone(),
                        text: Filter::text(&e.id, &e.name, &e.category),
                        json: Bytes::from(serde_json::to_vec(r)?),
                    })
                })
                .collect::<serde_json::Result<_>>()?,
        })
    }

    /// The rows on the page asked for among those that pass `filter` (their indices), how
    /// many pass, and the answer's size at most; stops at `deadline`.
    pub(crate) fn select(
        &self,
        filter: &Filter,
        offset: usize,
        limit: Option<usize>,
        deadline: &Deadline,
    ) -> Result<Selection, close_core::error::Error> {
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

    /// The answer of `selection`, [`crate::answer::SampleList`]'s JSON.
    pub(crate) fn answer(
        &self,
        selection: &Selection,
        offset: usize,
        limit: Option<usize>,
    ) -> Bytes {
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
pub(crate) struct Selection {
    page: Vec<usize>,
    total: usize,
    pub(crate) bytes: usize,
}

#[cfg(test)]
mod tests {
    use super::*;
    use close_io::catalog;

    fn rows(count: usize) -> Vec<SampleRow> {
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
        (0..count).map(|k| SampleRow::dataset(&entry(k))).collect()
    }

    fn listing(count: usize) -> Listing {
        Listing::of(&rows(count)).unwrap()
    }

    #[test]
    fn a_page_is_written_as_its_size_said_and_as_serde_would() {
        let listing = listing(10);
        let filter = catalog::Filter::new(None, Some("ROW")).unwrap();
        let selection = listing.select(&filter, 3, Some(4), &Deadline::default()).unwrap();
        assert_eq!((selection.page.clone(), selection.total), (vec![3, 4, 5, 6], 10));
        let answer = listing.answer(&selection, 3, Some(4));
        assert!(answer.len() <= selection.bytes, "{} > {}", answer.len(), selection.bytes);
        let rows = rows(10);
        let typed = crate::answer::SampleList {
            samples: rows[3..7].iter().collect(),
            total: 10,
            offset: 3,
            limit: Some(4),
            categories: vec![
                Category { name: "even", count: 5 },
                Category { name: "odd", count: 5 },
            ],
        };
        assert_eq!(answer, serde_json::to_vec(&typed).unwrap());
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
        let odd = catalog::Filter::new(Some("odd"), None).unwrap();
        let selection = listing.select(&odd, 0, None, &Deadline::default()).unwrap();
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
        let filter = catalog::Filter::new(None, None).unwrap();
        assert!(matches!(
            listing.select(&filter, 0, None, &expired),
            Err(close_core::error::Error::Cancelled)
        ));
    }
}
