//! The items of a list value.
//!
//! [`Items`] are shared and cheap to clone. Usually they are [`Value`]s. A list a node builds
//! from plain data can instead be *packed*: one row of a shared table of vectors, numbers or label codes,
//! the table being the node's own result moved in, not copied (a 1000 × 1000 construction's plane
//! normals are one table of a million `DVec3`s, its configurations one table of a million bytes),
//! or a row of numbers (JSON decodes an array of numbers into one). A
//! packed list is the same list as its values in every respect: it builds them (once) only when
//! something reads it as values, while the hot paths (finiteness, equality, hashing, JSON) read the
//! plain data directly.

use std::fmt;
use std::ops::{Deref, Range};
use std::sync::{Arc, OnceLock};

use glam::DVec3;

use super::Value;

/// The items of a list value ([`Value::List`]): shared; dereferences to `[Value]`.
#[derive(Clone)]
pub struct Items(Arc<Repr>);

enum Repr {
    Values(Vec<Value>),
    Packed {
        items: Packed,
        values: OnceLock<Vec<Value>>,
    },
}

/// The plain items of a packed list.
#[derive(Clone)]
pub enum Packed {
    /// Vectors ([`Value::Vector`] each): `table[range]`.
    Vectors {
        /// The shared table (all rows).
        table: Arc<Vec<DVec3>>,
        /// This row's items.
        range: Range<usize>,
    },
    /// Numbers ([`Value::Number`] each): `table[range]`.
    Numbers {
        /// The shared table (all rows).
        table: Arc<Vec<f64>>,
        /// This row's items.
        range: Range<usize>,
    },
    /// Labels: item k is `labels[table[range][k]]` ([`Value::Null`] for a code without a label).
    Labels {
        /// The shared table of codes (all rows).
        table: Arc<Vec<u8>>,
        /// This row's items.
        range: Range<usize>,
        /// The value of each code.
        labels: Arc<[Value]>,
    },
}

impl Packed {
    /// The number of items.
    pub fn len(&self) -> usize {
        match self {
            Packed::Vectors { range, .. }
            | Packed::Numbers { range, .. }
            | Packed::Labels { range, .. } => range.len(),
        }
    }

    /// True when there are no items.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Item k as a value (k < [`Packed::len`]).
    pub fn value(&self, k: usize) -> Value {
        match self {
            Packed::Vectors { table, range } => Value::Vector(table[range.start + k]),
            Packed::Numbers { table, range } => Value::Number(table[range.start + k]),
            Packed::Labels {
                table,
                range,
                labels,
            } => Self::label(labels, table[range.start + k]),
        }
    }

    /// The shared table's address, how many handles share it and its size in bytes.
    pub(crate) fn table_sharing(&self) -> (usize, usize, u64) {
        fn of<T>(t: &Arc<Vec<T>>) -> (usize, usize, u64) {
            let bytes = (t.capacity() * std::mem::size_of::<T>()) as u64;
            (
                Arc::as_ptr(t) as *const u8 as usize,
                Arc::strong_count(t),
                bytes,
            )
        }
        match self {
            Packed::Vectors { table, .. } => of(table),
            Packed::Numbers { table, .. } => of(table),
            Packed::Labels { table, .. } => of(table),
        }
    }

    fn label(labels: &[Value], code: u8) -> Value {
        labels.get(code as usize).cloned().unwrap_or_default()
    }

    fn values(&self) -> Vec<Value> {
        match self {
            Packed::Vectors { table, range } => table[range.clone()]
                .iter()
                .map(|&p| Value::Vector(p))
                .collect(),
            Packed::Numbers { table, range } => table[range.clone()]
                .iter()
                .map(|&x| Value::Number(x))
                .collect(),
            Packed::Labels {
                table,
                range,
                labels,
            } => table[range.clone()]
                .iter()
                .map(|&c| Self::label(labels, c))
                .collect(),
        }
    }
}

impl Items {
    /// A list of values.
    pub fn new(items: Vec<Value>) -> Self {
        Items(Arc::new(Repr::Values(items)))
    }

    /// A packed list of vectors: `table[range]` (the range is clamped to the table).
    pub fn vectors(table: Arc<Vec<DVec3>>, range: Range<usize>) -> Self {
        let range = clamp(range, table.len());
        Self::packed(Packed::Vectors { table, range })
    }

    /// A packed list of numbers: `table[range]` (the range is clamped to the table).
    pub fn numbers(table: Arc<Vec<f64>>, range: Range<usize>) -> Self {
        let range = clamp(range, table.len());
        Self::packed(Packed::Numbers { table, range })
    }

