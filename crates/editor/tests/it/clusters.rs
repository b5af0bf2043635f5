//! Clusters in the editor, driven through egui_kittest: make a cluster from a selection, explode
//! it, open it in place and come back, the library in the palette, cluster files reloaded when
//! they change on disk.

use crate::common;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::time::Duration;

use cnets_editor::app::EditorApp;
use cnets_editor::canvas::CanvasAction;
use cnets_editor::edit::Edit;
use cnets_editor::worker::NodeStatus;
use cnets_engine::Value;
use cnets_engine::cluster::Cluster;
use common::{harness, harness_with, settle, temp_config};
use egui::{Key, Modifiers, Pos2};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

fn face_positions(app: &EditorApp) -> Vec<[u32; 3]> {
    app.viewport()
        .scene()
        .face_vertices()
        .iter()
        .map(|v| v.position.map(f32::to_bits))
        .collect()
}

fn wires(app: &EditorApp) -> BTreeSet<String> {
    app.doc()
        .graph
        .wires()
        .iter()
        .map(ToString::to_string)
        .collect()
}

fn node_ids(app: &EditorApp) -> BTreeSet<String> {
    app.doc().graph.nodes().map(|(_, n)| n.id.clone()).collect()
}

/// Presses and releases the primary button twice at `at`.
fn double_click(h: &mut Harness<'static, EditorApp>, at: Pos2) {
    h.hover_at(at);
    h.run_steps(2);
    for _ in 0..2 {
        for pressed in [true, false] {
            h.event(egui::Event::PointerButton {
                pos: at,
                button: egui::PointerButton::Primary,
                pressed,
                modifiers: Modifiers::NONE,
            });
        }
    }
    h.run_steps(3);
}

/// The screen centre of the title label of node `id` (labels on the canvas have canvas
/// coordinates).
fn title(h: &Harness<'static, EditorApp>, id: &str) -> Pos2 {
    let canvas = &h.state().canvas();
    let node = canvas.node_screen_rect(id).expect("the node is drawn");
    h.get_all_by_label(id)
        .map(|l| canvas.to_screen(l.rect().center()))
        .find(|p| node.contains(*p))
        .expect("the node's title")
}

/// Selects nodes with Shift+click on their frames (as the designer does).
fn select(h: &mut Harness<'static, EditorApp>, ids: &[&str]) {
    for id in ids {
        let rect = h.state().canvas().node_screen_rect(id).expect("drawn");
        let at = Pos2::new(rect.center().x, rect.bottom() - 4.0);
        h.hover_at(at);
        h.event(egui::Event::ModifiersChanged(Modifiers::SHIFT));
        for pressed in [true, false] {
            h.event(egui::Event::PointerButton {
                pos: at,
                button: egui::PointerButton::Primary,
                pressed,
                modifiers: Modifiers::SHIFT,
            });
        }
        h.event(egui::Event::ModifiersChanged(Modifiers::NONE));
        h.run_steps(2);
    }
    let selected: BTreeSet<String> = h.state().canvas().selected.iter().cloned().collect();
    let wanted: BTreeSet<String> = ids.iter().map(|s| s.to_string()).collect();
    assert_eq!(selected, wanted, "Shift+click selects");
}

/// Selects `ids` and makes a cluster of them with Ctrl+G.
fn make_cluster(h: &mut Harness<'static, EditorApp>, ids: &[&str]) {
    select(h, ids);
    h.key_press_modifiers(Modifiers::COMMAND, Key::G);
    settle(h);
}

