//! One answer through every door (issue 27 §1): every node type of the registry, evaluated on
//! random inputs of its ports' types — nested lists of every depth the ports accept, ragged ones
//! included — gives the same outputs (or the same error) whether the inputs come
//!
//! - as RON literals in a graph file, loaded and evaluated as `cnets run` does;
//! - as `cnets eval` JSON: the text read into a document and decoded by the host
//!   (`cnets_host::inputs::node_inputs`, the CLI's and Python's shared code), evaluated as `cnets
//!   eval` does — and for the first cases of every node type through the `cnets` binary itself;
//! - as the plain values, and as the same values with every list of numbers, vectors or texts
//!   *packed* (one row of a shared table): a packed row is the same list to every node.
//!
//! The cases and their `cnets eval` answers are written to `target/tmp/three_doors_cases.json`
//! for the third door, Python's `cnets.eval` (`python/tests/test_three_doors.py`).
//!
//! `THREE_DOORS_CASES` sets the cases per node type (default 24).

use crate::common;

use std::cell::{Cell, RefCell};
use std::collections::BTreeSet;
use std::process::Command;
use std::sync::Arc;

use cnets_engine::eval::{Evaluator, NodeResult, evaluate_node};
use cnets_engine::file::{literal, load_str};
use cnets_engine::value::json::{read_document, to_json};
use cnets_engine::{
    Access, Items, NodeContext, NodeDef, NodeError, NodeFlag, Record, Registry, Value, ValueType,
};
use cnets_geometry::{Line, Plane, PolygonMesh, Polyline, QuadGrid};
use glam::DVec3;
use proptest::prelude::*;
use proptest::test_runner::{Config, TestCaseError, TestRunner};
use serde_json::{Map, Value as Json, json};

/// Node types not evaluated here, and why. Every other registered type is.
const SKIPPED: &[(&str, &str)] = &[
    ("io.read_polylines", "reads a file"),
    ("io.read_mesh", "reads a file"),
    ("io.export_gltf", "writes a file"),
    ("io.export_obj", "writes a file"),
    ("io.export_svg", "writes a file"),
    ("io.export_dxf", "writes a file"),
    ("io.export_json", "writes a file"),
    ("io.export_csv", "writes a file"),
    ("cluster", "the node of a graph file: not a type of its own"),
];

/// Cases of every node type whose JSON also goes through the `cnets` binary.
const CLI_CASES: usize = 2;

/// Cases of every node type written for the Python door.
const PYTHON_CASES: usize = 6;

/// What a door gives for one evaluation.
#[derive(Debug, Clone)]
enum Outcome {
    /// The node ran: its outputs and warnings.
    Ran(Vec<Value>, Vec<String>),
    /// The node ran and failed with this error (compared typed: kind, fields and words).
    Failed(NodeError),
    /// The inputs were refused before the node ran (a door's own words).
    Refused(String),
}

impl Outcome {
    fn same_as(&self, other: &Outcome) -> bool {
        match (self, other) {
            (Outcome::Ran(a, w), Outcome::Ran(b, v)) => {
                a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.same_as(y)) && w == v
            }
            (Outcome::Failed(a), Outcome::Failed(b)) => a == b,
            _ => false,
        }
    }
}

/// One generated evaluation: the node type and the inputs given (port index, value).
#[derive(Debug, Clone)]
struct Case {
    inputs: Vec<(usize, Value)>,
}

// ------------------------------------------------------------------------------------------------
// Values by port type

fn number() -> BoxedStrategy<f64> {
    prop_oneof![
        3 => (-3i32..8).prop_map(f64::from),
        3 => -100.0..100.0f64,
        1 => prop::sample::select(vec![0.5, 0.25, -0.0, 1e-3, 90.0]),
    ]
    .boxed()
}

fn integer() -> BoxedStrategy<i64> {
    prop_oneof![4 => -2i64..12, 1 => prop::sample::select(vec![0i64, 1, 2, 100])].boxed()
}

fn text() -> BoxedStrategy<String> {
    prop_oneof![
        3 => prop::sample::select(
            [
                "sum", "product", "mean", "number", "integer", "point", "vector", "any", "text",
                "boolean", "graph", "bezier", "linear", "x", "x + y", "sin(pi*x)^2 + y/4",
                "", "rows", "columns", "a", "b",
            ]
            .map(String::from)
            .to_vec()
        ),
        1 => "[a-z ]{0,6}",
    ]
    .boxed()
}

