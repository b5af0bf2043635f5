//! Optimization runs: the engine's optimizer on a worker thread over a copy of the graph,
//! reporting each iteration; stopping, and accepting or reverting the result.
//!
//! The 3D view follows the run: each iteration reports the best point so far, and
//! [`OptimizationPanel::live_graph`] gives the document's graph with that point applied — at most
//! [`LIVE_PER_SECOND`] times a second — for the app to evaluate and draw in place of the document.
//! After the run (stopped or finished) the view shows its result until *Accept* (which writes it)
//! or *Revert* (the document's own values again).

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, channel};
use std::thread::JoinHandle;
use web_time::{Duration, Instant};

use cnets_engine::cluster::Cluster;
use cnets_engine::eval::OutputMask;
use cnets_engine::optimize::{self, Iteration, Outcome, Setup};
use cnets_engine::{Evaluator, Graph, NodeContext, Value};
use cnets_geometry::fabrication::FaceClass;

use super::{OptimizationPanel, fmt};
use crate::document::GraphDocument;

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
    /// Warnings about the fitted design (faces left not (++)(++)), shown with the result.
    pub warnings: Vec<String>,
}

enum Message {
    Iteration(Iteration),
    Done(Box<Result<(Outcome, Vec<String>), String>>),
}

/// Pictures a second the live view of a run is updated at most.
pub const LIVE_PER_SECOND: f64 = 10.0;

/// The live view of a run: the document's graph with the variables of the run's setup, to which
/// each best point is applied.
pub(super) struct Live {
    problem: optimize::Problem,
    /// The point last handed out, and when.
    sent: Option<(Vec<f64>, Instant)>,
    /// The display options it was handed out with (other options: sent again).
    options: Option<crate::preview::PreviewOptions>,
}

