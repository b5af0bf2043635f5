//! Moving the memos to a graph that replaces the evaluated one (another document opened in its
//! place): continued nodes keep their results.

use super::{Evaluator, OutputMask};
use crate::graph::{Continued, Graph, NodeInstance};

impl Evaluator {
    /// Moves the memos over to `next`, a graph replacing the one this evaluator last evaluated
    /// (another document opened in its place), given the nodes that continue one another
    /// ([`Graph::take_over`]; `next` may have been edited since): each continued node still in
    /// `next` keeps its result, run count and stamps; every other memo is dropped. When
    /// `same_folder` is false (relative paths of `next` resolve in another folder) the memos of
    /// nodes that read files are dropped too, since the same path may name another file.
    pub fn carry_over(&mut self, next: &Graph, carried: &[Continued], same_folder: bool) {
        let mut old = std::mem::take(&mut self.memos);
        let bound = next.index_bound();
        self.memos = Vec::new();
        self.memos.resize_with(bound, || None);
        self.marks = vec![0; bound];
        // Every side table follows the new graph's bound (prepare only grows them with the memos).
        self.demand = vec![OutputMask::NONE; bound];
        self.demand_stamp = vec![0; bound];
        self.satisfied = vec![false; bound];
        self.stamp = 0;
        self.live = 0;
        for c in carried {
            let Some(slot) = old.get_mut(c.previous.index()) else {
                continue;
            };
            if next.node_at(c.next).map(NodeInstance::uid) != Some(c.uid) {
                continue;
            }
            let Some(mut memo) = slot.take() else {
                continue;
            };
            if !same_folder && !memo.reads.is_empty() {
                continue;
            }
            memo.uid = c.uid;
            self.live = self.live.saturating_add(memo.owned);
            self.memos[c.next.index()] = Some(memo);
        }
        self.swept_at = 0;
    }
}
