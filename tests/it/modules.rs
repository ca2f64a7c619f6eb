//! The library's layering, checked like `cargo modules dependencies --acyclic` would. The
//! crates (`crates/core` → `io` → `render` → `server`) are kept one-way by Cargo itself;
//! inside and across them, the top-level modules (named `crate::module`, module = first
//! segment of a `crate::` or `close_<crate>::` path) must import each other one way only.
//!
//! The graph is read from the sources: every `crate::…` and `close_core::…` (`close_io`,
//! `close_render`) path, grouped imports `crate::{a, b::c}` included, and every `super::…`
//! path that climbs to the crate root, with comments stripped. Names a crate root
//! re-exports (`close_core::Error`) count as the module they come from.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

type Graph = BTreeMap<String, BTreeSet<String>>;

/// The library's crates, lowest first: their names in paths and their source folders.
const CRATES: [&str; 4] = ["core", "io", "render", "server"];
const ROOTS: [&str; 4] = [
    concat!(env!("CARGO_MANIFEST_DIR"), "/crates/core/src"),
    concat!(env!("CARGO_MANIFEST_DIR"), "/crates/io/src"),
    concat!(env!("CARGO_MANIFEST_DIR"), "/crates/render/src"),
    concat!(env!("CARGO_MANIFEST_DIR"), "/crates/server/src"),
];
const CORE: &str = ROOTS[0];
const IO: &str = ROOTS[1];

/// The source without `//` comments (doc comments hold intra-doc links, not imports) and
/// without `/* … */` blocks.
fn strip_comments(source: &str) -> String {
    let mut out = String::with_capacity(source.len());
    let mut rest = source;
    while let Some(k) = rest.find("/") {
        out.push_str(&rest[..k]);
        let tail = &rest[k..];
        if tail.starts_with("//") {
            rest = tail.find('\n').map_or("", |e| &tail[e..]);
        } else if tail.starts_with("/*") {
            rest = tail.find("*/").map_or("", |e| &tail[e + 2..]);
        } else {
            out.push('/');
            rest = &tail[1..];
        }
    }
    out.push_str(rest);
    out
}

