//! The Drag net tool's solver: while a cone-net's vertex is dragged in the 3D view, the design's
//! free inputs are solved (the engine's [`drag`]: minimum-change Levenberg–Marquardt steps on the
//! exact Jacobian, pins held, faces kept (++)(++)) so the vertex follows the pointer.
//!
//! The solves run on a thread of their own over a copy of the graph taken at the press, each
//! one starting from the last answer and aiming at the newest target (targets that arrive while
//! a solve runs replace each other: the solver never falls behind the pointer). Each answer is
//! the value of every input the drag has changed so far; the app writes the newest into the
//! document as one edit of the drag's gesture ([`crate::edit::Edit::SetDragged`]), so the net,
//! the sliders and the handles move while the pointer moves and the whole drag is one undo step.
//! A solve takes at most [`STEPS_PER_SOLVE`] steps, so the picture follows the pointer; at the
//! release the last target is solved on to the end ([`STEPS_TO_FINISH`]) and the app waits for
//! that answer (half a second at most) before it closes the undo step. Where threads are not
//! available (the web page) the solves run in the frame instead.
//!
//! Free inputs: the optimization setup's variables when it has any, else every slider, point
//! list, mapper handle and list of numbers upstream of the net ([`default_free`]) except the
//! nodes locked for dragging (a node's context menu).

use std::collections::BTreeSet;
use std::sync::mpsc::{Receiver, Sender, channel};
use std::sync::{Arc, Condvar, Mutex};

use cnets_engine::optimize::Variable;
use cnets_engine::optimize::drag::{DragRequest, default_free, drag};
use cnets_engine::{Graph, NodeContext, Value};
use cnets_geometry::DVec3;
use web_time::{Duration, Instant};

use crate::viewport::NetDragTarget;

/// Steps a solve takes at most: a solve answers within a frame or two on the gallery's nets, and
/// the next one continues from its answer.
pub const STEPS_PER_SOLVE: usize = 8;

/// Steps the last solve of a drag may take (after the release, for where the pointer let go).
pub const STEPS_TO_FINISH: usize = 40;

/// What one solve reached.
#[derive(Clone, Debug)]
pub struct Solved {
    /// Every input the drag changed so far, with its value now: (node, input, value).
    pub values: Vec<(String, String, Value)>,
    /// Where the grabbed vertex is.
    pub reached: DVec3,
    /// Its distance to the target.
    pub distance_left: f64,
    /// How far a pinned vertex moved at most.
    pub pin_drift: f64,
    /// Faces that are not (++)(++) on the dragged net.
    pub not_convex: usize,
    /// The solve's wall time (ms).
    pub solve_ms: f64,
    /// The solve stopped before its last step: at the target, or as close as the inputs go.
    pub settled: bool,
}

/// One drag's problem: the graph (the last answer), what is grabbed and pinned, what may move.
struct Solver {
    graph: Graph,
    node: String,
    vertex: (usize, usize),
    item: Option<usize>,
    pins: Vec<(usize, usize)>,
    pinned_at: Vec<DVec3>,
    free: Vec<Variable>,
    ctx: NodeContext,
    /// Every (node, input) changed so far.
    touched: BTreeSet<(String, String)>,
}

impl Solver {
    /// Solves for `target`, from the last answer.
    fn solve(&mut self, target: DVec3, steps: usize) -> Result<Solved, String> {
        let started = Instant::now();
        let mut request = DragRequest::new(self.node.clone(), self.vertex, target);
        request.pins = self.pins.clone();
        request.item = self.item;
        request.pinned_at = Some(self.pinned_at.clone());
        request.free = Some(self.free.clone());
        request.max_iter = steps;
        let report = drag(&self.graph, &request, &self.ctx).map_err(|e| e.to_string())?;
        self.touched.extend(
            report
                .changes
                .iter()
                .map(|c| (c.input.node.clone(), c.input.port.clone())),
        );
        self.graph = report.graph;
        let values = self
            .touched
            .iter()
            .filter_map(|(node, input)| {
                let n = self.graph.node(node)?;
                let value = n.value(n.def.input_index(input)?)?.clone();
                Some((node.clone(), input.clone(), value))
            })
            .collect();
        let not_convex = report
            .not_convex
            .iter()
            .filter(|(n, _)| *n == self.node)
            .map(|(_, c)| c.unwrap_or(0))
            .sum();
        Ok(Solved {
            values,
            reached: report.reached,
            distance_left: report.distance_left,
            pin_drift: report.pin_drift,
            not_convex,
            solve_ms: started.elapsed().as_secs_f64() * 1e3,
            settled: report.iterations < steps,
        })
    }
}

