//! A re-run whose outputs are unchanged stops propagation (backdating).

use crate::common;

use cnets_engine::{Evaluator, NodeContext, Value};

#[test]
fn equal_outputs_stop_propagation() {
    // x -> sign -> n0 -> n1 -> n2
    let mut g = common::graph();
    g.add_node("x", "t.num").unwrap();
    g.set_value("x", "value", Value::Number(2.0)).unwrap();
    g.add_node("sign", "t.sign").unwrap();
    g.connect("x", "out", "sign", "x").unwrap();
    let mut prev = ("sign".to_string(), "out");
    for k in 0..3 {
        let id = format!("n{k}");
        g.add_node(&id, "t.add").unwrap();
        g.connect(&prev.0, prev.1, &id, "a").unwrap();
        prev = (id, "sum");
    }
    let mut ev = Evaluator::new();
    let ctx = NodeContext::default();
    ev.evaluate_all(&g, &ctx);
    let changed_before = ev.changed_at(&g, "sign").unwrap();

    g.set_value("x", "value", Value::Number(7.0)).unwrap();
    let s = ev.evaluate_all(&g, &ctx);
    assert_eq!(s.ran, 2, "x and sign re-run; sign's output 1 is unchanged");
    assert_eq!(s.cut_off, 1);
    assert_eq!(ev.runs(&g, "sign"), 2);
    assert_eq!(ev.runs(&g, "n0"), 1);
    assert_eq!(ev.runs(&g, "n2"), 1);
    assert_eq!(
        ev.changed_at(&g, "sign"),
        Some(changed_before),
        "sign was backdated"
    );

    g.set_value("x", "value", Value::Number(-1.0)).unwrap();
    let s = ev.evaluate_all(&g, &ctx);
    assert_eq!(s.ran, 5, "the sign flipped: everything downstream re-runs");
    assert_eq!(ev.output(&g, "n2", "sum"), Some(&Value::Number(-1.0)));
}

#[test]
fn output_hashes_identify_content() {
    let mut g = common::graph();
    g.add_node("x", "t.num").unwrap();
    let mut ev = Evaluator::new();
    let ctx = NodeContext::default();
    ev.evaluate_all(&g, &ctx);
    let h0 = ev.output_hashes(&g, "x").unwrap().to_vec();
    g.set_value("x", "value", Value::Number(1.0)).unwrap();
    ev.evaluate_all(&g, &ctx);
    let h1 = ev.output_hashes(&g, "x").unwrap().to_vec();
    assert_ne!(h0, h1);
    g.set_value("x", "value", Value::Number(0.0)).unwrap();
    ev.evaluate_all(&g, &ctx);
    assert_eq!(ev.output_hashes(&g, "x").unwrap(), h0.as_slice());
}
