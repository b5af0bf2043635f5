//! A file an importing node reads, re-saved by another program while the graph is open, is read
//! again: the editor's watch sees it changed and the worker re-runs the reader and its dependents.

use crate::common;

use cnets_editor::app::EditorApp;
use cnets_editor::worker::NodeStatus;
use common::{harness_with, settle, temp_config};

const GRAPH: &str = r#"(
    version: 1,
    nodes: {
        "read": (type: "io.read_polylines", position: (0.0, 0.0), inputs: {"path": "profile.csv"}),
        "first": (type: "list.item", position: (300.0, 0.0)),
        "len": (type: "curve.length", position: (600.0, 0.0)),
    },
    edges: ["read.curves -> first.list", "first.item -> len.curve"],
)"#;

fn output_of(app: &EditorApp, id: &str) -> Vec<String> {
    match &app.statuses()[id] {
        NodeStatus::Ok { outputs, .. } => outputs.clone(),
        other => panic!("{id}: {other:?}"),
    }
}

#[test]
fn a_re_saved_import_is_read_again() {
    let dir = temp_config("imported-files");
    std::fs::write(dir.join("profile.csv"), "0,0,0\n3,0,0\n").unwrap();
    let file = dir.join("main.ron");
    std::fs::write(&file, GRAPH).unwrap();
    let mut h = harness_with("imported", Some(file), temp_config("imported-config"));
    settle(&mut h);
    let before = output_of(h.state(), "len");
    assert!(before.iter().any(|o| o.contains('3')), "{before:?}");
    assert!(
        !h.state_mut().check_imported_files(),
        "first look: remembered"
    );
    std::fs::write(dir.join("profile.csv"), "0,0,0\n0,0,4.5\n").unwrap();
    assert!(h.state_mut().check_imported_files(), "the rewrite is seen");
    settle(&mut h);
    let after = output_of(h.state(), "len");
    assert!(after.iter().any(|o| o.contains("4.5")), "{after:?}");
    assert!(
        !h.state().doc().is_dirty(),
        "the graph's text did not change"
    );
}
