//! List tools: item, length, reverse, repeat, slice, flatten, graft, transpose, tables; sorting and
//! shifting ([`order`]), culling, dispatching and weaving ([`pattern`]), cross references and partitions
//! ([`combine`]).
//!
//! Nodes with a `list` input take a whole list per run; a list of lists (a table) runs them once per
//! row, as Grasshopper does per branch. `list.flatten`, `list.repeat` and `list.transpose` take any
//! nesting as it is.

pub mod combine;
pub mod order;
pub mod pattern;

use cnets_engine::prelude::*;

/// Resolves a possibly negative index (−1 = last) into `0..len`, or `None` when out of range.
fn resolve_index(index: i64, len: usize) -> Option<usize> {
    let len_i = i64::try_from(len).ok()?;
    let k = if index < 0 { index + len_i } else { index };
    (0..len_i).contains(&k).then_some(k as usize)
}

node! {
    /// The item at `index` of a list (0 = first; negative indices count from the end, −1 = last).
    /// Out of range is an error unless `wrap` is on (the index then wraps around the list). On a
    /// table, picks the item of every row; a list of indices picks several items.
    #[node(id = "list.item", category = "Lists")]
    pub fn item(
        /// The list.
        list: k::List<k::Any>,
        /// Index of the item.
        index: k::Integer = 0,
        /// Wrap out-of-range indices around the list.
        wrap: k::Boolean = false,
    ) -> (
        /// The item.
        item: k::Any,
    ) {
        if list.is_empty() {
            return Err(format!("the list is empty: there is no item {index}").into());
        }
        let k = if wrap {
            index.rem_euclid(list.len() as i64) as usize
        } else {
            resolve_index(index, list.len()).ok_or_else(|| {
                NodeError::new(format!(
                    "index {index} is out of range for a list of {} items",
                    list.len()
                ))
            })?
        };
        Ok((list[k].clone(),))
    }
}

node! {
    /// The number of items in a list (on a table: of every row).
    #[node(id = "list.length", category = "Lists")]
    pub fn length(
        /// The list.
        list: k::List<k::Any>,
    ) -> (
        /// Number of items.
        length: k::Integer,
    ) {
        Ok((list.len(),))
    }
}

node! {
    /// The list in reverse order (on a table: every row reversed).
    #[node(id = "list.reverse", category = "Lists")]
    pub fn reverse(
        /// The list.
        list: k::List<k::Any>,
    ) -> (
        /// The reversed list.
        list: k::List<k::Any>,
    ) {
        let mut list = list;
        list.reverse();
        Ok((list,))
    }
}

node! {
    /// A list of `count` copies of `value`, whatever it is: a number gives a list of numbers, a
    /// list gives a table of `count` equal rows (flatten it to concatenate the copies instead).
    /// Count 0 gives an empty list.
    #[node(id = "list.repeat", category = "Lists")]
    pub fn repeat[ctx](
        /// What to repeat (an item, a list or a table).
        value: k::Tree<k::Any>,
        /// Number of copies (≥ 0).
        count: k::Integer = 2,
    ) -> (
        /// The copies.
        list: k::List<k::Any>,
    ) {
        if count < 0 {
            return Err(format!("count must be 0 or more, got {count}").into());
        }
        if count > 10_000_000 {
            return Err(format!("count {count} is too large (at most 10000000)").into());
        }
        ctx.reserve_values(count as u128, &format!("a list of {count} copies"))?;
        Ok((vec![value; count as usize],))
    }
}

node! {
    /// The items from index `start` up to, not including, `end` (negative indices count from the
    /// end; no `end`: to the end of the list). Indices beyond the list are clamped to it, so a slice
    /// is never an error; `start` ≥ `end` gives an empty list.
    #[node(id = "list.slice", category = "Lists")]
    pub fn slice(
        /// The list.
        list: k::List<k::Any>,
        /// First index taken.
        start: k::Integer = 0,
        /// First index not taken (none: the list's length).
        end: Option<k::Integer>,
    ) -> (
        /// The slice.
        list: k::List<k::Any>,
    ) {
        let len = list.len() as i64;
        let clamp = |i: i64| -> usize {
            let i = if i < 0 { i + len } else { i };
            i.clamp(0, len) as usize
        };
        let a = clamp(start);
        let b = clamp(end.unwrap_or(len));
        let out = if a < b { list[a..b].to_vec() } else { Vec::new() };
        Ok((out,))
    }
}

