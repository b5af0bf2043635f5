//! Cost of one finite-difference gradient of the `tube-closure` objective (40 variables, 81 objective
//! evaluations): incremental evaluation versus re-evaluating the whole graph every time. Prints the
//! node runs of each, then times them.

use std::hint::black_box;

use cnets_engine::NodeContext;
use cnets_engine::optimize::{Options, optimize};
use criterion::{Criterion, criterion_group, criterion_main};

fn bench(c: &mut Criterion) {
    let doc = cnets_tests::load("tube-closure");
    let setup = doc.meta.optimization.clone().unwrap();
    let ctx = NodeContext::default();
    // max_iter 0: the start value and one gradient.
    let options = Options {
        max_iter: Some(0),
        ..Options::default()
    };
    for incremental in [true, false] {
        let o = optimize(
            &doc.graph,
            &setup,
            &Options {
                incremental,
                ..options.clone()
            },
            &ctx,
            &mut |_| {},
        )
        .unwrap();
        println!(
            "one gradient ({}): {} objective evaluations, {} node runs ({:.2} per evaluation)",
            if incremental {
                "incremental"
            } else {
                "full re-evaluation"
            },
            o.evaluations,
            o.node_runs,
            o.node_runs as f64 / o.evaluations as f64
        );
    }
    let mut group = c.benchmark_group("tube_closure_gradient");
    for incremental in [true, false] {
        let name = if incremental { "incremental" } else { "full" };
        group.bench_function(name, |b| {
            b.iter(|| {
                black_box(
                    optimize(
                        &doc.graph,
                        &setup,
                        &Options {
                            incremental,
                            ..options.clone()
                        },
                        &ctx,
                        &mut |_| {},
                    )
                    .unwrap(),
                )
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
