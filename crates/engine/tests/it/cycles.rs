//! Connections are validated: cycles, unknown ports and type mismatches are refused.

use crate::common;

use cnets_engine::GraphError;

#[test]
fn cycles_are_rejected_with_the_path() {
    let mut g = common::chain(3);
    let e = g.connect("n2", "sum", "n0", "b").unwrap_err();
    match &e {
        GraphError::Cycle { path, .. } => assert_eq!(path, "n0 -> n1 -> n2 -> n0"),
        other => panic!("{other:?}"),
    }
    assert!(e.to_string().contains("would create a cycle"));
    assert!(matches!(
        g.connect("n0", "sum", "n0", "b"),
        Err(GraphError::Cycle { .. })
    ));
    assert_eq!(g.wire_count(), 3, "the graph is unchanged");
}

#[test]
fn type_mismatches_and_unknown_ports_are_rejected() {
    let mut g = common::graph();
    g.add_node("t", "t.text").unwrap();
    g.add_node("s", "t.sign").unwrap();
    let e = g.connect("t", "out", "s", "x").unwrap_err();
    assert_eq!(
        e.to_string(),
        "type mismatch: t.out gives text but s.x takes number"
    );
    let e = g.connect("t", "nope", "s", "x").unwrap_err();
    assert!(
        e.to_string()
            .contains("has no output 'nope'; its outputs are: out"),
        "{e}"
    );
    let e = g.connect("t", "out", "s", "y").unwrap_err();
    assert!(e.to_string().contains("its inputs are: x"), "{e}");
    let e = g.add_node("z", "t.sgn").unwrap_err();
    assert_eq!(
        e.to_string(),
        "unknown node type 't.sgn' (did you mean 't.sign'?)"
    );
    assert!(matches!(
        g.add_node("t", "t.num"),
        Err(GraphError::DuplicateId(_))
    ));
    assert!(matches!(
        g.add_node("a.b", "t.num"),
        Err(GraphError::InvalidId(_))
    ));
}

#[test]
fn implicit_conversions_are_allowed() {
    let mut g = common::graph();
    g.add_node("series", "t.series").unwrap();
    g.add_node("sum", "t.sum").unwrap();
    g.connect("series", "out", "sum", "xs").unwrap();
    g.add_node("add", "t.add").unwrap();
    g.connect("sum", "count", "add", "a").unwrap(); // integer -> number
    assert!(
        g.set_value("add", "b", cnets_engine::Value::Integer(2))
            .is_ok()
    );
    assert!(
        g.set_value("add", "b", cnets_engine::Value::text("two"))
            .is_err()
    );
}