/// The number of items a flatten of `v` gives, counting each shared list once (a list of the same
/// list twice, 40 times over, is counted in 40 steps, not 2⁴⁰); saturates instead of overflowing.
fn leaf_count(v: &Value, memo: &mut std::collections::HashMap<*const Value, u128>) -> u128 {
    match v {
        Value::List(items) if items.as_packed().is_some() => items.len() as u128,
        Value::List(items) => {
            let key = items.as_ptr();
            if let Some(&n) = memo.get(&key) {
                return n;
            }
            let n = items
                .iter()
                .fold(0u128, |n, i| n.saturating_add(leaf_count(i, memo)));
            memo.insert(key, n);
            n
        }
        _ => 1,
    }
}

fn flatten_into(v: &Value, out: &mut Vec<Value>) {
    match v {
        Value::List(items) => items.iter().for_each(|i| flatten_into(i, out)),
        other => out.push(other.clone()),
    }
}

node! {
    /// All items of any nesting (a table, a list of tables…) in one flat list, in reading order.
    #[node(id = "list.flatten", category = "Lists")]
    pub fn flatten[ctx](
        /// The nested list.
        tree: k::Tree<k::Any>,
    ) -> (
        /// The flat list.
        list: k::List<k::Any>,
    ) {
        let n = leaf_count(&tree, &mut Default::default());
        ctx.reserve_values(n, &format!("a flat list of {n} items"))?;
        let mut out = Vec::with_capacity(n as usize);
        flatten_into(&tree, &mut out);
        Ok((out,))
    }
}

node! {
    /// Every item in its own list: [a, b, c] becomes [[a], [b], [c]].
    #[node(id = "list.graft", category = "Lists")]
    pub fn graft(
        /// The list.
        list: k::List<k::Any>,
    ) -> (
        /// The list of one-item lists.
        tree: k::Tree<k::Any>,
    ) {
        Ok((Value::list(list.into_iter().map(|v| Value::list(vec![v])).collect()),))
    }
}

node! {
    /// Swaps rows and columns of a table: N lists of M items become M lists of N items (e.g. a
    /// ratio table per generatrix point ↔ per directrix column). A flat list counts as one row, so
    /// it becomes a column of one-item lists. Rows of different lengths are an error.
    #[node(id = "list.transpose", category = "Lists")]
    pub fn transpose[ctx](
        /// The table (a list of equally long lists).
        table: k::Tree<k::Any>,
    ) -> (
        /// The transposed table.
        table: k::Tree<k::Any>,
    ) {
        let n = leaf_count(&table, &mut Default::default());
        ctx.reserve_values(n.saturating_mul(2), &format!("transposing a table of {n} items"))?;
        let rows: Vec<Vec<Value>> = match &table {
            Value::List(items) if items.iter().all(|r| matches!(r, Value::List(_))) && !items.is_empty() => {
                items.iter().map(|r| r.as_list().unwrap_or(&[]).to_vec()).collect()
            }
            Value::List(items) if items.iter().any(|r| matches!(r, Value::List(_))) => {
                return Err("the table mixes rows (lists) and single items".into());
            }
            Value::List(items) => vec![items.to_vec()],
            single => vec![vec![single.clone()]],
        };
        let width = rows.first().map_or(0, Vec::len);
        if let Some((i, r)) = rows.iter().enumerate().find(|(_, r)| r.len() != width) {
            return Err(format!(
                "row {i} has {} items, but row 0 has {width}: a table needs rows of equal length",
                r.len()
            )
            .into());
        }
        let out = (0..width)
            .map(|j| Value::list(rows.iter().map(|r| r[j].clone()).collect()))
            .collect();
        Ok((Value::list(out),))
    }
}

