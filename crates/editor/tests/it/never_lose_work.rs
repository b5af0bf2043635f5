//! The editor never loses a designer's work: the unsaved-changes guard on every path that
//! replaces or closes the document, examples opened as untitled copies, and a file that fails to
//! load shown with its diagnostics while the document stays. (Recovery after SIGKILL in the real
//! window: `tests/it/window.rs`.)

use crate::common;

use std::path::{Path, PathBuf};

use cnets_editor::app::{DEFAULT_GRAPH, EditorApp};
use cnets_editor::menus::MenuAction;
use cnets_editor::unsaved::Replace;
use cnets_engine::Value;
use common::{harness, harness_with, temp_config};
use egui::{Key, Modifiers};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

type H = Harness<'static, EditorApp>;

/// A file dropped on the window (what egui-winit hands egui).
#[derive(Debug)]
struct Dropped(PathBuf);

impl egui::DroppedFile for Dropped {
    fn path(&self) -> &Path {
        &self.0
    }

    fn bytes(&self) -> Result<Vec<u8>, String> {
        std::fs::read(&self.0).map_err(|e| e.to_string())
    }
}

fn make_dirty(h: &mut H, x: f64) {
    h.state_mut()
        .edit_graph(|g, _| {
            g.set_value("ratio", "value", Value::Number(x))
                .map(|_| ())
                .map_err(|e| e.to_string())
        })
        .unwrap();
    h.run_steps(2);
    assert!(h.state().doc().is_dirty());
}

/// Another valid graph file (in a folder of its own, so it is no example).
fn other_graph(config: &Path) -> PathBuf {
    let dir = config.join("work");
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("other.ron");
    let text = DEFAULT_GRAPH.replace("\"ratio\"", "\"ratio_other\"");
    let text = text.replace("ratio.value", "ratio_other.value");
    std::fs::write(&p, text).unwrap();
    p
}

fn ratio(h: &H) -> Option<f64> {
    h.state()
        .doc()
        .graph
        .node("ratio")
        .and_then(|n| n.value_of("ratio").or_else(|| n.value_of("value")))
        .and_then(Value::as_f64)
}

