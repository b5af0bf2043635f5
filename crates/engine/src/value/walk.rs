//! Walking the items of a list, or a plain table of points or numbers: on several threads when
//! it is large (a 1000 × 1000 table holds a million values), on the calling thread otherwise.

use glam::DVec3;
use rayon::prelude::*;

use super::Value;

/// Values below which a walk stays on the calling thread (splitting costs more than it saves).
const PARALLEL_MIN_VALUES: usize = 1 << 16;

/// Items a parallel walk hands to one task at least.
const CHUNK_MIN_VALUES: usize = 1 << 12;

/// True when `pred` holds for every item of `items`; in parallel for a list of at least
/// [`PARALLEL_MIN_VALUES`] values, counting the items of nested lists by the first one's length.
pub(crate) fn all_items(items: &[Value], pred: impl Fn(&Value) -> bool + Sync) -> bool {
    let per_item = match items.first() {
        Some(Value::List(inner)) => inner.len().max(1),
        _ => 1,
    };
    if items.len().saturating_mul(per_item) < PARALLEL_MIN_VALUES {
        return items.iter().all(pred);
    }
    let chunk = CHUNK_MIN_VALUES.div_ceil(per_item);
    items.par_chunks(chunk).all(|chunk| chunk.iter().all(&pred))
}

/// True when every number of `points` is finite; in parallel for at least
/// [`PARALLEL_MIN_VALUES`] points.
pub(crate) fn all_finite(points: &[DVec3]) -> bool {
    all_of(points, |p| p.is_finite())
}

/// True when every number of `numbers` is finite; in parallel for at least
/// [`PARALLEL_MIN_VALUES`] numbers.
pub(crate) fn all_finite_numbers(numbers: &[f64]) -> bool {
    all_of(numbers, |x| x.is_finite())
}

/// True when `pred` holds for every element of a plain slice; in parallel when it is large.
fn all_of<T: Sync>(items: &[T], pred: impl Fn(&T) -> bool + Sync) -> bool {
    if items.len() < PARALLEL_MIN_VALUES {
        return items.iter().all(pred);
    }
    items
        .par_chunks(CHUNK_MIN_VALUES)
        .all(|chunk| chunk.iter().all(&pred))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(rows: usize, cols: usize, bad: Option<(usize, usize)>) -> Vec<Value> {
        (0..rows)
            .map(|i| {
                Value::list(
                    (0..cols)
                        .map(|j| {
                            if bad == Some((i, j)) {
                                Value::Text("x".into())
                            } else {
                                Value::Number((i * cols + j) as f64)
                            }
                        })
                        .collect(),
                )
            })
            .collect()
    }

    fn numbers_only(v: &Value) -> bool {
        v.as_list()
            .is_some_and(|row| row.iter().all(|x| matches!(x, Value::Number(_))))
    }

    #[test]
    fn finds_the_one_failing_item_in_small_and_large_lists() {
        for (rows, cols) in [(3, 4), (300, 300), (1, 70_000)] {
            assert!(all_items(&table(rows, cols, None), numbers_only));
            for bad in [(0, 0), (rows - 1, cols - 1), (rows / 2, cols / 3)] {
                assert!(
                    !all_items(&table(rows, cols, Some(bad)), numbers_only),
                    "{rows}×{cols}, bad at {bad:?}"
                );
            }
        }
        let flat: Vec<Value> = (0..100_000).map(|k| Value::Number(k as f64)).collect();
        assert!(all_items(&flat, |v| matches!(v, Value::Number(_))));
        assert!(!all_items(&flat, |v| v.as_f64() != Some(77_777.0)));
        assert!(all_items(&[], |_| false));
    }
}
