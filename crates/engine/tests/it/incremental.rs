//! Only the downstream cone of an edit re-runs; nothing runs when nothing changed.

use crate::common;

use cnets_engine::{Evaluator, NodeContext, Value};

#[test]
fn first_evaluation_runs_every_node_once() {
    let g = common::chain(10);
    let mut ev = Evaluator::new();
    let s = ev.evaluate_all(&g, &NodeContext::default());
    assert_eq!(s.ran, 11);
    assert_eq!(ev.output(&g, "n9", "sum"), Some(&Value::Number(10.0)));
    for k in 0..10 {
        assert_eq!(ev.runs(&g, &format!("n{k}")), 1);
    }
}

#[test]
fn nothing_runs_when_nothing_changed() {
    let mut g = common::chain(10);
    let mut ev = Evaluator::new();
    let ctx = NodeContext::default();
    ev.evaluate_all(&g, &ctx);
    let before = ev.total_runs();
    assert_eq!(ev.evaluate_all(&g, &ctx).ran, 0);
    // Setting an equal value is not an edit.
    assert!(!g.set_value("n3", "b", Value::Number(1.0)).unwrap());
    assert_eq!(ev.evaluate_all(&g, &ctx).ran, 0);
    // Moving a node or toggling preview is not an edit either.
    g.set_position("n3", [10.0, 20.0]).unwrap();
    g.set_preview("n3", false).unwrap();
    assert_eq!(ev.evaluate_all(&g, &ctx).ran, 0);
    assert_eq!(ev.total_runs(), before);
}

#[test]
fn only_the_downstream_cone_reruns() {
    // head -> n0 -> … -> n9, plus an independent branch `side` and a node `join` fed by n4 and side.
    let mut g = common::chain(10);
    g.add_node("side", "t.num").unwrap();
    g.add_node("join", "t.add").unwrap();
    g.connect("n4", "sum", "join", "a").unwrap();
    g.connect("side", "out", "join", "b").unwrap();
    let mut ev = Evaluator::new();
    let ctx = NodeContext::default();
    ev.evaluate_all(&g, &ctx);

    g.set_value("n5", "b", Value::Number(2.0)).unwrap();
    let s = ev.evaluate_all(&g, &ctx);
    assert_eq!(s.ran, 5, "n5..n9 re-run, nothing else");
    for k in 0..5 {
        assert_eq!(
            ev.runs(&g, &format!("n{k}")),
            1,
            "n{k} is upstream of the edit"
        );
    }
    for k in 5..10 {
        assert_eq!(
            ev.runs(&g, &format!("n{k}")),
            2,
            "n{k} is downstream of the edit"
        );
    }
    assert_eq!(ev.runs(&g, "join"), 1);
    assert_eq!(ev.runs(&g, "side"), 1);
    assert_eq!(ev.output(&g, "n9", "sum"), Some(&Value::Number(11.0)));

    g.set_value("side", "value", Value::Number(5.0)).unwrap();
    let s = ev.evaluate_all(&g, &ctx);
    assert_eq!(s.ran, 2, "side and join");
    assert_eq!(ev.output(&g, "join", "sum"), Some(&Value::Number(10.0)));
}

#[test]
fn pull_based_evaluation_runs_only_what_is_requested() {
    let mut g = common::chain(5);
    g.add_node("other", "t.num").unwrap();
    let mut ev = Evaluator::new();
    let ctx = NodeContext::default();
    let n2 = g.index("n2").unwrap();
    let s = ev.evaluate(&g, &[n2], &ctx, &mut |_, _| {});
    assert_eq!(s.ran, 4, "head, n0, n1, n2");
    assert_eq!(ev.runs(&g, "n3"), 0);
    assert_eq!(ev.runs(&g, "other"), 0);
    assert!(ev.result(&g, "n4").is_none());
}