#[test]
fn make_cluster_keeps_the_mesh_undo_restores_the_text_explode_restores_the_nodes() {
    let mut h = harness("make-cluster");
    let before_text = h.state().doc().to_ron();
    let before_mesh = face_positions(h.state());
    let before_wires = wires(h.state());
    let before_nodes = node_ids(h.state());
    assert!(!before_mesh.is_empty());
    let steps = h.state().doc().history.undo_len();

    make_cluster(&mut h, &["apex", "ratio", "construct"]);
    let app = h.state();
    let node = app
        .doc()
        .graph
        .node("cluster")
        .unwrap_or_else(|| panic!("a cluster node: {}", app.message()));
    let inputs: Vec<&str> = node.def.inputs.iter().map(|p| p.name.as_ref()).collect();
    let outputs: Vec<&str> = node.def.outputs.iter().map(|p| p.name.as_ref()).collect();
    assert_eq!(inputs, ["directrix", "generatrix"], "the wires coming in");
    assert_eq!(outputs, ["mesh"], "the wire going out");
    assert!(Cluster::of(&node.def).is_some());
    for gone in ["apex", "ratio", "construct"] {
        assert!(app.doc().graph.node(gone).is_none());
    }
    assert_eq!(app.doc().history.undo_len(), steps + 1, "one undo step");
    assert!(
        matches!(app.statuses()["cluster"], NodeStatus::Ok { .. }),
        "{:?}",
        app.statuses()["cluster"]
    );
    assert_eq!(
        face_positions(app),
        before_mesh,
        "the viewport's mesh is unchanged, bit for bit"
    );

    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    settle(&mut h);
    assert_eq!(
        h.state().doc().to_ron(),
        before_text,
        "undo restores the text"
    );
    assert_eq!(face_positions(h.state()), before_mesh);

    h.key_press_modifiers(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z);
    settle(&mut h);
    assert!(h.state().doc().graph.node("cluster").is_some(), "redo");
    h.state_mut().focus_node(Some("cluster".into()));
    h.state_mut().select_nodes(Vec::new());
    h.key_press_modifiers(Modifiers::COMMAND | Modifiers::SHIFT, Key::G);
    settle(&mut h);
    let app = h.state();
    assert_eq!(node_ids(app), before_nodes, "explode gives the nodes back");
    assert_eq!(wires(app), before_wires, "and the wires");
    for (id, n) in app.doc().graph.nodes().map(|(_, n)| (n.id.clone(), n)) {
        let ours: Vec<_> = (0..n.def.inputs.len())
            .map(|k| n.value(k).cloned())
            .collect();
        let original = cnets_engine::file::load_str(&before_text, "before", app.registry())
            .unwrap()
            .graph;
        let o = original.node(&id).unwrap();
        let theirs: Vec<_> = (0..o.def.inputs.len())
            .map(|k| o.value(k).cloned())
            .collect();
        assert_eq!(ours, theirs, "values of '{id}'");
    }
    assert_eq!(face_positions(app), before_mesh);
}

