//! Ports describe themselves (issue 26, point 1): choice ports are checked when a value is set —
//! in a graph file with its line and column —, wired choices are checked by the node, stored
//! aliases keep loading, and the designer-facing ports declare their widgets and layers, so no
//! front end guesses from node ids or port names.

use std::sync::Arc;

use cnets_engine::{Evaluator, Graph, Layer, NodeContext, Registry, Value, Widget, file};

/// Evaluates every node; the error of each node that did not run, by id.
fn failures(graph: &Graph) -> Vec<(String, String)> {
    let mut eval = Evaluator::new();
    eval.evaluate_all(graph, &NodeContext::new(None, None));
    graph
        .nodes()
        .filter_map(|(k, n)| {
            let e = eval.result_at(graph, k)?.error()?;
            Some((n.id.clone(), e.to_string()))
        })
        .collect()
}

fn registry() -> Arc<Registry> {
    Arc::new(cnets_nodes::registry())
}

const CURVES: &str = r#"
        "d": (type: "curve.polyline", inputs: {"points": [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.3]]}),
        "g": (type: "curve.polyline", inputs: {"points": [[0.0, 0.0, 0.0], [0.0, 0.5, 1.0], [0.0, 1.0, 2.0]]}),
"#;

fn construct_graph(end_planes: &str) -> String {
    format!(
        r#"(version: 1, nodes: {{{CURVES}
        "net": (type: "cnets.construct", inputs: {{"end_planes": {end_planes}}}),
}}, edges: ["d.curve -> net.directrix", "g.curve -> net.generatrix"])"#
    )
}

#[test]
fn a_word_that_is_not_a_choice_fails_to_load_with_its_place_and_the_valid_words() {
    let text = construct_graph(r#""mirrored""#);
    let Err(err) = file::load_str(&text, "bad.ron", &registry()) else {
        panic!("a bad choice must not load");
    };
    let d = &err.diagnostics[0];
    let pos = d.pos.expect("the error has a line and column");
    let line = text.lines().nth(pos.line as usize - 1).unwrap();
    assert!(line.contains("\"mirrored\""), "{line:?} at {pos:?}");
    assert!(
        d.message
            .contains("'mirrored' is not one of its choices; valid: perpendicular, mirror"),
        "{}",
        d.message
    );
    assert!(
        d.message.contains("net.end_planes") || d.message.contains("'net'"),
        "{}",
        d.message
    );
}

#[test]
fn stored_aliases_and_cases_keep_loading_and_running() {
    for word in [r#""mirror""#, r#"" Mirror ""#, r#""PERPENDICULAR""#] {
        let doc = file::load_str(&construct_graph(word), "ok.ron", &registry())
            .unwrap_or_else(|e| panic!("{word}: {e}"));
        let failed = failures(&doc.graph);
        assert!(failed.is_empty(), "{word}: {failed:?}");
    }
    // A mapper kind stored as an alias (`line`, `sin`) loads and runs as before.
    for alias in ["line", "sin", "Bezier"] {
        let text = format!(
            r#"(version: 1, nodes: {{"m": (type: "mapper.graph", inputs: {{"kind": "{alias}"}})}}, edges: [])"#
        );
        let doc = file::load_str(&text, "m.ron", &registry()).unwrap();
        assert!(failures(&doc.graph).is_empty(), "{alias}");
    }
}

#[test]
fn a_wired_choice_is_checked_by_the_node_with_the_same_words() {
    let graph = |picked: usize| {
        format!(
            r#"(version: 1, nodes: {{
        "kinds": (type: "param.choice", inputs: {{"options": ["linear", "bezier", "zigzag"], "index": {picked}}}),
        "m": (type: "mapper.graph", inputs: {{"count": 5}}),
}}, edges: ["kinds.value -> m.kind"])"#
        )
    };
    let doc = file::load_str(&graph(1), "g.ron", &registry()).unwrap();
    assert!(failures(&doc.graph).is_empty());
    let doc = file::load_str(&graph(2), "g.ron", &registry()).unwrap();
    let message = failures(&doc.graph)
        .iter()
        .find(|(id, _)| id == "m")
        .map(|(_, m)| m.clone())
        .expect("the mapper fails on a wired word that is not a kind");
    assert!(
        message.contains("'zigzag' is not one of its choices"),
        "{message}"
    );
    assert!(
        message.contains("valid: linear, bezier, parabola"),
        "{message}"
    );
}

