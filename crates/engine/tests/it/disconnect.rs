//! Dropping every wire of one port: `Graph::disconnect_input` and `Graph::disconnect_output`.

use crate::common;

use cnets_engine::GraphError;

/// `head` feeds both inputs of `n0` and the `a` of `n1`; `n0` also feeds `n1.b`.
fn fan() -> cnets_engine::Graph {
    let mut g = common::graph();
    g.add_node("head", "t.num").unwrap();
    g.add_node("n0", "t.add").unwrap();
    g.add_node("n1", "t.add").unwrap();
    g.connect("head", "out", "n0", "a").unwrap();
    g.connect("head", "out", "n0", "b").unwrap();
    g.connect("head", "out", "n1", "a").unwrap();
    g.connect("n0", "sum", "n1", "b").unwrap();
    g
}

fn wires(g: &cnets_engine::Graph) -> Vec<String> {
    g.wires()
        .into_iter()
        .map(|w| format!("{}.{}->{}.{}", w.from, w.output, w.to, w.input))
        .collect()
}

#[test]
fn an_input_loses_only_its_own_wires() {
    let mut g = fan();
    let before = g.node("n0").unwrap().edited_at();
    assert_eq!(g.disconnect_input("n0", "a").unwrap(), 1);
    assert_eq!(
        wires(&g),
        ["head.out->n0.b", "head.out->n1.a", "n0.sum->n1.b"]
    );
    assert!(
        g.node("n0").unwrap().edited_at() > before,
        "the target re-runs"
    );
    let revision = g.revision();
    assert_eq!(g.disconnect_input("n0", "a").unwrap(), 0);
    assert_eq!(g.revision(), revision, "nothing to drop is not an edit");
}

#[test]
fn an_output_loses_every_wire_it_feeds() {
    let mut g = fan();
    let (r0, r1) = (
        g.node("n0").unwrap().edited_at(),
        g.node("n1").unwrap().edited_at(),
    );
    assert_eq!(g.disconnect_output("head", "out").unwrap(), 3);
    assert_eq!(wires(&g), ["n0.sum->n1.b"]);
    assert!(g.node("n0").unwrap().edited_at() > r0);
    assert!(g.node("n1").unwrap().edited_at() > r1);
}

#[test]
fn unknown_nodes_and_ports_are_errors() {
    let mut g = fan();
    assert!(matches!(
        g.disconnect_input("nope", "a"),
        Err(GraphError::UnknownNode(_))
    ));
    assert!(matches!(
        g.disconnect_input("n0", "zz"),
        Err(GraphError::UnknownInput { .. })
    ));
    assert!(matches!(
        g.disconnect_output("n0", "zz"),
        Err(GraphError::UnknownOutput { .. })
    ));
    assert_eq!(g.wire_count(), 4, "the graph is unchanged");
}
