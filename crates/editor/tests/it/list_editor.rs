//! Literal lists and tables (issue 25), driven through egui_kittest: the summary and **Edit…** on
//! the node, the table window, a cell typed in (only that number changes in the saved text, one
//! undo step, undone exactly, the window following), pasted tab-separated rows, a `param.list`
//! table keeping rows × columns, a wired input read-only, and a picture of the window.

use crate::common;

use std::path::PathBuf;

use cnets_editor::app::EditorApp;
use cnets_editor::edit::Edit;
use cnets_editor::list_editor::PasteMode;
use cnets_engine::Value;
use cnets_geometry::DVec3;
use common::{graphs_dir, harness_with, settle, temp_config};
use egui::accesskit::Role;
use egui::{Key, Modifiers, Pos2};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

type H = Harness<'static, EditorApp>;

/// A graph file of the test's own, in a folder of its own.
fn write_graph(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("cnets-list-editor-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(format!("{name}.ron"));
    std::fs::write(&path, text).unwrap();
    path
}

/// The editor on `file`, framed so that every node is in view.
fn open(name: &str, file: PathBuf) -> H {
    let mut h = harness_with(name, Some(file), temp_config(name));
    h.key_press(Key::Home);
    h.run_steps(4);
    h
}

/// Clicks (pointer press and release) at a screen position.
fn click_at(h: &mut H, p: Pos2) {
    h.hover_at(p);
    h.run_steps(1);
    for pressed in [true, false] {
        h.event(egui::Event::PointerButton {
            pos: p,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: Modifiers::NONE,
        });
        h.run_steps(1);
    }
    h.run_steps(2);
}

/// Screen centres of the **Edit…** buttons drawn inside `node` (accessibility rectangles of
/// canvas widgets are in canvas coordinates).
fn edit_buttons(h: &H, node: &str) -> Vec<Pos2> {
    let canvas = &h.state().canvas();
    let frame = canvas.node_screen_rect(node).expect("the node is drawn");
    h.get_all_by_label("Edit…")
        .map(|b| canvas.to_screen(b.rect().center()))
        .filter(|p| frame.contains(*p))
        .collect()
}

/// Clicks the **Edit…** button of `node`'s `input` and waits for its window.
fn open_editor(h: &mut H, node: &str, input: &str) {
    let area = h
        .state()
        .canvas()
        .editor_screen_rect(node, input)
        .expect("the input has an Edit… button");
    let button = edit_buttons(h, node)
        .into_iter()
        .find(|p| area.expand(1.0).contains(*p))
        .expect("Edit… by its label, inside the node");
    click_at(h, button);
    assert!(
        h.state().list_editors().is_open(node, input),
        "Edit… opens the window of {node}.{input}"
    );
    assert!(
        h.query_by_label(&format!("{node} · {input}")).is_some(),
        "the window's title names the node and the input"
    );
}

/// Types `text` into cell `cell` (its accessible name, e.g. `row 1 y`) and presses Enter.
fn type_into(h: &mut H, cell: &str, text: &str) {
    type_only(h, cell, text);
    h.key_press(Key::Enter);
    h.run_steps(3);
}

/// Clicks cell `cell` (press and release in frames of their own, as a hand does) and types
/// `text` in it (its text is selected first: typing replaces it).
fn type_only(h: &mut H, cell: &str, text: &str) {
    // Windows are not zoomed: their widgets' rectangles are screen rectangles.
    let at = h.get_by_label(cell).rect().center();
    click_at(h, at);
    let field = h.get_by(|n| n.role() == Role::TextInput && n.is_focused());
    field.type_text(text);
    h.run_steps(2);
}

/// The text a cell shows (its accessible value).
fn shown(h: &H, cell: &str) -> String {
    h.get_by_label(cell).value().unwrap_or_default()
}

fn literal(app: &EditorApp, node: &str, input: &str) -> Value {
    app.doc()
        .graph
        .node(node)
        .unwrap()
        .value_of(input)
        .cloned()
        .expect("a literal")
}

#[test]
fn a_typed_cell_changes_only_that_number_and_undo_restores_the_text() {
    // The shipped tube: its directrix is a spline through four literal points.
    let mut h = open("cell", graphs_dir().join("tube-closure.ron"));
    assert!(
        h.query_by_label("4 points").is_some(),
        "the node shows the list's summary"
    );
    let before = h.state().doc().to_ron();
    let steps = h.state().doc().history.undo_len();
    open_editor(&mut h, "directrix", "points");
    assert_eq!(shown(&h, "row 1 y"), "4");
    type_into(&mut h, "row 1 y", "4.40179139375686646");
    settle(&mut h);
    let after = h.state().doc().to_ron();
    assert_eq!(
        after,
        before.replacen(
            "(0.0, 4.0, 3.0), (-4.0",
            "(0.0, 4.4017913937568665, 3.0), (-4.0",
            1
        ),
        "the saved text changed in that number only (typed in full, kept in full)"
    );
    assert_eq!(
        h.state().doc().history.undo_len(),
        steps + 1,
        "one undo step"
    );
    assert_eq!(shown(&h, "row 1 y"), "4.4017913937568665", "shown in full");
    assert!(
        literal(h.state(), "directrix", "points").as_list().unwrap()[1]
            .same_as(&Value::Point(DVec3::new(0.0, 4.401_791_393_756_866_5, 3.0))),
        "a point stays a point"
    );
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    settle(&mut h);
    assert_eq!(
        h.state().doc().to_ron(),
        before,
        "undo restores the text exactly"
    );
    assert_eq!(shown(&h, "row 1 y"), "4", "the window follows undo");
    h.key_press_modifiers(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z);
    settle(&mut h);
    assert_eq!(h.state().doc().to_ron(), after, "and redo");
    assert_eq!(shown(&h, "row 1 y"), "4.4017913937568665");
    // A bad cell is refused in the window, and the document does not change.
    type_into(&mut h, "row 2 x", "4,5");
    settle(&mut h);
    assert_eq!(h.state().doc().to_ron(), after);
    assert!(
        h.query_by_label_contains("use '.' as the decimal point")
            .is_some(),
        "the window says why"
    );
    h.key_press(Key::Escape);
    h.run_steps(3);
}

const SPLINE: &str = r#"(
    version: 1,
    nodes: {
        "curve": (
            type: "curve.spline",
            position: (0.0, 0.0),
            inputs: {
                "points": [(0.0, 0.0, 0.0), (1.0, 2.0, 0.0), (3.0, 1.0, 0.5), (4.0, 0.0, 0.0)],
            },
        ),
        "source": (
            type: "param.points",
            position: (0.0, 260.0),
            inputs: {
                "points": [(0.0, 0.0, 0.0), (5.0, 5.0, 0.0)],
            },
        ),
    },
)"#;

