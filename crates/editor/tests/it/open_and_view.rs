//! Opening keeps the evaluator; graphs open readable; values are readable in place (issue 14).

use crate::common;

use std::collections::{HashSet, VecDeque};
use std::path::Path;
use std::time::Duration;

use cnets_editor::app::EditorApp;
use cnets_editor::unsaved::Replace;
use common::{graphs_dir, harness, settle, temp_config};
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

fn open(h: &mut Harness<'static, EditorApp>, path: &Path) {
    h.state_mut().request(Replace::Open(path.to_path_buf()));
    settle(h);
    assert_eq!(
        h.state().doc().path.as_deref(),
        Some(path),
        "{}: {:?}",
        h.state().message(),
        h.state().load_failure().as_ref().map(|f| &f.error)
    );
}

/// The nodes downstream of `id` (itself included) in the open document.
fn downstream(app: &EditorApp, id: &str) -> usize {
    let wires = app.doc().graph.wires();
    let mut seen = HashSet::from([id.to_string()]);
    let mut queue = VecDeque::from([id.to_string()]);
    while let Some(n) = queue.pop_front() {
        for w in wires.iter().filter(|w| w.from == n) {
            if seen.insert(w.to.clone()) {
                queue.push_back(w.to.clone());
            }
        }
    }
    seen.len()
}

#[test]
fn open_keeps_the_evaluator_and_reruns_only_what_differs() {
    let dir = temp_config("open-keeps-evaluator-files");
    let text = std::fs::read_to_string(graphs_dir().join("editor-default.ron")).unwrap();
    let a = dir.join("a.ron");
    std::fs::write(&a, &text).unwrap();
    // A file sharing every node but one slider value.
    let b = dir.join("b.ron");
    let changed = text.replacen("\"value\": 0.5", "\"value\": 0.62", 1);
    assert_ne!(changed, text, "the ratio slider's value is in the file");
    std::fs::write(&b, changed).unwrap();

    let mut h = harness("open-keeps-evaluator");
    h.state_mut().request(Replace::New);
    settle(&mut h);
    open(&mut h, &a);
    let all = h.state().doc().graph.node_count();
    assert_eq!(
        h.state().latency().ran,
        all,
        "from an empty graph every node runs"
    );
    let mesh_a = face_positions(h.state());
    assert!(!mesh_a.is_empty());

    // Reopening the same file recomputes nothing and shows the same design.
    open(&mut h, &a);
    assert_eq!(
        h.state().latency().ran,
        0,
        "nothing recomputed on reopening"
    );
    assert_eq!(face_positions(h.state()), mesh_a);

    // A file that differs in one slider re-runs only that slider's downstream cone.
    open(&mut h, &b);
    let cone = downstream(h.state(), "ratio");
    assert!(cone < all, "the test needs nodes outside the cone");
    assert_eq!(
        h.state().latency().ran,
        cone,
        "only the changed slider's cone"
    );
    let mesh_b = face_positions(h.state());
    assert_ne!(mesh_b, mesh_a, "the new ratio reached the viewport");

    // The same as a fresh evaluation of that file.
    h.state_mut().request(Replace::New);
    settle(&mut h);
    open(&mut h, &b);
    assert_eq!(h.state().latency().ran, all);
    assert_eq!(face_positions(h.state()), mesh_b);

    // Edits after an open stay incremental, and undo keeps the evaluator.
    open(&mut h, &a);
    assert_eq!(h.state().latency().ran, cone);
    h.state_mut()
        .edit_graph(|g, _| {
            g.set_value("ratio", "value", cnets_engine::Value::Number(0.3))
                .map_err(|e| e.to_string())
        })
        .unwrap();
    settle(&mut h);
    assert_eq!(h.state().latency().ran, cone);
    assert!(h.state_mut().undo());
    settle(&mut h);
    assert_eq!(h.state().latency().ran, cone);
    assert_eq!(face_positions(h.state()), mesh_a);
}

