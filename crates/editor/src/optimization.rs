//! The optimization panel (View › Optimization): the graph's stored optimization setup
//! (`cnets_engine::optimize::Setup`: variables with bounds, objective, penalties, method, iteration
//! limit), picked from the canvas and edited as document edits (undo, saved in the file's
//! `optimization` section), and runs of the engine's optimizer on a worker thread with a live
//! objective plot.
//!
//! Picking: right-click an unconnected input's label › *Optimize this value* (a number, an item of a
//! list, a coordinate of a point; bounds: a `param.number`'s slider range, `[0, 1]` for graph-mapper
//! handles, ±50 % of the value otherwise), right-click a number output › *Minimize this output* or
//! *Add as penalty*. A setup needs an objective and at least one variable to be stored in the file;
//! until both are picked the panel keeps a draft.
//!
//! A run works on a copy of the graph (cluster instances duplicated, so caches stay separate) and
//! never blocks the UI: *Stop* sets the evaluation context's cancel flag; when it ends, *Accept*
//! writes the optimized values into the document as one undo step, *Revert* discards them.

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, channel};
use std::thread::JoinHandle;
use web_time::{Duration, Instant};

use cnets_engine::cluster::Cluster;
use cnets_engine::optimize::{
    self, Iteration, Method, Outcome, Penalty, PenaltyKind, Setup, Stop, ValuePath, Variable,
};
use cnets_engine::{Graph, NodeContext, NodeInstance, Value, ValueType};
use egui::{Color32, Pos2, Rect, Stroke, Ui};

use crate::canvas::CanvasAction;
use crate::document::GraphDocument;
use crate::history::EditKey;
use crate::widgets::{effective_value, slider_range};

/// Most numbers one input offers in its "Optimize" menu.
pub const MAX_CANDIDATES: usize = 64;

/// A number inside an input's literal value that can become a variable.
#[derive(Clone, Debug, PartialEq)]
pub struct Candidate {
    /// Where it is.
    pub path: ValuePath,
    /// Its current value.
    pub value: f64,
    /// Default lower bound.
    pub min: f64,
    /// Default upper bound.
    pub max: f64,
    /// A literal to set on the input first (a mapper's default handles have none yet).
    pub prepare: Option<Value>,
}

/// Default bounds for a number without a natural range: ±50 % of it (±1 around zero).
pub fn default_bounds(x: f64) -> (f64, f64) {
    if x == 0.0 {
        (-1.0, 1.0)
    } else {
        let d = 0.5 * x.abs();
        (x - d, x + d)
    }
}

fn leaves(value: &Value, indices: &mut Vec<usize>, out: &mut Vec<(Vec<usize>, f64)>) {
    if out.len() >= MAX_CANDIDATES {
        return;
    }
    match value {
        Value::Number(x) => out.push((indices.clone(), *x)),
        Value::Point(p) | Value::Vector(p) => {
            for (c, x) in p.to_array().into_iter().enumerate() {
                indices.push(c);
                out.push((indices.clone(), x));
                indices.pop();
            }
        }
        Value::List(items) => {
            for (i, item) in items.iter().enumerate() {
                indices.push(i);
                leaves(item, indices, out);
                indices.pop();
            }
        }
        _ => {}
    }
}

/// The numbers of input `k` of `node` that can become optimization variables, with default
/// bounds (empty for wired-only types, integers, text…).
pub fn variable_candidates(node: &NodeInstance, k: usize) -> Vec<Candidate> {
    let Some(port) = node.def.inputs.get(k) else {
        return Vec::new();
    };
    // `Any` ports (a literal list or table, e.g. `param.list`) offer the numbers they hold.
    if !matches!(
        port.ty,
        ValueType::Number | ValueType::Point | ValueType::Vector | ValueType::Any
    ) {
        return Vec::new();
    }
    let is_handles = crate::mapper::is_mapper(node) && crate::mapper::handles_port(node) == Some(k);
    let (value, prepare) = match effective_value(node, k) {
        Some(v) if !(is_handles && matches!(&v, Value::List(items) if items.is_empty())) => {
            (v, None)
        }
        _ if is_handles => {
            // No handles set: the kind's defaults, written on the input with the variable.
            let handles = Value::list(
                crate::mapper::handles(node)
                    .into_iter()
                    .map(|h| Value::Point(cnets_geometry::DVec3::new(h.x, h.y, 0.0)))
                    .collect(),
            );
            (handles.clone(), Some(handles))
        }
        _ => return Vec::new(),
    };
    let mut found = Vec::new();
    leaves(&value, &mut Vec::new(), &mut found);
    let slider = node.def.id == "param.number" && port.name == "value";
    found
        .into_iter()
        .filter(|(indices, _)| !is_handles || indices.last() != Some(&2))
        .map(|(indices, x)| {
            let (min, max) = if slider {
                let (lo, hi, _) = slider_range(node);
                (lo, hi)
            } else if is_handles {
                (0.0, 1.0)
            } else {
                default_bounds(x)
            };
            Candidate {
                path: ValuePath {
                    node: node.id.clone(),
                    port: port.name.to_string(),
                    indices,
                },
                value: x,
                min,
                max,
                prepare: prepare.clone(),
            }
        })
        .collect()
}