fn point() -> BoxedStrategy<DVec3> {
    (number(), number(), number())
        .prop_map(|(x, y, z)| DVec3::new(x, y, z))
        .boxed()
}

fn polyline() -> BoxedStrategy<Value> {
    (prop::collection::vec(point(), 2..6), any::<bool>())
        .prop_map(|(points, closed)| Value::from(Polyline { points, closed }))
        .boxed()
}

/// A rows × cols grid, bumped: a plausible surface.
fn grid_vertices(rows: usize, cols: usize, bumps: &[f64]) -> Vec<DVec3> {
    (0..rows * cols)
        .map(|k| {
            let (i, j) = (k / cols, k % cols);
            DVec3::new(j as f64, i as f64, bumps[k % bumps.len()])
        })
        .collect()
}

fn quad_mesh() -> BoxedStrategy<Value> {
    (
        2usize..5,
        2usize..5,
        prop::collection::vec(-1.0..1.0f64, 1..8),
        any::<bool>(),
        any::<bool>(),
    )
        .prop_map(|(rows, cols, bumps, wrap_rows, wrap_cols)| {
            let grid = QuadGrid::new(rows, cols, grid_vertices(rows, cols, &bumps))
                .expect("a grid of rows × cols vertices");
            Value::from(grid.with_wrap(wrap_rows, wrap_cols))
        })
        .boxed()
}

fn polygon_mesh() -> BoxedStrategy<Value> {
    (
        2usize..4,
        2usize..4,
        prop::collection::vec(-1.0..1.0f64, 1..8),
        any::<bool>(),
    )
        .prop_map(|(rows, cols, bumps, triangles)| {
            let vertices = grid_vertices(rows, cols, &bumps);
            let mut faces: Vec<Vec<u32>> = Vec::new();
            for i in 0..rows - 1 {
                for j in 0..cols - 1 {
                    let v = |i: usize, j: usize| (i * cols + j) as u32;
                    let quad = [v(i, j), v(i, j + 1), v(i + 1, j + 1), v(i + 1, j)];
                    if triangles {
                        faces.push(vec![quad[0], quad[1], quad[2]]);
                        faces.push(vec![quad[0], quad[2], quad[3]]);
                    } else {
                        faces.push(quad.to_vec());
                    }
                }
            }
            Value::from(PolygonMesh::from_faces(vertices, &faces).expect("a valid mesh"))
        })
        .boxed()
}

fn plane() -> BoxedStrategy<Value> {
    let normal = prop_oneof![
        prop::sample::select(vec![
            DVec3::Z,
            DVec3::X,
            -DVec3::Y,
            DVec3::new(1.0, 1.0, 0.0)
        ]),
        point(),
    ];
    (point(), normal)
        .prop_filter_map("a plane needs a normal", |(origin, normal)| {
            Plane::from_normal(origin, normal).ok().map(Value::from)
        })
        .boxed()
}

fn lines() -> BoxedStrategy<Value> {
    prop::collection::vec((point(), point()), 1..4)
        .prop_map(|s| {
            Value::Lines(Arc::new(
                s.into_iter().map(|(a, b)| Line::new(a, b)).collect(),
            ))
        })
        .boxed()
}

/// A scalar an `any` port can get through every door.
fn any_scalar() -> BoxedStrategy<Value> {
    prop_oneof![
        3 => number().prop_map(Value::Number),
        3 => integer().prop_map(Value::Integer),
        1 => any::<bool>().prop_map(Value::Boolean),
        2 => text().prop_map(Value::text),
        1 => Just(Value::Null),
    ]
    .boxed()
}

fn record() -> BoxedStrategy<Value> {
    let field = prop_oneof![
        3 => any_scalar(),
        1 => prop::collection::vec(any_scalar(), 0..4).prop_map(Value::list),
    ];
    prop::collection::vec(("[a-c]{1,2}", field), 0..4)
        .prop_map(|fields| {
            let mut r = Record::new();
            for (name, v) in fields {
                r.set(name, v);
            }
            Value::from(r)
        })
        .boxed()
}

/// One item of an `any` port: what JSON, RON and Python can all say. (A JSON array is a list on
/// an `any` port, so points, vectors, planes and lines are not `any` items here: JSON has no
/// literal of its own for them.)
fn any_item() -> BoxedStrategy<Value> {
    prop_oneof![
        8 => any_scalar(),
        1 => polyline(),
        1 => quad_mesh(),
        1 => polygon_mesh(),
        1 => record(),
    ]
    .boxed()
}

