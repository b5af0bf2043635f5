//! Incremental, pull-based evaluation with early cutoff.
//!
//! The model is salsa's: every node has a memo with the revision it was last *verified* at and the
//! revision its outputs last *changed* at. Evaluating a request walks only the requested nodes and
//! what they depend on, skipping nodes already verified at the current revision. A node re-runs only
//! when it was edited or one of its sources changed after it was verified. When a re-run produces
//! outputs equal to the previous ones (same content hash, confirmed bitwise), its `changed_at` is
//! kept — it is *backdated* — so its dependents do not re-run (early cutoff).
//!
//! Outputs are lazy: each node is asked only for the outputs the request needs (those wired to a
//! node that runs, and those the caller requests: [`demand`]). A node may skip the others; its memo
//! records which outputs it computed and when each one last changed. A node whose inputs did not
//! change but which is now asked for an output it skipped runs again to *fill in* that output: the
//! outputs it had keep their values and revisions, so their consumers stay verified.
//!
//! One phase a file, as salsa's `function/` module: the memo of a node and the side tables
//! (`memo`), a request's walk (`evaluate`), planning what it needs (`plan`), deciding whether a
//! planned node is up to date (`verify`), files read by nodes (`reads`), storing a result with
//! backdating and fill-ins (`backdate`), gathering a node's inputs (`inputs`), the memory budget
//! after a run (`budget`), running one node with the NaN policy (`execute`), moving memos to a
//! replacing graph (`carry_over`) and reading results (`query`).

mod backdate;
mod budget;
mod carry_over;
mod evaluate;
mod execute;
mod inputs;
mod mapping;
mod memo;
mod not_run;
mod panic_guard;
mod plan;
mod query;
mod reads;
mod result;
mod verify;

/// What a node saw of a file it read (the node contract's own type, moved down to `node`).
pub use crate::node::FileStamp;
/// Which outputs are requested (the node contract's own type, moved down to `node`).
pub use crate::node::OutputMask;
pub use execute::{evaluate_node, evaluate_node_outputs};
pub use mapping::run_mapped;
pub use not_run::{Blocked, InvalidInput};
pub use result::{NodeOutputs, NodeResult};

use petgraph::stable_graph::NodeIndex;

use crate::graph::Revision;
use memo::Memo;

/// The evaluator's clock: the graph's revision, then a count of the times files read by nodes
/// changed while the graph stood still (ordered lexicographically).
type Tick = (Revision, u64);

/// What one call to [`Evaluator::evaluate`] did.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct EvalSummary {
    /// Nodes looked at (requested plus their out-of-date dependencies).
    pub visited: usize,
    /// Nodes that actually ran.
    pub ran: usize,
    /// Re-runs whose outputs were unchanged (early cutoff stopped propagation there).
    pub cut_off: usize,
    /// Runs that only filled in outputs asked for after the node had skipped them (counted in
    /// `ran` too).
    pub filled: usize,
    /// The evaluation stopped early because cancellation was requested.
    pub cancelled: bool,
}

/// Memoized evaluation state for one graph. Keep one evaluator per graph and call
/// [`Evaluator::evaluate`] after edits; only what changed re-runs.
#[derive(Debug, Default)]
pub struct Evaluator {
    memos: Vec<Option<Memo>>,
    stack: Vec<(NodeIndex, bool)>,
    order: Vec<NodeIndex>,
    marks: Vec<u32>,
    stamp: u32,
    /// The outputs requested of each node in the current plan (valid where `demand_stamp` is the
    /// current stamp).
    demand: Vec<OutputMask>,
    demand_stamp: Vec<u32>,
    /// The node was planned as up to date (not expanded): more demand may expand it.
    satisfied: Vec<bool>,
    total_runs: u64,
    swept_at: Revision,
    file_epoch: u64,
    /// Bytes held by all memoized results (the sum of their `owned`).
    live: u64,
}

impl Evaluator {
    /// A fresh evaluator with nothing memoized.
    pub fn new() -> Self {
        Self::default()
    }
}