#[test]
fn pasted_rows_replace_all_or_go_in_at_the_selected_cell_in_one_step_each() {
    let mut h = open("paste", write_graph("paste", SPLINE));
    open_editor(&mut h, "curve", "points");
    let steps = h.state().doc().history.undo_len();
    // Replacing all rows (the choice in the window), with spreadsheet text.
    h.get_by_label("replacing all rows").click();
    h.run_steps(2);
    h.event(egui::Event::Paste(
        "1\t2\t3\n4\t5\t6\r\n7\t8\t9.125\n".into(),
    ));
    h.run_steps(3);
    settle(&mut h);
    let expected = Value::list(vec![
        Value::Point(DVec3::new(1.0, 2.0, 3.0)),
        Value::Point(DVec3::new(4.0, 5.0, 6.0)),
        Value::Point(DVec3::new(7.0, 8.0, 9.125)),
    ]);
    assert!(
        literal(h.state(), "curve", "points").same_as(&expected),
        "{:?}",
        literal(h.state(), "curve", "points")
    );
    assert_eq!(h.state().doc().history.undo_len(), steps + 1, "one step");
    assert_eq!(
        h.state().doc().graph.node_count(),
        2,
        "the paste went to the table, not to the canvas"
    );
    assert_eq!(
        h.query_all_by_label("3 points").count(),
        2,
        "the summaries on the node and in the window follow"
    );
    // At the selected cell: row 1, from y on; a line past the end adds a row.
    h.state_mut()
        .set_paste_mode("curve", "points", PasteMode::AtCell);
    h.get_by_label("row 1 y").click();
    h.run_steps(3);
    h.event(egui::Event::Paste("50,60\n80,90\n110,120".into()));
    h.run_steps(3);
    // The cell clicked was being typed in: the paste ended that, so Enter commits nothing stale.
    h.key_press(Key::Enter);
    h.run_steps(3);
    settle(&mut h);
    let expected = Value::list(vec![
        Value::Point(DVec3::new(1.0, 2.0, 3.0)),
        Value::Point(DVec3::new(4.0, 50.0, 60.0)),
        Value::Point(DVec3::new(7.0, 80.0, 90.0)),
        Value::Point(DVec3::new(7.0, 110.0, 120.0)),
    ]);
    assert!(
        literal(h.state(), "curve", "points").same_as(&expected),
        "{:?}",
        literal(h.state(), "curve", "points")
    );
    assert_eq!(h.state().doc().history.undo_len(), steps + 2);
    // A bad field: refused naming its line and field; nothing changes.
    let text = h.state().doc().to_ron();
    h.event(egui::Event::Paste("1\t2\n3\tx\n".into()));
    h.run_steps(3);
    assert_eq!(h.state().doc().to_ron(), text);
    assert!(
        h.query_by_label_contains("line 2, field 2: 'x' is not a number")
            .is_some()
    );
    // Undo goes back one paste at a time.
    h.key_press(Key::Escape);
    h.run_steps(2);
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    settle(&mut h);
    assert_eq!(
        literal(h.state(), "curve", "points")
            .as_list()
            .unwrap()
            .len(),
        3
    );
}

