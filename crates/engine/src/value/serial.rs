//! Values in serde's data model, for the messages between the web page and its evaluation worker
//! (`crates/web/src/wire`): [`Value`] derives it; a list's items cross as a sequence of values (a
//! packed list as the values it stands for, without building them); lists and records nest at
//! most [`MAX_NESTING`] deep when read, so a hostile message is an error, not a stack overflow.

use std::cell::Cell;

use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::{Items, Value};

/// Lists and records nest at most this deep in a value read back.
pub const MAX_NESTING: usize = 64;

thread_local! {
    /// How deep the value being read nests here (lists and records).
    static NESTING: Cell<usize> = const { Cell::new(0) };
}

/// Leaves one level of nesting when dropped (also when reading failed).
struct Level;

impl Drop for Level {
    fn drop(&mut self) {
        NESTING.with(|n| n.set(n.get().saturating_sub(1)));
    }
}

/// Reads a list's or record's content one level deeper, refusing more than [`MAX_NESTING`].
pub(super) fn nested<'de, D: Deserializer<'de>, T: Deserialize<'de>>(d: D) -> Result<T, D::Error> {
    let depth = NESTING.with(|n| {
        n.set(n.get() + 1);
        n.get()
    });
    let _level = Level;
    if depth > MAX_NESTING {
        return Err(D::Error::custom(format!(
            "values nest more than {MAX_NESTING} lists or records deep"
        )));
    }
    T::deserialize(d)
}

impl Serialize for Items {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self.as_packed() {
            Some(packed) => s.collect_seq((0..packed.len()).map(|k| packed.value(k))),
            None => s.collect_seq(self.iter()),
        }
    }
}

impl<'de> Deserialize<'de> for Items {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        Vec::<Value>::deserialize(d).map(Items::new)
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use glam::DVec3;

    use super::*;
    use crate::value::Record;

    fn round_trip(v: &Value) -> Value {
        let bytes = postcard::to_allocvec(v).unwrap();
        postcard::from_bytes(&bytes).unwrap()
    }

    #[test]
    fn every_kind_of_value_comes_back_equal() {
        let values = [
            Value::Null,
            Value::Number(-0.25),
            Value::Integer(i64::MIN),
            Value::Boolean(true),
            Value::text("rib"),
            Value::Point(DVec3::new(1.0, 2.0, 3.0)),
            Value::Vector(DVec3::Z),
            Value::list(vec![Value::Integer(3), Value::list(vec![Value::Null])]),
            Value::List(Items::numbers(Arc::new(vec![1.0, 2.0, 3.0]), 1..3)),
            Value::Record(Arc::new(Record::new().with("planarity", 1e-12))),
        ];
        for v in &values {
            assert_eq!(&round_trip(v), v, "{v:?}");
        }
        let packed = Value::List(Items::numbers(Arc::new(vec![1.0, 2.0, 3.0]), 1..3));
        assert_eq!(
            round_trip(&packed),
            Value::list(vec![Value::Number(2.0), Value::Number(3.0)]),
            "a packed row crosses as its values, not its table"
        );
    }

    #[test]
    fn nesting_past_the_limit_is_an_error_not_a_stack_overflow() {
        let mut deep = Value::Null;
        for _ in 0..MAX_NESTING {
            deep = Value::list(vec![deep]);
        }
        assert_eq!(round_trip(&deep), deep, "{MAX_NESTING} lists deep is read");
        let deeper = Value::list(vec![deep]);
        let bytes = postcard::to_allocvec(&deeper).unwrap();
        assert!(
            postcard::from_bytes::<Value>(&bytes).is_err(),
            "one level more"
        );
        // The counter is left at zero: the next value reads.
        assert_eq!(round_trip(&Value::list(vec![])), Value::list(vec![]));
    }
}
