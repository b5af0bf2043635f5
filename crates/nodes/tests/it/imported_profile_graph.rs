//! `graphs/imported-profile.ron` reads a profile drawn in another program (an SVG next to the
//! graph, found relative to the graph file's folder) and sweeps it into a cone-net.

use std::path::PathBuf;
use std::sync::Arc;

use cnets_engine::file::load_file;
use cnets_engine::{Evaluator, NodeContext, Value};

#[test]
fn an_imported_svg_profile_becomes_the_generatrix_of_a_cone_net() {
    let path = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../graphs/imported-profile.ron"
    ));
    let registry = Arc::new(cnets_nodes::registry());
    let doc = load_file(&path, &registry).unwrap_or_else(|e| panic!("{e:?}"));
    let graph = doc.graph;
    let mut ev = Evaluator::new();
    let ctx = NodeContext::new(None, path.parent().map(PathBuf::from));
    ev.evaluate_all(&graph, &ctx);
    for (index, node) in graph.nodes() {
        let result = ev.result_at(&graph, index).unwrap();
        assert!(
            result.outputs().is_some(),
            "{}: {:?}",
            node.id,
            result.error()
        );
    }
    // The SVG path starts at (0, 0) and rises 60 units (y flipped): scaled by 0.05, stood upright
    // about x and moved by (9, 0, 0), it runs from (9, 0, 0) up to z = 3.
    let Some(Value::Polyline(g)) = ev.output(&graph, "generatrix", "curve") else {
        panic!("generatrix polyline")
    };
    assert_eq!(g.points.len(), 8);
    assert!((g.points[0] - cnets_geometry::DVec3::new(9.0, 0.0, 0.0)).length() < 1e-12);
    assert!((g.points[7].z - 3.0).abs() < 1e-12);
    assert!(g.points.iter().all(|p| p.y.abs() < 1e-12));
    let Some(Value::QuadMesh(mesh)) = ev.output(&graph, "construct", "mesh") else {
        panic!("cone-net mesh")
    };
    assert_eq!((mesh.rows, mesh.cols), (8, 17));
}
