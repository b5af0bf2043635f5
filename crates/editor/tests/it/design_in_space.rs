//! Design in space (issue 25), in kittest with the wgpu renderer: handles dragged in the Top view
//! move their point by the grid-snapped amount and nothing else, a curve drawn in the Front view
//! becomes `param.points` + `curve.spline` with the snapped clicks, a face of a cone-net is picked
//! by node and (i, j), the legend's fold entry frames the folds, the measure tool snaps to
//! vertices, the named views are one key away, and a curve read from a file is internalised as
//! editable points.

use crate::common;

use cnets_editor::app::EditorApp;
use cnets_editor::viewport::pick::Hit;
use cnets_editor::viewport::screen::steps;
use cnets_editor::viewport::{NamedView, Tool};
use cnets_engine::Value;
use cnets_geometry::DVec3;
use common::{graphs_dir, harness_with, settle, temp_config};
use egui::{Key, Pos2, vec2};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

/// A graph of four points (preview on) drawn as a spline.
const POINTS_GRAPH: &str = r#"(
    version: 1,
    nodes: {
        "pts": (
            type: "param.points",
            position: (0.0, 0.0),
            preview: true,
            inputs: {
                "points": [(0.0, 0.0, 0.0), (2.0, 1.0, 0.0), (4.0, -1.0, 0.0), (6.0, 0.5, 0.25)],
            },
        ),
        "curve": (
            type: "curve.spline",
            position: (300.0, 0.0),
        ),
    },
    edges: ["pts.points -> curve.points"],
)"#;

fn open(name: &str, text: &str) -> Harness<'static, EditorApp> {
    let dir = temp_config(&format!("{name}-files"));
    let file = dir.join(format!("{name}.ron"));
    std::fs::write(&file, text).unwrap();
    harness_with(name, Some(file), temp_config(name))
}

fn points_of(app: &EditorApp, node: &str) -> Vec<Value> {
    app.doc()
        .graph
        .node(node)
        .and_then(|n| n.value_of("points"))
        .and_then(Value::as_list)
        .map(<[Value]>::to_vec)
        .unwrap_or_default()
}

/// Shows a named view and lets it settle.
fn view(h: &mut Harness<'static, EditorApp>, v: NamedView) {
    h.state_mut().viewport_mut().set_view(v);
    h.run_steps(3);
}

fn screen_of(h: &Harness<'static, EditorApp>, p: DVec3) -> Pos2 {
    h.state()
        .viewport()
        .screen_map()
        .to_screen(p)
        .expect("in front of the camera")
}

fn drag(h: &mut Harness<'static, EditorApp>, a: Pos2, b: Pos2) {
    h.hover_at(a);
    h.run_steps(1);
    h.drag_at(a);
    h.run_steps(1);
    for t in [0.2, 0.5, 0.8, 1.0] {
        h.hover_at(a + (b - a) * t);
        h.run_steps(1);
    }
    h.drop_at(b);
    h.run_steps(2);
}

fn click(h: &mut Harness<'static, EditorApp>, at: Pos2) {
    h.hover_at(at);
    h.run_steps(1);
    h.drag_at(at);
    h.run_steps(1);
    h.drop_at(at);
    h.run_steps(1);
}

