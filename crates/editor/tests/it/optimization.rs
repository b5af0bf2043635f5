//! The optimization panel, driven through egui_kittest: variables and the objective picked with
//! the canvas's context menus, a run on `graphs/tube-closure.ron` (live plot, objective down),
//! Stop, Accept (one undo step) and Revert.

use crate::common;

use std::time::Duration;

use cnets_editor::app::EditorApp;
use cnets_engine::optimize::{Method, Stop};
use common::{graphs_dir, harness, harness_with, settle, temp_config};
use egui::accesskit::Role;
use egui::{Modifiers, Pos2};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

/// Right-clicks at `at` (opens a context menu).
fn right_click(h: &mut Harness<'static, EditorApp>, at: Pos2) {
    h.hover_at(at);
    h.run_steps(2);
    for pressed in [true, false] {
        h.event(egui::Event::PointerButton {
            pos: at,
            button: egui::PointerButton::Secondary,
            pressed,
            modifiers: Modifiers::NONE,
        });
    }
    h.run_steps(3);
}

/// Screen centre of the label `name` drawn inside node `node` on its input (left) or output
/// (right) side. An input's name is drawn beside its pin at the node's left edge; an output's
/// name left of its summary's slot, so further in than a quarter of the node's width.
fn port_label(h: &Harness<'static, EditorApp>, node: &str, name: &str, input: bool) -> Pos2 {
    let canvas = &h.state().canvas();
    let rect = canvas.node_screen_rect(node).expect("the node is drawn");
    let quarter = rect.left() + rect.width() / 4.0;
    h.get_all_by_label(name)
        .map(|l| canvas.to_screen(l.rect().center()))
        .find(|p| rect.contains(*p) && ((p.x < quarter) == input))
        .unwrap_or_else(|| panic!("label {name} of {node}"))
}

/// Adds a graph mapper, frames the canvas and opens its plot's "Optimize a value" menu; returns
/// the mapper's id.
fn open_mapper_optimize_menu(h: &mut Harness<'static, EditorApp>) -> String {
    let id = h
        .state_mut()
        .add_node("mapper.graph", [420.0, 560.0])
        .unwrap();
    h.state_mut().fit_canvas();
    h.run_steps(4);
    let at = h
        .state()
        .canvas()
        .mapper_screen_pos(&id, 0.5, 0.9)
        .expect("the mapper plot");
    right_click(h, at);
    h.get_by_label_contains("Optimize a value").hover();
    h.run_steps(3);
    id
}

#[test]
fn variables_and_the_objective_are_picked_on_the_canvas_as_one_undo_step() {
    let mut h = harness("opt-pick");
    let before = h.state().doc().to_ron();
    let steps = h.state().doc().history.undo_len();
    // The apex slider's value: bounds from the slider's own range.
    let at = port_label(&h, "apex", "value", true);
    right_click(&mut h, at);
    h.get_by_label("Optimize this value").click();
    h.run_steps(3);
    assert!(h.state().optimization().open, "the panel opens");
    assert_eq!(h.state().optimization().draft.variables.len(), 1);
    assert!(
        h.state().doc().meta.optimization.is_none(),
        "no objective yet: a draft"
    );
    assert!(
        h.state().message().contains("objective"),
        "{}",
        h.state().message()
    );
    // planarity.max as the objective: the setup is complete and stored. (The panel took the
    // bottom of the window: zoom out to see the whole graph above it.)
    h.state_mut().zoom_canvas(0.55, None);
    h.run_steps(3);
    let at = port_label(&h, "planarity", "max", false);
    right_click(&mut h, at);
    h.get_by_label("Minimize this output").click();
    h.run_steps(3);
    let app = h.state();
    let setup = app
        .doc()
        .meta
        .optimization
        .clone()
        .expect("stored in the document");
    assert_eq!(setup.objective.to_string(), "planarity.max");
    assert_eq!(setup.variables.len(), 1);
    assert_eq!(setup.variables[0].input.to_string(), "apex.value");
    assert_eq!((setup.variables[0].min, setup.variables[0].max), (0.5, 1.5));
    assert_eq!(app.doc().history.undo_len(), steps + 1);
    assert!(app.doc().to_ron().contains("objective: \"planarity.max\""));

    // A graph-mapper handle coordinate, from the widget's context menu: bounds [0, 1], and the
    // default handles are written so the variable has a literal to live in.
    let id = open_mapper_optimize_menu(&mut h);
    let handles = cnets_editor::mapper::handles(h.state().doc().graph.node(&id).unwrap());
    let entry = format!(
        "[1][1] = {}",
        cnets_editor::worker::format_number(handles[1].y)
    );
    h.get_by_label(&entry).click();
    h.run_steps(3);
    let app = h.state();
    let setup = app.doc().meta.optimization.clone().unwrap();
    assert_eq!(setup.variables.len(), 2, "{}", app.message());
    assert_eq!(
        setup.variables[1].input.to_string(),
        format!("{id}.handles[1][1]")
    );
    assert_eq!((setup.variables[1].min, setup.variables[1].max), (0.0, 1.0));
    assert!(
        app.doc()
            .graph
            .node(&id)
            .unwrap()
            .value_of("handles")
            .is_some(),
        "the handles are set"
    );
    // Undo twice: no variable, no setup, the original text.
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::Z);
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::Z);
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::Z);
    h.run_steps(2);
    assert_eq!(h.state().doc().to_ron(), before);
}

