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
//! that answer (half a second at most) before it closes the undo step. On the web page (no threads)
//! the solves run in a drag worker of their own ([`RemoteDrag`]): the release does not wait there,
//! the undo step closes when the last answer arrives ([`NetDragSession::closed`]). Where neither
//! is available the solves run in the frame.
//!
//! Free inputs: the optimization setup's variables when it has any, else every slider, point
//! list, mapper handle and list of numbers upstream of the net ([`default_free`]) except the
//! nodes locked for dragging (a node's context menu).

use std::collections::BTreeSet;
use std::sync::mpsc::{Receiver, Sender, channel};
use std::sync::{Arc, Condvar, Mutex};

use cnets_engine::optimize::Variable;
use cnets_engine::optimize::drag::default_free;
use cnets_engine::{Graph, NodeContext};
use cnets_geometry::DVec3;
use web_time::{Duration, Instant};

pub use crate::drag_solver::{DragProblem, DragSolver, RemoteDrag, Solved};
use crate::viewport::NetDragTarget;

/// Steps a solve takes at most: a solve answers within a frame or two on the gallery's nets, and
/// the next one continues from its answer.
pub const STEPS_PER_SOLVE: usize = 8;

/// Steps the last solve of a drag may take (after the release, for where the pointer let go).
pub const STEPS_TO_FINISH: usize = 40;

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
    /// In the web page's drag worker.
    Remote {
        service: Box<dyn RemoteDrag>,
        /// The release asked for its last answer.
        closing: bool,
    },
    /// In the frame (no thread could be started).
    Inline {
        solver: Box<DragSolver>,
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
    /// `grab` held; `wake` is called when an answer is ready. With `remote` the solves run there
    /// (the web page's drag worker), else on a thread of their own.
    pub fn start(
        graph: &Graph,
        grab: &NetDragTarget,
        free: Vec<Variable>,
        ctx: NodeContext,
        wake: Arc<dyn Fn() + Send + Sync>,
        remote: Option<Box<dyn RemoteDrag>>,
    ) -> Self {
        let problem = DragProblem {
            graph: crate::optimization::isolated(graph),
            node: grab.grabbed.node.clone(),
            vertex: grab.grabbed.vertex,
            item: grab.grabbed.item,
            pins: grab.pins.iter().map(|p| p.0).collect(),
            pinned_at: grab.pins.iter().map(|p| p.1).collect(),
            free,
        };
        let (node, vertex, item) = (problem.node.clone(), problem.vertex, problem.item);
        let runner = match remote {
            Some(mut service) => {
                service.start(&problem, ctx.base_dir.as_deref());
                Runner::Remote {
                    service,
                    closing: false,
                }
            }
            None => Self::on_a_thread(DragSolver::new(problem, ctx), wake),
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

    /// Runs `solver` on a thread of its own (in the frame when no thread can be started).
    fn on_a_thread(solver: DragSolver, wake: Arc<dyn Fn() + Send + Sync>) -> Runner {
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
        match spawned {
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
            Runner::Remote { service, .. } => service.aim(target, STEPS_PER_SOLVE),
            Runner::Inline { target: t, .. } => *t = Some(target),
        }
    }

    /// The newest answer since the last call, if any (inline: solves for the newest target now).
    pub fn poll(&mut self) -> Option<Result<Solved, String>> {
        let answer = match &mut self.runner {
            Runner::Thread { answers, .. } => answers.try_iter().last(),
            Runner::Remote { service, .. } => service.receive().pop(),
            Runner::Inline { solver, target } => {
                target.take().map(|t| solver.solve(t, STEPS_PER_SOLVE))
            }
        };
        self.count(answer)
    }

    /// Ends the drag: waits up to `timeout` for the answer to the last target (where the pointer
    /// was released) and returns the newest answer not yet taken. A solve still running then is
    /// left to finish on its own; its answer is dropped. In the drag worker nothing is waited
    /// for: the last target is asked for to the end, and its answer comes by [`Self::poll`]
    /// until [`Self::closed`].
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
            Runner::Remote { service, closing } => {
                // The last target to the end (one step when it was reached already); the window
                // does not wait for it.
                *closing = true;
                newest = service.receive().pop();
                if let Some(t) = self.last_target {
                    service.aim(t, STEPS_TO_FINISH);
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

    /// Whether the drag has its last answer: always once finished, except in the drag worker,
    /// until the answer to the release's target arrived.
    pub fn closed(&self) -> bool {
        match &self.runner {
            Runner::Remote { service, closing } => *closing && service.idle(),
            _ => true,
        }
    }

    /// Whether the solves run in the web page's drag worker.
    pub fn is_remote(&self) -> bool {
        matches!(self.runner, Runner::Remote { .. })
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
