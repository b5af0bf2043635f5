//! The canvas shows the toolbox's reading and choosing nodes as Grasshopper does: a `view.panel`
//! node's text inside the node (multi-line, resizable), a `param.choice` node as a drop-down of
//! its options.

use crate::common;

use cnets_editor::worker::NodeStatus;
use cnets_engine::Value;
use common::{harness, settle};
use egui_kittest::kittest::Queryable;

fn connect(
    h: &mut egui_kittest::Harness<'static, cnets_editor::EditorApp>,
    from: &str,
    output: &str,
    to: &str,
    input: &str,
) {
    h.state_mut()
        .edit_graph(|g, _| {
            g.connect(from, output, to, input)
                .map(|_| ())
                .map_err(|e| e.to_string())
        })
        .unwrap();
}

fn show_node(h: &mut egui_kittest::Harness<'static, cnets_editor::EditorApp>, id: &str) {
    h.run_steps(2);
    let centre = h.state().canvas().node_rect(id).expect("drawn").center();
    h.state_mut().zoom_canvas(1.0, Some(centre));
    h.run_steps(4);
}

#[test]
fn a_panel_node_shows_its_text_inside_and_resizes() {
    let mut h = harness("panel");
    let id = h.state_mut().add_node("view.panel", [0.0, 720.0]).unwrap();
    // The construction's apices: a list of points, one a line under its branch {0}.
    connect(&mut h, "construct", "apices", &id, "value");
    settle(&mut h);
    show_node(&mut h, &id);
    let readout = match &h.state().statuses()[&id] {
        NodeStatus::Ok { readout, .. } => readout.clone().expect("the panel's text"),
        other => panic!("{other:?}"),
    };
    assert!(readout.starts_with("{0}\n0  "), "{readout}");
    assert!(readout.lines().count() > 10, "multi-line: {readout}");
    // The text is drawn inside the node, every line of it in one label.
    let node = h.state().canvas().node_screen_rect(&id).unwrap();
    let canvas = &h.state().canvas();
    let label = h.get_by_label(readout.as_str());
    let at = canvas.to_screen(label.rect().min);
    assert!(
        node.contains(at + egui::vec2(4.0, 4.0)),
        "inside the node: {at:?} in {node:?}"
    );
    h.snapshot("editor_panel_node");
    // Drag the readout's bottom-right corner: the box grows.
    let before = h
        .state()
        .canvas()
        .panel_screen_rect(&id)
        .expect("the readout is drawn");
    let corner = before.max - egui::vec2(3.0, 3.0);
    let to = corner + egui::vec2(120.0, 80.0);
    h.hover_at(corner);
    h.run_steps(2);
    h.drag_at(corner);
    h.run_steps(2);
    for t in [0.25, 0.5, 0.75, 1.0] {
        h.hover_at(corner + (to - corner) * t);
        h.run_steps(2);
    }
    h.drop_at(to);
    h.run_steps(4);
    let after = h.state().canvas().panel_screen_rect(&id).unwrap();
    assert!(
        after.width() > before.width() + 60.0 && after.height() > before.height() + 40.0,
        "resized: {before:?} → {after:?}"
    );
    assert_eq!(
        h.state().doc().graph.node(&id).unwrap().position,
        [0.0, 720.0],
        "resizing does not move the node"
    );
}

#[test]
fn a_choice_node_is_a_drop_down_of_its_options() {
    let mut h = harness("choice");
    let id = h
        .state_mut()
        .add_node("param.choice", [0.0, 720.0])
        .unwrap();
    let options = Value::list(vec![
        Value::text("flat"),
        Value::text("arched"),
        Value::text("folded"),
    ]);
    h.state_mut()
        .edit_graph(|g, _| {
            g.set_value(&id, "options", options)
                .map(|_| ())
                .map_err(|e| e.to_string())
        })
        .unwrap();
    settle(&mut h);
    show_node(&mut h, &id);
    let steps = h.state().doc().history.undo_len();
    // The drop-down shows the chosen option; open it and pick another.
    let combo = h
        .get_all_by_role(egui::accesskit::Role::ComboBox)
        .find(|c| c.value().as_deref() == Some("flat"))
        .expect("the drop-down showing the chosen option");
    // Widgets on the canvas have canvas coordinates.
    let at = h.state().canvas().to_screen(combo.rect().center());
    h.hover_at(at);
    h.run_steps(2);
    for pressed in [true, false] {
        h.event(egui::Event::PointerButton {
            pos: at,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: egui::Modifiers::NONE,
        });
    }
    h.run_steps(3);
    h.get_by_label("arched").click();
    h.run_steps(3);
    settle(&mut h);
    let node = h.state().doc().graph.node(&id).unwrap();
    assert_eq!(node.value_of("index"), Some(&Value::Integer(1)));
    assert_eq!(
        h.state().doc().history.undo_len(),
        steps + 1,
        "one undo step"
    );
    match &h.state().statuses()[&id] {
        NodeStatus::Ok { outputs, .. } => assert!(outputs[0].contains("arched"), "{outputs:?}"),
        other => panic!("{other:?}"),
    }
    h.snapshot("editor_choice_node");
}