const TABLE: &str = r#"(
    version: 1,
    nodes: {
        "ratios": (
            type: "param.list",
            position: (0.0, 0.0),
            inputs: {
                "values": [
                    [0.1, 0.2, 0.30000000000000004, 0.4],
                    [0.5, 0.6, 0.7, 0.8],
                    [0.9, 1.0, 1.1, 1.2],
                ],
                "item_type": "number",
            },
        ),
    },
)"#;

/// The rows × columns of a table value, and its numbers.
fn table_of(v: &Value) -> (Vec<usize>, Vec<f64>) {
    let rows = v.as_list().expect("a list");
    let widths = rows
        .iter()
        .map(|r| r.as_list().expect("each row a list").len())
        .collect();
    let numbers = rows
        .iter()
        .flat_map(|r| r.as_list().unwrap().iter().map(|x| x.as_f64().unwrap()))
        .collect();
    (widths, numbers)
}

#[test]
fn a_param_list_table_keeps_rows_by_columns() {
    let mut h = open("table", write_graph("table", TABLE));
    assert!(h.query_by_label("3 × 4 numbers, 0.1 … 1.2").is_some());
    let before = h.state().doc().to_ron();
    open_editor(&mut h, "ratios", "values");
    assert_eq!(shown(&h, "row 0, column 2"), "0.30000000000000004");
    type_into(&mut h, "row 1, column 2", "0.75");
    settle(&mut h);
    let (widths, numbers) = table_of(&literal(h.state(), "ratios", "values"));
    assert_eq!(widths, vec![4, 4, 4], "a table stays a table");
    assert_eq!(numbers[6], 0.75);
    assert_eq!(
        h.state().doc().to_ron(),
        before.replacen("0.6, 0.7, 0.8", "0.6, 0.75, 0.8", 1),
        "only that number changed"
    );
    // A cell typed in, then another clicked and typed in: two changes, two undo steps.
    let steps = h.state().doc().history.undo_len();
    type_only(&mut h, "row 0, column 0", "0.15");
    type_into(&mut h, "row 2, column 3", "1.25");
    settle(&mut h);
    let (_, numbers) = table_of(&literal(h.state(), "ratios", "values"));
    assert_eq!((numbers[0], numbers[11]), (0.15, 1.25));
    assert_eq!(
        h.state().doc().history.undo_len(),
        steps + 2,
        "one step each"
    );
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    settle(&mut h);
    let (_, numbers) = table_of(&literal(h.state(), "ratios", "values"));
    assert_eq!(
        (numbers[0], numbers[11]),
        (0.15, 1.2),
        "undo takes back the last only"
    );
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    settle(&mut h);
    // Add row: after the selected row 0, midway to row 1.
    h.get_by_label("select row 0").click();
    h.run_steps(2);
    h.get_by_label("Add row").click();
    h.run_steps(3);
    settle(&mut h);
    let (widths, numbers) = table_of(&literal(h.state(), "ratios", "values"));
    assert_eq!(widths, vec![4, 4, 4, 4]);
    let midway: Vec<f64> = [0.1, 0.2, 0.30000000000000004, 0.4]
        .iter()
        .zip([0.5, 0.6, 0.75, 0.8])
        .map(|(x, y)| x + (y - x) * 0.5)
        .collect();
    assert_eq!(&numbers[4..8], &midway[..]);
    // Remove the selected row (the added one) again.
    h.get_by_label("Remove 1 row").click();
    h.run_steps(3);
    settle(&mut h);
    assert_eq!(
        table_of(&literal(h.state(), "ratios", "values")).0,
        vec![4, 4, 4]
    );
    // Replacing all with a 2 × 5 table: still a table, rows × columns as pasted.
    h.get_by_label("replacing all rows").click();
    h.run_steps(2);
    h.event(egui::Event::Paste("1;2;3;4;5\n6;7;8;9;10\n".into()));
    h.run_steps(3);
    settle(&mut h);
    let (widths, numbers) = table_of(&literal(h.state(), "ratios", "values"));
    assert_eq!(widths, vec![5, 5]);
    assert_eq!(numbers, (1..=10).map(f64::from).collect::<Vec<_>>());
    assert_eq!(
        h.query_all_by_label("2 × 5 numbers, 1 … 10").count(),
        2,
        "on the node and in the window"
    );
}