/// The texts painted in the last frame that start with `prefix`, with their height on screen
/// (points; the harness draws one pixel a point).
fn painted_texts(h: &Harness<'static, EditorApp>, prefix: &str) -> Vec<(String, f32)> {
    h.output()
        .shapes
        .iter()
        .filter_map(|c| match &c.shape {
            egui::Shape::Text(t) if t.galley.text().starts_with(prefix) => Some((
                t.galley.text().to_string(),
                t.galley.rows.first().map_or(0.0, |r| r.height()),
            )),
            _ => None,
        })
        .collect()
}

#[test]
fn mapper_handles_show_their_values_while_hovered_and_dragged() {
    use cnets_editor::mapper::{handle_label, handles};
    let mut h = harness("mapper-labels");
    let id = h
        .state_mut()
        .add_node("mapper.graph", [760.0, 0.0])
        .unwrap();
    h.run_steps(1);
    // The new node's first result in before the picture (its outputs size the node).
    h.state_mut().wait_for_worker(Duration::from_secs(60));
    h.run_steps(3);
    let centre = h.state().canvas().node_rect(&id).expect("drawn").center();
    // At the smallest zoom, where the canvas' own text is smallest.
    h.state_mut()
        .zoom_canvas(cnets_editor::canvas::MIN_ZOOM, Some(centre));
    h.run_steps(4);
    assert!(
        painted_texts(&h, "u ").is_empty(),
        "no label before hovering"
    );
    let b = handles(h.state().doc().graph.node(&id).unwrap())[1];
    let at = h
        .state()
        .canvas()
        .mapper_screen_pos(&id, b.x as f32, b.y as f32)
        .unwrap();
    h.hover_at(at);
    h.run_steps(2);
    let shown = painted_texts(&h, "u ");
    assert_eq!(shown.len(), 1, "{shown:?}");
    assert_eq!(shown[0].0, handle_label(b));
    assert!(shown[0].1 >= 10.0, "readable at zoom 0.5: {shown:?}");
    h.snapshot("editor_mapper_handle_label");
    // While dragged, the label follows the (snapped) value being written.
    let to = h
        .state()
        .canvas()
        .mapper_screen_pos(&id, b.x as f32, 0.3)
        .unwrap();
    h.drag_at(at);
    h.run_steps(2);
    for t in [0.5, 1.0] {
        h.hover_at(at + (to - at) * t);
        h.run_steps(2);
    }
    let now = handles(h.state().doc().graph.node(&id).unwrap())[1];
    assert!((now.y - 0.3).abs() < 0.05, "dragged: {now:?}");
    let shown = painted_texts(&h, "u ");
    assert_eq!(shown.len(), 1, "{shown:?}");
    assert_eq!(shown[0].0, handle_label(now), "the value being written");
    h.drop_at(to);
    h.hover_at(centre + egui::vec2(0.0, 400.0));
    h.run_steps(3);
    assert!(
        painted_texts(&h, "u ").is_empty(),
        "gone once the pointer left"
    );
}

#[test]
fn the_overlap_hint_goes_once_nodes_no_longer_overlap() {
    let dir = temp_config("overlap-hint-files");
    let file = dir.join("heap.ron");
    std::fs::write(
        &file,
        r#"(
    version: 1,
    nodes: {
        "a": (type: "param.number", position: (0.0, 0.0)),
        "b": (type: "param.number", position: (20.0, 10.0)),
        "c": (type: "math.add", position: (10.0, 30.0)),
    },
    edges: ["a.value -> c.a", "b.value -> c.b"],
)"#,
    )
    .unwrap();
    let mut h = harness("overlap-hint");
    open(&mut h, &file);
    assert!(h.state().canvas().has_overlaps());
    assert!(h.state().overlap_hint(), "{}", h.state().message());
    let hint = cnets_editor::app::OVERLAP_HINT;
    assert!(
        h.query_by_label(hint).is_some(),
        "the status bar shows the hint"
    );
    // Still overlapping: the hint stays.
    h.run_steps(3);
    assert!(h.state().overlap_hint());
    // View › Arrange graph (Ctrl+L): laid out, the hint goes.
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::L);
    h.run_steps(6);
    assert!(!h.state().canvas().has_overlaps());
    assert!(!h.state().overlap_hint());
    assert!(h.query_by_label(hint).is_none(), "the hint is gone");
    // A document whose nodes do not overlap gets no hint.
    assert!(h.state_mut().open(&graphs_dir().join("editor-default.ron")));
    settle(&mut h);
    assert!(!h.state().canvas().has_overlaps());
    assert!(!h.state().overlap_hint());
}

