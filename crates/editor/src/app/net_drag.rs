//! The Drag net tool's glue: a drag's solver started at the press ([`NetDragSession`]), the
//! pointer's targets handed to it, its answers written into the document as one gesture, the
//! drag committed (one undo step, autosaved with the document) at the release — on the web page,
//! whose drag worker is not waited for, when the release's answer arrives.

use std::collections::BTreeSet;

use cnets_geometry::DVec3;
use web_time::Duration;

use super::EditorApp;
use crate::edit::Edit;
use crate::net_drag::{NetDragSession, RemoteDrag, Solved, free_inputs};
use crate::viewport::NetDragTarget;
use crate::worker::format_number;

/// How long the release waits for the answer to the pointer's last position.
const FINISH_WAIT: Duration = Duration::from_millis(500);

/// How long a released drag waits for the drag worker's last answer before it closes anyway.
const CLOSING_WAIT: Duration = Duration::from_secs(5);

/// The Drag net tool's state.
#[derive(Default)]
pub(super) struct NetDrags {
    /// The drag in progress.
    pub(super) running: Option<NetDragSession>,
    /// A released drag whose last answer is still being solved in the drag worker (the web
    /// page): its undo step closes when the answer arrives (with the release's time, ms).
    pub(super) closing: Option<(NetDragSession, f64)>,
    /// Where drags are solved when not on a thread (the web page's drag worker).
    pub(super) remote: Option<Box<dyn RemoteDrag>>,
    /// What the last drag measured.
    pub(super) last: Option<NetDragFigures>,
    /// The UI thread's frame times of the drag running (ms), for its figures.
    pub(super) frames: Vec<f64>,
}

impl EditorApp {
    /// What the last drag of the net measured.
    pub fn last_net_drag(&self) -> Option<&NetDragFigures> {
        self.net_drags.last.as_ref()
    }

    /// Drags of the net are solved by `remote` (the web page's drag worker) instead of a thread.
    pub fn set_net_drag_remote(&mut self, remote: Box<dyn RemoteDrag>) {
        self.net_drags.remote = Some(remote);
    }

    /// The pointer asks for the grabbed vertex at `target`: starts the drag's solver at the
    /// first target of a press, then hands it the newest.
    pub(super) fn drag_net_to(&mut self, target: NetDragTarget) {
        if self
            .net_drags
            .running
            .as_ref()
            .is_none_or(|s| !s.is_for(&target))
        {
            self.close_released_net_drag(true);
            self.net_drags.running = None;
            self.net_drags.frames.clear();
            if !self.doc.view_path().is_empty() {
                self.message = "the net can be dragged at the top level of the graph: close the \
                                cluster first"
                    .into();
                return;
            }
            let graph = self.doc.eval_graph();
            let variables = self
                .doc
                .meta
                .optimization
                .as_ref()
                .map(|s| s.variables.clone())
                .unwrap_or_default();
            let free = match free_inputs(
                &graph,
                &target.grabbed.node,
                &variables,
                &self.canvas.drag_locked,
            ) {
                Ok(free) => free,
                Err(e) => {
                    self.message = format!("cannot drag the net: {e}");
                    return;
                }
            };
            let ctx = self.session().context(self.doc.base_dir());
            self.net_drags.running = Some(NetDragSession::start(
                &graph,
                &target,
                free,
                ctx,
                self.wake.clone(),
                self.net_drags.remote.as_ref().map(|r| r.handle()),
            ));
        }
        if let Some(session) = &mut self.net_drags.running {
            session.aim(target.target);
        }
    }

    /// Counts a frame's UI-thread time (`started`: the frame's start) in the drag's figures while
    /// a drag runs.
    pub(super) fn time_net_drag_frame(&mut self, started: web_time::Instant) {
        if self.net_drags.running.is_some() && self.net_drags.frames.len() < 100_000 {
            self.net_drags
                .frames
                .push(started.elapsed().as_secs_f64() * 1e3);
        }
    }

    /// A released drag of the net waits for the drag worker's last answer (its undo step open).
    pub(super) fn net_drag_closing(&self) -> bool {
        self.net_drags.closing.is_some()
    }

    /// Takes the drag's newest answer, if one arrived (every frame), and closes a released one
    /// whose last answer came.
    pub(super) fn poll_net_drag(&mut self) {
        if let Some(answer) = self.net_drags.running.as_mut().and_then(|s| s.poll()) {
            self.take_solved(answer);
        }
        self.close_released_net_drag(false);
    }

