//! The documentation cannot drift from the code. Each result table of the README and of
//! the pages under `docs/` is rendered from a checked-in `close eval --json` snapshot
//! (`tests/snapshots/`), each snapshot must equal what the binary prints now, and every
//! table of a results page must be one of these renderings. Every relative link of the
//! README, `docs/` and the guides at the root must lead to a file (and heading) that exists.
//!
//! A change that moves the results on purpose regenerates both, for review in its diff:
//! `UPDATE_SNAPSHOTS=1 cargo test --test it readme::` writes the snapshots from the binary
//! and the pages' generated regions from the snapshots.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use close::eval::{Report, SampleResult, Stat};
use serde_json::Value;

use crate::common::{builtin, root, updating};

/// A snapshot: its file name under `tests/snapshots/` and the `close eval --json` arguments
/// that make it (paths relative to the repository).
const SNAPSHOTS: &[(&str, &[&str])] = &[
    ("builtin", &["--builtin"]),
    ("reference", &["tests/fixtures/reference"]),
    ("reference_paper", &["tests/fixtures/reference", "--method", "paper"]),
    ("physics", &["assets/physics"]),
    ("mujoco", &["tests/fixtures/physics-mujoco/border"]),
    ("vrfolding", &["tests/fixtures/vrfolding/vr_simulation_folding2_dataset.zarr"]),
];

const BEGIN: &str = "<!-- generated: ";
const END: &str = "<!-- end generated -->";

fn snapshot_path(name: &str) -> PathBuf {
    root().join("tests/snapshots").join(format!("{name}.json"))
}

/// What `close eval --json ARGS` prints now.
fn binary_eval(args: &[&str]) -> Value {
    let out = Command::new(env!("CARGO_BIN_EXE_close"))
        .current_dir(root())
        .args(["eval", "--json"])
        .args(args)
        .output()
        .expect("run close");
    assert!(out.status.success(), "close eval {args:?}: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("close eval --json prints JSON")
}

fn read_snapshot(name: &str) -> Value {
    let path = snapshot_path(name);
    let text = std::fs::read(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (UPDATE_SNAPSHOTS=1 writes it)", path.display()));
    serde_json::from_slice(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Where two JSON values differ: numbers to 1e-9 relative (the same code on the same data;
/// the margin only absorbs the last digit of a printed float), everything else exactly.
fn differences(path: &str, a: &Value, b: &Value, out: &mut Vec<String>) {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap_or(f64::NAN), y.as_f64().unwrap_or(f64::NAN));
            if (x - y).abs() > 1e-9 * x.abs().max(y.abs()).max(1e-300) {
                out.push(format!("{path}: {x} now, {y} in the snapshot"));
            }
        }
        (Value::Array(x), Value::Array(y)) if x.len() == y.len() => {
            x.iter()
                .zip(y)
                .enumerate()
                .for_each(|(k, (x, y))| differences(&format!("{path}[{k}]"), x, y, out));
        }
        (Value::Object(x), Value::Object(y)) if x.keys().eq(y.keys()) => {
            x.iter().for_each(|(k, v)| differences(&format!("{path}.{k}"), v, &y[k], out));
        }
        _ if a == b => {}
        _ => out.push(format!("{path}: {a:.200} now, {b:.200} in the snapshot")),
    }
}

/// The snapshots this build can make (the store needs the `vrfolding` feature).
fn snapshots() -> impl Iterator<Item = &'static (&'static str, &'static [&'static str])> {
    SNAPSHOTS.iter().filter(|(name, _)| cfg!(feature = "vrfolding") || *name != "vrfolding")
}

/// With `UPDATE_SNAPSHOTS`, write every snapshot from the binary, once for both tests (the
/// README is rendered from them, so they are written first).
fn update_snapshots() {
    static UPDATED: std::sync::Once = std::sync::Once::new();
    if updating() {
        UPDATED.call_once(|| {
            for (name, args) in snapshots() {
                let text = serde_json::to_string_pretty(&binary_eval(args)).expect("JSON") + "\n";
                std::fs::write(snapshot_path(name), text).expect("write the snapshot");
            }
        });
    }
}

