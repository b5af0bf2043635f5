//! The optimization panel's UI: the setup editor (variables, penalties, method), the run
//! controls, the objective plot and the result with Accept / Revert.

use std::path::PathBuf;
use web_time::Duration;

use cnets_engine::Graph;
use cnets_engine::optimize::{Method, PenaltyKind, Setup, Stop, ValuePath};
use egui::{Color32, Ui};

use super::{OptimizationPanel, fmt};
use crate::document::GraphDocument;
use crate::history::EditKey;
use crate::plot::objective_plot;
use crate::widgets::effective_value;

impl OptimizationPanel {
    /// Shows the panel's content; returns a status message when something happened.
    pub fn show(
        &mut self,
        ui: &mut Ui,
        doc: &mut GraphDocument,
        base_dir: Option<PathBuf>,
    ) -> Option<String> {
        self.poll();
        self.clear_stale(doc);
        let mut message = None;
        let mut say = |r: Result<String, String>| match r {
            Ok(m) => message = Some(m),
            Err(e) => message = Some(format!("refused: {e}")),
        };
        ui.horizontal(|ui| {
            ui.heading("Optimization");
            if let Some(l) = doc.levels().last() {
                ui.weak(format!("inside {}", l.node));
            }
        });
        let width = ui.available_width();
        let height = ui.available_height();
        ui.horizontal_top(|ui| {
            ui.vertical(|ui| {
                ui.set_width((width * 0.55).max(200.0));
                egui::ScrollArea::vertical()
                    .id_salt("cnets-optimization")
                    .max_height(height)
                    .auto_shrink([false, true])
                    .show(ui, |ui| match doc.meta.optimization.clone() {
                        Some(setup) => {
                            if let Some(m) = setup_editor(ui, doc, &setup) {
                                say(m);
                            }
                        }
                        None => self.draft_view(ui),
                    });
            });
            ui.separator();
            ui.vertical(|ui| {
                self.run_controls(ui, doc, base_dir, &mut say);
                self.plot_and_result(ui, doc, &mut say);
            });
        });
        if self.running.is_some() {
            ui.ctx().request_repaint_after(Duration::from_millis(50));
        }
        message
    }

    fn draft_view(&mut self, ui: &mut Ui) {
        ui.label("No optimization setup yet.");
        ui.weak(
            "Right-click an unconnected number input › Optimize this value, \
             and a number output › Minimize this output.",
        );
        let d = &mut self.draft;
        if let Some(o) = &d.objective {
            ui.label(format!("objective: minimize {o}"));
        }
        let mut remove = None;
        for (k, v) in d.variables.iter().enumerate() {
            ui.horizontal(|ui| {
                ui.label(format!(
                    "variable {} in [{}, {}]",
                    v.input,
                    fmt(v.min),
                    fmt(v.max)
                ));
                if ui.small_button("×").clicked() {
                    remove = Some(k);
                }
            });
        }
        if let Some(k) = remove {
            d.variables.remove(k);
        }
    }

    fn run_controls(
        &mut self,
        ui: &mut Ui,
        doc: &GraphDocument,
        base_dir: Option<PathBuf>,
        say: &mut dyn FnMut(Result<String, String>),
    ) {
        ui.horizontal(|ui| {
            let can_run = doc.meta.optimization.is_some() && self.running.is_none();
            if ui
                .add_enabled(can_run, egui::Button::new("▶ Run"))
                .on_hover_text(
                    "optimize on a copy of the graph (the document is unchanged until Accept)",
                )
                .clicked()
            {
                say(self
                    .start(doc, base_dir, None)
                    .map(|()| "optimization started".to_string()));
            }
            if ui
                .add_enabled(self.running.is_some(), egui::Button::new("■ Stop"))
                .clicked()
            {
                self.stop();
            }
            if self.running.is_some() {
                ui.spinner();
            }
        });
        if let Some(last) = self.iterations.last() {
            egui::Grid::new("cnets-opt-figures")
                .num_columns(2)
                .show(ui, |ui| {
                    ui.label("iteration");
                    ui.label(last.iteration.to_string());
                    ui.end_row();
                    ui.label("objective");
                    ui.label(format!("{:.4e}", last.objective));
                    ui.end_row();
                    ui.label("evaluations");
                    ui.label(last.evaluations.to_string());
                    ui.end_row();
                    ui.label("node runs");
                    ui.label(last.node_runs.to_string());
                    ui.end_row();
                    ui.label("method");
                    ui.label(last.method.name());
                    ui.end_row();
                });
        }
    }