/// The wires of the graph being edited, as text.
fn wire_texts(app: &EditorApp) -> Vec<String> {
    app.doc()
        .graph
        .wires()
        .iter()
        .map(ToString::to_string)
        .collect()
}

#[test]
fn inside_a_cluster_the_3d_view_shows_the_whole_design_and_ports_rename_keeping_their_wires() {
    use cnets_engine::cluster::OUTPUT_TYPE;
    let mut h = harness("cluster-ports");
    let mesh = face_positions(h.state());
    assert!(!mesh.is_empty());
    let ids = ["directrix".to_string(), "generatrix".to_string()];
    assert!(h.state_mut().make_cluster(&ids), "{}", h.state().message());
    settle(&mut h);
    let outer: Vec<String> = wire_texts(h.state());
    let wire = outer
        .iter()
        .find(|w| w.starts_with("cluster.") && w.ends_with("-> construct.directrix"))
        .unwrap_or_else(|| panic!("the cluster feeds the directrix: {outer:?}"))
        .clone();
    let port = wire["cluster.".len()..wire.find(" ->").unwrap()].to_string();
    h.state_mut().open_cluster("cluster");
    settle(&mut h);
    assert_eq!(h.state().doc().depth(), 1);
    // The inside holds only the two curves; the 3D view still shows the whole design.
    assert!(
        face_positions(h.state()) == mesh,
        "the whole design, inside too"
    );

    // Rename port, from the graph.output node's context menu.
    let out = h
        .state()
        .doc()
        .graph
        .nodes()
        .map(|(_, n)| n)
        .find(|n| {
            n.def.id == OUTPUT_TYPE && n.value_of("name") == Some(&cnets_engine::Value::text(&port))
        })
        .map(|n| n.id.clone())
        .expect("the graph.output node of that port");
    let title = h.state().canvas().node_rect(&out).expect("drawn");
    let at = h
        .state()
        .canvas()
        .to_screen(title.left_top() + egui::vec2(title.width() * 0.5, 8.0));
    h.hover_at(at);
    h.run_steps(1);
    h.event(egui::Event::PointerButton {
        pos: at,
        button: egui::PointerButton::Secondary,
        pressed: true,
        modifiers: egui::Modifiers::NONE,
    });
    h.event(egui::Event::PointerButton {
        pos: at,
        button: egui::PointerButton::Secondary,
        pressed: false,
        modifiers: egui::Modifiers::NONE,
    });
    h.run_steps(3);
    assert!(h.query_by_label("Rename port").is_some(), "the menu entry");
    h.ctx.data_mut(|d| {
        d.insert_temp(
            egui::Id::new(("rename-port", out.as_str())),
            "rail".to_string(),
        )
    });
    h.run_steps(1);
    h.get_by_label("Rename").click();
    h.run_steps(3);
    settle(&mut h);
    assert_eq!(
        h.state()
            .doc()
            .graph
            .node(&out)
            .and_then(|n| n.value_of("name")),
        Some(&cnets_engine::Value::text("rail"))
    );
    // The live copy keeps the wire on the renamed port: the design is unchanged.
    assert!(
        face_positions(h.state()) == mesh,
        "still wired while inside"
    );

    // Back out: the cluster node's port is renamed and keeps its wire.
    h.state_mut().leave_to(0);
    settle(&mut h);
    let app = h.state();
    let outputs: Vec<&str> = app
        .doc()
        .graph
        .node("cluster")
        .unwrap()
        .def
        .outputs
        .iter()
        .map(|p| p.name.as_ref())
        .collect();
    assert!(
        outputs.contains(&"rail") && !outputs.contains(&port.as_str()),
        "{outputs:?}"
    );
    let now = wire_texts(app);
    assert!(
        now.contains(&"cluster.rail -> construct.directrix".to_string()),
        "{now:?}"
    );
    assert_eq!(now.len(), outer.len(), "no wire dropped: {}", app.message());
    assert!(!app.message().contains("dropped"), "{}", app.message());
    assert!(
        app.doc().to_ron().contains("\"name\": \"rail\""),
        "stored in the cluster"
    );
    assert!(face_positions(app) == mesh);
    // Undo takes the rename back (inside the cluster, where it was made).
    assert!(h.state_mut().undo());
    settle(&mut h);
    assert!(h.state_mut().undo());
    settle(&mut h);
    h.state_mut().leave_to(0);
    settle(&mut h);
    assert_eq!(
        wire_texts(h.state()),
        outer,
        "the old port name and its wire"
    );
}

