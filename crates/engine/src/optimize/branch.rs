//! Branches of piecewise-smooth nodes. A node whose output has kinks (the assisted correction,
//! the ratio → angle map at ½, a min or a clamp) may tell which smooth piece a run was on
//! ([`NodeDef::branch`](crate::NodeDef::branch)); the reverse pass differentiates the piece taken,
//! and the optimizer compares the pieces of consecutive gradients, so a step that crosses a kink
//! is reported ("node 'construct' crossed a branch …") instead of passing silently.

use std::collections::HashMap;

pub use crate::node::derivative::{Branch, BranchFn};

/// Most crossings reported one by one; the rest are counted.
pub const MAX_REPORTED: u64 = 10;

/// The pieces seen at the last gradient, per node, and the crossings since the start.
#[derive(Debug, Default)]
pub struct BranchWatch {
    last: HashMap<String, Branch>,
    /// Steps on which some node changed its piece.
    pub crossings: u64,
}

impl BranchWatch {
    /// Records the pieces of gradient number `gradient`; returns a report line for each node that
    /// changed its piece since the previous gradient (at most [`MAX_REPORTED`] over a run).
    pub fn observe(&mut self, gradient: u64, branches: Vec<(String, Branch)>) -> Vec<String> {
        let mut reports = Vec::new();
        for (node, branch) in branches {
            let crossed = self
                .last
                .get(&node)
                .filter(|old| old.key != branch.key)
                .map(|old| old.summary.clone());
            if let Some(old) = crossed {
                self.crossings += 1;
                if self.crossings <= MAX_REPORTED {
                    reports.push(format!(
                        "gradient {gradient}: node '{node}' crossed a branch ({old} → {}); \
                         its exact derivative is the one of the new piece",
                        branch.summary
                    ));
                } else if self.crossings == MAX_REPORTED + 1 {
                    reports.push(format!(
                        "more than {MAX_REPORTED} branch crossings: see the count in the summary"
                    ));
                }
            }
            self.last.insert(node, branch);
        }
        reports
    }
}

/// A key from a sequence of small codes (FNV-1a), for branch functions.
pub fn key_of(codes: impl IntoIterator<Item = u64>) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for c in codes {
        h ^= c;
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    fn piece(key: u64) -> Branch {
        Branch {
            key,
            summary: format!("piece {key}"),
        }
    }

    #[test]
    fn a_changed_piece_is_reported_once_per_step() {
        let mut w = BranchWatch::default();
        assert!(w.observe(1, vec![("a".into(), piece(1))]).is_empty());
        assert!(w.observe(2, vec![("a".into(), piece(1))]).is_empty());
        let r = w.observe(3, vec![("a".into(), piece(2)), ("b".into(), piece(5))]);
        assert_eq!(r.len(), 1, "{r:?}");
        assert!(r[0].contains("gradient 3: node 'a' crossed a branch (piece 1 → piece 2)"));
        assert_eq!(w.crossings, 1);
    }

    #[test]
    fn reports_stop_after_the_limit_but_the_count_goes_on() {
        let mut w = BranchWatch::default();
        let mut lines = 0;
        for k in 0..40 {
            lines += w.observe(k, vec![("a".into(), piece(k % 2))]).len();
        }
        assert_eq!(w.crossings, 39);
        assert_eq!(lines as u64, MAX_REPORTED + 1);
    }

    #[test]
    fn keys_tell_sequences_apart() {
        assert_eq!(key_of([1, 2, 3]), key_of([1, 2, 3]));
        assert_ne!(key_of([1, 2, 3]), key_of([1, 3, 2]));
        assert_ne!(key_of([]), key_of([0]));
    }
}
