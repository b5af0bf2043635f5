//! Planning a request: the out-of-date nodes it needs, sources before targets, and the outputs
//! asked of each (lazy outputs).

use petgraph::stable_graph::NodeIndex;

use super::{Evaluator, OutputMask, Tick};
use crate::graph::Graph;

impl Evaluator {
    /// Fills `self.order` with the out-of-date part of the request, sources before targets, and
    /// `self.demand` with the outputs asked of each planned node: the request's, and those wired
    /// into a node that is expanded (may run). A node already verified at `revision` and holding
    /// its demand is not expanded — unless a later consumer asks it for an output it lacks.
    pub(super) fn plan(
        &mut self,
        graph: &Graph,
        request: &[NodeIndex],
        masks: Option<&[OutputMask]>,
        revision: Tick,
    ) {
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.marks.iter_mut().for_each(|m| *m = 0);
            self.demand_stamp.iter_mut().for_each(|m| *m = 0);
            self.stamp = 1;
        }
        self.order.clear();
        self.stack.clear();
        for (k, &node) in request.iter().enumerate().rev() {
            self.add_demand(node, masks.map_or(OutputMask::ALL, |m| m[k]));
            self.stack.push((node, false));
        }
        while let Some((node, expanded)) = self.stack.pop() {
            if expanded {
                self.order.push(node);
                continue;
            }
            let k = node.index();
            if k >= self.marks.len() || graph.node_at(node).is_none() {
                continue;
            }
            if self.marks[k] == self.stamp {
                // Planned already: expanded (its demand is read when it runs), or up to date and
                // still holding everything asked of it.
                if !self.satisfied[k] || self.covered(k) {
                    continue;
                }
            } else {
                self.marks[k] = self.stamp;
                if self.memos[k]
                    .as_ref()
                    .is_some_and(|m| m.verified_at == revision)
                    && self.covered(k)
                {
                    self.satisfied[k] = true;
                    continue;
                }
            }
            self.satisfied[k] = false;
            self.stack.push((node, true));
            for (source, output) in graph.inputs_of(node) {
                self.add_demand(source, OutputMask::one(output));
                let s = source.index();
                if s < self.marks.len() && (self.marks[s] != self.stamp || self.satisfied[s]) {
                    self.stack.push((source, false));
                }
            }
        }
    }

    /// Adds outputs to what the current plan asks of `node`.
    fn add_demand(&mut self, node: NodeIndex, mask: OutputMask) {
        let k = node.index();
        if k >= self.demand.len() {
            return;
        }
        if self.demand_stamp[k] != self.stamp {
            self.demand_stamp[k] = self.stamp;
            self.demand[k] = OutputMask::NONE;
        }
        self.demand[k] = self.demand[k].union(mask);
    }

    /// The outputs the current plan asks of the node at index `k`.
    pub(super) fn demand_at(&self, k: usize) -> OutputMask {
        if self.demand_stamp.get(k) == Some(&self.stamp) {
            self.demand[k]
        } else {
            OutputMask::NONE
        }
    }

    /// True when the node's memo holds every output the current plan asks of it.
    fn covered(&self, k: usize) -> bool {
        self.memos[k]
            .as_ref()
            .is_some_and(|m| m.have().covers(self.demand_at(k)))
    }
}