#[test]
fn rewiring_reruns_the_target() {
    let mut g = common::chain(3);
    g.add_node("alt", "t.num").unwrap();
    g.set_value("alt", "value", Value::Number(100.0)).unwrap();
    let mut ev = Evaluator::new();
    let ctx = NodeContext::default();
    ev.evaluate_all(&g, &ctx);
    g.disconnect("n0", "sum", "n1", "a").unwrap();
    g.connect("alt", "out", "n1", "a").unwrap();
    let s = ev.evaluate_all(&g, &ctx);
    assert_eq!(s.ran, 2, "n1 and n2");
    assert_eq!(ev.output(&g, "n2", "sum"), Some(&Value::Number(102.0)));
    g.remove_node("alt").unwrap();
    ev.evaluate_all(&g, &ctx);
    assert_eq!(
        ev.output(&g, "n2", "sum"),
        Some(&Value::Number(2.0)),
        "n1.a falls back to its default 0"
    );
}

#[test]
fn a_removed_node_index_reused_by_a_new_node_does_not_inherit_its_memo() {
    let mut g = common::graph();
    g.add_node("a", "t.num").unwrap();
    g.set_value("a", "value", Value::Number(3.0)).unwrap();
    let mut ev = Evaluator::new();
    let ctx = NodeContext::default();
    ev.evaluate_all(&g, &ctx);
    g.remove_node("a").unwrap();
    g.add_node("b", "t.num").unwrap();
    ev.evaluate_all(&g, &ctx);
    assert_eq!(ev.output(&g, "b", "out"), Some(&Value::Number(0.0)));
    assert_eq!(ev.runs(&g, "b"), 1);
}

#[test]
fn a_restored_snapshot_reruns_only_what_differs_and_its_downstream_cone() {
    // head -> n0 -> … -> n9, and an independent branch side -> join <- n4.
    let mut g = common::chain(10);
    g.add_node("side", "t.num").unwrap();
    g.add_node("join", "t.add").unwrap();
    g.connect("n4", "sum", "join", "a").unwrap();
    g.connect("side", "out", "join", "b").unwrap();
    let mut ev = Evaluator::new();
    let ctx = NodeContext::default();
    ev.evaluate_all(&g, &ctx);
    // An edit (a slider change on n5), evaluated, then undone by restoring the snapshot.
    let snapshot = g.clone();
    g.set_value("n5", "b", Value::Number(2.0)).unwrap();
    ev.evaluate_all(&g, &ctx);
    let runs = |ev: &Evaluator, g: &cnets_engine::Graph, id: &str| ev.runs(g, id);
    let before: Vec<u64> = (0..10).map(|k| runs(&ev, &g, &format!("n{k}"))).collect();
    let side_before = (runs(&ev, &g, "side"), runs(&ev, &g, "join"));
    let mut restored = snapshot;
    restored.succeed(&g);
    assert!(restored.revision() > g.revision());
    let s = ev.evaluate_all(&restored, &ctx);
    assert_eq!(s.ran, 5, "n5..n9 re-run, nothing else");
    for (k, was) in before.iter().enumerate() {
        let expected = was + u64::from(k >= 5);
        assert_eq!(runs(&ev, &restored, &format!("n{k}")), expected, "n{k}");
    }
    assert_eq!(
        (runs(&ev, &restored, "side"), runs(&ev, &restored, "join")),
        side_before
    );
    assert_eq!(
        ev.output(&restored, "n9", "sum"),
        Some(&Value::Number(10.0)),
        "the old result"
    );
    // Without `succeed` the restored graph's stamps are older than the memos: nothing would run
    // and n9 would keep the edited result.
    let mut stale = common::chain(10);
    let mut ev2 = Evaluator::new();
    ev2.evaluate_all(&stale, &ctx);
    let old = stale.clone();
    stale.set_value("n5", "b", Value::Number(2.0)).unwrap();
    ev2.evaluate_all(&stale, &ctx);
    assert_eq!(
        ev2.evaluate_all(&old, &ctx).ran,
        0,
        "the bug succeed avoids"
    );
    // A node removed after the snapshot comes back; nodes added later get fresh uids.
    let snap = restored.clone();
    restored.remove_node("side").unwrap();
    ev.evaluate_all(&restored, &ctx);
    let mut back = snap;
    back.succeed(&restored);
    let s = ev.evaluate_all(&back, &ctx);
    assert_eq!(s.ran, 2, "side and join run again, the chain does not");
    back.add_node("fresh", "t.num").unwrap();
    let uids: std::collections::HashSet<u64> = back.nodes().map(|(_, n)| n.uid()).collect();
    assert_eq!(uids.len(), back.node_count());
}