#[test]
fn a_handle_dragged_in_the_top_view_moves_by_the_snapped_amount_and_undo_restores_it() {
    let mut h = open("handles", POINTS_GRAPH);
    view(&mut h, NamedView::Top);
    let before = points_of(h.state(), "pts");
    let text_before = h.state().doc().to_ron();
    assert_eq!(h.state().viewport().handle_list().len(), 4, "four handles");
    let step = h.state().viewport().grid_step();
    let wpp = h.state().viewport().screen_map().world_per_point();
    // Three grid steps right and two down (−y in the Top view), plus a third of a step of slack
    // that the snap takes away.
    let from = screen_of(&h, DVec3::new(2.0, 1.0, 0.0));
    let by = vec2(
        ((3.0 + 0.3) * step / wpp) as f32,
        ((2.0 - 0.3) * step / wpp) as f32,
    );
    let steps = h.state().doc().history.undo_len();
    drag(&mut h, from, from + by);
    settle(&mut h);
    let after = points_of(h.state(), "pts");
    assert_eq!(after.len(), 4, "the list keeps its length");
    let expected = DVec3::new(2.0 + 3.0 * step, 1.0 - 2.0 * step, 0.0);
    let moved = after[1].as_vec3().unwrap();
    assert!(
        (moved - expected).length() < 1e-12,
        "moved to {moved}, expected {expected} (grid {step})"
    );
    for k in [0, 2, 3] {
        assert_eq!(after[k], before[k], "point {k} is untouched, bit for bit");
    }
    assert_eq!(
        h.state().doc().history.undo_len(),
        steps + 1,
        "one undo step"
    );
    assert!(h.state_mut().undo());
    assert_eq!(
        h.state().doc().to_ron(),
        text_before,
        "undo restores the text"
    );
}

#[test]
fn a_curve_drawn_in_the_front_view_becomes_points_and_a_spline() {
    let mut h = open("draw", POINTS_GRAPH);
    view(&mut h, NamedView::Front);
    h.state_mut()
        .viewport_mut()
        .toggle_tool(Tool::Draw(Default::default()));
    let step = h.state().viewport().grid_step();
    let wpp = h.state().viewport().screen_map().world_per_point();
    // Four clicks on XZ, each a little off the grid (less than half a step).
    let clicks: Vec<DVec3> = [(0.0, 0.0), (2.0, 3.0), (5.0, 3.0), (7.0, 0.0)]
        .iter()
        .map(|&(x, z)| DVec3::new(steps(x, step), 0.0, steps(z, step)))
        .collect();
    let jitter = vec2((0.3 * step / wpp) as f32, (-0.2 * step / wpp) as f32);
    for p in &clicks {
        let at = screen_of(&h, *p) + jitter;
        click(&mut h, at);
    }
    h.key_press(Key::Enter);
    h.run_steps(2);
    settle(&mut h);
    let app = h.state();
    let spline = app
        .doc()
        .graph
        .nodes()
        .find(|(_, n)| n.def.id == "curve.spline" && n.id != "curve")
        .map(|(_, n)| n.id.clone())
        .expect("a new curve.spline");
    let wires = app.doc().graph.wires();
    let source = wires
        .iter()
        .find(|w| w.to == spline && w.input == "points")
        .expect("wired");
    let points = points_of(app, &source.from);
    let got: Vec<DVec3> = points.iter().filter_map(Value::as_vec3).collect();
    assert_eq!(got, clicks, "the snapped clicks, on the XZ plane");
    assert_eq!(
        app.canvas().selected,
        vec![spline.clone()],
        "the curve node alone is selected (Delete removes the curve, not its points too)"
    );
    assert!(
        matches!(
            app.statuses().get(&spline),
            Some(cnets_editor::worker::NodeStatus::Ok { .. })
        ),
        "the spline evaluates"
    );
}

