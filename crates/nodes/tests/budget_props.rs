//! Property tests over sizes and depths: under any memory budget, the nodes that can blow up either
//! fit and succeed, or fail before allocating with the size they need — never abort, never take
//! long, whatever the sizes or the nesting.

use std::time::{Duration, Instant};

use cnets_engine::eval::evaluate_node;
use cnets_engine::{MemoryBudget, NodeContext, Value};
use proptest::prelude::*;

const SLOT: u128 = std::mem::size_of::<Value>() as u128;

fn run(id: &str, ctx: &NodeContext, inputs: &[(&str, Value)]) -> Result<Vec<Value>, String> {
    let registry = cnets_nodes::registry();
    let def = registry.get(id).unwrap();
    let mut values: Vec<Value> = def
        .inputs
        .iter()
        .map(|p| p.default.clone().unwrap_or_default())
        .collect();
    for (name, v) in inputs {
        values[def.input_index(name).unwrap()] = v.clone();
    }
    evaluate_node(def, ctx, &values)
        .map(|o| o.values)
        .map_err(|e| e.to_string())
}

fn numbers(n: usize) -> Value {
    Value::list((0..n).map(|k| Value::Number(k as f64 * 0.25)).collect())
}

/// Whether `slots` list slots (plus the list itself, which a full read visits) fit under `limit`:
/// `Some(true)` must fit, `Some(false)` must fail, `None` at the boundary may go either way.
fn fits(slots: u128, limit: u64) -> Option<bool> {
    if (slots + 1) * SLOT <= limit as u128 {
        Some(true)
    } else if slots * SLOT > limit as u128 {
        Some(false)
    } else {
        None
    }
}

fn over_budget(message: &str) -> bool {
    message.contains(" needs ") && message.contains("the limit is")
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// `list.table`: rows × columns against the budget.
    #[test]
    fn tables_fit_or_fail_with_their_size(n in 0usize..3000, m in 0usize..3000, limit in 10_000u64..50_000_000) {
        let ctx = NodeContext::default().with_budget(MemoryBudget::new(limit));
        let fits = fits((n as u128) * (m as u128 + 1), limit);
        match run("list.table", &ctx, &[("rows", numbers(n)), ("columns", numbers(m))]) {
            Ok(out) => {
                prop_assert!(fits != Some(false), "{n} × {m} under {limit} should have failed");
                prop_assert_eq!(out[0].as_list().map(<[Value]>::len), Some(n));
            }
            Err(e) => prop_assert!(fits != Some(true) && over_budget(&e), "{n} × {m} under {limit}: {e}"),
        }
    }

    /// `list.flatten` of a list shared twice over at every level: the items are counted each
    /// shared list once, before anything is allocated. (Deeper ladders than this cannot reach a
    /// node in a graph: the evaluator refuses a result that reads as more values than the budget.)
    #[test]
    fn flattening_shared_ladders_fits_or_fails_quickly(depth in 0u32..20, width in 1usize..8, limit in 10_000u64..50_000_000) {
        let mut v = numbers(width);
        for _ in 0..depth {
            v = Value::list(vec![v.clone(), v]);
        }
        let leaves = (width as u128) << depth;
        let ctx = NodeContext::default().with_budget(MemoryBudget::new(limit));
        let start = Instant::now();
        match run("list.flatten", &ctx, &[("tree", v)]) {
            Ok(out) => {
                prop_assert!(fits(leaves, limit) != Some(false));
                prop_assert_eq!(out[0].as_list().map(|l| l.len() as u128), Some(leaves));
            }
            Err(e) => prop_assert!(fits(leaves, limit) != Some(true) && over_budget(&e), "{e}"),
        }
        // A hang guard (issue 30): the 48 cases together take 0.45–0.84 s under load.
        prop_assert!(start.elapsed() < Duration::from_secs(10));
    }

    /// `list.repeat` and `param.series` counts against the budget.
    #[test]
    fn counts_fit_or_fail_with_their_size(count in 0i64..2_000_000, limit in 10_000u64..80_000_000) {
        let ctx = NodeContext::default().with_budget(MemoryBudget::new(limit));
        let fits = fits(count as u128, limit);
        for (id, inputs) in [
            ("list.repeat", vec![("value", Value::Number(1.5)), ("count", Value::Integer(count))]),
            ("param.series", vec![("count", Value::Integer(count))]),
        ] {
            match run(id, &ctx, &inputs) {
                Ok(out) => {
                    prop_assert!(fits != Some(false), "{id} {count} under {limit}");
                    prop_assert_eq!(out[0].as_list().map(|l| l.len() as i64), Some(count));
                }
                Err(e) => prop_assert!(fits != Some(true) && over_budget(&e), "{id} {count} under {limit}: {e}"),
            }
        }
    }
}