#[test]
fn every_value_of_an_input_is_one_whole_input_variable() {
    // A graph mapper's handles: "Optimize every value" adds the whole list (each handle's v) as
    // one whole-input variable in [0, 1], writing the default handles first.
    let mut h = harness("opt-whole");
    let id = open_mapper_optimize_menu(&mut h);
    h.get_by_label("Optimize every value").click();
    h.run_steps(3);
    let app = h.state();
    let variables = &app.optimization().draft.variables;
    assert_eq!(variables.len(), 1, "{}", app.message());
    assert_eq!(variables[0].input.to_string(), format!("{id}.handles"));
    assert_eq!((variables[0].min, variables[0].max), (0.0, 1.0));
    assert!(
        app.doc()
            .graph
            .node(&id)
            .unwrap()
            .value_of("handles")
            .is_some(),
        "the default handles are written so the variable has a literal to live in"
    );
    // The variables table says how many numbers the variable stands for: one per handle.
    let handles = cnets_editor::mapper::handles(app.doc().graph.node(&id).unwrap()).len();
    assert_eq!(
        cnets_editor::optimization::value_label(&app.doc().graph, &variables[0].input),
        format!("{handles} numbers")
    );
}

fn tube(name: &str) -> Harness<'static, EditorApp> {
    let mut h = harness_with(
        name,
        Some(graphs_dir().join("tube-closure.ron")),
        temp_config(name),
    );
    h.state_mut()
        .run(cnets_editor::menus::MenuAction::ToggleOptimization);
    h.run_steps(2);
    // The file's nodes overlap: lay them out (overlapping nodes may be drawn in either order,
    // which the snapshot must not depend on).
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::L);
    settle(&mut h);
    assert!(!h.state().canvas().has_overlaps());
    h
}

/// The run that ended, with its outcome (the test fails when none ended or it failed).
fn finished_run(app: &EditorApp) -> &cnets_editor::optimization::Finished {
    app.optimization()
        .result
        .as_ref()
        .expect("a run ended")
        .as_ref()
        .expect("the run succeeded")
}

fn set_run(h: &mut Harness<'static, EditorApp>, max_iter: usize, method: Method) {
    h.state_mut()
        .edit_graph(|_, meta| {
            let s = meta.optimization.as_mut().ok_or("no setup")?;
            s.max_iter = max_iter;
            s.method = method;
            Ok::<_, String>(())
        })
        .unwrap();
    h.run_steps(2);
}

#[test]
fn a_run_plots_the_objective_going_down_and_accept_is_one_undo_step() {
    let mut h = tube("opt-run");
    set_run(&mut h, 6, Method::Auto);
    let before = h.state().doc().to_ron();
    let steps = h.state().doc().history.undo_len();
    h.get_by_label("▶ Run").click();
    h.run_steps(2);
    assert!(
        h.state().optimization().running() || h.state().optimization().result.is_some(),
        "{}",
        h.state().message()
    );
    assert!(
        h.state_mut()
            .wait_for_optimization(Duration::from_secs(300))
    );
    h.run_steps(3);
    let app = h.state();
    let its = &app.optimization().iterations;
    assert!(its.len() >= 2, "the plot has points: {}", its.len());
    let (first, last) = (its[0].objective, its[its.len() - 1].objective);
    assert!(
        last < first * 0.5,
        "the objective decreased: {first} -> {last}"
    );
    assert!(its.windows(2).all(|w| w[1].evaluations > w[0].evaluations));
    let finished = finished_run(app);
    assert_eq!(finished.outcome.stop, Stop::MaxIterations);
    assert_eq!(
        app.doc().to_ron(),
        before,
        "the document is unchanged until Accept"
    );
    assert!(h.query_by_label("Accept").is_some());
    h.remove_cursor();
    // The 3D view shows the best point once the worker has evaluated it: on a busy machine (a
    // clean clone's test command, the site's build beside it) two frames were not enough, and the
    // snapshot caught the tube before the run.
    settle(&mut h);
    h.snapshot("editor_optimization_panel");

    h.get_by_label("Accept").click();
    settle(&mut h);
    let app = h.state();
    assert_ne!(app.doc().to_ron(), before, "Accept changes the document");
    assert_eq!(app.doc().history.undo_len(), steps + 1, "one undo step");
    assert!(app.optimization().result.is_none());
    assert!(app.message().contains("accepted"), "{}", app.message());
    // The accepted values are the optimizer's best point.
    let best = cnets_editor::optimization::current_value(
        &app.doc().graph,
        &app.doc().meta.optimization.as_ref().unwrap().variables[3].input,
    )
    .unwrap();
    assert!((0.1..=0.9).contains(&best));
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::Z);
    h.run_steps(2);
    assert_eq!(h.state().doc().to_ron(), before, "undo restores the text");
}

