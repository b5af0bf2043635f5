//! Item ports fed lists run the node per item with longest-list matching; list ports take whole lists.

use crate::common;

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
        ev.result(&g, "c").unwrap().error().as_deref(),
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

fn grafted(xs: &[f64]) -> Value {
    Value::list(xs.iter().map(|&x| nums(&[x])).collect())
}

#[test]
fn a_grafted_list_against_a_flat_list_gives_one_branch_per_graft() {
    // Grasshopper's grid idiom: 9 grafted rows × 13 columns → 9 branches of 13 values.
    let rows: Vec<f64> = (0..9).map(|i| 1.0 + i as f64).collect();
    let cols: Vec<f64> = (0..13).map(|j| 100.0 * (j as f64 + 1.0)).collect();
    let mut g = common::graph();
    g.add_node("add", "t.add").unwrap();
    g.set_value("add", "a", grafted(&rows)).unwrap();
    g.set_value("add", "b", nums(&cols)).unwrap();
    let mut ev = Evaluator::new();
    ev.evaluate_all(&g, &NodeContext::default());
    let expected = Value::list(
        rows.iter()
            .map(|r| nums(&cols.iter().map(|c| r + c).collect::<Vec<_>>()))
            .collect(),
    );
    assert_eq!(ev.output(&g, "add", "sum"), Some(&expected));
    // The rule is symmetric: the flat list on the other port gives the same shape.
    g.set_value("add", "a", nums(&cols)).unwrap();
    g.set_value("add", "b", grafted(&rows)).unwrap();
    ev.evaluate_all(&g, &NodeContext::default());
    assert_eq!(ev.output(&g, "add", "sum"), Some(&expected));
}

#[test]
fn equal_depths_match_branch_by_branch_and_repeat_the_last_branch() {
    let mut g = common::graph();
    g.add_node("add", "t.add").unwrap();
    let a = Value::list(vec![nums(&[1.0, 2.0]), nums(&[3.0]), nums(&[4.0, 5.0])]);
    let b = Value::list(vec![nums(&[10.0]), nums(&[20.0, 30.0])]);
    g.set_value("add", "a", a).unwrap();
    g.set_value("add", "b", b).unwrap();
    let mut ev = Evaluator::new();
    ev.evaluate_all(&g, &NodeContext::default());
    let expected = Value::list(vec![
        nums(&[11.0, 12.0]),
        nums(&[23.0, 33.0]),
        nums(&[24.0, 35.0]),
    ]);
    assert_eq!(ev.output(&g, "add", "sum"), Some(&expected));
}

#[test]
fn a_single_value_meets_every_leaf_of_a_deep_tree() {
    let mut g = common::graph();
    g.add_node("add", "t.add").unwrap();
    let tree = Value::list(vec![
        grafted(&[1.0, 2.0]),
        Value::list(vec![nums(&[3.0, 4.0])]),
    ]);
    g.set_value("add", "a", tree).unwrap();
    g.set_value("add", "b", Value::Number(0.5)).unwrap();
    let mut ev = Evaluator::new();
    ev.evaluate_all(&g, &NodeContext::default());
    let expected = Value::list(vec![
        grafted(&[1.5, 2.5]),
        Value::list(vec![nums(&[3.5, 4.5])]),
    ]);
    assert_eq!(ev.output(&g, "add", "sum"), Some(&expected));
}
