//! Clusters: graphs used as nodes. They evaluate like the inlined nodes, incrementally inside, with
//! separate caches per instance; bad includes give clear, located errors.

use crate::common;

use std::path::{Path, PathBuf};

use cnets_engine::cluster::{Cluster, explode, make_cluster};
use cnets_engine::file::{load_file, load_str, to_ron};
use cnets_engine::{Evaluator, Graph, NodeContext, Value};

const SUB: &str = r#"(
    version: 1,
    name: "double and sign",
    nodes: {
        "x": (type: "graph.input", inputs: {"name": "x", "type": "number", "default": 1.0}),
        "k": (type: "graph.input", inputs: {"name": "k", "type": "number", "default": 10.0}),
        "twice": (type: "t.add"),
        "plus_k": (type: "t.add"),
        "sign": (type: "t.sign"),
        "sum": (type: "graph.output", inputs: {"name": "sum", "type": "number"}),
        "s": (type: "graph.output", inputs: {"name": "sign", "type": "number"}),
    },
    edges: [
        "x.value -> twice.a", "x.value -> twice.b",
        "twice.sum -> plus_k.a", "k.value -> plus_k.b",
        "x.value -> sign.x",
        "plus_k.sum -> sum.value", "sign.out -> s.value",
    ],
)"#;

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("cnets-clusters-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

const MAIN: &str = r#"(
    version: 1,
    nodes: {
        "v": (type: "t.num", inputs: {"value": 3.0}),
        "c1": (type: "cluster", source: "sub.ron"),
        "c2": (type: "cluster", source: "sub.ron", inputs: {"k": 100.0}),
        "after": (type: "t.add"),
    },
    edges: ["v.out -> c1.x", "v.out -> c2.x", "c1.sum -> after.a", "c2.sign -> after.b"],
)"#;

fn load(dir: &Path) -> Graph {
    write(dir, "sub.ron", SUB);
    let main = write(dir, "main.ron", MAIN);
    load_file(&main, &common::registry())
        .unwrap_or_else(|e| panic!("{e}"))
        .graph
}

#[test]
fn a_cluster_evaluates_like_its_nodes_and_exposes_their_ports() {
    let g = load(&dir("eval"));
    let def = &g.node("c1").unwrap().def;
    assert_eq!(def.id, "cluster");
    assert_eq!(def.input_names(), "x, k");
    assert_eq!(def.output_names(), "sum, sign");
    assert!(def.doc.contains("double and sign"));
    let mut ev = Evaluator::new();
    ev.evaluate_all(&g, &NodeContext::default());
    assert_eq!(
        ev.output(&g, "c1", "sum"),
        Some(&Value::Number(16.0)),
        "3 + 3 + 10"
    );
    assert_eq!(
        ev.output(&g, "c2", "sum"),
        Some(&Value::Number(106.0)),
        "k literal on the instance"
    );
    assert_eq!(ev.output(&g, "after", "sum"), Some(&Value::Number(17.0)));
}

#[test]
fn evaluation_inside_is_incremental_and_instances_cache_separately() {
    let mut g = load(&dir("incremental"));
    let mut ev = Evaluator::new();
    let ctx = NodeContext::default();
    ev.evaluate_all(&g, &ctx);
    let c1 = Cluster::shared(&g.node("c1").unwrap().def).unwrap();
    let c2 = Cluster::shared(&g.node("c2").unwrap().def).unwrap();
    assert!(
        !std::sync::Arc::ptr_eq(&c1, &c2),
        "two instances, two caches"
    );
    assert_eq!(c1.inner_node_runs("twice"), 1);
    assert_eq!(c2.inner_node_runs("twice"), 1);

    // Changing k on c1 re-runs only plus_k inside c1 (twice and sign do not depend on k).
    g.set_value("c1", "k", Value::Number(20.0)).unwrap();
    ev.evaluate_all(&g, &ctx);
    assert_eq!(ev.output(&g, "c1", "sum"), Some(&Value::Number(26.0)));
    assert_eq!(c1.inner_node_runs("plus_k"), 2);
    assert_eq!(c1.inner_node_runs("twice"), 1);
    assert_eq!(c1.inner_node_runs("sign"), 1);
    assert_eq!(
        c2.inner_node_runs("plus_k"),
        1,
        "the other instance did not run"
    );

    // Changing v to another positive number: sign re-runs, its output is unchanged (early cutoff
    // inside), twice and plus_k re-run.
    g.set_value("v", "value", Value::Number(5.0)).unwrap();
    ev.evaluate_all(&g, &ctx);
    assert_eq!(c1.inner_node_runs("sign"), 2);
    assert_eq!(c1.inner_node_runs("twice"), 2);
    assert_eq!(ev.output(&g, "after", "sum"), Some(&Value::Number(31.0)));
}

