//! Everyday fluency on the canvas (issue 26, point 5): numbers shown with their significant
//! digits and never clipped, labels ellipsised with the full text in a tooltip, the first click
//! after a wire drag, and the hit area of a triangle pin.

use crate::common;

use cnets_editor::EditorApp;
use cnets_editor::worker::NodeStatus;
use common::{harness, settle};
use egui::accesskit::Role;
use egui::{Pos2, Rect};
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};

type H = Harness<'static, EditorApp>;

fn set_number(h: &mut H, node: &str, input: &str, x: f64) {
    h.state_mut()
        .edit_graph(|g, _| {
            g.set_value(node, input, cnets_engine::Value::Number(x))
                .map(|_| ())
                .map_err(|e| e.to_string())
        })
        .unwrap();
}

fn show_node(h: &mut H, id: &str) {
    h.run_steps(2);
    let centre = h.state().canvas().node_rect(id).expect("drawn").center();
    h.state_mut().zoom_canvas(1.0, Some(centre));
    h.run_steps(4);
}

/// A widget's rectangle on the screen (widgets on the canvas have canvas coordinates).
fn on_screen(h: &H, canvas: Rect) -> Rect {
    let c = &h.state().canvas();
    Rect::from_min_max(c.to_screen(canvas.min), c.to_screen(canvas.max))
}

fn output_summary(h: &H, node: &str, k: usize) -> String {
    match &h.state().statuses()[node] {
        NodeStatus::Ok { outputs, .. } => outputs[k].clone(),
        other => panic!("{other:?}"),
    }
}

/// A click of the primary button, a frame for each step.
fn click(h: &mut H, at: Pos2) {
    h.hover_at(at);
    h.run_steps(1);
    h.drag_at(at);
    h.run_steps(1);
    h.drop_at(at);
    h.run_steps(2);
}

#[test]
fn numbers_show_their_significant_digits_unclipped() {
    let mut h = harness("numbers");
    // Multiply: the output is the product, the inputs are number drag values.
    let id = h
        .state_mut()
        .add_node("math.multiply", [0.0, 720.0])
        .unwrap();
    set_number(&mut h, &id, "a", 1.124e-16);
    set_number(&mut h, &id, "b", 1e-6);
    settle(&mut h);
    show_node(&mut h, &id);
    let node = h.state().canvas().node_screen_rect(&id).unwrap();
    // The output's summary, whole and inside the node.
    let product = output_summary(&h, &id, 0);
    assert_eq!(product, "1.124e-22");
    let label = h.get_by_label(product.as_str());
    let r = on_screen(&h, label.rect());
    assert!(
        node.contains_rect(r.shrink(0.5)),
        "the summary {r:?} lies in the node {node:?}"
    );
    // Each input's drag value shows the number's digits (not "0.00"), whole.
    for text in ["1.124e-16", "1e-6"] {
        let field = h
            .get_all_by_role(Role::SpinButton)
            .find(|n| n.value().as_deref() == Some(text))
            .unwrap_or_else(|| panic!("a drag value showing {text}"));
        let r = on_screen(&h, field.rect());
        assert!(
            node.contains_rect(r.shrink(0.5)),
            "{text}: {r:?} in {node:?}"
        );
    }
    h.snapshot("fluency_small_numbers");

    // The other cases, each a drag value and the summary of its product with 1.
    for (x, text) in [(0.01, "0.01"), (12.5, "12.5"), (1.5e9, "1.5e9")] {
        set_number(&mut h, &id, "a", x);
        set_number(&mut h, &id, "b", 1.0);
        settle(&mut h);
        h.run_steps(2);
        assert_eq!(output_summary(&h, &id, 0), text);
        assert!(
            h.get_all_by_role(Role::SpinButton)
                .any(|n| n.value().as_deref() == Some(text)),
            "a drag value showing {text}"
        );
        let node = h.state().canvas().node_screen_rect(&id).unwrap();
        let label = h
            .query_all_by_label(text)
            .find(|n| n.accesskit_node().role() != Role::SpinButton)
            .unwrap_or_else(|| panic!("the summary {text}"));
        let r = on_screen(&h, label.rect());
        assert!(
            node.contains_rect(r.shrink(0.5)),
            "{text}: {r:?} in {node:?}"
        );
    }

    // Typing a number in scientific notation sets it.
    let field = h
        .get_all_by_role(Role::SpinButton)
        .find(|n| n.value().as_deref() == Some("12.5"))
        .is_none();
    assert!(field, "a is 1.5e9 now");
    let at = {
        let f = h
            .get_all_by_role(Role::SpinButton)
            .find(|n| n.value().as_deref() == Some("1.5e9"))
            .unwrap();
        on_screen(&h, f.rect()).center()
    };
    click(&mut h, at);
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    // The drag value being edited as text keeps its role.
    h.get_by(|n| n.role() == Role::SpinButton && n.is_focused())
        .type_text("2.5e-7");
    h.run_steps(1);
    h.key_press(egui::Key::Enter);
    h.run_steps(2);
    settle(&mut h);
    let a = h.state().doc().graph.node(&id).unwrap().value(0).cloned();
    assert_eq!(a, Some(cnets_engine::Value::Number(2.5e-7)));
    assert_eq!(output_summary(&h, &id, 0), "2.5e-7");
}

