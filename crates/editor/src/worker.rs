//! Evaluation off the UI thread.
//!
//! A worker thread owns the engine [`Evaluator`]. The UI submits graph snapshots ([`Graph`] is
//! cheap to clone: payloads are shared); the latest submission wins: submitting sets the cancel
//! flag of the evaluation in progress (checked by the engine between nodes and between the items
//! of mapped nodes), and the worker skips every queued snapshot but the newest. After an
//! evaluation the worker builds the preview [`Scene`] (CPU work stays off the UI thread too) and
//! sends a [`EvalResponse`] back with the status of every node.
//!
//! Without threads (the web build, wasm32) the worker is *inline*: [`Worker::poll`] evaluates the
//! newest submission on the calling thread (the UI's, once per frame), with the same
//! latest-change-wins rule — or *remote* ([`Worker::remote`]): the web page's Web Worker
//! evaluates ([`crate::remote`]).

use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, Sender, channel};
use std::thread::JoinHandle;
use web_time::{Duration, Instant};

use cnets_engine::cluster::Cluster;
use cnets_engine::eval::OutputMask;
use cnets_engine::{Continued, Evaluator, Graph, NodeContext, NodeFlag, NodeResult, Value};
use cnets_render::Scene;
use petgraph::stable_graph::NodeIndex;

use crate::preview::{Picks, Preview, PreviewOptions, PreviewStats, build_preview};

/// The state of one node after an evaluation, for badges and pin labels.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum NodeStatus {
    /// Ran; warnings (if any) and a short description of each output value.
    Ok {
        /// Warnings the node reported.
        warnings: Vec<String>,
        /// One short text per output, e.g. `quad mesh 11 × 19`.
        outputs: Vec<String>,
        /// Run time of the last run in milliseconds.
        time_ms: f64,
        /// The whole text a `view.panel` node shows inside itself (its `text` output).
        readout: Option<String>,
        /// The input values a graph mapper ran on (its widget shows wired ones from these).
        ran_on: Option<Vec<Value>>,
    },
    /// The node failed, or could not start (missing input, bad value).
    Error(String),
    /// An upstream node failed or is disabled.
    Blocked(String),
    /// Disabled by the designer.
    Disabled,
    /// Not evaluated in the editor (export nodes run on File › Export only).
    Idle,
    /// Waiting or running: the 3D view was updated first, this node (not previewed, or slow) runs
    /// after; `last_ms` is how long its last run took.
    Running {
        /// Duration of its last run in milliseconds (0 before its first run).
        last_ms: f64,
    },
}

impl NodeStatus {
    /// The message for an error badge, if any.
    pub fn error(&self) -> Option<&str> {
        match self {
            NodeStatus::Error(m) => Some(m),
            _ => None,
        }
    }

    /// The input values a graph mapper ran on (`None` for other nodes and before a run).
    pub fn ran_on(&self) -> Option<&[Value]> {
        match self {
            NodeStatus::Ok { ran_on, .. } => ran_on.as_deref(),
            _ => None,
        }
    }

    /// The warnings of a node that ran.
    pub fn warnings(&self) -> &[String] {
        match self {
            NodeStatus::Ok { warnings, .. } => warnings,
            _ => &[],
        }
    }
}

/// How the graph of a new generation continues the one the worker evaluated before (another
/// document opened in place of the last, [`Graph::take_over`]): the evaluator is kept and the
/// continued nodes keep their results.
#[derive(Clone, Debug)]
pub struct Carry {
    /// The generation the graph continues.
    pub from_generation: u64,
    /// The nodes that continue nodes of that generation's graph.
    pub continued: Arc<Vec<Continued>>,
    /// Whether relative paths resolve in the same folder as before (else the results of nodes
    /// that read files are dropped).
    pub same_folder: bool,
}

