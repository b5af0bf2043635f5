//! The evaluation worker's side of the page (docs/web.md, "The evaluation worker"): it owns the
//! engine's [`Evaluator`] in its own instance of the wasm module and answers the page's requests
//! as the desktop's worker thread does (`cnets_editor::worker::evaluate`): the previewed nodes
//! first (`complete: false`), then the rest of the graph.
//!
//! Each request carries the whole graph as RON text, its large literal values by reference
//! (`crate::literals`: sent once, kept here, put back into the parsed graph). The graph parsed
//! from it takes over from the one evaluated before ([`Graph::take_over`]): nodes with the same
//! type, values and wires keep their results, so a slider edit re-runs the slider's downstream
//! cone only, as on the desktop.
//!
//! The worker's thread is the worker's own: it cannot see a newer request while it evaluates. So
//! [`Service::begin`] stops after the first phase, and the caller (`worker_main`, in the browser)
//! looks for a newer request before calling [`Service::finish`] for the rest — a request made
//! stale by a newer one is dropped there (its rest never runs).

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use cnets_editor::worker::{EvalRequest, evaluate};
use cnets_engine::file::LoadOptions;
use cnets_engine::{Evaluator, Graph, Registry};
use cnets_render::Scene;
use web_time::Instant;

use crate::literals::LiteralStore;
use crate::wire::{self, Job, ParseJob, Parsed};

/// The evaluator and what the page was sent last.
pub struct Service {
    registry: Arc<Registry>,
    evaluator: Evaluator,
    /// The graph evaluated last and its folder: the next graph takes over from it.
    last: Option<(Graph, Option<PathBuf>)>,
    /// The scene the page has (sent last): an equal one is not sent again.
    sent: Option<Arc<Scene>>,
    /// The large literal values the page sent (`crate::literals`).
    literals: LiteralStore,
}

/// A request whose previewed nodes are answered; the rest of its graph remains.
pub struct Rest {
    request: EvalRequest,
}

impl Rest {
    /// The request's sequence number.
    pub fn seq(&self) -> u64 {
        self.request.seq
    }
}

impl Service {
    /// A service evaluating with the node types of `registry`.
    pub fn new(registry: Arc<Registry>) -> Self {
        Self {
            registry,
            evaluator: Evaluator::new(),
            last: None,
            sent: None,
            literals: LiteralStore::default(),
        }
    }

    /// Keeps a large literal value the page sent, for the requests that name `key`.
    pub fn remember(&mut self, key: u64, value: cnets_engine::Value) {
        self.literals.remember(key, value);
    }

    /// Reads a graph file for the page (which keeps answering meanwhile): the message answering
    /// it, the graph as RON without its large literals and those in the wire's binary encoding.
    /// The worker keeps the literals, so the page's first request only names them.
    pub fn parse(&mut self, job: ParseJob) -> Vec<u8> {
        let origin = PathBuf::from(&job.origin);
        let library: Vec<PathBuf> = job.library.iter().map(PathBuf::from).collect();
        let options = cnets_host::document_options(Some(&origin), &library);
        let text = String::from_utf8_lossy(&job.text);
        let name = origin.display().to_string();
        let result =
            cnets_engine::file::load_str_with(&text, &name, &self.registry, &options).map(|doc| {
                let mut graph = doc.graph;
                let literals = self.literals.take_out(&mut graph);
                Parsed {
                    skeleton: cnets_engine::file::to_ron(&graph, &doc.meta),
                    literals,
                }
            });
        wire::encode_parsed(job.token, result)
    }

    /// Drops large literal values no request names any more.
    pub fn forget(&mut self, keys: &[u64]) {
        self.literals.forget(keys);
    }