/// Drags with the primary button from `a` to `b` in a few moves, a frame or two each.
fn drag(h: &mut H, a: Pos2, b: Pos2) {
    h.hover_at(a);
    h.run_steps(2);
    h.drag_at(a);
    h.run_steps(2);
    for t in [0.25, 0.5, 0.75, 1.0] {
        h.hover_at(a + (b - a) * t);
        h.run_steps(2);
    }
    h.drop_at(b);
    h.run_steps(3);
}

#[test]
fn a_triangle_pin_starts_a_wire_from_any_of_its_points() {
    let mut h = harness("triangle-pin");
    show_node(&mut h, "construct");
    let def = h.state().doc().graph.node("construct").unwrap().def.clone();
    let planes = def.output_index("planes").unwrap();
    let flip = def.input_index("ratios").unwrap();
    // The 9-point triangle reaches 5.7 points above its centre and 5.8 to each side at its foot
    // (4.4 below): grab it at its tip and at a foot corner, outside a 9 × 9 square.
    for offset in [egui::vec2(0.0, -5.0), egui::vec2(5.0, 4.0)] {
        let from = h
            .state()
            .canvas()
            .pin_screen_pos("construct", false, planes)
            .expect("the planes pin is drawn");
        let position = h.state().doc().graph.node("construct").unwrap().position;
        let wires = h.state().doc().graph.wires().len();
        // Onto the construct's own ratios input: a cycle, refused, so nothing changes in the
        // graph if a wire was dragged; the node would follow the pointer if it was grabbed.
        let to = h
            .state()
            .canvas()
            .pin_screen_pos("construct", true, flip)
            .unwrap();
        drag(&mut h, from + offset, to);
        h.key_press(egui::Key::Escape);
        h.run_steps(3);
        assert_eq!(
            h.state().doc().graph.node("construct").unwrap().position,
            position,
            "grabbing the triangle at {offset:?} does not move the node"
        );
        assert_eq!(h.state().doc().graph.wires().len(), wires);
    }
}

