//! The parameter panel (View › Parameters, Ctrl+P): the graph's sliders in one docked list,
//! editable there.

use crate::common;

use cnets_editor::canvas::CanvasAction;
use cnets_editor::edit::Edit;
use cnets_editor::parameters;
use cnets_engine::{Graph, Value};
use egui::accesskit::Role;
use egui::{Key, Modifiers};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

#[test]
fn the_panel_is_docked_and_its_sliders_edit_the_graph() {
    // In the editor: Ctrl+P docks the panel, listing the graph's sliders.
    let mut h = common::harness("parameters");
    h.key_press_modifiers(Modifiers::COMMAND, Key::P);
    h.run_steps(3);
    assert!(h.state().parameters_open());
    h.get_by_label("Parameters");
    h.get_by_label("this graph");
    h.snapshot("editor_parameters_panel");
    // An edit from the panel is an ordinary edit: applied, one undo step, undone exactly.
    let before = h.state().doc().to_ron();
    let graph: Graph = h.state().doc().graph.clone();
    let mut panel = Harness::builder()
        .with_size(egui::vec2(320.0, 420.0))
        .build_ui_state(
            |ui, state: &mut (Graph, Vec<CanvasAction>)| {
                let a = parameters::show(ui, &state.0, &Default::default());
                state.1.extend(a);
            },
            (graph, Vec::new()),
        );
    panel.run();
    let slider = panel
        .get_all_by_role(Role::Slider)
        .next()
        .expect("the first slider (apex)")
        .rect();
    let (a, b) = (slider.center(), slider.center() + egui::vec2(40.0, 0.0));
    panel.hover_at(a);
    panel.run_steps(2);
    panel.drag_at(a);
    panel.run_steps(2);
    panel.hover_at(b);
    panel.run_steps(2);
    panel.drop_at(b);
    panel.run_steps(2);
    let actions = std::mem::take(&mut panel.state_mut().1);
    let last = actions
        .into_iter()
        .rev()
        .find(|a| matches!(a, CanvasAction::Edit(Edit::SetValue { node, .. }) if node == "apex"))
        .expect("the apex slider was dragged");
    let CanvasAction::Edit(Edit::SetValue { value, .. }) = &last else {
        unreachable!()
    };
    assert!(value.as_f64().unwrap() > 1.0, "{value:?}");
    assert!(h.state_mut().apply(last.clone()));
    h.state_mut().end_gesture();
    assert_eq!(
        h.state()
            .doc()
            .graph
            .node("apex")
            .unwrap()
            .value_of("value"),
        Some(value)
    );
    assert_eq!(h.state().doc().history.undo_len(), 1);
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run_steps(2);
    assert_eq!(h.state().doc().to_ron(), before);
    let _ = Value::Null;
}
