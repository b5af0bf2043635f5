//! Storing a node's new result: outputs equal to the previous ones (content hash, confirmed
//! bitwise) keep their old `changed` revision — they are backdated, so dependents do not re-run
//! (early cutoff) — and a fill-in run's outputs are merged into the memo's.

use std::sync::Arc;

use petgraph::stable_graph::NodeIndex;

use super::memo::{Memo, Stored};
use super::{Evaluator, NodeOutputs, NodeResult, Tick};
use crate::value::{Value, content_hash, footprint};

impl Evaluator {
    /// Merges a fill-in run's result into the memo's: the outputs the memo had keep their values
    /// (their consumers stay verified), the newly computed ones are added. Returns the merged
    /// result and whether it was a fill-in (not when either run failed: then the new result stands
    /// as a full run's).
    pub(super) fn fill_in(&self, node: NodeIndex, result: NodeResult) -> (NodeResult, bool) {
        let old = match self.memos[node.index()].as_ref().map(|m| &m.result) {
            Some(NodeResult::Ok(old)) => old,
            _ => return (result, false),
        };
        let NodeResult::Ok(new) = &result else {
            return (result, false);
        };
        let values: Vec<Value> = old
            .values
            .iter()
            .zip(&new.values)
            .enumerate()
            .map(|(k, (o, n))| if old.missing.contains(k) { n } else { o }.clone())
            .collect();
        let merged = NodeOutputs {
            footprint: footprint(&values),
            values,
            warnings: new.warnings.clone(),
            files: new.files.clone(),
            missing: old.missing.intersection(new.missing),
        };
        (NodeResult::Ok(Arc::new(merged)), true)
    }

    /// Stores a new result; returns true when it equals the previous one (backdated).
    pub(super) fn store(
        &mut self,
        node: NodeIndex,
        uid: u64,
        revision: Tick,
        stored: Stored,
    ) -> bool {
        let Stored {
            result,
            time,
            executed,
            fill,
            owned,
            reads,
        } = stored;
        let ran = u64::from(executed);
        self.total_runs += ran;
        let hashes: Vec<u64> = match &result {
            NodeResult::Ok(outputs) => outputs.values.iter().map(content_hash).collect(),
            _ => Vec::new(),
        };
        let slot = &mut self.memos[node.index()];
        let old = slot.as_ref().filter(|old| old.uid == uid);
        let (changed, changed_at, unchanged) = match (old, &result) {
            // A fill-in: the kept outputs keep their revisions, and the new ones count as changed
            // at the run that skipped them (when the inputs they come from last changed).
            (Some(old), NodeResult::Ok(_)) if fill => (old.changed.clone(), old.changed_at, false),
            (Some(old), NodeResult::Ok(new)) => match &old.result {
                NodeResult::Ok(prev) => {
                    let mut changed = Vec::with_capacity(new.values.len());
                    let mut latest = None;
                    let mut all_same = prev.missing == new.missing;
                    for (k, value) in new.values.iter().enumerate() {
                        let same = !new.missing.contains(k)
                            && !prev.missing.contains(k)
                            && old.hashes.get(k) == hashes.get(k)
                            && prev.values.get(k).is_some_and(|p| p.same_as(value));
                        let tick = if same { old.changed_of(k) } else { revision };
                        if !new.missing.contains(k) {
                            all_same &= same;
                            latest = latest.max(Some(tick));
                        }
                        changed.push(tick);
                    }
                    let latest = latest.unwrap_or(if all_same { old.changed_at } else { revision });
                    (changed, latest, all_same)
                }
                _ => (vec![revision; new.values.len()], revision, false),
            },
            (Some(old), _) if old.result.same_as(&result) => {
                (old.changed.clone(), old.changed_at, true)
            }
            _ => {
                let count = result.outputs().map_or(1, |o| o.values.len());
                (vec![revision; count], revision, false)
            }
        };
        let runs = old.map_or(0, |m| m.runs) + ran;
        self.live = self
            .live
            .saturating_sub(slot.as_ref().map_or(0, |m| m.owned))
            .saturating_add(owned);
        *slot = Some(Memo {
            uid,
            verified_at: revision,
            changed_at,
            changed,
            result,
            hashes,
            time,
            runs,
            reads,
            stale: false,
            owned,
        });
        unchanged
    }
}