/// A word of a choice port, as a designer may type it (case and surrounding spaces vary). A word
/// that is none of the choices is refused where it is set — by the graph loader, by the node for
/// a wired or JSON value — which `tests/port_hints.rs` of cnets-nodes tests; here every door gets
/// a word it accepts.
fn choice(words: &'static [&'static str]) -> BoxedStrategy<Value> {
    (prop::sample::select(words.to_vec()), 0..3usize)
        .prop_map(|(w, form)| match form {
            0 => Value::text(w),
            1 => Value::text(w.to_uppercase()),
            _ => Value::text(format!(" {w} ")),
        })
        .boxed()
}

/// One item of type `ty`, the port's default among the choices.
fn item(
    ty: &ValueType,
    default: Option<&Value>,
    words: Option<&'static [&'static str]>,
) -> BoxedStrategy<Value> {
    use ValueType as T;
    let fresh = match (ty, words) {
        (T::Text, Some(words)) => choice(words),
        _ => fresh_item(ty),
    };
    match default {
        Some(d) if !matches!(d, Value::List(_) | Value::Null) => {
            prop_oneof![1 => Just(d.clone()), 2 => fresh].boxed()
        }
        _ => fresh,
    }
}

/// One item of type `ty`.
fn fresh_item(ty: &ValueType) -> BoxedStrategy<Value> {
    use ValueType as T;
    match ty {
        T::Any | T::List(_) => any_item(),
        T::Number => number().prop_map(Value::Number).boxed(),
        T::Integer => integer().prop_map(Value::Integer).boxed(),
        T::Boolean => any::<bool>().prop_map(Value::Boolean).boxed(),
        T::Text => text().prop_map(Value::text).boxed(),
        T::Point => point().prop_map(Value::Point).boxed(),
        T::Vector => point().prop_map(Value::Vector).boxed(),
        T::Plane => plane(),
        T::Lines => lines(),
        T::Polyline => polyline(),
        T::QuadMesh => quad_mesh(),
        T::Mesh => prop_oneof![quad_mesh(), polygon_mesh()].boxed(),
        T::Record => record(),
    }
}

/// Lists `depth` deep around items of `item`; `ragged` lets an item or a shallower list stand
/// beside deeper ones.
fn nested(item: BoxedStrategy<Value>, depth: usize, ragged: bool) -> BoxedStrategy<Value> {
    if depth == 0 {
        return item;
    }
    let inner = nested(item.clone(), depth - 1, ragged);
    let child = if ragged {
        prop_oneof![3 => inner, 1 => item].boxed()
    } else {
        inner
    };
    prop::collection::vec(child, 0..4)
        .prop_map(Value::list)
        .boxed()
}

/// A value for a port: its item type nested as deep as the port takes it and one or two levels
/// more (which maps the node over the extra levels).
fn port_value(
    ty: &ValueType,
    access: Access,
    default: Option<&Value>,
    words: Option<&'static [&'static str]>,
) -> BoxedStrategy<Value> {
    let item = item(ty, default, words);
    let deepest = match access {
        Access::Item => 2,
        Access::List => 3,
        Access::Table | Access::Tree => 3,
    };
    let depths: Vec<BoxedStrategy<Value>> = (0..=deepest)
        .flat_map(|d| {
            let uniform = nested(item.clone(), d, false);
            let ragged = (d >= 2).then(|| nested(item.clone(), d, true));
            std::iter::once(uniform).chain(ragged)
        })
        .collect();
    proptest::strategy::Union::new(depths).boxed()
}

/// Inputs for `def`: every required input, each optional or defaulted one three times in four.
fn case(def: &NodeDef) -> BoxedStrategy<Case> {
    let ports: Vec<BoxedStrategy<Option<(usize, Value)>>> = def
        .inputs
        .iter()
        .enumerate()
        .map(|(k, port)| {
            let words = port.choices.map(|c| c.options);
            let value = port_value(&port.ty, port.access, port.default.as_ref(), words)
                .prop_map(move |v| Some((k, v)));
            if port.optional || port.default.is_some() {
                prop_oneof![1 => Just(None), 3 => value].boxed()
            } else {
                value.boxed()
            }
        })
        .collect();
    ports
        .prop_map(|given| Case {
            inputs: given.into_iter().flatten().collect(),
        })
        .boxed()
}

// ------------------------------------------------------------------------------------------------
// The doors

