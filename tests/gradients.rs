//! Exact gradients through the real node library: the reverse pass against finite differences of
//! the whole graph, whole-input variables, and a 1 600-ratio fit that finite differences cannot do.

use cnets_engine::optimize::{Options, Setup, ValuePath, Variable, check_gradient, optimize};
use cnets_engine::{NodeContext, Value};
use cnets_tests::load;
use proptest::prelude::*;

/// tube-closure with the ratio handles at `v` (40 values, 5 per generatrix polyline).
fn tube_with_handles(v: &[f64]) -> (cnets_engine::Graph, Setup) {
    let mut doc = load("tube-closure");
    let rows: Vec<Value> = v
        .chunks(5)
        .map(|row| {
            Value::list(
                row.iter()
                    .enumerate()
                    .map(|(k, y)| Value::Point(glam::DVec3::new(k as f64 * 0.25, *y, 0.0)))
                    .collect(),
            )
        })
        .collect();
    doc.graph
        .set_value("ratios", "handles", Value::list(rows))
        .unwrap();
    (doc.graph, doc.meta.optimization.unwrap())
}

#[test]
fn tube_closure_gradient_is_exact_through_the_construction() {
    let v: Vec<f64> = (0..40)
        .map(|k| 0.4 + 0.2 * ((k as f64) * 0.77).sin().abs())
        .collect();
    let (graph, setup) = tube_with_handles(&v);
    let check = check_gradient(&graph, &setup, &NodeContext::default()).unwrap();
    assert_eq!(check.exact.len(), 40);
    assert!(
        check.largest_relative_difference < 1e-6,
        "largest relative difference {:e}",
        check.largest_relative_difference
    );
    // The monotone-spline mapper, the construction, the column and the distance are all
    // differentiated exactly: no node falls back to finite differences of its own run.
    let fd: Vec<&str> = check.node_notes.iter().map(|n| n.0.as_str()).collect();
    assert!(fd.is_empty(), "{:?}", check.node_notes);
    assert!(check.exact.iter().any(|g| g.abs() > 1e-3));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3))]
    #[test]
    fn random_tube_designs_have_exact_gradients(
        v in proptest::collection::vec(0.3f64..0.7, 40),
    ) {
        // Off the kink of the ratio → angle map at ½ (the mapper's flat runs are kinks too).
        let v: Vec<f64> = v.into_iter().map(|x| if (x - 0.5).abs() < 1e-2 { x + 2e-2 } else { x }).collect();
        let (graph, setup) = tube_with_handles(&v);
        let check = check_gradient(&graph, &setup, &NodeContext::default()).unwrap();
        prop_assert!(
            check.largest_relative_difference < 1e-6,
            "largest relative difference {:e}",
            check.largest_relative_difference
        );
    }
}

#[test]
fn a_whole_table_variable_fits_1600_ratios() {
    let doc = load("ratio-fit");
    let setup = doc.meta.optimization.clone().unwrap();
    assert_eq!(
        setup.variables.len(),
        1,
        "one whole-input variable in the file"
    );
    let ctx = NodeContext::default();
    let options = Options {
        max_iter: Some(15),
        ..Options::default()
    };
    let out = optimize(&doc.graph, &setup, &options, &ctx, &mut |_| {}).unwrap();
    assert_eq!(out.x.len(), 1600, "every number of the 40 × 40 table");
    assert_eq!(out.variables[41].input.to_string(), "ratios.values[1][1]");
    assert_eq!(out.gradients, out.exact_gradients, "{:?}", out.notes);
    // No finite differences anywhere; the only notes are the steps that move ratios across ½
    // (the start has them all at ½, on the kink of the ratio → angle map).
    assert!(
        out.notes
            .iter()
            .all(|n| n.contains("crossed a branch") || n.starts_with("more than")),
        "{:?}",
        out.notes
    );
    assert!(out.branch_crossings >= 1);
    assert!(
        out.objective < 0.05 * out.start,
        "{:.3e} -> {:.3e}",
        out.start,
        out.objective
    );
    assert!(out.x.iter().all(|x| (0.1..=0.9).contains(x)));
    // Fewer evaluations than one finite-difference gradient (3 201).
    assert!(out.evaluations < 3201, "{}", out.evaluations);
}

