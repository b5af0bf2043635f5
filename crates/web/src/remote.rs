//! The page's end of the evaluation worker (wasm32 only): a Web Worker running `worker.js`, which
//! instantiates this same wasm module (the compiled module is handed over, not fetched again) and
//! evaluates there ([`crate::worker_main`]). The editor's `Worker` hands it its requests as
//! [`Remote`]; answers arrive as messages, are decoded into `EvalResponse`s and wake the UI.
//!
//! Files opened on the page are sent to the worker too (its nodes read them there). When the
//! worker stops (a panic), a new one is started with the same files; the request it stopped on
//! is not sent again (the next edit is).

use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::Rc;
use std::sync::Arc;

use cnets_editor::preview::{Picks, PreviewStats};
use cnets_editor::remote::Remote;
use cnets_editor::worker::{EvalRequest, EvalResponse, NodeStatus};
use cnets_engine::file::{GraphMeta, LoadError, to_ron};
use cnets_render::Scene;
use wasm_bindgen::JsCast as _;
use wasm_bindgen::prelude::*;
use web_time::Instant;

use crate::literals::LiteralCache;
use crate::wire::{self, FromWorker, Job, ParseJob, Parsed, ToWorker};

/// Figures about the worker, for the browser test.
#[derive(Clone, Debug, Default)]
pub struct Figures {
    /// Requests sent.
    pub sent: u64,
    /// Answers received.
    pub answers: u64,
    /// Requests whose 3D view was answered but whose rest was dropped (a newer request came).
    pub rests_dropped: u64,
    /// Time spent decoding answers on the page, in milliseconds.
    pub decode_ms: f64,
    /// Workers started (1 unless one stopped).
    pub started: u64,
    /// Large literal values sent to the worker (each once while requests name it).
    pub literals_sent: u64,
    /// Time spent decoding the last file the worker read, in milliseconds.
    pub read_decode_ms: f64,
    /// Time spent preparing requests on the page (the graph written out, new large literals
    /// encoded), in milliseconds: the last request's and the longest.
    pub send_ms: (f64, f64),
}

struct Shared {
    worker: Option<web_sys::Worker>,
    ready: bool,
    /// The newest job not yet posted (the worker is starting).
    job: Option<Vec<u8>>,
    /// Messages not yet posted (the worker is starting): large literal values and files to read,
    /// posted before `job`.
    queued: Vec<Vec<u8>>,
    /// Files the worker reads for the page, not yet answered (their tokens), and the answers.
    reading: Vec<u64>,
    read: Vec<(u64, Result<Parsed, LoadError>)>,
    next_token: u64,
    /// The large literal values the worker holds.
    literals: LiteralCache,
    /// Every file opened on the page, in order (sent again to a restarted worker).
    files: Vec<Vec<u8>>,
    /// When each request in flight was made.
    changed_at: HashMap<u64, Instant>,
    /// The newest request posted.
    last_seq: u64,
    /// Requests answered incompletely so far (the rest may be dropped).
    open: Vec<u64>,
    responses: Vec<EvalResponse>,
    /// The last preview and statuses received (an answer may reuse them).
    preview: (Arc<Scene>, PreviewStats, Arc<Picks>),
    statuses: HashMap<String, NodeStatus>,
    /// A message for the designer (the worker stopped, a graph did not load there).
    notice: Option<String>,
    figures: Figures,
    ctx: egui::Context,
    /// The page's pointer is held (a drag), and whether the last request posted was made so.
    held: bool,
    sent_held: bool,
}

/// The evaluation worker (cheap to clone: the page and the editor's `Worker` share it).
#[derive(Clone)]
pub struct WebWorker(Rc<RefCell<Shared>>);

