//! Reading the evaluator: results, outputs, run counts, times, hashes and revisions of change per
//! node, and the inputs a node last ran on (for the optimizer's reverse pass).

use std::borrow::Cow;
use std::time::Duration;

use petgraph::stable_graph::NodeIndex;

use super::memo::Memo;
use super::{Evaluator, NodeResult};
use crate::graph::{Graph, Revision};
use crate::node::NodeContext;
use crate::value::Value;

impl Evaluator {
    /// The input values the node at `index` last ran on (wired values from the memoized results,
    /// merged as for a run, else the literal or default): the optimizer's reverse pass reads them.
    pub fn inputs_of(
        &self,
        graph: &Graph,
        index: NodeIndex,
        ctx: &NodeContext,
    ) -> Result<Vec<Value>, String> {
        let instance = graph.node_at(index).ok_or("no such node")?;
        self.gather_inputs(graph, index, instance, ctx)
            .map_err(|r| {
                r.error()
                    .map_or_else(|| "the node cannot run".to_string(), Cow::into_owned)
            })
    }

    /// The last result of a node.
    pub fn result(&self, graph: &Graph, id: &str) -> Option<&NodeResult> {
        let index = graph.index(id).ok()?;
        self.result_at(graph, index)
    }

    /// The last result of the node at `index` (if it is still the same node).
    pub fn result_at(&self, graph: &Graph, index: NodeIndex) -> Option<&NodeResult> {
        let uid = graph.node_at(index)?.uid();
        let memo = self.memos.get(index.index())?.as_ref()?;
        (memo.uid == uid).then_some(&memo.result)
    }

    /// The value of a named output after the last evaluation (`None` also when the node was not
    /// asked for it and skipped it).
    pub fn output(&self, graph: &Graph, id: &str, output: &str) -> Option<&Value> {
        let node = graph.node(id)?;
        let k = node.def.output_index(output)?;
        self.result(graph, id)?.outputs()?.computed(k)
    }

    /// How many times the node has run since it was added (or since this evaluator was created).
    pub fn runs(&self, graph: &Graph, id: &str) -> u64 {
        self.memo(graph, id).map_or(0, |m| m.runs)
    }

    /// Duration of the node's last run.
    pub fn time(&self, graph: &Graph, id: &str) -> Option<Duration> {
        self.memo(graph, id).map(|m| m.time)
    }

    /// Content hashes of the node's outputs after its last successful run.
    pub fn output_hashes(&self, graph: &Graph, id: &str) -> Option<&[u64]> {
        self.memo(graph, id).map(|m| m.hashes.as_slice())
    }

    /// Revision at which the node's outputs last changed.
    pub fn changed_at(&self, graph: &Graph, id: &str) -> Option<Revision> {
        self.memo(graph, id).map(|m| m.changed_at.0)
    }

    /// Total node runs over the life of this evaluator.
    pub fn total_runs(&self) -> u64 {
        self.total_runs
    }

    pub(super) fn memo(&self, graph: &Graph, id: &str) -> Option<&Memo> {
        let index = graph.index(id).ok()?;
        let uid = graph.node_at(index)?.uid();
        self.memos
            .get(index.index())?
            .as_ref()
            .filter(|m| m.uid == uid)
    }
}