#[test]
fn a_wired_input_is_read_only_and_the_window_closes_with_its_node() {
    let mut h = open("wired", write_graph("wired", SPLINE));
    open_editor(&mut h, "curve", "points");
    assert!(h.query_by_label("Add row").is_some());
    let ok = h.state_mut().edit(Edit::Connect {
        from: "source".into(),
        output: "points".into(),
        to: "curve".into(),
        input: "points".into(),
        replace: true,
    });
    assert!(ok);
    settle(&mut h);
    assert!(
        h.query_by_label_contains("Connected: this input takes its value from a wire")
            .is_some()
    );
    assert!(h.query_by_label("Add row").is_none(), "no tools when wired");
    assert!(
        edit_buttons(&h, "curve").is_empty(),
        "a wired input has no Edit… on its node"
    );
    let text = h.state().doc().to_ron();
    h.get_by_label("row 1 y").click();
    h.run_steps(3);
    assert!(
        h.query_by(|n| n.role() == Role::TextInput && n.is_focused())
            .is_none(),
        "cells are not typed in"
    );
    h.event(egui::Event::Paste("1\t2\t3\n".into()));
    h.run_steps(3);
    assert_eq!(h.state().doc().to_ron(), text, "nothing pasted");
    let ok = h.state_mut().edit(Edit::Remove(vec!["curve".into()]));
    assert!(ok);
    h.run_steps(3);
    assert!(h.state().list_editors().is_empty(), "its node is gone");
}

#[test]
fn snapshot_of_the_table_window() {
    // At the zoom the graph opens at (readable), the window beside the Edit… clicked.
    let name = "picture";
    let mut h = harness_with(
        name,
        Some(graphs_dir().join("tube-closure.ron")),
        temp_config(name),
    );
    open_editor(&mut h, "directrix", "points");
    h.get_by_label("select row 2").click();
    h.run_steps(2);
    h.get_by_label("row 1 z").click();
    h.run_steps(3);
    h.key_press(Key::Escape);
    h.hover_at(Pos2::new(600.0, 700.0));
    h.run_steps(3);
    settle(&mut h);
    h.snapshot("editor_list_editor");
}

const PROFILES: &str = r#"(
    version: 1,
    nodes: {
        "profiles": (
            type: "param.list",
            position: (0.0, 0.0),
            inputs: {
                "values": [
                    (points: [(0.0, 0.0, 0.0), (0.0, 0.3, 3.0), (0.0, 0.9, 6.0)], closed: false),
                    (points: [(0.0, 0.3, 3.0), (0.0, -1.2, 3.4), (0.0, -2.6, 3.6)], closed: true),
                ],
                "item_type": "any",
            },
        ),
    },
)"#;

#[test]
fn a_list_of_polylines_is_edited_one_polyline_at_a_time() {
    // As facade.ron's profiles: literal polylines in a param.list.
    let mut h = open("profiles", write_graph("profiles", PROFILES));
    assert!(h.query_by_label("2 polylines").is_some());
    let before = h.state().doc().to_ron();
    let old = literal(h.state(), "profiles", "values");
    open_editor(&mut h, "profiles", "values");
    assert_eq!(shown(&h, "row 1 y"), "0.3", "the first polyline at first");
    h.get_by_label("polyline 1 · 3 points, closed").click();
    h.run_steps(3);
    assert_eq!(shown(&h, "row 1 y"), "-1.2");
    type_into(&mut h, "row 1 y", "-1.25");
    settle(&mut h);
    assert_eq!(
        h.state().doc().to_ron(),
        before.replacen("(0.0, -1.2, 3.4)", "(0.0, -1.25, 3.4)", 1),
        "only that number changed"
    );
    let new = literal(h.state(), "profiles", "values");
    let (old, new) = (old.as_list().unwrap(), new.as_list().unwrap());
    assert!(new[0].same_as(&old[0]), "the other polyline is untouched");
    let Value::Polyline(p) = &new[1] else {
        panic!("a polyline stays a polyline")
    };
    assert!(p.closed, "with its closed flag");
    assert_eq!(p.points[1], DVec3::new(0.0, -1.25, 3.4));
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    settle(&mut h);
    assert_eq!(
        h.state().doc().to_ron(),
        before,
        "one undo step, undone exactly"
    );
}

/// Escape closes the list window, unless it ends a cell's edit (the window stays then).
#[test]
fn escape_closes_the_list_window_but_first_ends_a_cells_edit() {
    let mut h = open("escape", write_graph("escape", SPLINE));
    open_editor(&mut h, "curve", "points");
    type_only(&mut h, "row 1 x", "7");
    h.key_press(Key::Escape);
    h.run_steps(3);
    assert!(
        h.state().list_editors().is_open("curve", "points"),
        "the first Escape cancels the cell's edit"
    );
    h.key_press(Key::Escape);
    h.run_steps(3);
    assert!(
        !h.state().list_editors().is_open("curve", "points"),
        "the next closes the window"
    );
}
