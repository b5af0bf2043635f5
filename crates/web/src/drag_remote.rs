//! The page's end of the drag worker (wasm32 only): a second Web Worker, started at the first
//! drag of the net and kept for the next, solves the Drag net tool's problem
//! ([`crate::drag_service`]) so the page's frames never wait for a solve while the evaluation
//! worker draws the answers. One target is solved at a time: the newest one waits for the answer
//! to the one before (replacing an older one waiting), so the solver never falls behind the
//! pointer.

use std::cell::RefCell;
use std::path::Path;
use std::rc::Rc;

use cnets_editor::net_drag::{DragProblem, RemoteDrag, Solved};
use cnets_geometry::DVec3;

use crate::remote::{WebWorker, post, start_worker};
use crate::wire::{self, DragJob, FromWorker, ToWorker};

struct Shared {
    worker: Option<web_sys::Worker>,
    ready: bool,
    /// Messages waiting for the worker to start (the files, the problem).
    queued: Vec<Vec<u8>>,
    /// A target is being solved.
    in_flight: bool,
    /// The newest target not yet posted.
    waiting: Option<Vec<u8>>,
    /// Answers still to come for an earlier drag (dropped on arrival).
    stale: usize,
    /// Answers not yet taken.
    answers: Vec<Result<Solved, String>>,
    /// Answers received (the browser test's figure).
    answered: u64,
    /// The files opened on the page already sent to this worker.
    files_sent: usize,
    /// The evaluation worker, whose opened files this one reads too.
    files: WebWorker,
    ctx: egui::Context,
}

/// The drag worker (cheap to clone: every drag's session holds a handle).
#[derive(Clone)]
pub struct WebDrag(Rc<RefCell<Shared>>);

impl WebDrag {
    /// The page's drag worker (started at the first drag); answers wake `ctx`; the files opened
    /// on the page (given to `files`) are readable by its nodes.
    pub fn new(ctx: egui::Context, files: WebWorker) -> Self {
        Self(Rc::new(RefCell::new(Shared {
            worker: None,
            ready: false,
            queued: Vec::new(),
            in_flight: false,
            waiting: None,
            stale: 0,
            answers: Vec::new(),
            answered: 0,
            files_sent: 0,
            files,
            ctx,
        })))
    }

    /// Answers the drag worker has sent so far.
    pub fn answered(&self) -> u64 {
        self.0.borrow().answered
    }

    fn spawn(&self) {
        let me = self.clone();
        let on_message = move |bytes: Vec<u8>| me.received(&bytes);
        let me = self.clone();
        let on_error = move |message: String| me.stopped(&message);
        let mut s = self.0.borrow_mut();
        match start_worker(on_message, on_error) {
            Ok(worker) => s.worker = Some(worker),
            Err(e) => s
                .answers
                .push(Err(format!("cannot start the drag worker: {e}"))),
        }
        s.ready = false;
        s.files_sent = 0;
    }

    fn received(&self, bytes: &[u8]) {
        let mut s = self.0.borrow_mut();
        match wire::decode_from_worker(bytes) {
            Ok(FromWorker::Ready) => {
                s.ready = true;
                for m in std::mem::take(&mut s.queued) {
                    post(s.worker.as_ref(), &m);
                }
                if let Some(m) = s.waiting.take() {
                    post(s.worker.as_ref(), &m);
                    s.in_flight = true;
                }
            }
            Ok(FromWorker::Dragged(answer)) => {
                s.in_flight = false;
                s.answered += 1;
                if s.stale > 0 {
                    s.stale -= 1;
                } else {
                    s.answers.push(answer);
                }
                if let Some(m) = s.waiting.take() {
                    post(s.worker.as_ref(), &m);
                    s.in_flight = true;
                }
            }
            Ok(FromWorker::Stopped { message }) => {
                drop(s);
                self.stopped(&message);
                return;
            }
            Ok(_) => web_sys::console::warn_1(&"cnets: an unexpected drag worker message".into()),
            Err(e) => web_sys::console::warn_1(&format!("cnets: {e}").into()),
        }
        s.ctx.request_repaint();
    }

    /// The worker stopped: the drag says so; the next drag starts another worker.
    fn stopped(&self, message: &str) {
        let mut s = self.0.borrow_mut();
        if let Some(w) = s.worker.take() {
            w.terminate();
        }
        s.ready = false;
        s.in_flight = false;
        s.waiting = None;
        s.stale = 0;
        s.queued.clear();
        s.answers
            .push(Err(format!("the drag worker stopped ({message})")));
        s.ctx.request_repaint();
    }

    fn post_or_queue(s: &mut Shared, message: Vec<u8>) {
        if s.ready {
            post(s.worker.as_ref(), &message);
        } else {
            s.queued.push(message);
        }
    }
}

impl RemoteDrag for WebDrag {
    fn start(&mut self, problem: &DragProblem, base_dir: Option<&Path>) {
        if self.0.borrow().worker.is_none() {
            self.spawn();
        }
        let mut s = self.0.borrow_mut();
        // An answer still to come belongs to the drag before.
        if s.in_flight {
            s.stale = 1;
        }
        s.waiting = None;
        s.answers.clear();
        let files = s.files.file_messages(s.files_sent);
        for m in files {
            s.files_sent += 1;
            Self::post_or_queue(&mut s, m);
        }
        let job = ToWorker::DragStart(Box::new(DragJob::of(problem, base_dir)));
        Self::post_or_queue(&mut s, wire::encode_to_worker(&job));
    }

    fn aim(&mut self, target: DVec3, steps: usize) {
        let message = wire::encode_to_worker(&ToWorker::DragAim {
            target: target.to_array(),
            steps: steps as u64,
        });
        let mut s = self.0.borrow_mut();
        if s.ready && !s.in_flight {
            post(s.worker.as_ref(), &message);
            s.in_flight = true;
        } else {
            s.waiting = Some(message);
        }
    }

    fn receive(&mut self) -> Vec<Result<Solved, String>> {
        std::mem::take(&mut self.0.borrow_mut().answers)
    }

    fn idle(&self) -> bool {
        let s = self.0.borrow();
        !s.in_flight && s.waiting.is_none()
    }

    fn handle(&self) -> Box<dyn RemoteDrag> {
        Box::new(self.clone())
    }
}