#[test]
fn snapshots_are_what_the_binary_prints() {
    update_snapshots();
    let mut drift = Vec::new();
    for (name, args) in snapshots() {
        let now = binary_eval(args);
        let mut found = Vec::new();
        differences(name, &now, &read_snapshot(name), &mut found);
        drift.extend(found.into_iter().take(20));
    }
    assert!(
        drift.is_empty(),
        "the results moved (UPDATE_SNAPSHOTS=1 if on purpose):\n{}",
        drift.join("\n")
    );
}

/// The shared in-process evaluation of the built-in set (which the other tests read) is the
/// binary's: the same JSON as its snapshot.
#[test]
fn the_shared_builtin_evaluation_is_the_snapshot() {
    let mut found = Vec::new();
    let shared = serde_json::to_value(&builtin().report).expect("JSON");
    differences("builtin", &shared, &read_snapshot("builtin"), &mut found);
    assert!(found.is_empty(), "{}", found.join("\n"));
}

fn report(name: &str) -> Report {
    serde_json::from_value(read_snapshot(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn mean(stat: Option<Stat>) -> String {
    stat.map_or("–".into(), |s| format!("{:.4}", s.mean))
}

fn median(mut values: Vec<f64>) -> Option<f64> {
    values.sort_by(f64::total_cmp);
    let k = values.len();
    (k > 0)
        .then(|| if k % 2 == 1 { values[k / 2] } else { (values[k / 2 - 1] + values[k / 2]) / 2.0 })
}

fn stat_of(
    results: &[&SampleResult],
    value: impl Fn(&SampleResult) -> Option<f64>,
) -> Option<Stat> {
    let values: Vec<f64> = results.iter().filter_map(|r| value(r)).collect();
    (!values.is_empty()).then(|| {
        let m = values.iter().sum::<f64>() / values.len() as f64;
        Stat {
            mean: m,
            var: values.iter().map(|v| (v - m).powi(2)).sum::<f64>() / values.len() as f64,
        }
    })
}

/// `close eval`'s text table of a snapshot.
fn table(name: &str) -> String {
    format!("```\n{}```", report(name).table())
}

/// The fold methods side by side on a snapshot pair (default, paper) of the same samples.
fn methods(names: &[&str]) -> String {
    let mut out = String::from("| method | folded samples with one fold | mean RMSE | median RMSE | mean Fréchet |\n|---|---|---|---|---|\n");
    for name in names {
        let r = report(name);
        let folded: Vec<&SampleResult> =
            r.samples.iter().filter(|s| s.expected_folds == 1).collect();
        let right = folded.iter().filter(|s| s.folds == 1).count();
        let rmse = median(folded.iter().filter_map(|s| s.rmse).collect())
            .map_or("–".into(), |m| format!("{m:.4}"));
        let label = if name.ends_with("_paper") {
            "`close --method paper` (the paper's fitted curves alone)"
        } else {
            "`close` (cut + analysis by synthesis)"
        };
        out += &format!(
            "| {label} | {right} of {} | {} | {rmse} | {} |\n",
            folded.len(),
            mean(stat_of(&folded, |s| s.rmse)),
            mean(stat_of(&folded, |s| s.frechet))
        );
    }
    out.trim_end().to_string()
}

/// First folds (one-step samples) and second folds (step 2 of two-step samples) of a
/// snapshot.
fn folds(name: &str) -> String {
    let r = report(name);
    let first: Vec<&SampleResult> = r.samples.iter().filter(|s| s.steps.len() == 1).collect();
    let second: Vec<&SampleResult> = r.samples.iter().filter(|s| s.steps.len() == 2).collect();
    let right = |rs: &[&SampleResult]| {
        rs.iter().filter(|s| s.error.is_none() && s.folds == s.expected_folds).count()
    };
    let step2 = |s: &SampleResult| s.steps.get(1).map(|t| (t.rmse, t.frechet));
    let mut out =
        String::from("| | count | right fold count | RMSE | Fréchet |\n|---|---|---|---|---|\n");
    out += &format!(
        "| first folds | {} | {} | {} | {} |\n",
        first.len(),
        right(&first),
        mean(stat_of(&first, |s| s.rmse)),
        mean(stat_of(&first, |s| s.frechet))
    );
    out += &format!(
        "| second folds (scored on step 2) | {} | {} | {} | {} |",
        second.len(),
        right(&second),
        mean(stat_of(&second, |s| step2(s).map(|t| t.0))),
        mean(stat_of(&second, |s| step2(s).map(|t| t.1)))
    );
    out
}

/// Each sample's fold count and the RMSE, Fréchet and aligned RMSE of its last step, of a
/// snapshot.
fn steps(name: &str) -> String {
    let r = report(name);
    let mut out = String::from("| sample | folds found / expected | RMSE (last step) | Fréchet (last step) | aligned RMSE (last step) |\n|---|---|---|---|---|\n");
    let cell = |v: Option<f64>| v.map_or("–".into(), |v| format!("{v:.4}"));
    for s in &r.samples {
        let last = s.steps.last();
        let [rmse, frechet, aligned] =
            [last.map(|t| t.rmse), last.map(|t| t.frechet), last.and_then(|t| t.aligned_rmse)]
                .map(cell);
        out += &format!(
            "| `{}` | {} / {} | {rmse} | {frechet} | {aligned} |\n",
            s.name, s.folds, s.expected_folds
        );
    }
    let last = |f: fn(&close::eval::StepResult) -> Option<f64>| {
        stat_of(&r.samples.iter().collect::<Vec<_>>(), |s| s.steps.last().and_then(f))
    };
    out += &format!(
        "| mean | | {} | {} | {} |",
        mean(last(|t| Some(t.rmse))),
        mean(last(|t| Some(t.frechet))),
        mean(last(|t| t.aligned_rmse))
    );
    out
}

/// The MuJoCo fold loop's outcome per goal, from the `results.json` that
/// `examples/fold_loop.py` wrote on its last run, checked in as `tests/snapshots/NAME.json`
/// (MuJoCo and the Python package are not here at test time, so it is not rerun: a new run
/// replaces the file, for review in its diff).
fn fold_loop(name: &str) -> String {
    let run = read_snapshot(name);
    let results = run["results"].as_array().expect("results.json: a `results` list");
    let mut out = String::from(
        "| cloth (border N) | goal | after try 1: fold distance, shape distance | after try 2 | reached |\n|---|---|---|---|---|\n",
    );
    let after = |t: Option<&Value>| {
        t.map_or("–".into(), |t| {
            let d = &t["distance"];
            let number = |v: &Value| v.as_f64().map_or("–".into(), |v| format!("{v:.3}"));
            let verdict = if t["reached"] == true { "reached" } else { "not reached" };
            format!("{verdict}: {}, {}", number(&d["folds"]), number(&d["geometric"]))
        })
    };
    let within_two = |r: &Value| r["reached_within"].as_u64().is_some_and(|k| k <= 2);
    for r in results {
        let tries = r["tries"].as_array().map(Vec::as_slice).unwrap_or_default();
        let reached = r["reached_within"].as_u64().map_or("no".into(), |k| format!("try {k}"));
        out += &format!(
            "| {} ({}) | {} | {} | {} | {reached} |\n",
            r["cloth"].as_str().unwrap_or("?"),
            r["n"],
            r["goal"].as_str().unwrap_or("?").replace('_', " "),
            after(tries.first()),
            after(tries.get(1)),
        );
    }
    // One-fold goals per cloth, and the sequences apart.
    let kind = |r: &Value| {
        let cloth = r["cloth"].as_str().unwrap_or("?");
        match r["folds"].as_array().map(Vec::len) {
            Some(1) => cloth.to_string(),
            _ => format!("{cloth} sequences"),
        }
    };
    let mut kinds: Vec<String> = results.iter().map(kind).collect();
    kinds.dedup();
    let shares: Vec<String> = kinds
        .iter()
        .map(|k| {
            let of: Vec<&Value> = results.iter().filter(|r| kind(r) == *k).collect();
            format!("{k} {} of {}", of.iter().filter(|r| within_two(r)).count(), of.len())
        })
        .collect();
    out += &format!(
        "| all | {} goals | | | {} within 2 tries ({}) |",
        results.len(),
        results.iter().filter(|r| within_two(r)).count(),
        shares.join(", ")
    );
    out
}

/// The rendering a region's header names: `table NAME`, `methods NAME NAME`, `folds NAME`,
/// `steps NAME`, `fold_loop NAME`.
fn render(page: &str, header: &str) -> String {
    let words: Vec<&str> = header.split_whitespace().collect();
    match words.as_slice() {
        ["table", name] => table(name),
        ["methods", names @ ..] => methods(names),
        ["folds", name] => folds(name),
        ["steps", name] => steps(name),
        ["fold_loop", name] => fold_loop(name),
        _ => panic!("{page}: unknown generated region {header:?}"),
    }
}

/// A generated region of a page: its header (`table builtin`) and its lines, from the
/// opening comment to the closing one.
struct Region {
    header: String,
    lines: std::ops::Range<usize>,
}

/// The page with every generated region rendered anew, and its regions.
fn regenerate(page: &str, text: &str) -> (String, Vec<Region>) {
    let (mut out, mut regions, mut lines) = (String::new(), Vec::new(), text.lines().enumerate());
    while let Some((k, line)) = lines.next() {
        out += line;
        out.push('\n');
        let Some(header) = line.strip_prefix(BEGIN).and_then(|h| h.strip_suffix(" -->")) else {
            continue;
        };
        let end = lines
            .by_ref()
            .find(|(_, l)| *l == END)
            .unwrap_or_else(|| panic!("{page} line {}: {header:?} has no {END}", k + 1))
            .0;
        out += &render(page, header);
        out += "\n";
        out += END;
        out.push('\n');
        regions.push(Region { header: header.to_string(), lines: k..end });
    }
    (out, regions)
}

/// The heading under which a results page keeps its dated measurements: tables there were
/// written by hand as measured then, and stay as they were.
const HISTORY: &str = "## History of measurements";

/// The documentation's pages, relative to the repository: the README, the guides at the
/// root and every page under `docs/`.
fn pages() -> Vec<String> {
    let mut docs: Vec<String> = std::fs::read_dir(root().join("docs"))
        .expect("docs/")
        .map(|e| e.expect("docs/ entry").file_name().to_string_lossy().into_owned())
        .filter(|name| name.ends_with(".md"))
        .map(|name| format!("docs/{name}"))
        .collect();
    docs.sort();
    let guides = ["README.md", "ARCHITECTURE.md", "CONTRIBUTING.md", "CHANGELOG.md"];
    guides.iter().map(|g| g.to_string()).chain(docs).collect()
}

#[test]
fn results_tables_are_rendered_from_the_snapshots() {
    update_snapshots();
    let mut shown = Vec::new();
    for page in pages() {
        let path = root().join(&page);
        let mut text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{page}: {e}"));
        let (fresh, regions) = regenerate(&page, &text);
        // A page without generated regions holds no results (and a guide may hold other
        // tables); the README is a results page whatever it holds.
        if regions.is_empty() && page != "README.md" {
            continue;
        }
        if updating() && fresh != text {
            std::fs::write(&path, &fresh).unwrap_or_else(|e| panic!("write {page}: {e}"));
            text.clone_from(&fresh);
        }
        let stale: Vec<String> = text
            .lines()
            .zip(fresh.lines())
            .enumerate()
            .filter(|(_, (a, b))| a != b)
            .map(|(k, (a, b))| format!("{page} line {}: {a:?} should be {b:?}", k + 1))
            .take(10)
            .collect();
        assert!(
            stale.is_empty() && text == fresh,
            "{page}: tables differ from the snapshots (UPDATE_SNAPSHOTS=1):\n{}",
            stale.join("\n")
        );
        // Every table above the history is generated: markdown tables and `close eval`'s
        // text tables alike.
        let inside = |k: usize| regions.iter().any(|r| r.lines.contains(&k));
        let loose: BTreeMap<usize, &str> = text
            .lines()
            .take_while(|l| *l != HISTORY)
            .enumerate()
            .filter(|(k, l)| (l.starts_with('|') || l.starts_with("category ")) && !inside(*k))
            .map(|(k, l)| (k + 1, l))
            .collect();
        assert!(loose.is_empty(), "{page}: tables written by hand: {loose:#?}");
        shown.extend(regions.into_iter().map(|r| r.header));
    }
    // Every snapshot is shown somewhere: one left out of the pages would drift unseen.
    let names = SNAPSHOTS.iter().map(|(name, _)| *name).chain(["fold_loop"]);
    let unshown: Vec<&str> = names
        .filter(|name| !shown.iter().any(|h| h.split_whitespace().skip(1).any(|w| w == *name)))
        .collect();
    assert!(unshown.is_empty(), "snapshots no page renders: {unshown:?} (regions: {shown:?})");
}

/// The README's Set-up says how many tests are `#[ignore]`d (they need programs beyond Rust):
/// that number is the count of `#[ignore` attributes under `tests/`, `src/` and `crates/`.
#[test]
fn readme_counts_the_ignored_tests() {
    fn count(dir: &Path) -> usize {
        let Ok(entries) = std::fs::read_dir(dir) else { return 0 };
        entries
            .flatten()
            .map(|e| e.path())
            .map(|p| match p.extension() {
                _ if p.is_dir() => count(&p),
                Some(ext) if ext == "rs" => std::fs::read_to_string(&p).map_or(0, |text| {
                    text.lines().filter(|l| l.trim_start().starts_with("#[ignore")).count()
                }),
                _ => 0,
            })
            .sum()
    }
    let ignored: usize = ["tests", "src", "crates"].iter().map(|d| count(&root().join(d))).sum();
    let words = ["No", "One", "Two", "Three", "Four", "Five", "Six", "Seven", "Eight", "Nine"];
    let said = words.get(ignored).map_or_else(|| ignored.to_string(), |w| w.to_string());
    let readme = std::fs::read_to_string(root().join("README.md")).expect("README.md");
    let sentence = format!("{said} {}", if ignored == 1 { "test needs" } else { "tests need" });
    assert!(
        readme.contains(&sentence),
        "README.md should say \"{sentence}…\": {ignored} tests are #[ignore]d"
    );
}

/// The Upload view states the limits the library and the server's default apply.
#[test]
fn upload_view_states_the_limits_applied() {
    let thousands = |n: usize| {
        let digits = n.to_string();
        let mut out = String::new();
        for (k, c) in digits.chars().enumerate() {
            if k > 0 && (digits.len() - k).is_multiple_of(3) {
                out.push(',');
            }
            out.push(c);
        }
        out
    };
    let page = std::fs::read_to_string(root().join("web/index.html")).expect("web/index.html");
    let body_mib = close::server::Config::default().body_limit >> 20;
    let stated = format!(
        "Limits: {} border vertices and {} frames per sample; {body_mib} MiB per upload",
        thousands(close::border::MAX_VERTICES),
        thousands(close::border::MAX_FRAMES),
    );
    assert!(page.contains(&stated), "web/index.html should say \"{stated}\"");
}

/// The page without its code: fenced blocks dropped, inline code spans blanked, so that a
/// path or a `[x](y)` shown as code is not taken for a link.
fn prose(markdown: &str) -> String {
    let mut out = String::new();
    let mut fenced = false;
    for line in markdown.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            out.push('\n');
            continue;
        }
        if !fenced {
            // Odd-numbered pieces between backticks are code.
            for (k, piece) in line.split('`').enumerate() {
                if k % 2 == 0 {
                    out += piece;
                }
            }
        }
        out.push('\n');
    }
    out
}

/// The targets of a page's relative links and images (`[text](target)`,
/// `![alt](target)`): not those with a scheme (`https:`, `mailto:`).
fn relative_links(markdown: &str) -> Vec<String> {
    let text = prose(markdown);
    text.match_indices("](")
        .filter_map(|(k, _)| {
            let rest = &text[k + 2..];
            let target = &rest[..rest.find(')')?];
            // `(a b)` after a bracket is prose; a target has no spaces (a title is not used).
            let scheme = target.split_once(':').is_some_and(|(s, _)| !s.contains(['/', '#']));
            (!target.is_empty() && !target.contains(char::is_whitespace) && !scheme)
                .then(|| target.to_string())
        })
        .collect()
}

/// The anchors of a page's headings as GitHub makes them: the heading's text in lower case,
/// without punctuation but `-` and `_`, spaces as `-`, and `-1`, `-2`… after repeats.
fn anchors(markdown: &str) -> Vec<String> {
    let mut seen: BTreeMap<String, usize> = BTreeMap::new();
    let mut out = Vec::new();
    let mut fenced = false;
    for line in markdown.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
        }
        let Some(heading) = line.strip_prefix('#').filter(|_| !fenced) else { continue };
        let heading = heading.trim_start_matches('#').trim();
        let slug: String = heading
            .to_lowercase()
            .chars()
            .filter(|c| c.is_alphanumeric() || matches!(c, ' ' | '-' | '_'))
            .map(|c| if c == ' ' { '-' } else { c })
            .collect();
        let count = seen.entry(slug.clone()).or_default();
        out.push(if *count == 0 { slug } else { format!("{slug}-{count}") });
        *count += 1;
    }
    out
}