fn candidate_action(c: &Candidate) -> CanvasAction {
    CanvasAction::Optimize {
        path: c.path.clone(),
        min: c.min,
        max: c.max,
        prepare: c.prepare.clone(),
    }
}

/// The whole-input variable of several candidates of one input (`node.port`: every number of the
/// list, table, points or handles), bounded by the widest of their default bounds; `None` for
/// fewer than two.
pub fn whole_input(candidates: &[Candidate]) -> Option<Candidate> {
    let [first, _, ..] = candidates else {
        return None;
    };
    Some(Candidate {
        path: ValuePath {
            indices: Vec::new(),
            ..first.path.clone()
        },
        value: first.value,
        min: candidates
            .iter()
            .map(|c| c.min)
            .fold(f64::INFINITY, f64::min),
        max: candidates
            .iter()
            .map(|c| c.max)
            .fold(f64::NEG_INFINITY, f64::max),
        prepare: first.prepare.clone(),
    })
}

/// The "Optimize" entries of an input's context menu; returns the action picked.
pub fn variable_menu(ui: &mut Ui, candidates: &[Candidate]) -> Option<CanvasAction> {
    let mut picked = None;
    if let Some(all) = whole_input(candidates)
        && ui
            .button("Optimize every value")
            .on_hover_text(format!(
                "add every number of {} as optimization variables in [{}, {}] (one whole-input variable)",
                all.path,
                fmt(all.min),
                fmt(all.max)
            ))
            .clicked()
    {
        ui.close();
        return Some(candidate_action(&all));
    }
    if let [c] = candidates {
        if ui
            .button("Optimize this value")
            .on_hover_text(format!(
                "add {} as an optimization variable in [{}, {}]",
                c.path,
                fmt(c.min),
                fmt(c.max)
            ))
            .clicked()
        {
            picked = Some(candidate_action(c));
            ui.close();
        }
        return picked;
    }
    ui.menu_button("Optimize a value", |ui| {
        egui::ScrollArea::vertical()
            .max_height(320.0)
            .show(ui, |ui| {
                for c in candidates {
                    let label = format!(
                        "{} = {}",
                        c.path
                            .indices
                            .iter()
                            .map(|i| format!("[{i}]"))
                            .collect::<String>(),
                        fmt(c.value)
                    );
                    if ui.button(label).clicked() {
                        picked = Some(candidate_action(c));
                        ui.close();
                    }
                }
            });
    });
    picked
}

fn fmt(x: f64) -> String {
    crate::worker::format_number(x)
}

/// A setup still missing its objective or its variables (not stored in the file yet).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Draft {
    /// The objective, once picked.
    pub objective: Option<ValuePath>,
    /// Variables picked so far.
    pub variables: Vec<Variable>,
    /// Penalties picked so far.
    pub penalties: Vec<Penalty>,
}

/// A finished run.
pub struct Finished {
    /// The setup that ran.
    pub setup: Setup,
    /// What the optimizer returned (the graph with the best values applied).
    pub outcome: Outcome,
    /// The clusters opened when it started (the run belongs to that graph).
    pub view: Vec<String>,
    /// Wall time.
    pub seconds: f64,
}

enum Message {
    Iteration(Iteration),
    Done(Box<Result<Outcome, String>>),
}

struct Running {
    cancel: Arc<AtomicBool>,
    rx: Receiver<Message>,
    thread: Option<JoinHandle<()>>,
    setup: Setup,
    view: Vec<String>,
    started: Instant,
}