#[test]
fn every_path_that_replaces_or_closes_the_document_asks_first() {
    let config = temp_config("guard");
    let other = other_graph(&config);
    let example = common::examples_of(&config).join("cnets-example.ron");
    std::fs::write(&example, DEFAULT_GRAPH).unwrap();
    let mut h = harness_with("guard", None, config.clone());
    let (tx, rx) = std::sync::mpsc::channel();
    h.state_mut().set_inbox(rx);
    make_dirty(&mut h, 0.31);
    let text = h.state().doc().to_ron();
    type Trigger = Box<dyn Fn(&mut H)>;
    let o = other.clone();
    let o2 = other.clone();
    let o3 = other.clone();
    let o4 = other.clone();
    let e = example.clone();
    let paths: Vec<(&str, Trigger, Replace)> = vec![
        (
            "File ▸ New",
            Box::new(|h: &mut H| h.state_mut().run(MenuAction::New)),
            Replace::New,
        ),
        (
            "File ▸ Open…",
            Box::new(move |h: &mut H| {
                h.state_mut().run(MenuAction::Open);
                h.run_steps(2);
                h.state_mut().dialog_mut().unwrap().path = o.display().to_string();
                h.run_steps(6);
                h.get_by_label("Open").click();
            }),
            Replace::Open(other.clone()),
        ),
        (
            "Open recent",
            Box::new(move |h: &mut H| h.state_mut().run(MenuAction::OpenPath(o2.clone()))),
            Replace::Open(other.clone()),
        ),
        (
            "Open example",
            Box::new(move |h: &mut H| h.state_mut().run(MenuAction::OpenExample(e.clone()))),
            Replace::Example(example.clone()),
        ),
        (
            "a file dropped on the window",
            Box::new(move |h: &mut H| {
                h.input_mut()
                    .dropped_files
                    .push(std::sync::Arc::new(Dropped(o3.clone())))
            }),
            Replace::Open(other.clone()),
        ),
        (
            "cnets-editor FILE while the window is open",
            Box::new(move |_h: &mut H| tx.send(o4.clone()).unwrap()),
            Replace::Open(other.clone()),
        ),
        (
            "Ctrl+Q",
            Box::new(|h: &mut H| h.key_press_modifiers(Modifiers::COMMAND, Key::Q)),
            Replace::Quit,
        ),
        (
            "the window's close button",
            Box::new(|h: &mut H| {
                h.input_mut()
                    .viewports
                    .entry(egui::ViewportId::ROOT)
                    .or_default()
                    .events
                    .push(egui::ViewportEvent::Close)
            }),
            Replace::Quit,
        ),
    ];
    for (name, trigger, expected) in &paths {
        trigger(&mut h);
        h.run_steps(3);
        assert_eq!(
            h.state().unsaved_question(),
            Some(expected),
            "{name}: asks before replacing"
        );
        assert_eq!(
            h.state().doc().to_ron(),
            text,
            "{name}: nothing replaced yet"
        );
        assert!(!h.state().wants_to_quit(), "{name}: not closing yet");
        h.get_by_label("Cancel").click();
        h.run_steps(2);
        assert!(
            h.state().unsaved_question().is_none(),
            "{name}: question gone"
        );
        assert_eq!(
            h.state().doc().to_ron(),
            text,
            "{name}: Cancel keeps the document"
        );
        assert!(
            h.state().doc().is_dirty() && !h.state().wants_to_quit(),
            "{name}"
        );
    }
    // Don't save: the other graph replaces the document.
    h.state_mut().run(MenuAction::OpenPath(other.clone()));
    h.run_steps(2);
    h.get_by_label("Don't save").click();
    h.run_steps(2);
    assert_eq!(h.state().doc().path.as_deref(), Some(other.as_path()));
    assert!(
        h.state().doc().graph.node("ratio_other").is_some(),
        "the other graph"
    );
    assert!(!h.state().doc().is_dirty());
    std::fs::remove_file(&example).ok();
}

#[test]
fn save_in_the_question_saves_first_untitled_through_save_as() {
    let config = temp_config("guard-save");
    let other = other_graph(&config);
    // An untitled document: Save opens Save As, then the open goes on.
    let mut h = harness_with("guard-save", None, config.clone());
    make_dirty(&mut h, 0.27);
    let text = h.state().doc().to_ron();
    h.state_mut().run(MenuAction::OpenPath(other.clone()));
    h.run_steps(2);
    h.get_by_label("Save").click();
    h.run_steps(2);
    let target = config.join("mine.ron");
    h.state_mut().dialog_mut().expect("Save As is shown").path = target.display().to_string();
    // Let the dialog lay itself out for the new folder before clicking (its size follows the
    // listing; a click in the same frame can miss the moved button).
    h.run_steps(4);
    h.get_by_label("Save").click();
    h.run_steps(3);
    assert_eq!(
        std::fs::read_to_string(&target).unwrap(),
        text,
        "saved first"
    );
    assert_eq!(
        h.state().doc().path.as_deref(),
        Some(other.as_path()),
        "then opened"
    );
    // A document with a file: Save writes it in place, then File ▸ New goes on.
    h.state_mut()
        .edit_graph(|g, _| {
            g.set_value("ratio_other", "value", Value::Number(0.29))
                .map(|_| ())
                .map_err(|e| e.to_string())
        })
        .unwrap();
    let text = h.state().doc().to_ron();
    h.state_mut().run(MenuAction::New);
    h.run_steps(2);
    h.get_by_label("Save").click();
    h.run_steps(2);
    assert_eq!(
        std::fs::read_to_string(&other).unwrap(),
        text,
        "saved in place"
    );
    assert_eq!(h.state().doc().graph.node_count(), 0, "then the new graph");
    // Untitled, Save, then Cancel in Save As: nothing is saved or replaced.
    h.state_mut().add_node("param.number", [0.0, 0.0]).unwrap();
    let text = h.state().doc().to_ron();
    h.state_mut().run(MenuAction::OpenPath(other.clone()));
    h.run_steps(2);
    h.get_by_label("Save").click();
    h.run_steps(4);
    assert!(h.state_mut().dialog_mut().is_some());
    h.get_by_label("Cancel").click();
    h.run_steps(2);
    assert_eq!(
        h.state().doc().to_ron(),
        text,
        "the untitled document stays"
    );
    assert!(h.state_mut().dialog_mut().is_none());
}

