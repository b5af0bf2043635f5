//! Parallel folds over rows whose floating-point result does not depend on scheduling.
//!
//! rayon's `fold` + `reduce` splits work where threads happen to steal it, so a sum of floats
//! comes out in a different order, and may round differently, from one run to the next. Here the
//! rows are cut into fixed blocks (independent of the thread count), each block is folded in row
//! order on some thread, and the blocks' results are merged in block order.

use rayon::prelude::*;

/// Rows folded together on one thread.
const ROWS_PER_BLOCK: usize = 16;

/// Folds `add(acc, i)` over rows `0..rows` starting from `empty()` for each block of
/// [`ROWS_PER_BLOCK`] rows, then merges the blocks left to right with `merge`. The same inputs
/// give the same bits on any number of threads.
pub(crate) fn fold_rows<A: Send>(
    rows: usize,
    empty: impl Fn() -> A + Sync,
    add: impl Fn(&mut A, usize) + Sync,
    merge: impl Fn(&mut A, A),
) -> A {
    let blocks: Vec<A> = (0..rows.div_ceil(ROWS_PER_BLOCK))
        .into_par_iter()
        .map(|b| {
            let mut acc = empty();
            for i in b * ROWS_PER_BLOCK..rows.min((b + 1) * ROWS_PER_BLOCK) {
                add(&mut acc, i);
            }
            acc
        })
        .collect();
    let mut blocks = blocks.into_iter();
    let mut total = blocks.next().unwrap_or_else(&empty);
    for block in blocks {
        merge(&mut total, block);
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Terms whose sum depends on the order of addition.
    fn terms(n: usize) -> Vec<f64> {
        (0..n)
            .map(|k| if k % 3 == 0 { 1e16 } else { 1.0 + k as f64 * 1e-3 } * if k % 2 == 0 { 1.0 } else { -1.0 })
            .collect()
    }

    fn sum(terms: &[f64]) -> f64 {
        fold_rows(terms.len(), || 0.0, |s, i| *s += terms[i], |s, t| *s += t)
    }

    #[test]
    fn the_sum_is_the_blockwise_left_to_right_sum_on_any_pool() {
        for n in [0, 1, 15, 16, 17, 1000] {
            let t = terms(n);
            let expected = t
                .chunks(ROWS_PER_BLOCK)
                .map(|c| c.iter().fold(0.0, |s, x| s + x))
                .fold(None, |acc: Option<f64>, b| Some(acc.map_or(b, |a| a + b)))
                .unwrap_or(0.0);
            for threads in [1, 2, 3, 8] {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                for _ in 0..20 {
                    let s = pool.install(|| sum(&t));
                    assert_eq!(
                        s.to_bits(),
                        expected.to_bits(),
                        "n = {n}, {threads} threads"
                    );
                }
            }
        }
    }
}