/// A run in progress (dropping it stops it and joins its thread).
pub(super) struct Running {
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

impl OptimizationPanel {
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
        // The live view applies the best points to the graph the editor evaluates (at the top
        // level; inside a cluster the view keeps the document until the result is accepted).
        self.live = if doc.view_path().is_empty() {
            optimize::Problem::new(doc.eval_graph(), setup.clone(), false)
                .ok()
                .map(|problem| Live {
                    problem,
                    sent: None,
                    options: None,
                })
        } else {
            None
        };
        let (tx, rx) = channel();
        let cancel = Arc::new(AtomicBool::new(false));
        let flag = cancel.clone();
        let wake = self.wake.clone();
        let run_setup = setup.clone();
        let thread = std::thread::Builder::new()
            .name("cnets-optimize".into())
            .spawn(move || {
                let ctx = cnets_host::Session::new()
                    .with_cancel(flag)
                    .context(base_dir);
                let options = optimize::Options::default();
                let result = optimize::optimize(&graph, &run_setup, &options, &ctx, &mut |it| {
                    let _ = tx.send(Message::Iteration(it.clone()));
                    wake();
                });
                // What the fit left: faces that are not (++)(++) (issue 32: a table fit left 55
                // concave faces without a word).
                let result = result
                    .map(|outcome| {
                        let warnings = fold_warnings(&outcome.graph, &ctx);
                        (outcome, warnings)
                    })
                    .map_err(|e| e.to_string());
                let _ = tx.send(Message::Done(Box::new(result)));
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
                self.result = Some(r.map(|(outcome, warnings)| Finished {
                    setup: run.setup.clone(),
                    outcome,
                    warnings,
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
            Ok::<_, String>(())
        })?;
        let message = format!(
            "accepted the optimized values: objective {} -> {}",
            fmt(finished.outcome.start),
            fmt(finished.outcome.objective)
        );
        self.result = None;
        self.live = None;
        Ok(message)
    }

    /// Discards the finished run's values (the view shows the document's own again).
    pub fn revert(&mut self) {
        self.result = None;
        self.live = None;
    }

    /// Whether the 3D view shows the run (running, or finished and not yet accepted or reverted)
    /// rather than the document.
    pub fn shows_live_view(&self) -> bool {
        self.live.is_some() && (self.running.is_some() || matches!(self.result, Some(Ok(_))))
    }

    /// The document's graph at the run's best point so far, when the view is due a new picture:
    /// the point moved (or the display options changed) and the last one went out at least
    /// 1/[`LIVE_PER_SECOND`] s ago. A point held back by that limit asks for another frame.
    pub fn live_graph(&mut self, options: crate::preview::PreviewOptions) -> Option<Graph> {
        if !self.shows_live_view() {
            return None;
        }
        let best: Vec<f64> = match &self.result {
            Some(Ok(finished)) => finished.outcome.x.clone(),
            _ => self.iterations.last()?.best.clone(),
        };
        let live = self.live.as_mut()?;
        let same_point = live.sent.as_ref().is_some_and(|(x, _)| *x == best);
        if same_point && live.options == Some(options) {
            return None;
        }
        let due = live
            .sent
            .as_ref()
            .is_none_or(|(_, at)| at.elapsed() >= Duration::from_secs_f64(1.0 / LIVE_PER_SECOND));
        // The final point of a finished run goes out at once.
        if !due && self.running.is_some() {
            (self.wake)();
            return None;
        }
        live.problem.apply(&best).ok()?;
        live.sent = Some((best, Instant::now()));
        live.options = Some(options);
        Some(live.problem.graph().clone())
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

/// Warnings about a fitted design: every construction (a node with a quad-mesh output and one of
/// role [`cnets_engine::Role::Configurations`]) whose net has faces that are not (++)(++) — folded or concave, which a fit to a
/// distance alone may leave — with their count.
pub fn fold_warnings(graph: &Graph, ctx: &NodeContext) -> Vec<String> {
    let mut request = Vec::new();
    for (index, node) in graph.nodes() {
        if !node.enabled {
            continue;
        }
        let outputs = &node.def.outputs;
        if let (Some(m), Some(c)) = (
            outputs
                .iter()
                .position(|p| p.ty == cnets_engine::ValueType::QuadMesh),
            outputs
                .iter()
                .position(|p| p.hint.role == cnets_engine::Role::Configurations),
        ) {
            let mut mask = OutputMask::one(m);
            mask.insert(c);
            request.push((index, m, c, mask));
        }
    }
    if request.is_empty() {
        return Vec::new();
    }
    let mut eval = Evaluator::new();
    let asked: Vec<_> = request.iter().map(|r| (r.0, r.3)).collect();
    eval.evaluate_outputs(graph, &asked, ctx, &mut |_, _| {});
    let mut warnings = Vec::new();
    for (index, m, c, _) in request {
        let Some(node) = graph.node_at(index) else {
            continue;
        };
        let Some(outputs) = eval.result_at(graph, index).and_then(|r| r.outputs()) else {
            continue;
        };
        let (Some(mesh), Some(confs)) = (outputs.computed(m), outputs.computed(c)) else {
            continue;
        };
        // A construction mapped over a list gives lists of nets and of their tables.
        let pairs: Vec<(&Value, &Value)> = match (mesh, confs) {
            (Value::List(meshes), Value::List(tables)) if meshes.len() == tables.len() => {
                meshes.iter().zip(tables.iter()).collect()
            }
            _ => vec![(mesh, confs)],
        };
        let (mut bad, mut faces) = (0, 0);
        for (mesh, confs) in pairs {
            if let Value::QuadMesh(grid) = mesh
                && let Some(classes) = crate::preview::face_classes(grid, confs)
            {
                faces += classes.len();
                bad += classes
                    .iter()
                    .filter(|c| !matches!(c, FaceClass::Convex | FaceClass::Unclassified))
                    .count();
            }
        }
        if bad > 0 {
            warnings.push(format!(
                "'{}': {bad} of {faces} faces are not (++)(++) after the fit (folded or concave): \
                 check them before fabrication; tighter bounds or a penalty can keep them convex",
                node.id
            ));
        }
    }
    warnings
}