#[test]
fn examples_open_as_untitled_copies_and_the_first_save_asks_where() {
    let config = temp_config("example");
    let examples = config.join("graphs");
    std::fs::create_dir_all(&examples).unwrap();
    let shipped = examples.join("torus-monge.ron");
    std::fs::write(&shipped, DEFAULT_GRAPH).unwrap();
    // Started with no file on an examples folder holding torus-monge.ron: an untitled copy.
    let mut h = common::harness_on(config.clone(), None, examples.clone());
    assert_eq!(h.state().doc().path, None, "untitled");
    assert_eq!(h.state().doc().origin.as_deref(), Some(shipped.as_path()));
    assert!(
        h.state()
            .doc()
            .title()
            .contains("copy of example torus-monge.ron")
    );
    make_dirty(&mut h, 0.33);
    h.key_press_modifiers(Modifiers::COMMAND, Key::S);
    h.run_steps(2);
    let dialog = h.state_mut().dialog_mut().expect("Ctrl+S asks where");
    assert!(
        !dialog.path.starts_with(&examples.display().to_string()),
        "not into the examples folder: {}",
        dialog.path
    );
    let mine = config.join("my-torus.ron");
    dialog.path = mine.display().to_string();
    h.run_steps(1);
    // Files appear in the listed folder between the frame that placed Save and the click (as
    // autosave's thread writes recovery.ron there at its own time): Save stays where it was.
    for i in 0..3 {
        std::fs::write(config.join(format!("appeared-{i}.ron")), "x").unwrap();
    }
    h.get_by_label("Save").click();
    h.run_steps(2);
    assert_eq!(
        std::fs::read_to_string(&shipped).unwrap(),
        DEFAULT_GRAPH,
        "the example is untouched"
    );
    assert!(std::fs::read_to_string(&mine).unwrap().contains("0.33"));
    assert_eq!(h.state().doc().path.as_deref(), Some(mine.as_path()));
    // File ▸ Open example, and a shipped file given on the command line, are copies too.
    h.state_mut().run(MenuAction::OpenExample(shipped.clone()));
    h.run_steps(2);
    assert_eq!(
        (h.state().doc().path.clone(), h.state().doc().origin.clone()),
        (None, Some(shipped.clone()))
    );
    let h2 = common::harness_on(
        temp_config("example2"),
        Some(shipped.clone()),
        examples.clone(),
    );
    assert_eq!(h2.state().doc().path, None);
    let _ = ratio(&h2);
}

