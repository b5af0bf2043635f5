//! `Graph::replace_def` (a cluster rebuilt from its edited subgraph keeps its place, values and the
//! wires whose ports still exist) and `Cluster::inspect` (the instance's inner results).

use crate::common;

use std::sync::Arc;

use cnets_engine::cluster::{Cluster, ClusterSource, make_cluster};
use cnets_engine::file::{GraphMeta, load_str, to_ron};
use cnets_engine::{Evaluator, NodeContext, Value};

const MAIN: &str = r#"(
    version: 1,
    nodes: {
        "v": (type: "t.num", inputs: {"value": 3.0}),
        "a": (type: "t.add", inputs: {"b": 1.0}),
        "b": (type: "t.add", inputs: {"b": 2.0}),
        "after": (type: "t.add"),
        "last": (type: "t.sign"),
    },
    edges: ["v.out -> a.a", "a.sum -> b.a", "b.sum -> after.a", "a.sum -> after.b", "after.sum -> last.x"],
)"#;

#[test]
fn a_rebuilt_cluster_keeps_its_place_and_the_wires_whose_ports_remain() {
    let registry = common::registry();
    let mut g = load_str(MAIN, "main", &registry).unwrap().graph;
    let cluster = make_cluster(&mut g, &["a", "b"], "c").unwrap();
    let before = to_ron(&g, &GraphMeta::default());
    let mut ev = Evaluator::new();
    ev.evaluate_all(&g, &NodeContext::default());
    let first = ev.output(&g, "last", "out").cloned().unwrap();

    // The same subgraph: the text is unchanged, the node keeps its place in the file.
    let same = Cluster::new(
        ClusterSource::Inline,
        cluster.template.clone(),
        cluster.meta.clone(),
        None,
    )
    .unwrap();
    let dropped = g.replace_def("c", Arc::new(same.node_def())).unwrap();
    assert!(dropped.is_empty());
    assert_eq!(to_ron(&g, &GraphMeta::default()), before);

    // Rename output 'sum' (b's) inside: its outer wire is dropped and reported; the other stays.
    let mut sub = cluster.template.clone();
    let out = sub
        .nodes()
        .find(|(_, n)| n.value_of("name") == Some(&Value::text("sum")))
        .map(|(_, n)| n.id.clone())
        .unwrap();
    sub.set_value(&out, "name", Value::text("total")).unwrap();
    sub.set_value("b", "b", Value::Number(5.0)).unwrap();
    let edited = Cluster::new(ClusterSource::Inline, sub, cluster.meta.clone(), None).unwrap();
    let dropped = g.replace_def("c", Arc::new(edited.node_def())).unwrap();
    assert_eq!(dropped.len(), 1, "{dropped:?}");
    assert_eq!(dropped[0].from, "c");
    assert_eq!(dropped[0].output, "sum");
    assert!(g.wires().iter().any(|w| w.from == "v" && w.to == "c"));
    assert!(g.node("c").unwrap().def.output_index("total").is_some());
    let text = to_ron(&g, &GraphMeta::default());
    let order = |t: &str| -> Vec<String> {
        t.lines()
            .filter(|l| l.starts_with("        \"") && l.ends_with("\": ("))
            .map(str::to_string)
            .collect()
    };
    assert_eq!(
        order(&text),
        order(&before),
        "the nodes keep their order in the file"
    );
    assert!(order(&text).len() >= 4);
    // The evaluator sees the new definition.
    g.connect("c", "total", "after", "a").unwrap();
    ev.evaluate_all(&g, &NodeContext::default());
    let c = Cluster::of(&g.node("c").unwrap().def).unwrap();
    let inner = c.inspect(|inner, ev| ev.output(inner, "b", "sum").cloned());
    assert_eq!(inner, Some(Value::Number(3.0 + 1.0 + 5.0)), "inner results");
    let _ = first;
}

#[test]
fn values_are_kept_by_name_and_dropped_when_the_type_no_longer_takes_them() {
    let registry = common::registry();
    let mut g = load_str(MAIN, "main", &registry).unwrap().graph;
    let def = g.node("b").unwrap().def.clone();
    // Same def: values and wires stay.
    assert!(g.replace_def("b", def).unwrap().is_empty());
    assert_eq!(
        g.node("b").unwrap().value_of("b"),
        Some(&Value::Number(2.0))
    );
    // A sign node has input 'x' only: b's value 'b' goes, its wires go (no 'a' input, no 'sum').
    let sign = registry.get("t.sign").unwrap().clone();
    let dropped = g.replace_def("b", sign).unwrap();
    assert_eq!(dropped.len(), 2);
    assert_eq!(g.node("b").unwrap().value(0), None);
    assert!(
        g.replace_def("nope", registry.get("t.sign").unwrap().clone())
            .is_err()
    );
}
