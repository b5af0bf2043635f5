//! A fit that keeps the faces convex: the catamaran hull of the gallery fitted to its reference
//! (graphs/reference/catamaran-hull.obj, an analytic hull written by
//! scripts/make-reference-hull.py) with and without `convex: ["hull"]`. Without it the fit ends with
//! folded faces; with it none fold, without the assisted correction, and the distance to the
//! reference stays within 10 % of the unconstrained fit's (docs/optimizer.md, Keeping faces convex).

use cnets_engine::optimize::{Options, Outcome, optimize};
use cnets_engine::{Evaluator, NodeContext, Value};
use cnets_tests::{load, root};

fn context() -> NodeContext {
    NodeContext::new(None, Some(root().join("graphs")))
}

fn fit(convex: bool) -> Outcome {
    let doc = load("catamaran-hull");
    let mut setup = doc.meta.optimization.clone().expect("a stored setup");
    if convex {
        setup.convex = vec!["hull".to_string()];
    }
    optimize(
        &doc.graph,
        &setup,
        &Options::default(),
        &context(),
        &mut |_| {},
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

/// Measured afresh on the result, independently of the run's own figures: the RMS symmetric
/// distance to the reference (no barrier in it), the faces whose two configurations are not both
/// (++) (read from the `configurations` output, not the margins) and the corrections made.
fn measured(out: &Outcome) -> (f64, usize, usize) {
    let g = &out.graph;
    let mut eval = Evaluator::new();
    eval.evaluate_all(g, &context());
    let number = |node: &str, port: &str| {
        eval.output(g, node, port)
            .and_then(Value::as_f64)
            .unwrap_or_else(|| panic!("{node}.{port}"))
    };
    let rms = number("fit", "symmetric").sqrt();
    let Some(Value::List(rows)) = eval.output(g, "hull", "configurations") else {
        panic!("hull.configurations")
    };
    let rows: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            r.as_list()
                .expect("a row of labels")
                .iter()
                .map(|c| match c {
                    Value::Text(t) => t.to_string(),
                    other => panic!("a label, not {other:?}"),
                })
                .collect()
        })
        .collect();
    let folded = (0..rows.len() - 1)
        .flat_map(|i| (0..rows[i].len()).map(move |j| (i, j)))
        .filter(|&(i, j)| rows[i][j] != "++" || rows[i + 1][j] != "++")
        .count();
    let corrections = eval
        .output(g, "hull", "corrections")
        .and_then(Value::as_list)
        .map_or(0, <[Value]>::len);
    (rms, folded, corrections)
}

#[test]
fn a_fit_that_keeps_faces_convex_ends_with_none_folded_and_nearly_the_same_distance() {
    let free = fit(false);
    let kept = fit(true);
    let (rms_free, folded_free, corrections_free) = measured(&free);
    let (rms_kept, folded_kept, corrections_kept) = measured(&kept);
    eprintln!(
        "free: RMS {rms_free:.4} m, {folded_free} faces not (++)(++), {} node runs; \
         convex: RMS {rms_kept:.4} m, {folded_kept} faces, {} node runs",
        free.node_runs, kept.node_runs
    );
    // The case is worth testing: the free fit folds faces.
    assert!(folded_free > 0, "the unconstrained fit folds no face");
    assert_eq!(folded_kept, 0, "faces folded with `convex`");
    assert_eq!(
        (corrections_free, corrections_kept),
        (0, 0),
        "no correction"
    );
    assert!(
        rms_kept <= 1.10 * rms_free,
        "RMS {rms_kept} with convex against {rms_free} without"
    );
    // The run's own report agrees with the independent count.
    assert_eq!(
        free.not_convex,
        vec![("hull".to_string(), Some(folded_free))]
    );
    assert_eq!(kept.not_convex, vec![("hull".to_string(), Some(0))]);
}