/// The toolbar shows the kind of curve while Draw curve is active: Polyline clicked draws straight
/// segments (a `curve.polyline`, the curve node alone selected), and P switches the kind.
#[test]
fn the_draw_tool_offers_a_polyline_on_the_toolbar_and_p_switches() {
    let mut h = open("draw-polyline", POINTS_GRAPH);
    view(&mut h, NamedView::Front);
    // The pointer over the 3D view, nothing typed.
    let centre = h.state().viewport().rect().center();
    h.hover_at(centre);
    h.key_press(Key::C);
    h.run_steps(2);
    assert!(
        matches!(h.state().viewport().tool(), Tool::Draw(_)),
        "C: Draw curve"
    );
    // The toolbar's Polyline, clicked with the pointer.
    let toggle = h.get_by_label("Polyline").rect().center();
    click(&mut h, toggle);
    h.run_steps(1);
    let polyline = |h: &Harness<'static, EditorApp>| match &h.state().viewport().tool() {
        Tool::Draw(d) => d.polyline,
        other => panic!("still drawing: {}", other.label()),
    };
    assert!(polyline(&h), "the toolbar's Polyline chosen");
    // P switches the kind while the tool is active.
    h.hover_at(centre);
    h.key_press(Key::P);
    h.run_steps(2);
    assert!(!polyline(&h), "P: a spline");
    h.key_press(Key::P);
    h.run_steps(2);
    assert!(polyline(&h), "P again: a polyline");
    let step = h.state().viewport().grid_step();
    for (x, z) in [(0.0, 0.0), (4.0, 0.0), (4.0, 3.0)] {
        let at = screen_of(&h, DVec3::new(steps(x, step), 0.0, steps(z, step)));
        click(&mut h, at);
    }
    h.key_press(Key::Enter);
    h.run_steps(2);
    settle(&mut h);
    let app = h.state();
    let made: Vec<String> = app
        .doc()
        .graph
        .nodes()
        .filter(|(_, n)| n.def.id == "curve.polyline")
        .map(|(_, n)| n.id.clone())
        .collect();
    assert_eq!(made.len(), 1, "one curve.polyline drawn: {made:?}");
    assert_eq!(
        app.canvas().selected,
        made,
        "the curve node alone is selected"
    );
}

#[test]
fn picking_a_face_names_its_node_and_row_and_column_and_a_click_selects_the_node() {
    let mut h = harness_with(
        "pick",
        Some(graphs_dir().join("torus-monge.ron")),
        temp_config("pick"),
    );
    view(&mut h, NamedView::Top);
    settle(&mut h);
    let picks = h.state().viewport().picks().clone();
    let (m, mesh) = picks
        .meshes
        .iter()
        .enumerate()
        .find(|(_, m)| m.geometry.face_row_col(0).is_some())
        .expect("a previewed quad mesh");
    // A face in the middle of the grid, seen from the top: its centre.
    let faces = mesh.geometry.face_count();
    let target = (0..faces)
        .map(|f| (f, mesh.geometry.face_corners(f)))
        .filter(|(_, c)| {
            let centre = c.iter().copied().sum::<DVec3>() / c.len() as f64;
            h.state()
                .viewport()
                .screen_map()
                .to_screen(centre)
                .is_some_and(|s| h.state().viewport().rect().shrink(40.0).contains(s))
        })
        .max_by(|a, b| {
            let z = |c: &Vec<DVec3>| c.iter().map(|p| p.z).sum::<f64>();
            z(&a.1).total_cmp(&z(&b.1))
        })
        .expect("a face in view");
    let centre = target.1.iter().copied().sum::<DVec3>() / 4.0;
    let at = screen_of(&h, centre);
    h.hover_at(at);
    h.run_steps(2);
    let hit = h
        .state()
        .viewport()
        .tools()
        .hover
        .clone()
        .expect("something under the pointer");
    let Hit::Face { mesh: hm, face, .. } = hit else {
        panic!("a face, not {hit:?}")
    };
    // The topmost face under the pointer: the one chosen, or one drawn over it at that point.
    let (i, j) = picks.meshes[hm].geometry.face_row_col(face).unwrap();
    let graph = &h.state().doc().graph;
    let text = cnets_editor::viewport::pick::describe(&picks, &hit, graph);
    assert!(text.contains(&format!("face (i {i}, j {j})")), "{text}");
    assert!(text.contains(&picks.meshes[hm].node), "{text}");
    // A named node is called by its name.
    let node = picks.meshes[hm].node.clone();
    let mut named = graph.clone();
    named.set_name(&node, Some("Roof panels".into())).unwrap();
    let text = cnets_editor::viewport::pick::describe(&picks, &hit, &named);
    assert!(text.starts_with("Roof panels · "), "{text}");
    if hm == m {
        assert_eq!(face, target.0, "the face under its centre");
    }
    click(&mut h, at);
    assert_eq!(
        h.state().canvas().focused.as_deref(),
        Some(picks.meshes[hm].node.as_str()),
        "clicking selects the node"
    );
}