#[test]
fn the_planarity_limit_is_set_in_the_viewport_and_kept_in_the_settings() {
    use cnets_editor::preview::{ColorMode, LegendInfo};
    let config = temp_config("planarity-limit");
    let mut h = common::harness_with("planarity-limit", None, config.clone());
    assert!(
        h.query_by_label("not planar from").is_none(),
        "only in planarity mode"
    );
    h.state_mut()
        .viewport_mut()
        .display_mut()
        .options
        .color_mode = ColorMode::Planarity;
    settle(&mut h);
    let top = |h: &Harness<'static, EditorApp>| match &h.state().viewport().stats().legend {
        LegendInfo::Planarity(l) => l.labels.last().cloned().unwrap_or_default(),
        other => panic!("a planarity legend: {other:?}"),
    };
    assert!(top(&h).contains("1e-3"), "{}", top(&h));
    // Step the slider down with the keyboard.
    let slider = h.get_by(|n| {
        n.role() == egui::accesskit::Role::Slider
            && n.label().is_some_and(|l| l.contains("not planar from"))
    });
    slider.focus();
    h.run_steps(1);
    h.key_press(egui::Key::ArrowLeft);
    h.run_steps(2);
    settle(&mut h);
    let limit = h.state().viewport().display().options.planarity_limit();
    assert!(limit < 1e-3, "the slider lowered the limit: {limit}");
    assert_eq!(h.state().settings().planarity_limit(), Some(limit), "saved");
    assert!(!top(&h).contains("1e-3"), "the legend follows: {}", top(&h));
    // A new session in the same settings folder starts with it.
    drop(h);
    let h = common::harness_with("planarity-limit-2", None, config);
    assert_eq!(
        h.state().viewport().display().options.planarity_limit(),
        limit
    );
}