node! {
    /// A table of N rows × M columns from a per-row list (N numbers, e.g. a graph mapper sampled
    /// at N generatrix points) and a per-column list (M numbers, e.g. a mapper sampled at the M − 1
    /// directrix columns of a cone-net's ratios). `rule` combines them: `sum` (row + column −
    /// centre: deviations from `centre` add, so a constant-centre row list gives exactly the column
    /// values in every row), `product` (row · column) or `mean` ((row + column) / 2).
    #[node(id = "list.table", category = "Lists")]
    pub fn table[ctx](
        /// One number per row (N).
        rows: k::List<k::Number>,
        /// One number per column (M).
        columns: k::List<k::Number>,
        /// `sum`, `product` or `mean`.
        rule: k::Choice<crate::choices::TableRule> = "sum",
        /// The neutral value of the `sum` rule (0.5: the Monge ratio).
        centre: k::Number = 0.5,
    ) -> (
        /// N lists of M numbers.
        table: k::Tree<k::Number>,
    ) {
        let combine: fn(f64, f64, f64) -> f64 = match rule {
            "sum" => |r, c, m| r + c - m,
            "product" => |r, c, _| r * c,
            "mean" => |r, c, _| 0.5 * (r + c),
            _ => return Err(format!("unknown rule '{rule}': expected sum, product or mean").into()),
        };
        if !centre.is_finite() {
            return Err(format!("centre must be finite, got {centre}").into());
        }
        for (what, list) in [("rows", &rows), ("columns", &columns)] {
            if let Some(k) = list.iter().position(|v| !v.is_finite()) {
                return Err(format!("{what} value {k} is not finite").into());
            }
        }
        let (n, m) = (rows.len(), columns.len());
        ctx.reserve_values(
            (n as u128).saturating_mul(m as u128 + 1),
            &format!("a table of {n} × {m} numbers"),
        )?;
        let mut out = Vec::with_capacity(rows.len());
        for &r in &rows {
            let row: Vec<Value> = columns
                .iter()
                .map(|&c| Value::Number(combine(r, c, centre)))
                .collect();
            if row.iter().any(|v| !v.as_f64().is_some_and(f64::is_finite)) {
                return Err("a table value overflows".into());
            }
            out.push(Value::list(row));
        }
        Ok((Value::list(out),))
    }
}

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![
        item(),
        length(),
        reverse(),
        repeat(),
        slice(),
        flatten(),
        graft(),
        transpose(),
        table(),
        order::sort(),
        order::shift(),
        pattern::cull(),
        pattern::dispatch(),
        pattern::weave(),
        combine::cross_reference(),
        combine::partition(),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(def: NodeDef, named: &[(&str, Value)]) -> Result<Vec<Value>, String> {
        crate::testing::run_named(&def, named)
    }

    fn nums(xs: &[f64]) -> Value {
        Value::list(xs.iter().map(|&x| Value::Number(x)).collect())
    }

    fn int(i: i64) -> Value {
        Value::Integer(i)
    }

    #[test]
    fn item_indices_wrap_and_errors() {
        let l = nums(&[1.0, 2.0, 3.0]);
        let get = |i: i64, wrap: bool| {
            run(
                item(),
                &[
                    ("list", l.clone()),
                    ("index", int(i)),
                    ("wrap", Value::Boolean(wrap)),
                ],
            )
        };
        assert_eq!(get(0, false).unwrap()[0], Value::Number(1.0));
        assert_eq!(get(-1, false).unwrap()[0], Value::Number(3.0));
        assert_eq!(get(4, true).unwrap()[0], Value::Number(2.0));
        assert!(get(3, false).unwrap_err().contains("out of range"));
        assert!(get(-4, false).is_err());
        assert!(
            run(item(), &[("list", nums(&[]))])
                .unwrap_err()
                .contains("empty")
        );
        // Several indices pick several items; a table picks per row.
        let out = run(
            item(),
            &[
                ("list", l.clone()),
                ("index", Value::list(vec![int(2), int(0)])),
            ],
        )
        .unwrap();
        assert_eq!(out[0], nums(&[3.0, 1.0]));
        let table = Value::list(vec![nums(&[1.0, 2.0]), nums(&[3.0, 4.0])]);
        let out = run(item(), &[("list", table), ("index", int(1))]).unwrap();
        assert_eq!(out[0], nums(&[2.0, 4.0]));
    }

    #[test]
    fn length_reverse_slice() {
        assert_eq!(
            run(length(), &[("list", nums(&[1.0, 2.0]))]).unwrap()[0],
            int(2)
        );
        assert_eq!(run(length(), &[("list", nums(&[]))]).unwrap()[0], int(0));
        let r = run(reverse(), &[("list", nums(&[1.0, 2.0, 3.0]))]).unwrap();
        assert_eq!(r[0], nums(&[3.0, 2.0, 1.0]));
        let l = nums(&[0.0, 1.0, 2.0, 3.0, 4.0]);
        let s = |a: i64, b: Option<i64>| {
            run(
                slice(),
                &[
                    ("list", l.clone()),
                    ("start", int(a)),
                    ("end", b.map_or(Value::Null, int)),
                ],
            )
            .unwrap()[0]
                .clone()
        };
        assert_eq!(s(1, Some(3)), nums(&[1.0, 2.0]));
        assert_eq!(s(-2, None), nums(&[3.0, 4.0]));
        assert_eq!(s(0, Some(-1)), nums(&[0.0, 1.0, 2.0, 3.0]));
        assert_eq!(s(3, Some(1)), nums(&[]));
        assert_eq!(s(-10, Some(10)), l);
    }

    #[test]
    fn repeat_flatten_graft() {
        let out = run(
            repeat(),
            &[("value", Value::Number(0.5)), ("count", int(3))],
        )
        .unwrap();
        assert_eq!(out[0], nums(&[0.5, 0.5, 0.5]));
        let row = nums(&[1.0, 2.0]);
        let out = run(repeat(), &[("value", row.clone()), ("count", int(2))]).unwrap();
        let table = Value::list(vec![row.clone(), row.clone()]);
        assert_eq!(out[0], table);
        assert!(run(repeat(), &[("value", row), ("count", int(-1))]).is_err());
        let flat = run(flatten(), &[("tree", table)]).unwrap();
        assert_eq!(flat[0], nums(&[1.0, 2.0, 1.0, 2.0]));
        let g = run(graft(), &[("list", nums(&[1.0, 2.0]))]).unwrap();
        assert_eq!(g[0], Value::list(vec![nums(&[1.0]), nums(&[2.0])]));
    }

    #[test]
    fn transpose_swaps_rows_and_columns() {
        let t = Value::list(vec![nums(&[1.0, 2.0, 3.0]), nums(&[4.0, 5.0, 6.0])]);
        let out = run(transpose(), &[("table", t.clone())]).unwrap();
        let expected = Value::list(vec![
            nums(&[1.0, 4.0]),
            nums(&[2.0, 5.0]),
            nums(&[3.0, 6.0]),
        ]);
        assert_eq!(out[0], expected);
        let back = run(transpose(), &[("table", out[0].clone())]).unwrap();
        assert_eq!(back[0], t);
        let flat = run(transpose(), &[("table", nums(&[1.0, 2.0]))]).unwrap();
        assert_eq!(flat[0], Value::list(vec![nums(&[1.0]), nums(&[2.0])]));
        let ragged = Value::list(vec![nums(&[1.0, 2.0]), nums(&[3.0])]);
        let e = run(transpose(), &[("table", ragged)]).unwrap_err();
        assert!(e.contains("row 1 has 1 items"), "{e}");
        let mixed = Value::list(vec![nums(&[1.0]), Value::Number(2.0)]);
        assert!(run(transpose(), &[("table", mixed)]).is_err());
    }

    #[test]
    fn table_combines_rows_and_columns() {
        let rows = nums(&[0.5, 0.6]);
        let cols = nums(&[0.4, 0.5, 0.7]);
        let out = run(
            table(),
            &[("rows", rows.clone()), ("columns", cols.clone())],
        )
        .unwrap();
        let t = out[0].as_list().unwrap();
        assert_eq!(t.len(), 2);
        assert_eq!(t[0], cols);
        let r1: Vec<f64> = t[1]
            .as_list()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        for (got, want) in r1.iter().zip([0.5, 0.6, 0.8]) {
            assert!((got - want).abs() < 1e-15);
        }
        let out = run(
            table(),
            &[
                ("rows", rows.clone()),
                ("columns", cols.clone()),
                ("rule", Value::text("product")),
            ],
        )
        .unwrap();
        assert_eq!(out[0].as_list().unwrap()[0], nums(&[0.2, 0.25, 0.35]));
        let out = run(
            table(),
            &[
                ("rows", rows.clone()),
                ("columns", cols.clone()),
                ("rule", Value::text("mean")),
            ],
        )
        .unwrap();
        assert_eq!(
            out[0].as_list().unwrap()[1].as_list().unwrap()[1],
            Value::Number(0.55)
        );
        assert!(
            run(
                table(),
                &[
                    ("rows", rows.clone()),
                    ("columns", cols),
                    ("rule", Value::text("max"))
                ]
            )
            .is_err()
        );
        let out = run(table(), &[("rows", rows), ("columns", nums(&[]))]).unwrap();
        assert_eq!(out[0], Value::list(vec![nums(&[]), nums(&[])]));
    }
}