#[test]
fn a_file_that_fails_to_load_shows_its_diagnostics_and_keeps_the_document() {
    // A fixed folder: the path is in the snapshot.
    let config = std::env::temp_dir().join("cnets-editor-badfile");
    std::fs::create_dir_all(&config).unwrap();
    let bad = config.join("bad.ron");
    std::fs::write(
        &bad,
        DEFAULT_GRAPH.replacen("\"curve.arc\"", "\"curve.arcc\"", 1),
    )
    .unwrap();
    let mut h = harness("badfile-doc");
    make_dirty(&mut h, 0.41);
    let text = h.state().doc().to_ron();
    h.state_mut().run(MenuAction::OpenPath(bad.clone()));
    h.run_steps(2);
    h.get_by_label("Don't save").click();
    h.run_steps(3);
    assert_eq!(
        h.state().doc().to_ron(),
        text,
        "the previous document stays"
    );
    assert!(h.state().doc().is_dirty(), "and keeps its unsaved changes");
    let failure = h
        .state()
        .load_failure()
        .cloned()
        .expect("the failure is shown");
    let all = failure.error.to_string();
    assert!(
        all.contains("bad.ron:") && all.contains("did you mean"),
        "{all}"
    );
    assert!(failure.first_line().is_some(), "file:line:col");
    // The dialog shows them, and the file as text on request.
    h.get_by_label_contains("did you mean");
    h.get_by_label("Show the file as text").click();
    h.run_steps(6);
    assert!(
        h.state()
            .load_failure()
            .as_ref()
            .unwrap()
            .text
            .as_deref()
            .unwrap()
            .contains("curve.arcc")
    );
    h.snapshot("editor_load_failure");
    h.run_steps(6);
    h.get_by_label("Close").click();
    h.run_steps(2);
    assert!(h.state().load_failure().is_none());
    // At start-up: an empty untitled document under the dialog, not the default graph.
    let h = harness_with(
        "badfile-start",
        Some(bad.clone()),
        temp_config("badfile-start"),
    );
    assert!(h.state().load_failure().is_some());
    assert_eq!(
        h.state().doc().graph.node_count(),
        0,
        "nothing that looks like the file"
    );
    let _ = ratio(&h);
}

/// The editor as the web page runs it (its requests queued for the page).
fn in_page(name: &str) -> H {
    let mut h = harness(name);
    h.state_mut().in_page();
    h
}

/// The `.ron` downloads the page was asked for: (name, text).
fn downloads(h: &mut H) -> Vec<(String, String)> {
    assert!(h.state().page().is_some(), "in a page");
    h.state_mut()
        .take_page_requests()
        .into_iter()
        .filter_map(|r| match r {
            cnets_editor::page::PageRequest::Download { name, bytes } => {
                Some((name, String::from_utf8(bytes).unwrap()))
            }
            _ => None,
        })
        .collect()
}

#[test]
fn a_graph_dropped_on_the_page_asks_before_it_replaces_unsaved_work() {
    let other = std::fs::read_to_string(common::graphs_dir().join("editor-default.ron"))
        .unwrap()
        .replace("0.5", "0.55");
    // Nothing unsaved: the dropped graph opens at once, named by its file.
    let mut h = in_page("page-drop-clean");
    assert!(h.state_mut().receive_text(&other, Path::new("dropped.ron")));
    assert_eq!(h.state().doc().name.as_deref(), Some("dropped.ron"));
    assert_eq!(h.state().message(), "opened dropped.ron");
    // Unsaved work: the question first; Cancel keeps the work and lets the dropped graph go.
    let mut h = in_page("page-drop-cancel");
    make_dirty(&mut h, 0.31);
    let mine = h.state().doc().to_ron();
    assert!(h.state_mut().receive_text(&other, Path::new("dropped.ron")));
    assert_eq!(h.state().doc().to_ron(), mine, "not replaced yet");
    h.run_steps(2);
    assert_eq!(
        h.state().unsaved_question(),
        Some(&Replace::Loaded(PathBuf::from("dropped.ron")))
    );
    h.get_by_label("Cancel").click();
    h.run_steps(3);
    assert_eq!(h.state().doc().to_ron(), mine, "the work stays");
    assert_eq!(h.state().waiting(), None, "the dropped graph is let go");
    assert!(
        h.state().message().contains("was not opened"),
        "{}",
        h.state().message()
    );
    // Save: the work is downloaded (the page's save), then the dropped graph opens.
    assert!(h.state_mut().receive_text(&other, Path::new("dropped.ron")));
    h.run_steps(2);
    h.get_by_label("Save").click();
    h.run_steps(3);
    let saved = downloads(&mut h);
    assert_eq!(saved.len(), 1, "one download");
    assert_eq!(saved[0].1, mine, "the work as it was");
    assert_eq!(h.state().doc().name.as_deref(), Some("dropped.ron"));
    assert!(!h.state().doc().is_dirty());
    // A file that does not load: its diagnostics, the document stays (no question).
    make_dirty(&mut h, 0.32);
    let mine = h.state().doc().to_ron();
    assert!(
        !h.state_mut()
            .receive_text("(version: 1, nodes: {", Path::new("bad.ron"))
    );
    h.run_steps(2);
    assert_eq!(h.state().unsaved_question(), None);
    assert!(h.state().load_failure().is_some());
    assert_eq!(h.state().doc().to_ron(), mine);
}