fn is_ident(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// The first path segment of each item in a `{a, b::c, d::{e, f}}` group (`text` starts
/// after the opening brace).
fn group_heads(text: &str) -> Vec<String> {
    let mut heads = Vec::new();
    let (mut depth, mut start_of_item) = (0usize, true);
    for (k, c) in text.char_indices() {
        match c {
            '{' => depth += 1,
            '}' if depth == 0 => break,
            '}' => depth -= 1,
            ',' if depth == 0 => start_of_item = true,
            c if start_of_item && is_ident(c) && depth == 0 => {
                heads.push(text[k..].chars().take_while(|&c| is_ident(c)).collect());
                start_of_item = false;
            }
            _ => {}
        }
    }
    heads
}

/// First segments of the paths that start at `prefix` (`crate::`, or a `super::` chain
/// that reaches the root) in `code`.
fn heads_after(code: &str, prefix: &str) -> Vec<String> {
    let mut heads = Vec::new();
    for (k, _) in code.match_indices(prefix) {
        if code[..k].chars().next_back().is_some_and(|c| is_ident(c) || c == ':') {
            continue;
        }
        let rest = &code[k + prefix.len()..];
        match rest.strip_prefix('{') {
            Some(group) => heads.extend(group_heads(group)),
            None => heads.push(rest.chars().take_while(|&c| is_ident(c)).collect()),
        }
    }
    heads
}

/// Top-level module paths of one file: `src/a.rs` and `src/a/mod.rs` → [a], `src/a/b.rs`
/// → [a, b].
fn module_path(file: &Path) -> Vec<String> {
    let relative = ROOTS
        .iter()
        .find_map(|root| file.strip_prefix(root).ok())
        .unwrap_or(file)
        .with_extension("");
    let mut parts: Vec<String> =
        relative.iter().map(|p| p.to_string_lossy().into_owned()).collect();
    if parts.last().is_some_and(|p| p == "mod") {
        parts.pop();
    }
    parts
}

/// Every module a file imports from a crate root, as (crate, name as written): its own
/// crate's (`crate::`, `super::` to the root) and the lower crates' (`close_core::`, …).
fn imports(file: &Path, own: &str, code: &str) -> Vec<(String, String)> {
    let mut heads: Vec<(String, String)> =
        heads_after(code, "crate::").into_iter().map(|h| (own.to_string(), h)).collect();
    // `super::` pops one segment each; a chain that empties the path lands at the root.
    let depth = module_path(file).len();
    if depth >= 1 {
        heads.extend(
            heads_after(code, &"super::".repeat(depth)).into_iter().map(|h| (own.to_string(), h)),
        );
    }
    for name in CRATES {
        heads.extend(
            heads_after(code, &format!("close_{name}::"))
                .into_iter()
                .map(|h| (name.to_string(), h)),
        );
    }
    heads
}

/// Root re-exports `pub use module::{A, B}` / `pub use module::A` of `lib.rs`: name → module.
fn root_reexports(lib: &str) -> BTreeMap<String, String> {
    let mut names = BTreeMap::new();
    for line in lib.lines().filter_map(|l| l.trim().strip_prefix("pub use ")) {
        let Some((module, rest)) = line.split_once("::") else { continue };
        let items = rest.trim_end_matches(';');
        let items = items.strip_prefix('{').map_or(vec![items.to_string()], group_heads);
        for item in items {
            let last = item.rsplit("::").next().unwrap_or(&item).to_string();
            names.insert(last, module.to_string());
        }
    }
    names
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap().flatten() {
        let path = entry.path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The module graph of the crates' sources (their `lib.rs` files are not modules); nodes
/// are `crate::module`.
fn crate_graph() -> Graph {
    let mut modules = BTreeSet::new();
    let mut reexports = BTreeMap::new();
    for (name, root) in CRATES.iter().zip(ROOTS) {
        let lib = std::fs::read_to_string(format!("{root}/lib.rs")).unwrap();
        for line in lib.lines() {
            let line = line.trim();
            if let Some(m) = line.strip_prefix("pub mod ").or_else(|| line.strip_prefix("mod ")) {
                modules.insert(format!("{name}::{}", m.trim_end_matches(';')));
            }
        }
        for (item, module) in root_reexports(&lib) {
            reexports.insert(format!("{name}::{item}"), format!("{name}::{module}"));
        }
    }
    let mut graph: Graph = modules.iter().map(|m| (m.clone(), BTreeSet::new())).collect();
    for (name, root) in CRATES.iter().zip(ROOTS) {
        let mut files = Vec::new();
        rust_files(Path::new(root), &mut files);
        for file in files.iter().filter(|f| f.file_name().is_none_or(|n| n != "lib.rs")) {
            let Some(first) = module_path(file).first().map(|m| format!("{name}::{m}")) else {
                continue;
            };
            if !modules.contains(&first) {
                continue;
            }
            let code = strip_comments(&std::fs::read_to_string(file).unwrap());
            for (krate, head) in imports(file, name, &code) {
                let node = format!("{krate}::{head}");
                let to = if modules.contains(&node) { Some(&node) } else { reexports.get(&node) };
                if let Some(to) = to.filter(|to| **to != first) {
                    graph.entry(first.clone()).or_default().insert(to.clone());
                }
            }
        }
    }
    graph
}

/// A cycle of the graph (first node repeated at the end), if there is one (depth-first
/// search with the path on the stack).
fn find_cycle(graph: &Graph) -> Option<Vec<String>> {
    fn visit(
        node: &str,
        graph: &Graph,
        path: &mut Vec<String>,
        done: &mut BTreeSet<String>,
    ) -> Option<Vec<String>> {
        if let Some(k) = path.iter().position(|p| p == node) {
            let mut cycle = path[k..].to_vec();
            cycle.push(node.to_string());
            return Some(cycle);
        }
        if done.contains(node) {
            return None;
        }
        path.push(node.to_string());
        for next in graph.get(node).into_iter().flatten() {
            if let Some(cycle) = visit(next, graph, path, done) {
                return Some(cycle);
            }
        }
        path.pop();
        done.insert(node.to_string());
        None
    }
    let mut done = BTreeSet::new();
    graph.keys().find_map(|node| visit(node, graph, &mut Vec::new(), &mut done))
}

#[test]
fn modules_import_each_other_one_way_only() {
    let graph = crate_graph();
    assert!(graph.len() > 10, "too few modules found: {graph:?}");
    // The readers sit below the border and mesh code: the edge that once closed a cycle.
    assert!(graph["io::formats"].contains("io::mesh"), "{graph:?}");
    assert!(graph["io::formats"].contains("core::border"), "{graph:?}");
    if let Some(cycle) = find_cycle(&graph) {
        panic!("module cycle: {}\nfull graph: {graph:#?}", cycle.join(" → "));
    }
}

#[test]
fn the_checker_finds_a_cycle_and_accepts_a_chain() {
    let edges = |list: &[(&str, &str)]| {
        let mut g = Graph::new();
        for (a, b) in list {
            g.entry(a.to_string()).or_default().insert(b.to_string());
            g.entry(b.to_string()).or_default();
        }
        g
    };
    let chain = edges(&[
        ("formats", "mesh"),
        ("mesh", "border"),
        ("formats", "border"),
        ("border", "error"),
    ]);
    assert_eq!(find_cycle(&chain), None);
    let cyclic = edges(&[("formats", "mesh"), ("mesh", "formats"), ("border", "error")]);
    assert_eq!(find_cycle(&cyclic), Some(vec!["formats".into(), "mesh".into(), "formats".into()]));
    let long = edges(&[("a", "b"), ("b", "c"), ("c", "d"), ("d", "b")]);
    assert_eq!(find_cycle(&long).map(|c| c.join(" → ")), Some("b → c → d → b".into()));
}

#[test]
fn the_parser_reads_grouped_imports_super_and_reexports() {
    let code = strip_comments(
        "use crate::{border::{Point, to_xyz}, error::Error};\n// crate::server is a comment\nuse super::super::mesh::X;\nlet a = crate::Error::Empty; /* crate::fold */\nlet b = notcrate::formats;\nuse close_core::angle::TAU;",
    );
    let heads = imports(Path::new(&format!("{IO}/formats/obj.rs")), "io", &code);
    let io = |m: &str| ("io".to_string(), m.to_string());
    assert_eq!(
        heads,
        vec![io("border"), io("error"), io("Error"), io("mesh"), ("core".into(), "angle".into())]
    );
    // In a top-level file one `super::` reaches the root.
    assert_eq!(
        imports(Path::new(&format!("{CORE}/disk.rs")), "core", "use super::gli::f;"),
        vec![("core".to_string(), "gli".to_string())]
    );
    // Two levels down, one `super::` stays inside the module.
    assert!(imports(Path::new(&format!("{IO}/formats/obj.rs")), "io", "use super::MeshFrame;")
        .is_empty());
    let names = root_reexports("pub use error::{Error, Result};\npub use formats::Sample;");
    assert_eq!(names.get("Error").map(String::as_str), Some("error"));
    assert_eq!(names.get("Sample").map(String::as_str), Some("formats"));
}