#[test]
fn open_a_cluster_edit_inside_and_go_back_changes_the_outer_result_undo_crosses_levels() {
    let mut h = harness("open-cluster");
    make_cluster(&mut h, &["apex", "ratio", "construct"]);
    let made = h.state().doc().to_ron();
    let outer_mesh = face_positions(h.state());

    // Double-click the cluster's title: the canvas shows the subgraph.
    let at = title(&h, "cluster");
    double_click(&mut h, at);
    settle(&mut h);
    let app = h.state();
    assert_eq!(app.doc().depth(), 1, "{}", app.message());
    assert!(app.doc().graph.node("construct").is_some(), "the subgraph");
    assert_eq!(app.doc().breadcrumbs(), ["main", "cluster (inline)"]);
    // The inner nodes ran on the values the cluster receives (the graph inputs have no default).
    assert!(
        matches!(app.statuses()["construct"], NodeStatus::Ok { .. }),
        "{:?}",
        app.statuses().get("construct")
    );
    assert!(h.query_by_label("main").is_some(), "the breadcrumb bar");
    h.remove_cursor();
    h.run_steps(2);
    h.snapshot("editor_cluster_breadcrumbs");

    // Change a value inside: the live evaluation follows at once.
    let steps = h.state().doc().history.undo_len();
    assert!(h.state_mut().apply(CanvasAction::Edit(Edit::SetValue {
        node: "ratio".into(),
        input: "value".into(),
        value: Value::Number(0.3),
    })));
    h.state_mut().end_gesture();
    settle(&mut h);
    assert_ne!(
        h.state().doc().to_ron(),
        made,
        "the document text includes the edit"
    );

    // Esc goes back: the cluster is rebuilt and the outer result changes.
    h.key_press(Key::Escape);
    settle(&mut h);
    let app = h.state();
    assert_eq!(app.doc().depth(), 0);
    assert!(app.doc().graph.node("planarity").is_some());
    assert!(
        app.doc()
            .graph
            .wires()
            .iter()
            .any(|w| w.from == "cluster" && w.to == "planarity"),
        "the cluster keeps its wires"
    );
    assert_ne!(face_positions(app), outer_mesh, "the outer mesh changed");
    assert!(app.doc().to_ron().contains("0.3"), "saved inline");
    assert_eq!(
        app.doc().history.undo_len(),
        steps + 2,
        "the edit and the leave"
    );

    // Undo across levels: back inside with the edit, then without it.
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    settle(&mut h);
    assert_eq!(h.state().doc().depth(), 1, "undo returns inside");
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    settle(&mut h);
    let value = h
        .state()
        .doc()
        .graph
        .node("ratio")
        .and_then(|n| n.value_of("value"))
        .and_then(Value::as_f64);
    assert_eq!(value, Some(0.5));
    assert_eq!(h.state().doc().to_ron(), made, "the text before the edit");
    h.key_press(Key::Escape);
    settle(&mut h);
    assert_eq!(h.state().doc().depth(), 0);
    assert_eq!(
        h.state().doc().to_ron(),
        made,
        "leaving unchanged changes nothing"
    );
    assert_eq!(face_positions(h.state()), outer_mesh);
}

#[test]
fn nested_clusters_open_with_breadcrumbs_of_any_depth() {
    let mut h = harness("nested");
    make_cluster(&mut h, &["apex", "ratio"]);
    make_cluster(&mut h, &["cluster", "construct"]);
    let outer = h.state().doc().to_ron();
    h.state_mut().open_cluster("cluster_2");
    h.state_mut().open_cluster("cluster");
    settle(&mut h);
    let app = h.state();
    assert_eq!(app.doc().depth(), 2);
    assert_eq!(
        app.doc().breadcrumbs(),
        ["main", "cluster_2 (inline)", "cluster (inline)"]
    );
    assert!(matches!(app.statuses()["apex"], NodeStatus::Ok { .. }));
    h.state_mut().apply(CanvasAction::Edit(Edit::SetValue {
        node: "apex".into(),
        input: "value".into(),
        value: Value::Number(1.2),
    }));
    settle(&mut h);
    // The first crumb goes back to the document's graph through both levels.
    h.get_by_label("main").click();
    settle(&mut h);
    let app = h.state();
    assert_eq!(app.doc().depth(), 0, "{}", app.message());
    assert_ne!(app.doc().to_ron(), outer);
    assert!(app.doc().to_ron().contains("1.2"));
}

const TWICE: &str = r#"(
    version: 1,
    name: "twice",
    description: "Twice its input.",
    nodes: {
        "x": (type: "graph.input", position: (0.0, 0.0), inputs: {"name": "x", "type": "number", "default": 1.0}),
        "times": (type: "math.multiply", position: (200.0, 0.0), inputs: {"b": 2.0}),
        "y": (type: "graph.output", position: (400.0, 0.0), inputs: {"name": "y", "type": "number"}),
    },
    edges: ["x.value -> times.a", "times.result -> y.value"],
)"#;

fn library(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "cnets-editor-library-{}-{name}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn output_of(app: &EditorApp, id: &str) -> Vec<String> {
    match &app.statuses()[id] {
        NodeStatus::Ok { outputs, .. } => outputs.clone(),
        other => panic!("{id}: {other:?}"),
    }
}

