//! The drag worker's side of the page (docs/web.md, "Dragging the net"): a second Web Worker
//! solves the Drag net tool's problem, so the page's frames never wait for a solve and the
//! evaluation worker keeps drawing the answers. It is the desktop's drag thread
//! (`cnets_editor::net_drag`) over messages: the problem arrives once at the press, then each
//! target, one at a time (the page sends the newest when the answer to the last came).

use std::path::PathBuf;
use std::sync::Arc;

use cnets_editor::net_drag::{DragProblem, DragSolver};
use cnets_engine::file::LoadOptions;
use cnets_engine::{NodeContext, Registry};
use cnets_geometry::DVec3;

use crate::wire::{self, DragJob};

/// The drag in progress in this worker.
pub struct DragService {
    registry: Arc<Registry>,
    solver: Result<DragSolver, String>,
}

impl DragService {
    /// A worker that has no drag yet.
    pub fn new(registry: Arc<Registry>) -> Self {
        Self {
            registry,
            solver: Err("no drag of the net was started".into()),
        }
    }

    /// Starts the drag of `job` (a graph that does not load is the answer to every target).
    pub fn start(&mut self, job: &DragJob) {
        self.solver = self
            .problem(job)
            .map(|(problem, base_dir)| DragSolver::new(problem, NodeContext::new(None, base_dir)));
    }

    fn problem(&self, job: &DragJob) -> Result<(DragProblem, Option<PathBuf>), String> {
        let base_dir = job.base_dir.as_ref().map(PathBuf::from);
        let mut options =
            LoadOptions::for_file(&base_dir.clone().unwrap_or_default().join("graph.ron"));
        if base_dir.is_none() {
            options.base_dir = None;
        }
        let graph = cnets_engine::file::load_str_with(&job.ron, "graph", &self.registry, &options)
            .map_err(|e| e.to_string())?
            .graph;
        let (pins, pinned_at) = job.pins();
        let problem = DragProblem {
            graph,
            node: job.node.clone(),
            vertex: job.vertex(),
            item: job.item.map(|k| usize::try_from(k).unwrap_or(usize::MAX)),
            pins,
            pinned_at,
            free: job.variables()?,
        };
        Ok((problem, base_dir))
    }

    /// The answer (its message) to the vertex at `target`, solved in at most `steps` steps.
    pub fn aim(&mut self, target: [f64; 3], steps: u64) -> Vec<u8> {
        let steps = usize::try_from(steps).unwrap_or(usize::MAX).min(1000);
        let answer = match &mut self.solver {
            Ok(solver) => solver.solve(DVec3::from_array(target), steps),
            Err(e) => Err(e.clone()),
        };
        wire::encode_dragged(answer)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wire::{FromWorker, ToWorker, decode_from_worker, decode_to_worker};
    use cnets_engine::optimize::drag::default_free;

    fn torus() -> DragProblem {
        crate::bundle::provide_all();
        let registry = Arc::new(cnets_nodes::registry());
        let text = crate::bundle::example("torus-monge").expect("bundled");
        let graph = cnets_engine::file::load_str_with(
            text,
            "torus-monge",
            &registry,
            &LoadOptions::default(),
        )
        .unwrap()
        .graph;
        let free = default_free(&graph, "varying_ratios").unwrap();
        DragProblem {
            graph,
            node: "varying_ratios".into(),
            vertex: (6, 12),
            item: None,
            pins: Vec::new(),
            pinned_at: Vec::new(),
            free,
        }
    }

    /// Over the wire (the problem's message, the worker's solve, the answer's message) a drag
    /// answers as the desktop's solver does in-process, to the last bit.
    #[test]
    fn a_drag_over_the_wire_answers_as_the_thread_does() {
        let mut problem = torus();
        // Where a vertex is: a solve of no steps reports it.
        let at = |vertex| {
            let mut p = problem.clone();
            p.vertex = vertex;
            let mut probe = DragSolver::new(p, NodeContext::default());
            probe.solve(DVec3::ZERO, 0).unwrap().reached
        };
        let start = at((6, 12));
        problem.pinned_at = vec![at((0, 0))];
        problem.pins = vec![(0, 0)];
        let target = start + DVec3::new(0.3, 0.1, 0.0);
        let mut local = DragSolver::new(problem.clone(), NodeContext::default());
        let expected = local.solve(target, 8).unwrap();

        let job = DragJob::of(&problem, None);
        let sent = wire::encode_to_worker(&ToWorker::DragStart(Box::new(job.clone())));
        let Ok(ToWorker::DragStart(received)) = decode_to_worker(&sent) else {
            panic!("a drag start");
        };
        assert_eq!(*received, job);
        let mut service = DragService::new(Arc::new(cnets_nodes::registry()));
        service.start(&received);
        let message = service.aim(target.to_array(), 8);
        let Ok(FromWorker::Dragged(Ok(answer))) = decode_from_worker(&message) else {
            panic!("an answer");
        };
        assert!(answer.distance_left < expected.distance_left + 1e-12);
        assert_eq!(answer.values, expected.values);
        assert_eq!(answer.reached, expected.reached);
        assert!(!answer.values.is_empty(), "the drag moved nothing");
    }

    #[test]
    fn a_drag_whose_graph_does_not_load_answers_why() {
        let mut service = DragService::new(Arc::new(cnets_nodes::registry()));
        let mut job = DragJob::of(&torus(), None);
        job.ron = "(nodes: {".into();
        service.start(&job);
        let Ok(FromWorker::Dragged(Err(e))) = decode_from_worker(&service.aim([0.0; 3], 8)) else {
            panic!("an error");
        };
        assert!(!e.is_empty());
        // A path that does not parse is refused too.
        let mut job = DragJob::of(&torus(), None);
        job.free[0].0 = "no path".into();
        service.start(&job);
        let Ok(FromWorker::Dragged(Err(_))) = decode_from_worker(&service.aim([0.0; 3], 8)) else {
            panic!("an error");
        };
    }
}
