//! `graphs/inputs-demo.ron` drives a cone-net from sliders, curves, mappers and list tools only, and
//! follows its sliders: changing the column and row counts changes every shape downstream.

use std::path::PathBuf;
use std::sync::Arc;

use cnets_engine::file::load_file;
use cnets_engine::{Evaluator, Graph, NodeContext, Value};

fn demo_path() -> PathBuf {
    PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../graphs/inputs-demo.ron"
    ))
}

fn evaluate(graph: &Graph) -> Evaluator {
    let mut evaluator = Evaluator::new();
    let ctx = NodeContext::new(None, demo_path().parent().map(PathBuf::from));
    evaluator.evaluate_all(graph, &ctx);
    for (index, node) in graph.nodes() {
        let result = evaluator.result_at(graph, index).expect("evaluated");
        assert!(
            result.outputs().is_some(),
            "node '{}' ({}) did not run: {:?}",
            node.id,
            node.def.id,
            result.error()
        );
    }
    evaluator
}

fn shape(ev: &Evaluator, graph: &Graph) -> (usize, usize, usize, usize, usize) {
    let Some(Value::QuadMesh(mesh)) = ev.output(graph, "construct", "mesh") else {
        panic!("construct.mesh is a quad mesh")
    };
    let ratios = ev
        .output(graph, "ratios", "table")
        .unwrap()
        .as_list()
        .unwrap();
    let row_len = ratios[0].as_list().unwrap().len();
    assert!(ratios.iter().all(|r| r.as_list().unwrap().len() == row_len));
    let apex = ev
        .output(graph, "apex", "y")
        .unwrap()
        .as_list()
        .unwrap()
        .len();
    (mesh.rows, mesh.cols, ratios.len(), row_len, apex)
}

#[test]
fn the_demo_builds_a_cone_net_and_follows_its_sliders() {
    let registry = Arc::new(cnets_nodes::registry());
    let doc = load_file(&demo_path(), &registry).unwrap_or_else(|e| panic!("{e:?}"));
    let mut graph = doc.graph;
    let ev = evaluate(&graph);
    // N = 9 generatrix points, M = 15 directrix points: ratios N × (M−1), apex M−1.
    assert_eq!(shape(&ev, &graph), (9, 15, 9, 14, 14));
    let Some(Value::Record(quality)) = ev.output(&graph, "construct", "quality") else {
        panic!("quality record")
    };
    let planarity = quality
        .get("max_planarity")
        .and_then(Value::as_f64)
        .unwrap();
    assert!(planarity < 1e-9, "cone-net faces are planar: {planarity}");

    graph
        .set_value("columns", "value", Value::Integer(21))
        .unwrap();
    graph.set_value("rows", "value", Value::Integer(5)).unwrap();
    let ev = evaluate(&graph);
    assert_eq!(shape(&ev, &graph), (5, 21, 5, 20, 20));
}