#[test]
fn missing_files_recursion_renamed_ports_and_type_mismatches_are_clear_errors() {
    let d = dir("errors");
    let missing = write(
        &d,
        "missing.ron",
        "(version: 1, nodes: {\"c\": (type: \"cluster\", source: \"nope.ron\")})",
    );
    let e = load_file(&missing, &common::registry())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("missing.ron:1:53: node 'c': cluster source 'nope.ron' not found"),
        "{e}"
    );

    write(
        &d,
        "a.ron",
        "(version: 1, nodes: {\"b\": (type: \"cluster\", source: \"b.ron\")})",
    );
    write(
        &d,
        "b.ron",
        "(version: 1, nodes: {\"a\": (type: \"cluster\", source: \"a.ron\")})",
    );
    let e = load_file(&d.join("a.ron"), &common::registry())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("recursive cluster: a.ron -> b.ron -> a.ron"),
        "{e}"
    );

    write(
        &d,
        "sub.ron",
        &SUB.replace("\"name\": \"k\"", "\"name\": \"scale\""),
    );
    let main = write(&d, "main.ron", MAIN);
    let e = load_file(&main, &common::registry())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("node 'c2' (cluster) has no input 'k'; its inputs are: x, scale"),
        "{e}"
    );

    write(&d, "sub.ron", SUB);
    let text = write(
        &d,
        "typed.ron",
        r#"(version: 1, nodes: {
        "c": (type: "cluster", source: "sub.ron"), "t": (type: "t.text")},
        edges: ["t.out -> c.x"])"#,
    );
    let e = load_file(&text, &common::registry())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("type mismatch: t.out gives text but c.x takes number"),
        "{e}"
    );

    let bad_type = write(
        &d,
        "bad_type.ron",
        r#"(version: 1, nodes: {"i": (type: "graph.input", inputs: {"type": "nmber"})})"#,
    );
    let using = write(
        &d,
        "using.ron",
        r#"(version: 1, nodes: {"c": (type: "cluster", source: "bad_type.ron")})"#,
    );
    let _ = bad_type;
    let e = load_file(&using, &common::registry())
        .unwrap_err()
        .to_string();
    assert!(e.contains("unknown port type 'nmber'"), "{e}");
}

#[test]
fn inner_failures_name_the_inner_node() {
    let d = dir("inner-failure");
    write(
        &d,
        "sub.ron",
        r#"(version: 1, nodes: {
        "x": (type: "graph.input", inputs: {"name": "x", "type": "number"}),
        "check": (type: "t.check"),
        "o": (type: "graph.output", inputs: {"name": "out", "type": "number"})},
        edges: ["x.value -> check.x", "check.out -> o.value"])"#,
    );
    let main = write(
        &d,
        "main.ron",
        r#"(version: 1, nodes: {"c": (type: "cluster", source: "sub.ron", inputs: {"x": -4.0})})"#,
    );
    let g = load_file(&main, &common::registry()).unwrap().graph;
    let mut ev = Evaluator::new();
    ev.evaluate_all(&g, &NodeContext::default());
    let e = ev.result(&g, "c").unwrap().error().unwrap().to_string();
    assert_eq!(
        e,
        "inside cluster 'sub.ron': node 'check' (t.check) failed: x = -4 is negative"
    );
}

fn semantic(graph: &Graph) -> (Vec<String>, Vec<String>) {
    let mut nodes: Vec<String> = graph
        .nodes()
        .map(|(_, n)| {
            let values: Vec<String> = n
                .def
                .inputs
                .iter()
                .enumerate()
                .filter_map(|(k, p)| Some(format!("{}={:?}", p.name, n.value(k)?)))
                .collect();
            format!(
                "{} {} {} {} {}",
                n.id,
                n.def.id,
                n.preview,
                n.enabled,
                values.join(",")
            )
        })
        .collect();
    nodes.sort();
    let mut wires: Vec<String> = graph.wires().iter().map(ToString::to_string).collect();
    wires.sort();
    (nodes, wires)
}