#[test]
fn save_in_the_pages_question_downloads_and_goes_on() {
    // File ▸ New in the page with unsaved work: Save downloads the design, then the new graph.
    let mut h = in_page("page-new-save");
    make_dirty(&mut h, 0.29);
    let mine = h.state().doc().to_ron();
    h.state_mut().run(MenuAction::New);
    h.run_steps(2);
    h.get_by_label("Save").click();
    h.run_steps(3);
    assert_eq!(
        downloads(&mut h)
            .into_iter()
            .map(|d| d.1)
            .collect::<Vec<_>>(),
        [mine]
    );
    assert_eq!(h.state().doc().graph.node_count(), 0, "the new graph");
    assert!(!h.state().doc().is_dirty());
}

/// Every dialog closes on Escape, with its safe answer: the load failure closes, the file dialog
/// cancels, the unsaved-changes question keeps the document, and the restore offer keeps the
/// work aside (File › Restore kept work opens it) instead of deleting it.
#[test]
fn escape_closes_every_dialog_with_its_safe_answer() {
    let config = temp_config("escape-dialogs");
    // Work left by a "previous session".
    std::fs::write(config.join("recovery.ron"), DEFAULT_GRAPH).unwrap();
    std::fs::write(config.join("recovery.path"), "\n\n").unwrap();
    let mut h = harness_with("escape-dialogs", None, config.clone());
    assert!(h.state().restore_offered(), "the restore offer is shown");
    h.key_press(Key::Escape);
    h.run_steps(3);
    assert!(!h.state().restore_offered(), "Escape closes the offer");
    assert!(
        config.join("held.ron").is_file(),
        "the work is kept aside, not deleted"
    );
    assert_eq!(h.state().kept_recovery(), Some("untitled"));
    // The file dialog.
    h.state_mut().run(MenuAction::Open);
    h.run_steps(2);
    assert!(h.state().dialog().is_some());
    h.key_press(Key::Escape);
    h.run_steps(3);
    assert!(
        h.state().dialog().is_none(),
        "Escape cancels the file dialog"
    );
    // The unsaved-changes question keeps the document.
    make_dirty(&mut h, 0.37);
    let text = h.state().doc().to_ron();
    h.state_mut().run(MenuAction::New);
    h.run_steps(2);
    assert!(
        h.query_by_label("Don't save").is_some(),
        "the question is shown"
    );
    h.key_press(Key::Escape);
    h.run_steps(3);
    assert!(h.query_by_label("Don't save").is_none());
    assert_eq!(h.state().doc().to_ron(), text, "the document stays");
    // A load failure's report.
    h.state_mut().mark_saved();
    let bad = config.join("bad.ron");
    std::fs::write(&bad, "(version: 1, nodes: {\"a\": (type: \"no.such\")})").unwrap();
    h.state_mut().open(&bad);
    h.run_steps(2);
    assert!(h.state().load_failure().is_some());
    h.key_press(Key::Escape);
    h.run_steps(3);
    assert!(
        h.state().load_failure().is_none(),
        "Escape closes the report"
    );
    // The kept work comes back from File › Restore kept work.
    h.state_mut().run(MenuAction::RestoreKept);
    h.run_steps(3);
    assert!(h.state().doc().is_dirty(), "restored as unsaved work");
    assert_eq!(h.state().kept_recovery(), None);
    assert!(!config.join("held.ron").exists());
}
