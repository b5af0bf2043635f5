//! Lazy outputs: a node computes only the outputs that are wired or requested; an output asked for
//! later is computed then (once, memoized) without re-running the consumers of the others.

use std::cell::Cell;
use std::sync::Arc;

use cnets_engine::eval::OutputMask;
use cnets_engine::prelude::*;
use cnets_engine::{Evaluator, Graph, Registry};

thread_local! {
    /// How often `t.lazy` computed each of its outputs on this thread (cheap, costly).
    static COMPUTED: Cell<(usize, usize)> = const { Cell::new((0, 0)) };
}

fn computed() -> (usize, usize) {
    COMPUTED.with(Cell::get)
}

node! {
    /// Two outputs; counts how often each is computed (on the test's thread).
    #[node(id = "t.lazy", category = "Test")]
    pub fn lazy[ctx](
        /// Input.
        x: k::Number = 1.0,
    ) -> (
        /// x + 1.
        cheap: k::Number,
        /// 10 x.
        costly: k::Number,
    ) {
        let (mut a, mut b) = computed();
        let cheap = if ctx.wants("cheap") {
            a += 1;
            x + 1.0
        } else {
            0.0
        };
        let costly = if ctx.wants("costly") {
            b += 1;
            x * 10.0
        } else {
            0.0
        };
        COMPUTED.with(|c| c.set((a, b)));
        Ok((cheap, costly))
    }
}

node! {
    /// Passes a number through (computes its only output always).
    #[node(id = "t.pass", category = "Test")]
    pub fn pass(
        /// Input.
        x: k::Number = 0.0,
    ) -> (
        /// The input.
        out: k::Number,
    ) {
        Ok((x,))
    }
}

fn graph() -> Graph {
    let mut r = Registry::new();
    r.register(lazy());
    r.register(pass());
    for def in cnets_engine::cluster::nodes() {
        r.register(def);
    }
    let mut g = Graph::new(Arc::new(r));
    g.add_node("src", "t.lazy").unwrap();
    g.set_value("src", "x", Value::Number(2.0)).unwrap();
    g.add_node("a", "t.pass").unwrap();
    g.connect("src", "cheap", "a", "x").unwrap();
    g
}

fn request(g: &Graph, ids: &[&str]) -> Vec<petgraph::stable_graph::NodeIndex> {
    ids.iter().map(|id| g.index(id).unwrap()).collect()
}

#[test]
fn an_unwired_output_is_not_computed_until_it_is_wired() {
    COMPUTED.with(|c| c.set((0, 0)));
    let mut g = graph();
    let mut ev = Evaluator::new();
    let ctx = NodeContext::default();
    let s = ev.evaluate(&g, &request(&g, &["a"]), &ctx, &mut |_, _| {});
    assert_eq!(s.ran, 2);
    assert_eq!(computed(), (1, 0), "only the wired output was computed");
    assert_eq!(ev.output(&g, "a", "out"), Some(&Value::Number(3.0)));
    assert_eq!(ev.output(&g, "src", "costly"), None, "not computed");
    let cheap_changed = ev.changed_at(&g, "src");

    // Wiring the other output later computes it then, once.
    g.add_node("b", "t.pass").unwrap();
    g.connect("src", "costly", "b", "x").unwrap();
    let s = ev.evaluate(&g, &request(&g, &["a", "b"]), &ctx, &mut |_, _| {});
    assert_eq!(s.filled, 1, "src filled in its missing output");
    assert_eq!(s.ran, 2, "src (fill-in) and b");
    assert_eq!(computed(), (1, 1), "costly computed once, cheap kept");
    assert_eq!(ev.output(&g, "b", "out"), Some(&Value::Number(20.0)));
    assert_eq!(
        ev.runs(&g, "a"),
        1,
        "the consumer of the kept output did not re-run"
    );
    assert_eq!(ev.changed_at(&g, "src"), cheap_changed);

    // Memoized: nothing runs again.
    let s = ev.evaluate(&g, &request(&g, &["a", "b"]), &ctx, &mut |_, _| {});
    assert_eq!(s.ran, 0);
    assert_eq!(computed(), (1, 1));

    // An edit re-runs the node for both wired outputs in one run.
    g.set_value("src", "x", Value::Number(3.0)).unwrap();
    ev.evaluate(&g, &request(&g, &["a", "b"]), &ctx, &mut |_, _| {});
    assert_eq!(computed(), (2, 2));
    assert_eq!(ev.runs(&g, "src"), 3);

    // The same values as an eager evaluation of everything.
    let mut eager = Evaluator::new();
    eager.evaluate_all(&g, &ctx);
    for (id, out) in [
        ("src", "cheap"),
        ("src", "costly"),
        ("a", "out"),
        ("b", "out"),
    ] {
        assert_eq!(
            ev.output(&g, id, out),
            eager.output(&g, id, out),
            "{id}.{out}"
        );
    }
}

