//! Paper Fig. 11 with cnets' own optimizer: the `tube-closure` graph's end polygon is driven onto
//! its targets by five ratio handles per generatrix polyline.

use cnets_engine::NodeContext;
use cnets_engine::file::{load_str, to_ron};
use cnets_engine::optimize::{Options, Stop, optimize};
use cnets_tests::{Evaluated, load, registry};

#[test]
fn the_monge_tube_misses_its_targets() {
    let e = Evaluated::new(load("tube-closure"));
    let gap = e.number("gap", "max");
    assert!(
        gap > 0.1,
        "the Monge tube should visibly miss its targets, max gap {gap}"
    );
    let quality = e.output("tube", "quality");
    let cnets_engine::Value::Record(q) = quality else {
        panic!("quality record")
    };
    assert!(q.get("max_planarity").and_then(|v| v.as_f64()).unwrap() < 1e-12);
}

#[test]
fn optimization_closes_the_tube_reproducibly() {
    let doc = load("tube-closure");
    let setup = doc.meta.optimization.clone().expect("a stored setup");
    assert_eq!(
        setup.variables.len(),
        40,
        "five ratio handles for each of the 8 generatrix polylines"
    );
    let ctx = NodeContext::default();
    let options = Options {
        max_iter: Some(100),
        ..Options::default()
    };
    let mut history = Vec::new();
    let a = optimize(&doc.graph, &setup, &options, &ctx, &mut |i| {
        history.push(i.objective)
    })
    .unwrap();
    assert!(
        a.objective <= a.start * 1e-6,
        "only {:.3e} -> {:.3e}",
        a.start,
        a.objective
    );
    assert!(a.iterations <= 100);
    assert!(matches!(a.stop, Stop::Converged(_)), "{:?}", a.stop);
    assert!(history.windows(2).all(|w| w[1] <= w[0]));
    assert!(
        a.x.iter()
            .zip(&setup.variables)
            .all(|(x, v)| (v.min..=v.max).contains(x))
    );

    let b = optimize(&doc.graph, &setup, &options, &ctx, &mut |_| {}).unwrap();
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&a.x), bits(&b.x), "bit-for-bit reproducible");
    assert_eq!(a.objective.to_bits(), b.objective.to_bits());

    // The optimized graph, saved and loaded again, evaluates to the closed tube.
    let text = to_ron(&a.graph, &doc.meta);
    let again = load_str(&text, "optimized.ron", &registry()).unwrap();
    let e = Evaluated::new(again);
    assert_eq!(e.number("gap", "value").to_bits(), a.objective.to_bits());
    assert!(e.number("gap", "max") < 1e-5);
}

#[test]
fn incremental_gradients_run_fewer_nodes_than_full_re_evaluation() {
    let doc = load("tube-closure");
    let setup = doc.meta.optimization.clone().unwrap();
    let ctx = NodeContext::default();
    // Finite-difference gradients (81 evaluations each): the baseline the figures compare.
    let options = Options {
        max_iter: Some(1),
        exact_gradients: false,
        ..Options::default()
    };
    let inc = optimize(&doc.graph, &setup, &options, &ctx, &mut |_| {}).unwrap();
    let full = optimize(
        &doc.graph,
        &setup,
        &Options {
            incremental: false,
            ..options
        },
        &ctx,
        &mut |_| {},
    )
    .unwrap();
    assert_eq!(inc.evaluations, full.evaluations);
    assert_eq!(
        full.node_runs,
        full.evaluations * doc.graph.node_count() as u64
    );
    assert!(
        inc.node_runs < full.node_runs,
        "{} vs {}",
        inc.node_runs,
        full.node_runs
    );
}