    /// Loads the job's graph and evaluates its previewed nodes: the messages to send, and the
    /// rest of the graph when more remains.
    pub fn begin(&mut self, job: Job) -> (Vec<Vec<u8>>, Option<Rest>) {
        let base_dir = job.base_dir.map(PathBuf::from);
        let mut options =
            LoadOptions::for_file(&base_dir.clone().unwrap_or_default().join("graph.ron"));
        if base_dir.is_none() {
            options.base_dir = None;
        }
        let mut graph =
            match cnets_engine::file::load_str_with(&job.ron, "graph", &self.registry, &options) {
                Ok(doc) => doc.graph,
                Err(e) => return (vec![wire::encode_failed(job.seq, &e.to_string())], None),
            };
        if let Err(e) = self.literals.restore(&mut graph, &job.literals) {
            return (vec![wire::encode_failed(job.seq, &e)], None);
        }
        match self.last.take() {
            Some((previous, previous_dir)) => {
                let continued = graph.take_over(&previous);
                self.evaluator
                    .carry_over(&graph, &continued, previous_dir == base_dir);
            }
            None => self.evaluator = Evaluator::new(),
        }
        self.last = Some((graph.clone(), base_dir.clone()));
        let request = EvalRequest {
            seq: job.seq,
            generation: 0,
            carry: None,
            graph,
            options: job.options,
            base_dir,
            allow_read: Vec::new(),
            view: job.view,
            cancel: Arc::new(AtomicBool::new(false)),
            changed_at: Instant::now(),
        };
        // Stop after the first answer when it is not the whole graph: the caller decides whether
        // the rest still matters.
        let stop = request.cancel.clone();
        let mut rest_follows = false;
        let messages = self.run(&request, &mut |complete| {
            if !complete {
                stop.store(true, Ordering::Relaxed);
                rest_follows = true;
            }
            true
        });
        let rest = rest_follows.then(|| Rest {
            request: EvalRequest {
                cancel: Arc::new(AtomicBool::new(false)),
                ..request
            },
        });
        (messages, rest)
    }

    /// Evaluates the rest of a request's graph: the messages to send (its complete answer).
    pub fn finish(&mut self, rest: Rest) -> Vec<Vec<u8>> {
        // The previewed nodes are up to date: their answer, sent already, is not sent again.
        self.run(&rest.request, &mut |complete| complete)
    }

    /// Both phases at once (tests; a worker that finds no newer request does the same).
    pub fn handle(&mut self, job: Job) -> Vec<Vec<u8>> {
        let (mut messages, rest) = self.begin(job);
        if let Some(rest) = rest {
            messages.extend(self.finish(rest));
        }
        messages
    }

