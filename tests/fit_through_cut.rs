//! Fitting a hull through `mesh.cut_by_plane` and `mesh.mirror` (issue 32): the cut and the mirror
//! have exact derivatives, so the fit with them in the graph costs about what the fit without them
//! does (before, every gradient took finite differences over all of the cut's input coordinates:
//! 60× slower). The reference is generated in the graph: the same construction with other ratios.

use std::time::{Duration, Instant};

use cnets_engine::NodeContext;
use cnets_engine::file::load_str;
use cnets_engine::optimize::{Options, Outcome, check_gradient, optimize};
use cnets_tests::registry;

/// A hull (directrix along x, a half section from the keel up) whose 6 ratio handles are fitted
/// to a target built the same way with other handles; both are mirrored in the plane y = 0.3
/// before they are measured, and with `cut` first cut by it (trimming the keel: edges cross it).
fn graph(cut: bool) -> String {
    let handles = |name: &str, v: [f64; 3], count: usize| {
        format!(
            r#""{name}": (type: "mapper.graph", inputs: {{ "kind": "spline", "count": {count},
                "handles": [(0.0, {}, 0.0), (0.5, {}, 0.0), (1.0, {}, 0.0)] }}),"#,
            v[0], v[1], v[2]
        )
    };
    let (net, target) = if cut {
        ("net_half.mesh", "target_half.mesh")
    } else {
        ("net.mesh", "target.mesh")
    };
    format!(
        r#"(
    version: 1,
    name: "hull fit",
    optimization: (
        objective: "fit.symmetric",
        variables: [
            (input: "rows.handles[0][1]", min: 0.2, max: 0.8),
            (input: "rows.handles[1][1]", min: 0.2, max: 0.8),
            (input: "rows.handles[2][1]", min: 0.2, max: 0.8),
            (input: "columns.handles[0][1]", min: 0.2, max: 0.8),
            (input: "columns.handles[1][1]", min: 0.2, max: 0.8),
            (input: "columns.handles[2][1]", min: 0.2, max: 0.8),
        ],
        max_iter: 60,
    ),
    nodes: {{
        "directrix": (type: "curve.spline", inputs: {{ "method": "natural", "count": 21,
            "points": [(0.0, 0.0, 2.0), (4.0, 0.0, 2.05), (6.4, 0.0, 2.2), (8.0, 0.0, 2.6)] }}),
        "section": (type: "curve.spline", inputs: {{ "count": 9,
            "points": [(0.0, 0.0, 0.0), (0.0, 0.55, 0.25), (0.0, 0.95, 0.9), (0.0, 1.15, 1.6), (0.0, 1.2, 2.0)] }}),
        {}
        {}
        {}
        {}
        "ratios": (type: "list.table"),
        "target_ratios": (type: "list.table"),
        "net": (type: "cnets.construct"),
        "target": (type: "cnets.construct"),
        "plane": (type: "vector.plane", inputs: {{ "origin": (0.0, 0.3, 0.0), "normal": (0.0, 1.0, 0.0) }}),
        "net_half": (type: "mesh.cut_by_plane"),
        "net_whole": (type: "mesh.mirror"),
        "target_half": (type: "mesh.cut_by_plane"),
        "target_whole": (type: "mesh.mirror"),
        "fit": (type: "measure.surface_distance"),
    }},
    edges: [
        "rows.y -> ratios.rows", "columns.y -> ratios.columns",
        "target_rows.y -> target_ratios.rows", "target_columns.y -> target_ratios.columns",
        "directrix.curve -> net.directrix", "section.curve -> net.generatrix", "ratios.table -> net.ratios",
        "directrix.curve -> target.directrix", "section.curve -> target.generatrix",
        "target_ratios.table -> target.ratios",
        "net.mesh -> net_half.mesh", "plane.plane -> net_half.plane",
        "{net} -> net_whole.mesh", "plane.plane -> net_whole.plane",
        "target.mesh -> target_half.mesh", "plane.plane -> target_half.plane",
        "{target} -> target_whole.mesh", "plane.plane -> target_whole.plane",
        "net_whole.mesh -> fit.mesh", "target_whole.mesh -> fit.reference",
    ],
)"#,
        handles("rows", [0.5, 0.5, 0.5], 9),
        handles("columns", [0.5, 0.5, 0.5], 20),
        handles("target_rows", [0.42, 0.61, 0.47], 9),
        handles("target_columns", [0.56, 0.44, 0.63], 20),
    )
}

