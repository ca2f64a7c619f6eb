//! The wire contract. Every answer the CLI, the server and Python give is a serde type of
//! the library (the analysis, the plan, the interpolation, the evaluation report, the
//! server's analysis and error); their JSON Schemas are generated from those types
//! (schemars, describing how they serialise) and checked in under `schema/`.
//!
//! The test fails when a type and its checked-in schema drift, when an answer of the binary
//! or the server does not fit its schema (every object closed: a key the schema does not
//! name is an error), and when the Python stubs' `TypedDict`s name other keys than the
//! schema does. After a change of the types on purpose,
//! `UPDATE_SNAPSHOTS=1 cargo test --test it schema::` rewrites the schemas, for review in
//! the diff; the stubs (`python/close/__init__.pyi`) are edited by hand.

use std::path::PathBuf;
use std::process::Command;

use axum::body::{to_bytes, Body};
use axum::http::{header, Request};
use schemars::generate::SchemaSettings;
use schemars::JsonSchema;
use serde_json::{json, Value};
use tower::ServiceExt;

use crate::common::{root, updating};

/// Makes a schema.
type Generate = fn() -> Value;

/// The schemas: file name under `schema/` and the type whose serialisation it describes.
const SCHEMAS: &[(&str, Generate)] = &[
    ("analysis", generate::<close::Analysis>),
    ("plan", generate::<close::plan::Answer>),
    ("interpolation", generate::<close::interpolate::Interpolation>),
    ("evaluation", generate::<close::eval::Report>),
    ("sample", generate::<close::Sample>),
    ("api-analysis", generate::<close::server::answer::AnalyzeAnswer<'static>>),
    ("api-plan", generate::<close::server::answer::PlanAnswer>),
    ("api-samples", generate::<close::server::answer::SampleList<'static>>),
    ("error", generate::<close::server::answer::ErrorBody>),
];

/// The JSON Schema (2020-12) of how `T` serialises.
fn generate<T: JsonSchema>() -> Value {
    let generator = SchemaSettings::draft2020_12().for_serialize().into_generator();
    serde_json::to_value(generator.into_root_schema_for::<T>()).expect("a schema is JSON")
}

fn schema_path(name: &str) -> PathBuf {
    root().join("schema").join(format!("{name}.json"))
}

/// The checked-in schema `name`.
fn schema(name: &str) -> Value {
    let path = schema_path(name);
    let text = std::fs::read(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (UPDATE_SNAPSHOTS=1 writes it)", path.display()));
    serde_json::from_slice(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn the_checked_in_schemas_are_the_types_schemas() {
    let mut drifted = Vec::new();
    for (name, make) in SCHEMAS {
        let generated = make();
        if updating() {
            let text = serde_json::to_string_pretty(&generated).unwrap() + "\n";
            std::fs::create_dir_all(root().join("schema")).unwrap();
            std::fs::write(schema_path(name), text).unwrap();
        } else if schema(name) != generated {
            drifted.push(*name);
        }
    }
    assert!(
        drifted.is_empty(),
        "schema/{{{}}}.json differ from the types: UPDATE_SNAPSHOTS=1 cargo test --test it schema:: rewrites them",
        drifted.join(",")
    );
}

/// The schema `schema` resolved through `$ref` (into the root's `$defs`).
fn resolve<'a>(root: &'a Value, schema: &'a Value) -> &'a Value {
    match schema.get("$ref").and_then(Value::as_str) {
        Some(reference) => {
            let name = reference.strip_prefix("#/$defs/").unwrap_or_else(|| {
                panic!("a reference outside $defs: {reference}");
            });
            resolve(root, &root["$defs"][name])
        }
        None => schema,
    }
}

fn type_fits(kind: &str, value: &Value) -> bool {
    match kind {
        "null" => value.is_null(),
        "boolean" => value.is_boolean(),
        "integer" => value.is_i64() || value.is_u64(),
        "number" => value.is_number(),
        "string" => value.is_string(),
        "array" => value.is_array(),
        "object" => value.is_object(),
        other => panic!("a schema type this check does not know: {other}"),
    }
}

/// Where `value` does not fit `schema`, each as "path: problem", for the part of JSON
/// Schema that schemars writes: `type`, `enum`, `const`, `anyOf`/`oneOf`/`allOf`,
/// `properties`/`required`/`additionalProperties`, `items`/`prefixItems`, `minItems`/
/// `maxItems` and `minimum`. An object schema with `properties` is closed: its value may
/// hold no other key.
fn misfits(root: &Value, schema: &Value, value: &Value, path: &str, out: &mut Vec<String>) {
    let schema = resolve(root, schema);
    if schema == &Value::Bool(true) {
        return;
    }
    if let Some(kinds) = schema.get("type") {
        let kinds: Vec<&str> = match kinds {
            Value::String(k) => vec![k.as_str()],
            Value::Array(ks) => ks.iter().filter_map(Value::as_str).collect(),
            _ => panic!("{path}: a type that is neither a name nor a list"),
        };
        if !kinds.iter().any(|k| type_fits(k, value)) {
            out.push(format!("{path}: {value} is not {kinds:?}"));
            return;
        }
    }
    if let Some(Value::Array(allowed)) = schema.get("enum") {
        if !allowed.contains(value) {
            out.push(format!("{path}: {value} is not one of {allowed:?}"));
        }
    }
    if let Some(constant) = schema.get("const") {
        if constant != value {
            out.push(format!("{path}: {value} is not {constant}"));
        }
    }
    for key in ["anyOf", "oneOf"] {
        if let Some(Value::Array(branches)) = schema.get(key) {
            let fits = branches.iter().any(|b| {
                let mut inner = Vec::new();
                misfits(root, b, value, path, &mut inner);
                inner.is_empty()
            });
            if !fits {
                out.push(format!("{path}: {value:.80} fits none of its {key} branches"));
            }
        }
    }
    if let Some(Value::Array(all)) = schema.get("allOf") {
        for b in all {
            misfits(root, b, value, path, out);
        }
    }
    if let Some(minimum) = schema.get("minimum").and_then(Value::as_f64) {
        if value.as_f64().is_some_and(|v| v < minimum) {
            out.push(format!("{path}: {value} is under {minimum}"));
        }
    }
    if let Value::Object(fields) = value {
        let properties = schema.get("properties").and_then(Value::as_object);
        for required in schema.get("required").and_then(Value::as_array).into_iter().flatten() {
            let key = required.as_str().unwrap_or_default();
            if !fields.contains_key(key) {
                out.push(format!("{path}: no `{key}`"));
            }
        }
        for (key, field) in fields {
            let inner = format!("{path}.{key}");
            match (properties.and_then(|p| p.get(key)), schema.get("additionalProperties")) {
                (Some(property), _) => misfits(root, property, field, &inner, out),
                (None, Some(Value::Bool(false))) => out.push(format!("{inner}: not in the schema")),
                (None, Some(extra)) => misfits(root, extra, field, &inner, out),
                (None, None) if properties.is_some() => {
                    out.push(format!("{inner}: not in the schema"))
                }
                (None, None) => {}
            }
        }
    }
    if let Value::Array(items) = value {
        let count = items.len() as f64;
        if schema.get("minItems").and_then(Value::as_f64).is_some_and(|m| count < m) {
            out.push(format!("{path}: {} items, under minItems", items.len()));
        }
        if schema.get("maxItems").and_then(Value::as_f64).is_some_and(|m| count > m) {
            out.push(format!("{path}: {} items, over maxItems", items.len()));
        }
        let prefix = schema.get("prefixItems").and_then(Value::as_array);
        for (k, item) in items.iter().enumerate() {
            let inner = format!("{path}[{k}]");
            match (prefix.and_then(|p| p.get(k)), schema.get("items")) {
                (Some(first), _) => misfits(root, first, item, &inner, out),
                (None, Some(rest)) => misfits(root, rest, item, &inner, out),
                (None, None) => {}
            }
        }
    }
}

/// Asserts that `value` (the answer `what`) fits the checked-in schema `name`.
fn assert_fits(name: &str, value: &Value, what: &str) {
    let root = schema(name);
    let mut out = Vec::new();
    misfits(&root, &root, value, "$", &mut out);
    assert!(out.is_empty(), "{what} does not fit schema/{name}.json:\n{}", out.join("\n"));
}

#[test]
fn the_checker_finds_a_key_too_many_or_missing_and_a_wrong_type() {
    let root = json!({
        "type": "object",
        "properties": {"a": {"type": "integer", "minimum": 0}, "b": {"$ref": "#/$defs/B"}},
        "required": ["a"],
        "$defs": {"B": {"anyOf": [{"type": "null"}, {"type": "array", "prefixItems": [{"type": "number"}, {"type": "number"}], "minItems": 2, "maxItems": 2}]}},
    });
    let check = |value: Value| {
        let mut out = Vec::new();
        misfits(&root, &root, &value, "$", &mut out);
        out
    };
    assert!(check(json!({"a": 1, "b": [0.5, 2]})).is_empty());
    assert!(check(json!({"a": 1, "b": null})).is_empty());
    assert_eq!(check(json!({"b": null})), ["$: no `a`"]);
    assert_eq!(check(json!({"a": 1, "c": 2})), ["$.c: not in the schema"]);
    assert_eq!(check(json!({"a": -1})), ["$.a: -1 is under 0"]);
    assert_eq!(check(json!({"a": 0.5})).len(), 1);
    assert_eq!(check(json!({"a": 1, "b": [1]})).len(), 1);
}

/// What `close ARGS` prints, as JSON.
fn cli(args: &[&str]) -> Value {
    let out = Command::new(env!("CARGO_BIN_EXE_close"))
        .current_dir(root())
        .args(args)
        .output()
        .expect("run close");
    assert!(out.status.success(), "close {args:?}: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("close prints JSON")
}

/// Samples that exercise every part of an analysis: a flat fold, a second fold across
/// stacked layers of several arcs along a line of its own, a mesh, and no fold at all.
const SAMPLES: &[&str] = &[
    "tests/fixtures/physics/disk_f1_half_bottom_up.json",
    "tests/fixtures/physics-mujoco/border/trousers_q1_leg_over_leg_then_half.json",
    "tests/fixtures/physics/q3_napkin_half_then_quarter_31x31.json",
];

#[test]
fn the_clis_answers_fit_their_schemas() {
    for sample in SAMPLES {
        let analysis = cli(&["analyze", sample, "--json"]);
        assert_fits("analysis", &analysis, &format!("close analyze {sample}"));
        let paper = cli(&["analyze", sample, "--json", "--method", "paper"]);
        assert_fits("analysis", &paper, &format!("close analyze {sample} --method paper"));
        let plan = cli(&["plan", sample, "--goal", "0.5,3.6", "--json"]);
        assert_fits("plan", &plan, &format!("close plan {sample}"));
        // A sample as the library writes it (a file may hold keys the readers skip).
        let read = close::formats::json::parse_sample(&std::fs::read(sample).unwrap()).unwrap();
        let written = serde_json::from_str(&close::formats::json::to_json(&read)).unwrap();
        assert_fits("sample", &written, sample);
    }
    // The multi-arc step names its arcs and its line.
    let trousers = cli(&["analyze", SAMPLES[1], "--json"]);
    assert!(trousers["steps"][1]["arcs"].as_array().is_some_and(|a| a.len() > 1), "{trousers}");
    let unchanged = cli(&["analyze", SAMPLES[0], "--json", "--end", "0"]);
    assert_fits("analysis", &unchanged, "an analysis of one frame");
    let eval = cli(&[
        "eval",
        "--json",
        "tests/fixtures/physics",
        "tests/fixtures/vrfolding/vr_simulation_folding2_dataset.zarr",
    ]);
    assert_fits("evaluation", &eval, "close eval --json");
    // Its units said in it (issue 45): the field names stay `f1_error`, `rmse`.
    assert_eq!(eval["units"], json!({"angle": "rad", "length": "normalised"}));
    let table = Command::new(env!("CARGO_BIN_EXE_close"))
        .current_dir(root())
        .args(["eval", "tests/fixtures/physics"])
        .output()
        .expect("run close");
    let table = String::from_utf8_lossy(&table.stdout);
    let header = table.lines().next().unwrap_or_default();
    assert!(header.contains("f1 err°") && header.contains("f2 err°"), "{table}");
}

/// Words of a field's name that make it an angle: the fold coordinates (f1, f2, a fold, its
/// arcs, a goal), corners on the border circle, a curve's rim and coefficients, turns, and
/// directions (which may be angles or vectors: they must say which).
const ANGLE_NAMES: &[&str] = &[
    "angle",
    "angles",
    "theta",
    "fold",
    "folds",
    "f1",
    "f2",
    "arcs",
    "corners",
    "rim",
    "goal",
    "turns",
    "a0",
    "a1",
    "direction",
];
/// Words of a description that make a field an angle, whatever its name.
const ANGLE_WORDS: &[&str] = &["angle", "angular", "2π", "θ", "theta", "radian", "degree"];
/// Endings of a name that say the field's unit (the contract's rule: another unit is named
/// in the field's name).
const UNIT_ENDINGS: &[&str] = &["_percent", "_edges", "_deg", "_degrees"];
/// What a description says of a field with an angle's name that is no angle.
const NOT_ANGLES: &[&str] = &["border parameters", "unit vector"];

/// Whether `schema` holds floating-point numbers: a number, an array of them (at any depth),
/// either of those or null, or a statistic of them (an object of numbers: `{mean, var}`).
fn holds_floats(root: &Value, schema: &Value) -> bool {
    let schema = resolve(root, schema);
    let kinds: Vec<&str> = match schema.get("type") {
        Some(Value::String(k)) => vec![k.as_str()],
        Some(Value::Array(ks)) => ks.iter().filter_map(Value::as_str).collect(),
        _ => Vec::new(),
    };
    let items = schema.get("prefixItems").and_then(Value::as_array).into_iter().flatten();
    (kinds.contains(&"number"))
        || (kinds.contains(&"array")
            && items.chain(schema.get("items")).any(|i| holds_floats(root, i)))
        || ["anyOf", "oneOf"].iter().any(|k| {
            schema
                .get(*k)
                .and_then(Value::as_array)
                .is_some_and(|bs| bs.iter().any(|b| holds_floats(root, b)))
        })
        || (kinds.contains(&"object")
            && schema.get("properties").and_then(Value::as_object).is_some_and(|ps| {
                !ps.is_empty() && ps.values().all(|p| p.get("type") == Some(&json!("number")))
            }))
}

/// Whether a description says an angle's unit: radians (or `rad`), degrees or °.
fn says_angle_unit(description: &str) -> bool {
    let text = description.to_lowercase();
    text.contains("radian")
        || text.contains("degree")
        || text.contains('°')
        || text.split(|c: char| !c.is_alphanumeric()).any(|w| w == "rad")
}

/// The fields of schema `root` (named `file`) that hold angles: each as
/// (`file Definition.field`, whether it says its unit).
fn angle_fields(file: &str, root: &Value) -> Vec<(String, bool)> {
    let definitions = root.get("$defs").and_then(Value::as_object).into_iter().flatten();
    let mut found = Vec::new();
    for (definition, node) in std::iter::once((&"root".to_string(), root)).chain(definitions) {
        let properties = node.get("properties").and_then(Value::as_object).into_iter().flatten();
        for (name, property) in properties {
            if !holds_floats(root, property) {
                continue;
            }
            let description = property.get("description").and_then(Value::as_str).unwrap_or("");
            let lower = description.to_lowercase();
            let by_name = name.split('_').any(|w| ANGLE_NAMES.contains(&w));
            let by_words = ANGLE_WORDS.iter().any(|w| lower.contains(w));
            if !(by_name || by_words) || UNIT_ENDINGS.iter().any(|e| name.ends_with(e)) {
                continue;
            }
            let said = says_angle_unit(description) || NOT_ANGLES.iter().any(|w| lower.contains(w));
            found.push((format!("{file} {definition}.{name}: {description:?}"), said));
        }
    }
    found
}

/// Issue 45: every angle of every answer is in radians, and its schema says so in the field's
/// description (or the field names another unit in its name, or says it is no angle).
#[test]
fn every_angle_field_says_its_unit() {
    let mut fields = Vec::new();
    for (name, _) in SCHEMAS {
        fields.extend(angle_fields(name, &schema(name)));
    }
    let silent: Vec<&str> = fields.iter().filter(|f| !f.1).map(|f| f.0.as_str()).collect();
    assert!(
        silent.is_empty(),
        "angle fields whose description says no unit (write '(radians)' in the field's doc comment):\n{}",
        silent.join("\n")
    );
    // The check sees the angles it is for.
    for known in [
        "evaluation Summary.f1_error",
        "evaluation FoldSummary.f2_error",
        "evaluation SampleResult.angle_error",
        "analysis root.corners",
        "analysis root.folds",
        "analysis Step.fold",
        "analysis Curve.a0",
        "plan root.goal",
        "plan Pick.angle",
        "interpolation root.folds",
        "sample Truth.folds",
    ] {
        assert!(
            fields.iter().any(|f| f.0.starts_with(&format!("{known}:"))),
            "{known} is not seen as an angle: {fields:#?}"
        );
    }
}

#[test]
fn the_angle_check_finds_an_angle_without_its_unit() {
    let root = json!({
        "type": "object",
        "properties": {
            "fold": {"type": "array", "prefixItems": [{"type": "number"}, {"type": "number"}]},
            "corners": {"type": "array", "items": {"type": "number"}, "description": "Corner angles (radians)."},
            "folded_percent": {"type": "number"},
            "folded_corners": {"type": "array", "items": {"type": "integer"}},
            "mean_error": {"$ref": "#/$defs/Stat", "description": "Its angular error."},
            "explained": {"type": "number", "description": "Share of the mismatch its folds explain."},
            "line": {"$ref": "#/$defs/Line"},
        },
        "$defs": {
            "Stat": {"type": "object", "properties": {"mean": {"type": "number"}, "var": {"type": "number"}}},
            "Line": {"type": "object", "properties": {
                "point": {"type": "array", "items": {"type": "number"}},
                "direction": {"type": ["array", "null"], "items": {"type": "number"}, "description": "A unit vector."},
            }},
        },
    });
    let found = angle_fields("t", &root);
    let names: Vec<(&str, bool)> =
        found.iter().map(|(f, said)| (f.split(':').next().unwrap(), *said)).collect();
    assert_eq!(
        names,
        [
            ("t root.fold", false),
            ("t root.corners", true),
            ("t root.mean_error", false),
            ("t Line.direction", true)
        ],
        "{found:#?}"
    );
}

async fn request(app: &axum::Router, method: &str, uri: &str, body: Option<&Value>) -> Value {
    let builder = Request::builder().method(method).uri(uri);
    let request = match body {
        Some(b) => {
            builder.header(header::CONTENT_TYPE, "application/json").body(Body::from(b.to_string()))
        }
        None => builder.body(Body::empty()),
    }
    .unwrap();
    let response = app.clone().oneshot(request).await.expect("the router never fails");
    let bytes = to_bytes(response.into_body(), usize::MAX).await.expect("a body");
    serde_json::from_slice(&bytes)
        .unwrap_or_else(|e| panic!("{uri}: not JSON ({e}): {}", String::from_utf8_lossy(&bytes)))
}

#[tokio::test]
async fn the_servers_answers_fit_their_schemas() {
    let app = close::server::app(close::server::AppState::new());
    let sample: Value =
        serde_json::from_slice(&std::fs::read(root().join(SAMPLES[1])).unwrap()).unwrap();
    let analysis = request(&app, "POST", "/api/analyze", Some(&sample)).await;
    assert_fits("api-analysis", &analysis, "POST /api/analyze");
    // A listed sample's answer holds the sample.
    let rows = request(&app, "GET", "/api/samples?limit=1", None).await;
    assert_fits("api-samples", &rows, "GET /api/samples");
    let id =
        rows["samples"][0]["id"].as_str().or_else(|| rows[0]["id"].as_str()).map(str::to_string);
    let id = id.unwrap_or_else(|| panic!("no sample id in {rows:.200}"));
    let listed = request(&app, "GET", &format!("/api/samples/{id}"), None).await;
    assert!(listed.get("sample").is_some(), "{listed:.200}");
    assert_fits("api-analysis", &listed, "GET /api/samples/{id}");
    let plan =
        request(&app, "POST", "/api/plan", Some(&json!({"sample": sample, "goal": [0.5, 3.6]})))
            .await;
    assert!(plan.get("states").is_some(), "{plan:.200}");
    assert_fits("api-plan", &plan, "POST /api/plan");
    let border = &analysis["start_border"];
    let between = json!({"border": border, "from": [0.5, 3.6], "to": [1.0, 4.0], "steps": 5});
    let interpolation = request(&app, "POST", "/api/interpolate", Some(&between)).await;
    assert_fits("interpolation", &interpolation, "POST /api/interpolate (from, to)");
    let step = &analysis["steps"][1];
    let turned = json!({"border": analysis["steps"][0]["predicted"], "reference": border, "arcs": step["arcs"], "line": step["line"], "steps": 5});
    let interpolation = request(&app, "POST", "/api/interpolate", Some(&turned)).await;
    assert!(interpolation.get("turns").is_some(), "{interpolation:.200}");
    assert_fits("interpolation", &interpolation, "POST /api/interpolate (arcs, line)");
    let error = request(&app, "GET", "/api/samples/no-such-sample", None).await;
    assert_fits("error", &error, "a 404");
}

/// A `TypedDict` of the stubs: its name, the schema definition it names (`schema/FILE.json`
/// or `schema/FILE.json#/$defs/NAME` in its docstring or in a comment line before it), and
/// its keys, each with whether it is `NotRequired`.
#[derive(Debug)]
struct TypedDict {
    name: String,
    schema: Option<(String, Option<String>)>,
    keys: Vec<(String, bool)>,
}

/// The `schema/FILE.json[#/$defs/NAME]` named in `text`.
fn schema_marker(text: &str) -> Option<(String, Option<String>)> {
    let at = text.find("schema/")?;
    let rest = &text[at + "schema/".len()..];
    let end = rest.find(".json")?;
    let file = rest[..end].to_string();
    let definition = rest[end + ".json".len()..]
        .strip_prefix("#/$defs/")
        .map(|d| d.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect());
    Some((file, definition))
}

/// The `TypedDict`s of a stub file: class form (`class X(TypedDict):` and `key: type`
/// lines) and call form (`X = TypedDict("X", {"key": type, ...})`, for keys that are
/// Python keywords).
fn typed_dicts(stubs: &str) -> Vec<TypedDict> {
    let lines: Vec<&str> = stubs.lines().collect();
    let mut found = Vec::new();
    for (k, line) in lines.iter().enumerate() {
        let before = if k > 0 { lines[k - 1] } else { "" };
        if let Some(rest) = line.strip_prefix("class ") {
            if !rest.contains("TypedDict") {
                continue;
            }
            let name = rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
            let body: Vec<&str> = lines[k + 1..]
                .iter()
                .take_while(|l| l.starts_with("    ") || l.is_empty())
                .copied()
                .collect();
            let text = body.join("\n");
            let keys = body
                .iter()
                .filter_map(|l| {
                    let l = l.trim();
                    let (key, kind) = l.split_once(':')?;
                    let plain = key.chars().all(|c| c.is_alphanumeric() || c == '_');
                    (plain && !l.starts_with('#') && !l.starts_with('"'))
                        .then(|| (key.to_string(), kind.trim().starts_with("NotRequired")))
                })
                .collect();
            found.push(TypedDict {
                name,
                schema: schema_marker(&text).or_else(|| schema_marker(before)),
                keys,
            });
        } else if let Some((name, rest)) = line.split_once(" = TypedDict(") {
            let call: String = lines[k..]
                .iter()
                .scan(false, |done, l| {
                    (!*done).then(|| {
                        *done = l.trim_end().ends_with(')');
                        *l
                    })
                })
                .collect::<Vec<_>>()
                .join("\n");
            let keys = call
                .split('"')
                .collect::<Vec<_>>()
                .windows(3)
                .filter(|w| w[2].trim_start().starts_with(':'))
                .map(|w| {
                    (w[1].to_string(), w[2].trim_start()[1..].trim().starts_with("NotRequired"))
                })
                .collect();
            let _ = rest;
            found.push(TypedDict {
                name: name.trim().to_string(),
                schema: schema_marker(before),
                keys,
            });
        }
    }
    found
}

#[test]
fn the_python_stubs_name_the_schemas_keys() {
    let stubs = std::fs::read_to_string(root().join("python/close/__init__.pyi")).unwrap();
    let dicts = typed_dicts(&stubs);
    let checked: Vec<&TypedDict> = dicts.iter().filter(|d| d.schema.is_some()).collect();
    assert!(checked.len() >= 10, "too few TypedDicts tied to a schema: {dicts:?}");
    let mut problems = Vec::new();
    for dict in checked {
        let (file, definition) = dict.schema.clone().unwrap();
        let root = schema(&file);
        let node = match &definition {
            Some(d) => resolve(&root, &root["$defs"][d]),
            None => &root,
        };
        let properties = node.get("properties").and_then(Value::as_object).unwrap_or_else(|| {
            panic!("{}: schema/{file}.json {definition:?} has no properties", dict.name)
        });
        let required: Vec<&str> = node
            .get("required")
            .and_then(Value::as_array)
            .map(|r| r.iter().filter_map(Value::as_str).collect())
            .unwrap_or_default();
        let mut theirs: Vec<(String, bool)> =
            properties.keys().map(|k| (k.clone(), !required.contains(&k.as_str()))).collect();
        let mut ours = dict.keys.clone();
        theirs.sort();
        ours.sort();
        if theirs != ours {
            problems.push(format!(
                "{} (schema/{file}.json {}): stub keys {ours:?}, schema keys {theirs:?} (true: NotRequired)",
                dict.name,
                definition.as_deref().unwrap_or("root")
            ));
        }
    }
    assert!(problems.is_empty(), "the stubs and the schemas differ:\n{}", problems.join("\n"));
}

#[test]
fn the_stub_parser_reads_both_forms_and_their_markers() {
    let stubs = "class Metrics(TypedDict):\n    \"\"\"schema/analysis.json#/$defs/Metrics\"\"\"\n\n    rmse: float\n    note: NotRequired[str]\n\n# schema/plan.json#/$defs/Pick\nPick = TypedDict(\"Pick\", {\"vertex\": int, \"from\": List[float], \"to\": NotRequired[List[float]]})\n\nclass Other:\n    x: int\n";
    let dicts = typed_dicts(stubs);
    assert_eq!(dicts.len(), 2, "{dicts:?}");
    assert_eq!(dicts[0].name, "Metrics");
    assert_eq!(dicts[0].schema, Some(("analysis".into(), Some("Metrics".into()))));
    assert_eq!(dicts[0].keys, [("rmse".to_string(), false), ("note".to_string(), true)]);
    assert_eq!(dicts[1].name, "Pick");
    assert_eq!(dicts[1].schema, Some(("plan".into(), Some("Pick".into()))));
    assert_eq!(
        dicts[1].keys,
        [("vertex".to_string(), false), ("from".to_string(), false), ("to".to_string(), true)]
    );
}
