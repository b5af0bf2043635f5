//! The optimizer drives number inputs to minimize a number output: bounded L-BFGS with
//! finite-difference gradients (Nelder–Mead for non-smooth objectives), deterministic, cancellable,
//! and cheaper with incremental evaluation.

use crate::common;

use std::sync::atomic::Ordering;

use cnets_engine::file::{load_str, to_ron};
use cnets_engine::optimize::{Method, Options, Stop, optimize};
use cnets_engine::{NodeContext, Value};

/// f(x, y) = (x − 3)² + (y + 1)², with a branch per variable and a shared sum.
const GRAPH: &str = r#"(
    version: 1,
    optimization: (
        objective: "f.sum",
        variables: [
            (input: "x.value", min: -10.0, max: 10.0),
            (input: "y.value", min: -10.0, max: 10.0),
        ],
        method: "lbfgsb",
        max_iter: 60,
    ),
    nodes: {
        "x": (type: "t.num", inputs: {"value": 0.0}),
        "dx": (type: "t.add", inputs: {"b": -3.0}),
        "sx": (type: "t.sq"),
        "y": (type: "t.num", inputs: {"value": 0.0}),
        "dy": (type: "t.add", inputs: {"b": 1.0}),
        "sy": (type: "t.sq"),
        "f": (type: "t.add"),
    },
    edges: ["x.out -> dx.a", "dx.sum -> sx.x", "y.out -> dy.a", "dy.sum -> sy.x", "sx.out -> f.a", "sy.out -> f.b"],
)"#;

