//! A failing (or panicking) node is marked with its message; dependents are blocked; independent
//! branches still evaluate.

use crate::common;

use cnets_engine::{Blocked, Evaluator, NodeContext, NodeResult, Value};

fn setup(kind: &str) -> cnets_engine::Graph {
    let mut g = common::graph();
    g.add_node("x", "t.num").unwrap();
    g.add_node("bad", kind).unwrap();
    g.connect("x", "out", "bad", "x").unwrap();
    g.add_node("after", "t.add").unwrap();
    g.connect("bad", "out", "after", "a").unwrap();
    g.add_node("other", "t.num").unwrap();
    g.set_value("other", "value", Value::Number(4.0)).unwrap();
    g
}

#[test]
fn errors_are_isolated_and_dependents_blocked() {
    let mut g = setup("t.check");
    g.set_value("x", "value", Value::Number(-2.0)).unwrap();
    let mut ev = Evaluator::new();
    let ctx = NodeContext::default();
    ev.evaluate_all(&g, &ctx);
    match ev.result(&g, "bad").unwrap() {
        NodeResult::Failed(e) => assert_eq!(e.to_string(), "x = -2 is negative"),
        other => panic!("expected failure, got {other:?}"),
    }
    match ev.result(&g, "after").unwrap() {
        NodeResult::Blocked(b) => {
            assert_eq!(b.upstream(), "bad");
            assert!(matches!(b, Blocked::UpstreamFailed { .. }), "{b:?}");
            assert_eq!(b.to_string(), "input 'a' comes from 'bad', which failed");
        }
        other => panic!("expected blocked, got {other:?}"),
    }
    assert_eq!(ev.runs(&g, "after"), 0, "a blocked node does not run");
    assert_eq!(ev.output(&g, "other", "out"), Some(&Value::Number(4.0)));

    g.set_value("x", "value", Value::Number(3.0)).unwrap();
    ev.evaluate_all(&g, &ctx);
    assert_eq!(
        ev.output(&g, "after", "sum"),
        Some(&Value::Number(3.0)),
        "recovers after a fix"
    );
}

#[test]
fn panics_inside_nodes_are_caught() {
    let mut g = setup("t.panicky");
    g.set_value("x", "value", Value::Number(-1.0)).unwrap();
    let mut ev = Evaluator::new();
    ev.evaluate_all(&g, &NodeContext::default());
    let message = ev.result(&g, "bad").unwrap().error().unwrap().to_string();
    assert!(
        message.starts_with("node panicked: index out of bounds"),
        "{message}"
    );
    assert!(matches!(
        ev.result(&g, "after"),
        Some(NodeResult::Blocked(_))
    ));
    assert_eq!(ev.output(&g, "other", "out"), Some(&Value::Number(4.0)));
}

#[test]
fn an_overflow_to_infinity_fails_the_node_and_blocks_its_dependents() {
    let mut g = setup("t.sq");
    g.set_value("x", "value", Value::Number(1e200)).unwrap();
    let mut ev = Evaluator::new();
    let ctx = NodeContext::default();
    ev.evaluate_all(&g, &ctx);
    assert_eq!(
        ev.result(&g, "bad").unwrap().error().as_deref(),
        Some(
            "output 'out' is not a finite number (an overflow or an undefined result: check the inputs' values and scale)"
        )
    );
    assert_eq!(ev.output(&g, "bad", "out"), None);
    assert!(matches!(
        ev.result(&g, "after"),
        Some(NodeResult::Blocked(_))
    ));
    g.set_value("x", "value", Value::Number(1e100)).unwrap();
    ev.evaluate_all(&g, &ctx);
    assert_eq!(ev.output(&g, "bad", "out"), Some(&Value::Number(1e200)));
}

#[test]
fn missing_required_input_is_reported_on_the_node() {
    let mut g = common::graph();
    g.add_node("s", "t.sign").unwrap();
    let mut ev = Evaluator::new();
    ev.evaluate_all(&g, &NodeContext::default());
    let r = ev.result(&g, "s").unwrap();
    assert!(r.is_failure());
    assert_eq!(
        r.error().as_deref(),
        Some("input 'x' is required: connect it or set a value")
    );
}

#[test]
fn disabled_nodes_block_their_dependents() {
    let mut g = setup("t.check");
    g.set_enabled("bad", false).unwrap();
    let mut ev = Evaluator::new();
    ev.evaluate_all(&g, &NodeContext::default());
    assert!(matches!(ev.result(&g, "bad"), Some(NodeResult::Disabled)));
    let m = ev.result(&g, "after").unwrap().error().unwrap().to_string();
    assert!(m.contains("disabled"), "{m}");
}
