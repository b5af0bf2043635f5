//! A graph mapper's curve type and handles live in the graph file as plain node inputs: they load,
//! save and load again unchanged, and the mapper evaluates from them (so an editor can show and
//! drag them).

use std::sync::Arc;

use cnets_engine::file::{load_str, to_ron};
use cnets_engine::{Evaluator, NodeContext, Value};

const GRAPH: &str = r#"(
    version: 1,
    nodes: {
        "shape": (
            type: "mapper.graph",
            position: (0.0, 0.0),
            inputs: {
                "kind": "bezier",
                "handles": [(0.0, 0.2, 0.0), (0.3, 0.9, 0.0), (0.7, 0.1, 0.0), (1.0, 0.8, 0.0)],
                "x_start": 0.0,
                "x_end": 4.0,
                "count": 5,
            },
        ),
    },
    edges: [],
)"#;

#[test]
fn kind_and_handles_round_trip_through_the_file_and_drive_the_mapper() {
    let registry = Arc::new(cnets_nodes::registry());
    let doc = load_str(GRAPH, "mapper.ron", &registry).unwrap_or_else(|e| panic!("{e:?}"));
    let saved = to_ron(&doc.graph, &doc.meta);
    assert!(saved.contains("\"bezier\""), "{saved}");
    let again = load_str(&saved, "again.ron", &registry).unwrap();
    assert_eq!(to_ron(&again.graph, &again.meta), saved);
    let node = again.graph.node("shape").unwrap();
    let handles = node.value_of("handles").unwrap().as_list().unwrap();
    assert_eq!(handles.len(), 4);

    let mut ev = Evaluator::new();
    ev.evaluate_all(&again.graph, &NodeContext::default());
    let y = ev
        .output(&again.graph, "shape", "y")
        .unwrap()
        .as_list()
        .unwrap();
    let x = ev
        .output(&again.graph, "shape", "x")
        .unwrap()
        .as_list()
        .unwrap();
    assert_eq!(y.len(), 5);
    assert_eq!(x[4], Value::Number(4.0));
    // The bezier passes through its end handles.
    assert!((y[0].as_f64().unwrap() - 0.2).abs() < 1e-12);
    assert!((y[4].as_f64().unwrap() - 0.8).abs() < 1e-12);
}
