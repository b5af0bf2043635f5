//! The worker glue: submitting the graph when it changed and taking the evaluation's answers (one
//! response path for the frame's poll and the tests' wait).

use crate::worker::Carry;
use crate::worker::NodeStatus;
use crate::worker::Worker;
use std::collections::HashMap;
use std::sync::Arc;
use web_time::Duration;
use web_time::Instant;

use super::{EditorApp, Latency};

impl EditorApp {
    /// Every node's status after the last finished evaluation.
    pub fn statuses(&self) -> &HashMap<String, NodeStatus> {
        &self.evaluation.statuses
    }

    /// The statuses shown, to hold one back (a test of a result that arrives mid-gesture).
    pub fn statuses_mut(&mut self) -> &mut HashMap<String, NodeStatus> {
        &mut self.evaluation.statuses
    }

    /// The change-to-picture figures.
    pub fn latency(&self) -> &Latency {
        &self.evaluation.latency
    }

    pub(super) fn poll_worker(&mut self) {
        if let Some(r) = self.evaluation.worker.poll() {
            self.take_response(r);
        }
    }

    /// Takes an evaluation's results: node statuses, the scene and its figures.
    pub(super) fn take_response(&mut self, r: crate::worker::EvalResponse) {
        self.evaluation.statuses = r.statuses;
        if r.view != self.evaluation.statuses_view || self.fresh.take_refit() {
            // The first results of a document or of another graph level: frame it once they are
            // drawn.
            self.canvas.fit_later();
        }
        self.evaluation.statuses_view = r.view;
        self.evaluation.latency.eval_ms = r.eval_ms;
        self.evaluation.latency.scene_ms = r.stats.build_ms;
        self.evaluation.latency.ran = r.ran;
        // The rest of the graph finished after the preview: the same scene, nothing to upload.
        if !Arc::ptr_eq(&r.scene, self.viewport.scene()) {
            self.viewport.set_scene(r.scene, r.stats, r.picks);
            if !r.complete {
                self.evaluation.latency.early_pictures += 1;
            }
            self.evaluation.awaiting_picture = Some((self.viewport.scene_version(), r.changed_at));
        }
        self.check_refused_reads();
    }

    /// The nodes "Preview only the selected" draws, sorted: the canvas's selection (else its
    /// focused node) when the toggle is on at the graph's top level; `None` draws every
    /// previewed node (the toggle off, nothing selected, or inside an opened cluster).
    fn previewed_only(&self) -> Option<Vec<String>> {
        if !self.viewport.display().only_selected || self.doc.depth() > 0 {
            return None;
        }
        let mut ids = self.canvas.targets();
        ids.sort();
        (!ids.is_empty()).then_some(ids)
    }

    /// Sends the graph to the worker when it (or the display options, or the nodes drawn)
    /// changed since the last submission.
    pub fn submit_if_changed(&mut self) {
        // An optimization shows its best point live (≤ 10 pictures a second), then its result
        // until Accept or Revert; the document is submitted again afterwards.
        if self.optimization.shows_live_view() {
            if let Some(graph) = self
                .optimization
                .live_graph(self.viewport.display().options)
            {
                // Its own generation: the worker starts a fresh evaluator for the run's graphs
                // and again for the document's afterwards (whose stamps are older than the run's).
                let (view, generation) = (self.doc.view_path(), self.doc.generation() ^ (1 << 63));
                let (options, base) = (self.viewport.display().options, self.doc.base_dir());
                self.evaluation.worker.submit_view(
                    graph,
                    view,
                    generation,
                    options,
                    base,
                    Instant::now(),
                );
                self.evaluation.submitted = None;
            }
            return;
        }
        let only = self.previewed_only();
        let key = (
            self.doc.generation(),
            self.doc.version(),
            self.viewport.display().options,
            only.as_ref().map_or(0, |ids| {
                use std::hash::{Hash, Hasher};
                let mut h = std::collections::hash_map::DefaultHasher::new();
                ids.hash(&mut h);
                h.finish() | 1
            }),
        );
        if self.evaluation.submitted == Some(key) {
            return;
        }
        let changed_at = self
            .evaluation
            .pending_change
            .take()
            .unwrap_or_else(Instant::now);
        let base = self.doc.base_dir();
        let generation = self.doc.generation();
        if let Some((from, previous, previous_base)) = self
            .evaluation
            .last_evaluated
            .take()
            .filter(|(g, ..)| *g != generation)
        {
            // Another document (or this one replaced wholesale): it continues the graph the
            // worker evaluated last, which keeps its evaluator and the results of shared nodes.
            let continued = self.doc.take_over(&previous);
            self.evaluation.worker.set_carry(Some(Carry {
                from_generation: from,
                continued: Arc::new(continued),
                same_folder: previous_base == base,
            }));
        }
        let mut graph = self.doc.eval_graph();
        self.evaluation.last_evaluated = Some((generation, graph.clone(), base.clone()));
        if let Some(ids) = &only {
            // Not an edit: a preview flag changes what is drawn (and asked for), no stamp.
            let hidden: Vec<String> = graph
                .nodes()
                .filter(|(_, n)| n.preview && !ids.contains(&n.id))
                .map(|(_, n)| n.id.clone())
                .collect();
            for id in hidden {
                let _ = graph.set_preview(&id, false);
            }
        }
        self.evaluation
            .worker
            .set_allow_read(self.doc.allowed_reads.clone());
        self.evaluation.worker.submit_view(
            graph,
            self.doc.view_path(),
            generation,
            self.viewport.display().options,
            base,
            changed_at,
        );
        self.evaluation.submitted = Some(key);
    }

    /// Evaluates with `worker` from now on (the web page: its Web Worker, [`Worker::remote`]);
    /// the graph is submitted to it at the next frame.
    pub fn set_worker(&mut self, worker: Worker) {
        self.evaluation.worker = worker;
        self.evaluation.submitted = None;
        self.evaluation.last_evaluated = None;
    }

    /// Whether an evaluation is in progress.
    pub fn busy(&self) -> bool {
        self.evaluation.worker.busy()
    }

    /// Waits (up to `timeout`) for the worker to answer the latest submission and takes the
    /// result, as the next frame would. For tests and the screenshot mode.
    pub fn wait_for_worker(&mut self, timeout: Duration) {
        self.submit_if_changed();
        if let Some(r) = self.evaluation.worker.wait(timeout) {
            self.take_response(r);
        }
    }

    /// Evaluates the graph again at the next frame (the web page: after a file was opened that a
    /// node imports).
    pub fn reevaluate(&mut self) {
        self.evaluation.submitted = None;
    }

    /// Checks the files the graph's importing nodes read; when one changed, submits the graph
    /// again so the worker re-runs the nodes that read it (and only what depends on them).
    /// Returns whether a file changed.
    pub fn check_imported_files(&mut self) -> bool {
        let base = self.doc.base_dir();
        let changed = self
            .watching
            .import_watch
            .changed(&self.doc.graph, base.as_deref());
        if changed {
            self.evaluation.submitted = None;
        }
        changed
    }
}
