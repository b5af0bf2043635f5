//! Whether a planned node is up to date, must run, or only fill in outputs it skipped: its edit
//! stamp, the files it read, and when its sources' outputs last changed against when it was last
//! verified (salsa's `maybe_changed_after`).

use petgraph::stable_graph::NodeIndex;

use super::{Evaluator, OutputMask};
use crate::graph::{Graph, NodeInstance};

/// What a planned node needs.
pub(super) enum Action {
    /// Its memo is valid and holds every requested output.
    UpToDate,
    /// Its inputs did not change, but it lacks these requested outputs.
    Fill(OutputMask),
    /// Its inputs changed (or it never ran): run it for these outputs.
    Run(OutputMask),
}

impl Evaluator {
    /// Whether a planned node must run, fill in outputs, or is up to date.
    pub(super) fn action(
        &self,
        graph: &Graph,
        node: NodeIndex,
        instance: &NodeInstance,
        demand: OutputMask,
    ) -> Action {
        let Some(memo) = &self.memos[node.index()] else {
            return Action::Run(demand);
        };
        if memo.uid != instance.uid() || memo.stale || instance.edited_at() > memo.verified_at.0 {
            return Action::Run(demand);
        }
        let sources_changed = graph.inputs_of(node).any(|(s, output)| {
            self.memos[s.index()]
                .as_ref()
                .is_none_or(|m| m.changed_of(output) > memo.verified_at)
        });
        if sources_changed {
            return Action::Run(demand);
        }
        let have = memo.have();
        if have.covers(demand) {
            Action::UpToDate
        } else {
            Action::Fill(demand.minus(have))
        }
    }
}