impl Drop for Running {
    fn drop(&mut self) {
        self.cancel.store(true, Ordering::Relaxed);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// The panel's state.
pub struct OptimizationPanel {
    /// Whether the panel is shown.
    pub open: bool,
    /// The setup being picked while it is incomplete.
    pub draft: Draft,
    /// The iterations reported by the current (or last) run.
    pub iterations: Vec<Iteration>,
    /// The last finished run, until accepted or reverted; or why it could not run.
    pub result: Option<Result<Finished, String>>,
    running: Option<Running>,
    wake: Arc<dyn Fn() + Send + Sync>,
}

impl OptimizationPanel {
    /// A closed panel; `wake` is called by the run's thread after each iteration.
    pub fn new(wake: Arc<dyn Fn() + Send + Sync>) -> Self {
        Self {
            open: false,
            draft: Draft::default(),
            iterations: Vec::new(),
            result: None,
            running: None,
            wake,
        }
    }

    /// Whether a run is in progress.
    pub fn running(&self) -> bool {
        self.running.is_some()
    }

    /// Forgets the draft and any result (another document was opened).
    pub fn reset(&mut self) {
        self.running = None;
        self.draft = Draft::default();
        self.iterations.clear();
        self.result = None;
    }

    /// Adds a variable (or updates its bounds); returns a status message.
    pub fn add_variable(
        &mut self,
        doc: &mut GraphDocument,
        variable: Variable,
        prepare: Option<Value>,
    ) -> Result<String, String> {
        let path = variable.input.clone();
        let message = format!(
            "optimization variable {path} in [{}, {}]",
            fmt(variable.min),
            fmt(variable.max)
        );
        if doc.meta.optimization.is_some() {
            doc.edit(None, |g, meta| {
                if let Some(v) = prepare {
                    g.set_value(&path.node, &path.port, v)
                        .map_err(|e| e.to_string())?;
                }
                let setup = meta.optimization.as_mut().ok_or("no setup")?;
                match setup.variables.iter_mut().find(|v| v.input == path) {
                    Some(v) => *v = variable,
                    None => setup.variables.push(variable),
                }
                Ok(())
            })?;
            return Ok(message);
        }
        if let Some(v) = prepare {
            doc.edit(None, |g, _| {
                g.set_value(&path.node, &path.port, v)
                    .map(|_| ())
                    .map_err(|e| e.to_string())
            })?;
        }
        match self.draft.variables.iter_mut().find(|v| v.input == path) {
            Some(v) => *v = variable,
            None => self.draft.variables.push(variable),
        }
        self.commit_draft(doc).map(|stored| {
            if stored {
                message
            } else {
                format!("{message}; now pick the objective (right-click a number output)")
            }
        })
    }

    /// Makes `path` the objective; returns a status message.
    pub fn set_objective(
        &mut self,
        doc: &mut GraphDocument,
        path: ValuePath,
    ) -> Result<String, String> {
        let message = format!("optimization objective: minimize {path}");
        if doc.meta.optimization.is_some() {
            doc.edit(None, |_, meta| {
                if let Some(s) = meta.optimization.as_mut() {
                    s.objective = path;
                }
                Ok(())
            })?;
            return Ok(message);
        }
        self.draft.objective = Some(path);
        self.commit_draft(doc).map(|stored| {
            if stored {
                message
            } else {
                format!("{message}; now pick variables (right-click a number input)")
            }
        })
    }

    /// Adds `path` as a penalty (kind `at_most`, target 0, weight 1: edit them in the panel).
    pub fn add_penalty(
        &mut self,
        doc: &mut GraphDocument,
        path: ValuePath,
    ) -> Result<String, String> {
        let penalty = Penalty {
            output: path.clone(),
            weight: 1.0,
            kind: PenaltyKind::AtMost,
            target: 0.0,
        };
        if doc.meta.optimization.is_some() {
            doc.edit(None, |_, meta| {
                if let Some(s) = meta.optimization.as_mut() {
                    s.penalties.push(penalty);
                }
                Ok(())
            })?;
        } else {
            self.draft.penalties.push(penalty);
        }
        Ok(format!("optimization penalty on {path}"))
    }

    /// Stores the draft in the document once it is complete (one undo step); returns whether it
    /// was stored.
    fn commit_draft(&mut self, doc: &mut GraphDocument) -> Result<bool, String> {
        let Some(objective) = self.draft.objective.clone() else {
            return Ok(false);
        };
        if self.draft.variables.is_empty() {
            return Ok(false);
        }
        let setup = Setup {
            objective,
            variables: self.draft.variables.clone(),
            penalties: self.draft.penalties.clone(),
            method: Method::Auto,
            max_iter: 100,
        };
        doc.edit(None, |_, meta| {
            meta.optimization = Some(setup);
            Ok(())
        })?;
        self.draft = Draft::default();
        Ok(true)
    }

    /// Starts optimizing the document's stored setup on a copy of the graph being edited.
    pub fn start(
        &mut self,
        doc: &GraphDocument,
        base_dir: Option<PathBuf>,
        max_iter: Option<usize>,
    ) -> Result<(), String> {
        if self.running.is_some() {
            return Err("an optimization is already running".into());
        }
        let mut setup = doc
            .meta
            .optimization
            .clone()
            .ok_or("no optimization setup: pick variables and an objective first")?;
        if let Some(n) = max_iter {
            setup.max_iter = n;
        }
        let graph = isolated(&doc.graph);
        let (tx, rx) = channel();
        let cancel = Arc::new(AtomicBool::new(false));
        let flag = cancel.clone();
        let wake = self.wake.clone();
        let run_setup = setup.clone();
        let thread = std::thread::Builder::new()
            .name("cnets-optimize".into())
            .spawn(move || {
                let mut ctx = NodeContext::new(None, base_dir);
                ctx.cancel = flag;
                let options = optimize::Options::default();
                let result = optimize::optimize(&graph, &run_setup, &options, &ctx, &mut |it| {
                    let _ = tx.send(Message::Iteration(it.clone()));
                    wake();
                });
                let _ = tx.send(Message::Done(Box::new(result.map_err(|e| e.to_string()))));
                wake();
            })
            .map_err(|e| format!("cannot start the optimizer: {e}"))?;
        self.iterations.clear();
        self.result = None;
        self.running = Some(Running {
            cancel,
            rx,
            thread: Some(thread),
            setup,
            view: doc.view_path(),
            started: Instant::now(),
        });
        Ok(())
    }

    /// Asks the run to stop (it ends after the evaluation in progress, keeping the best point).
    pub fn stop(&mut self) {
        if let Some(r) = &self.running {
            r.cancel.store(true, Ordering::Relaxed);
        }
    }

    /// Takes what the run reported; returns whether anything arrived.
    pub fn poll(&mut self) -> bool {
        let Some(run) = &mut self.running else {
            return false;
        };
        let mut any = false;
        let mut done = None;
        while let Ok(m) = run.rx.try_recv() {
            any = true;
            match m {
                Message::Iteration(it) => self.iterations.push(it),
                Message::Done(r) => done = Some(*r),
            }
        }
        if let Some(r) = done {
            let run = self.running.take();
            if let Some(mut run) = run {
                if let Some(t) = run.thread.take() {
                    let _ = t.join();
                }
                self.result = Some(r.map(|outcome| Finished {
                    setup: run.setup.clone(),
                    outcome,
                    view: run.view.clone(),
                    seconds: run.started.elapsed().as_secs_f64(),
                }));
            }
        }
        any
    }

    /// Waits (up to `timeout`) for the run to end, taking its reports. For tests.
    pub fn wait(&mut self, timeout: Duration) -> bool {
        let deadline = Instant::now() + timeout;
        while self.running.is_some() && Instant::now() < deadline {
            self.poll();
            std::thread::sleep(Duration::from_millis(5));
        }
        self.poll();
        self.running.is_none()
    }

    /// Writes the optimized values into the document (one undo step) and closes the result.
    pub fn accept(&mut self, doc: &mut GraphDocument) -> Result<String, String> {
        let Some(Ok(finished)) = &self.result else {
            return Err("no finished optimization to accept".into());
        };
        if finished.view != doc.view_path() {
            return Err("the optimization ran on another graph level: go back to it first".into());
        }
        let best = &finished.outcome.graph;
        let mut inputs: Vec<(String, String)> = Vec::new();
        for v in &finished.setup.variables {
            let key = (v.input.node.clone(), v.input.port.clone());
            if !inputs.contains(&key) {
                inputs.push(key);
            }
        }
        doc.edit(None, |g, _| {
            for (node, port) in &inputs {
                let value = best
                    .node(node)
                    .and_then(|n| n.value_of(port))
                    .cloned()
                    .ok_or_else(|| format!("{node}.{port} has no optimized value"))?;
                g.set_value(node, port, value).map_err(|e| e.to_string())?;
            }
            Ok(())
        })?;
        let message = format!(
            "accepted the optimized values: objective {} -> {}",
            fmt(finished.outcome.start),
            fmt(finished.outcome.objective)
        );
        self.result = None;
        Ok(message)
    }

    /// Discards the finished run's values.
    pub fn revert(&mut self) {
        self.result = None;
    }

    /// Shows the panel's content; returns a status message when something happened.
    pub fn show(
        &mut self,
        ui: &mut Ui,
        doc: &mut GraphDocument,
        base_dir: Option<PathBuf>,
    ) -> Option<String> {
        self.poll();
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

/// A copy of `graph` whose cluster nodes have their own instances (a run must not share caches
/// with the editor's evaluation).
pub fn isolated(graph: &Graph) -> Graph {
    let mut g = graph.clone();
    let clusters: Vec<(String, Arc<Cluster>)> = g
        .nodes()
        .filter_map(|(_, n)| Cluster::shared(&n.def).map(|c| (n.id.clone(), c)))
        .collect();
    for (id, c) in clusters {
        let _ = g.replace_def(&id, Arc::new(c.duplicate().node_def()));
    }
    g
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
        let handles =
            crate::mapper::is_mapper(node) && crate::mapper::handles_port(node) == Some(k);
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
                            .max_decimals(6),
                    )
                    .changed()
                {
                    key = Some(EditKey::Optimization(format!("min{k}")));
                }
                if ui
                    .add(
                        egui::DragValue::new(&mut v.max)
                            .speed(speed)
                            .max_decimals(6),
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
    let structural = remove_var.is_some() || remove_pen.is_some();
    if let Some(k) = remove_var {
        edited.variables.remove(k);
    }
    if let Some(k) = remove_pen {
        edited.penalties.remove(k);
    }
    if key.is_none() && !structural {
        return None;
    }
    for v in &mut edited.variables {
        if v.min > v.max {
            std::mem::swap(&mut v.min, &mut v.max);
        }
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

/// Draws the objective per iteration on a log scale (painter lines; no plotting crate).
pub fn objective_plot(ui: &mut Ui, points: &[(f64, f64)]) -> Rect {
    let width = ui.available_width().clamp(160.0, 420.0);
    let (rect, _) = ui.allocate_exact_size(egui::vec2(width, 150.0), egui::Sense::hover());
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect, 2.0, Color32::from_gray(250));
    painter.rect_stroke(
        rect,
        2.0,
        Stroke::new(1.0, Color32::from_gray(170)),
        egui::StrokeKind::Inside,
    );
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|(_, y)| y.is_finite())
        .map(|&(x, y)| (x, y.max(1e-300).log10()))
        .collect();
    if logs.is_empty() {
        return rect;
    }
    let lo = logs
        .iter()
        .map(|p| p.1)
        .fold(f64::INFINITY, f64::min)
        .floor();
    let hi = logs
        .iter()
        .map(|p| p.1)
        .fold(f64::NEG_INFINITY, f64::max)
        .ceil()
        .max(lo + 1.0);
    let x_max = logs.iter().map(|p| p.0).fold(1.0, f64::max);
    let plot = Rect::from_min_max(
        rect.min + egui::vec2(44.0, 8.0),
        rect.max - egui::vec2(8.0, 20.0),
    );
    let to_screen = |x: f64, y: f64| {
        Pos2::new(
            plot.left() + (x / x_max) as f32 * plot.width(),
            plot.bottom() - ((y - lo) / (hi - lo)) as f32 * plot.height(),
        )
    };
    let text = ui.visuals().text_color();
    let font = egui::FontId::proportional(10.0);
    // Decades as grid lines, every one labelled when there is room.
    let decades = (hi - lo) as i64;
    let step = (decades / 6).max(1);
    let mut d = lo as i64;
    while d <= hi as i64 {
        let y = to_screen(0.0, d as f64).y;
        painter.line_segment(
            [Pos2::new(plot.left(), y), Pos2::new(plot.right(), y)],
            Stroke::new(0.5, Color32::from_gray(215)),
        );
        painter.text(
            Pos2::new(plot.left() - 4.0, y),
            egui::Align2::RIGHT_CENTER,
            format!("1e{d}"),
            font.clone(),
            text,
        );
        d += step;
    }
    painter.text(
        Pos2::new(plot.right(), rect.bottom() - 3.0),
        egui::Align2::RIGHT_BOTTOM,
        format!("iteration {}", x_max as usize),
        font.clone(),
        text,
    );
    painter.text(
        Pos2::new(plot.left(), rect.bottom() - 3.0),
        egui::Align2::LEFT_BOTTOM,
        "0",
        font,
        text,
    );
    let line: Vec<Pos2> = logs.iter().map(|&(x, y)| to_screen(x, y)).collect();
    let blue = Color32::from_rgb(0x1f, 0x5f, 0xbf);
    painter.add(egui::Shape::line(line.clone(), Stroke::new(1.5, blue)));
    for p in line {
        painter.circle_filled(p, 2.0, blue);
    }
    rect
}

#[cfg(test)]
mod tests {
    use super::*;

    fn graph() -> Graph {
        let registry = Arc::new(cnets_nodes::registry());
        let mut g = Graph::new(registry);
        g.add_node("n", "param.number").unwrap();
        g.set_value("n", "value", Value::Number(0.3)).unwrap();
        g.set_value("n", "min", Value::Number(0.1)).unwrap();
        g.set_value("n", "max", Value::Number(2.0)).unwrap();
        g.add_node("m", "mapper.graph").unwrap();
        g.add_node("arc", "curve.arc").unwrap();
        g.set_value("arc", "radius", Value::Number(4.0)).unwrap();
        g
    }

    #[test]
    fn candidates_have_sensible_bounds() {
        let g = graph();
        let n = g.node("n").unwrap();
        let c = variable_candidates(n, n.def.input_index("value").unwrap());
        assert_eq!(c.len(), 1);
        assert_eq!((c[0].min, c[0].max, c[0].value), (0.1, 2.0, 0.3));
        assert_eq!(c[0].path.to_string(), "n.value");
        let arc = g.node("arc").unwrap();
        let c = variable_candidates(arc, arc.def.input_index("radius").unwrap());
        assert_eq!((c[0].min, c[0].max), (2.0, 6.0), "±50 %");
        let c = variable_candidates(arc, arc.def.input_index("centre").unwrap());
        assert_eq!(c.len(), 3, "a point's coordinates");
        assert_eq!(c[1].path.to_string(), "arc.centre[1]");
        assert!(variable_candidates(arc, arc.def.input_index("count").unwrap()).is_empty());
        let m = g.node("m").unwrap();
        let k = crate::mapper::handles_port(m).unwrap();
        let c = variable_candidates(m, k);
        let handles = crate::mapper::handles(m);
        assert_eq!(c.len(), 2 * handles.len(), "u and v of each default handle");
        assert!(c.iter().all(|c| c.min == 0.0 && c.max == 1.0));
        assert!(
            c[0].prepare.is_some(),
            "the default handles are written first"
        );
        let all = whole_input(&c).expect("a whole-input variable");
        assert_eq!(all.path.to_string(), "m.handles");
        assert_eq!((all.min, all.max), (0.0, 1.0));
        assert!(all.prepare.is_some());
        let one = variable_candidates(n, n.def.input_index("value").unwrap());
        assert!(
            whole_input(&one).is_none(),
            "one number: no whole-input entry"
        );
        assert_eq!(default_bounds(0.0), (-1.0, 1.0));
        assert_eq!(default_bounds(-2.0), (-3.0, -1.0));
    }

    #[test]
    fn a_draft_becomes_the_stored_setup_once_complete() {
        let mut doc = GraphDocument::from_parts(graph(), Default::default(), None);
        let mut panel = OptimizationPanel::new(Arc::new(|| {}));
        let var = Variable {
            input: ValuePath::parse("n.value").unwrap(),
            min: 0.1,
            max: 2.0,
        };
        let m = panel.add_variable(&mut doc, var, None).unwrap();
        assert!(m.contains("objective"), "{m}");
        assert!(doc.meta.optimization.is_none(), "incomplete: a draft");
        assert!(!doc.history.can_undo());
        panel
            .set_objective(&mut doc, ValuePath::parse("n.value").unwrap())
            .unwrap();
        let setup = doc.meta.optimization.clone().expect("stored");
        assert_eq!(setup.variables.len(), 1);
        assert_eq!(doc.history.undo_len(), 1);
        assert!(doc.to_ron().contains("optimization: ("));
        assert!(doc.undo());
        assert!(doc.meta.optimization.is_none());
    }
}
