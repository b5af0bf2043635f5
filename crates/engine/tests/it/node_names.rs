//! Node display names: a name given to a node is saved with the graph and loaded back, an old
//! file without names loads and saves unchanged, and a name is not an edit for evaluation.

use crate::common;

use cnets_engine::file::{load_str, to_ron};
use cnets_engine::{Evaluator, NodeContext};

const NAMED: &str = r#"(
    version: 1,
    name: "named",
    description: "",
    nodes: {
        "x": (
            type: "t.num",
            name: "Span \"A\" (m)",
            position: (0.0, 0.0),
            inputs: {
                "value": 2.5,
            },
        ),
        "y": (
            type: "t.num",
            position: (0.0, 100.0),
        ),
    },
    edges: [
    ],
)
"#;

#[test]
fn a_name_is_saved_with_the_graph_and_loaded_back() {
    let doc = load_str(NAMED, "named.ron", &common::registry()).unwrap();
    let x = doc.graph.node("x").unwrap();
    assert_eq!(x.name.as_deref(), Some("Span \"A\" (m)"));
    assert_eq!(x.label(), "Span \"A\" (m)");
    assert_eq!(doc.graph.node("y").unwrap().label(), "y");
    assert_eq!(
        to_ron(&doc.graph, &doc.meta),
        NAMED,
        "saved exactly as written"
    );
}

#[test]
fn an_old_file_loads_unchanged_and_a_bad_name_is_a_diagnostic() {
    let old = NAMED.replace("            name: \"Span \\\"A\\\" (m)\",\n", "");
    assert!(!old.contains("name: \"Span"));
    let doc = load_str(&old, "old.ron", &common::registry()).unwrap();
    assert!(doc.graph.nodes().all(|(_, n)| n.name.is_none()));
    assert_eq!(to_ron(&doc.graph, &doc.meta), old);
    let bad = NAMED.replace("name: \"Span \\\"A\\\" (m)\"", "name: 3");
    let e = load_str(&bad, "bad.ron", &common::registry()).unwrap_err();
    assert!(e.to_string().contains("'name' must be a string"), "{e}");
}

#[test]
fn naming_a_node_is_not_an_edit_for_evaluation() {
    let mut doc = load_str(NAMED, "named.ron", &common::registry()).unwrap();
    let g = &mut doc.graph;
    let ctx = NodeContext::default();
    let mut ev = Evaluator::new();
    let all: Vec<_> = g.nodes().map(|(i, _)| i).collect();
    ev.evaluate(g, &all, &ctx, &mut |_, _| {});
    let revision = g.revision();
    g.set_name("y", Some("  Depth  ".into())).unwrap();
    assert_eq!(
        g.node("y").unwrap().name.as_deref(),
        Some("Depth"),
        "trimmed"
    );
    assert_eq!(g.revision(), revision);
    let again = ev.evaluate(g, &all, &ctx, &mut |_, _| {});
    assert_eq!(again.ran, 0, "nothing re-runs for a name");
    g.set_name("y", Some("   ".into())).unwrap();
    assert_eq!(
        g.node("y").unwrap().label(),
        "y",
        "a blank name shows the id again"
    );
    assert!(g.set_name("missing", Some("z".into())).is_err());
}