/// One evaluation request.
pub struct EvalRequest {
    /// Sequence number (increasing).
    pub seq: u64,
    /// Document generation: a new generation starts a fresh evaluator, unless `carry` says how
    /// it continues the previous one.
    pub generation: u64,
    /// For a graph of a new generation: the nodes it shares with the previous generation's.
    pub carry: Option<Carry>,
    /// The graph to evaluate.
    pub graph: Graph,
    /// Preview display options.
    pub options: PreviewOptions,
    /// Folder relative import paths resolve against.
    pub base_dir: Option<PathBuf>,
    /// Folders (and single files) besides `base_dir` that nodes may read: the document's allowed
    /// reads (a file picked with Browse…, a folder allowed at a prompt), as `--allow-read`.
    pub allow_read: Vec<PathBuf>,
    /// Cluster nodes opened in place, outermost first: statuses and the preview are those of the
    /// innermost cluster's subgraph, as its instance evaluated it inside `graph`.
    pub view: Vec<String>,
    /// Set by the UI when a newer request supersedes this one.
    pub cancel: Arc<AtomicBool>,
    /// When the change was made (for latency figures).
    pub changed_at: Instant,
}

/// The result of one evaluation.
pub struct EvalResponse {
    /// The request's sequence number.
    pub seq: u64,
    /// The opened clusters the statuses and the scene belong to (see [`EvalRequest::view`]).
    pub view: Vec<String>,
    /// Status per node id.
    pub statuses: HashMap<String, NodeStatus>,
    /// The preview scene.
    pub scene: Arc<Scene>,
    /// Figures about it.
    pub stats: PreviewStats,
    /// What the scene drew, by node (for picking in the 3D view).
    pub picks: Arc<Picks>,
    /// Evaluation time in milliseconds (nodes only).
    pub eval_ms: f64,
    /// Nodes that ran.
    pub ran: usize,
    /// When the change was made.
    pub changed_at: Instant,
    /// When the response was ready.
    pub finished_at: Instant,
    /// Every node has its final status. A first, incomplete response comes as soon as the
    /// previewed nodes are done (the 3D view is updated then); the rest of the graph follows.
    pub complete: bool,
}

/// A previewed node whose last run took longer than this runs after the 3D view is updated
/// (its previous result stays in the view meanwhile).
pub const SLOW_MS: f64 = 40.0;

/// The handle the UI keeps: submit snapshots, poll results.
pub struct Worker {
    tx: Option<Sender<EvalRequest>>,
    rx: Receiver<EvalResponse>,
    seq: u64,
    last_received: u64,
    /// The sequence number of the last complete response.
    last_complete: u64,
    running_cancel: Option<Arc<AtomicBool>>,
    carry: Option<Carry>,
    allow_read: Vec<PathBuf>,
    thread: Option<JoinHandle<()>>,
    /// The inline worker's state (no thread): the requests and the evaluator.
    inline: Option<Inline>,
    /// The service that evaluates instead of a thread (the web page's Web Worker).
    remote: Option<Box<dyn crate::remote::Remote>>,
}

/// An inline worker's own end of the request channel and its evaluator.
struct Inline {
    requests: Receiver<EvalRequest>,
    responses: Sender<EvalResponse>,
    evaluator: Evaluator,
    generation: Option<u64>,
}

impl Worker {
    /// Starts the worker thread; `wake` is called after each finished evaluation (e.g. to request
    /// a repaint of the UI).
    ///
    /// On the web (wasm32, no threads) this is [`Worker::inline`].
    pub fn spawn(wake: Arc<dyn Fn() + Send + Sync>) -> Self {
        if cfg!(target_arch = "wasm32") {
            return Self::inline();
        }
        let (tx, requests) = channel::<EvalRequest>();
        let (responses, rx) = channel::<EvalResponse>();
        let thread = std::thread::Builder::new()
            .name("cnets-eval".into())
            .spawn(move || run(requests, responses, wake))
            .ok();
        Self {
            tx: Some(tx),
            rx,
            seq: 0,
            last_received: 0,
            last_complete: 0,
            running_cancel: None,
            carry: None,
            allow_read: Vec::new(),
            thread,
            inline: None,
            remote: None,
        }
    }

    /// A worker whose requests `remote` evaluates (the web page's Web Worker).
    pub fn remote(remote: Box<dyn crate::remote::Remote>) -> Self {
        let mut worker = Self::inline();
        worker.inline = None;
        worker.remote = Some(remote);
        worker
    }

    /// A worker without a thread: [`Worker::poll`] (and [`Worker::wait`]) evaluate the newest
    /// submission on the calling thread.
    pub fn inline() -> Self {
        let (tx, requests) = channel::<EvalRequest>();
        let (responses, rx) = channel::<EvalResponse>();
        Self {
            tx: Some(tx),
            rx,
            seq: 0,
            last_received: 0,
            last_complete: 0,
            running_cancel: None,
            carry: None,
            allow_read: Vec::new(),
            thread: None,
            inline: Some(Inline {
                requests,
                responses,
                evaluator: Evaluator::new(),
                generation: None,
            }),
            remote: None,
        }
    }