/// The newest target, handed from the UI thread to the solver's.
#[derive(Default)]
struct Mailbox {
    target: Mutex<(Option<DVec3>, bool)>,
    ready: Condvar,
}

impl Mailbox {
    /// Leaves `target` for the solver (replacing one it has not taken).
    fn post(&self, target: DVec3) {
        if let Ok(mut m) = self.target.lock() {
            m.0 = Some(target);
            self.ready.notify_one();
        }
    }

    /// Waits for a target; `None` once the drag ended and the last target was taken.
    fn take(&self) -> Option<DVec3> {
        let mut m = self.target.lock().ok()?;
        loop {
            if let Some(t) = m.0.take() {
                return Some(t);
            }
            if m.1 {
                return None;
            }
            m = self.ready.wait(m).ok()?;
        }
    }

    /// Ends the drag: the solver stops once it has answered the last target.
    fn close(&self) {
        if let Ok(mut m) = self.target.lock() {
            m.1 = true;
            self.ready.notify_one();
        }
    }
}

/// Where the solves run.
enum Runner {
    /// On a thread of their own.
    Thread {
        mailbox: Arc<Mailbox>,
        answers: Receiver<Result<Solved, String>>,
    },
    /// In the frame (no threads: the web page).
    Inline {
        solver: Box<Solver>,
        target: Option<DVec3>,
    },
}

/// A drag of the net in progress (dropping it stops the solver after the solve in progress).
pub struct NetDragSession {
    /// The dragged net's node.
    pub node: String,
    /// The grabbed vertex.
    pub vertex: (usize, usize),
    /// Which of the node's nets.
    pub item: Option<usize>,
    runner: Runner,
    /// Solves answered, and their total wall time (ms): the update rate the docs report.
    pub solves: usize,
    /// Total solve time (ms).
    pub solve_ms: f64,
    /// When the drag started.
    pub started: Instant,
    /// Targets handed to the solver.
    pub targets: usize,
    /// The newest target.
    pub last_target: Option<DVec3>,
    /// The newest answer.
    pub newest: Option<Solved>,
}

impl Drop for NetDragSession {
    /// Stops the solver after the solve in progress (not waited for: the window never blocks).
    fn drop(&mut self) {
        if let Runner::Thread { mailbox, .. } = &self.runner {
            mailbox.close();
        }
    }
}

/// The free inputs of a drag of `node` in `graph`: the optimization setup's variables when it
/// has any, else [`default_free`] less the inputs of the `locked` nodes.
pub fn free_inputs(
    graph: &Graph,
    node: &str,
    setup_variables: &[Variable],
    locked: &BTreeSet<String>,
) -> Result<Vec<Variable>, String> {
    if !setup_variables.is_empty() {
        return Ok(setup_variables.to_vec());
    }
    let free: Vec<Variable> = default_free(graph, node)
        .map_err(|e| e.to_string())?
        .into_iter()
        .filter(|v| !locked.contains(&v.input.node))
        .collect();
    if free.is_empty() {
        return Err(format!(
            "nothing upstream of '{node}' can move: no slider, point list, mapper handle or list \
             of numbers that is not locked for dragging"
        ));
    }
    Ok(free)
}

