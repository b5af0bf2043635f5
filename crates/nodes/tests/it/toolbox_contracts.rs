//! The everyday toolbox of issue 16: the examples its contract promises, through `cnets eval`'s
//! path (`evaluate_node`), and the nested-list rule that makes Grasshopper's grid idiom work (a
//! grafted list times a flat list). The nodes' ids and ports (names, order, types and defaults)
//! are frozen in `crates/nodes/signatures.txt`, checked by `node_contracts.rs`.

use cnets_engine::eval::evaluate_node;
use cnets_engine::{NodeContext, Value};

#[test]
fn the_contract_examples_hold() {
    let registry = cnets_nodes::registry();
    let run = |id: &str, inputs: Vec<Value>| {
        let def = registry.get(id).unwrap();
        evaluate_node(def, &NodeContext::default(), &inputs).map(|o| o.values)
    };
    let n = |x: f64| Value::Number(x);
    let nums = |xs: &[f64]| Value::list(xs.iter().map(|&x| n(x)).collect());
    let v = run(
        "math.expression",
        vec![Value::text("sin(pi*x)^2 + y/4"), n(0.5), n(2.0), n(0.0)],
    )
    .unwrap();
    assert!((v[0].as_f64().unwrap() - 1.5).abs() < 1e-15);
    let v = run(
        "list.shift",
        vec![
            nums(&[1.0, 2.0, 3.0, 4.0]),
            Value::Integer(1),
            Value::Boolean(true),
        ],
    )
    .unwrap();
    assert_eq!(v[0], nums(&[2.0, 3.0, 4.0, 1.0]));
    let v = run(
        "list.shift",
        vec![
            nums(&[1.0, 2.0, 3.0, 4.0]),
            Value::Integer(1),
            Value::Boolean(false),
        ],
    )
    .unwrap();
    assert_eq!(v[0], nums(&[2.0, 3.0, 4.0]));
    let pattern = Value::list(vec![Value::Boolean(true), Value::Boolean(false)]);
    let v = run(
        "list.cull",
        vec![nums(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0]), pattern],
    )
    .unwrap();
    assert_eq!(v[0], nums(&[1.0, 3.0, 5.0]));
    let lists = Value::list(vec![nums(&[1.0, 2.0, 3.0]), nums(&[10.0, 20.0, 30.0])]);
    let v = run(
        "list.weave",
        vec![
            lists,
            Value::list(vec![Value::Integer(0), Value::Integer(1)]),
        ],
    )
    .unwrap();
    assert_eq!(v[0], nums(&[1.0, 10.0, 2.0, 20.0, 3.0, 30.0]));
    let v = run(
        "list.cross_reference",
        vec![nums(&[1.0, 2.0]), nums(&[10.0, 20.0, 30.0])],
    )
    .unwrap();
    assert_eq!(
        v,
        vec![
            nums(&[1.0, 1.0, 1.0, 2.0, 2.0, 2.0]),
            nums(&[10.0, 20.0, 30.0, 10.0, 20.0, 30.0])
        ]
    );
}

/// `math.multiply` with `a` = graft of [r0 … r8] and `b` = [c0 … c12] gives 9 lists of 13 values
/// r_i · c_j — through a real graph with `list.graft`.
#[test]
fn a_grafted_list_times_a_flat_list_is_a_table() {
    use std::sync::Arc;
    let mut g = cnets_engine::Graph::new(Arc::new(cnets_nodes::registry()));
    let rows: Vec<f64> = (0..9).map(|i| 0.4 + 0.01 * i as f64).collect();
    let cols: Vec<f64> = (0..13).map(|j| 1.0 + 0.02 * j as f64).collect();
    let list = |xs: &[f64]| Value::list(xs.iter().map(|&x| Value::Number(x)).collect());
    g.add_node("rows", "param.list").unwrap();
    g.set_value("rows", "values", list(&rows)).unwrap();
    g.add_node("graft", "list.graft").unwrap();
    g.connect("rows", "values", "graft", "list").unwrap();
    g.add_node("cols", "param.list").unwrap();
    g.set_value("cols", "values", list(&cols)).unwrap();
    g.add_node("mul", "math.multiply").unwrap();
    g.connect("graft", "tree", "mul", "a").unwrap();
    g.connect("cols", "values", "mul", "b").unwrap();
    let mut ev = cnets_engine::Evaluator::new();
    ev.evaluate_all(&g, &NodeContext::default());
    let table = ev.output(&g, "mul", "result").expect("evaluated");
    let outer = table.as_list().unwrap();
    assert_eq!(outer.len(), 9);
    for (i, row) in outer.iter().enumerate() {
        let row = row.as_list().unwrap();
        assert_eq!(row.len(), 13);
        for (j, x) in row.iter().enumerate() {
            assert_eq!(x.as_f64().unwrap(), rows[i] * cols[j]);
        }
    }
    // The panel shows it branch by branch with paths.
    g.add_node("panel", "view.panel").unwrap();
    g.connect("mul", "result", "panel", "value").unwrap();
    ev.evaluate_all(&g, &NodeContext::default());
    let Some(Value::Text(text)) = ev.output(&g, "panel", "text") else {
        panic!("panel text")
    };
    assert!(text.starts_with("{0}\n0  0.4\n"), "{text}");
    assert!(text.contains("\n{8}\n"), "{text}");
}
