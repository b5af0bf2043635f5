//! One drag of the net's solves, wherever they run (a thread of the desktop editor, the web
//! page's drag worker): the problem taken at the press ([`DragProblem`]), each solve continued
//! from the last answer ([`DragSolver`]), and what a solve reached ([`Solved`]).

use std::collections::BTreeSet;

use cnets_engine::optimize::Variable;
use cnets_engine::optimize::drag::{DragRequest, drag};
use cnets_engine::{Graph, NodeContext, Value};
use cnets_geometry::DVec3;
use web_time::Instant;

/// What one solve reached.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
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

/// One drag's problem: the graph (at the press), what is grabbed and pinned, what may move.
#[derive(Clone)]
pub struct DragProblem {
    /// The graph, its clusters isolated (`crate::optimization::isolated`).
    pub graph: Graph,
    /// The dragged net's node.
    pub node: String,
    /// The grabbed vertex (i, j).
    pub vertex: (usize, usize),
    /// Which of the node's nets (a list of them), if any.
    pub item: Option<usize>,
    /// The pinned vertices.
    pub pins: Vec<(usize, usize)>,
    /// Where each pin must stay.
    pub pinned_at: Vec<DVec3>,
    /// The inputs the drag may change.
    pub free: Vec<Variable>,
}

/// Solves a drag's targets one after the other, each from the last answer.
pub struct DragSolver {
    problem: DragProblem,
    ctx: NodeContext,
    /// Every (node, input) changed so far.
    touched: BTreeSet<(String, String)>,
}

impl DragSolver {
    /// A solver of `problem`, its nodes run with `ctx`.
    pub fn new(problem: DragProblem, ctx: NodeContext) -> Self {
        Self {
            problem,
            ctx,
            touched: BTreeSet::new(),
        }
    }

    /// Solves for `target` in at most `steps` steps, from the last answer.
    pub fn solve(&mut self, target: DVec3, steps: usize) -> Result<Solved, String> {
        let started = Instant::now();
        let p = &mut self.problem;
        let mut request = DragRequest::new(p.node.clone(), p.vertex, target);
        request.pins = p.pins.clone();
        request.item = p.item;
        request.pinned_at = Some(p.pinned_at.clone());
        request.free = Some(p.free.clone());
        request.max_iter = steps;
        let report = drag(&p.graph, &request, &self.ctx).map_err(|e| e.to_string())?;
        self.touched.extend(
            report
                .changes
                .iter()
                .map(|c| (c.input.node.clone(), c.input.port.clone())),
        );
        p.graph = report.graph;
        let values = self
            .touched
            .iter()
            .filter_map(|(node, input)| {
                let n = p.graph.node(node)?;
                let value = n.value(n.def.input_index(input)?)?.clone();
                Some((node.clone(), input.clone(), value))
            })
            .collect();
        let not_convex = report
            .not_convex
            .iter()
            .filter(|(n, _)| *n == p.node)
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

/// A drag's solver outside this thread that is not a Rust thread (the web page's drag worker).
/// One request is solved at a time; the newest target waits for the answer to the one before,
/// replacing any older one waiting.
pub trait RemoteDrag {
    /// Starts solving `problem` (its nodes read files from `base_dir`), forgetting any other.
    fn start(&mut self, problem: &DragProblem, base_dir: Option<&std::path::Path>);

    /// Asks for the vertex at `target` in at most `steps` steps, from the last answer.
    fn aim(&mut self, target: DVec3, steps: usize);

    /// The answers that arrived since the last call, oldest first.
    fn receive(&mut self) -> Vec<Result<Solved, String>>;

    /// Nothing is being solved or waiting to be.
    fn idle(&self) -> bool;

    /// Another handle on the same service.
    fn handle(&self) -> Box<dyn RemoteDrag>;
}