fn fit(cut: bool) -> (Outcome, Duration) {
    let doc = load_str(&graph(cut), "hull-fit.ron", &registry()).unwrap_or_else(|e| panic!("{e}"));
    let setup = doc.meta.optimization.clone().unwrap();
    let t = Instant::now();
    let out = optimize(
        &doc.graph,
        &setup,
        &Options::default(),
        &NodeContext::default(),
        &mut |_| {},
    )
    .unwrap();
    (out, t.elapsed())
}

#[test]
fn the_gradient_through_cut_and_mirror_is_exact() {
    let doc = load_str(&graph(true), "hull-fit.ron", &registry()).unwrap_or_else(|e| panic!("{e}"));
    let mut g = doc.graph;
    // Off the kinks of the ratio map at ½ and of the mapper's slope limiter (level handles, an
    // end slope at its clamp: 0.46, 0.55, 0.52 is on one).
    for (node, v) in [
        ("rows", [0.46, 0.55, 0.50]),
        ("columns", [0.53, 0.47, 0.58]),
    ] {
        let handles = cnets_engine::Value::list(
            v.iter()
                .enumerate()
                .map(|(k, y)| cnets_engine::Value::Point(glam::DVec3::new(k as f64 * 0.5, *y, 0.0)))
                .collect(),
        );
        g.set_value(node, "handles", handles).unwrap();
    }
    let check =
        check_gradient(&g, &doc.meta.optimization.unwrap(), &NodeContext::default()).unwrap();
    assert!(
        check.largest_relative_difference <= 1e-6,
        "largest relative difference {:e}: exact {:?}, differences {:?}",
        check.largest_relative_difference,
        check.exact,
        check.finite_differences
    );
    // Neither the cut nor the mirror falls back to finite differences.
    for (node, why) in &check.node_notes {
        assert!(!node.starts_with("net_"), "{node}: {why}");
    }
}

#[test]
fn a_fit_with_the_cut_costs_at_most_twice_the_node_runs_of_the_same_fit_without() {
    // The least of three runs each, alternating (the machine is shared).
    let (mut with, mut without) = (Duration::MAX, Duration::MAX);
    let (mut last_with, mut last_without) = (None, None);
    for _ in 0..3 {
        let (out, t) = fit(false);
        without = without.min(t);
        last_without = Some(out);
        let (out, t) = fit(true);
        with = with.min(t);
        last_with = Some(out);
    }
    let (a, b) = (last_with.unwrap(), last_without.unwrap());
    eprintln!(
        "with the cut: {:.3e} -> {:.3e}, {} iterations, {} evaluations, {} node runs, {:.3} s",
        a.start,
        a.objective,
        a.iterations,
        a.evaluations,
        a.node_runs,
        with.as_secs_f64()
    );
    eprintln!(
        "without the cut: {:.3e} -> {:.3e}, {} iterations, {} evaluations, {} node runs, {:.3} s",
        b.start,
        b.objective,
        b.iterations,
        b.evaluations,
        b.node_runs,
        without.as_secs_f64()
    );
    for out in [&a, &b] {
        assert!(
            out.objective < 1e-3 * out.start,
            "{} -> {}",
            out.start,
            out.objective
        );
        assert!(
            !out.notes
                .iter()
                .any(|n| n.contains("net_half") || n.contains("net_whole")),
            "{:?}",
            out.notes
        );
    }
    // The speed is a figure (issue 30: the time ratio measured 0.8–1.1 under load, and a 2× bound
    // on it failed on a busy machine). What is asserted is the work, node runs with any finite
    // differences included (3 411 with the cut, 3 236 without), and a time ratio of 10, ≥ 9× the
    // measured one, that only a fallback to finite differences (60× slower) reaches.
    eprintln!(
        "time with / without the cut: {:.2}",
        with.as_secs_f64() / without.as_secs_f64()
    );
    assert!(
        a.node_runs <= 2 * b.node_runs,
        "node runs with the cut {}, without {}",
        a.node_runs,
        b.node_runs
    );
    assert!(
        with <= without * 10,
        "with the cut {:.3} s, without {:.3} s",
        with.as_secs_f64(),
        without.as_secs_f64()
    );
}
