//! `measure.surface_distance`: its figure after a fit against a dense, independent measure (the
//! gallery's catamaran hull fitted to its reference), and its memory budget declared before it
//! builds anything (docs/optimizer.md, Sampling and accuracy).

use std::path::Path;
use std::sync::Arc;

use cnets_engine::budget::format_bytes;
use cnets_engine::eval::evaluate_node;
use cnets_engine::optimize::{Options, optimize};
use cnets_engine::{Evaluator, MemoryBudget, NodeContext, Value};
use cnets_geometry::mesh_query::MeshQuery;
use cnets_geometry::surface_fit::{Directions, working_bytes};
use cnets_geometry::{DVec3, PolygonMesh};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .parent()
        .unwrap()
}

fn mesh_of(v: &Value) -> PolygonMesh {
    match v {
        Value::Mesh(m) => (**m).clone(),
        Value::QuadMesh(q) => PolygonMesh::from(&**q),
        other => panic!("a mesh, not {}", other.type_name()),
    }
}

/// The RMS distance both ways, measured densely and independently of the node: every fan
/// triangle split `n` times per edge and sampled at its sub-triangles' centroids (the midpoint
/// rule), closest points from parry's hierarchy ([`MeshQuery`]): √(½ (mean d² to + mean d² from)).
fn dense_rms(mesh: &PolygonMesh, reference: &PolygonMesh, n: usize) -> f64 {
    let one = |from: &PolygonMesh, to: &PolygonMesh| {
        let query = MeshQuery::new(to).unwrap();
        let v = &from.vertices;
        let nf = n as f64;
        let (mut points, mut weights) = (Vec::new(), Vec::new());
        for f in from.faces() {
            for c in 1..f.len() - 1 {
                let (a, b, cc) = (v[f[0] as usize], v[f[c] as usize], v[f[c + 1] as usize]);
                let area = 0.5 * (b - a).cross(cc - a).length();
                let at = |x: f64, y: f64| a + (b - a) * (x / nf) + (cc - a) * (y / nf);
                for i in 0..n {
                    for j in 0..n - i {
                        let (i, j) = (i as f64, j as f64);
                        points.push((at(i, j) + at(i + 1.0, j) + at(i, j + 1.0)) / 3.0);
                        weights.push(area);
                        if i + j + 2.0 <= nf {
                            points.push(
                                (at(i + 1.0, j) + at(i, j + 1.0) + at(i + 1.0, j + 1.0)) / 3.0,
                            );
                            weights.push(area);
                        }
                    }
                }
            }
        }
        let hits = query.closest_all(&points).unwrap();
        let total: f64 = weights.iter().sum();
        hits.iter()
            .zip(&weights)
            .map(|(h, w)| w * h.distance * h.distance)
            .sum::<f64>()
            / total
    };
    (0.5 * (one(mesh, reference) + one(reference, mesh))).sqrt()
}

/// Fits a catamaran graph (the gallery's, or a variant of its text) as `cnets optimize` does and
/// prints and checks the node's RMS against the dense measure of the fitted hull.
fn fit_and_compare(label: &str, text: &str) {
    let registry = Arc::new(cnets_nodes::registry());
    let doc = cnets_engine::file::load_str(text, "catamaran-hull.ron", &registry)
        .unwrap_or_else(|e| panic!("{e}"));
    let setup = doc.meta.optimization.clone().expect("a stored setup");
    assert_eq!(setup.objective.to_string(), "fit.symmetric");
    let ctx = NodeContext::new(None, Some(root().join("graphs")));
    let out = optimize(&doc.graph, &setup, &Options::default(), &ctx, &mut |_| {})
        .unwrap_or_else(|e| panic!("{e}"));
    let mut eval = Evaluator::new();
    eval.evaluate_all(&out.graph, &ctx);
    let value = |node: &str, port: &str| {
        eval.output(&out.graph, node, port)
            .unwrap_or_else(|| panic!("{node}.{port}"))
            .clone()
    };
    let node = value("fit", "symmetric").as_f64().unwrap().sqrt();
    let (hull, reference) = (
        mesh_of(&value("whole", "mesh")),
        mesh_of(&value("reference_hull", "mesh")),
    );
    let dense = dense_rms(&hull, &reference, 24);
    eprintln!(
        "{label}: objective {:.3e} -> {:.3e} in {} iterations; RMS {:.3} cm (node), {:.3} cm \
         (dense, 24 per edge), {:+.1} %",
        out.start,
        out.objective,
        out.iterations,
        100.0 * node,
        100.0 * dense,
        100.0 * (node / dense - 1.0)
    );
    assert!(out.objective < 0.2 * out.start, "{label}: the fit worked");
    assert!(
        (node / dense - 1.0).abs() <= 0.05,
        "{label}: {node} vs {dense}"
    );
}