#[test]
fn the_fold_entry_of_the_legend_frames_the_folded_faces() {
    let mut h = harness_with(
        "folds",
        Some(graphs_dir().join("correction.ron")),
        temp_config("folds"),
    );
    settle(&mut h);
    let folds = h.state().viewport().picks().folded_faces();
    assert!(!folds.is_empty(), "correction.ron shows folding inputs");
    let entry = h
        .state()
        .viewport()
        .last_frame()
        .fold_entry
        .expect("the legend's fold entry");
    click(&mut h, entry.center());
    h.run_steps(3);
    let app = h.state();
    assert!(app.viewport().drawn().folds_shown);
    let picks = app.viewport().picks().clone();
    let map = app.viewport().screen_map();
    for (m, f) in &folds {
        for p in picks.meshes[*m].geometry.face_corners(*f) {
            let s = map.to_screen(p).expect("in front");
            assert!(
                app.viewport().rect().expand(1.0).contains(s),
                "fold corner {p} at {s:?} is framed in {:?}",
                app.viewport().rect()
            );
        }
    }
    let edges: usize = folds
        .iter()
        .map(|(m, f)| picks.meshes[*m].geometry.face_corners(*f).len())
        .sum();
    assert_eq!(
        app.viewport().highlight().len(),
        edges,
        "every fold outlined"
    );
    h.key_press(Key::Escape);
    h.run_steps(2);
    assert!(
        h.state().viewport().highlight().is_empty(),
        "Esc clears the outline"
    );
}

#[test]
fn the_measure_tool_snaps_to_vertices_and_reports_their_distance() {
    let mut h = open("measure", POINTS_GRAPH);
    view(&mut h, NamedView::Top);
    h.state_mut()
        .viewport_mut()
        .toggle_tool(Tool::Measure(Default::default()));
    let a = DVec3::new(0.0, 0.0, 0.0);
    let b = DVec3::new(6.0, 0.5, 0.25);
    // A few points off each handle: the clicks snap to them.
    let (sa, sb) = (screen_of(&h, a), screen_of(&h, b));
    click(&mut h, sa + vec2(3.0, -2.0));
    click(&mut h, sb + vec2(-2.0, 3.0));
    let Tool::Measure(m) = &h.state().viewport().tool() else {
        panic!("still measuring")
    };
    let d = m.distance().expect("two points");
    assert!((d - (b - a).length()).abs() < 1e-12, "{d}");
    assert!(
        h.state().message().starts_with("distance "),
        "{}",
        h.state().message()
    );
}

#[test]
fn named_views_are_one_key_away_and_orthographic() {
    let mut h = open("views", POINTS_GRAPH);
    for (key, v) in [
        (Key::Num1, NamedView::Top),
        (Key::Num2, NamedView::Front),
        (Key::Num3, NamedView::Right),
        (Key::Num4, NamedView::Perspective),
    ] {
        // The pointer over the 3D view, nothing typed.
        let centre = h.state().viewport().rect().center();
        h.hover_at(centre);
        h.key_press(key);
        h.run_steps(3);
        let vp = &h.state().viewport();
        assert_eq!(vp.framing().view, v);
        assert_eq!(
            vp.framing().camera.is_orthographic(),
            v != NamedView::Perspective
        );
        // Each frames the previewed geometry: every handle is in view.
        for handle in vp.handle_list() {
            let s = vp.screen_map().to_screen(handle.position).unwrap();
            assert!(vp.rect().contains(s), "{v:?}: {handle:?} at {s:?}");
        }
    }
}

