//! The editor at project size (issue 26, point 3): a definition of hundreds of nodes lays out only
//! the nodes in view, keeps every node's rectangle and pins (wires to nodes out of view are still
//! drawn), and a slider drag edits the graph as on a small one.

use crate::common;

use common::{harness_with, settle, temp_config};

/// A slider feeding `branches` chains of add → multiply → expression → clamp.
fn graph(branches: usize) -> String {
    let mut nodes = vec![
        r#""slider": (type: "param.number", position: (0.0, 0.0), inputs: {"value": 0.5})"#
            .to_string(),
    ];
    let mut edges = Vec::new();
    for b in 0..branches {
        let y = 120.0 * b as f64;
        for (k, (kind, inputs)) in [
            ("math.add", r#"{"b": 1.0}"#),
            ("math.multiply", r#"{"b": 1.5}"#),
            ("math.expression", r#"{"expression": "sin(x) + x^2"}"#),
            ("math.clamp", r#"{"min": -1.0, "max": 4.0}"#),
        ]
        .iter()
        .enumerate()
        {
            let x = 300.0 + 260.0 * k as f64;
            nodes.push(format!(
                r#""n{b}_{k}": (type: "{kind}", position: ({x}, {y}), inputs: {inputs})"#
            ));
        }
        edges.push(format!(r#""slider.value -> n{b}_0.a""#));
        edges.push(format!(r#""n{b}_0.result -> n{b}_1.a""#));
        edges.push(format!(r#""n{b}_1.result -> n{b}_2.x""#));
        edges.push(format!(r#""n{b}_2.result -> n{b}_3.value""#));
    }
    format!(
        "(version: 1, nodes: {{ {} }}, edges: [{}])",
        nodes.join(",\n"),
        edges.join(", ")
    )
}

#[test]
fn only_the_nodes_in_view_are_laid_out_and_every_node_keeps_its_place() {
    let dir = temp_config("project-size-files");
    let file = dir.join("scale-401.ron");
    std::fs::write(&file, graph(100)).unwrap();
    let mut h = harness_with("project-size", Some(file), temp_config("project-size"));
    settle(&mut h);
    let app = h.state();
    let total = app.doc().graph.node_count();
    assert_eq!(total, 401);
    let laid_out = app.canvas().laid_out();
    assert!(
        laid_out > 0 && laid_out < total / 3,
        "{laid_out} of {total} nodes laid out"
    );
    // Every node has its rectangle, at its position, and its pins (for wires).
    for (_, n) in app.doc().graph.nodes() {
        let r = app
            .canvas()
            .node_rect(&n.id)
            .unwrap_or_else(|| panic!("{} has a rectangle", n.id));
        assert!(
            (r.min.x - n.position[0]).abs() < 40.0 && (r.min.y - n.position[1]).abs() < 40.0,
            "{}: {r:?} at {:?}",
            n.id,
            n.position
        );
    }
    let last = "n99_3";
    assert!(
        app.canvas().pin_screen_pos(last, true, 0).is_some(),
        "a node far out of view keeps its pin"
    );
    // An edit of the slider reaches the farthest clamp.
    h.state_mut().edit(cnets_editor::edit::Edit::SetValue {
        node: "slider".into(),
        input: "value".into(),
        value: cnets_engine::Value::Number(0.75),
    });
    settle(&mut h);
    assert!(matches!(
        h.state().statuses().get(last),
        Some(cnets_editor::worker::NodeStatus::Ok { .. })
    ));
}

/// Panning and zooming the canvas changes nothing in the 3D view: its picture is blitted again,
/// not rendered again (on a software rasterizer a render of the 3D view is most of a frame).
/// Turning the camera renders it.
#[test]
fn panning_the_canvas_blits_the_3d_view_without_rendering_it_again() {
    let mut h = common::harness("project-size-pan");
    h.render().expect("a first picture");
    let first = h.state().viewport().pictures_rendered();
    assert!(first >= 1, "the 3D view was rendered ({first})");
    for k in 0..12 {
        let zoom = 0.6 + 0.03 * k as f32;
        let around = egui::pos2(40.0 * k as f32, -25.0 * k as f32);
        h.state_mut().zoom_canvas(zoom, Some(around));
        h.run_steps(1);
        h.render().expect("a picture");
    }
    assert_eq!(
        h.state().viewport().pictures_rendered(),
        first,
        "12 frames of canvas pan and zoom rendered the 3D view again"
    );
    h.state_mut().viewport_mut().orbit(0.3, 0.1);
    h.run_steps(1);
    h.render().expect("a picture");
    assert!(
        h.state().viewport().pictures_rendered() > first,
        "turning the camera renders the 3D view"
    );
}