#[test]
fn the_fitted_catamaran_hull_reads_within_five_percent_of_a_dense_measure() {
    let text = std::fs::read_to_string(root().join("graphs/catamaran-hull.ron")).unwrap();
    // The gallery's setup: 6 ratio handles.
    fit_and_compare("catamaran, 6 handles", &text);
    // A freer fit that can bend the hull much closer to the reference: the whole ratio table
    // (9 × 30) and every coordinate of the section's points, 200 iterations.
    let table = vec![format!("[{}]", vec!["0.5"; 30].join(", ")); 9].join(", ");
    let free = text
        .replace(
            "            (input: \"column_ratios.handles[2][1]\", min: 0.2, max: 0.8),\n",
            "            (input: \"column_ratios.handles[2][1]\", min: 0.2, max: 0.8),\n            \
             (input: \"section.points\", min: -0.5, max: 2.5),\n            \
             (input: \"hull.ratios\", min: 0.2, max: 0.8),\n",
        )
        .replace("max_iter: 40", "max_iter: 200")
        .replace(
            "            type: \"cnets.construct\",\n            position: (2099.0, 230.0),\n            \
             preview: false,\n",
            &format!(
                "            type: \"cnets.construct\",\n            position: (2099.0, 230.0),\n            \
                 preview: false,\n            inputs: {{ \"ratios\": [{table}] }},\n"
            ),
        )
        .replace("        \"ratios.table -> hull.ratios\",\n", "");
    assert!(free.contains("hull.ratios\", min") && !free.contains("-> hull.ratios"));
    fit_and_compare("catamaran, ratio table and section free", &free);
}

/// A wavy n × n grid of quads over [0, 1]² lifted by `z`.
fn grid(n: usize, z: f64) -> Value {
    let mut vertices = Vec::new();
    for i in 0..=n {
        for j in 0..=n {
            let (x, y) = (j as f64 / n as f64, i as f64 / n as f64);
            vertices.push(DVec3::new(x, y, z + 0.1 * (5.0 * x).sin() * y));
        }
    }
    let id = |i: usize, j: usize| (i * (n + 1) + j) as u32;
    let faces: Vec<Vec<u32>> = (0..n)
        .flat_map(|i| {
            (0..n).map(move |j| vec![id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j)])
        })
        .collect();
    Value::Mesh(Arc::new(PolygonMesh::from_faces(vertices, &faces).unwrap()))
}

fn run(ctx: &NodeContext, mesh: &Value, reference: &Value) -> Result<Vec<Value>, String> {
    let registry = cnets_nodes::registry();
    let def = registry.get("measure.surface_distance").unwrap();
    let inputs = vec![mesh.clone(), reference.clone(), Value::Integer(2)];
    evaluate_node(def, ctx, &inputs)
        .map(|o| o.values)
        .map_err(|e| e.to_string())
}

#[test]
fn the_node_declares_its_bytes_before_building_and_fails_over_the_budget() {
    let (mesh, reference) = (grid(60, 0.0), grid(80, 0.05));
    // Both directions (every output wanted): the larger direction's fan triangles, vertex mask and
    // hierarchy — 7 200 and 12 800 triangles, 3 721 and 6 561 vertices: towards the reference,
    // the mesh's triangles (12 bytes), its vertex mask (1) and the reference's triangles and
    // hierarchy (112).
    let needed = working_bytes(7_200, 3_721, 12_800, 6_561, Directions::BOTH, false);
    assert_eq!(needed, 12 * 7_200 + 3_721 + 112 * 12_800);
    for limit in [10_000, needed / 2, needed - 1] {
        let ctx = NodeContext::default().with_budget(MemoryBudget::new(limit));
        let e = run(&ctx, &mesh, &reference).expect_err("over the budget");
        assert!(
            e.contains(
                "the surface distance between a mesh of 7200 triangles and a reference of \
                        12800 triangles"
            ) && e.contains(&format!("needs {}", format_bytes(needed)))
                && e.contains(&format!("the limit is {}", format_bytes(limit))),
            "{e}"
        );
    }
    let ctx = NodeContext::default().with_budget(MemoryBudget::new(needed));
    let out = run(&ctx, &mesh, &reference).expect("within the budget");
    let symmetric = out[2].as_f64().unwrap();
    assert!(symmetric > 0.0 && symmetric.is_finite());
}
