//! The canvas's right-click menus driven with pointer events, as a designer uses them: a node's
//! preview colour picked from its eye (issue 32) and a node renamed from its title (issue 26).
//! Widgets on the canvas have canvas coordinates, so the clicks go to their places on the screen.

use crate::common;

use cnets_editor::EditorApp;
use common::{harness, settle};
use egui::accesskit::Role;
use egui::{Pos2, Rect};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

type H = Harness<'static, EditorApp>;

/// A widget's rectangle on the screen (widgets on the canvas have canvas coordinates).
fn on_screen(h: &H, canvas: Rect) -> Rect {
    let c = &h.state().canvas();
    Rect::from_min_max(c.to_screen(canvas.min), c.to_screen(canvas.max))
}

/// Zooms the canvas to 1 around a node, so its widgets are drawn at their size.
fn show_node(h: &mut H, id: &str) {
    h.run_steps(2);
    let centre = h.state().canvas().node_rect(id).expect("drawn").center();
    h.state_mut().zoom_canvas(1.0, Some(centre));
    h.run_steps(4);
}

/// A click of `button` at a screen position, the press and the release in frames of their own.
fn click_with(h: &mut H, at: Pos2, button: egui::PointerButton) {
    h.hover_at(at);
    h.run_steps(1);
    for pressed in [true, false] {
        h.event(egui::Event::PointerButton {
            pos: at,
            button,
            pressed,
            modifiers: egui::Modifiers::default(),
        });
        h.run_steps(1);
    }
    h.run_steps(2);
}

/// The screen rectangle of the widget labelled `label` inside node `id` on the canvas.
fn widget_in_node(h: &H, id: &str, label: &str) -> Rect {
    let node = h.state().canvas().node_rect(id).expect("drawn");
    h.get_all_by_label(label)
        .map(|n| n.rect())
        .find(|r| node.contains(r.center()))
        .map(|r| on_screen(h, r))
        .unwrap_or_else(|| panic!("no {label:?} in node {id}"))
}

#[test]
fn the_eyes_right_click_menu_picks_the_nodes_preview_colour() {
    let mut h = harness("colour-menu");
    // Plain colours (the default mode colours the faces by their class).
    let mut o = h.state().viewport().display().options;
    o.color_mode = cnets_editor::preview::ColorMode::Plain;
    h.state_mut()
        .run(cnets_editor::menus::MenuAction::SetPreview(o));
    settle(&mut h);
    show_node(&mut h, "construct");
    assert_eq!(h.state().doc().graph.node("construct").unwrap().color, None);
    let eye = widget_in_node(&h, "construct", "👁");
    click_with(&mut h, eye.center(), egui::PointerButton::Secondary);
    let title = h.get_by_label("Preview colour").rect();
    // The swatches: the buttons on the row under the menu's title, blue first.
    let mut swatches: Vec<Rect> = h
        .get_all_by_role(Role::Button)
        .map(|n| n.rect())
        .filter(|r| r.top() >= title.bottom() && r.top() < title.bottom() + 24.0)
        .filter(|r| r.left() >= title.left() - 4.0)
        .collect();
    swatches.sort_by(|a, b| a.left().total_cmp(&b.left()));
    assert_eq!(swatches.len(), 8, "{swatches:?}");
    h.snapshot("context_menu_preview_colour");
    // Orange, the second swatch.
    click_with(&mut h, swatches[1].center(), egui::PointerButton::Primary);
    settle(&mut h);
    assert_eq!(
        h.state().doc().graph.node("construct").unwrap().color,
        Some([0xe0, 0x8a, 0x2c])
    );
    assert!(
        h.query_by_label("Preview colour").is_none(),
        "the menu closed"
    );
    // The surface in the 3D view takes the colour (shaded: its hue stays orange).
    let orange = h
        .state()
        .viewport()
        .scene()
        .face_vertices()
        .iter()
        .filter(|v| {
            let [r, g, b, _] = v.color.0;
            r > g && g > b && u16::from(r) > u16::from(b) + 60
        })
        .count();
    let all = h.state().viewport().scene().face_vertices().len();
    assert!(orange * 10 >= all * 9, "{orange} of {all} vertices orange");
    // One undo step brings the default back; the file keeps the colour.
    let text = cnets_engine::file::to_ron(&h.state().doc().graph, &Default::default());
    assert!(text.contains("color: \"#e08a2c\""), "{text}");
    h.state_mut().run(cnets_editor::menus::MenuAction::Undo);
    settle(&mut h);
    assert_eq!(h.state().doc().graph.node("construct").unwrap().color, None);
}

#[test]
fn a_node_is_renamed_from_its_titles_right_click_menu() {
    let mut h = harness("rename-menu");
    show_node(&mut h, "apex");
    let node = on_screen(&h, h.state().canvas().node_rect("apex").unwrap());
    // The title bar: the top strip of the node.
    let title = egui::pos2(node.center().x, node.top() + 12.0);
    click_with(&mut h, title, egui::PointerButton::Secondary);
    h.get_by(|n| n.role() == Role::TextInput && n.value().as_deref() == Some("apex"))
        .focus();
    h.run_steps(2);
    for _ in 0.."apex".len() {
        h.key_press(egui::Key::Backspace);
        h.run_steps(1);
    }
    h.get_by(|n| n.role() == Role::TextInput && n.is_focused())
        .type_text("Apex height");
    h.run_steps(2);
    let button = h.get_by_label("Rename node").rect();
    click_with(&mut h, button.center(), egui::PointerButton::Primary);
    settle(&mut h);
    let graph = &h.state().doc().graph;
    assert_eq!(graph.node("apex").unwrap().label(), "Apex height");
    // The title shows the name; the id stays (wires and `--set` use it).
    assert!(h.query_by_label("Apex height").is_some());
    assert!(
        cnets_engine::file::to_ron(graph, &Default::default()).contains("name: \"Apex height\"")
    );
}

/// Issue 41: a right-click on a slider locks its node for dragging (the Drag net tool leaves it
/// alone; the node's title shows 🔒), a second one unlocks it; the slider's value is untouched.
#[test]
fn a_right_click_on_a_slider_toggles_locked_for_dragging() {
    let mut h = harness("slider-lock");
    show_node(&mut h, "apex");
    let before = h
        .state()
        .doc()
        .graph
        .node("apex")
        .unwrap()
        .value(0)
        .cloned();
    let slider = h
        .state()
        .canvas()
        .editor_screen_rect("apex", "value")
        .expect("the apex slider is drawn");
    assert!(!h.state().canvas().drag_locked.contains("apex"));
    click_with(&mut h, slider.center(), egui::PointerButton::Secondary);
    assert!(
        h.state().canvas().drag_locked.contains("apex"),
        "locked after one right-click: {:?}",
        h.state().canvas().drag_locked
    );
    assert_eq!(
        h.state()
            .doc()
            .graph
            .node("apex")
            .unwrap()
            .value(0)
            .cloned(),
        before,
        "the right-click did not move the slider"
    );
    assert!(
        h.query_by_label("🔒").is_some(),
        "the node says it is locked"
    );
    click_with(&mut h, slider.center(), egui::PointerButton::Secondary);
    assert!(h.state().canvas().drag_locked.is_empty(), "unlocked again");
}