impl WebWorker {
    /// Starts the worker; answers wake `ctx`.
    pub fn start(ctx: egui::Context) -> Self {
        let me = Self(Rc::new(RefCell::new(Shared {
            worker: None,
            ready: false,
            job: None,
            queued: Vec::new(),
            reading: Vec::new(),
            read: Vec::new(),
            next_token: 0,
            literals: LiteralCache::default(),
            files: Vec::new(),
            changed_at: HashMap::new(),
            last_seq: 0,
            held: false,
            sent_held: false,
            open: Vec::new(),
            responses: Vec::new(),
            preview: (
                Arc::new(Scene::new()),
                PreviewStats::default(),
                Arc::new(Picks::default()),
            ),
            statuses: HashMap::new(),
            notice: None,
            figures: Figures::default(),
            ctx,
        })));
        me.spawn();
        me
    }

    /// Makes a file opened on the page readable by the worker's nodes.
    pub fn provide(&self, name: &str, bytes: Vec<u8>) {
        let message = wire::encode_to_worker(&ToWorker::Provide {
            name: name.to_string(),
            bytes,
        });
        let mut s = self.0.borrow_mut();
        if s.ready {
            post(s.worker.as_ref(), &message);
        }
        s.files.push(message);
    }

    /// Has the worker read (parse) a graph file for the page, which keeps answering meanwhile:
    /// the token its answer ([`WebWorker::take_read`]) carries.
    pub fn read_file(&self, origin: &str, library: Vec<String>, text: Vec<u8>) -> u64 {
        let mut s = self.0.borrow_mut();
        s.next_token += 1;
        let token = s.next_token;
        let message = wire::encode_to_worker(&ToWorker::Parse(ParseJob {
            token,
            origin: origin.to_string(),
            library,
            text,
        }));
        s.reading.push(token);
        s.post_or_queue(message);
        token
    }

    /// The files the worker has read since the last call, by token.
    pub fn take_read(&self) -> Vec<(u64, Result<Parsed, LoadError>)> {
        std::mem::take(&mut self.0.borrow_mut().read)
    }

    /// The page's graph holds `value` as the large literal the worker keeps under `key` (from a
    /// file it read): requests name it instead of sending it.
    pub fn adopt_literal(&self, key: u64, value: cnets_engine::Value) {
        self.0.borrow_mut().literals.adopt(key, value);
    }

    /// A message for the designer, once (the worker stopped, or did not load a graph).
    pub fn take_notice(&self) -> Option<String> {
        self.0.borrow_mut().notice.take()
    }

    /// Tells the worker whether the page's pointer is held (called every frame): when a drag
    /// that made requests ends, the last request's rest may run.
    pub fn set_held(&self, held: bool) {
        let mut s = self.0.borrow_mut();
        if s.held && !held && s.sent_held {
            s.sent_held = false;
            s.post_or_queue(wire::encode_to_worker(&ToWorker::Released));
        }
        s.held = held;
    }

    /// The worker's figures so far.
    pub fn figures(&self) -> Figures {
        self.0.borrow().figures.clone()
    }

    /// The files opened on the page from the `from`-th on, as the messages that give them to a
    /// worker.
    pub fn file_messages(&self, from: usize) -> Vec<Vec<u8>> {
        let s = self.0.borrow();
        s.files.get(from..).unwrap_or_default().to_vec()
    }

    fn spawn(&self) {
        let me = self.clone();
        let on_message = move |bytes: Vec<u8>| me.received(&bytes);
        let me = self.clone();
        let on_error = move |message: String| me.stopped(&message);
        let worker = match start_worker(on_message, on_error) {
            Ok(w) => w,
            Err(text) => {
                self.0.borrow_mut().notice =
                    Some(format!("cannot start the evaluation worker: {text}"));
                return;
            }
        };
        let mut s = self.0.borrow_mut();
        s.worker = Some(worker);
        s.ready = false;
        s.figures.started += 1;
        // A new worker holds no literal values: the next request sends what it names.
        s.literals.clear();
        s.queued.clear();
        s.job = None;
    }