    /// The inline worker's turn: evaluates the newest queued request, if any.
    fn run_inline(&mut self) {
        let Some(inline) = &mut self.inline else {
            return;
        };
        let Ok(first) = inline.requests.try_recv() else {
            return;
        };
        let responses = inline.responses.clone();
        step(
            first,
            &inline.requests,
            &mut inline.evaluator,
            &mut inline.generation,
            &mut |r| {
                let _ = responses.send(r);
            },
        );
    }

    /// Submits a snapshot; cancels the evaluation in progress. Returns its sequence number.
    pub fn submit(
        &mut self,
        graph: Graph,
        generation: u64,
        options: PreviewOptions,
        base_dir: Option<PathBuf>,
        changed_at: Instant,
    ) -> u64 {
        self.submit_view(graph, Vec::new(), generation, options, base_dir, changed_at)
    }

    /// Attaches `carry` to the following submissions: when the worker meets their (new)
    /// generation it carries its evaluator over instead of starting afresh.
    pub fn set_carry(&mut self, carry: Option<Carry>) {
        self.carry = carry;
    }

    /// Lets the following submissions' nodes read under `allow_read` too (the document's allowed
    /// reads, as `--allow-read`).
    pub fn set_allow_read(&mut self, allow_read: Vec<PathBuf>) {
        self.allow_read = allow_read;
    }

    /// Like [`Worker::submit`], showing the subgraph of the cluster at `view` (node ids from the
    /// outermost cluster in).
    pub fn submit_view(
        &mut self,
        graph: Graph,
        view: Vec<String>,
        generation: u64,
        options: PreviewOptions,
        base_dir: Option<PathBuf>,
        changed_at: Instant,
    ) -> u64 {
        if let Some(flag) = self.running_cancel.take() {
            flag.store(true, Ordering::Relaxed);
        }
        self.seq += 1;
        let cancel = Arc::new(AtomicBool::new(false));
        self.running_cancel = Some(cancel.clone());
        let request = EvalRequest {
            seq: self.seq,
            generation,
            carry: self.carry.clone(),
            graph,
            options,
            base_dir,
            allow_read: self.allow_read.clone(),
            view,
            cancel,
            changed_at,
        };
        if let Some(remote) = &mut self.remote {
            remote.send(request);
        } else if let Some(tx) = &self.tx {
            let _ = tx.send(request);
        }
        self.seq
    }

    /// The newest finished response, if any arrived since the last poll (older ones are dropped).
    pub fn poll(&mut self) -> Option<EvalResponse> {
        self.run_inline();
        let mut latest = None;
        while let Ok(r) = self.rx.try_recv() {
            latest = Some(r);
        }
        if let Some(remote) = &mut self.remote {
            latest = remote.receive().pop().or(latest);
        }
        if let Some(r) = &latest {
            self.received(r);
        }
        latest
    }

    fn received(&mut self, r: &EvalResponse) {
        self.last_received = r.seq;
        if r.complete {
            self.last_complete = r.seq;
        }
    }

    /// Whether a submitted snapshot has not been answered completely yet.
    pub fn busy(&self) -> bool {
        self.last_complete < self.seq
    }

    /// Blocks until the newest submission is answered completely or `timeout` passes; returns
    /// the last response.
    pub fn wait(&mut self, timeout: Duration) -> Option<EvalResponse> {
        if self.remote.is_some() {
            // A remote service answers between the page's frames: nothing to block on.
            return self.poll();
        }
        self.run_inline();
        let deadline = Instant::now() + timeout;
        let mut latest = None;
        while self.busy() {
            let left = deadline.saturating_duration_since(Instant::now());
            if left.is_zero() {
                break;
            }
            match self.rx.recv_timeout(left) {
                Ok(r) => {
                    self.received(&r);
                    latest = Some(r);
                }
                Err(_) => break,
            }
        }
        latest
    }
}

