//! The graph-mapper widget shows the truth and never reshapes data (issue 26, point 2), over every
//! shipped graph: the curve the widget draws is the one the node evaluates (compared with the
//! node's own output at its sample points, wired kinds and handle trees included), and dragging
//! any handle by one pixel keeps the stored value's nesting and item counts exactly.

use crate::common;

use std::time::Duration;

use cnets_editor::app::EditorApp;
use cnets_editor::mapper::node::{Shape, shape};
use cnets_editor::mapper::{Shown, handles_port, is_mapper};
use cnets_engine::{Evaluator, NodeContext, Value};
use cnets_geometry::curves::GraphMapper;
use common::{graphs_dir, harness_with, settle, temp_config};
use egui::{Pos2, vec2};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

/// The shipped graphs holding graph mappers, with their mapper node ids.
fn graphs_with_mappers() -> Vec<(std::path::PathBuf, Vec<String>)> {
    let registry = std::sync::Arc::new(cnets_nodes::registry());
    let mut found = Vec::new();
    let mut files: Vec<_> = std::fs::read_dir(graphs_dir())
        .unwrap()
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    files.sort();
    for file in files {
        let doc = cnets_engine::file::load_file(&file, &registry).expect("a shipped graph loads");
        let mappers: Vec<String> = doc
            .graph
            .nodes()
            .filter(|(_, n)| is_mapper(n))
            .map(|(_, n)| n.id.clone())
            .collect();
        if !mappers.is_empty() {
            found.push((file, mappers));
        }
    }
    found
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_list()
        .expect("a list")
        .iter()
        .map(|x| x.as_f64().expect("a number"))
        .collect()
}

/// Rows of numbers: a flat list is one row, a tree one row per branch.
fn rows(v: &Value) -> Vec<Vec<f64>> {
    let items = v.as_list().expect("a list");
    if items.iter().any(|x| matches!(x, Value::List(_))) {
        items.iter().map(numbers).collect()
    } else {
        vec![numbers(v)]
    }
}

/// Asserts that what the widget showed for `id` is the curve the node evaluated: for each row, at
/// each sample x, the shown kind and handles give the node's y (domains mapped back to the unit
/// square).
fn assert_curve_is_the_nodes(app: &EditorApp, file: &str, id: &str, shown: &Shown) {
    let graph = &app.doc().graph;
    let ctx = NodeContext::default();
    let mut ev = Evaluator::new();
    ev.evaluate_all(graph, &ctx);
    let index = graph.index(id).unwrap();
    let inputs = ev.inputs_of(graph, index, &ctx).expect("the mapper ran");
    let def = &graph.node(id).unwrap().def;
    let input = |name: &str| inputs[def.input_index(name).unwrap()].as_f64().unwrap();
    let (x0, x1, y0, y1) = (
        input("x_start"),
        input("x_end"),
        input("y_start"),
        input("y_end"),
    );
    let xs = rows(ev.output(graph, id, "x").expect("x computed"));
    let ys = rows(ev.output(graph, id, "y").expect("y computed"));
    // One shown row per output row, or one row the node runs on every output row (another input
    // given as a list, e.g. several counts).
    assert!(
        shown.rows.len() == ys.len() || shown.rows.len() == 1,
        "{file} {id}: {} shown rows for {} output rows",
        shown.rows.len(),
        ys.len()
    );
    for (r, (xr, yr)) in xs.iter().cycle().zip(&ys).enumerate() {
        let kind = shown
            .kind(r)
            .unwrap_or_else(|| panic!("{file} {id}: kind of row {r}"));
        let row = r.min(shown.rows.len() - 1);
        let mapper = GraphMapper::new(kind, &shown.rows[row])
            .unwrap_or_else(|e| panic!("{file} {id} row {r}: {e}"));
        for (x, y) in xr.iter().zip(yr) {
            let u = (x - x0) / (x1 - x0);
            let v = (y - y0) / (y1 - y0);
            let drawn = mapper.eval(u);
            assert!(
                (drawn - v).abs() <= 1e-9 * (1.0 + v.abs()),
                "{file} {id} row {r}: the widget draws v({u}) = {drawn}, the node outputs {v}"
            );
        }
    }
}

/// A one-pixel drag in the harness, by `dy` screen pixels (±1).
fn nudge(h: &mut Harness<'static, EditorApp>, at: Pos2, dy: f32) {
    h.hover_at(at);
    h.run_steps(1);
    h.drag_at(at);
    h.run_steps(1);
    h.hover_at(at + vec2(0.0, dy));
    h.run_steps(1);
    h.drop_at(at + vec2(0.0, dy));
    h.run_steps(2);
}

/// Clicks the button labelled `label` inside node `id` (accessibility rectangles of canvas
/// widgets are in canvas coordinates).
fn click_in_node(h: &mut Harness<'static, EditorApp>, id: &str, label: &str) {
    let canvas = &h.state().canvas();
    let node = canvas.node_screen_rect(id).expect("the node is drawn");
    let at = h
        .get_all_by_label(label)
        .map(|b| canvas.to_screen(b.rect().center()))
        .find(|p| node.contains(*p))
        .unwrap_or_else(|| panic!("no '{label}' button in {id}"));
    h.hover_at(at);
    h.run_steps(1);
    h.drag_at(at);
    h.run_steps(1);
    h.drop_at(at);
    h.run_steps(2);
}