/// A 100 × 100 cone-net (ratios ≠ ½ everywhere) and L = Σ |G − T|² against a target net: one
/// exact gradient through the engine (evaluation + reverse pass) — the side-by-side figure.
fn hundred_by_hundred() -> cnets_engine::file::Document {
    let text = std::fs::read_to_string(cnets_tests::root().join("graphs/ratio-fit.ron")).unwrap();
    let table = |v: f64| {
        let row = format!("[{}]", vec![format!("{v}"); 99].join(", "));
        format!("[{}]", vec![row; 100].join(", "))
    };
    let start = text.find("\"values\": [").unwrap() + "\"values\": ".len();
    let end =
        start + text[start..].find("\n                ],").unwrap() + "\n                ]".len();
    let column = text.find("\"column_field\"").unwrap();
    let text = format!(
        "{}{}",
        &text[..column],
        text[column..].replacen("\"count\": 40", "\"count\": 99", 1)
    );
    let text = format!("{}{}{}", &text[..start], table(0.45), &text[end..])
        .replace("\"count\": 41", "\"count\": 100")
        .replace("\"count\": 40", "\"count\": 100")
        .replace("\"b\": 0.001", "\"b\": 0.0");
    cnets_engine::file::load_str(&text, "hundred.ron", &cnets_tests::registry()).unwrap()
}

#[test]
#[ignore = "timings for docs/optimizer.md: cargo test --release -p cnets-tests --test gradients -- --ignored --nocapture"]
fn figures() {
    use std::time::Instant;
    let ctx = NodeContext::default();
    // tube-closure: exact against finite differences.
    let doc = load("tube-closure");
    let setup = doc.meta.optimization.clone().unwrap();
    for exact in [true, false] {
        let t = Instant::now();
        let o = optimize(
            &doc.graph,
            &setup,
            &Options {
                exact_gradients: exact,
                ..Options::default()
            },
            &ctx,
            &mut |_| {},
        )
        .unwrap();
        println!(
            "tube-closure exact={exact}: {:.3e} -> {:.3e}, {} iterations, {} evaluations, {} gradients, {} node runs, {:.3} s",
            o.start,
            o.objective,
            o.iterations,
            o.evaluations,
            o.gradients,
            o.node_runs,
            t.elapsed().as_secs_f64()
        );
    }
    // ratio-fit: exact, then finite differences for the same time.
    let doc = load("ratio-fit");
    let setup = doc.meta.optimization.clone().unwrap();
    let t = Instant::now();
    let o = optimize(&doc.graph, &setup, &Options::default(), &ctx, &mut |_| {}).unwrap();
    let exact_time = t.elapsed();
    println!(
        "ratio-fit exact: {:.3e} -> {:.3e}, {} iterations, {} evaluations, {} gradients, {:.3} s, {:?}",
        o.start,
        o.objective,
        o.iterations,
        o.evaluations,
        o.gradients,
        exact_time.as_secs_f64(),
        o.stop
    );
    let fd_ctx = NodeContext::default();
    let cancel = std::sync::Arc::clone(&fd_ctx.cancel);
    std::thread::spawn(move || {
        std::thread::sleep(exact_time);
        cancel.store(true, std::sync::atomic::Ordering::Relaxed);
    });
    let t = Instant::now();
    let o = optimize(
        &doc.graph,
        &setup,
        &Options {
            exact_gradients: false,
            ..Options::default()
        },
        &fd_ctx,
        &mut |_| {},
    )
    .unwrap();
    println!(
        "ratio-fit finite differences, stopped after the same time: {:.3e} -> {:.3e}, {} iterations, {} evaluations, {} gradients, {:.3} s, {:?}",
        o.start,
        o.objective,
        o.iterations,
        o.evaluations,
        o.gradients,
        t.elapsed().as_secs_f64(),
        o.stop
    );
    // One gradient of a 100 × 100 vertex-distance objective.
    let doc = hundred_by_hundred();
    let setup = doc.meta.optimization.clone().unwrap();
    let mut problem = cnets_engine::optimize::Problem::new(doc.graph.clone(), setup, true).unwrap();
    let x = problem.start();
    assert_eq!(x.len(), 9900);
    let _ = problem.gradient(&x, &ctx).unwrap();
    let mut times = Vec::new();
    for k in 0..7 {
        // Change every ratio so that the construction re-runs (a fresh point each time).
        let y: Vec<f64> = x.iter().map(|v| v + 1e-3 * (k + 1) as f64).collect();
        let t = Instant::now();
        let g = problem.gradient(&y, &ctx).unwrap();
        times.push(t.elapsed().as_secs_f64() * 1e3);
        assert!(
            g.finite_differences.is_empty(),
            "{:?}",
            g.finite_differences
        );
    }
    times.sort_by(f64::total_cmp);
    println!(
        "100 × 100 gradient (evaluation + reverse pass, 9 900 ratios): median {:.1} ms, min {:.1} ms, max {:.1} ms",
        times[3], times[0], times[6]
    );
}

