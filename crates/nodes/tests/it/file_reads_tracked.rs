//! Files read by nodes are tracked: a file rewritten by another program re-runs the node that read
//! it at the next evaluation (and its dependents), though nobody edited the graph; an unchanged
//! file re-runs nothing. Also through a cluster.

use std::path::PathBuf;
use std::sync::Arc;

use cnets_engine::{Evaluator, Graph, NodeContext, Value};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("cnets-reads-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn length(ev: &Evaluator, g: &Graph) -> f64 {
    let v = ev.output(g, "len", "length").expect("length evaluated");
    v.as_list()
        .map_or_else(|| v.as_f64(), |l| l[0].as_f64())
        .unwrap()
}

#[test]
fn a_rewritten_file_re_runs_its_reader_and_dependents_only() {
    let dir = scratch("polylines");
    std::fs::write(dir.join("p.csv"), "0,0,0\n3,0,0\n").unwrap();
    let mut g = Graph::new(Arc::new(cnets_nodes::registry()));
    g.add_node("read", "io.read_polylines").unwrap();
    g.set_value("read", "path", Value::text("p.csv")).unwrap();
    g.add_node("len", "curve.length").unwrap();
    g.connect("read", "curves", "len", "curve").unwrap();
    g.add_node("other", "math.add").unwrap();
    let ctx = NodeContext::new(None, Some(dir.clone()));
    let mut ev = Evaluator::new();
    ev.evaluate_all(&g, &ctx);
    assert_eq!(length(&ev, &g), 3.0);
    assert_eq!(ev.reads(&g, "read").len(), 1);

    // Nothing changed: nothing runs.
    let summary = ev.evaluate_all(&g, &ctx);
    assert_eq!(summary.ran, 0);

    // Same length, same second: only the content hash tells.
    std::fs::write(dir.join("p.csv"), "0,0,0\n4,0,0\n").unwrap();
    let summary = ev.evaluate_all(&g, &ctx);
    assert_eq!(
        summary.ran, 2,
        "the reader and its dependent re-ran, not the other node"
    );
    assert_eq!(length(&ev, &g), 4.0);
    assert_eq!(ev.runs(&g, "read"), 2);
    assert_eq!(ev.runs(&g, "other"), 1);

    // A broken file fails the node; fixing it re-runs it again.
    std::fs::write(dir.join("p.csv"), "0,0,0\nbad\n").unwrap();
    ev.evaluate_all(&g, &ctx);
    assert!(ev.output(&g, "len", "length").is_none());
    std::fs::write(dir.join("p.csv"), "0,0,0\n0,5,0\n").unwrap();
    ev.evaluate_all(&g, &ctx);
    assert_eq!(length(&ev, &g), 5.0);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_file_read_inside_a_cluster_re_runs_the_cluster() {
    let dir = scratch("cluster");
    std::fs::write(dir.join("p.csv"), "0,0,0\n1,0,0\n").unwrap();
    std::fs::write(
        dir.join("reader.ron"),
        r#"(
    version: 1,
    nodes: {
        "read": (type: "io.read_polylines", inputs: {"path": "p.csv"}),
        "out": (type: "graph.output", inputs: {"name": "curves", "type": "list<polyline>"}),
    },
    edges: ["read.curves -> out.value"],
)"#,
    )
    .unwrap();
    std::fs::write(
        dir.join("main.ron"),
        r#"(
    version: 1,
    nodes: {
        "c": (type: "cluster", source: "reader.ron"),
        "len": (type: "curve.length"),
    },
    edges: ["c.curves -> len.curve"],
)"#,
    )
    .unwrap();
    let registry = Arc::new(cnets_nodes::registry());
    let g = cnets_engine::file::load_file(&dir.join("main.ron"), &registry)
        .unwrap_or_else(|e| panic!("{e:?}"))
        .graph;
    let ctx = NodeContext::new(None, Some(dir.clone()));
    let mut ev = Evaluator::new();
    ev.evaluate_all(&g, &ctx);
    assert_eq!(length(&ev, &g), 1.0);
    std::fs::write(dir.join("p.csv"), "0,0,0\n2,0,0\n").unwrap();
    ev.evaluate_all(&g, &ctx);
    assert_eq!(length(&ev, &g), 2.0);
    std::fs::remove_dir_all(&dir).unwrap();
}
