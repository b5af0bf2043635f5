//! The one broadcast rule: how a node runs over lists its ports do not consume themselves. The
//! evaluator (`eval::run_mapped`) runs a node by it and the optimizer's reverse pass
//! (`optimize::vjp`) takes the node's derivative by it, so both split the same inputs the same way.
//!
//! At each level the deepest inputs (the most list levels beyond what their ports take) are split
//! into their items and the shallower ones are passed whole to every item, until the deeper inputs
//! have come down to the depth of the shallower ones; inputs split together are matched item by
//! item, a shorter list repeating its last item (Grasshopper's longest list). A packed row gives
//! its items one at a time, without building its values.

use crate::convert::excess_depth;
use crate::node::PortDef;
use crate::value::{Items, Value};

/// What to do with a node's inputs at one level.
#[derive(Debug)]
pub enum Level<'a> {
    /// Nothing left to map: the node runs on the inputs (converted to its ports).
    Run,
    /// The deepest inputs are split into their items.
    Split(Split<'a>),
}

/// The inputs split at one level.
#[derive(Debug)]
pub struct Split<'a> {
    /// Per input, its list when it is split at this level (`None`: passed whole).
    pub lists: Vec<Option<&'a Items>>,
    /// How many runs: the longest split list.
    pub count: usize,
    /// A split list is empty: no run at all (every output is an empty list).
    pub empty: bool,
}

/// The level of `inputs` (one per port of `ports`).
pub fn level<'a>(ports: &[PortDef], inputs: &'a [Value]) -> Level<'a> {
    let excess: Vec<usize> = inputs
        .iter()
        .zip(ports)
        .map(|(v, port)| excess_depth(v, &port.ty, port.access))
        .collect();
    let deepest = excess.iter().copied().max().unwrap_or(0);
    if deepest == 0 {
        return Level::Run;
    }
    let lists: Vec<Option<&Items>> = inputs
        .iter()
        .zip(&excess)
        .map(|(v, &e)| match v {
            Value::List(items) if e == deepest => Some(items),
            _ => None,
        })
        .collect();
    let count = lists.iter().flatten().map(|l| l.len()).max().unwrap_or(0);
    let empty = lists.iter().flatten().any(|l| l.is_empty());
    Level::Split(Split {
        lists,
        count,
        empty,
    })
}

impl Split<'_> {
    /// The position in input `input`'s list of run `k`'s item (the last item repeating); `None`
    /// when the input is passed whole or its list is empty.
    pub fn index(&self, input: usize, k: usize) -> Option<usize> {
        let list = self.lists.get(input).copied().flatten()?;
        (!list.is_empty()).then(|| k.min(list.len() - 1))
    }

    /// Puts run `k`'s items into the slots of the split inputs (the others are left as they are).
    pub fn fill(&self, slots: &mut [Value], k: usize) {
        for (input, slot) in slots.iter_mut().enumerate() {
            if let (Some(list), Some(at)) = (self.lists[input], self.index(input, k)) {
                *slot = item(list, at);
            }
        }
    }
}

/// Item `k` of a list: a packed row's item is made on its own.
fn item(items: &Items, k: usize) -> Value {
    match items.as_packed() {
        Some(packed) => packed.value(k),
        None => items[k].clone(),
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::value::{Access, ValueType};

    fn numbers(xs: &[f64]) -> Value {
        Value::list(xs.iter().map(|&x| Value::Number(x)).collect())
    }

    #[test]
    fn the_deepest_inputs_split_and_the_shorter_repeats_its_last_item() {
        let ports = [
            PortDef::new("a", ValueType::Number, Access::Item),
            PortDef::new("b", ValueType::Number, Access::Item),
        ];
        let inputs = [numbers(&[1.0, 2.0, 3.0]), numbers(&[10.0])];
        let Level::Split(split) = level(&ports, &inputs) else {
            panic!("lists on item ports split")
        };
        assert_eq!((split.count, split.empty), (3, false));
        let mut slots = inputs.to_vec();
        split.fill(&mut slots, 2);
        assert_eq!(slots, [Value::Number(3.0), Value::Number(10.0)]);
        // A grafted list against a flat one: only the deeper splits first.
        let grafted = Value::list(vec![numbers(&[1.0]), numbers(&[2.0])]);
        let inputs = [grafted, numbers(&[10.0, 20.0])];
        let Level::Split(split) = level(&ports, &inputs) else {
            panic!("split")
        };
        assert!(split.lists[0].is_some() && split.lists[1].is_none());
        assert!(matches!(
            level(&ports, &[Value::Number(1.0), Value::Null]),
            Level::Run
        ));
    }

    #[test]
    fn a_packed_row_gives_its_items_without_building_its_values() {
        let ports = [PortDef::new("a", ValueType::Number, Access::Item)];
        let row = Value::List(Items::numbers(Arc::new(vec![0.5, 1.5, 2.5]), 0..3));
        let inputs = [row];
        let Level::Split(split) = level(&ports, &inputs) else {
            panic!("split")
        };
        let mut slots = vec![Value::Null];
        split.fill(&mut slots, 1);
        assert_eq!(slots[0], Value::Number(1.5));
        let Value::List(items) = &inputs[0] else {
            unreachable!()
        };
        assert!(
            items.built_values().is_none(),
            "the row's values were not built"
        );
    }
}