#[test]
fn every_choice_ports_default_is_one_of_its_words() {
    let registry = registry();
    let mut choice_ports = 0;
    for def in registry.iter() {
        for p in &def.inputs {
            let Some(c) = &p.choices else { continue };
            choice_ports += 1;
            assert!(!c.options.is_empty(), "{}.{}", def.id, p.name);
            // A drop-down on the node, or the node's own widget (a mapper's kind).
            assert!(
                matches!(p.widget(), Widget::Choice | Widget::Hidden),
                "{}.{}",
                def.id,
                p.name
            );
            if let Some(Value::Text(t)) = &p.default {
                assert!((c.accepts)(t), "{}.{}: default {t:?}", def.id, p.name);
            }
            for o in c.options {
                assert!((c.accepts)(o), "{}.{}: {o}", def.id, p.name);
            }
        }
    }
    // end_planes ×3, direction ×3, kind, method, scheme, rule, two formats, item_type.
    assert!(choice_ports >= 13, "{choice_ports} choice ports");
}

#[test]
fn designer_facing_ports_declare_their_widgets_and_layers() {
    let registry = registry();
    let widget = |id: &str, port: &str| {
        let def = registry.get(id).unwrap();
        def.inputs[def.input_index(port).unwrap()].widget()
    };
    assert_eq!(widget("param.number", "value"), Widget::Slider);
    assert_eq!(widget("param.integer", "value"), Widget::Slider);
    assert_eq!(widget("param.boolean", "value"), Widget::Toggle);
    assert_eq!(widget("param.choice", "index"), Widget::Choice);
    assert_eq!(widget("param.point", "value"), Widget::PointHandles);
    assert_eq!(widget("param.points", "points"), Widget::PointHandles);
    assert_eq!(widget("mapper.graph", "handles"), Widget::MapperHandles);
    // Picked in the mapper widget, not a second drop-down on the node.
    assert_eq!(widget("mapper.graph", "kind"), Widget::Hidden);
    assert_eq!(widget("io.read_mesh", "path"), Widget::FilePath);
    assert_eq!(widget("io.read_polylines", "path"), Widget::FilePath);
    assert_eq!(widget("io.export_svg", "name"), Widget::OutputName);
    assert_eq!(widget("cnets.construct", "end_planes"), Widget::Choice);
    let layer = |id: &str, port: &str| {
        let def = registry.get(id).unwrap();
        def.outputs[def.output_index(port).unwrap()].hint.layer
    };
    assert_eq!(
        layer("cnets.conical_support", "mesh"),
        Some(Layer::Supports)
    );
    assert_eq!(layer("pq.parallel_support", "mesh"), Some(Layer::Supports));
    assert_eq!(
        layer("cnets.support_strips", "strips"),
        Some(Layer::Supports)
    );
    assert_eq!(layer("cnets.torsion_free_axes", "axes"), Some(Layer::Axes));
    assert_eq!(layer("cnets.construct", "apices"), Some(Layer::Apices));
    assert_eq!(layer("pq.unroll_strips", "outlines"), Some(Layer::Unrolled));
    assert_eq!(layer("pq.unroll_strips", "folds"), Some(Layer::Unrolled));
    assert_eq!(layer("pq.unroll_strips", "marks"), Some(Layer::Unrolled));
    assert_eq!(layer("fab.nest", "outlines"), Some(Layer::Unrolled));
    assert_eq!(layer("cnets.construct", "mesh"), None);
    // Display names come from the nodes (Grasshopper's names where a designer expects them).
    assert_eq!(
        registry.get("param.number").unwrap().name(),
        "Number slider"
    );
    assert_eq!(
        registry.get("curve.closest_point").unwrap().name(),
        "Closest point"
    );
}

#[test]
fn every_shipped_graph_loads_with_choices_checked() {
    let graphs = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../graphs");
    let mut n = 0;
    for entry in std::fs::read_dir(&graphs).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "ron") {
            file::load_file(&path, &registry()).unwrap_or_else(|e| panic!("{e}"));
            n += 1;
        }
    }
    assert!(n >= 15, "{n} graphs");
}