impl Drop for Worker {
    fn drop(&mut self) {
        if let Some(flag) = self.running_cancel.take() {
            flag.store(true, Ordering::Relaxed);
        }
        self.tx = None; // closes the channel: the thread ends
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

fn run(
    requests: Receiver<EvalRequest>,
    responses: Sender<EvalResponse>,
    wake: Arc<dyn Fn() + Send + Sync>,
) {
    let mut evaluator = Evaluator::new();
    let mut generation = None;
    while let Ok(first) = requests.recv() {
        let mut open = true;
        step(
            first,
            &requests,
            &mut evaluator,
            &mut generation,
            &mut |r| {
                open &= responses.send(r).is_ok();
                wake();
            },
        );
        if !open {
            break;
        }
    }
}

/// Evaluates the newest of `first` and the requests queued after it with `evaluator` (a fresh one
/// for a new document generation), handing each response to `send` (nothing when cancelled).
fn step(
    first: EvalRequest,
    requests: &Receiver<EvalRequest>,
    evaluator: &mut Evaluator,
    generation: &mut Option<u64>,
    send: &mut dyn FnMut(EvalResponse),
) {
    let mut request = first;
    // Latest change wins: skip every queued snapshot but the newest.
    while let Ok(newer) = requests.try_recv() {
        request = newer;
    }
    if *generation != Some(request.generation) {
        match &request.carry {
            // Another document continuing the one evaluated last: keep what it shares.
            Some(c) if *generation == Some(c.from_generation) => {
                evaluator.carry_over(&request.graph, &c.continued, c.same_folder);
            }
            _ => *evaluator = Evaluator::new(),
        }
        *generation = Some(request.generation);
    }
    evaluate(evaluator, &request, send);
}

/// Evaluates a request with `evaluator` in two phases, handing each response to `send`:
///
/// 1. the previewed nodes (and panels) — but not those whose last run was slow ([`SLOW_MS`]) —
///    with what they need; then the preview is built and sent (`complete: false` when more
///    follows), so the 3D view follows an edit however slow the rest of the graph is;
/// 2. every other node (not previewed, or slow); the final statuses follow (`complete: true`),
///    with the preview built again only when a slow previewed node ran.
///
/// A newer request cancels the evaluation (the cancel flag is checked between nodes): nothing more
/// is sent then.
pub fn evaluate(
    evaluator: &mut Evaluator,
    request: &EvalRequest,
    send: &mut dyn FnMut(EvalResponse),
) {
    let graph = &request.graph;
    let session = cnets_host::Session::new()
        .with_allow_read(request.allow_read.iter().cloned())
        .with_cancel(request.cancel.clone());
    let ctx = session.context(request.base_dir.clone());
    let cancelled = || request.cancel.load(Ordering::Relaxed);
    // Previewed nodes and panels are asked for all their outputs, the others only for what is
    // wired from them (lazy outputs). Every node runs (its status shows).
    let mut first: Vec<(NodeIndex, OutputMask)> = Vec::new();
    let mut deferred_shown = false;
    let all: Vec<(NodeIndex, OutputMask)> = graph
        .nodes()
        .filter(|(_, n)| !n.def.has_flag(NodeFlag::Export))
        .map(|(k, n)| {
            // The reference of the distance colours is needed by the preview too.
            let shown = (n.preview && n.enabled)
                || readout_output(&n.def).is_some()
                || request.options.distance_to == Some(n.uid());
            let mask = if shown {
                OutputMask::ALL
            } else {
                OutputMask::NONE
            };
            if shown {
                let slow = evaluator
                    .time(graph, &n.id)
                    .is_some_and(|t| t.as_secs_f64() * 1e3 > SLOW_MS);
                if slow {
                    deferred_shown = true;
                } else {
                    first.push((k, mask));
                }
            }
            (k, mask)
        })
        .collect();
    // The nodes phase 1 brings up to date: the requested ones and everything upstream.
    let fresh = upstream(graph, first.iter().map(|(k, _)| *k));
    let rest: Vec<(NodeIndex, OutputMask)> = all
        .iter()
        .copied()
        .filter(|(k, _)| !fresh.contains(k))
        .collect();
    // What the rest took last time (a node that never ran counts as slow).
    let rest_ms: f64 = rest
        .iter()
        .filter_map(|(k, _)| graph.node_at(*k))
        .map(|n| {
            evaluator
                .time(graph, &n.id)
                .map_or(SLOW_MS, |t| t.as_secs_f64() * 1e3)
        })
        .sum();
    let split = deferred_shown || rest_ms >= SLOW_MS;
    let first = if split { first } else { all.clone() };
    let start = Instant::now();
    let summary = evaluator.evaluate_outputs(graph, &first, &ctx, &mut |_, _| {});
    if summary.cancelled || cancelled() {
        return;
    }
    let eval_ms = start.elapsed().as_secs_f64() * 1e3;
    let shown = |p: Preview| (Arc::new(p.scene), p.stats, Arc::new(p.picks));
    let (scene, stats, picks) = shown(build_preview(graph, evaluator, &request.options));
    let respond = |evaluator: &Evaluator, complete: bool, eval_ms: f64, ran: usize| {
        let statuses = if request.view.is_empty() {
            let mut statuses = statuses(graph, evaluator, &ctx);
            if !complete {
                for (k, _) in &rest {
                    if let Some(n) = graph.node_at(*k) {
                        let last_ms = evaluator
                            .time(graph, &n.id)
                            .map_or(0.0, |t| t.as_secs_f64() * 1e3);
                        statuses.insert(n.id.clone(), NodeStatus::Running { last_ms });
                    }
                }
            }
            statuses
        } else {
            // Inside opened clusters: the statuses of the innermost instance's subgraph, with the
            // values the cluster received (every inner node is evaluated, not only those feeding
            // the outputs); the 3D view keeps showing the whole design.
            descend(graph, &request.view, &mut |cluster, g, ev| {
                let wanted: Vec<_> = g
                    .nodes()
                    .filter(|(_, n)| !n.def.has_flag(NodeFlag::Export))
                    .map(|(k, _)| k)
                    .collect();
                // Relative paths inside resolve against the cluster's own folder, as when it runs.
                let inner = session
                    .clone()
                    .with_allow_read(request.base_dir.clone())
                    .context(cluster.base_dir.clone());
                ev.evaluate(g, &wanted, &inner, &mut |_, _| {});
                statuses(g, ev, &inner)
            })
            .unwrap_or_default()
        };
        EvalResponse {
            seq: request.seq,
            view: request.view.clone(),
            statuses,
            scene: scene.clone(),
            stats: stats.clone(),
            picks: picks.clone(),
            eval_ms,
            ran,
            changed_at: request.changed_at,
            finished_at: Instant::now(),
            complete,
        }
    };
    let response = respond(evaluator, !split, eval_ms, summary.ran);
    if cancelled() {
        return;
    }
    send(response);
    if !split {
        return;
    }
    let summary2 = evaluator.evaluate_outputs(graph, &rest, &ctx, &mut |_, _| {});
    if summary2.cancelled || cancelled() {
        return;
    }
    let eval_ms = start.elapsed().as_secs_f64() * 1e3;
    let mut last = respond(evaluator, true, eval_ms, summary.ran + summary2.ran);
    if deferred_shown {
        // A slow previewed node ran: the preview again, with its new result.
        (last.scene, last.stats, last.picks) =
            shown(build_preview(graph, evaluator, &request.options));
    }
    if !cancelled() {
        send(last);
    }
}

/// `nodes` and every node upstream of them.
fn upstream(
    graph: &Graph,
    nodes: impl Iterator<Item = NodeIndex>,
) -> std::collections::HashSet<NodeIndex> {
    let mut seen = std::collections::HashSet::new();
    let mut stack: Vec<NodeIndex> = nodes.collect();
    while let Some(k) = stack.pop() {
        if seen.insert(k) {
            stack.extend(graph.sources(k));
        }
    }
    seen
}

/// The output whose text is shown inside the node (Grasshopper's Panel): the one its port
/// declares as the node's readout ([`cnets_engine::Role::Readout`]).
pub fn readout_output(def: &cnets_engine::NodeDef) -> Option<usize> {
    def.outputs
        .iter()
        .position(|p| p.hint.role == cnets_engine::Role::Readout)
}

/// The status of every node of `graph` after an evaluation with `evaluator`.
pub fn statuses(
    graph: &Graph,
    evaluator: &Evaluator,
    ctx: &NodeContext,
) -> HashMap<String, NodeStatus> {
    graph
        .nodes()
        .map(|(k, n)| {
            let status = if n.def.has_flag(NodeFlag::Export) {
                NodeStatus::Idle
            } else {
                match evaluator.result_at(graph, k) {
                    Some(NodeResult::Ok(out)) => NodeStatus::Ok {
                        warnings: out.warnings.clone(),
                        outputs: out
                            .values
                            .iter()
                            .enumerate()
                            .map(|(k, v)| match out.computed(k) {
                                Some(_) => describe(v),
                                None => "not computed (not wired, previewed or asked for)".into(),
                            })
                            .collect(),
                        time_ms: evaluator
                            .time(graph, &n.id)
                            .map_or(0.0, |t| t.as_secs_f64() * 1e3),
                        readout: readout_output(&n.def).and_then(|k| match out.values.get(k) {
                            Some(Value::Text(t)) => Some(t.to_string()),
                            _ => None,
                        }),
                        ran_on: crate::mapper::is_mapper(n)
                            .then(|| evaluator.inputs_of(graph, k, ctx).ok())
                            .flatten(),
                    },
                    Some(NodeResult::Failed(e)) => NodeStatus::Error(failure_text(e)),
                    Some(NodeResult::Invalid(m)) => NodeStatus::Error(m.to_string()),
                    Some(NodeResult::Blocked(m)) => NodeStatus::Blocked(m.to_string()),
                    Some(NodeResult::Disabled) => NodeStatus::Disabled,
                    None => NodeStatus::Idle,
                }
            };
            (n.id.clone(), status)
        })
        .collect()
}

/// Runs `f` on the cluster instance at `view` inside `graph` (node ids from the outermost cluster
/// in), with its working subgraph and evaluator; `None` when a node on the way is missing or not a
/// cluster.
pub fn descend<R>(
    graph: &Graph,
    view: &[String],
    f: &mut dyn FnMut(&Cluster, &Graph, &mut Evaluator) -> R,
) -> Option<R> {
    let (first, rest) = view.split_first()?;
    let cluster = Cluster::shared(&graph.node(first)?.def)?;
    cluster.inspect(|inner, ev| {
        if rest.is_empty() {
            Some(f(&cluster, inner, ev))
        } else {
            descend(inner, rest, f)
        }
    })
}

/// A short description of a value for an output pin: `0.5`, `quad mesh 11 × 19`, `18 items`.
pub fn describe(value: &Value) -> String {
    match value {
        Value::Null => "—".into(),
        Value::Number(x) => format_number(*x),
        Value::Integer(i) => i.to_string(),
        Value::Boolean(b) => b.to_string(),
        Value::Text(t) => {
            let t: String = t.chars().take(24).collect();
            format!("\"{t}\"")
        }
        Value::Point(p) | Value::Vector(p) => format!(
            "({}, {}, {})",
            format_number(p.x),
            format_number(p.y),
            format_number(p.z)
        ),
        Value::Plane(_) => "plane".into(),
        Value::Lines(l) => format!("{} segments", l.len()),
        Value::Polyline(p) => format!("polyline, {} points", p.points.len()),
        Value::QuadMesh(g) => format!("quad mesh {} × {}", g.rows, g.cols),
        Value::Mesh(m) => format!("mesh, {} faces", m.face_count()),
        Value::List(items) => format!("{} items", items.len()),
        Value::Record(r) => format!("record, {} fields", r.len()),
    }
}

/// A duration in milliseconds as the canvas shows it: `612 ms`, `1.4 s`.
pub fn format_ms(ms: f64) -> String {
    if ms >= 1000.0 {
        format!("{:.1} s", ms / 1000.0)
    } else {
        format!("{ms:.0} ms")
    }
}

/// A number with at most 4 significant decimals, no trailing zeros; below 0.001 and from a
/// million on in scientific notation with up to 4 significant digits (`1e-6`, `1.124e-16`,
/// `1.5e9`), so a small number never reads as `0`.
pub fn format_number(x: f64) -> String {
    if !x.is_finite() {
        return x.to_string();
    }
    if x != 0.0 && (x.abs() < 1e-3 || x.abs() >= 1e6) {
        let s = format!("{x:.3e}");
        let (mantissa, exponent) = s.split_once('e').unwrap_or((&s, "0"));
        let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
        return format!("{mantissa}e{exponent}");
    }
    let s = format!("{x:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

/// A failed node's error as the editor shows it. A reader's place in its file comes from the
/// error's fields ([`NodeError::Located`](cnets_engine::NodeError::Located)), not from its text:
/// what is wrong first, then the file's name and the line and column, on a line of their own
/// (the full path stays in the hover's last line).
pub fn failure_text(e: &cnets_engine::NodeError) -> String {
    match e {
        cnets_engine::NodeError::Located {
            file,
            line,
            column,
            message,
        } => {
            let name = std::path::Path::new(file)
                .file_name()
                .map_or_else(|| file.clone(), |n| n.to_string_lossy().into_owned());
            let place = match column {
                Some(c) => format!("line {line}, column {c}"),
                None => format!("line {line}"),
            };
            format!("{message}\n{name}, {place}\n{file}")
        }
        other => other.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;

    /// Issue 27 §5: a reader's line and column are shown from the error's fields.
    #[test]
    fn a_readers_place_is_shown_from_the_errors_fields() {
        let e = cnets_engine::NodeError::Located {
            file: "/work/designs/profile.csv".into(),
            line: 3,
            column: Some(7),
            message: "expected 2 or 3 numbers, got '4,5,q'".into(),
        };
        assert_eq!(
            failure_text(&e),
            "expected 2 or 3 numbers, got '4,5,q'\nprofile.csv, line 3, column 7\n/work/designs/profile.csv"
        );
        let e = cnets_engine::NodeError::Located {
            file: "a.obj".into(),
            line: 12,
            column: None,
            message: "bad face".into(),
        };
        assert_eq!(failure_text(&e), "bad face\na.obj, line 12\na.obj");
        assert_eq!(
            failure_text(&cnets_engine::NodeError::new("plain")),
            "plain"
        );
    }

    fn graph() -> Graph {
        let registry = Arc::new(cnets_nodes::registry());
        let mut g = Graph::new(registry);
        g.add_node("n", "param.number").unwrap();
        g.add_node("arc", "curve.arc").unwrap();
        g.connect("n", "value", "arc", "radius").unwrap();
        g
    }

    #[test]
    fn latest_submission_wins_and_results_come_back() {
        let woken = Arc::new(Mutex::new(0));
        let w2 = woken.clone();
        let mut worker = Worker::spawn(Arc::new(move || *w2.lock().unwrap() += 1));
        let mut g = graph();
        let opts = PreviewOptions::default();
        for k in 1..=20 {
            g.set_value("n", "value", Value::Number(k as f64 / 20.0))
                .unwrap();
            worker.submit(g.clone(), 0, opts, None, Instant::now());
        }
        let last = worker.wait(Duration::from_secs(60)).expect("an answer");
        assert_eq!(last.seq, 20, "the newest submission is answered last");
        assert!(!worker.busy());
        assert!(matches!(last.statuses["arc"], NodeStatus::Ok { .. }));
        assert!(!last.scene.is_empty(), "the arc is previewed");
        // The wake call follows the send: give it a moment.
        let deadline = Instant::now() + Duration::from_secs(30);
        while *woken.lock().unwrap() == 0 && Instant::now() < deadline {
            std::thread::sleep(Duration::from_millis(5));
        }
        assert!(
            *woken.lock().unwrap() >= 1,
            "the UI is woken after a result"
        );
    }

    #[test]
    fn the_inline_worker_answers_the_newest_submission_when_polled() {
        let mut worker = Worker::inline();
        let mut g = graph();
        let opts = PreviewOptions::default();
        assert!(worker.poll().is_none(), "nothing submitted");
        for k in 1..=5 {
            g.set_value("n", "value", Value::Number(k as f64 / 5.0))
                .unwrap();
            worker.submit(g.clone(), 0, opts, None, Instant::now());
        }
        assert!(worker.busy());
        let r = worker.poll().expect("evaluated on this thread");
        assert_eq!(r.seq, 5, "only the newest submission is evaluated");
        assert!(!worker.busy());
        assert!(matches!(r.statuses["arc"], NodeStatus::Ok { .. }));
        assert!(!r.scene.is_empty());
        assert!(worker.poll().is_none(), "answered once");
    }

    #[test]
    fn cancelled_requests_give_no_response() {
        let g = graph();
        let cancel = Arc::new(AtomicBool::new(true));
        let request = EvalRequest {
            seq: 1,
            generation: 0,
            carry: None,
            graph: g,
            options: PreviewOptions::default(),
            base_dir: None,
            allow_read: Vec::new(),
            view: Vec::new(),
            cancel,
            changed_at: Instant::now(),
        };
        assert!(responses(&mut Evaluator::new(), &request).is_empty());
    }

    /// Every response `evaluate` gives for a request.
    fn responses(ev: &mut Evaluator, request: &EvalRequest) -> Vec<EvalResponse> {
        let mut out = Vec::new();
        evaluate(ev, request, &mut |r| out.push(r));
        out
    }

    fn request(g: &Graph, seq: u64) -> EvalRequest {
        EvalRequest {
            seq,
            generation: 0,
            carry: None,
            graph: g.clone(),
            options: PreviewOptions::default(),
            base_dir: None,
            allow_read: Vec::new(),
            view: Vec::new(),
            cancel: Arc::new(AtomicBool::new(false)),
            changed_at: Instant::now(),
        }
    }

    #[test]
    fn the_view_follows_an_edit_before_a_slow_node_downstream_runs() {
        use cnets_engine::{Access, NodeDef, PortDef, ValueType};
        // A slider feeds a previewed arc and a slow node that is not previewed.
        let slow = NodeDef::new("t.slow", "Test", "Takes 150 ms.")
            .input(PortDef::new("x", ValueType::Number, Access::Item))
            .output(PortDef::new("y", ValueType::Number, Access::Item))
            .run(|_, inputs| {
                std::thread::sleep(Duration::from_millis(150));
                Ok(vec![inputs[0].clone()])
            });
        let mut g = graph();
        g.add_node_with_def("slow", Arc::new(slow)).unwrap();
        g.connect("n", "value", "slow", "x").unwrap();
        g.set_preview("slow", false).unwrap();
        let mut ev = Evaluator::new();
        let first = responses(&mut ev, &request(&g, 1));
        assert!(first.last().unwrap().complete);
        // Edit the slider: the preview comes first, the slow node's status follows.
        g.set_value("n", "value", Value::Number(3.0)).unwrap();
        let second = responses(&mut ev, &request(&g, 2));
        assert_eq!(second.len(), 2, "the 3D view first, then the rest");
        assert!(!second[0].complete && second[1].complete);
        assert!(
            matches!(second[0].statuses["slow"], NodeStatus::Running { last_ms } if last_ms >= 150.0),
            "{:?}",
            second[0].statuses["slow"]
        );
        assert!(matches!(second[0].statuses["arc"], NodeStatus::Ok { .. }));
        assert_ne!(
            second[0].scene.face_vertices().len() + second[0].scene.segments().len(),
            0
        );
        let before: Vec<_> = first[0].scene.segments().to_vec();
        assert_ne!(
            second[0].scene.segments().to_vec(),
            before,
            "the first response already shows the new arc"
        );
        assert!(matches!(second[1].statuses["slow"], NodeStatus::Ok { .. }));
        assert!(
            Arc::ptr_eq(&second[0].scene, &second[1].scene),
            "nothing previewed was slow: the same scene"
        );
    }

    #[test]
    fn errors_are_reported_per_node() {
        let mut g = graph();
        g.set_value("arc", "count", Value::Integer(0)).unwrap();
        let request = EvalRequest {
            seq: 1,
            generation: 0,
            carry: None,
            graph: g,
            options: PreviewOptions::default(),
            base_dir: None,
            allow_read: Vec::new(),
            view: Vec::new(),
            cancel: Arc::new(AtomicBool::new(false)),
            changed_at: Instant::now(),
        };
        let r = responses(&mut Evaluator::new(), &request).pop().unwrap();
        assert!(
            r.statuses["arc"].error().is_some(),
            "{:?}",
            r.statuses["arc"]
        );
        assert!(matches!(r.statuses["n"], NodeStatus::Ok { .. }));
    }

    #[test]
    fn numbers_are_short() {
        assert_eq!(format_number(0.5), "0.5");
        assert_eq!(format_number(2.0), "2");
        assert_eq!(format_number(1.0 / 3.0), "0.3333");
        assert_eq!(format_number(-0.0), "0");
        assert_eq!(format_number(1e-6), "1e-6");
        assert_eq!(format_number(1.124e-16), "1.124e-16");
        assert_eq!(format_number(0.01), "0.01");
        assert_eq!(format_number(12.5), "12.5");
        assert_eq!(format_number(1.5e9), "1.5e9");
        assert_eq!(format_number(-2.5e-4), "-2.5e-4");
    }
}
