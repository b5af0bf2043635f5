//! The memory budget: the evaluator counts the values it keeps and fails a node whose outputs do
//! not fit beside them, or whose outputs would read as more values than the budget holds.

mod common;

use cnets_engine::value::Access;
use cnets_engine::{
    Evaluator, MemoryBudget, NodeContext, NodeDef, NodeResult, PortDef, Value, ValueType,
};

fn ctx(limit: u64) -> NodeContext {
    NodeContext::default().with_budget(MemoryBudget::new(limit))
}

fn error(ev: &Evaluator, g: &cnets_engine::Graph, id: &str) -> String {
    match ev.result(g, id) {
        Some(NodeResult::Failed(e)) => e.to_string(),
        other => panic!("{id}: expected a failure, got {other:?}"),
    }
}

#[test]
fn results_that_do_not_fit_beside_the_live_values_fail_and_free_their_memory() {
    let mut g = common::graph();
    for k in 0..3 {
        let id = format!("s{k}");
        g.add_node(&id, "t.series").unwrap();
        g.set_value(&id, "n", Value::Integer(100_000)).unwrap();
    }
    let one = 100_000 * std::mem::size_of::<Value>() as u64;
    let mut ev = Evaluator::new();
    let c = ctx(2 * one + one / 2);
    ev.evaluate_all(&g, &c);
    assert!(ev.result(&g, "s0").unwrap().outputs().is_some());
    assert!(ev.result(&g, "s1").unwrap().outputs().is_some());
    assert_eq!(
        error(&ev, &g, "s2"),
        "the outputs of 's2' needs 3.2 MB, the limit is 8 MB (6.4 MB already held by other values)"
    );
    assert_eq!(ev.live_bytes(), 2 * one);
    assert_eq!(
        c.in_use(),
        0,
        "the context's count is restored after the evaluation"
    );

    // Removing a node frees its share: the failed one fits on the next evaluation.
    g.remove_node("s0").unwrap();
    g.set_value("s2", "n", Value::Integer(100_001)).unwrap();
    ev.evaluate_all(&g, &c);
    assert!(ev.result(&g, "s2").unwrap().outputs().is_some());
    assert_eq!(
        ev.live_bytes(),
        one + one + std::mem::size_of::<Value>() as u64
    );
}

#[test]
fn results_that_read_as_more_values_than_the_budget_holds_fail() {
    // 2⁴⁰ values through sharing, in 40 small lists.
    let ladder = NodeDef::new("t.ladder", "Test", "A list of a list twice, 40 times over.")
        .output(PortDef::new("out", ValueType::Number, Access::Tree))
        .run(|_, _| {
            let mut v = Value::list(vec![Value::Number(1.0)]);
            for _ in 0..40 {
                v = Value::list(vec![v.clone(), v]);
            }
            Ok(vec![v])
        });
    let mut g = common::graph();
    g.add_node_with_def("l", std::sync::Arc::new(ladder))
        .unwrap();
    let mut ev = Evaluator::new();
    let start = std::time::Instant::now();
    ev.evaluate_all(&g, &ctx(1_000_000_000));
    let message = error(&ev, &g, "l");
    assert!(
        message.starts_with("reading the outputs (3298534883327 values"),
        "{message}"
    );
    assert!(message.contains("the limit is 1 GB"), "{message}");
    assert!(
        start.elapsed().as_secs() < 5,
        "the size is measured without reading every value"
    );
}

#[test]
fn a_node_reserving_more_than_the_budget_fails_before_allocating() {
    let c = ctx(1_000_000);
    c.set_in_use(400_000);
    let e = c
        .reserve_values(20_000, "a list of 20000 items")
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "a list of 20000 items needs 640 kB, the limit is 1 MB (400 kB already held by other values)"
    );
    assert!(c.reserve_values(18_000, "fits").is_ok());
    assert!(c.reserve_values(u128::MAX, "huge").is_err());
}

#[test]
fn lists_merged_from_several_wires_count_against_the_budget() {
    // Two wires of 100 000 numbers into one list input: the merged list is new memory, held by
    // the node that passes it through.
    let mut g = common::graph();
    for id in ["a", "b"] {
        g.add_node(id, "t.series").unwrap();
        g.set_value(id, "n", Value::Integer(100_000)).unwrap();
    }
    g.add_node("s", "t.sum").unwrap();
    g.connect("a", "out", "s", "xs").unwrap();
    g.connect("b", "out", "s", "xs").unwrap();
    let one = 100_000 * std::mem::size_of::<Value>() as u64;
    let mut ev = Evaluator::new();
    ev.evaluate_all(&g, &ctx(3 * one));
    let message = match ev.result(&g, "s") {
        Some(NodeResult::Failed(e)) => e.to_string(),
        other => panic!("expected a failure, got {other:?}"),
    };
    assert!(
        message.starts_with("input 'xs': merging 2 wires into a list of 200000 items needs 6.4 MB"),
        "{message}"
    );
    let mut ev = Evaluator::new();
    ev.evaluate_all(&g, &ctx(5 * one));
    assert!(ev.result(&g, "s").unwrap().outputs().is_some());
}