#[test]
fn requested_outputs_are_computed_and_the_rest_skipped() {
    COMPUTED.with(|c| c.set((0, 0)));
    let g = graph();
    let mut ev = Evaluator::new();
    let ctx = NodeContext::default();
    let src = g.index("src").unwrap();
    // Asked for nothing: the node still runs (its errors would be reported) but computes nothing.
    ev.evaluate_outputs(&g, &[(src, OutputMask::NONE)], &ctx, &mut |_, _| {});
    assert_eq!(computed(), (0, 0));
    assert_eq!(ev.runs(&g, "src"), 1);
    // Asked for `costly`: a fill-in computes it alone.
    let costly = OutputMask::one(1);
    ev.evaluate_outputs(&g, &[(src, costly)], &ctx, &mut |_, _| {});
    assert_eq!(computed(), (0, 1));
    assert_eq!(ev.output(&g, "src", "costly"), Some(&Value::Number(20.0)));
    assert_eq!(ev.output(&g, "src", "cheap"), None);
    // Every output (the plain request): the missing one is filled in.
    ev.evaluate(&g, &[src], &ctx, &mut |_, _| {});
    assert_eq!(computed(), (1, 1));
    assert_eq!(ev.output(&g, "src", "cheap"), Some(&Value::Number(3.0)));
}

#[test]
fn a_node_reached_twice_gets_the_union_of_its_consumers_outputs() {
    COMPUTED.with(|c| c.set((0, 0)));
    let mut g = graph();
    g.add_node("b", "t.pass").unwrap();
    g.connect("src", "costly", "b", "x").unwrap();
    let mut ev = Evaluator::new();
    let ctx = NodeContext::default();
    // `a` first: src is verified with `cheap`; then `b` asks it for `costly` in the same plan.
    ev.evaluate(&g, &request(&g, &["a"]), &ctx, &mut |_, _| {});
    assert_eq!(computed(), (1, 0));
    let s = ev.evaluate(&g, &request(&g, &["a", "b"]), &ctx, &mut |_, _| {});
    assert_eq!((s.ran, s.filled), (2, 1));
    assert_eq!(computed(), (1, 1));
    // Planned as up to date first (asked for nothing), then asked for `costly` by a consumer
    // later in the same plan: expanded there and filled in before the consumer runs.
    g.add_node("c", "t.pass").unwrap();
    g.connect("src", "costly", "c", "x").unwrap();
    let (src, c) = (g.index("src").unwrap(), g.index("c").unwrap());
    COMPUTED.with(|c| c.set((0, 0)));
    let mut ev = Evaluator::new();
    ev.evaluate(&g, &request(&g, &["a"]), &ctx, &mut |_, _| {});
    let s = ev.evaluate_outputs(
        &g,
        &[(src, OutputMask::NONE), (c, OutputMask::ALL)],
        &ctx,
        &mut |_, _| {},
    );
    assert_eq!((s.ran, s.filled), (2, 1), "src filled in, c ran");
    assert_eq!(computed(), (1, 1));
    assert_eq!(ev.output(&g, "c", "out"), Some(&Value::Number(20.0)));
    // A fresh evaluator asked for both consumers at once runs src once for both outputs.
    COMPUTED.with(|c| c.set((0, 0)));
    let mut fresh = Evaluator::new();
    fresh.evaluate(&g, &request(&g, &["b", "a"]), &ctx, &mut |_, _| {});
    assert_eq!(computed(), (1, 1));
    assert_eq!(fresh.runs(&g, "src"), 1);
}

#[test]
fn a_consumer_of_a_skipped_output_reruns_when_the_inputs_changed_meanwhile() {
    COMPUTED.with(|c| c.set((0, 0)));
    let mut g = graph();
    g.add_node("b", "t.pass").unwrap();
    g.connect("src", "costly", "b", "x").unwrap();
    let mut ev = Evaluator::new();
    let ctx = NodeContext::default();
    ev.evaluate_all(&g, &ctx);
    assert_eq!(ev.output(&g, "b", "out"), Some(&Value::Number(20.0)));
    // Edit while only `a` is looked at: `costly` is skipped (and now stale).
    g.set_value("src", "x", Value::Number(5.0)).unwrap();
    ev.evaluate(&g, &request(&g, &["a"]), &ctx, &mut |_, _| {});
    assert_eq!(ev.output(&g, "a", "out"), Some(&Value::Number(6.0)));
    assert_eq!(ev.output(&g, "src", "costly"), None);
    // Looking at `b` again fills `costly` in and re-runs `b` with the new value.
    ev.evaluate(&g, &request(&g, &["b"]), &ctx, &mut |_, _| {});
    assert_eq!(ev.output(&g, "b", "out"), Some(&Value::Number(50.0)));
    assert_eq!(ev.runs(&g, "b"), 2);
    assert_eq!(ev.runs(&g, "a"), 2);
}