    fn received(&self, bytes: &[u8]) {
        let start = Instant::now();
        let message = wire::decode_from_worker(bytes);
        let mut s = self.0.borrow_mut();
        match message {
            Ok(FromWorker::Ready) => {
                s.ready = true;
                for f in &s.files {
                    post(s.worker.as_ref(), f);
                }
                for m in std::mem::take(&mut s.queued) {
                    post(s.worker.as_ref(), &m);
                }
                if let Some(job) = s.job.take() {
                    post(s.worker.as_ref(), &job);
                }
            }
            Ok(FromWorker::Answer(a)) => {
                let a = *a;
                if let Some(preview) = a.preview {
                    s.preview = preview;
                }
                s.statuses = a.statuses.clone();
                s.figures.answers += 1;
                s.figures.decode_ms += start.elapsed().as_secs_f64() * 1e3;
                let stale = s.open.iter().filter(|&&q| q < a.seq).count() as u64;
                s.figures.rests_dropped += stale;
                s.open.retain(|&q| q > a.seq);
                if !a.complete {
                    s.open.push(a.seq);
                }
                let changed_at = if a.complete {
                    s.changed_at.retain(|&q, _| q > a.seq);
                    s.changed_at.remove(&a.seq)
                } else {
                    s.changed_at.get(&a.seq).copied()
                };
                let response = EvalResponse {
                    seq: a.seq,
                    view: a.view,
                    statuses: a.statuses,
                    scene: s.preview.0.clone(),
                    stats: s.preview.1.clone(),
                    picks: s.preview.2.clone(),
                    eval_ms: a.eval_ms,
                    ran: a.ran,
                    changed_at: changed_at.unwrap_or(start),
                    finished_at: Instant::now(),
                    complete: a.complete,
                };
                s.responses.push(response);
            }
            Ok(FromWorker::Failed { seq, message }) => {
                s.notice = Some(format!(
                    "the evaluation could not load the graph: {message}"
                ));
                let done = s.answer_unchanged(seq);
                s.responses.push(done);
            }
            Ok(FromWorker::Parsed { token, result }) => {
                s.figures.read_decode_ms = start.elapsed().as_secs_f64() * 1e3;
                s.reading.retain(|&t| t != token);
                s.read.push((token, result));
            }
            Ok(FromWorker::Dragged(_)) => {
                web_sys::console::warn_1(
                    &"cnets: a drag's answer from the evaluation worker".into(),
                );
            }
            Ok(FromWorker::Stopped { message }) => {
                drop(s);
                self.stopped(&message);
                return;
            }
            Err(e) => web_sys::console::warn_1(&format!("cnets: {e}").into()),
        }
        s.ctx.request_repaint();
    }

    /// The worker stopped: say so, close the request it was on, start another worker.
    fn stopped(&self, message: &str) {
        {
            let mut s = self.0.borrow_mut();
            if let Some(w) = s.worker.take() {
                w.terminate();
            }
            s.notice = Some(format!(
                "the evaluation stopped ({message}); edit the graph to evaluate it again"
            ));
            for token in std::mem::take(&mut s.reading) {
                let why = format!("the worker reading it stopped ({message})");
                s.read.push((token, Err(LoadError::message(why))));
            }
            let seq = s.last_seq;
            let done = s.answer_unchanged(seq);
            s.responses.push(done);
            s.ctx.request_repaint();
        }
        self.spawn();
    }
}

impl Shared {
    /// Posts `message` now, or once the worker is ready (before the newest request).
    fn post_or_queue(&mut self, message: Vec<u8>) {
        if self.ready {
            post(self.worker.as_ref(), &message);
        } else {
            self.queued.push(message);
        }
    }