#[test]
fn a_curve_read_from_a_file_is_internalised_as_editable_points() {
    let dir = temp_config("internalise-files");
    std::fs::write(
        dir.join("outline.svg"),
        r#"<svg xmlns="http://www.w3.org/2000/svg"><polyline points="0,0 10,0 10,5"/></svg>"#,
    )
    .unwrap();
    let file = dir.join("internalise.ron");
    std::fs::write(
        &file,
        r#"(version: 1, nodes: {
            "read": (type: "io.read_polylines", position: (0.0, 0.0), inputs: {"path": "outline.svg"}),
        }, edges: [])"#,
    )
    .unwrap();
    let mut h = harness_with("internalise", Some(file), temp_config("internalise"));
    let message = h.state_mut().internalise("read").expect("internalised");
    assert!(message.contains("1 curve"), "{message}");
    settle(&mut h);
    let app = h.state();
    let points = app
        .doc()
        .graph
        .nodes()
        .find(|(_, n)| n.def.id == "param.points")
        .map(|(_, n)| n.id.clone())
        .expect("a param.points node");
    let got: Vec<DVec3> = points_of(app, &points)
        .iter()
        .filter_map(Value::as_vec3)
        .collect();
    assert_eq!(got.len(), 3, "{got:?}");
    assert!(
        app.doc()
            .graph
            .wires()
            .iter()
            .any(|w| w.from == points && w.input == "points"),
        "wired into a polyline"
    );
}

#[test]
fn a_box_selects_handles_arrows_nudge_them_and_the_inspector_takes_a_coordinate() {
    let mut h = open("box", POINTS_GRAPH);
    view(&mut h, NamedView::Top);
    // Zoomed out, so the box's corners are in the view.
    h.state_mut().viewport_mut().zoom(2.0);
    h.run_steps(2);
    let step = h.state().viewport().grid_step();
    // A box around the first three points (the fourth, at x = 6, stays out).
    let a = screen_of(&h, DVec3::new(-0.5, 1.5, 0.0));
    let b = screen_of(&h, DVec3::new(4.5, -1.5, 0.0));
    drag(&mut h, a, b);
    let selected: Vec<usize> = h
        .state()
        .viewport()
        .tools()
        .handles
        .selected
        .iter()
        .map(|k| k.index)
        .collect();
    assert_eq!(
        selected,
        vec![0, 1, 2],
        "the box selects the handles inside"
    );
    let before = points_of(h.state(), "pts");
    // The arrow keys move the selected handles one grid step in the view's plane.
    let centre = h.state().viewport().rect().center();
    h.hover_at(centre);
    h.key_press(Key::ArrowRight);
    h.run_steps(2);
    h.key_press(Key::ArrowUp);
    h.run_steps(2);
    let after = points_of(h.state(), "pts");
    for k in 0..3 {
        let (p, q) = (before[k].as_vec3().unwrap(), after[k].as_vec3().unwrap());
        assert!(
            (q - p - DVec3::new(step, step, 0.0)).length() < 1e-12,
            "point {k}: {p} → {q}"
        );
    }
    assert_eq!(after[3], before[3], "the fourth point stays");
    // One handle selected: the inspector shows its coordinates and takes a typed one.
    let at = screen_of(&h, after[3].as_vec3().unwrap());
    click(&mut h, at);
    assert_eq!(h.state().viewport().tools().handles.selected.len(), 1);
    h.run_steps(2);
    let view_rect = h.state().viewport().rect();
    let z_field = h
        .get_all_by_role(egui::accesskit::Role::SpinButton)
        .map(|n| n.rect().center())
        .filter(|p| view_rect.contains(*p))
        .max_by(|a, b| a.x.total_cmp(&b.x))
        .expect("the inspector's z field (its rightmost)");
    h.hover_at(z_field);
    h.run_steps(1);
    h.drag_at(z_field);
    h.run_steps(1);
    h.drop_at(z_field);
    h.run_steps(2);
    h.key_press_modifiers(egui::Modifiers::COMMAND, Key::A);
    h.run_steps(1);
    h.event(egui::Event::Text("1.75".into()));
    h.key_press(Key::Enter);
    h.run_steps(3);
    let z = points_of(h.state(), "pts")[3].as_vec3().unwrap().z;
    assert_eq!(z, 1.75, "the inspector set z");
}