#[test]
fn stop_cancels_a_run_and_revert_leaves_the_document_alone() {
    let mut h = tube("opt-stop");
    // Nelder–Mead with a huge limit: it would run for a long time.
    set_run(&mut h, 1_000_000, Method::NelderMead);
    let before = h.state().doc().to_ron();
    let steps = h.state().doc().history.undo_len();
    h.get_by_label("▶ Run").click();
    h.run_steps(2);
    // Wait for a few iterations, then Stop.
    for _ in 0..2000 {
        h.state_mut().poll_optimization();
        if h.state().optimization().iterations.len() >= 3 {
            break;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    h.run_steps(1);
    h.get_by_label("■ Stop").click();
    h.run_steps(1);
    assert!(
        h.state_mut().wait_for_optimization(Duration::from_secs(30)),
        "Stop ends the run"
    );
    h.run_steps(2);
    let app = h.state();
    let finished = finished_run(app);
    assert_eq!(finished.outcome.stop, Stop::Cancelled);
    assert!(finished.outcome.iterations < 1_000_000);
    h.get_by_label("Revert").click();
    h.run_steps(2);
    let app = h.state();
    assert!(app.optimization().result.is_none());
    assert_eq!(
        app.doc().to_ron(),
        before,
        "Revert does not change the document"
    );
    assert_eq!(app.doc().history.undo_len(), steps);
}

#[test]
fn a_typed_min_above_max_is_refused_with_a_message_and_not_stored() {
    let mut h = tube("opt-bounds");
    let before = h.state().doc().meta.optimization.clone().unwrap();
    let (min, max) = (before.variables[0].min, before.variables[0].max);
    assert!(max < 1.2, "{max}");
    // The first spin button of the variables table is the first variable's min.
    h.get_all_by_role(Role::SpinButton).next().unwrap().click();
    h.run_steps(2);
    h.get_all_by_role(Role::SpinButton).next().unwrap().focus();
    h.run_steps(1);
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::A);
    h.get_all_by_role(Role::SpinButton)
        .next()
        .unwrap()
        .type_text("1.2");
    h.run_steps(1);
    h.key_press(egui::Key::Enter);
    h.run_steps(3);
    let app = h.state();
    let after = app.doc().meta.optimization.clone().unwrap();
    assert_eq!(
        (after.variables[0].min, after.variables[0].max),
        (min, max),
        "the stored bounds are unchanged"
    );
    assert!(
        app.message().contains("refused") && app.message().contains("is above max"),
        "{}",
        app.message()
    );
    // A bound within range is stored as typed.
    h.get_all_by_role(Role::SpinButton).next().unwrap().click();
    h.run_steps(2);
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::A);
    h.get_all_by_role(Role::SpinButton)
        .next()
        .unwrap()
        .type_text("0.05");
    h.run_steps(1);
    h.key_press(egui::Key::Enter);
    h.run_steps(3);
    let after = h.state().doc().meta.optimization.clone().unwrap();
    assert_eq!(
        (after.variables[0].min, after.variables[0].max),
        (0.05, max)
    );
}

#[test]
fn the_view_follows_the_best_point_live_and_revert_restores_it() {
    let mut h = tube("opt-live");
    // Nelder–Mead with a huge limit: the run lasts until Stop.
    set_run(&mut h, 1_000_000, Method::NelderMead);
    h.state_mut().wait_for_worker(Duration::from_secs(60));
    h.run_steps(2);
    let before = h.state().viewport().scene().face_vertices().to_vec();
    assert!(!before.is_empty());
    h.get_by_label("▶ Run").click();
    // While it runs, the picture moves with the optimizer's best point.
    let mut pictures = 0;
    let mut last = before.clone();
    for _ in 0..600 {
        h.run_steps(1);
        h.state_mut().wait_for_worker(Duration::from_millis(500));
        let now = h.state().viewport().scene().face_vertices().to_vec();
        if now != last {
            pictures += 1;
            last = now;
        }
        if pictures >= 2 {
            break;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    assert!(
        h.state().optimization().running(),
        "the run was still going"
    );
    assert!(pictures >= 2, "{pictures} new pictures during the run");
    assert_ne!(last, before);
    h.get_by_label("■ Stop").click();
    // The click reaches the app in the next frame.
    h.run_steps(1);
    assert!(
        h.state_mut().wait_for_optimization(Duration::from_secs(30)),
        "Stop ends the run"
    );
    h.run_steps(2);
    h.get_by_label("Revert").click();
    h.run_steps(1);
    h.state_mut().wait_for_worker(Duration::from_secs(60));
    h.run_steps(2);
    assert_eq!(
        h.state().viewport().scene().face_vertices(),
        &before[..],
        "Revert shows the document's own values again"
    );
}