impl NetDragSession {
    /// Starts a drag of `grab`'s vertex in a copy of `graph` (evaluated with `ctx`), the pins of
    /// `grab` held; `wake` is called when an answer is ready.
    pub fn start(
        graph: &Graph,
        grab: &NetDragTarget,
        free: Vec<Variable>,
        ctx: NodeContext,
        wake: Arc<dyn Fn() + Send + Sync>,
    ) -> Self {
        let solver = Solver {
            graph: crate::optimization::isolated(graph),
            node: grab.grabbed.node.clone(),
            vertex: grab.grabbed.vertex,
            item: grab.grabbed.item,
            pins: grab.pins.iter().map(|p| p.0).collect(),
            pinned_at: grab.pins.iter().map(|p| p.1).collect(),
            free,
            ctx,
            touched: BTreeSet::new(),
        };
        let (node, vertex, item) = (solver.node.clone(), solver.vertex, solver.item);
        let mailbox = Arc::new(Mailbox::default());
        let (tx, answers): (Sender<Result<Solved, String>>, _) = channel();
        let inbox = mailbox.clone();
        // The solver moves to the thread; when no thread can be started it comes back.
        let slot = Arc::new(Mutex::new(Some(solver)));
        let theirs = slot.clone();
        let spawned = std::thread::Builder::new()
            .name("cnets-drag-net".into())
            .spawn(move || {
                let Some(mut solver) = theirs.lock().ok().and_then(|mut s| s.take()) else {
                    return;
                };
                let mut unsettled = None;
                while let Some(target) = inbox.take() {
                    let answer = solver.solve(target, STEPS_PER_SOLVE);
                    unsettled = answer.as_ref().is_ok_and(|s| !s.settled).then_some(target);
                    if tx.send(answer).is_err() {
                        return;
                    }
                    wake();
                }
                // Released: where the pointer let go, solved to the end.
                if let Some(target) = unsettled {
                    let _ = tx.send(solver.solve(target, STEPS_TO_FINISH));
                    wake();
                }
            });
        let runner = match spawned {
            // Detached: it ends once the drag is closed and its last answer sent.
            Ok(_thread) => Runner::Thread { mailbox, answers },
            Err(_) => Runner::Inline {
                solver: Box::new(
                    slot.lock()
                        .ok()
                        .and_then(|mut s| s.take())
                        .expect("the thread did not start: the solver is still here"),
                ),
                target: None,
            },
        };
        Self {
            node,
            vertex,
            item,
            runner,
            solves: 0,
            solve_ms: 0.0,
            started: Instant::now(),
            targets: 0,
            last_target: None,
            newest: None,
        }
    }

    /// Whether `target` belongs to this drag (the same vertex of the same net).
    pub fn is_for(&self, target: &NetDragTarget) -> bool {
        self.node == target.grabbed.node
            && self.item == target.grabbed.item
            && self.vertex == target.grabbed.vertex
    }

    /// Asks for the vertex at `target` (the newest target wins).
    pub fn aim(&mut self, target: DVec3) {
        self.targets += 1;
        self.last_target = Some(target);
        match &mut self.runner {
            Runner::Thread { mailbox, .. } => mailbox.post(target),
            Runner::Inline { target: t, .. } => *t = Some(target),
        }
    }

    /// The newest answer since the last call, if any (inline: solves for the newest target now).
    pub fn poll(&mut self) -> Option<Result<Solved, String>> {
        let answer = match &mut self.runner {
            Runner::Thread { answers, .. } => answers.try_iter().last(),
            Runner::Inline { solver, target } => {
                target.take().map(|t| solver.solve(t, STEPS_PER_SOLVE))
            }
        };
        self.count(answer)
    }

    /// Ends the drag: waits up to `timeout` for the answer to the last target (where the pointer
    /// was released) and returns the newest answer not yet taken. A solve still running then is
    /// left to finish on its own; its answer is dropped.
    pub fn finish(&mut self, timeout: Duration) -> Option<Result<Solved, String>> {
        let deadline = Instant::now() + timeout;
        let mut newest = None;
        match &mut self.runner {
            Runner::Thread { mailbox, answers } => {
                mailbox.close();
                loop {
                    let wait = deadline.saturating_duration_since(Instant::now());
                    match answers.recv_timeout(wait) {
                        Ok(answer) => newest = Some(answer),
                        Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => break,
                        // Not waited for longer: the window does not block on it.
                        Err(std::sync::mpsc::RecvTimeoutError::Timeout) => break,
                    }
                }
            }
            Runner::Inline { solver, target } => {
                let unsettled = self.newest.as_ref().is_some_and(|s| !s.settled);
                newest = target
                    .take()
                    .or(self.last_target.filter(|_| unsettled))
                    .map(|t| solver.solve(t, STEPS_TO_FINISH));
            }
        }
        self.count(newest)
    }

    /// Counts an answer in the figures.
    fn count(&mut self, answer: Option<Result<Solved, String>>) -> Option<Result<Solved, String>> {
        if let Some(Ok(s)) = &answer {
            self.solves += 1;
            self.solve_ms += s.solve_ms;
            self.newest = Some(s.clone());
        }
        answer
    }

    /// Solved updates a second since the drag started.
    pub fn rate(&self) -> f64 {
        let t = self.started.elapsed().as_secs_f64();
        if t > 0.0 { self.solves as f64 / t } else { 0.0 }
    }
}