/// A selected cut shows its plane and the side it keeps: the side the normal points to, the
/// other with `flip`; a wired plane is not drawn, nor a cut that is not selected.
#[test]
fn a_selected_cut_shows_its_plane_and_the_side_it_keeps() {
    use cnets_editor::edit::Edit;
    let mut h = harness_with("cut-plane", None, temp_config("cut-plane"));
    let id = h
        .state_mut()
        .add_node("mesh.cut_by_plane", [900.0, 400.0])
        .unwrap();
    let plane = cnets_geometry::Plane::from_normal(DVec3::new(2.0, 0.0, 0.0), DVec3::X).unwrap();
    assert!(h.state_mut().edit(Edit::SetValue {
        node: id.clone(),
        input: "plane".into(),
        value: Value::Plane(std::sync::Arc::new(plane)),
    }));
    // Another node selected.
    h.state_mut().select_nodes(vec!["construct".into()]);
    settle(&mut h);
    assert!(
        h.state().viewport().cut_overlays().is_empty(),
        "not selected: not drawn"
    );
    h.state_mut().select_nodes(vec![id.clone()]);
    h.run_steps(3);
    let cuts = h.state().viewport().cut_overlays().to_vec();
    assert_eq!(cuts.len(), 1);
    assert_eq!(cuts[0].origin, DVec3::new(2.0, 0.0, 0.0));
    assert_eq!(cuts[0].kept, DVec3::X, "the side the normal points to");
    // The picture, to look at: target/tmp/cut-plane.png.
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../target/tmp");
    std::fs::create_dir_all(&dir).unwrap();
    if let Ok(image) = h.render() {
        image.save(dir.join("cut-plane.png")).unwrap();
    }
    assert!(h.state_mut().edit(Edit::SetValue {
        node: id.clone(),
        input: "flip".into(),
        value: Value::Boolean(true),
    }));
    h.run_steps(3);
    assert_eq!(
        h.state().viewport().cut_overlays()[0].kept,
        -DVec3::X,
        "flip keeps the other side"
    );
    h.state_mut().select_nodes(vec!["construct".into()]);
    h.run_steps(3);
    assert!(h.state().viewport().cut_overlays().is_empty());
}

/// The screen rectangles of `ids` on the canvas, each asserted to lie wholly inside the canvas
/// (not under the 3D view beside it).
fn assert_in_canvas(h: &Harness<'static, EditorApp>, ids: &[String], what: &str) {
    let app = h.state();
    let view = app.canvas().screen_rect();
    assert!(!ids.is_empty(), "{what}: nodes were added");
    for id in ids {
        let r = app
            .canvas()
            .node_screen_rect(id)
            .unwrap_or_else(|| panic!("{what}: {id} is drawn"));
        assert!(
            view.contains_rect(r),
            "{what}: {id} at {r:?} is not wholly in the canvas {view:?} (the 3D view starts at {})",
            app.viewport().rect().left()
        );
    }
}

/// New nodes go where they can be seen: a curve drawn with the right-most node of the graph
/// selected (its nodes go below the selection) and a node added from Add › Node… with it selected
/// (right of the selection) both land wholly inside the canvas, not half under the 3D view.
#[test]
fn new_nodes_are_placed_in_the_visible_canvas() {
    let mut h = harness_with(
        "new-nodes-in-view",
        Some(graphs_dir().join("editor-default.ron")),
        temp_config("new-nodes-in-view"),
    );
    settle(&mut h);
    let right_most = |h: &Harness<'static, EditorApp>| {
        let app = h.state();
        app.doc()
            .graph
            .nodes()
            .filter_map(|(_, n)| Some((n.id.clone(), app.canvas().node_screen_rect(&n.id)?)))
            .max_by(|a, b| a.1.right().total_cmp(&b.1.right()))
            .map(|(id, _)| id)
            .unwrap()
    };
    let before: Vec<String> = h
        .state()
        .doc()
        .graph
        .nodes()
        .map(|(_, n)| n.id.clone())
        .collect();
    let added = |h: &Harness<'static, EditorApp>| -> Vec<String> {
        h.state()
            .doc()
            .graph
            .nodes()
            .map(|(_, n)| n.id.clone())
            .filter(|id| !before.contains(id))
            .collect()
    };
    // A drawn curve with the right-most node selected.
    let id = right_most(&h);
    h.state_mut().select_nodes(vec![id]);
    h.run_steps(2);
    h.state_mut().add_curve(cnets_editor::viewport::DrawnCurve {
        points: vec![
            DVec3::ZERO,
            DVec3::new(2.0, 1.0, 0.0),
            DVec3::new(4.0, 0.0, 0.0),
        ],
        closed: false,
        spline: true,
    });
    settle(&mut h);
    h.run_steps(4);
    let curve_nodes = added(&h);
    assert_eq!(curve_nodes.len(), 2, "points and a spline: {curve_nodes:?}");
    assert_in_canvas(&h, &curve_nodes, "a drawn curve");
    // A node from Add › Node… with the right-most node selected.
    let id = right_most(&h);
    h.state_mut().select_nodes(vec![id]);
    h.run_steps(2);
    let at = h.state_mut().new_node_place();
    let node = h.state_mut().add_node("math.add", at).unwrap();
    settle(&mut h);
    h.run_steps(4);
    assert_in_canvas(&h, &[node], "Add › Node…");
}