/// The issue's "the first click on a field right after a wire drag does nothing": here a wire
/// connected out → in and one dropped on the background, each followed at once by a click on a
/// field. The first click edits the field in the harness, as it did in the variants tried while
/// writing this (in → out, dropped on a field, the release in the frame of the last move, the
/// click's press and release in one frame); the report from a real window is not reproduced, so
/// this guards the behaviour and nothing was changed for it.
#[test]
fn the_first_click_on_a_field_after_a_wire_drag_edits_it() {
    let mut h = harness("click-after-wire");
    let id = h
        .state_mut()
        .add_node("math.multiply", [0.0, 720.0])
        .unwrap();
    settle(&mut h);
    show_node(&mut h, &id);
    let def = h.state().doc().graph.node(&id).unwrap().def.clone();
    let a = def.input_index("a").unwrap();
    let result = def.output_index("result").unwrap();
    // A wire from the apex slider's value into `a`.
    let from = h.state().canvas().pin_screen_pos("apex", false, 0).unwrap();
    let to = h.state().canvas().pin_screen_pos(&id, true, a).unwrap();
    let wires = h.state().doc().graph.wires().len();
    drag(&mut h, from, to);
    assert_eq!(h.state().doc().graph.wires().len(), wires + 1, "connected");
    // The first click on `b`'s field, at once (the evaluation still running), edits it.
    let field = h.state().canvas().editor_screen_rect(&id, "b").unwrap();
    click(&mut h, field.center());
    assert!(
        h.query_by(|n| n.role() == Role::SpinButton && n.is_focused())
            .is_some(),
        "the first click after connecting edits the field"
    );
    h.key_press(egui::Key::Escape);
    h.run_steps(2);
    // A wire dragged out of `result` and dropped on the background, then a click on `b`.
    let from = h
        .state()
        .canvas()
        .pin_screen_pos(&id, false, result)
        .unwrap();
    drag(&mut h, from, from + egui::vec2(80.0, 120.0));
    h.run_steps(2);
    let field = h.state().canvas().editor_screen_rect(&id, "b").unwrap();
    click(&mut h, field.center());
    assert!(
        h.query_by(|n| n.role() == Role::SpinButton && n.is_focused())
            .is_some(),
        "the first click after a dropped wire edits the field"
    );
}

/// A node's text: its label, else its value (a label's text).
fn text(n: &egui_kittest::Node<'_>) -> Option<String> {
    let a = n.accesskit_node();
    a.label().or_else(|| a.value())
}

const LONG: &str = r#"(
    version: 1,
    name: "long",
    nodes: {
        "x": (type: "graph.input", position: (0.0, 0.0), inputs: {"name": "the_spacing_between_neighbouring_strips", "type": "number", "default": 1.0}),
        "times": (type: "math.multiply", position: (200.0, 0.0), inputs: {"b": 2.0}),
        "y": (type: "graph.output", position: (400.0, 0.0), inputs: {"name": "label_points_of_every_unrolled_strip", "type": "number"}),
    },
    edges: ["x.value -> times.a", "times.result -> y.value"],
)"#;

const MAIN: &str = r#"(
    version: 1,
    nodes: {
        "t": (type: "cluster", source: "long.ron", position: (0.0, 0.0)),
    },
    edges: [],
)"#;