    /// A packed list of labels: item k is `labels[table[range][k]]` (the range is clamped to the
    /// table; a code without a label reads as [`Value::Null`]).
    pub fn labels(table: Arc<Vec<u8>>, range: Range<usize>, labels: Arc<[Value]>) -> Self {
        let range = clamp(range, table.len());
        Self::packed(Packed::Labels {
            table,
            range,
            labels,
        })
    }

    fn packed(items: Packed) -> Self {
        Items(Arc::new(Repr::Packed {
            items,
            values: OnceLock::new(),
        }))
    }

    /// The plain items when this list is packed.
    pub fn as_packed(&self) -> Option<&Packed> {
        match &*self.0 {
            Repr::Packed { items, .. } => Some(items),
            Repr::Values(_) => None,
        }
    }

    /// The number of items (without building a packed list's values).
    pub fn len(&self) -> usize {
        match &*self.0 {
            Repr::Values(items) => items.len(),
            Repr::Packed { items, .. } => items.len(),
        }
    }

    /// True when there are no items.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// True when both are the same shared list.
    pub fn ptr_eq(a: &Items, b: &Items) -> bool {
        Arc::ptr_eq(&a.0, &b.0)
    }

    /// The address of the shared list and how many handles share it (for the memory budget).
    pub(crate) fn sharing(&self) -> (usize, usize) {
        (
            Arc::as_ptr(&self.0) as *const u8 as usize,
            Arc::strong_count(&self.0),
        )
    }

    /// The values a packed list has built so far (none for a plain list or before first use).
    pub(crate) fn built_values(&self) -> Option<&[Value]> {
        match &*self.0 {
            Repr::Packed { values, .. } => values.get().map(Vec::as_slice),
            Repr::Values(_) => None,
        }
    }

    /// The plain list's values, without building a packed list's.
    pub(crate) fn plain_values(&self) -> Option<&[Value]> {
        match &*self.0 {
            Repr::Values(items) => Some(items),
            Repr::Packed { .. } => None,
        }
    }

    /// The items as a vector of values, moved out when this is their only owner.
    pub fn into_vec(self) -> Vec<Value> {
        match Arc::try_unwrap(self.0) {
            Ok(Repr::Values(items)) => items,
            Ok(repr) => Items(Arc::new(repr)).to_vec(),
            Err(shared) => Items(shared).to_vec(),
        }
    }
}

fn clamp(range: Range<usize>, len: usize) -> Range<usize> {
    let end = range.end.min(len);
    range.start.min(end)..end
}

impl Deref for Items {
    type Target = [Value];

    /// The items as values; a packed list builds them on first use and keeps them.
    fn deref(&self) -> &[Value] {
        match &*self.0 {
            Repr::Values(items) => items,
            Repr::Packed { items, values } => values.get_or_init(|| items.values()),
        }
    }
}

impl From<Vec<Value>> for Items {
    fn from(items: Vec<Value>) -> Self {
        Items::new(items)
    }
}

impl fmt::Debug for Items {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table() -> Arc<Vec<DVec3>> {
        Arc::new((0..12).map(|k| DVec3::new(k as f64, 0.5, -1.0)).collect())
    }

    #[test]
    fn a_packed_row_reads_as_its_values() {
        let row = Items::vectors(table(), 4..8);
        assert_eq!(row.len(), 4);
        assert!(row.as_packed().is_some());
        let expected: Vec<Value> = (4..8)
            .map(|k| Value::Vector(DVec3::new(k as f64, 0.5, -1.0)))
            .collect();
        assert_eq!(&*row, &expected[..]);
        assert_eq!(row[1], Value::Vector(DVec3::new(5.0, 0.5, -1.0)));
        assert_eq!(row.as_packed().unwrap().value(3), expected[3]);
        assert_eq!(row.clone().into_vec(), expected);
    }

    #[test]
    fn packed_numbers_read_as_number_values() {
        let row = Items::numbers(Arc::new(vec![0.5, -1.0, 2.0]), 1..3);
        assert_eq!(row.to_vec(), vec![Value::Number(-1.0), Value::Number(2.0)]);
        assert_eq!(row.as_packed().unwrap().value(0), Value::Number(-1.0));
    }

    #[test]
    fn labels_map_codes_and_unknown_codes_read_as_null() {
        let labels: Arc<[Value]> = vec![Value::text("++"), Value::text("--")].into();
        let row = Items::labels(Arc::new(vec![0, 1, 1, 7]), 1..4, labels);
        assert_eq!(
            row.to_vec(),
            vec![Value::text("--"), Value::text("--"), Value::Null]
        );
    }

    #[test]
    fn ranges_beyond_the_table_are_clamped() {
        assert_eq!(Items::vectors(table(), 10..20).len(), 2);
        assert!(Items::vectors(table(), 30..40).is_empty());
        let (start, end) = (9, 3);
        assert!(Items::vectors(table(), start..end).is_empty());
    }
}
