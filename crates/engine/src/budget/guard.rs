//! Counting a reader's or a writer's memory as it grows, where its work is split.

use super::{BudgetError, MemoryBudget, allocated};

/// What a piece of work (reading a file, expanding a curve) has allocated so far, checked against
/// the memory budget at every step ([`Guard::grow`]). Where the process's allocations are counted
/// ([`allocated`]) the step is checked against them (everything: the file's bytes, the parser's
/// tables, the values made); elsewhere against the bytes the work declared so far beside the values
/// already held.
#[derive(Debug, Clone)]
pub struct Guard {
    limit: u64,
    held: u64,
    grown: u64,
    what: String,
}

impl Guard {
    /// A guard for `what` under `budget`, beside `held` bytes of live values.
    pub fn new(budget: MemoryBudget, held: u64, what: impl Into<String>) -> Self {
        Self {
            limit: budget.limit,
            held,
            grown: 0,
            what: what.into(),
        }
    }

    /// A guard that never refuses (for parsers called outside an evaluation).
    pub fn unlimited() -> Self {
        Self::new(MemoryBudget::new(u64::MAX), 0, "")
    }

    /// Declares that `bytes` more are about to be allocated; refuses when they do not fit.
    pub fn grow(&mut self, bytes: u64) -> Result<(), BudgetError> {
        self.grown = self.grown.saturating_add(bytes);
        let (needed, live) = match allocated() {
            Some(now) => (bytes, now),
            None => (self.grown, self.held),
        };
        if needed.saturating_add(live) <= self.limit {
            return Ok(());
        }
        Err(BudgetError::TooLarge {
            what: self.what.clone(),
            needed: self.grown,
            in_use: live,
            limit: self.limit,
        })
    }

    /// [`Guard::grow`] for `count` items of `item_bytes` each.
    pub fn grow_items(&mut self, count: u64, item_bytes: usize) -> Result<(), BudgetError> {
        self.grow(super::bytes_of(u128::from(count), item_bytes))
    }

    /// The bytes declared so far.
    pub fn grown(&self) -> u64 {
        self.grown
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_guard_refuses_the_step_that_passes_the_budget() {
        let mut g = Guard::new(MemoryBudget::new(1000), 200, "reading 'x.obj'");
        assert!(g.grow(500).is_ok());
        let e = g.grow(301).unwrap_err().to_string();
        assert!(
            e.starts_with("reading 'x.obj' needs 801 bytes, the limit is 1 kB"),
            "{e}"
        );
        assert!(Guard::unlimited().grow_items(u64::MAX, 64).is_ok());
    }
}
