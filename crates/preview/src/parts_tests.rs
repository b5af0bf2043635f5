//! A joined structure's figures name each net it was joined from (`node.output: part`).

use std::sync::Arc;

use cnets_engine::{Evaluator, Graph, NodeContext, Value};
use cnets_geometry::{DVec3, PolygonMesh, QuadGrid};

use crate::{ColorMode, PreviewOptions, build_preview};

/// A `3 × 3` grid over `[x0, x0 + 2] × [0, 2]` with its middle vertex raised by `bump`.
fn net(x0: f64, bump: f64) -> PolygonMesh {
    let mut vertices: Vec<DVec3> = (0..9)
        .map(|k| DVec3::new(x0 + (k % 3) as f64, (k / 3) as f64, 0.0))
        .collect();
    vertices[4].z += bump;
    PolygonMesh::from(&QuadGrid::new(3, 3, vertices).unwrap())
}

#[test]
fn a_joined_structures_figures_name_each_of_its_nets() {
    let mut g = Graph::new(Arc::new(cnets_nodes::registry()));
    g.add_node("structure", "mesh.join").unwrap();
    let meshes = Value::list(vec![Value::from(net(0.0, 0.0)), Value::from(net(2.0, 0.5))]);
    g.set_value("structure", "meshes", meshes).unwrap();
    let names = Value::list(vec![Value::text("flat"), Value::text("bumpy")]);
    g.set_value("structure", "names", names).unwrap();
    g.set_value("structure", "weld", Value::Number(1e-9))
        .unwrap();
    let mut eval = Evaluator::new();
    eval.evaluate_all(&g, &NodeContext::new(None, None));
    let mut options = PreviewOptions::default();
    options.color_mode = ColorMode::Planarity;
    let s = build_preview(&g, &eval, &options).stats;
    let names: Vec<&str> = s.meshes.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(
        names,
        ["structure.mesh: flat", "structure.mesh: bumpy"],
        "{s:?}"
    );
    assert_eq!(s.meshes[0].faces, 4);
    assert_eq!(s.meshes[0].vertices, 9);
    assert_eq!(s.meshes[0].max_planarity, Some(0.0));
    assert!(s.meshes[1].max_planarity.unwrap() > 0.1, "{s:?}");
    assert_eq!(
        s.max_planarity_mesh.as_deref(),
        Some("structure.mesh: bumpy")
    );
    // The welded seam's three vertices belong to both nets; the scene counts them once.
    assert_eq!(s.vertices, 15);
}