fn load(text: &str) -> cnets_engine::file::Document {
    load_str(text, "opt.ron", &common::registry()).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn lbfgs_finds_the_minimum_and_writes_it_into_the_graph() {
    let doc = load(GRAPH);
    let setup = doc.meta.optimization.clone().unwrap();
    let mut iterations = Vec::new();
    let out = optimize(
        &doc.graph,
        &setup,
        &Options::default(),
        &NodeContext::default(),
        &mut |i| iterations.push(i.clone()),
    )
    .unwrap();
    assert_eq!(out.start, 10.0);
    assert!(out.objective < 1e-12, "{}", out.objective);
    assert!(
        (out.x[0] - 3.0).abs() < 1e-6 && (out.x[1] + 1.0).abs() < 1e-6,
        "{:?}",
        out.x
    );
    assert!(matches!(out.stop, Stop::Converged(_)), "{:?}", out.stop);
    assert_eq!(iterations[0].iteration, 0);
    assert!(
        iterations
            .windows(2)
            .all(|w| w[1].objective <= w[0].objective),
        "monotone decrease"
    );
    assert_eq!(
        out.graph.node("x").unwrap().value_of("value"),
        Some(&Value::Number(out.x[0]))
    );
}

#[test]
fn bounds_are_respected() {
    let doc = load(&GRAPH.replace(
        "(input: \"x.value\", min: -10.0, max: 10.0)",
        "(input: \"x.value\", min: -10.0, max: 2.0)",
    ));
    let setup = doc.meta.optimization.clone().unwrap();
    let out = optimize(
        &doc.graph,
        &setup,
        &Options::default(),
        &NodeContext::default(),
        &mut |_| {},
    )
    .unwrap();
    assert_eq!(out.x[0], 2.0);
    assert!((out.objective - 1.0).abs() < 1e-10, "{}", out.objective);
}

#[test]
fn runs_are_bit_for_bit_reproducible() {
    let doc = load(GRAPH);
    let setup = doc.meta.optimization.clone().unwrap();
    let run = || {
        optimize(
            &doc.graph,
            &setup,
            &Options::default(),
            &NodeContext::default(),
            &mut |_| {},
        )
        .unwrap()
    };
    let (a, b) = (run(), run());
    assert_eq!(
        a.x.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
        b.x.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
    );
    assert_eq!(a.objective.to_bits(), b.objective.to_bits());
    assert_eq!((a.evaluations, a.node_runs), (b.evaluations, b.node_runs));
}

#[test]
fn incremental_evaluation_runs_fewer_nodes_than_full_re_evaluation() {
    // Add a chain of six nodes that does not depend on the variables: a full re-evaluation runs it
    // every time, the incremental one never again.
    let text = GRAPH
        .replace("objective: \"f.sum\"", "objective: \"total.sum\"")
        .replace(
            "\"f\": (type: \"t.add\"),",
            "\"f\": (type: \"t.add\"), \"k0\": (type: \"t.num\"), \"k1\": (type: \"t.add\"), \"k2\": (type: \"t.add\"),
             \"k3\": (type: \"t.add\"), \"k4\": (type: \"t.add\"), \"total\": (type: \"t.add\"),",
        )
        .replace(
            "\"sy.out -> f.b\"",
            "\"sy.out -> f.b\", \"k0.out -> k1.a\", \"k1.sum -> k2.a\", \"k2.sum -> k3.a\", \"k3.sum -> k4.a\",
             \"f.sum -> total.a\", \"k4.sum -> total.b\"",
        );
    let doc = load(&text);
    let setup = doc.meta.optimization.clone().unwrap();
    let ctx = NodeContext::default();
    // Finite-difference gradients: every probe is an evaluation (the reverse pass would
    // differentiate these test nodes, which have no product, node by node).
    let options = Options {
        max_iter: Some(3),
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
    assert_eq!(
        inc.evaluations, full.evaluations,
        "same path, same evaluations"
    );
    assert_eq!(inc.x, full.x, "same result");
    assert_eq!(
        full.node_runs,
        13 * full.evaluations,
        "every evaluation runs all 13 nodes"
    );
    // A probe changes one or two variables: at most 2 × 3 branch nodes + f + total re-run.
    assert!(
        inc.node_runs <= 8 * inc.evaluations,
        "{} runs for {} evaluations",
        inc.node_runs,
        inc.evaluations
    );
    assert!(
        inc.node_runs * 2 < full.node_runs,
        "{} vs {}",
        inc.node_runs,
        full.node_runs
    );
}

#[test]
fn cancellation_stops_the_run() {
    let doc = load(GRAPH);
    let setup = doc.meta.optimization.clone().unwrap();
    let ctx = NodeContext::default();
    let cancel = ctx.cancel.clone();
    let out = optimize(&doc.graph, &setup, &Options::default(), &ctx, &mut |i| {
        if i.iteration == 1 {
            cancel.store(true, Ordering::Relaxed);
        }
    })
    .unwrap();
    assert_eq!(out.stop, Stop::Cancelled);
    assert_eq!(out.iterations, 1);
}

#[test]
fn nelder_mead_handles_a_non_smooth_objective() {
    let text = GRAPH
        .replace("\"sx\": (type: \"t.sq\")", "\"sx\": (type: \"t.abs\")")
        .replace("\"sy\": (type: \"t.sq\")", "\"sy\": (type: \"t.abs\")");
    let doc = load(&text);
    let setup = doc.meta.optimization.clone().unwrap();
    let out = optimize(
        &doc.graph,
        &setup,
        &Options {
            method: Some(Method::NelderMead),
            max_iter: Some(400),
            ..Options::default()
        },
        &NodeContext::default(),
        &mut |_| {},
    )
    .unwrap();
    assert!(out.objective < 1e-6, "{}", out.objective);
    let auto = optimize(
        &doc.graph,
        &setup,
        &Options {
            method: Some(Method::Auto),
            max_iter: Some(400),
            ..Options::default()
        },
        &NodeContext::default(),
        &mut |_| {},
    )
    .unwrap();
    assert!(
        auto.objective < 1e-6,
        "{} (fell back: {})",
        auto.objective,
        auto.fell_back
    );
}

#[test]
fn the_setup_round_trips_and_bad_references_are_located() {
    let doc = load(GRAPH);
    let text = to_ron(&doc.graph, &doc.meta);
    let again = load(&text);
    assert_eq!(again.meta.optimization, doc.meta.optimization);
    assert_eq!(to_ron(&again.graph, &again.meta), text);

    let bad = GRAPH.replace("objective: \"f.sum\"", "objective: \"f.total\"");
    let e = load_str(&bad, "opt.ron", &common::registry())
        .unwrap_err()
        .to_string();
    assert!(e.contains("opt.ron:3:19: optimization: f.total: node 'f' has no output 'total'; its outputs are: sum"), "{e}");
    let bad = GRAPH.replace("max_iter: 60", "max_iters: 60");
    let e = load_str(&bad, "opt.ron", &common::registry())
        .unwrap_err()
        .to_string();
    assert!(e.contains("unknown optimization field 'max_iters'"), "{e}");
    let wired = GRAPH.replace("(input: \"x.value\"", "(input: \"dx.a\"");
    let doc = load(&wired);
    let e = optimize(
        &doc.graph,
        doc.meta.optimization.as_ref().unwrap(),
        &Options::default(),
        &NodeContext::default(),
        &mut |_| {},
    )
    .unwrap_err();
    assert!(e.to_string().contains("the input is connected"), "{e}");
}

/// GRAPH with 0.5 added (a minimum of 0.5, not 0: a zero objective stops at once).
fn offset_graph() -> String {
    GRAPH
        .replace("objective: \"f.sum\"", "objective: \"g.sum\"")
        .replace("method: \"lbfgsb\"", "method: \"auto\"")
        .replace(
            "\"f\": (type: \"t.add\"),",
            "\"f\": (type: \"t.add\"),\n        \"g\": (type: \"t.add\", inputs: {\"b\": 0.5}),",
        )
        .replace("\"sy.out -> f.b\"]", "\"sy.out -> f.b\", \"f.sum -> g.a\"]")
}

#[test]
fn a_rerun_at_the_optimum_stops_there_without_nelder_mead() {
    // At the optimum up to 1e-9 (as a run leaves it). (The catamaran rerun in the CLI tests is
    // the case where no descent step exists: `optimize_cli.rs`.)
    let text = offset_graph()
        .replace(
            "\"x\": (type: \"t.num\", inputs: {\"value\": 0.0})",
            "\"x\": (type: \"t.num\", inputs: {\"value\": 3.000000001})",
        )
        .replace(
            "\"y\": (type: \"t.num\", inputs: {\"value\": 0.0})",
            "\"y\": (type: \"t.num\", inputs: {\"value\": -1.0})",
        );
    let doc = load(&text);
    let setup = doc.meta.optimization.clone().unwrap();
    let again = optimize(
        &doc.graph,
        &setup,
        &Options::default(),
        &NodeContext::default(),
        &mut |_| {},
    )
    .unwrap();
    assert!(!again.fell_back, "{:?} {:?}", again.stop, again.notes);
    assert!(again.objective <= again.start, "{again:?}");
    assert!(again.iterations <= 5, "{} iterations", again.iterations);
    assert!(
        matches!(&again.stop, Stop::Converged(_)),
        "{:?}",
        again.stop
    );
    assert!(
        !again.notes.iter().any(|n| n.contains("Nelder–Mead")),
        "{:?}",
        again.notes
    );
}
