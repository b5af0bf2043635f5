//! Lazy outputs of the construction nodes: asked for some outputs, a node computes those (the
//! values equal an eager run's) and marks the others as not computed; in a graph, an output wired
//! later is filled in without re-running the consumers of the others.

use std::sync::Arc;

use cnets_engine::eval::{OutputMask, evaluate_node_outputs};
use cnets_engine::{Evaluator, Graph, NodeContext, Value};
use cnets_geometry::{DVec3, Polyline};

const CONSTRUCTIONS: [&str; 3] = [
    "ctube.construct",
    "cnets.construct",
    "cnets.construct_coplanar",
];

fn polyline(points: impl Iterator<Item = DVec3>) -> Value {
    Value::Polyline(Arc::new(Polyline::open(points.collect())))
}

/// A gently curved directrix and a generatrix across it (no corrections needed).
fn inputs(def: &cnets_engine::NodeDef) -> Vec<Value> {
    let directrix = polyline((0..12).map(|k| {
        let t = k as f64 / 11.0;
        DVec3::new(4.0 * t, 0.6 * (2.0 * t).sin(), 0.2 * t * t)
    }));
    let generatrix = polyline((0..9).map(|k| {
        let s = k as f64 / 8.0 - 0.5;
        DVec3::new(-0.1 * s * s, 1.5 * s, 0.8 + 0.3 * s)
    }));
    def.inputs
        .iter()
        .map(|p| match p.name.as_ref() {
            "directrix" => directrix.clone(),
            "generatrix" => generatrix.clone(),
            "apex" => Value::Number(0.9),
            "assistance" => Value::Number(0.5),
            _ => p.default.clone().unwrap_or(Value::Null),
        })
        .collect()
}

#[test]
fn each_output_alone_equals_the_eager_output() {
    let registry = cnets_nodes::registry();
    for id in CONSTRUCTIONS {
        let def = registry.get(id).unwrap();
        let ins = inputs(def);
        let ctx = NodeContext::default();
        let eager = evaluate_node_outputs(def, &ctx, &ins, OutputMask::ALL).unwrap();
        assert!(eager.missing.is_empty(), "{id}: everything computed");
        for (k, port) in def.outputs.iter().enumerate() {
            let lazy = evaluate_node_outputs(def, &ctx, &ins, OutputMask::one(k)).unwrap();
            assert_eq!(
                lazy.computed(k),
                eager.computed(k),
                "{id}.{}: same value alone",
                port.name
            );
            // Everything except the mesh (always built) and the asked output is skipped.
            for (o, other) in def.outputs.iter().enumerate() {
                let expect_missing = o != k && other.name != "mesh";
                assert_eq!(
                    lazy.missing.contains(o),
                    expect_missing,
                    "{id}: asked for {}, {} missing?",
                    port.name,
                    other.name
                );
            }
        }
    }
}

#[test]
fn a_construction_wired_by_its_mesh_only_fills_in_the_planes_when_they_are_wired() {
    let registry = Arc::new(cnets_nodes::registry());
    for id in CONSTRUCTIONS {
        let def = registry.get(id).unwrap().clone();
        let ins = inputs(&def);
        let mut g = Graph::new(registry.clone());
        g.add_node("c", id).unwrap();
        for (port, value) in def.inputs.iter().zip(&ins) {
            if !value.is_null() {
                g.set_value("c", &port.name, value.clone()).unwrap();
            }
        }
        // A consumer of the mesh only.
        g.add_node("m", "list.length").unwrap();
        g.connect("c", "mesh", "m", "list").unwrap();
        let ctx = NodeContext::default();
        let mut ev = Evaluator::new();
        let m = g.index("m").unwrap();
        ev.evaluate_outputs(&g, &[(m, OutputMask::ALL)], &ctx, &mut |_, _| {});
        assert!(
            ev.output(&g, "m", "length").is_some(),
            "{id}: mesh consumer ran"
        );
        for name in ["apices", "planes", "configurations", "quality"] {
            assert_eq!(ev.output(&g, "c", name), None, "{id}.{name} skipped");
        }
        // Wire the planes: the construction fills them in; the mesh consumer does not re-run.
        g.add_node("q", "list.length").unwrap();
        g.connect("c", "planes", "q", "list").unwrap();
        let q = g.index("q").unwrap();
        let s = ev.evaluate_outputs(
            &g,
            &[(m, OutputMask::ALL), (q, OutputMask::ALL)],
            &ctx,
            &mut |_, _| {},
        );
        assert_eq!(s.filled, 1, "{id}: filled in");
        assert_eq!(ev.runs(&g, "m"), 1, "{id}: mesh consumer kept");
        assert_eq!(ev.runs(&g, "c"), 2, "{id}: one fill-in run");
        let eager = evaluate_node_outputs(&def, &ctx, &ins, OutputMask::ALL).unwrap();
        let planes = def.output_index("planes").unwrap();
        assert_eq!(ev.output(&g, "c", "planes"), eager.computed(planes));
        let mesh = def.output_index("mesh").unwrap();
        assert_eq!(ev.output(&g, "c", "mesh"), eager.computed(mesh));
    }
}