/// A graph file of `n` numbers (a `param.list`) written to `dir`.
fn large_graph(dir: &Path, name: &str, n: usize) -> std::path::PathBuf {
    let numbers: Vec<String> = (0..n)
        .map(|k| format!("{:.6}", 0.5 + k as f64 * 1e-4))
        .collect();
    let text = format!(
        "(version: 1, nodes: {{\"numbers\": (type: \"param.list\", position: (0.0, 0.0), \
         inputs: {{\"values\": [{}]}})}})",
        numbers.join(", ")
    );
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn a_large_file_is_read_off_the_ui_thread_and_the_latest_open_wins() {
    let dir = temp_config("large-open");
    let big = large_graph(&dir, "big.ron", 500_000);
    assert!(
        std::fs::metadata(&big).unwrap().len() >= cnets_editor::app::LARGE_GRAPH_BYTES,
        "large enough to be read off the UI thread"
    );
    let mut h = harness("large-open-window");
    assert!(h.state_mut().open(&big), "began to be read");
    assert_eq!(h.state().loading(), Some(big.as_path()));
    assert_ne!(
        h.state().doc().path.as_deref(),
        Some(big.as_path()),
        "not yet replaced"
    );
    assert!(
        h.state().message().starts_with("opening ") && h.state().message().ends_with(" MB)…"),
        "the status bar says so: {}",
        h.state().message()
    );
    // The window keeps drawing (with the notice) until the file is read, then it opens.
    h.run_steps(1);
    if h.state().loading().is_some() {
        assert!(
            h.query_by_label_contains("Opening big.ron").is_some(),
            "a frame drawn while the file is read shows the notice"
        );
    }
    let start = std::time::Instant::now();
    while h.state().loading().is_some() {
        assert!(
            start.elapsed() < std::time::Duration::from_secs(300),
            "read within five minutes"
        );
        h.run_steps(1);
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
    assert_eq!(
        h.state().doc().path.as_deref(),
        Some(big.as_path()),
        "{}",
        h.state().message()
    );
    assert!(!h.state().doc().is_dirty());
    assert_eq!(
        h.state()
            .doc()
            .graph
            .node("numbers")
            .unwrap()
            .value_of("values")
            .and_then(|v| v.as_list())
            .map(<[_]>::len),
        Some(500_000)
    );
    // Opened meanwhile, another document wins over the file still being read.
    let big2 = large_graph(&dir, "big2.ron", 500_000);
    assert!(h.state_mut().open(&big2));
    let small = graphs_dir().join("editor-default.ron");
    assert!(h.state_mut().open(&small));
    assert_eq!(h.state().loading(), None, "the read file no longer opens");
    std::thread::sleep(std::time::Duration::from_secs(2));
    h.run_steps(3);
    assert!(
        h.state().doc().graph.node("numbers").is_none(),
        "the document opened last stays: {}",
        h.state().message()
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_large_start_up_file_is_read_after_the_window_opens_and_an_example_stays_a_copy() {
    let dir = temp_config("large-start");
    let big = large_graph(&dir, "big.ron", 500_000);
    // The window is there before the file is read: the harness's first frames draw the notice
    // (or the file, once read); the document is the file when read.
    let mut h = common::harness_on(
        temp_config("large-start-cfg"),
        Some(big.clone()),
        dir.clone(),
    );
    let start = std::time::Instant::now();
    while h.state().loading().is_some() {
        assert!(
            start.elapsed() < Duration::from_secs(300),
            "read within five minutes"
        );
        h.run_steps(1);
        std::thread::sleep(Duration::from_millis(10));
    }
    // In the examples folder the file given is a shipped example: an untitled copy.
    assert_eq!(h.state().doc().path, None, "{}", h.state().message());
    assert_eq!(h.state().doc().origin.as_deref(), Some(big.as_path()));
    assert!(!h.state().doc().is_dirty());
    assert!(
        h.state().message().contains("copy of the example"),
        "{}",
        h.state().message()
    );
    let count = |app: &EditorApp| {
        app.doc()
            .graph
            .node("numbers")
            .and_then(|n| n.value_of("values"))
            .and_then(|v| v.as_list())
            .map(<[_]>::len)
    };
    assert_eq!(count(h.state()), Some(500_000));
    // Outside the examples folder: the file itself. `EditorApp::new` returns before it is read
    // (nothing has polled the reader yet), and the screenshot and benchmark modes wait for it.
    let mut app = EditorApp::new(cnets_editor::app::AppOptions {
        gpu: None,
        config_dir: temp_config("large-start-cfg2"),
        file: Some(big.clone()),
        examples_dir: std::env::temp_dir().join("cnets-no-examples"),
        wake: std::sync::Arc::new(|| {}),
    });
    assert_eq!(app.loading(), Some(big.as_path()), "read off the UI thread");
    assert_eq!(count(&app), None, "an empty document meanwhile");
    assert!(
        !app.wait_for_loading(Duration::from_secs(300)),
        "read in time"
    );
    assert_eq!(app.loading(), None);
    assert_eq!(
        app.doc().path.as_deref(),
        Some(big.as_path()),
        "{}",
        app.message()
    );
    assert_eq!(count(&app), Some(500_000));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_document_edited_while_a_large_file_is_read_is_not_replaced_without_asking() {
    let dir = temp_config("large-edited");
    let big = large_graph(&dir, "big.ron", 500_000);
    for (answer, opens) in [("Cancel", false), ("Don't save", true)] {
        let mut h = harness(&format!("large-edited-{opens}"));
        assert!(h.state_mut().open(&big), "began to be read");
        // An edit before the read is taken up (frames keep running while a file is read).
        h.state_mut()
            .add_node("param.number", [40.0, 40.0])
            .unwrap();
        let edited = h.state().doc().to_ron();
        assert!(!h.state_mut().wait_for_loading(Duration::from_secs(300)));
        assert_eq!(h.state().doc().to_ron(), edited, "not replaced yet");
        h.run_steps(2);
        assert_eq!(
            h.state().unsaved_question(),
            Some(&Replace::Loaded(big.clone())),
            "the unsaved-changes question is asked"
        );
        h.get_by_label(answer).click();
        h.run_steps(3);
        assert_eq!(h.state().unsaved_question(), None);
        assert_eq!(h.state().loading(), None, "{answer}: nothing left reading");
        assert_eq!(h.state().waiting(), None, "{answer}: nothing left waiting");
        if opens {
            assert_eq!(h.state().doc().path.as_deref(), Some(big.as_path()));
            assert!(h.state().doc().graph.node("numbers").is_some());
        } else {
            assert_eq!(
                h.state().doc().to_ron(),
                edited,
                "the edited document stays"
            );
            assert!(
                h.state().message().contains("was not opened"),
                "{}",
                h.state().message()
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// View › Preview only the selected (Grasshopper's *Only draw selected*): with the construction
/// selected only its net is drawn and counted; with nothing selected every previewed node again.
#[test]
fn preview_only_the_selected_draws_the_selected_nodes_alone() {
    let mut h = harness("only-selected");
    let drawn = |h: &Harness<'static, EditorApp>| {
        let picks = h.state().viewport().picks().clone();
        let mut nodes: Vec<String> = picks
            .meshes
            .iter()
            .map(|m| m.node.clone())
            .chain(picks.curves.iter().map(|c| c.node.clone()))
            .collect();
        nodes.sort();
        nodes.dedup();
        nodes
    };
    let all = drawn(&h);
    assert!(
        all.len() > 1 && all.contains(&"construct".to_string()),
        "{all:?}"
    );
    let vertices = h.state().viewport().stats().vertices;
    h.state_mut()
        .run(cnets_editor::menus::MenuAction::ToggleOnlySelected);
    h.state_mut().select_nodes(vec!["directrix".into()]);
    settle(&mut h);
    assert_eq!(drawn(&h), ["directrix"], "only the selected curve");
    assert_eq!(h.state().viewport().stats().vertices, 0, "no mesh counted");
    h.state_mut().select_nodes(vec!["construct".into()]);
    settle(&mut h);
    assert_eq!(drawn(&h), ["construct"]);
    assert_eq!(h.state().viewport().stats().vertices, vertices);
    // Nothing selected: every previewed node; the toggle off: the same.
    h.state_mut().select_nodes(Vec::new());
    settle(&mut h);
    assert_eq!(drawn(&h), all);
    h.state_mut()
        .run(cnets_editor::menus::MenuAction::ToggleOnlySelected);
    h.state_mut().select_nodes(vec!["construct".into()]);
    settle(&mut h);
    assert_eq!(drawn(&h), all, "the toggle off draws every previewed node");
}

/// A phone (390 × 844 points): the 3D view takes at least 60 % of the screen's height, its
/// controls in one row above it, and the parameters stay below it.
#[test]
fn on_a_phone_the_3d_view_takes_most_of_the_screen() {
    let mut h = harness("phone-view");
    h.set_size(egui::vec2(390.0, 844.0));
    settle(&mut h);
    h.run_steps(4);
    let view = h.state().viewport().rect();
    let share = view.height() / 844.0;
    eprintln!(
        "phone: 3D view {view:?}, {:.0} % of the height",
        share * 100.0
    );
    assert!(
        share >= 0.6,
        "the 3D view is {:.0} % of the screen",
        share * 100.0
    );
    assert!(view.width() >= 360.0, "{view:?}");
    let parameters = h
        .state()
        .parameters_rect()
        .expect("the parameters are shown");
    assert!(
        parameters.top() >= view.bottom() - 1.0,
        "{parameters:?} under {view:?}"
    );
    assert!(parameters.height() >= 100.0, "{parameters:?}");
}

/// A touch on the 3D view at `at`: finger `finger` in `phase`.
fn touch(h: &Harness<'static, EditorApp>, finger: u64, phase: egui::TouchPhase, at: egui::Pos2) {
    h.event(egui::Event::Touch {
        device_id: egui::TouchDeviceId(1),
        id: egui::TouchId(finger),
        phase,
        pos: at,
        force: None,
    });
}

/// The camera's distance from its target.
fn dist(c: &cnets_render::Camera) -> f32 {
    (c.eye() - c.target).length()
}

/// Two fingers on the 3D view: spreading them zooms in, moving them together pans (a phone's
/// pinch and two-finger drag).
#[test]
fn two_fingers_on_the_3d_view_pinch_zoom_and_pan() {
    let mut h = harness("pinch");
    settle(&mut h);
    h.run_steps(2);
    let centre = h.state().viewport().rect().center();
    let before = h.state().viewport().framing().camera;
    let apart = |d: f32| (centre - egui::vec2(d, 0.0), centre + egui::vec2(d, 0.0));
    let (a, b) = apart(40.0);
    // A browser's first finger also moves the pointer (egui starts a gesture where it is).
    h.hover_at(a);
    h.run_steps(1);
    touch(&h, 0, egui::TouchPhase::Start, a);
    touch(&h, 1, egui::TouchPhase::Start, b);
    h.run_steps(2);
    for d in [50.0, 60.0, 70.0, 80.0] {
        let (a, b) = apart(d);
        touch(&h, 0, egui::TouchPhase::Move, a);
        touch(&h, 1, egui::TouchPhase::Move, b);
        h.run_steps(1);
    }
    let zoomed = h.state().viewport().framing().camera;
    assert!(
        dist(&zoomed) < 0.7 * dist(&before),
        "spread to twice apart: distance {} → {}",
        dist(&before),
        dist(&zoomed)
    );
    // Both fingers move 60 points to the right together: the view pans (its target moves).
    let (a, b) = apart(80.0);
    for k in 1..=4 {
        let by = egui::vec2(15.0 * k as f32, 0.0);
        touch(&h, 0, egui::TouchPhase::Move, a + by);
        touch(&h, 1, egui::TouchPhase::Move, b + by);
        h.run_steps(1);
    }
    let by = egui::vec2(60.0, 0.0);
    touch(&h, 0, egui::TouchPhase::End, a + by);
    touch(&h, 1, egui::TouchPhase::End, b + by);
    h.run_steps(2);
    let panned = h.state().viewport().framing().camera;
    assert!(
        (panned.target - zoomed.target).length() > 1e-3 * dist(&zoomed),
        "the target moved: {:?} → {:?}",
        zoomed.target,
        panned.target
    );
    assert!(
        (dist(&panned) - dist(&zoomed)).abs() < 0.05 * dist(&zoomed),
        "a common move does not zoom"
    );
}

/// The figures drawn over the 3D view (statistics, legend, picker, axes, size, the grid's name)
/// never overlap, on a phone and on a desktop, in every colour mode.
#[test]
fn the_figures_over_the_3d_view_never_overlap() {
    for (width, height) in [(390.0, 844.0), (1280.0, 800.0)] {
        let mut h = harness("overlays");
        h.set_size(egui::vec2(width, height));
        h.state_mut().viewport_mut().display_mut().show_dimensions = true;
        for mode in cnets_editor::preview::ColorMode::ALL {
            h.state_mut()
                .viewport_mut()
                .display_mut()
                .options
                .color_mode = mode;
            settle(&mut h);
            h.run_steps(3);
            let overlays = h.state().viewport().last_frame().overlays.clone();
            let names: Vec<&str> = overlays.iter().map(|(n, _)| *n).collect();
            assert!(
                ["statistics", "axes", "grid", "size"]
                    .iter()
                    .all(|n| names.contains(n)),
                "{width} × {height}, {mode:?}: {names:?}"
            );
            for (k, (a, ra)) in overlays.iter().enumerate() {
                assert!(
                    h.state().viewport().rect().expand(1.0).contains_rect(*ra),
                    "{a} {ra:?}"
                );
                for (b, rb) in &overlays[k + 1..] {
                    assert!(
                        !ra.intersects(*rb),
                        "{width} × {height}, {mode:?}: {a} {ra:?} overlaps {b} {rb:?}"
                    );
                }
            }
        }
    }
}