/// The context every door evaluates in (made by a session, as `cnets eval`, `cnets run` and
/// Python make theirs; no folders).
fn context() -> NodeContext {
    cnets_host::Session::new().context(None)
}

fn outcome(result: Result<cnets_engine::eval::NodeOutputs, NodeError>) -> Outcome {
    match result {
        Ok(o) => Outcome::Ran(o.values, o.warnings),
        Err(m) => Outcome::Failed(m),
    }
}

/// The graph file of one node `n` whose inputs are `case`'s, as RON literals.
fn graph_text(def: &NodeDef, case: &Case) -> String {
    let mut text = format!(
        "(\n    version: 1,\n    nodes: {{\n        \"n\": (\n            type: {:?},\n            inputs: {{\n",
        def.id
    );
    for (k, v) in &case.inputs {
        let port = &def.inputs[*k];
        text.push_str(&format!(
            "                {:?}: {},\n",
            port.name,
            literal::encode(v, &port.ty, 4)
        ));
    }
    text.push_str("            },\n        ),\n    },\n    edges: [],\n)\n");
    text
}

/// Door 1: a RON literal in a graph file, loaded and evaluated.
fn ron_door(registry: &Arc<Registry>, def: &NodeDef, case: &Case) -> Outcome {
    let text = graph_text(def, case);
    let doc = match load_str(&text, "three_doors.ron", registry) {
        Ok(doc) => doc,
        Err(e) => return Outcome::Refused(e.to_string()),
    };
    let mut evaluator = Evaluator::new();
    evaluator.evaluate_all(&doc.graph, &context());
    match evaluator.result(&doc.graph, "n") {
        Some(NodeResult::Ok(o)) => Outcome::Ran(o.values.clone(), o.warnings.clone()),
        Some(NodeResult::Failed(e)) => Outcome::Failed(e.clone()),
        other => Outcome::Refused(format!("{other:?}")),
    }
}

/// The `cnets eval` JSON object of `case`'s inputs.
fn json_inputs(def: &NodeDef, case: &Case) -> Json {
    let fields: Map<String, Json> = case
        .inputs
        .iter()
        .map(|(k, v)| (def.inputs[*k].name.to_string(), to_json(v)))
        .collect();
    Json::Object(fields)
}

/// Door 2: `cnets eval` JSON, read and decoded as the CLI (and Python's host code) does.
fn json_door(def: &NodeDef, text: &str) -> Outcome {
    let doc = read_document(text.as_bytes()).expect("the generated JSON reads");
    match cnets_host::inputs::node_inputs(def, doc) {
        Ok(values) => outcome(evaluate_node(def, &context(), &values)),
        Err(e) => Outcome::Refused(e.to_string()),
    }
}

/// The value with every non-empty list of numbers, vectors or texts packed, recursively.
fn packed(v: &Value) -> Value {
    let Value::List(items) = v else {
        return v.clone();
    };
    let items: Vec<Value> = items.iter().map(packed).collect();
    let n = items.len();
    if n > 0 && items.iter().all(|x| matches!(x, Value::Number(_))) {
        let table = items.iter().filter_map(Value::as_f64).collect();
        return Value::List(Items::numbers(Arc::new(table), 0..n));
    }
    if n > 0 && items.iter().all(|x| matches!(x, Value::Vector(_))) {
        let table = items.iter().filter_map(Value::as_vec3).collect();
        return Value::List(Items::vectors(Arc::new(table), 0..n));
    }
    if n > 0 && items.iter().all(|x| matches!(x, Value::Text(_))) {
        let mut labels: Vec<Value> = Vec::new();
        let codes: Option<Vec<u8>> = items
            .iter()
            .map(|x| {
                let k = labels.iter().position(|l| l.same_as(x)).unwrap_or_else(|| {
                    labels.push(x.clone());
                    labels.len() - 1
                });
                u8::try_from(k).ok()
            })
            .collect();
        if let Some(codes) = codes {
            return Value::List(Items::labels(Arc::new(codes), 0..n, labels.into()));
        }
    }
    Value::list(items)
}

/// Door 3 (the engine's own): the values as they are, and packed.
fn value_doors(def: &NodeDef, case: &Case) -> (Outcome, Outcome) {
    let given = |f: &dyn Fn(&Value) -> Value| {
        let mut values = vec![None; def.inputs.len()];
        for (k, v) in &case.inputs {
            values[*k] = Some(f(v));
        }
        cnets_host::complete_inputs(def, values).expect("every required input is given")
    };
    let plain = outcome(evaluate_node(def, &context(), &given(&|v| v.clone())));
    let packed = outcome(evaluate_node(def, &context(), &given(&packed)));
    (plain, packed)
}