#[test]
#[ignore = "timings for docs/editor/3d-view.md: cargo test --release -p cnets-tests --test gradients -- --ignored --nocapture drag"]
fn drag_rate_figures() {
    use cnets_engine::optimize::drag::{DragRequest, drag};
    use std::time::Instant;
    let ctx = NodeContext::default();
    for (name, net, size) in [
        ("torus-monge", "varying_ratios", None),
        ("torus-monge", "varying_ratios", Some(100)),
    ] {
        let mut graph = load(name).graph;
        if let Some(n) = size {
            graph.set_value("rows", "value", Value::Integer(n)).unwrap();
            graph
                .set_value("columns", "value", Value::Integer(n))
                .unwrap();
        }
        let vertex = size.map_or((6, 12), |n| (n as usize / 2, n as usize / 2));
        // Where the vertex is: a request of no steps reports it.
        let mut request = DragRequest::new(net, vertex, glam::DVec3::ZERO);
        request.max_iter = 0;
        let start = drag(&graph, &request, &ctx).unwrap().reached;
        // As the tool does: 8 targets 0.6 m apart in eighths, each solved from the last answer
        // in at most 8 steps.
        let mut times = Vec::new();
        let mut steps = 0;
        for k in 1..=8 {
            let target = start + glam::DVec3::Z * 0.6 * f64::from(k) / 8.0;
            let mut request = DragRequest::new(net, vertex, target);
            request.max_iter = 8;
            let t = Instant::now();
            let report = drag(&graph, &request, &ctx).unwrap();
            times.push(t.elapsed().as_secs_f64() * 1e3);
            steps += report.iterations;
            graph = report.graph;
        }
        times.sort_by(f64::total_cmp);
        let median = 0.5 * (times[3] + times[4]);
        println!(
            "drag {name} {net} {:?}: median solved update {median:.1} ms ({:.1} steps on average), {:.1} updates a second",
            vertex,
            steps as f64 / 8.0,
            1e3 / median
        );
    }
}

/// Paper Fig. 5's leaning ratios with the assisted correction at ½ (it changes planes), the
/// area of the blended net as the objective and the construction's constant apex as the variable
/// (the lean only moves the ratios the correction repairs, so the net does not depend on it).
fn assisted_correction() -> (cnets_engine::Graph, Setup) {
    let mut graph = load("correction").graph;
    graph
        .set_value(
            "assistance",
            "values",
            Value::list(vec![Value::Number(0.5)]),
        )
        .unwrap();
    graph.add_node("area", "measure.area").unwrap();
    graph.connect("nets", "mesh", "area", "mesh").unwrap();
    let setup = Setup {
        // The construction is mapped over four offsets: the first net's area.
        objective: ValuePath::parse("area.total[0]").unwrap(),
        variables: vec![Variable {
            input: ValuePath::parse("nets.apex").unwrap(),
            min: 0.5,
            max: 2.0,
        }],
        penalties: Vec::new(),
        convex: Vec::new(),
        method: cnets_engine::optimize::Method::Lbfgsb,
        max_iter: 5,
    };
    (graph, setup)
}

#[test]
fn a_run_the_blended_correction_changed_is_differentiated_exactly() {
    // The corrections are computed lazily: only because the construction's derivative asks for
    // them (`derivative_outputs`) does the reverse pass know that planes were changed; a blended
    // run (0 < α < 1) is chained through the planes it moved into the apex-only sweep.
    let (graph, setup) = assisted_correction();
    let mut eval = cnets_engine::Evaluator::new();
    eval.evaluate_all(&graph, &NodeContext::default());
    let corrections = eval
        .output(&graph, "nets", "corrections")
        .and_then(Value::as_list)
        .map_or(0, |runs| {
            runs.iter()
                .filter_map(Value::as_list)
                .map(<[Value]>::len)
                .sum()
        });
    assert!(corrections > 0, "the blend changed nothing at this start");
    let check = check_gradient(&graph, &setup, &NodeContext::default()).unwrap();
    assert!(
        check.node_notes.iter().all(|(node, _)| node != "nets"),
        "the construction falls back: {:?}",
        check.node_notes
    );
    assert!(
        check.finite_differences[0].abs() > 1e-6,
        "the area does not depend on the apex: {:?}",
        check.finite_differences
    );
    assert!(
        check.largest_relative_difference < 1e-4,
        "exact {:?} vs differences {:?}: largest relative difference {:e}",
        check.exact,
        check.finite_differences,
        check.largest_relative_difference
    );
}

