//! The memo of one node instance (its result, when it was verified and when each output last
//! changed, the files it read, the bytes it holds), what a run hands over to be stored, and the
//! side tables that follow the graph's index bound.

use std::time::Duration;

use petgraph::stable_graph::NodeIndex;

use super::{Evaluator, FileStamp, NodeResult, OutputMask, Tick};
use crate::graph::{Graph, NodeInstance, Revision};

/// The memo of one node instance.
#[derive(Debug, Clone)]
pub(super) struct Memo {
    pub(super) uid: u64,
    pub(super) verified_at: Tick,
    /// The latest of the computed outputs' `changed` (the node's revision of change).
    pub(super) changed_at: Tick,
    /// Per output: when its value last changed (an output not computed counts as changed at the
    /// run that did not compute it).
    pub(super) changed: Vec<Tick>,
    pub(super) result: NodeResult,
    pub(super) hashes: Vec<u64>,
    pub(super) time: Duration,
    pub(super) runs: u64,
    /// Files the node read on its last run.
    pub(super) reads: Vec<FileStamp>,
    /// One of those files changed since: the node must re-run.
    pub(super) stale: bool,
    /// Bytes the result holds that no other result holds (its share of the live memory).
    pub(super) owned: u64,
}

impl Memo {
    /// When output `k` last changed.
    pub(super) fn changed_of(&self, k: usize) -> Tick {
        self.changed
            .get(k)
            .or(self.changed.last())
            .copied()
            .unwrap_or(self.changed_at)
    }

    /// The outputs this memo holds values for (an error covers every output).
    pub(super) fn have(&self) -> OutputMask {
        match &self.result {
            NodeResult::Ok(outputs) => OutputMask::ALL.minus(outputs.missing),
            _ => OutputMask::ALL,
        }
    }
}

/// A node's new result, what it cost, and the files it read.
pub(super) struct Stored {
    pub(super) result: NodeResult,
    pub(super) time: Duration,
    pub(super) executed: bool,
    /// A fill-in run (see [`Evaluator::fill_in`]).
    pub(super) fill: bool,
    pub(super) owned: u64,
    pub(super) reads: Vec<FileStamp>,
}

impl Evaluator {
    /// Grows side tables to the graph's index bound and drops memos of removed nodes.
    pub(super) fn prepare(&mut self, graph: &Graph, revision: Revision) {
        let bound = graph.index_bound();
        if self.memos.len() < bound {
            self.memos.resize_with(bound, || None);
            self.marks.resize(bound, 0);
            self.demand.resize(bound, OutputMask::NONE);
            self.demand_stamp.resize(bound, 0);
            self.satisfied.resize(bound, false);
        }
        if self.swept_at != revision {
            self.swept_at = revision;
            for (k, memo) in self.memos.iter_mut().enumerate() {
                let alive = graph.node_at(NodeIndex::new(k)).map(NodeInstance::uid);
                if let Some(m) = memo.as_ref().filter(|m| Some(m.uid) != alive) {
                    self.live = self.live.saturating_sub(m.owned);
                    *memo = None;
                }
            }
        }
    }

    /// Bytes held by the memoized results (each shared payload counted once, by the result that
    /// made it).
    pub fn live_bytes(&self) -> u64 {
        self.live
    }
}