#[test]
fn a_library_graph_appears_in_the_palette_and_inserts_a_working_cluster() {
    let lib = library("palette");
    std::fs::write(lib.join("twice.ron"), TWICE).unwrap();
    let config = temp_config("library");
    std::fs::write(config.join("library.txt"), format!("{}\n", lib.display())).unwrap();
    let mut h = harness_with("library", None, config);
    h.state_mut().open_palette_at([900.0, 700.0]);
    h.run_steps(2);
    // The palette's search field has the focus (node editors have text fields too).
    h.get_by(|n| n.role() == egui::accesskit::Role::TextInput && n.is_focused())
        .type_text("twice");
    h.run_steps(3);
    h.get_by_label("twice (cluster)").click();
    h.run_steps(3);
    let id = common::focused_node(&h);
    assert_eq!(id, "twice");
    let node = h.state().doc().graph.node(&id).unwrap();
    let cluster = Cluster::of(&node.def).expect("a cluster node");
    assert_eq!(cluster.label(), "twice.ron");
    assert!(
        h.state().doc().to_ron().contains("source: \"twice.ron\""),
        "resolved through the library folder"
    );
    h.state_mut().apply(CanvasAction::Edit(Edit::SetValue {
        node: id.clone(),
        input: "x".into(),
        value: Value::Number(3.5),
    }));
    settle(&mut h);
    assert_eq!(output_of(h.state(), &id), ["7"]);
    // The saved file loads back with the same library folder.
    let saved = lib.join("uses-twice.ron");
    h.state_mut().save_as(&saved);
    let options = cnets_host::document_options(Some(&saved), std::slice::from_ref(&lib));
    cnets_engine::file::load_file_with(&saved, h.state().registry(), &options)
        .expect("loads again");
    std::fs::remove_dir_all(&lib).unwrap();
}

const MAIN: &str = r#"(
    version: 1,
    nodes: {
        "n": (type: "param.number", position: (0.0, 0.0), inputs: {"value": 4.0, "min": 0.0, "max": 10.0}),
        "t": (type: "cluster", source: "twice.ron", position: (250.0, 0.0)),
        "after": (type: "math.add", position: (500.0, 0.0), inputs: {"b": 1.0}),
    },
    edges: ["n.value -> t.x", "t.y -> after.a"],
)"#;

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn a_cluster_file_changed_on_disk_is_reloaded() {
    let dir = library("watch");
    write(&dir, "twice.ron", TWICE);
    let main = write(&dir, "main.ron", MAIN);
    let mut h = harness_with("watch", Some(main), temp_config("watch"));
    assert_eq!(output_of(h.state(), "after"), ["9"], "4 · 2 + 1");
    let steps = h.state().doc().history.undo_len();
    write(
        &dir,
        "twice.ron",
        &TWICE.replace("\"b\": 2.0", "\"b\": 3.0"),
    );
    // The editor polls about once a second.
    std::thread::sleep(Duration::from_millis(1100));
    h.run_steps(2);
    settle(&mut h);
    let app = h.state();
    assert!(app.message().contains("reloaded 't'"), "{}", app.message());
    assert_eq!(output_of(app, "after"), ["13"], "4 · 3 + 1");
    assert_eq!(app.doc().history.undo_len(), steps, "not an undo step");
    assert!(!app.doc().is_dirty(), "the graph's text did not change");
    // A renamed output drops the wire and says so.
    write(
        &dir,
        "twice.ron",
        &TWICE.replace("\"name\": \"y\"", "\"name\": \"z\""),
    );
    h.state_mut().check_cluster_files();
    settle(&mut h);
    let app = h.state();
    assert!(
        app.message().contains("dropped wires: t.y -> after.a"),
        "{}",
        app.message()
    );
    assert!(!app.doc().graph.wires().iter().any(|w| w.from == "t"));
    std::fs::remove_dir_all(&dir).unwrap();
}
