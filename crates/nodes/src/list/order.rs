//! Reordering lists: `list.sort` and `list.shift`.

use std::cmp::Ordering;

use cnets_engine::prelude::*;

/// A sort key: numbers sort before texts would, but a list mixes neither.
enum Key<'a> {
    Number(f64),
    Text(&'a str),
}

fn keys_of(list: &[Value]) -> Result<Vec<Key<'_>>, NodeError> {
    let mut numbers = 0;
    let keys = list
        .iter()
        .enumerate()
        .map(|(k, v)| match v {
            Value::Number(_) | Value::Integer(_) => {
                numbers += 1;
                Ok(Key::Number(v.as_f64().unwrap_or(f64::NAN)))
            }
            Value::Text(t) => Ok(Key::Text(t)),
            other => Err(NodeError::new(format!(
                "item {k} is a {}: list.sort sorts numbers or texts (give keys to sort anything else)",
                other.type_name()
            ))),
        })
        .collect::<Result<Vec<_>, _>>()?;
    if numbers != 0 && numbers != keys.len() {
        return Err("the list mixes numbers and texts: sort one kind, or give keys".into());
    }
    Ok(keys)
}

fn compare(a: &Key<'_>, b: &Key<'_>) -> Ordering {
    match (a, b) {
        (Key::Number(x), Key::Number(y)) => x.total_cmp(y),
        (Key::Text(x), Key::Text(y)) => x.cmp(y),
        (Key::Number(_), Key::Text(_)) => Ordering::Less,
        (Key::Text(_), Key::Number(_)) => Ordering::Greater,
    }
}

node! {
    /// Sorts a list of numbers (ascending) or texts (by character codes), or any list by `keys`
    /// (one number per item). The sort is stable: equal keys keep their order. `indices` are the
    /// original positions of the sorted items (Grasshopper's Sort List).
    #[node(id = "list.sort", category = "Lists")]
    pub fn sort(
        /// The list (numbers or texts; anything when keys are given).
        list: k::List<k::Any>,
        /// Sort keys, one per item of the list (optional).
        keys: Option<k::List<k::Number>>,
    ) -> (
        /// The sorted list.
        list: k::List<k::Any>,
        /// Original index of each sorted item.
        indices: k::List<k::Integer>,
    ) {
        let keys: Vec<Key<'_>> = match &keys {
            Some(keys) if keys.len() != list.len() => {
                return Err(format!(
                    "keys has {} numbers for a list of {} items: give one key per item",
                    keys.len(),
                    list.len()
                )
                .into());
            }
            Some(keys) => keys.iter().map(|&x| Key::Number(x)).collect(),
            None => keys_of(&list)?,
        };
        let mut order: Vec<usize> = (0..list.len()).collect();
        order.sort_by(|&a, &b| compare(&keys[a], &keys[b]));
        let sorted: Vec<Value> = order.iter().map(|&k| list[k].clone()).collect();
        let indices: Vec<i64> = order.iter().map(|&k| k as i64).collect();
        Ok((sorted, indices))
    }
}

node! {
    /// Shifts the items of a list: item k of the result is item k + offset of the input. With
    /// `wrap`, items that fall off one end come back at the other ([1,2,3,4] by 1 → [2,3,4,1]);
    /// without, they are dropped ([2,3,4]). Negative offsets shift the other way.
    #[node(id = "list.shift", category = "Lists")]
    pub fn shift(
        /// The list.
        list: k::List<k::Any>,
        /// How far to shift.
        offset: k::Integer = 1,
        /// Wrap items around instead of dropping them.
        wrap: k::Boolean = true,
    ) -> (
        /// The shifted list.
        list: k::List<k::Any>,
    ) {
        let n = list.len();
        if n == 0 {
            return Ok((list,));
        }
        let n_i = n as i64;
        let out = if wrap {
            let start = offset.rem_euclid(n_i) as usize;
            let mut out = list;
            out.rotate_left(start);
            out
        } else if offset >= 0 {
            let skip = offset.min(n_i) as usize;
            list[skip..].to_vec()
        } else {
            let keep = (n_i + offset).max(0) as usize;
            list[..keep].to_vec()
        };
        Ok((out,))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{ints, nums, run_named};

    #[test]
    fn sort_numbers_texts_and_by_keys_stably() {
        let out = run_named(&sort(), &[("list", nums(&[3.0, -1.0, 2.0, -1.0]))]).unwrap();
        assert_eq!(out[0], nums(&[-1.0, -1.0, 2.0, 3.0]));
        assert_eq!(out[1], ints(&[1, 3, 2, 0]), "stable: the first −1 first");
        let texts = Value::list(vec![Value::text("b"), Value::text("a"), Value::text("c")]);
        let out = run_named(&sort(), &[("list", texts)]).unwrap();
        assert_eq!(out[1], ints(&[1, 0, 2]));
        let points = crate::testing::points(&[[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]]);
        let out = run_named(
            &sort(),
            &[("list", points.clone()), ("keys", nums(&[5.0, 1.0, 5.0]))],
        )
        .unwrap();
        assert_eq!(out[1], ints(&[1, 0, 2]));
        let e = run_named(&sort(), &[("list", points)]).unwrap_err();
        assert!(e.contains("item 0 is a point"), "{e}");
        let mixed = Value::list(vec![Value::Number(1.0), Value::text("a")]);
        assert!(
            run_named(&sort(), &[("list", mixed)])
                .unwrap_err()
                .contains("mixes")
        );
        let e = run_named(
            &sort(),
            &[("list", nums(&[1.0, 2.0])), ("keys", nums(&[1.0]))],
        );
        assert!(e.unwrap_err().contains("one key per item"));
    }

    #[test]
    fn shift_wraps_or_drops() {
        let list = nums(&[1.0, 2.0, 3.0, 4.0]);
        let shifted = |offset: i64, wrap: bool| {
            run_named(
                &shift(),
                &[
                    ("list", list.clone()),
                    ("offset", Value::Integer(offset)),
                    ("wrap", Value::Boolean(wrap)),
                ],
            )
            .unwrap()
            .remove(0)
        };
        assert_eq!(shifted(1, true), nums(&[2.0, 3.0, 4.0, 1.0]));
        assert_eq!(shifted(1, false), nums(&[2.0, 3.0, 4.0]));
        assert_eq!(shifted(-1, true), nums(&[4.0, 1.0, 2.0, 3.0]));
        assert_eq!(shifted(-1, false), nums(&[1.0, 2.0, 3.0]));
        assert_eq!(shifted(9, true), nums(&[2.0, 3.0, 4.0, 1.0]));
        assert_eq!(shifted(9, false), nums(&[]));
        assert_eq!(shifted(i64::MIN, false), nums(&[]));
        assert_eq!(
            shifted(i64::MAX, true),
            shifted(i64::MAX.rem_euclid(4), true)
        );
    }
}
