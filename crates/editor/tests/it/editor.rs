//! The editor driven through egui_kittest, rendered with wgpu (in CI: the software Vulkan driver,
//! lavapipe): snapshot images and interactions.

use crate::common;

use std::time::Duration;

use cnets_editor::app::EditorApp;
use cnets_editor::worker::NodeStatus;
use cnets_engine::Value;
use common::{harness, harness_with, settle, temp_config};
use egui::accesskit::Role;
use egui::{Key, Modifiers, Pos2};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

fn face_positions(app: &EditorApp) -> Vec<[f32; 3]> {
    app.viewport()
        .scene()
        .face_vertices()
        .iter()
        .map(|v| v.position)
        .collect()
}

/// Drags with the primary button from `a` to `b` in a few moves.
fn drag(h: &mut Harness<'static, EditorApp>, a: Pos2, b: Pos2) {
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

fn pin(h: &Harness<'static, EditorApp>, node: &str, input: bool, port: &str) -> Pos2 {
    let app = h.state();
    let def = &app.doc().graph.node(node).unwrap().def;
    let k = if input {
        def.input_index(port)
    } else {
        def.output_index(port)
    }
    .unwrap();
    app.canvas()
        .pin_screen_pos(node, input, k)
        .unwrap_or_else(|| panic!("pin {node}.{port} was not drawn"))
}

#[test]
fn snapshot_default_graph_shows_canvas_and_mesh() {
    let mut h = harness("snap-default");
    let app = h.state();
    assert!(
        app.viewport().scene().triangle_count() > 0,
        "the cone-net is in the scene"
    );
    assert_eq!(app.viewport().stats().vertices, 11 * 19);
    assert!(app.viewport().stats().max_planarity.unwrap() < 1e-9);
    assert!(matches!(app.statuses()["construct"], NodeStatus::Ok { .. }));
    h.snapshot("editor_default");
}

#[test]
fn snapshot_palette_open() {
    let mut h = harness("snap-palette");
    h.state_mut().open_palette_at([0.0, 0.0]);
    h.run_steps(2);
    // A query whose answer does not change when other nodes are added to the library.
    h.get_by(|n| n.role() == Role::TextInput && n.is_focused())
        .type_text("cnets.construct");
    h.run_steps(3);
    // In the palette by its name then its id; on the canvas as the construct node's type label.
    assert!(
        h.query_by_label("CNets Construct  cnets.construct")
            .is_some()
    );
    assert_eq!(h.query_all_by_label("cnets.construct").count(), 1);
    assert!(
        h.query_by_label("CNets Construct Coplanar  cnets.construct_coplanar")
            .is_some()
    );
    assert_eq!(
        h.query_all_by_label("curve.arc").count(),
        2,
        "non-matching types are not listed"
    );
    h.snapshot("editor_palette");
}

#[test]
fn snapshot_node_in_error_with_message_on_hover() {
    let mut h = harness("snap-error");
    h.state_mut()
        .edit_graph(|g, _| {
            g.set_value("generatrix", "count", Value::Integer(1))
                .map_err(|e| e.to_string())
        })
        .unwrap();
    settle(&mut h);
    let message = h.state().statuses()["generatrix"]
        .error()
        .expect("generatrix fails")
        .to_string();
    assert!(matches!(
        h.state().statuses()["construct"],
        NodeStatus::Blocked(_)
    ));
    let badge = h
        .state()
        .canvas()
        .to_screen(h.get_by_label("⛔").rect().center());
    h.hover_at(badge);
    h.run_steps(90);
    assert!(
        h.query_by_label_contains(&message[..message.len().min(20)])
            .is_some(),
        "tooltip shows {message}"
    );
    h.snapshot("editor_node_error");
}

#[test]
fn dragging_a_slider_changes_the_mesh_and_undo_restores_the_graph_exactly() {
    let mut h = harness("slider");
    let before_text = h.state().doc().to_ron();
    let before_mesh = face_positions(h.state());
    // Accessibility rectangles of canvas widgets are in canvas coordinates.
    let canvas = &h.state().canvas();
    let node = canvas.node_screen_rect("apex").unwrap();
    let r = h
        .get_all_by_role(Role::Slider)
        .map(|s| {
            egui::Rect::from_min_max(
                canvas.to_screen(s.rect().min),
                canvas.to_screen(s.rect().max),
            )
        })
        .find(|r| node.contains(r.center()))
        .expect("the apex node's slider");
    // The handle sits in the middle (value 1 in 0.5..1.5): drag it to the right.
    drag(
        &mut h,
        r.center(),
        r.center() + egui::vec2(r.width() * 0.3, 0.0),
    );
    settle(&mut h);
    let app = h.state();
    let value = app
        .doc()
        .graph
        .node("apex")
        .unwrap()
        .value_of("value")
        .and_then(Value::as_f64)
        .unwrap();
    assert!(value > 1.05, "the drag raised the apex value: {value}");
    assert_ne!(
        face_positions(app),
        before_mesh,
        "the mesh in the viewport's scene changed"
    );
    assert_eq!(
        app.doc().history.undo_len(),
        1,
        "one undo step for the whole drag"
    );
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    settle(&mut h);
    assert_eq!(
        h.state().doc().to_ron(),
        before_text,
        "undo restores the graph exactly"
    );
    assert_eq!(face_positions(h.state()), before_mesh, "and the mesh");
    h.key_press_modifiers(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z);
    settle(&mut h);
    assert_ne!(h.state().doc().to_ron(), before_text, "redo");
}

#[test]
fn incompatible_and_cyclic_wires_are_refused_compatible_ones_connect() {
    let mut h = harness("wires");
    // The graph opens on its sources at a readable zoom; Home frames all of it.
    h.key_press(Key::Home);
    h.run_steps(3);
    let before = h.state().doc().to_ron();
    let wires = h.state().doc().graph.wire_count();
    // A quad mesh into a number input.
    let (a, b) = (
        pin(&h, "construct", false, "mesh"),
        pin(&h, "apex", true, "min"),
    );
    drag(&mut h, a, b);
    settle(&mut h);
    assert_eq!(h.state().doc().graph.wire_count(), wires);
    assert!(
        h.state().message().contains("type mismatch"),
        "{}",
        h.state().message()
    );
    assert_eq!(h.state().doc().to_ron(), before);
    // planarity.max into apex.min closes apex -> construct -> planarity -> apex.
    let (a, b) = (
        pin(&h, "planarity", false, "max"),
        pin(&h, "apex", true, "min"),
    );
    drag(&mut h, a, b);
    settle(&mut h);
    assert!(
        h.state().message().contains("cycle"),
        "{}",
        h.state().message()
    );
    assert_eq!(h.state().doc().to_ron(), before);
    // A number into a number: accepted.
    let (a, b) = (
        pin(&h, "ratio", false, "value"),
        pin(&h, "directrix", true, "start"),
    );
    drag(&mut h, a, b);
    settle(&mut h);
    assert_eq!(
        h.state().doc().graph.wire_count(),
        wires + 1,
        "{}",
        h.state().message()
    );
    assert!(
        h.state()
            .doc()
            .graph
            .wires()
            .iter()
            .any(|w| w.from == "ratio" && w.to == "directrix")
    );
}

#[test]
fn double_click_opens_the_palette_and_picking_adds_a_node() {
    let mut h = harness("palette");
    let n = h.state().doc().graph.node_count();
    // A point of the canvas away from every node.
    let canvas = &h.state().canvas();
    let area = canvas.screen_rect().shrink(30.0);
    let rects: Vec<egui::Rect> = [
        "directrix",
        "generatrix",
        "apex",
        "ratio",
        "construct",
        "planarity",
    ]
    .iter()
    .map(|n| canvas.node_screen_rect(n).unwrap().expand(20.0))
    .collect();
    let empty = (0..40)
        .flat_map(|i| (0..40).map(move |j| (i, j)))
        .map(|(i, j)| {
            area.min
                + egui::vec2(
                    area.width() * i as f32 / 40.0,
                    area.height() * j as f32 / 40.0,
                )
        })
        .find(|p| rects.iter().all(|r| !r.contains(*p)))
        .expect("some empty canvas");
    h.hover_at(empty);
    h.run_steps(2);
    for _ in 0..2 {
        h.event(egui::Event::PointerButton {
            pos: empty,
            button: egui::PointerButton::Primary,
            pressed: true,
            modifiers: Modifiers::NONE,
        });
        h.event(egui::Event::PointerButton {
            pos: empty,
            button: egui::PointerButton::Primary,
            pressed: false,
            modifiers: Modifiers::NONE,
        });
    }
    h.run_steps(3);
    assert!(h.state().palette().open, "double-click opened the palette");
    let window = h
        .ctx
        .memory(|m| m.area_rect(egui::Id::new("cnets-palette")))
        .expect("the palette window");
    assert!(
        window.min.distance(empty) < 2.0 || window.contains(empty),
        "opened at the click {empty:?}: {window:?}"
    );
    h.get_by(|n| n.role() == Role::TextInput && n.is_focused())
        .type_text("length");
    h.run_steps(2);
    // The designer's name first, the id after.
    h.get_by_label("Length  curve.length").click();
    h.run_steps(3);
    let app = h.state();
    assert_eq!(app.doc().graph.node_count(), n + 1);
    let added = app.doc().graph.node("length").expect("a curve.length node");
    let expected = app.canvas().to_canvas(empty);
    assert!(
        (added.position[0] - expected.x).abs() < 1.0
            && (added.position[1] - expected.y).abs() < 1.0,
        "placed where clicked: {:?} vs {expected:?}",
        added.position
    );
}

#[test]
fn delete_duplicate_copy_paste_and_undo() {
    let mut h = harness("edit");
    let original = h.state().doc().to_ron();
    let rect = h.state().canvas().node_screen_rect("planarity").unwrap();
    // Click the node's body (not a widget) to focus it.
    let at = Pos2::new(rect.center().x, rect.bottom() - 4.0);
    h.hover_at(at);
    h.drag_at(at);
    h.drop_at(at);
    h.run_steps(3);
    assert_eq!(h.state().canvas().focused.as_deref(), Some("planarity"));
    h.key_press_modifiers(Modifiers::COMMAND, Key::D);
    h.run_steps(3);
    assert!(
        h.state().doc().graph.node("planarity_2").is_some(),
        "duplicated"
    );
    assert!(
        h.state()
            .doc()
            .graph
            .wires()
            .iter()
            .any(|w| w.to == "planarity_2"),
        "with its input wire"
    );
    h.state_mut().focus_node(Some("planarity".into()));
    h.key_press(Key::Delete);
    h.run_steps(3);
    assert!(h.state().doc().graph.node("planarity").is_none(), "deleted");
    h.state_mut().run(cnets_editor::menus::MenuAction::Undo);
    h.state_mut().run(cnets_editor::menus::MenuAction::Undo);
    h.run_steps(2);
    assert_eq!(h.state().doc().to_ron(), original);
    h.state_mut().focus_node(Some("construct".into()));
    h.state_mut().run(cnets_editor::menus::MenuAction::Copy);
    h.state_mut().run(cnets_editor::menus::MenuAction::Paste);
    assert!(
        h.state().doc().graph.node("construct_2").is_some(),
        "pasted"
    );
}

#[test]
fn save_is_atomic_recent_files_persist_and_a_crash_offers_restore() {
    let config = temp_config("recovery");
    let mut h = harness_with("recovery", None, config.clone());
    let file = config.join("saved.ron");
    h.state_mut().save_as(&file);
    let saved = std::fs::read_to_string(&file).unwrap();
    assert_eq!(saved, h.state().doc().to_ron());
    assert_eq!(
        cnets_editor::settings::Settings::load(&config).recent[0],
        std::fs::canonicalize(&file).unwrap()
    );
    // An edit, then the autosave writes the recovery file.
    h.state_mut()
        .edit_graph(|g, _| {
            g.set_value("ratio", "value", Value::Number(0.25))
                .map(|_| ())
                .map_err(|e| e.to_string())
        })
        .unwrap();
    // (Written on autosave's thread: the frames after the edit pick up its result.)
    let recovery = config.join("recovery.ron");
    let start = std::time::Instant::now();
    while !recovery.is_file() && start.elapsed() < Duration::from_secs(30) {
        h.run_steps(1);
        std::thread::sleep(Duration::from_millis(20));
    }
    assert!(recovery.is_file(), "autosaved");
    assert_eq!(
        std::fs::read_to_string(&recovery).unwrap(),
        h.state().doc().to_ron(),
        "the edited document"
    );
    let edited = h.state().doc().to_ron();
    // "Crash": drop the editor without on_exit; the next start offers the restore.
    drop(h);
    let mut h = harness_with("recovery2", None, config.clone());
    assert!(h.state().restore_offered());
    h.run_steps(2);
    h.get_by_label("Restore").click();
    h.run_steps(3);
    assert!(!h.state().restore_offered());
    assert_eq!(h.state().doc().to_ron(), edited, "the unsaved edit is back");
    assert_eq!(h.state().doc().path.as_deref(), Some(file.as_path()));
    h.state_mut().on_exit();
    assert!(!recovery.exists(), "a clean exit removes the recovery file");
    let _ = Duration::ZERO;
}

#[test]
fn dragging_a_graph_mapper_handle_edits_its_handles_in_one_step() {
    let mut h = harness("mapper");
    let id = h
        .state_mut()
        .add_node("mapper.graph", [760.0, 0.0])
        .unwrap();
    h.run_steps(2);
    let centre = h.state().canvas().node_rect(&id).expect("drawn").center();
    h.state_mut().zoom_canvas(1.0, Some(centre));
    h.run_steps(4);
    let steps = h.state().doc().history.undo_len();
    let before = h.state().doc().to_ron();
    // The linear kind's default handles; drag the second one down.
    let handles = cnets_editor::mapper::handles(h.state().doc().graph.node(&id).unwrap());
    let b = handles[1];
    let canvas = &h.state().canvas();
    let from = canvas
        .mapper_screen_pos(&id, b.x as f32, b.y as f32)
        .expect("the mapper is drawn");
    let to = canvas.mapper_screen_pos(&id, b.x as f32, 0.25).unwrap();
    drag(&mut h, from, to);
    settle(&mut h);
    let app = h.state();
    let now = cnets_editor::mapper::handles(app.doc().graph.node(&id).unwrap());
    assert_eq!(now.len(), handles.len());
    assert!(
        (now[1].y - 0.25).abs() < 0.05,
        "the handle followed the pointer: {now:?}"
    );
    assert_eq!(
        app.doc().history.undo_len(),
        steps + 1,
        "one undo step for the drag"
    );
    assert!(
        matches!(app.statuses()[&id], NodeStatus::Ok { .. }),
        "{:?}",
        app.statuses()[&id]
    );
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run_steps(2);
    assert_eq!(h.state().doc().to_ron(), before);
}

#[test]
fn closing_with_unsaved_changes_asks_first() {
    let mut h = harness("close");
    h.state_mut().request_close();
    assert!(h.state().wants_to_quit(), "nothing unsaved: closes at once");
    let mut h = harness("close2");
    h.state_mut()
        .edit_graph(|g, _| {
            g.set_value("ratio", "value", Value::Number(0.3))
                .map(|_| ())
                .map_err(|e| e.to_string())
        })
        .unwrap();
    h.state_mut().request_close();
    h.run_steps(2);
    assert!(
        !h.state().wants_to_quit() && h.state().unsaved_question().is_some(),
        "asks first"
    );
    h.get_by_label("Cancel").click();
    h.run_steps(2);
    assert!(!h.state().wants_to_quit() && h.state().unsaved_question().is_none());
    h.state_mut().request_close();
    h.run_steps(2);
    h.get_by_label("Don't save").click();
    h.run_steps(2);
    assert!(h.state().wants_to_quit());
}

#[test]
fn arrange_lays_nodes_out_without_overlaps_in_one_undo_step() {
    let mut h = harness("arrange");
    // Pile every node on one spot.
    let ids: Vec<String> = h
        .state()
        .doc()
        .graph
        .nodes()
        .map(|(_, n)| n.id.clone())
        .collect();
    h.state_mut()
        .edit_graph(|g, _| {
            for id in &ids {
                g.set_position(id, [0.0, 0.0]).map_err(|e| e.to_string())?;
            }
            Ok::<_, String>(())
        })
        .unwrap();
    h.run_steps(3);
    assert!(h.state().canvas().has_overlaps());
    let steps = h.state().doc().history.undo_len();
    h.key_press_modifiers(Modifiers::COMMAND, Key::L);
    h.run_steps(4);
    assert!(!h.state().canvas().has_overlaps(), "arranged");
    assert_eq!(h.state().doc().history.undo_len(), steps + 1);
    let g = &h.state().doc().graph;
    let x = |id: &str| g.node(id).unwrap().position[0];
    assert!(
        x("directrix") < x("construct") && x("construct") < x("planarity"),
        "sources left of their targets"
    );
}

#[test]
fn viewport_orbits_pans_zooms_fits_and_switches_colours_and_layers() {
    use cnets_editor::preview::{ColorMode, Layer, LegendInfo};
    let mut h = harness("viewport");
    let view = h.state().canvas().screen_rect();
    // The viewport is the panel right of the canvas.
    let center = Pos2::new(view.right() + 300.0, view.center().y);
    let camera = h.state().viewport().framing().camera;
    drag(&mut h, center, center + egui::vec2(80.0, 30.0));
    let orbited = h.state().viewport().framing().camera;
    assert!((orbited.yaw - camera.yaw).abs() > 0.1, "left-drag orbits");
    assert_eq!(orbited.distance, camera.distance);
    h.hover_at(center);
    h.event(egui::Event::MouseWheel {
        unit: egui::MouseWheelUnit::Point,
        delta: egui::vec2(0.0, 120.0),
        phase: egui::TouchPhase::Move,
        modifiers: Modifiers::NONE,
    });
    h.run_steps(10);
    assert!(
        h.state().viewport().framing().camera.distance < orbited.distance,
        "the wheel zooms in"
    );
    h.key_press(Key::F);
    h.run_steps(2);
    assert!(
        h.state().viewport().framing().camera != orbited,
        "F frames the geometry again"
    );

    let mut o = h.state().viewport().display().options;
    o.color_mode = ColorMode::Planarity;
    h.state_mut()
        .run(cnets_editor::menus::MenuAction::SetPreview(o));
    settle(&mut h);
    match &h.state().viewport().stats().legend {
        LegendInfo::Planarity(l) => {
            assert!(
                l.labels[0].starts_with("planar"),
                "in words: {:?}",
                l.labels
            );
            // The default cone-net is planar to rounding: one colour, not a stretched patchwork.
            assert!(
                l.min == 1e-9 && l.max == 1e-3,
                "anchored to tolerances: {l:?}"
            );
        }
        other => panic!("{other:?}"),
    }
    h.snapshot("editor_planarity_legend");
    o.set(Layer::Surfaces, false);
    h.state_mut()
        .run(cnets_editor::menus::MenuAction::SetPreview(o));
    settle(&mut h);
    assert_eq!(
        h.state().viewport().scene().triangle_count(),
        0,
        "surfaces hidden"
    );
    assert!(
        !h.state().viewport().scene().segments().is_empty(),
        "curves still shown"
    );
}

#[test]
fn a_changing_view_renders_at_half_resolution_on_software_then_settles() {
    let mut h = harness("scale");
    assert_eq!(
        h.state().viewport().framing().render_scale,
        1.0,
        "settled: full resolution"
    );
    h.state_mut()
        .edit_graph(|g, _| {
            g.set_value("ratio", "value", Value::Number(0.4))
                .map(|_| ())
                .map_err(|e| e.to_string())
        })
        .unwrap();
    h.state_mut().wait_for_worker(Duration::from_secs(60));
    h.run_steps(2);
    // lavapipe in CI: half resolution while changing; a hardware adapter keeps full resolution.
    let software = h.state().gpu().is_some_and(|g| g.software);
    let expected = if software {
        cnets_editor::viewport::INTERACTIVE_SCALE
    } else {
        1.0
    };
    assert_eq!(
        h.state().viewport().framing().render_scale,
        expected,
        "software rasterizer: {software}"
    );
    h.run_steps(30);
    assert_eq!(
        h.state().viewport().framing().render_scale,
        1.0,
        "back to full resolution"
    );
}

#[test]
fn shift_click_on_a_title_selects_the_node() {
    let mut h = harness("shift-title");
    let was = h.state().doc().graph.node("apex").unwrap().position;
    let title = h
        .get_all_by_label("apex")
        .map(|l| h.state().canvas().to_screen(l.rect().center()))
        .find(|p| {
            let r = h.state().canvas().node_screen_rect("apex").unwrap();
            r.contains(*p) && p.y < r.top() + 30.0
        })
        .expect("the apex title");
    h.hover_at(title);
    h.run_steps(2);
    h.event(egui::Event::ModifiersChanged(Modifiers::SHIFT));
    for pressed in [true, false] {
        h.event(egui::Event::PointerButton {
            pos: title,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: Modifiers::SHIFT,
        });
    }
    h.run_steps(3);
    assert_eq!(h.state().canvas().selected, vec!["apex".to_string()]);
    assert_eq!(
        h.state().doc().graph.node("apex").unwrap().position,
        was,
        "not moved"
    );
}

#[test]
fn the_wheel_zooms_the_canvas_as_in_the_3d_view() {
    let mut h = harness("wheel");
    let at = h.state().canvas().screen_rect().center();
    let before = h.state().canvas().zoom();
    let mut raw = egui::RawInput {
        events: vec![
            egui::Event::PointerMoved(at),
            egui::Event::MouseWheel {
                unit: egui::MouseWheelUnit::Line,
                delta: egui::vec2(0.0, 2.0),
                modifiers: Modifiers::NONE,
                phase: egui::TouchPhase::Move,
            },
        ],
        ..Default::default()
    };
    h.state_mut().raw_input(&mut raw);
    assert!(
        matches!(raw.events[1], egui::Event::Zoom(f) if f > 1.0),
        "wheel up over the canvas is a zoom in: {:?}",
        raw.events[1]
    );
    for e in raw.events {
        h.event(e);
    }
    h.run_steps(3);
    assert!(
        h.state().canvas().zoom() > before * 1.1,
        "{} → {}",
        before,
        h.state().canvas().zoom()
    );
    // Over the 3D view the wheel stays a wheel (the viewport zooms with it itself).
    let view = egui::pos2(h.state().canvas().screen_rect().right() + 200.0, at.y);
    let mut raw = egui::RawInput {
        events: vec![
            egui::Event::PointerMoved(view),
            egui::Event::MouseWheel {
                unit: egui::MouseWheelUnit::Line,
                delta: egui::vec2(0.0, 2.0),
                modifiers: Modifiers::NONE,
                phase: egui::TouchPhase::Move,
            },
        ],
        ..Default::default()
    };
    h.state_mut().raw_input(&mut raw);
    assert!(matches!(raw.events[1], egui::Event::MouseWheel { .. }));
}