/// The `cnets eval` answer as the CLI prints it: the outputs object and the warnings (as stderr
/// and Python's `CnetsWarning`s say them: `<type>: <warning>`), or the failure.
fn answer(def: &NodeDef, outcome: &Outcome) -> Json {
    match outcome {
        Outcome::Ran(values, warnings) => {
            let outputs: Map<String, Json> = def
                .outputs
                .iter()
                .zip(values)
                .map(|(p, v)| (p.name.to_string(), to_json(v)))
                .collect();
            let warnings: Vec<String> = warnings
                .iter()
                .map(|w| format!("{}: {w}", def.id))
                .collect();
            json!({ "outputs": outputs, "warnings": warnings })
        }
        Outcome::Failed(m) => json!({ "error": format!("{}: {m}", def.id) }),
        Outcome::Refused(m) => json!({ "refused": m }),
    }
}

/// Runs `cnets eval` on the inputs and checks it prints `expected`.
fn check_cli(def: &NodeDef, inputs: &str, expected: &Json, dir: &std::path::Path) {
    let file = dir.join("inputs.json");
    std::fs::write(&file, inputs).expect("the inputs are written");
    let out = Command::new(env!("CARGO_BIN_EXE_cnets"))
        .args(["eval", &def.id, "--inputs"])
        .arg(&file)
        .current_dir(dir)
        .output()
        .expect("cnets runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    if let Some(outputs) = expected.get("outputs") {
        assert!(out.status.success(), "{}: {inputs}: {stderr}", def.id);
        let printed: Json = serde_json::from_str(&stdout).expect("cnets eval prints JSON");
        assert_eq!(&printed, outputs, "{}: {inputs}", def.id);
        assert_eq!(
            stdout.trim_end(),
            outputs.to_string(),
            "{}: {inputs}",
            def.id
        );
        // The warnings, one `warning: ` line each on stderr.
        let said: Vec<Json> = stderr
            .lines()
            .filter_map(|l| l.strip_prefix("warning: "))
            .map(Json::from)
            .collect();
        let expected = expected.get("warnings").cloned().unwrap_or(json!([]));
        assert_eq!(Json::from(said), expected, "{}: {inputs}: warnings", def.id);
    } else if let Some(error) = expected.get("error").and_then(Json::as_str) {
        assert_eq!(out.status.code(), Some(1), "{}: {inputs}: {stdout}", def.id);
        assert!(
            stderr.contains(error),
            "{}: {inputs}: expected {error:?} in {stderr:?}",
            def.id
        );
    } else {
        assert_eq!(out.status.code(), Some(2), "{}: {inputs}: {stdout}", def.id);
    }
}

// ------------------------------------------------------------------------------------------------

fn cases_per_node() -> u32 {
    std::env::var("THREE_DOORS_CASES")
        .ok()
        .and_then(|n| n.parse().ok())
        .unwrap_or(24)
}