#[test]
fn a_fit_that_leaves_the_ratio_kink_reports_the_branch_crossing() {
    // ratio-fit starts with every ratio at ½, on the kink of the ratio → angle map; its first
    // step moves ratios off it.
    let doc = load("ratio-fit");
    let setup = doc.meta.optimization.clone().unwrap();
    let options = Options {
        max_iter: Some(3),
        ..Options::default()
    };
    let o = optimize(
        &doc.graph,
        &setup,
        &options,
        &NodeContext::default(),
        &mut |_| {},
    )
    .unwrap();
    assert!(o.branch_crossings >= 1, "{:?}", o.notes);
    let crossing = o
        .notes
        .iter()
        .find(|n| n.contains("node 'net' crossed a branch"))
        .unwrap_or_else(|| panic!("{:?}", o.notes));
    assert!(crossing.contains("at ½: 1600"), "{crossing}");
}

/// The gallery's catamaran hull fit (the file's setup: the row and column ratio handles) runs on
/// exact gradients only — the ratio mappers, the widths mapper and the ratio table have products
/// — and with the widths handles free too the gradient matches differences of the whole graph.
#[test]
fn catamaran_hull_fit_has_no_finite_differences() {
    let doc = load("catamaran-hull");
    let setup = doc.meta.optimization.clone().unwrap();
    // The reference hull is read relative to the graph's folder.
    let ctx = NodeContext::new(None, Some(cnets_tests::root().join("graphs")));
    let options = Options {
        max_iter: Some(3),
        ..Options::default()
    };
    let out = optimize(&doc.graph, &setup, &options, &ctx, &mut |_| {}).unwrap();
    assert!(out.gradients > 1);
    // The file starts with level ratio handles: exactly on a kink of the spline mapper's slope
    // limiter, where its part of the first gradient is its own central differences (what a
    // change sees); every later gradient, off the kink, is exact.
    assert_eq!(out.gradients - 1, out.exact_gradients, "{:?}", out.notes);
    let mut fd = out.finite_difference_nodes.clone();
    fd.sort();
    assert_eq!(fd, ["column_ratios", "row_ratios"], "{:?}", out.notes);
    assert!(
        out.notes
            .iter()
            .filter(|n| n.contains("finite differences"))
            .all(|n| n.contains("kink of its slope limiter")),
        "{:?}",
        out.notes
    );

    // The check off every kink: the file starts with level ratio handles at ½ (flat spline
    // pieces and the ratio → angle map's kink); here the rows rise, the columns fall, all
    // ratios above ½. The widths mapper (a bezier feeding the apex function) is free as well:
    // its four handles' v.
    let mut graph = doc.graph.clone();
    let handles = |v: [f64; 3]| {
        Value::list(
            v.iter()
                .enumerate()
                .map(|(k, y)| Value::Point(glam::DVec3::new(k as f64 * 0.5, *y, 0.0)))
                .collect(),
        )
    };
    graph
        .set_value("row_ratios", "handles", handles([0.56, 0.6, 0.66]))
        .unwrap();
    graph
        .set_value("column_ratios", "handles", handles([0.62, 0.57, 0.54]))
        .unwrap();
    let mut setup = setup;
    for k in 0..4 {
        setup.variables.push(Variable {
            input: ValuePath::parse(&format!("widths.handles[{k}][1]")).unwrap(),
            min: 0.05,
            max: 1.5,
        });
    }
    let check = check_gradient(&graph, &setup, &ctx).unwrap();
    assert_eq!(check.exact.len(), 10);
    assert!(
        check.node_notes.is_empty(),
        "finite differences for {:?}",
        check.node_notes
    );
    assert!(
        check.largest_relative_difference < 1e-5,
        "largest relative difference {:e}: exact {:?}, differences {:?}",
        check.largest_relative_difference,
        check.exact,
        check.finite_differences
    );
    assert!(check.exact[6..].iter().any(|g| g.abs() > 1e-6));
}