    fn plot_and_result(
        &mut self,
        ui: &mut Ui,
        doc: &mut GraphDocument,
        say: &mut dyn FnMut(Result<String, String>),
    ) {
        let points: Vec<(f64, f64)> = self
            .iterations
            .iter()
            .map(|it| (it.iteration as f64, it.objective))
            .collect();
        if !points.is_empty() {
            objective_plot(ui, &points);
        }
        let mut action = None;
        match &self.result {
            Some(Ok(f)) => {
                let o = &f.outcome;
                ui.label(format!(
                    "{}: objective {:.3e} -> {:.3e} in {} iterations, {} evaluations, {} node runs",
                    match &o.stop {
                        Stop::Converged(why) => format!("converged ({why})"),
                        Stop::MaxIterations => "iteration limit".to_string(),
                        Stop::Cancelled => "stopped".to_string(),
                    },
                    o.start,
                    o.objective,
                    o.iterations,
                    o.evaluations,
                    o.node_runs,
                ));
                for w in &f.warnings {
                    ui.colored_label(Color32::from_rgb(0xd9, 0x8c, 0x1a), format!("warning: {w}"));
                }
                ui.horizontal(|ui| {
                    if ui
                        .button("Accept")
                        .on_hover_text("write the optimized values into the graph (one undo step)")
                        .clicked()
                    {
                        action = Some(true);
                    }
                    if ui
                        .button("Revert")
                        .on_hover_text("discard the optimized values")
                        .clicked()
                    {
                        action = Some(false);
                    }
                });
            }
            Some(Err(e)) => {
                ui.colored_label(Color32::from_rgb(0xd6, 0x2f, 0x2f), e);
            }
            None => {}
        }
        match action {
            Some(true) => say(self.accept(doc)),
            Some(false) => {
                self.revert();
                say(Ok("reverted: the optimized values were discarded".into()));
            }
            None => {}
        }
    }
}

/// The current value of a variable in `graph` (its literal, else its input's default).
pub fn current_value(graph: &Graph, path: &ValuePath) -> Option<f64> {
    let node = graph.node(&path.node)?;
    let k = node.def.input_index(&path.port)?;
    path.get(&effective_value(node, k)?).ok()
}

/// What the variables table shows as a variable's value: the number, or for a whole-input
/// variable how many numbers it stands for.
pub fn value_label(graph: &Graph, path: &ValuePath) -> String {
    if let Some(x) = current_value(graph, path) {
        return fmt(x);
    }
    let count = graph.node(&path.node).and_then(|node| {
        let k = node.def.input_index(&path.port)?;
        let mut value = effective_value(node, k)?;
        for &i in &path.indices {
            value = value.as_list()?.get(i)?.clone();
        }
        let n = cnets_engine::optimize::leaves::count(&value);
        // A mapper's handles: the v of each handle is a variable.
        let handles = crate::mapper::node::is_mapper(node)
            && crate::mapper::node::handles_port(node) == Some(k);
        Some(if handles { n / 3 } else { n })
    });
    match count {
        Some(n) if n > 1 => format!("{n} numbers"),
        _ => "?".to_string(),
    }
}