    /// Runs `request`, encoding each response that `keep(complete)` keeps.
    fn run(&mut self, request: &EvalRequest, keep: &mut dyn FnMut(bool) -> bool) -> Vec<Vec<u8>> {
        let Self {
            evaluator, sent, ..
        } = self;
        let mut messages = Vec::new();
        evaluate(evaluator, request, &mut |r| {
            if !keep(r.complete) {
                return;
            }
            let same = sent
                .as_ref()
                .is_some_and(|s| Arc::ptr_eq(s, &r.scene) || wire::same_scene(s, &r.scene));
            if !same {
                *sent = Some(r.scene.clone());
            }
            messages.push(wire::encode_answer(&r, same));
        });
        messages
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wire::{FromWorker, decode_from_worker};
    use cnets_editor::preview::PreviewOptions;
    use cnets_editor::worker::NodeStatus;

    fn service() -> Service {
        crate::bundle::provide_all();
        Service::new(Arc::new(cnets_nodes::registry()))
    }

    fn job(seq: u64, ron: &str) -> Job {
        Job {
            seq,
            ron: ron.to_string(),
            base_dir: Some("graphs".into()),
            view: Vec::new(),
            options: PreviewOptions::default(),
            literals: Vec::new(),
            forget: Vec::new(),
            held: false,
        }
    }

    fn answers(messages: &[Vec<u8>]) -> Vec<crate::wire::Answer> {
        messages
            .iter()
            .map(|m| match decode_from_worker(m).expect("decodes") {
                FromWorker::Answer(a) => *a,
                _ => panic!("not an answer"),
            })
            .collect()
    }

    /// torus-monge's RON with the first number value of node `node` set to `value`.
    fn torus_with(node: &str, value: f64) -> String {
        let ron = crate::bundle::example("torus-monge").unwrap();
        let at = ron
            .find(&format!("\"{node}\": ("))
            .expect("node in the file");
        let v = at + ron[at..].find("\"value\": ").unwrap() + "\"value\": ".len();
        let end = v + ron[v..].find(',').unwrap();
        format!("{}{value:?}{}", &ron[..v], &ron[end..])
    }

    #[test]
    fn a_gallery_graph_is_answered_with_statuses_and_a_scene() {
        let mut s = service();
        let out = answers(&s.handle(job(1, crate::bundle::example("torus-monge").unwrap())));
        let last = out.last().expect("an answer");
        assert!(last.complete && last.seq == 1);
        let (scene, stats, picks) = out[0].preview.as_ref().expect("the first answer's scene");
        assert!(!scene.is_empty() && stats.vertices > 0 && !picks.meshes.is_empty());
        assert!(
            last.statuses
                .values()
                .all(|st| !matches!(st, NodeStatus::Error(_) | NodeStatus::Running { .. })),
            "{:?}",
            last.statuses
        );
    }

    #[test]
    fn an_edit_re_runs_only_what_it_reaches_and_the_newest_scene_follows() {
        let mut s = service();
        let first = answers(&s.handle(job(1, &torus_with("columns", 12.0))));
        let ran_first: usize = first.iter().map(|a| a.ran).max().unwrap();
        let again = answers(&s.handle(job(2, &torus_with("columns", 12.0))));
        assert_eq!(
            again.last().unwrap().ran,
            0,
            "the same graph again: nothing re-runs"
        );
        assert!(
            again.iter().all(|a| a.preview.is_none()),
            "the same scene is not sent again"
        );
        let edited = answers(&s.handle(job(3, &torus_with("columns", 16.0))));
        let ran = edited.last().unwrap().ran;
        assert!(
            ran > 0 && ran < ran_first,
            "an edit re-runs part of the graph: {ran} of {ran_first}"
        );
        let (_, stats, _) = edited[0].preview.as_ref().expect("a new scene");
        let (_, stats_first, _) = first[0].preview.as_ref().unwrap();
        assert!(stats.vertices > stats_first.vertices, "16 columns, not 12");
    }

    #[test]
    fn large_literals_sent_once_evaluate_as_the_whole_text_does() {
        use crate::literals::{LARGE_LITERAL_ITEMS, LiteralCache};
        use cnets_engine::Value;
        use cnets_engine::file::{GraphMeta, to_ron};
        let registry = Arc::new(cnets_nodes::registry());
        let mut g = cnets_engine::Graph::new(registry);
        g.add_node("big", "param.list").unwrap();
        let n = LARGE_LITERAL_ITEMS + 5;
        let numbers = Value::list((0..n).map(|k| Value::Number(k as f64 / 8.0)).collect());
        g.set_value("big", "values", numbers).unwrap();
        let outputs = |a: &crate::wire::Answer| match &a.statuses["big"] {
            NodeStatus::Ok { outputs, .. } => outputs.clone(),
            other => panic!("{other:?}"),
        };
        // The whole graph as text, as before.
        let whole = answers(&service().handle(job(1, &to_ron(&g, &GraphMeta::default()))));
        let expected = outputs(whole.last().unwrap());
        assert!(expected[0].contains(&n.to_string()), "{expected:?}");
        // The large list by reference: sent once, then named.
        let mut cache = LiteralCache::default();
        let mut s = service();
        let split = cache.split(&g);
        let skeleton = to_ron(split.skeleton.as_ref().unwrap(), &GraphMeta::default());
        assert!(skeleton.len() < 2_000, "the list is not in the text");
        for (key, value) in split.new {
            let message = wire::encode_to_worker(&wire::ToWorker::Literal { key, value });
            match wire::decode_to_worker(&message).unwrap() {
                wire::ToWorker::Literal { key, value } => s.remember(key, value),
                _ => unreachable!(),
            }
        }
        let by_ref = |seq: u64, refs: &[crate::literals::LiteralRef]| Job {
            literals: refs.to_vec(),
            ..job(seq, &skeleton)
        };
        let first = answers(&s.handle(by_ref(2, &split.refs)));
        assert_eq!(outputs(first.last().unwrap()), expected);
        // The same graph again (a node moved): nothing is sent, nothing re-runs.
        g.set_position("big", [10.0, 20.0]).unwrap();
        let again = cache.split(&g);
        assert!(again.new.is_empty());
        let second = answers(&s.handle(by_ref(3, &again.refs)));
        assert_eq!(second.last().unwrap().ran, 0);
        // A key the worker does not hold is a failure that names the input, not a wrong answer.
        s.forget(&[again.refs[0].key]);
        match decode_from_worker(&s.handle(by_ref(4, &again.refs))[0]).unwrap() {
            FromWorker::Failed { seq, message } => {
                assert_eq!(seq, 4);
                assert!(message.contains("big.values"), "{message}");
            }
            _ => panic!("expected a failure"),
        }
    }

    #[test]
    fn a_file_read_for_the_page_comes_back_as_it_loads_and_its_literals_stay() {
        use crate::literals::{LARGE_LITERAL_ITEMS, LiteralCache, WORKER_KEYS};
        use crate::wire::{ParseJob, decode_from_worker};
        let numbers: Vec<String> = (0..LARGE_LITERAL_ITEMS + 1)
            .map(|k| format!("{:.6}", k as f64 * 1e-4 + 0.5))
            .collect();
        let text = format!(
            "(version: 1, name: \"big\", nodes: {{\"numbers\": (type: \"param.list\", \
             position: (0.0, 0.0), inputs: {{\"values\": [{}]}}), \"item\": (type: \
             \"list.item\", position: (300.0, 0.0), inputs: {{\"index\": 7}})}}, \
             edges: [\"numbers.values -> item.list\"])",
            numbers.join(", ")
        );
        let mut s = service();
        let read = |text: &str| ParseJob {
            token: 5,
            origin: "big.ron".into(),
            library: Vec::new(),
            text: text.as_bytes().to_vec(),
        };
        let parsed = match decode_from_worker(&s.parse(read(&text))).unwrap() {
            FromWorker::Parsed { token: 5, result } => result.expect("loads"),
            _ => panic!("not a read file"),
        };
        assert!(parsed.skeleton.len() < 2_000, "the list is not in the text");
        assert_eq!(parsed.literals.len(), 1);
        assert!(parsed.literals[0].0.key >= WORKER_KEYS);
        // The page's graph: the skeleton with the literal put back is the file's graph.
        let registry = Arc::new(cnets_nodes::registry());
        let options = cnets_engine::file::LoadOptions::default();
        let load = |t: &str| cnets_engine::file::load_str_with(t, "big.ron", &registry, &options);
        let mut page = load(&parsed.skeleton).unwrap();
        let (at, value) = parsed.literals[0].clone();
        page.graph.set_value(&at.node, &at.input, value).unwrap();
        let direct = load(&text).unwrap();
        let ron = |d: &cnets_engine::file::Document| cnets_engine::file::to_ron(&d.graph, &d.meta);
        assert_eq!(ron(&page), ron(&direct));
        // The first request names the literal; the worker evaluates with the one it kept.
        let mut cache = LiteralCache::default();
        let held = page
            .graph
            .node("numbers")
            .unwrap()
            .value_of("values")
            .unwrap();
        cache.adopt(at.key, held.clone());
        let split = cache.split(&page.graph);
        assert!(split.new.is_empty());
        let request = Job {
            literals: split.refs,
            ..job(
                1,
                &cnets_engine::file::to_ron(split.skeleton.as_ref().unwrap(), &page.meta),
            )
        };
        let out = answers(&s.handle(request));
        match &out.last().unwrap().statuses["item"] {
            NodeStatus::Ok { outputs, .. } => assert!(outputs[0].contains("0.5007"), "{outputs:?}"),
            other => panic!("{other:?}"),
        }
        // A file that does not load says why, as the page's own reading would.
        match decode_from_worker(&s.parse(read("(nodes: {\"a\": (type: \"no.such\")})"))).unwrap() {
            FromWorker::Parsed { result: Err(e), .. } => {
                assert!(e.to_string().contains("no.such"), "{e}");
                assert!(e.first_line().is_some(), "the place crosses typed: {e:?}");
            }
            _ => panic!("expected the load error"),
        }
    }

    #[test]
    fn a_graph_that_does_not_load_is_a_failure_message() {
        let mut s = service();
        let out = s.handle(job(7, "(nodes: {\"a\": (type: \"no.such.node\")})"));
        match decode_from_worker(&out[0]).unwrap() {
            FromWorker::Failed { seq, message } => {
                assert_eq!(seq, 7);
                assert!(!message.is_empty());
            }
            _ => panic!("expected a failure"),
        }
    }
}
