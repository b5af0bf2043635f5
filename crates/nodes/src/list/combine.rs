//! Combining and splitting lists: `list.cross_reference`, `list.partition`.

use cnets_engine::prelude::*;

/// Most pairs one cross reference makes.
pub const MAX_PAIRS: usize = 10_000_000;

node! {
    /// Every pair of an item of `a` with an item of `b`, `a` varying slowest (Grasshopper's Cross
    /// Reference, holistic): [1,2] × [10,20,30] → a = [1,1,1,2,2,2], b = [10,20,30,10,20,30].
    #[node(id = "list.cross_reference", category = "Lists")]
    pub fn cross_reference(
        /// First list (varies slowest).
        a: k::List<k::Any>,
        /// Second list (varies fastest).
        b: k::List<k::Any>,
    ) -> (
        /// The item of `a` of each pair.
        a: k::List<k::Any>,
        /// The item of `b` of each pair.
        b: k::List<k::Any>,
    ) {
        let pairs = a.len().checked_mul(b.len()).filter(|&n| n <= MAX_PAIRS).ok_or_else(|| {
            NodeError::new(format!(
                "{} × {} = {} pairs is more than {MAX_PAIRS}",
                a.len(),
                b.len(),
                a.len() as u128 * b.len() as u128
            ))
        })?;
        let mut first = Vec::with_capacity(pairs);
        let mut second = Vec::with_capacity(pairs);
        for x in &a {
            for y in &b {
                first.push(x.clone());
                second.push(y.clone());
            }
        }
        Ok((first, second))
    }
}

node! {
    /// Cuts a list into consecutive chunks of `size` items (the last one may be shorter), a table:
    /// Grasshopper's Partition List. A flat list of rows × columns values becomes `rows` lists of
    /// `columns` (e.g. ratios computed over a cross reference, for `cnets.construct`).
    #[node(id = "list.partition", category = "Lists")]
    pub fn partition(
        /// The list.
        list: k::List<k::Any>,
        /// Items per chunk (≥ 1).
        size: k::Integer = 2,
    ) -> (
        /// The chunks, in order.
        chunks: k::Tree<k::Any>,
    ) {
        let size = usize::try_from(size)
            .ok()
            .filter(|&s| s >= 1)
            .ok_or_else(|| NodeError::new(format!("size must be 1 or more, got {size}")))?;
        let chunks = list.chunks(size).map(|c| Value::list(c.to_vec())).collect();
        Ok((Value::list(chunks),))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{nums, run_named};

    #[test]
    fn every_pair_with_a_slowest() {
        let out = run_named(
            &cross_reference(),
            &[("a", nums(&[1.0, 2.0])), ("b", nums(&[10.0, 20.0, 30.0]))],
        )
        .unwrap();
        assert_eq!(out[0], nums(&[1.0, 1.0, 1.0, 2.0, 2.0, 2.0]));
        assert_eq!(out[1], nums(&[10.0, 20.0, 30.0, 10.0, 20.0, 30.0]));
        let out = run_named(&cross_reference(), &[("a", nums(&[])), ("b", nums(&[1.0]))]);
        assert_eq!(out.unwrap()[0], nums(&[]));
    }

    #[test]
    fn partition_cuts_rows_and_keeps_a_short_last_one() {
        let out = run_named(
            &partition(),
            &[
                ("list", nums(&[1.0, 2.0, 3.0, 4.0, 5.0])),
                ("size", Value::Integer(2)),
            ],
        )
        .unwrap();
        let expected = Value::list(vec![nums(&[1.0, 2.0]), nums(&[3.0, 4.0]), nums(&[5.0])]);
        assert_eq!(out[0], expected);
        let e = run_named(
            &partition(),
            &[("list", nums(&[1.0])), ("size", Value::Integer(0))],
        );
        assert!(e.unwrap_err().contains("size"));
    }
}