#[test]
fn every_relative_link_of_the_docs_leads_somewhere() {
    let mut broken = Vec::new();
    let mut count = 0;
    for page in pages() {
        let text = std::fs::read_to_string(root().join(&page)).expect("a page");
        let folder = Path::new(&page).parent().unwrap_or(Path::new(""));
        for link in relative_links(&text) {
            count += 1;
            let (file, anchor) = link.split_once('#').unwrap_or((&link, ""));
            let target = if file.is_empty() { PathBuf::from(&page) } else { folder.join(file) };
            let path = root().join(&target);
            if !path.exists() {
                broken.push(format!("{page}: ({link}): no {}", target.display()));
                continue;
            }
            if !anchor.is_empty() && path.extension().is_some_and(|e| e == "md") {
                let heads = anchors(&std::fs::read_to_string(&path).expect("a linked page"));
                if !heads.iter().any(|h| h == anchor) {
                    broken.push(format!("{page}: ({link}): no heading #{anchor} in it"));
                }
            }
        }
    }
    assert!(count > 50, "only {count} relative links found in {:?}", pages());
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

#[test]
fn the_link_checker_reads_links_outside_code_and_anchors_as_github_does() {
    let page = "See [a](docs/a.md#units), ![p](x.png) and [web](https://example.org/x).\n\
                Code: `[not](code.md)` and\n```\n[nor](this.md)\n```\n[mail](mailto:x@y), [b](b.md).";
    assert_eq!(relative_links(page), ["docs/a.md#units", "x.png", "b.md"]);
    let headings = "# Results and speed\n## VR-Folding (the paper's Table I)\n```\n# not\n```\n\
                    ## History of measurements\n### 2026-12-07: a `corpus`, 30 % less\n## Units\n## Units";
    assert_eq!(
        anchors(headings),
        [
            "results-and-speed",
            "vr-folding-the-papers-table-i",
            "history-of-measurements",
            "2026-12-07-a-corpus-30--less",
            "units",
            "units-1"
        ]
    );
}