/// The first 3D view of torus-monge (three surfaces over a box of 49 m × 48.5 m) is framed on
/// the surfaces — every vertex in view, their picture centred and spanning most of the view one
/// way — and its grid is sized to them: it reaches no farther than two major cells (or a quarter
/// of the design) beyond the drawn box, where it reached 60 cells around the target (to 120 m).
#[test]
fn torus_monge_opens_framed_on_its_surfaces_with_a_grid_of_their_size() {
    let mut h = harness_with(
        "torus-first-view",
        Some(graphs_dir().join("torus-monge.ron")),
        temp_config("torus-first-view"),
    );
    settle(&mut h);
    h.run_steps(4);
    let app = h.state();
    let view = app.viewport().rect();
    let map = app.viewport().screen_map();
    let picks = app.viewport().picks();
    let mut drawn = egui::Rect::NOTHING;
    for mesh in &picks.meshes {
        for p in mesh.geometry.vertices() {
            let at = map.to_screen(*p).expect("in front of the camera");
            assert!(
                view.contains(at),
                "{} vertex {p} at {at:?} out of {view:?}",
                mesh.node
            );
            drawn = drawn.union(egui::Rect::from_min_max(at, at));
        }
    }
    assert_eq!(picks.meshes.len(), 3, "the three surfaces");
    let spans = (drawn.width() / view.width()).max(drawn.height() / view.height());
    assert!(
        spans > 0.7,
        "the surfaces span {spans:.2} of the view: {drawn:?} in {view:?}"
    );
    let off = drawn.center() - view.center();
    assert!(
        off.x.abs() < 0.05 * view.width() && off.y.abs() < 0.1 * view.height(),
        "the surfaces' picture {drawn:?} is off the view's centre {:?}",
        view.center()
    );
    // The grid drawn now, in the world XY plane: within the margin of the drawn box.
    let bounds = app.viewport().bounds().expect("something is drawn");
    let grid = cnets_editor::viewport::grid::Grid::new(
        &map,
        cnets_editor::viewport::screen::CPlane::XY,
        Some(&bounds),
    );
    let size = bounds.max - bounds.min;
    let reach = cnets_editor::viewport::grid::around_margin(
        f64::from(size.x),
        f64::from(size.y),
        grid.spacing,
    ) + grid.spacing.major;
    for s in grid.segments.iter().filter(|s| s.width < 1.55) {
        for p in [s.a, s.b] {
            let (x, y) = (f64::from(p[0]), f64::from(p[1]));
            assert!(
                x >= f64::from(bounds.min.x) - reach
                    && x <= f64::from(bounds.max.x) + reach
                    && y >= f64::from(bounds.min.y) - reach
                    && y <= f64::from(bounds.max.y) + reach,
                "a grid line reaches ({x}, {y}), beyond {reach} m of {bounds:?}"
            );
        }
    }
    println!(
        "torus-monge's first view: the surfaces span {spans:.2} of the view, W × D {:.1} × {:.1} m, \
         grid {} m",
        size.x, size.y, grid.spacing.minor
    );
}
