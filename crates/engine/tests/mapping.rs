//! Item ports fed lists run the node per item with longest-list matching; list ports take whole lists.

mod common;

use cnets_engine::{Evaluator, NodeContext, Value};
use glam::DVec3;

fn nums(xs: &[f64]) -> Value {
    Value::list(xs.iter().map(|&x| Value::Number(x)).collect())
}

#[test]
fn longest_list_matching_repeats_the_last_item() {
    let mut g = common::graph();
    g.add_node("add", "t.add").unwrap();
    g.set_value("add", "a", nums(&[1.0, 2.0, 3.0])).unwrap();
    g.set_value("add", "b", nums(&[10.0, 20.0])).unwrap();
    let mut ev = Evaluator::new();
    ev.evaluate_all(&g, &NodeContext::default());
    assert_eq!(
        ev.output(&g, "add", "sum"),
        Some(&nums(&[11.0, 22.0, 23.0]))
    );
}

#[test]
fn nested_lists_map_deeper_and_list_ports_take_lists() {
    let mut g = common::graph();
    g.add_node("sum", "t.sum").unwrap();
    g.set_value(
        "sum",
        "xs",
        Value::list(vec![nums(&[1.0, 2.0]), nums(&[3.0])]),
    )
    .unwrap();
    g.add_node("single", "t.sum").unwrap();
    g.set_value("single", "xs", Value::Number(5.0)).unwrap();
    let mut ev = Evaluator::new();
    ev.evaluate_all(&g, &NodeContext::default());
    assert_eq!(ev.output(&g, "sum", "total"), Some(&nums(&[3.0, 3.0])));
    assert_eq!(
        ev.output(&g, "sum", "count"),
        Some(&Value::list(vec![Value::Integer(2), Value::Integer(1)]))
    );
    assert_eq!(
        ev.output(&g, "single", "total"),
        Some(&Value::Number(5.0)),
        "a single value is a one-element list"
    );
}

#[test]
fn empty_lists_give_empty_outputs() {
    let mut g = common::graph();
    g.add_node("add", "t.add").unwrap();
    g.set_value("add", "a", Value::list(vec![])).unwrap();
    let mut ev = Evaluator::new();
    ev.evaluate_all(&g, &NodeContext::default());
    assert_eq!(ev.output(&g, "add", "sum"), Some(&Value::list(vec![])));
}

#[test]
fn a_list_of_points_is_a_polyline_and_several_wires_merge() {
    let mut g = common::graph();
    g.add_node("poly", "t.poly").unwrap();
    let pts = Value::list(vec![
        Value::Point(DVec3::ZERO),
        Value::Point(DVec3::X),
        Value::Point(DVec3::Y),
    ]);
    g.set_value("poly", "curve", pts).unwrap();
    g.add_node("a", "t.series").unwrap();
    g.add_node("b", "t.series").unwrap();
    g.set_value("b", "n", Value::Integer(2)).unwrap();
    g.add_node("sum", "t.sum").unwrap();
    g.connect("a", "out", "sum", "xs").unwrap();
    g.connect("b", "out", "sum", "xs").unwrap();
    let mut ev = Evaluator::new();
    ev.evaluate_all(&g, &NodeContext::default());
    assert_eq!(ev.output(&g, "poly", "count"), Some(&Value::Integer(3)));
    assert_eq!(
        ev.output(&g, "sum", "count"),
        Some(&Value::Integer(5)),
        "[0,1,2] ++ [0,1]"
    );
}

#[test]
fn item_errors_name_the_item() {
    let mut g = common::graph();
    g.add_node("c", "t.check").unwrap();
    g.set_value("c", "x", nums(&[1.0, -1.0])).unwrap();
    let mut ev = Evaluator::new();
    ev.evaluate_all(&g, &NodeContext::default());
    assert_eq!(
        ev.result(&g, "c").unwrap().error(),
        Some("item 1: x = -1 is negative")
    );
}

#[test]
fn optional_inputs_may_stay_empty() {
    let mut g = common::graph();
    g.add_node("m", "t.maybe").unwrap();
    let mut ev = Evaluator::new();
    ev.evaluate_all(&g, &NodeContext::default());
    assert_eq!(ev.output(&g, "m", "given"), Some(&Value::Boolean(false)));
}