#[test]
fn another_graph_taking_over_reruns_only_the_nodes_that_differ() {
    // The open document: head -> n0 -> … -> n5, and side -> join <- n2.
    let registry = common::registry();
    let build = |order: &[&str], n3_b: f64, with_side: bool| {
        let mut g = cnets_engine::Graph::new(registry.clone());
        for id in order {
            let kind = if *id == "head" || *id == "side" {
                "t.num"
            } else {
                "t.add"
            };
            if *id == "side" && !with_side {
                continue;
            }
            g.add_node(id, kind).unwrap();
        }
        for k in 0..6 {
            let b = if k == 3 { n3_b } else { 1.0 };
            g.set_value(&format!("n{k}"), "b", Value::Number(b))
                .unwrap();
        }
        g.connect("head", "out", "n0", "a").unwrap();
        for k in 1..6 {
            g.connect(&format!("n{}", k - 1), "sum", &format!("n{k}"), "a")
                .unwrap();
        }
        if with_side {
            g.connect("n2", "sum", "join", "a").unwrap();
            g.connect("side", "out", "join", "b").unwrap();
        }
        g
    };
    let forward = ["head", "n0", "n1", "n2", "n3", "n4", "n5", "side", "join"];
    let current = build(&forward, 1.0, true);
    let mut ev = Evaluator::new();
    let ctx = NodeContext::default();
    assert_eq!(ev.evaluate_all(&current, &ctx).ran, 9);
    // The same graph loaded again (nodes created in another order: other indices and uids).
    let backward: Vec<&str> = forward.iter().rev().copied().collect();
    let mut again = build(&backward, 1.0, true);
    let carried = again.take_over(&current);
    assert_eq!(carried.len(), 9, "every node continues");
    assert!(again.revision() > current.revision());
    ev.carry_over(&again, &carried, true);
    assert_eq!(ev.evaluate_all(&again, &ctx).ran, 0, "nothing recomputed");
    assert_eq!(ev.output(&again, "n5", "sum"), Some(&Value::Number(6.0)));
    assert_eq!(ev.runs(&again, "n5"), 1, "the run count came along");
    // A graph sharing nodes: n3 differs, side is gone (join loses a wire in).
    let mut other = build(&forward, 2.0, false);
    other.connect("n2", "sum", "join", "a").unwrap();
    let carried = other.take_over(&again);
    ev.carry_over(&other, &carried, true);
    let s = ev.evaluate_all(&other, &ctx);
    assert_eq!(s.ran, 4, "n3, n4, n5 and join re-run: {s:?}");
    // Continued nodes keep counting; n3 and join are new nodes (their memos start afresh).
    for (id, runs) in [
        ("head", 1),
        ("n2", 1),
        ("n3", 1),
        ("n4", 2),
        ("n5", 2),
        ("join", 1),
    ] {
        assert_eq!(ev.runs(&other, id), runs, "{id}");
    }
    assert_eq!(ev.output(&other, "n5", "sum"), Some(&Value::Number(7.0)));
    assert_eq!(ev.output(&other, "join", "sum"), Some(&Value::Number(3.0)));
    // Edits after the take-over are incremental as usual.
    other.set_value("n4", "b", Value::Number(5.0)).unwrap();
    assert_eq!(ev.evaluate_all(&other, &ctx).ran, 2);
    assert_eq!(ev.output(&other, "n5", "sum"), Some(&Value::Number(11.0)));
    // Without `carry_over` a fresh evaluator recomputes everything (what Open used to do).
    assert_eq!(Evaluator::new().evaluate_all(&other, &ctx).ran, 8);
}

