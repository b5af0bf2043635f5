//! Files and names (issue 26, point 5): File ▸ Export runs the graph's own export nodes and lists
//! what they wrote, a quick export asks for the name, a path input's Browse… and the "Allow
//! reading this folder" prompt make a file outside the graph's folder readable for the document
//! (kept with the editor's per-document settings, not in the graph file), and nodes get display
//! names that the canvas and the parameter panel show.

use crate::common;

use std::path::{Path, PathBuf};

use cnets_editor::EditorApp;
use cnets_editor::edit::Edit;
use cnets_editor::export::ExportFormat;
use cnets_editor::menus::MenuAction;
use cnets_editor::settings::Settings;
use cnets_editor::worker::NodeStatus;
use cnets_engine::Value;
use common::{harness, harness_with, settle, temp_config};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

type H = Harness<'static, EditorApp>;

/// A fresh folder for one test's files.
fn folder(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("cnets-files-names-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The editor's default graph with `extra` nodes and `wires` added.
fn graph_with(extra: &str, wires: &str) -> String {
    let text = include_str!("../../../../graphs/editor-default.ron");
    let text = text.replacen("    nodes: {\n", &format!("    nodes: {{\n{extra}"), 1);
    text.replacen("    edges: [\n", &format!("    edges: [\n{wires}"), 1)
}

/// A graph that unrolls the default cone-net and writes an SVG sheet `panels.svg` at `scale`.
fn svg_graph(scale: f64) -> String {
    graph_with(
        &format!(
            r#"        "unroll": (
            type: "pq.unroll_strips",
            position: (900.0, 0.0),
            preview: false,
        ),
        "sheet": (
            type: "io.export_svg",
            position: (1300.0, 0.0),
            inputs: {{
                "name": "panels.svg",
                "scale": {scale:?},
            }},
        ),
"#
        ),
        "        \"construct.mesh -> unroll.mesh\",\n        \"unroll.outlines -> sheet.outlines\",\n        \"unroll.labels -> sheet.labels\",\n",
    )
}

/// Types `path` into the open file dialog and clicks `button`.
fn choose(h: &mut H, path: &Path, button: &str) {
    h.run_steps(2);
    h.state_mut()
        .dialog_mut()
        .expect("the file dialog is open")
        .path = path.display().to_string();
    // Let the dialog lay itself out for the new folder before clicking.
    h.run_steps(4);
    h.get_by_label(button).click();
    h.run_steps(3);
}

/// Runs File ▸ Export ▸ Graph's exports… into `out` (the menu's action, then the dialog).
fn run_graph_exports(h: &mut H, out: &Path) {
    h.state_mut().run(MenuAction::RunExports);
    choose(h, out, "Export here");
}

#[test]
fn file_export_runs_the_graphs_own_export_nodes() {
    let dir = folder("export");
    let graph = dir.join("sheet.ron");
    std::fs::write(&graph, svg_graph(1000.0)).unwrap();
    let mut h = harness_with("export", Some(graph.clone()), temp_config("export"));
    let out = dir.join("out");
    run_graph_exports(&mut h, &out);
    // The node's own file name, not a name made up by the menu.
    let svg = out.join("panels.svg");
    let report = h
        .state()
        .export_report()
        .cloned()
        .expect("what was written is listed");
    assert_eq!(report.files(), vec![svg.clone()]);
    assert_eq!(report.runs[0].node, "sheet");
    assert!(
        h.query_by_label(&svg.display().to_string()).is_some(),
        "the dialog lists the written path"
    );
    let first = std::fs::read(&svg).unwrap();
    assert!(String::from_utf8_lossy(&first).contains("<svg"));
    // The list closes; the graph's settings change the file: half the scale, other bytes.
    h.get_by_label("Close").click();
    h.run_steps(2);
    assert!(h.state().export_report().is_none());
    assert!(h.state_mut().edit(Edit::SetValue {
        node: "sheet".into(),
        input: "scale".into(),
        value: Value::Number(500.0),
    }));
    h.run_steps(2);
    run_graph_exports(&mut h, &out);
    let second = std::fs::read(&svg).unwrap();
    assert_ne!(first, second, "the export follows the node's settings");
    // As the command line writes it: `cnets run --out` of the saved graph.
    assert_eq!(
        h.state().export_report().as_ref().unwrap().files(),
        vec![svg.clone()]
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_quick_export_of_the_preview_asks_for_the_name() {
    let dir = folder("quick");
    let graph = dir.join("canopy.ron");
    std::fs::write(&graph, graph_with("", "")).unwrap();
    let mut h = harness_with("quick", Some(graph), temp_config("quick"));
    // Without export nodes there is nothing to run.
    h.state_mut().run(MenuAction::RunExports);
    h.run_steps(2);
    assert!(h.state_mut().dialog_mut().is_none());
    assert_eq!(h.state().message(), "this graph has no export nodes");
    h.state_mut().run(MenuAction::Export(ExportFormat::Obj));
    h.run_steps(2);
    // The dialog offers the document's name, and takes the one typed.
    let offered = h.state_mut().dialog_mut().unwrap().path.clone();
    assert_eq!(offered, dir.join("canopy.obj").display().to_string());
    let named = dir.join("exports").join("my canopy");
    std::fs::create_dir_all(named.parent().unwrap()).unwrap();
    choose(&mut h, &named, "Export file");
    let obj = dir.join("exports").join("my canopy.obj");
    assert!(obj.is_file(), "{}", h.state().message());
    assert_eq!(
        h.state().export_report().as_ref().unwrap().files(),
        vec![obj.clone()]
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// A graph reading polylines from `path`.
fn reader_graph(path: &str) -> String {
    graph_with(
        &format!(
            r#"        "site": (
            type: "io.read_polylines",
            position: (900.0, 0.0),
            inputs: {{
                "path": {path:?},
            }},
        ),
"#
        ),
        "",
    )
}

fn site_status(h: &H) -> NodeStatus {
    h.state().statuses()["site"].clone()
}

/// Two polylines in a CSV file.
const CSV: &str = "0, 0, 0\n1, 0, 0\n1, 1, 0\n\n5, 5, 0\n6, 5, 0\n";

#[test]
fn a_browse_picked_file_outside_the_graphs_folder_is_read() {
    let dir = folder("browse");
    let (project, elsewhere) = (dir.join("project"), dir.join("survey"));
    std::fs::create_dir_all(&project).unwrap();
    std::fs::create_dir_all(&elsewhere).unwrap();
    let csv = elsewhere.join("site.csv");
    std::fs::write(&csv, CSV).unwrap();
    let graph = project.join("design.ron");
    std::fs::write(&graph, reader_graph("")).unwrap();
    let config = temp_config("browse");
    let mut h = harness_with("browse", Some(graph.clone()), config.clone());
    assert!(site_status(&h).error().is_some(), "no file yet");
    // The node's path input has its Browse… button; it asks for the built-in dialog (a click on
    // it inside the canvas does not register in this harness — see the report of issue 26 — so
    // the test makes the request the button makes), which is driven as a designer would.
    assert!(
        h.query_by_label("Browse…").is_some(),
        "the path input has Browse…"
    );
    h.state_mut().browse("site", "path");
    choose(&mut h, &csv, "Pick");
    settle(&mut h);
    let status = site_status(&h);
    assert!(status.error().is_none(), "{status:?}");
    assert_eq!(
        h.state().doc().graph.node("site").unwrap().value_of("path"),
        Some(&Value::text(csv.display().to_string()))
    );
    assert!(
        h.state().read_prompt().is_none(),
        "no prompt for a picked file"
    );
    // Kept with the document's settings, not in the graph file.
    assert_eq!(
        Settings::load(&config).allowed_reads(&graph),
        vec![csv.clone()]
    );
    h.state_mut().run(MenuAction::Save);
    h.run_steps(2);
    let saved = std::fs::read_to_string(&graph).unwrap();
    assert_eq!(
        saved.matches("survey").count(),
        1,
        "only the path itself:\n{saved}"
    );
    // A later session on the same file reads it without asking.
    drop(h);
    let h = harness_with("browse-again", Some(graph.clone()), config);
    assert!(site_status(&h).error().is_none(), "{:?}", site_status(&h));
    assert!(h.state().read_prompt().is_none());
    // Another document is not allowed: the permission is the document's.
    let other = project.join("other.ron");
    std::fs::write(&other, reader_graph(&csv.display().to_string())).unwrap();
    let h = harness_with("browse-other", Some(other), temp_config("browse-other"));
    let refused = site_status(&h);
    assert!(
        refused.error().is_some_and(|e| e.contains("outside")),
        "{refused:?}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_refused_read_asks_to_allow_its_folder() {
    let dir = folder("prompt");
    let (project, elsewhere) = (dir.join("project"), dir.join("survey"));
    std::fs::create_dir_all(&project).unwrap();
    std::fs::create_dir_all(&elsewhere).unwrap();
    let csv = elsewhere.join("site.csv");
    std::fs::write(&csv, CSV).unwrap();
    let graph = project.join("design.ron");
    std::fs::write(&graph, reader_graph(&csv.display().to_string())).unwrap();
    let config = temp_config("prompt");
    let mut h = harness_with("prompt", Some(graph.clone()), config.clone());
    let prompt = h
        .state()
        .read_prompt()
        .cloned()
        .expect("the refused read asks");
    assert_eq!(prompt.path, csv);
    assert_eq!(prompt.folder, elsewhere);
    h.get_by_label("Allow reading this folder").click();
    h.run_steps(2);
    settle(&mut h);
    assert!(site_status(&h).error().is_none(), "{:?}", site_status(&h));
    assert!(h.state().read_prompt().is_none());
    assert_eq!(
        Settings::load(&config).allowed_reads(&graph),
        vec![elsewhere.clone()]
    );
    // "Not now" is not asked again for the document.
    let other = project.join("other.ron");
    std::fs::write(&other, reader_graph(&csv.display().to_string())).unwrap();
    let mut h = harness_with("prompt-no", Some(other), temp_config("prompt-no"));
    assert!(h.state().read_prompt().is_some());
    h.get_by_label("Not now").click();
    h.run_steps(2);
    h.state_mut().reevaluate();
    settle(&mut h);
    assert!(
        h.state().read_prompt().is_none(),
        "declined: not asked again"
    );
    assert!(site_status(&h).error().is_some());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_renamed_node_is_shown_by_its_name_and_saved_with_the_graph() {
    let mut h = harness("rename");
    let before = h.state().doc().to_ron();
    h.state_mut().show_parameters(true);
    h.run_steps(3);
    assert!(h.query_by_label("Apex height").is_none());
    // Right-click ▸ Name ▸ Rename node makes this edit (the canvas's context menu does not open
    // from a right-click in this harness; see the report of issue 26).
    assert!(
        h.state_mut()
            .edit(Edit::Rename("apex".into(), Some("Apex height".into())))
    );
    h.run_steps(3);
    settle(&mut h);
    let app = h.state();
    let node = app.doc().graph.node("apex").unwrap();
    assert_eq!(node.name.as_deref(), Some("Apex height"));
    assert_eq!(node.id, "apex", "the id stays: wires and --set use it");
    // The canvas title and the parameter panel show the name (the panel's is a second label).
    assert_eq!(h.query_all_by_label("Apex height").count(), 2);
    // Saved with the graph, loaded back; the evaluation did not change.
    let text = app.doc().to_ron();
    assert!(text.contains("name: \"Apex height\""), "{text}");
    let registry = std::sync::Arc::new(cnets_nodes::registry());
    let loaded = cnets_engine::file::load_str(&text, "renamed", &registry).unwrap();
    assert_eq!(loaded.graph.node("apex").unwrap().label(), "Apex height");
    // One undo step, undone exactly; an old file (no names) loads unchanged.
    h.state_mut().run(MenuAction::Undo);
    h.run_steps(2);
    assert_eq!(h.state().doc().to_ron(), before);
    let old = cnets_engine::file::load_str(&before, "old", &registry).unwrap();
    assert!(old.graph.nodes().all(|(_, n)| n.name.is_none()));
    assert_eq!(cnets_engine::file::to_ron(&old.graph, &old.meta), before);
}
