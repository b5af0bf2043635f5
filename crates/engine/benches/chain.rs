//! A chain of 1 000 trivial nodes: full evaluation, re-evaluation after changing the head, and a
//! no-change re-evaluation.

use std::hint::black_box;
use std::sync::Arc;

use cnets_engine::prelude::*;
use cnets_engine::{Evaluator, Graph, Registry};
use criterion::{BatchSize, Criterion, criterion_group, criterion_main};

node! {
    /// Passes a number through.
    #[node(id = "b.num", category = "Bench")]
    fn num(
        /// The value.
        value: k::Number = 0.0,
    ) -> (
        /// The value.
        out: k::Number,
    ) {
        Ok((value,))
    }
}

node! {
    /// Adds one.
    #[node(id = "b.inc", category = "Bench")]
    fn inc(
        /// Input.
        x: k::Number = 0.0,
    ) -> (
        /// x + 1.
        out: k::Number,
    ) {
        Ok((x + 1.0,))
    }
}

const LEN: usize = 1000;

fn chain() -> Graph {
    let mut r = Registry::new();
    r.register(num());
    r.register(inc());
    let mut g = Graph::new(Arc::new(r));
    g.add_node("head", "b.num").unwrap();
    let mut prev = "head".to_string();
    for k in 0..LEN {
        let id = format!("n{k}");
        g.add_node(&id, "b.inc").unwrap();
        g.connect(&prev, "out", &id, "x").unwrap();
        prev = id;
    }
    g
}

fn bench(c: &mut Criterion) {
    let ctx = NodeContext::default();
    let mut group = c.benchmark_group("chain_1000");
    group.bench_function("full_evaluation", |b| {
        b.iter_batched(
            || (chain(), Evaluator::new()),
            |(g, mut ev)| black_box(ev.evaluate_all(&g, &ctx)),
            BatchSize::LargeInput,
        )
    });
    let mut g = chain();
    let mut ev = Evaluator::new();
    ev.evaluate_all(&g, &ctx);
    let tail = [g.index("n999").unwrap()];
    let mut value = 0.0;
    group.bench_function("reevaluate_after_head_change", |b| {
        b.iter(|| {
            value += 1.0;
            g.set_value("head", "value", Value::Number(value)).unwrap();
            let s = ev.evaluate(&g, &tail, &ctx, &mut |_, _| {});
            assert_eq!(s.ran, LEN + 1);
            black_box(s)
        })
    });
    group.bench_function("no_change_reevaluation", |b| {
        b.iter(|| black_box(ev.evaluate(&g, &tail, &ctx, &mut |_, _| {})))
    });
    let all: Vec<_> = g.nodes().map(|(k, _)| k).collect();
    group.bench_function("no_change_reevaluation_all_requested", |b| {
        b.iter(|| black_box(ev.evaluate(&g, &all, &ctx, &mut |_, _| {})))
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