#[test]
fn every_node_type_gives_one_answer_through_every_door() {
    let registry = Arc::new(cnets_nodes::registry());
    let skipped: BTreeSet<&str> = SKIPPED.iter().map(|(id, _)| *id).collect();
    // Exactly the file readers and writers are skipped: a new node type is tested unless it is
    // one of them (then it is listed above with its reason).
    let io: BTreeSet<&str> = registry
        .iter()
        .filter(|d| d.has_flag(NodeFlag::Import) || d.has_flag(NodeFlag::Export))
        .map(|d| d.id.as_ref())
        .chain(["cluster"])
        .collect();
    assert_eq!(
        skipped, io,
        "SKIPPED lists exactly the nodes that touch files"
    );

    let folder = common::Folder::new("three-doors");
    let python_cases: RefCell<Vec<Json>> = RefCell::new(Vec::new());
    let mut tested = 0;
    let mut ran = 0usize;
    let mut defs: Vec<&Arc<NodeDef>> = registry.iter().collect();
    defs.sort_by(|a, b| a.id.cmp(&b.id));
    for def in defs {
        if skipped.contains(def.id.as_ref()) {
            continue;
        }
        tested += 1;
        let mut runner = TestRunner::new(Config {
            cases: cases_per_node(),
            failure_persistence: None,
            ..Config::default()
        });
        let seen = Cell::new(0usize);
        let result = runner.run(&case(def), |case| {
            let (plain, packed) = value_doors(def, &case);
            let ron = ron_door(&registry, def, &case);
            let inputs = json_inputs(def, &case).to_string();
            let json = json_door(def, &inputs);
            let shown = || format!("{}\nRON:\n{}\nJSON: {inputs}", def.id, graph_text(def, &case));
            prop_assert!(
                packed.same_as(&plain),
                "packed rows changed the answer of {}\nplain: {plain:?}\npacked: {packed:?}",
                shown()
            );
            prop_assert!(
                ron.same_as(&plain),
                "the graph file's answer differs from the values' for {}\nRON: {ron:?}\nvalues: {plain:?}",
                shown()
            );
            prop_assert!(
                json.same_as(&plain),
                "the JSON answer differs from the values' for {}\nJSON: {json:?}\nvalues: {plain:?}",
                shown()
            );
            if seen.get() < CLI_CASES {
                check_cli(def, &inputs, &answer(def, &json), &folder);
            }
            if seen.get() < PYTHON_CASES {
                let types: Map<String, Json> = def
                    .inputs
                    .iter()
                    .map(|p| (p.name.to_string(), Json::from(p.type_name())))
                    .collect();
                let mut entry = json!({
                    "node": def.id,
                    "types": types,
                    "inputs": serde_json::from_str::<Json>(&inputs).map_err(|e| TestCaseError::fail(e.to_string()))?,
                });
                if let (Json::Object(e), Json::Object(a)) = (&mut entry, answer(def, &json)) {
                    e.extend(a);
                }
                python_cases.borrow_mut().push(entry);
            }
            seen.set(seen.get() + 1);
            Ok(())
        });
        if let Err(e) = result {
            panic!("{e}");
        }
        ran += seen.get();
    }
    assert!(tested > 100, "only {tested} node types were tested");
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("three_doors_cases.json");
    let python_cases = python_cases.into_inner();
    let text = serde_json::to_string(&python_cases).expect("the cases serialize");
    std::fs::write(&path, text).expect("the Python cases are written");
    eprintln!(
        "three doors: {tested} node types, {ran} cases, {} written to {}",
        python_cases.len(),
        path.display()
    );
}

/// The five calls of issue 27 §1, through the `cnets` binary, answer as a graph file does.
#[test]
fn the_issue_calls_answer_as_a_graph_file_does() {
    let cases = [
        (
            "list.cross_reference",
            r#"{"a": [1, 2], "b": [10, 20, 30]}"#,
            r#"{"a":[1,1,1,2,2,2],"b":[10,20,30,10,20,30]}"#,
        ),
        (
            "list.flatten",
            r#"{"tree": [[1,2,3],[10,20,30]]}"#,
            r#"{"list":[1,2,3,10,20,30]}"#,
        ),
        (
            "list.transpose",
            r#"{"table": [[1,2,3],[10,20,30]]}"#,
            r#"{"table":[[1,10],[2,20],[3,30]]}"#,
        ),
        (
            "list.weave",
            r#"{"lists": [[1,2,3],[10,20,30]], "pattern": [0,1]}"#,
            r#"{"list":[1,10,2,20,3,30]}"#,
        ),
        (
            "view.panel",
            r#"{"value": [[1,2,3],[10,20,30]]}"#,
            r#"{"text":"{0}\n0  1\n1  2\n2  3\n{1}\n0  10\n1  20\n2  30"}"#,
        ),
    ];
    let folder = common::Folder::new("three-doors-issue");
    let registry = Arc::new(cnets_nodes::registry());
    for (node, inputs, expected) in cases {
        let def = registry.get(node).expect("registered");
        let expected: Json = serde_json::from_str(expected).unwrap();
        check_cli(def, inputs, &json!({ "outputs": expected }), &folder);
        // The same inputs written as RON in a graph file give the same values.
        let doc = read_document(inputs.as_bytes()).unwrap();
        let values = cnets_host::inputs::node_inputs(def, doc).unwrap();
        let case = Case {
            inputs: values
                .into_iter()
                .enumerate()
                .filter(|(k, _)| {
                    let name = &def.inputs[*k].name;
                    inputs.contains(&format!("\"{name}\""))
                })
                .collect(),
        };
        let ron = ron_door(&registry, def, &case);
        assert!(
            ron.same_as(&json_door(def, inputs)),
            "{node}: {ron:?}\n{}",
            graph_text(def, &case)
        );
    }
}
