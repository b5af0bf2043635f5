//! `graphs/fabrication-demo.ron` runs end to end: a cone-net, its axes and two support layers,
//! unrolled strips, and all four file exports written into the output directory.

use crate::fab_support;

use std::path::PathBuf;
use std::sync::Arc;

use cnets_engine::file::load_file;
use cnets_engine::{Evaluator, Value};
use fab_support::*;

#[test]
fn the_fabrication_demo_graph_writes_every_file() {
    let path = repo_root().join("graphs/fabrication-demo.ron");
    let registry = Arc::new(cnets_nodes::registry());
    let doc = load_file(&path, &registry).unwrap_or_else(|e| panic!("{e:?}"));
    let graph = doc.graph;
    let out = scratch("demo-graph");
    let ctx = ctx_in(&out);
    let mut ev = Evaluator::new();
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
    let Some(Value::QuadMesh(net)) = ev.output(&graph, "net", "mesh") else {
        panic!("cone-net")
    };
    let Some(Value::QuadMesh(conical)) = ev.output(&graph, "conical", "mesh") else {
        panic!("conical layer")
    };
    assert_eq!((conical.rows, conical.cols), (net.rows, net.cols));
    let err = ev
        .output(&graph, "strips", "max_length_error")
        .and_then(Value::as_f64)
        .unwrap();
    assert!(err <= 1e-9, "{err}");
    let mut written: Vec<String> = entries(&out);
    written.sort();
    assert_eq!(
        written,
        [
            "fabrication-demo-strips.dxf",
            "fabrication-demo-strips.svg",
            "fabrication-demo.glb",
            "fabrication-demo.obj"
        ]
    );
    for name in &written {
        let p: PathBuf = out.join(name);
        assert!(
            std::fs::metadata(&p).unwrap().len() > 100,
            "{name} is too small"
        );
    }
    std::fs::remove_dir_all(&out).unwrap();
}