#[test]
fn a_larger_graph_taking_over_from_a_small_one_evaluates() {
    // Opening a bigger file after a small one: every side table of the evaluator must follow the
    // new graph's size (once panicked with an index out of bounds in the planner).
    let registry = common::registry();
    let chain = |len: usize| {
        let mut g = cnets_engine::Graph::new(registry.clone());
        g.add_node("head", "t.num").unwrap();
        for k in 0..len {
            g.add_node(&format!("n{k}"), "t.add").unwrap();
            g.set_value(&format!("n{k}"), "b", Value::Number(1.0))
                .unwrap();
            let from = if k == 0 {
                "head".to_string()
            } else {
                format!("n{}", k - 1)
            };
            let port = if k == 0 { "out" } else { "sum" };
            g.connect(&from, port, &format!("n{k}"), "a").unwrap();
        }
        g
    };
    let small = chain(1);
    let mut ev = Evaluator::new();
    let ctx = NodeContext::default();
    ev.evaluate_all(&small, &ctx);
    let mut big = chain(12);
    let carried = big.take_over(&small);
    ev.carry_over(&big, &carried, true);
    let s = ev.evaluate_all(&big, &ctx);
    assert_eq!(s.ran, 11, "only the new nodes run: {s:?}");
    assert_eq!(ev.output(&big, "n11", "sum"), Some(&Value::Number(12.0)));
}

/// A node whose run is cut short by cancellation (the editor's worker cancels a stale evaluation
/// while a slow node runs) leaves no result: it runs again next time, and its last complete run
/// time stays (the editor defers a node by that time, issue 26).
#[test]
fn a_run_cut_short_by_cancellation_is_not_stored() {
    use cnets_engine::{Access, NodeDef, PortDef, ValueType};
    use std::sync::Arc;
    use std::sync::atomic::{AtomicBool, Ordering};
    // Cancels the evaluation from inside its run when its input is negative (as a newer edit
    // would while it runs).
    let slow = NodeDef::new(
        "t.slow",
        "Test",
        "Sleeps 30 ms; cancels on a negative input.",
    )
    .input(PortDef::new("x", ValueType::Number, Access::Item))
    .output(PortDef::new("y", ValueType::Number, Access::Item))
    .run(|ctx, inputs| {
        std::thread::sleep(std::time::Duration::from_millis(30));
        let x = inputs[0].as_f64().unwrap_or(0.0);
        if x < 0.0 {
            ctx.cancel.store(true, Ordering::Relaxed);
        }
        Ok(vec![Value::Number(2.0 * x)])
    });
    let mut g = common::chain(1);
    g.add_node_with_def("slow", Arc::new(slow)).unwrap();
    g.connect("n0", "sum", "slow", "x").unwrap();
    let mut ev = Evaluator::new();
    assert!(!ev.evaluate_all(&g, &NodeContext::default()).cancelled);
    let complete = ev.time(&g, "slow").expect("ran");
    assert!(complete.as_millis() >= 30);
    let before = ev.output(&g, "slow", "y").cloned();

    g.set_value("n0", "b", Value::Number(-100.0)).unwrap();
    let mut ctx = NodeContext::default();
    ctx.cancel = Arc::new(AtomicBool::new(false));
    assert!(ev.evaluate_all(&g, &ctx).cancelled);
    assert_eq!(
        ev.time(&g, "slow"),
        Some(complete),
        "the last complete run's time"
    );
    assert_eq!(
        ev.output(&g, "slow", "y").cloned(),
        before,
        "no result of the cut run"
    );
    // Another edit, not cancelled: it runs on the new input.
    g.set_value("n0", "b", Value::Number(5.0)).unwrap();
    let s = ev.evaluate_all(&g, &NodeContext::default());
    assert!(!s.cancelled);
    assert_ne!(ev.output(&g, "slow", "y").cloned(), before);
}
