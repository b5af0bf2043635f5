//! Files read by nodes (through [`crate::NodeContext::read_file`]): a file changed on disk marks
//! its reader's memo stale, so it and its dependents re-run at the next evaluation.

use super::{Evaluator, FileStamp};
use crate::graph::Graph;

impl Evaluator {
    /// Marks the memos whose read files changed; true when there was one.
    pub(super) fn mark_changed_files(&mut self) -> bool {
        let mut any = false;
        for memo in self.memos.iter_mut().flatten() {
            if !memo.stale && memo.reads.iter().any(FileStamp::changed) {
                memo.stale = true;
                any = true;
            }
        }
        any
    }

    /// Every file read by the memoized nodes.
    pub fn all_reads(&self) -> Vec<FileStamp> {
        self.memos
            .iter()
            .flatten()
            .flat_map(|m| m.reads.iter().cloned())
            .collect()
    }

    /// The files the node read on its last run.
    pub fn reads(&self, graph: &Graph, id: &str) -> &[FileStamp] {
        self.memo(graph, id).map_or(&[], |m| m.reads.as_slice())
    }
}