/// The setup editor; returns the outcome of an edit.
fn setup_editor(
    ui: &mut Ui,
    doc: &mut GraphDocument,
    setup: &Setup,
) -> Option<Result<String, String>> {
    let mut edited = setup.clone();
    let mut key = None;
    let mut remove_var = None;
    let mut remove_pen = None;
    ui.horizontal(|ui| {
        ui.label("objective: minimize");
        ui.strong(setup.objective.to_string());
    });
    ui.add_space(4.0);
    ui.label(format!("variables ({})", setup.variables.len()));
    egui::Grid::new("cnets-opt-vars")
        .num_columns(5)
        .striped(true)
        .show(ui, |ui| {
            ui.weak("reference");
            ui.weak("min");
            ui.weak("max");
            ui.weak("value");
            ui.end_row();
            for (k, v) in edited.variables.iter_mut().enumerate() {
                ui.label(v.input.to_string());
                let speed = ((v.max - v.min).abs() * 0.005).max(1e-4);
                if ui
                    .add(
                        egui::DragValue::new(&mut v.min)
                            .speed(speed)
                            .max_decimals(6)
                            // A typed bound is checked when it is complete (Enter or focus
                            // lost), not at every keystroke ("1" of "1.2").
                            .update_while_editing(false),
                    )
                    .changed()
                {
                    key = Some(EditKey::Optimization(format!("min{k}")));
                }
                if ui
                    .add(
                        egui::DragValue::new(&mut v.max)
                            .speed(speed)
                            .max_decimals(6)
                            // A typed bound is checked when it is complete (Enter or focus
                            // lost), not at every keystroke ("1" of "1.2").
                            .update_while_editing(false),
                    )
                    .changed()
                {
                    key = Some(EditKey::Optimization(format!("max{k}")));
                }
                ui.label(value_label(&doc.graph, &v.input));
                if ui
                    .small_button("×")
                    .on_hover_text("remove this variable")
                    .clicked()
                {
                    remove_var = Some(k);
                }
                ui.end_row();
            }
        });
    if !setup.penalties.is_empty() {
        ui.add_space(4.0);
        ui.label("penalties");
        for (k, p) in edited.penalties.iter_mut().enumerate() {
            ui.horizontal(|ui| {
                ui.label(p.output.to_string());
                let mut kind = p.kind;
                egui::ComboBox::from_id_salt(("pen-kind", k))
                    .width(70.0)
                    .selected_text(kind_name(kind))
                    .show_ui(ui, |ui| {
                        for kd in [
                            PenaltyKind::Equal,
                            PenaltyKind::AtMost,
                            PenaltyKind::AtLeast,
                        ] {
                            ui.selectable_value(&mut kind, kd, kind_name(kd));
                        }
                    });
                if kind != p.kind {
                    p.kind = kind;
                    key = Some(EditKey::Optimization(format!("kind{k}")));
                }
                if ui
                    .add(
                        egui::DragValue::new(&mut p.target)
                            .speed(0.01)
                            .prefix("target "),
                    )
                    .changed()
                {
                    key = Some(EditKey::Optimization(format!("target{k}")));
                }
                if ui
                    .add(
                        egui::DragValue::new(&mut p.weight)
                            .speed(0.1)
                            .range(0.0..=f64::MAX)
                            .prefix("weight "),
                    )
                    .changed()
                {
                    key = Some(EditKey::Optimization(format!("weight{k}")));
                }
                if ui.small_button("×").clicked() {
                    remove_pen = Some(k);
                }
            });
        }
    }
    // Keep faces convex: one box per construction (a node reporting convexity margins).
    let mut convex_toggled = false;
    let constructions: Vec<(String, String)> = doc
        .graph
        .nodes()
        .filter(|(_, n)| {
            n.def
                .outputs
                .iter()
                .any(|p| p.hint.role == cnets_engine::Role::FaceMargins)
        })
        .map(|(_, n)| (n.id.clone(), n.label().to_string()))
        .collect();
    if !constructions.is_empty() {
        ui.add_space(4.0);
        ui.label("keep faces convex (++)(++)");
        for (id, label) in constructions {
            let mut on = edited.convex.contains(&id);
            if ui
                .checkbox(&mut on, label)
                .on_hover_text(
                    "the run keeps every face of this net (++)(++): a barrier on its convexity \
                     margins, no correction needed",
                )
                .changed()
            {
                if on {
                    edited.convex.push(id);
                } else {
                    edited.convex.retain(|c| *c != id);
                }
                convex_toggled = true;
            }
        }
    }
    ui.add_space(4.0);
    ui.horizontal(|ui| {
        ui.label("method");
        egui::ComboBox::from_id_salt("opt-method")
            .selected_text(edited.method.name())
            .show_ui(ui, |ui| {
                for m in [Method::Auto, Method::Lbfgsb, Method::NelderMead] {
                    if ui
                        .selectable_value(&mut edited.method, m, m.name())
                        .changed()
                    {
                        key = Some(EditKey::Optimization("method".into()));
                    }
                }
            });
        ui.label("max iterations");
        if ui
            .add(egui::DragValue::new(&mut edited.max_iter).range(1..=100_000))
            .changed()
        {
            key = Some(EditKey::Optimization("max_iter".into()));
        }
    });
    let structural = remove_var.is_some() || remove_pen.is_some() || convex_toggled;
    if let Some(k) = remove_var {
        edited.variables.remove(k);
    }
    if let Some(k) = remove_pen {
        edited.penalties.remove(k);
    }
    if key.is_none() && !structural {
        return None;
    }
    // Refused where typed, with a message; never swapped or clamped silently.
    if let Err(e) = super::check_bounds(&edited.variables) {
        return Some(Err(e));
    }
    let keep = !edited.variables.is_empty();
    let r = doc.edit(if structural { None } else { key }, |_, meta| {
        meta.optimization = keep.then_some(edited);
        Ok(())
    });
    Some(r.map(|()| {
        if keep {
            String::new()
        } else {
            "the last variable was removed: the optimization setup is gone (undo brings it back)"
                .to_string()
        }
    }))
}

fn kind_name(k: PenaltyKind) -> &'static str {
    match k {
        PenaltyKind::Equal => "equal",
        PenaltyKind::AtMost => "at most",
        PenaltyKind::AtLeast => "at least",
    }
}
