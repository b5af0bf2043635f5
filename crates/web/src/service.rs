//! The evaluation worker's side of the page (docs/web.md, "The evaluation worker"): it owns the
//! engine's [`Evaluator`] in its own instance of the wasm module and answers the page's requests
//! as the desktop's worker thread does (`cnets_editor::worker::evaluate`): the previewed nodes
//! first (`complete: false`), then the rest of the graph.
//!
//! Each request carries the whole graph as RON text. The graph parsed from it takes over from the
//! one evaluated before ([`Graph::take_over`]): nodes with the same type, values and wires keep
//! their results, so a slider edit re-runs the slider's downstream cone only, as on the desktop.
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

use crate::wire::{self, Job};

/// The evaluator and what the page was sent last.
pub struct Service {
    registry: Arc<Registry>,
    evaluator: Evaluator,
    /// The graph evaluated last and its folder: the next graph takes over from it.
    last: Option<(Graph, Option<PathBuf>)>,
    /// The scene the page has (sent last): an equal one is not sent again.
    sent: Option<Arc<Scene>>,
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
        }
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