#[test]
fn long_port_names_end_in_an_ellipsis_with_the_whole_name_on_hover() {
    let dir = std::env::temp_dir().join(format!("cnets-editor-long-names-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("long.ron"), LONG).unwrap();
    let main = dir.join("main.ron");
    std::fs::write(&main, MAIN).unwrap();
    let mut h = common::harness_with("long-names", Some(main), common::temp_config("long-names"));
    settle(&mut h);
    show_node(&mut h, "t");
    let node = h.state().canvas().node_screen_rect("t").unwrap();
    for full in [
        "the_spacing_between_neighbouring_strips",
        "label_points_of_every_unrolled_strip",
    ] {
        assert!(
            h.query_by_label(full).is_none(),
            "{full} is not drawn whole"
        );
        let label = h
            .query_all_by_label_contains(&full[..8])
            .find(|n| text(n).is_some_and(|l| l.ends_with('…')))
            .unwrap_or_else(|| panic!("{full} ends in an ellipsis"));
        let shown = text(&label).unwrap();
        let shown = shown.as_str();
        assert!(full.starts_with(shown.trim_end_matches('…')), "{shown}");
        let r = on_screen(&h, label.rect());
        assert!(
            r.width() <= cnets_editor::canvas::PORT_NAME_WIDTH + 1.0,
            "{shown}: {r:?}"
        );
        assert!(
            node.contains_rect(r.shrink(0.5)),
            "{shown}: {r:?} in {node:?}"
        );
        // The hover gives the whole name, then the type and doc.
        h.hover_at(r.center());
        h.run_steps(90);
        assert!(
            h.query_all_by_label_contains(full)
                .any(|n| text(&n).is_some_and(|l| l.starts_with(full))),
            "the hover over {shown} names {full}"
        );
        if full.starts_with("label") {
            h.snapshot("fluency_long_port_name");
        }
        h.hover_at(node.left_top() - egui::vec2(20.0, 20.0));
        h.run_steps(10);
    }
}

/// "The flip checkbox needed two clicks (the first only selected the node)": one click on an
/// unselected node's checkbox toggles it.
#[test]
fn the_first_click_on_a_checkbox_of_an_unselected_node_toggles_it() {
    let mut h = harness("checkbox-first-click");
    let id = h
        .state_mut()
        .add_node("mesh.cut_by_plane", [0.0, 720.0])
        .unwrap();
    settle(&mut h);
    show_node(&mut h, &id);
    h.state_mut().select_nodes(Vec::new());
    h.run_steps(2);
    let flip = |h: &H| {
        h.state()
            .doc()
            .graph
            .node(&id)
            .unwrap()
            .value_of("flip")
            .cloned()
    };
    assert_ne!(flip(&h), Some(cnets_engine::Value::Boolean(true)));
    let boxed = h.state().canvas().editor_screen_rect(&id, "flip").unwrap();
    click(&mut h, boxed.left_center() + egui::vec2(6.0, 0.0));
    assert_eq!(
        flip(&h),
        Some(cnets_engine::Value::Boolean(true)),
        "one click turned flip on"
    );
}

/// "An output's label grows when its data arrives, which moves the port": the output's summary
/// has a slot of its own width, so the pin is where it was before the result came; a wire drag
/// started beside the pin (within its grab margin) before the result, with the result arriving
/// mid-drag, connects.
#[test]
fn an_output_pin_stays_put_when_its_result_arrives_and_a_drag_beside_it_takes_it() {
    let mut h = harness("pin-stays");
    let id = h
        .state_mut()
        .add_node("math.multiply", [0.0, 720.0])
        .unwrap();
    let target = h.state_mut().add_node("math.add", [360.0, 720.0]).unwrap();
    settle(&mut h);
    show_node(&mut h, &id);
    let result = {
        let def = &h.state().doc().graph.node(&id).unwrap().def;
        def.output_index("result").unwrap()
    };
    let a = h
        .state()
        .doc()
        .graph
        .node(&target)
        .unwrap()
        .def
        .input_index("a")
        .unwrap();
    let with_result = h
        .state()
        .canvas()
        .pin_screen_pos(&id, false, result)
        .unwrap();
    assert!(!output_summary(&h, &id, result).is_empty());
    // The same frame without the node's result (as before it arrives).
    let status = h.state_mut().statuses_mut().remove(&id).unwrap();
    h.run_steps(4);
    let without = h
        .state()
        .canvas()
        .pin_screen_pos(&id, false, result)
        .unwrap();
    assert!(
        (without - with_result).length() < 0.5,
        "the pin moved from {without:?} to {with_result:?} when the result arrived"
    );
    // A press 6 points right of the pin takes it; the result arrives mid-drag; the drop on the
    // input connects.
    let wires = h.state().doc().graph.wires().len();
    let start = without + egui::vec2(6.0, 0.0);
    h.hover_at(start);
    h.run_steps(2);
    h.drag_at(start);
    h.run_steps(2);
    h.state_mut().statuses_mut().insert(id.clone(), status);
    let end = h.state().canvas().pin_screen_pos(&target, true, a).unwrap();
    for t in [0.25, 0.5, 0.75, 1.0] {
        h.hover_at(start + (end - start) * t);
        h.run_steps(2);
    }
    let end = h.state().canvas().pin_screen_pos(&target, true, a).unwrap();
    h.drop_at(end);
    h.run_steps(3);
    let graph = &h.state().doc().graph;
    assert_eq!(graph.wires().len(), wires + 1, "connected");
}
