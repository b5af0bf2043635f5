//! Load → save → load round-trips exactly; saves are atomic.

use crate::common;

use cnets_engine::file::{GraphMeta, load_str, save_file, to_ron};
use cnets_engine::{Evaluator, NodeContext, Value};

const SAMPLE: &str = r##"(
    version: 1,
    name: "sample",
    description: "A small graph with every kind of literal.",
    nodes: {
        "x": (
            type: "t.num",
            position: (10.0, -20.5),
            inputs: {
                "value": 2.5,
            },
        ),
        "series": (
            type: "t.series",
            position: (0.0, 100.0),
            preview: false,
            inputs: {
                "n": 4,
            },
        ),
        "sum": (
            type: "t.sum",
            position: (200.0, 100.0),
            color: "#d62f2f",
        ),
        "add": (
            type: "t.add",
            position: (200.0, 0.0),
            enabled: false,
            inputs: {
                "b": [1.0, 2.0, 0.1],
            },
        ),
        "poly": (
            type: "t.poly",
            position: (0.0, 0.0),
            inputs: {
                "curve": (points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 1.0, 0.0)], closed: true),
            },
        ),
        "label": (
            type: "t.text",
            position: (0.0, 0.0),
            inputs: {
                "value": "a \"quoted\" name\nwith a newline",
            },
        ),
    },
    edges: [
        "x.out -> add.a",
        "series.out -> sum.xs",
    ],
)
"##;

#[test]
fn canonical_files_save_byte_for_byte() {
    let doc = load_str(SAMPLE, "sample.ron", &common::registry()).unwrap();
    assert_eq!(to_ron(&doc.graph, &doc.meta), SAMPLE);
}

#[test]
fn a_node_colour_is_kept_optional_and_checked() {
    let doc = load_str(SAMPLE, "sample.ron", &common::registry()).unwrap();
    assert_eq!(
        doc.graph.node("sum").unwrap().color,
        Some([0xd6, 0x2f, 0x2f])
    );
    // Files without a colour load as before: no colour, none written.
    assert_eq!(doc.graph.node("x").unwrap().color, None);
    let plain = SAMPLE.replace("            color: \"#d62f2f\",\n", "");
    let doc = load_str(&plain, "plain.ron", &common::registry()).unwrap();
    assert!(doc.graph.nodes().all(|(_, n)| n.color.is_none()));
    assert_eq!(to_ron(&doc.graph, &doc.meta), plain);
    // A bad colour is a diagnostic at its place.
    let bad = SAMPLE.replace("#d62f2f", "red");
    let err = load_str(&bad, "bad.ron", &common::registry()).unwrap_err();
    let text = err.to_string();
    assert!(
        text.contains("'color' must be a colour") && text.contains("bad.ron:"),
        "{text}"
    );
    assert_eq!(
        cnets_engine::file::parse_color("#0A0b0c"),
        Some([10, 11, 12])
    );
    assert_eq!(cnets_engine::file::format_color([10, 11, 12]), "#0a0b0c");
    assert_eq!(cnets_engine::file::parse_color("#0a0b0"), None);
}

#[test]
fn saved_files_are_standard_ron() {
    let doc = load_str(SAMPLE, "sample.ron", &common::registry()).unwrap();
    let text = to_ron(&doc.graph, &doc.meta);
    let parsed: Result<ron::Value, _> = ron::from_str(&text);
    assert!(
        parsed.is_ok(),
        "the ron crate rejects our output: {parsed:?}"
    );
}

#[test]
fn load_save_load_gives_the_same_graph() {
    let registry = common::registry();
    let mut doc = load_str(SAMPLE, "sample.ron", &registry).unwrap();
    doc.graph
        .set_value("x", "value", Value::Number(0.1 + 0.2))
        .unwrap();
    doc.graph
        .set_value("add", "a", Value::Number(f64::NAN))
        .unwrap();
    let text = to_ron(&doc.graph, &doc.meta);
    let again = load_str(&text, "again.ron", &registry).unwrap();
    assert_eq!(to_ron(&again.graph, &again.meta), text);
    assert_eq!(
        again.graph.node("x").unwrap().value_of("value"),
        Some(&Value::Number(0.1 + 0.2))
    );
    assert_eq!(again.graph.wires(), doc.graph.wires());
    assert!(!again.graph.node("series").unwrap().preview);
    assert!(!again.graph.node("add").unwrap().enabled);
    assert_eq!(again.graph.node("x").unwrap().position, [10.0, -20.5]);
    let mut ev = Evaluator::new();
    ev.evaluate_all(&again.graph, &NodeContext::default());
    assert_eq!(
        ev.output(&again.graph, "sum", "total"),
        Some(&Value::Number(6.0))
    );
    assert_eq!(
        ev.output(&again.graph, "poly", "count"),
        Some(&Value::Integer(3))
    );
}

#[test]
fn saving_is_atomic_and_replaces_the_file() {
    let registry = common::registry();
    let doc = load_str(SAMPLE, "sample.ron", &registry).unwrap();
    let dir = std::env::temp_dir().join(format!("cnets-save-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("g.ron");
    std::fs::write(&path, "old contents").unwrap();
    save_file(&path, &doc.graph, &GraphMeta::default()).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.starts_with("(\n    version: 1,\n    nodes: {"));
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        1,
        "no temporary file left"
    );
    // A save into a missing directory fails and writes nothing.
    assert!(
        save_file(
            &dir.join("missing/g.ron"),
            &doc.graph,
            &GraphMeta::default()
        )
        .is_err()
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