#[test]
fn make_cluster_save_load_explode_round_trips() {
    let text = r#"(version: 1, nodes: {
        "x": (type: "t.num", inputs: {"value": 2.0}),
        "a": (type: "t.add", inputs: {"b": 1.5}),
        "b": (type: "t.add", preview: false),
        "s": (type: "t.sign"),
        "z": (type: "t.add"),
    }, edges: ["x.out -> a.a", "a.sum -> b.a", "x.out -> b.b", "b.sum -> s.x", "b.sum -> z.a", "a.sum -> z.b"])"#;
    let registry = common::registry();
    let original = load_str(text, "g.ron", &registry).unwrap();
    let mut ev = Evaluator::new();
    ev.evaluate_all(&original.graph, &NodeContext::default());
    let expected = (
        ev.output(&original.graph, "s", "out").cloned(),
        ev.output(&original.graph, "z", "sum").cloned(),
    );

    let mut g = original.graph.clone();
    let cluster = make_cluster(&mut g, &["a", "b"], "ab").unwrap();
    assert_eq!(g.node("ab").unwrap().def.input_names(), "a");
    assert_eq!(g.node("ab").unwrap().def.output_names(), "sum, sum_2");
    assert_eq!(
        cluster.interface.inputs.len(),
        1,
        "one input per outside source (x.out feeds a.a and b.b)"
    );

    // The clustered graph computes the same values, bit for bit.
    let mut ev2 = Evaluator::new();
    ev2.evaluate_all(&g, &NodeContext::default());
    assert_eq!(
        (
            ev2.output(&g, "s", "out").cloned(),
            ev2.output(&g, "z", "sum").cloned()
        ),
        expected
    );

    // Save with the inline cluster, load, save again: identical text.
    let saved = to_ron(&g, &original.meta);
    assert!(
        saved.contains("type: \"cluster\",\n            graph: ("),
        "{saved}"
    );
    let loaded =
        load_str(&saved, "saved.ron", &registry).unwrap_or_else(|e| panic!("{e}\n{saved}"));
    assert_eq!(to_ron(&loaded.graph, &loaded.meta), saved);

    let mut back = loaded.graph;
    let added = explode(&mut back, "ab").unwrap();
    assert_eq!(added, vec!["a", "b"]);
    assert_eq!(semantic(&back), semantic(&original.graph));
}

#[test]
fn cluster_ports_are_named_after_what_they_carry() {
    // Two number sources feeding an adder: their outputs are both `out`, which says nothing; the
    // cluster's outputs take the names of the inputs they feed (`a`, `b`), and an input fed
    // into an inner `value` takes the feeding node's output or id.
    let text = r#"(version: 1, nodes: {
        "width": (type: "t.num", inputs: {"value": 2.0}),
        "height": (type: "t.num", inputs: {"value": 3.0}),
        "src": (type: "t.add"),
        "fed": (type: "t.num"),
        "add": (type: "t.add"),
    }, edges: ["width.out -> add.a", "height.out -> add.b", "src.sum -> fed.value"])"#;
    let registry = common::registry();
    let mut g = load_str(text, "g.ron", &registry).unwrap().graph;
    make_cluster(&mut g, &["width", "height"], "sizes").unwrap();
    assert_eq!(g.node("sizes").unwrap().def.output_names(), "a, b");
    make_cluster(&mut g, &["fed"], "inner").unwrap();
    assert_eq!(g.node("inner").unwrap().def.input_names(), "sum");
}

#[test]
fn a_cluster_source_loads_as_a_node_of_a_graph_would() {
    use cnets_engine::file::{LoadOptions, load_cluster_source};
    let d = dir("source");
    let lib = d.join("lib");
    std::fs::create_dir_all(&lib).unwrap();
    write(&lib, "sub.ron", SUB);
    write(
        &lib,
        "broken.ron",
        "(version: 1, nodes: {\"n\": (type: \"t.nope\")}, edges: [])",
    );
    let registry = common::registry();
    // An untitled document: no folder of its own, the library folder searched.
    let mut options = LoadOptions::for_file(&d.join("untitled.ron")).with_library(&lib);
    options.base_dir = None;
    let cluster = load_cluster_source("sub", &registry, &options).unwrap_or_else(|e| panic!("{e}"));
    assert!(matches!(
        &cluster.source,
        cnets_engine::cluster::ClusterSource::File { written, resolved }
            if written == "sub" && resolved.ends_with("lib/sub.ron")
    ));
    assert_eq!(cluster.interface.inputs.len(), 2);
    // Not found: one diagnostic of no file, shown as its message alone, listing where it looked.
    let e = load_cluster_source("nope.ron", &registry, &options).unwrap_err();
    assert_eq!(e.diagnostics.len(), 1, "{e}");
    let shown = e.to_string();
    assert!(
        shown.starts_with("cluster source 'nope.ron' not found (looked for: "),
        "{shown}"
    );
    assert!(shown.contains("nope.ron"), "{shown}");
    // Errors inside the file: the source has errors, and the file's own diagnostic is located.
    let e = load_cluster_source("broken.ron", &registry, &options).unwrap_err();
    let shown = e.to_string();
    assert!(
        shown.starts_with("cluster source 'broken.ron' has errors\n"),
        "{shown}"
    );
    assert!(shown.contains("broken.ron:1:"), "{shown}");
    std::fs::remove_dir_all(&d).unwrap();
}