fn stored_handles(app: &EditorApp, id: &str) -> Option<Value> {
    let node = app.doc().graph.node(id)?;
    node.value(handles_port(node)?).cloned()
}

/// Shows the mapper `id` at zoom 1 in the middle of the canvas.
fn focus(h: &mut Harness<'static, EditorApp>, id: &str) {
    h.run_steps(2);
    let centre = h.state().canvas().node_rect(id).expect("drawn").center();
    h.state_mut().zoom_canvas(1.0, Some(centre));
    h.run_steps(3);
}

#[test]
fn every_shipped_mapper_draws_its_nodes_curve_and_a_one_pixel_drag_keeps_the_shape() {
    let cases = graphs_with_mappers();
    assert!(cases.len() >= 10, "graphs with mappers: {}", cases.len());
    let mut dragged = 0;
    for (file, mappers) in cases {
        let name = file.file_name().unwrap().to_string_lossy().into_owned();
        let mut h = harness_with(&name, Some(file.clone()), temp_config(&name));
        for id in &mappers {
            focus(&mut h, id);
            let (shown, _) = h
                .state()
                .canvas()
                .mapper_view(id)
                .cloned()
                .unwrap_or_else(|| panic!("{name} {id}: the widget was drawn"));
            assert!(!shown.unknown, "{name} {id}: evaluated values are shown");
            assert_curve_is_the_nodes(h.state(), &name, id, &shown);
            if !shown.editable() {
                continue;
            }
            let before = stored_handles(h.state(), id);
            let rows = shown.rows.len();
            // Every handle of the first and the last row (the rows between are the same code).
            for row in [0, rows - 1] {
                // Step the row selector to the last row.
                for _ in 0..row {
                    click_in_node(&mut h, id, "▶");
                }
                let count = shown.rows[row].len();
                for k in 0..count {
                    let (now, drawn_row) = h.state().canvas().mapper_view(id).cloned().unwrap();
                    assert_eq!(drawn_row, row, "{name} {id}: the row selector");
                    let p = now.rows[row][k];
                    let at = h
                        .state()
                        .canvas()
                        .mapper_screen_pos(id, p.x as f32, p.y as f32)
                        .unwrap();
                    let steps = h.state().doc().history.undo_len();
                    // Away from the plot's edge (a handle on v = 1 cannot go higher).
                    nudge(&mut h, at, if p.y > 0.5 { 1.0 } else { -1.0 });
                    let after = stored_handles(h.state(), id)
                        .unwrap_or_else(|| panic!("{name} {id}: the drag wrote the handles"));
                    match &before {
                        Some(b) => assert_eq!(
                            shape(&after),
                            shape(b),
                            "{name} {id} row {row} handle {k}: the stored value kept its shape"
                        ),
                        None => assert_eq!(
                            shape(&after),
                            Shape::List(vec![Shape::Leaf; count]),
                            "{name} {id}: the default handles written as one flat row"
                        ),
                    }
                    assert_eq!(
                        h.state().doc().history.undo_len(),
                        steps + 1,
                        "{name} {id} row {row} handle {k} at {at:?} ({p:?}): one undo step; message {}",
                        h.state().message()
                    );
                    assert!(h.state_mut().undo(), "undo");
                    // The undone value's results in (they may resize the node) before the next
                    // handle is located.
                    h.run_steps(1);
                    h.state_mut().wait_for_worker(Duration::from_secs(60));
                    h.run_steps(1);
                    assert_eq!(
                        stored_handles(h.state(), id),
                        before,
                        "{name} {id}: undo restores the handles"
                    );
                    dragged += 1;
                }
            }
            // Back to the first row for the next mapper.
            for _ in 1..rows {
                click_in_node(&mut h, id, "◀");
            }
        }
        settle(&mut h);
    }
    assert!(dragged >= 20, "handles dragged: {dragged}");
}

#[test]
fn a_wired_kind_is_shown_as_the_node_runs_it() {
    // grasshopper-style wires the mapper's kind from a value list set to "bezier".
    let file = graphs_dir().join("grasshopper-style.ron");
    let mut h = harness_with("gh-kind", Some(file), temp_config("gh-kind"));
    let id = h
        .state()
        .doc()
        .graph
        .nodes()
        .find(|(_, n)| is_mapper(n))
        .map(|(_, n)| n.id.clone())
        .expect("a mapper");
    focus(&mut h, &id);
    let (shown, _) = h.state().canvas().mapper_view(&id).cloned().unwrap();
    assert!(shown.kind_wired, "the kind is wired in grasshopper-style");
    assert_eq!(
        shown.kind(0).map(|k| k.name()),
        Some("bezier"),
        "the widget shows the wired kind"
    );
    assert_curve_is_the_nodes(h.state(), "grasshopper-style", &id, &shown);
}