    /// A released drag still solving in the drag worker: takes its answers and, once the last
    /// came (or `now`, or after [`CLOSING_WAIT`]), closes its undo step.
    fn close_released_net_drag(&mut self, now: bool) {
        let Some((mut session, release_ms)) = self.net_drags.closing.take() else {
            return;
        };
        if let Some(answer) = session.poll() {
            self.take_solved(answer);
        }
        let waited = session.started.elapsed().as_secs_f64() * 1e3 - release_ms;
        if now || session.closed() || waited > CLOSING_WAIT.as_secs_f64() * 1e3 {
            self.close_net_drag(session, 0.0);
        } else {
            self.net_drags.closing = Some((session, release_ms));
        }
    }

    /// The pointer was released: the answer to its last position, then the drag is one step.
    pub(super) fn end_net_drag(&mut self) {
        let Some(mut session) = self.net_drags.running.take() else {
            return;
        };
        let release = web_time::Instant::now();
        let last = session.finish(FINISH_WAIT);
        let release_ms = release.elapsed().as_secs_f64() * 1e3;
        if let Some(answer) = last {
            self.take_solved(answer);
        }
        if !session.closed() {
            // The drag worker solves the release's target: the gesture stays open until then.
            let at = session.started.elapsed().as_secs_f64() * 1e3;
            self.net_drags.closing = Some((session, at));
            return;
        }
        self.close_net_drag(session, release_ms);
    }

    /// Closes `session`'s undo step and keeps its figures.
    fn close_net_drag(&mut self, session: NetDragSession, release_ms: f64) {
        self.doc.history.end_gesture();
        let figures = NetDragFigures {
            node: session.node.clone(),
            vertex: session.vertex,
            target: session.last_target,
            solved: session.newest.clone(),
            solves: session.solves,
            seconds: session.started.elapsed().as_secs_f64(),
            solve_ms: session.solve_ms / session.solves.max(1) as f64,
            ui_frame_ms: std::mem::take(&mut self.net_drags.frames),
            release_ms,
        };
        let (i, j) = figures.vertex;
        let short = figures
            .solved
            .as_ref()
            .map(|s| s.distance_left)
            .filter(|d| *d > 1e-4)
            .map_or(String::new(), |d| {
                format!("; {} m short of the target", format_number(d))
            });
        self.message = format!(
            "dragged {} (i {i}, j {j}): {} solves, {:.0} a second{short} — Ctrl+Z undoes it",
            figures.node,
            figures.solves,
            figures.rate()
        );
        self.net_drags.last = Some(figures);
    }

    /// Writes an answer into the document (the drag's gesture) and the view.
    fn take_solved(&mut self, answer: Result<Solved, String>) {
        match answer {
            Ok(s) => {
                if !s.values.is_empty() {
                    self.edit(Edit::SetDragged(s.values.clone()));
                }
                self.viewport.set_net_reached(s.reached, s.distance_left);
                let mut text = match self.viewport.tool() {
                    crate::viewport::Tool::DragNet(d) => d.status().unwrap_or_default(),
                    _ => String::new(),
                };
                if s.not_convex > 0 {
                    text.push_str(&format!(" · {} faces not (++)(++)", s.not_convex));
                }
                self.message = text;
            }
            Err(e) => self.message = format!("cannot drag the net: {e}"),
        }
    }

    /// Locks `node` for dragging the net, or unlocks it.
    pub(super) fn toggle_drag_lock(&mut self, node: String) {
        let locked: &mut BTreeSet<String> = &mut self.canvas.drag_locked;
        self.message = if locked.remove(&node) {
            format!("'{node}' unlocked: dragging the net may change it again")
        } else {
            let text = format!("'{node}' locked for dragging: the Drag net tool leaves it alone");
            locked.insert(node);
            text
        };
    }
}

/// What the last drag of the net measured (the docs' update rates; tests read them).
#[derive(Clone, Debug)]
pub struct NetDragFigures {
    /// The dragged net's node.
    pub node: String,
    /// The grabbed vertex (i, j).
    pub vertex: (usize, usize),
    /// The last target the pointer asked for.
    pub target: Option<DVec3>,
    /// The last answer.
    pub solved: Option<Solved>,
    /// Solves answered.
    pub solves: usize,
    /// The drag's wall time (press to release), in seconds.
    pub seconds: f64,
    /// Mean wall time of a solve, in milliseconds.
    pub solve_ms: f64,
    /// The UI thread's time of each frame while the drag ran (press to release, the release's
    /// frame not counted), in milliseconds: the window's side of a drag, solves excluded.
    pub ui_frame_ms: Vec<f64>,
    /// How long the release's frame waited for the answer to the pointer's last position, in
    /// milliseconds (at most half a second).
    pub release_ms: f64,
}

impl NetDragFigures {
    /// Solved updates a second.
    pub fn rate(&self) -> f64 {
        self.solves as f64 / self.seconds.max(1e-9)
    }
}