    /// A complete answer for `seq` that changes nothing (the last preview and statuses).
    fn answer_unchanged(&mut self, seq: u64) -> EvalResponse {
        let now = Instant::now();
        EvalResponse {
            seq,
            view: Vec::new(),
            statuses: self.statuses.clone(),
            scene: self.preview.0.clone(),
            stats: self.preview.1.clone(),
            picks: self.preview.2.clone(),
            eval_ms: 0.0,
            ran: 0,
            changed_at: self.changed_at.remove(&seq).unwrap_or(now),
            finished_at: now,
            complete: true,
        }
    }
}

impl Remote for WebWorker {
    fn send(&mut self, request: EvalRequest) {
        let started = Instant::now();
        let mut s = self.0.borrow_mut();
        let split = s.literals.split(&request.graph);
        let graph = split.skeleton.as_ref().unwrap_or(&request.graph);
        for (key, value) in split.new {
            let message = wire::encode_to_worker(&ToWorker::Literal { key, value });
            s.figures.literals_sent += 1;
            s.post_or_queue(message);
        }
        let job = Job {
            seq: request.seq,
            ron: to_ron(graph, &GraphMeta::default()),
            base_dir: request
                .base_dir
                .as_ref()
                .map(|d| d.to_string_lossy().into_owned()),
            view: request.view,
            options: request.options,
            literals: split.refs,
            forget: split.forget,
            held: s.held,
        };
        s.sent_held = s.held;
        let message = wire::encode_to_worker(&ToWorker::Evaluate(job));
        let ms = started.elapsed().as_secs_f64() * 1e3;
        s.figures.send_ms = (ms, s.figures.send_ms.1.max(ms));
        s.changed_at.insert(request.seq, request.changed_at);
        s.last_seq = request.seq;
        s.figures.sent += 1;
        if s.ready {
            post(s.worker.as_ref(), &message);
        } else {
            s.job = Some(message);
        }
    }

    fn receive(&mut self) -> Vec<EvalResponse> {
        std::mem::take(&mut self.0.borrow_mut().responses)
    }
}

/// Starts a worker running `worker.js` on this page's compiled module: its messages' bytes go to
/// `on_message`, its errors to `on_error`.
pub(crate) fn start_worker(
    mut on_message: impl FnMut(Vec<u8>) + 'static,
    mut on_error: impl FnMut(String) + 'static,
) -> Result<web_sys::Worker, String> {
    let options = web_sys::WorkerOptions::new();
    options.set_type(web_sys::WorkerType::Module);
    let worker = web_sys::Worker::new_with_options("./worker.js", &options)
        .map_err(|e| e.as_string().unwrap_or_else(|| format!("{e:?}")))?;
    let on_message =
        Closure::<dyn FnMut(web_sys::MessageEvent)>::new(move |event: web_sys::MessageEvent| {
            on_message(js_sys::Uint8Array::new(&event.data()).to_vec());
        });
    worker.set_onmessage(Some(on_message.as_ref().unchecked_ref()));
    on_message.forget();
    let on_error =
        Closure::<dyn FnMut(web_sys::ErrorEvent)>::new(move |event: web_sys::ErrorEvent| {
            on_error(event.message());
        });
    worker.set_onerror(Some(on_error.as_ref().unchecked_ref()));
    on_error.forget();
    // The worker instantiates the module this page compiled.
    if let Err(e) = worker.post_message(&wasm_bindgen::module()) {
        web_sys::console::warn_2(&"cnets: cannot start a worker".into(), &e);
    }
    Ok(worker)
}

/// Posts a message to the worker (its bytes are transferred, not copied).
pub(crate) fn post(worker: Option<&web_sys::Worker>, bytes: &[u8]) {
    let Some(worker) = worker else { return };
    let array = js_sys::Uint8Array::from(bytes);
    let transfer = js_sys::Array::of1(&array.buffer());
    if let Err(e) = worker.post_message_with_transfer(&array, &transfer) {
        web_sys::console::warn_2(&"cnets: cannot reach the evaluation worker".into(), &e);
    }
}
