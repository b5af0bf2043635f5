//! A JSON document held compactly for decoding into values.
//!
//! A `serde_json::Value` tree spends about 80 bytes on each number and a heap array on each
//! `[x, y, z]`: a 224 MB input of points took 7 GB that way. Here a non-empty array of numbers is one
//! packed `Vec<f64>` row, an `[x, y, z]` triple is stored inline and an array of triples is one packed
//! `Vec<DVec3>`, so a document costs about as much as the numbers it holds (8 bytes each). It is read
//! straight from text or a reader by serde (no tree in between) or from an existing tree, and keeps
//! serde_json's limits (nesting deeper than 128 is a syntax error, not a stack overflow).
//!
//! A number written as an integer (`3`, not `3.0` or `3e0`) stays one: [`Document::Integer`], and in
//! a packed row a bit of [`Integers`] (allocated at the row's first integer). On a port of type `any`
//! it decodes to an integer value, as a graph file's `3` and Python's `3` do.

use std::fmt;

use glam::DVec3;
use indexmap::IndexMap;
use serde::de::{Deserialize, Deserializer, MapAccess, SeqAccess, Visitor};

/// The largest magnitude up to which every integer is exact as an `f64` (2⁵³).
const EXACT_INTEGER: u64 = 1 << 53;

/// Which numbers of a packed row were written as integers: one bit per number, nothing allocated
/// while there is none (a row of `0.5, 1.0, …` costs no more than its numbers). The words grow by
/// doubling; unused words are zero.
#[derive(Debug, Clone, Default)]
pub struct Integers(Option<Box<[u64]>>);

impl PartialEq for Integers {
    fn eq(&self, other: &Self) -> bool {
        let used = |w: &Option<Box<[u64]>>| {
            let w = w.as_deref().unwrap_or_default();
            let n = w.iter().rposition(|&x| x != 0).map_or(0, |k| k + 1);
            w[..n].to_vec()
        };
        used(&self.0) == used(&other.0)
    }
}

impl Integers {
    /// Marks number `k` as written as an integer.
    fn set(&mut self, k: usize) {
        let word = k / 64;
        let len = self.0.as_ref().map_or(0, |w| w.len());
        if word >= len {
            let mut grown = self.0.take().map(Vec::from).unwrap_or_default();
            grown.resize((word + 1).max(2 * len), 0);
            self.0 = Some(grown.into_boxed_slice());
        }
        if let Some(words) = self.0.as_mut() {
            words[word] |= 1 << (k % 64);
        }
    }

    /// Whether number `k` was written as an integer.
    pub fn get(&self, k: usize) -> bool {
        self.0
            .as_ref()
            .and_then(|w| w.get(k / 64))
            .is_some_and(|w| w & (1 << (k % 64)) != 0)
    }

    /// Whether no number of the row was written as an integer.
    pub fn none(&self) -> bool {
        self.0.is_none()
    }

    /// The number `x` at position `k` as a document item: an integer when it was written as one.
    fn item(&self, k: usize, x: f64) -> Document {
        if self.get(k) {
            Document::Integer(x as i64)
        } else {
            Document::Number(x)
        }
    }
}

/// A JSON document: the shapes of JSON with number rows and point lists packed.
#[derive(Debug, Clone, PartialEq)]
pub enum Document {
    /// `null`.
    Null,
    /// `true` / `false`.
    Bool(bool),
    /// A number written with a fraction or an exponent (`1.5`, `3.0`, `1e3`), or an integer beyond
    /// the range of `i64`.
    Number(f64),
    /// A number written as an integer that fits an `i64` (kept exact).
    Integer(i64),
    /// A string.
    Text(String),
    /// An array of exactly three numbers (which of them were integers).
    Triple([f64; 3], Integers),
    /// A non-empty array of numbers other than a triple (which were integers).
    Numbers(Vec<f64>, Integers),
    /// A non-empty array of triples (which coordinates were integers, three bits a point).
    Points(Vec<DVec3>, Integers),
    /// Any other array (including the empty one).
    Array(Vec<Document>),
    /// An object, its fields in the order written (a repeated field keeps its first place and its
    /// last value, as serde_json's ordered map does).
    Object(Box<IndexMap<String, Document>>),
}

impl Document {
    /// What the document holds, for error messages ("a number", "an array", …).
    pub fn kind(&self) -> &'static str {
        match self {
            Document::Null => "null",
            Document::Bool(_) => "a boolean",
            Document::Number(_) | Document::Integer(_) => "a number",
            Document::Text(_) => "a string",
            Document::Triple(..)
            | Document::Numbers(..)
            | Document::Points(..)
            | Document::Array(_) => "an array",
            Document::Object(_) => "an object",
        }
    }

    /// Whether this is an array (of any packing).
    pub fn is_array(&self) -> bool {
        matches!(
            self,
            Document::Triple(..)
                | Document::Numbers(..)
                | Document::Points(..)
                | Document::Array(_)
        )
    }

    /// The number, when this is one.
    pub fn as_f64(&self) -> Option<f64> {
        match *self {
            Document::Number(x) => Some(x),
            Document::Integer(i) => Some(i as f64),
            _ => None,
        }
    }

    /// The point, when this is an `[x, y, z]` triple.
    pub fn as_vec3(&self) -> Option<DVec3> {
        match self {
            Document::Triple(t, _) => Some(DVec3::from_array(*t)),
            _ => None,
        }
    }

    /// The items of an array, one document each (a packed row yields its numbers or triples,
    /// integers as integers); `None` when this is not an array.
    pub fn into_items(self) -> Option<Box<dyn ExactSizeIterator<Item = Document>>> {
        Some(match self {
            Document::Triple(t, ints) => Box::new((0..3).map(move |k| ints.item(k, t[k]))),
            Document::Numbers(v, ints) => {
                Box::new(v.into_iter().enumerate().map(move |(k, x)| ints.item(k, x)))
            }
            Document::Points(v, ints) => Box::new(v.into_iter().enumerate().map(move |(k, p)| {
                let mut marks = Integers::default();
                for c in 0..3 {
                    if ints.get(3 * k + c) {
                        marks.set(c);
                    }
                }
                Document::Triple(p.to_array(), marks)
            })),
            Document::Array(v) => Box::new(v.into_iter()),
            _ => return None,
        })
    }
}

impl From<&serde_json::Value> for Document {
    fn from(json: &serde_json::Value) -> Self {
        Document::deserialize(json).expect("a JSON tree always reads as a document")
    }
}

impl<'de> Deserialize<'de> for Document {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(DocumentVisitor)
    }
}

struct DocumentVisitor;

impl<'de> Visitor<'de> for DocumentVisitor {
    type Value = Document;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a JSON value")
    }

    fn visit_unit<E>(self) -> Result<Document, E> {
        Ok(Document::Null)
    }

    fn visit_none<E>(self) -> Result<Document, E> {
        Ok(Document::Null)
    }

    fn visit_some<D: Deserializer<'de>>(self, d: D) -> Result<Document, D::Error> {
        Document::deserialize(d)
    }

    fn visit_bool<E>(self, b: bool) -> Result<Document, E> {
        Ok(Document::Bool(b))
    }

    fn visit_i64<E>(self, i: i64) -> Result<Document, E> {
        Ok(Document::Integer(i))
    }

    fn visit_u64<E>(self, u: u64) -> Result<Document, E> {
        Ok(match i64::try_from(u) {
            Ok(i) => Document::Integer(i),
            Err(_) => Document::Number(u as f64),
        })
    }

    fn visit_f64<E>(self, x: f64) -> Result<Document, E> {
        Ok(Document::Number(x))
    }

    fn visit_str<E: serde::de::Error>(self, s: &str) -> Result<Document, E> {
        charge(s.len())?;
        Ok(Document::Text(s.to_owned()))
    }

    fn visit_string<E: serde::de::Error>(self, s: String) -> Result<Document, E> {
        charge(s.len())?;
        Ok(Document::Text(s))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Document, A::Error> {
        let mut array = ArrayBuilder::Empty;
        while let Some(item) = seq.next_element::<Document>()? {
            // What the item costs in the array, twice its size: a packed row doubles as it grows,
            // and while it moves to its new place both are in memory (a number 16 bytes, a point
            // 48, anything else two slots; its own contents were charged when it was read).
            charge(match (&array, &item) {
                (_, Document::Number(_) | Document::Integer(_)) => 16,
                (ArrayBuilder::Empty | ArrayBuilder::Points(..), Document::Triple(..)) => 48,
                _ => 2 * std::mem::size_of::<Document>(),
            })?;
            array.push(item);
        }
        Ok(array.finish())
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Document, A::Error> {
        let mut fields = IndexMap::new();
        while let Some((key, value)) = map.next_entry::<String, Document>()? {
            charge(key.len() + std::mem::size_of::<Document>() + 16)?;
            fields.insert(key, value);
        }
        Ok(Document::Object(Box::new(fields)))
    }
}

thread_local! {
    /// The memory limit of the document being read on this thread and what it has taken so far.
    static MEMORY: std::cell::Cell<Option<(u64, u64)>> = const { std::cell::Cell::new(None) };
}

/// Counts `bytes` more of the document being read against its limit ([`read_document_within`]).
fn charge<E: serde::de::Error>(bytes: usize) -> Result<(), E> {
    MEMORY.with(|m| match m.get() {
        Some((limit, used)) => {
            let used = used.saturating_add(bytes as u64);
            m.set(Some((limit, used)));
            if used > limit {
                Err(E::custom(format!(
                    "the input needs more than the memory limit of {}",
                    crate::budget::format_bytes(limit)
                )))
            } else {
                Ok(())
            }
        }
        None => Ok(()),
    })
}

/// An array being read: packed while its items allow it, general from the first item that does not
/// fit the packing.
enum ArrayBuilder {
    Empty,
    /// Up to three numbers, not yet allocated.
    Short([f64; 3], usize, Integers),
    Numbers(Vec<f64>, Integers),
    Points(Vec<DVec3>, Integers),
    General(Vec<Document>),
}

/// A number that packs into a row (an integer only while it is exact as an `f64`), and whether it
/// was written as an integer.
fn packable(item: &Document) -> Option<(f64, bool)> {
    match *item {
        Document::Number(x) => Some((x, false)),
        Document::Integer(i) if i.unsigned_abs() <= EXACT_INTEGER => Some((i as f64, true)),
        _ => None,
    }
}

impl ArrayBuilder {
    fn push(&mut self, item: Document) {
        match (&mut *self, packable(&item), item) {
            (ArrayBuilder::Empty, Some((x, int)), _) => {
                let mut ints = Integers::default();
                if int {
                    ints.set(0);
                }
                *self = ArrayBuilder::Short([x, 0.0, 0.0], 1, ints)
            }
            (ArrayBuilder::Short(t, n, ints), Some((x, int)), _) if *n < 3 => {
                if int {
                    ints.set(*n);
                }
                t[*n] = x;
                *n += 1;
            }
            (ArrayBuilder::Short(t, _, ints), Some((x, int)), _) => {
                let mut ints = std::mem::take(ints);
                if int {
                    ints.set(3);
                }
                *self = ArrayBuilder::Numbers(vec![t[0], t[1], t[2], x], ints);
            }
            (ArrayBuilder::Numbers(v, ints), Some((x, int)), _) => {
                if int {
                    ints.set(v.len());
                }
                v.push(x);
            }
            (ArrayBuilder::Empty, None, Document::Triple(t, marks)) => {
                *self = ArrayBuilder::Points(vec![DVec3::from_array(t)], marks);
            }
            (ArrayBuilder::Points(v, ints), None, Document::Triple(t, marks)) => {
                for c in (0..3).filter(|&c| marks.get(c)) {
                    ints.set(3 * v.len() + c);
                }
                v.push(DVec3::from_array(t));
            }
            (ArrayBuilder::General(v), _, item) => v.push(item),
            (_, _, item) => {
                let mut items = std::mem::replace(self, ArrayBuilder::Empty).into_documents();
                items.push(item);
                *self = ArrayBuilder::General(items);
            }
        }
    }

    /// The items read so far, one document each.
    fn into_documents(self) -> Vec<Document> {
        match self.finish().into_items() {
            Some(items) => items.collect(),
            None => Vec::new(),
        }
    }

    fn finish(self) -> Document {
        match self {
            ArrayBuilder::Empty => Document::Array(Vec::new()),
            ArrayBuilder::Short(t, 3, ints) => Document::Triple(t, ints),
            ArrayBuilder::Short(t, n, ints) => Document::Numbers(t[..n].to_vec(), ints),
            ArrayBuilder::Numbers(v, ints) => Document::Numbers(v, ints),
            ArrayBuilder::Points(v, ints) => Document::Points(v, ints),
            ArrayBuilder::General(v) => Document::Array(v),
        }
    }
}

/// [`read_document`] that fails, where it is in the text, as soon as the document would take more
/// than `limit` bytes (numbers 16 bytes each, points 48 — a packed row doubles as it grows —,
/// texts their length, other items two slots): a JSON input larger than the memory budget is
/// refused while it is read, before it is in memory.
pub fn read_document_within<R: std::io::Read>(
    reader: R,
    limit: u64,
) -> serde_json::Result<Document> {
    MEMORY.with(|m| m.set(Some((limit, 0))));
    let read = read_document(reader);
    MEMORY.with(|m| m.set(None));
    read
}

/// Reads a document from a JSON reader (buffered internally by serde_json), rejecting trailing
/// characters; the error keeps serde_json's line and column.
pub fn read_document<R: std::io::Read>(reader: R) -> serde_json::Result<Document> {
    let mut de = serde_json::Deserializer::from_reader(std::io::BufReader::new(reader));
    let doc = Document::deserialize(&mut de)?;
    de.end()?;
    Ok(doc)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn doc(text: &str) -> Document {
        serde_json::from_str(text).unwrap()
    }

    /// The marks of the numbers at `at`.
    fn ints(at: &[usize]) -> Integers {
        let mut marks = Integers::default();
        at.iter().for_each(|&k| marks.set(k));
        marks
    }

    #[test]
    fn number_rows_and_point_lists_are_packed() {
        assert_eq!(
            doc("[1, 2.5, 3]"),
            Document::Triple([1.0, 2.5, 3.0], ints(&[0, 2]))
        );
        assert_eq!(
            doc("[1.0, 2.5, 3e0]"),
            Document::Triple([1.0, 2.5, 3.0], Integers::default())
        );
        assert_eq!(
            doc("[1, 2.0]"),
            Document::Numbers(vec![1.0, 2.0], ints(&[0]))
        );
        assert_eq!(
            doc("[1, 2, 3, 4]"),
            Document::Numbers(vec![1.0, 2.0, 3.0, 4.0], ints(&[0, 1, 2, 3]))
        );
        assert_eq!(
            doc("[[0.0, 0.5, 0.0], [1, 2.5, 3]]"),
            Document::Points(
                vec![DVec3::new(0.0, 0.5, 0.0), DVec3::new(1.0, 2.5, 3.0)],
                ints(&[3, 5])
            )
        );
        assert_eq!(doc("[]"), Document::Array(Vec::new()));
    }

    #[test]
    fn integers_come_back_as_integers_item_by_item() {
        let items: Vec<Document> = doc("[[0.5, 1, 2], [3, 4.5, 5.0]]")
            .into_items()
            .unwrap()
            .flat_map(|p| p.into_items().unwrap())
            .collect();
        assert_eq!(
            items,
            [
                Document::Number(0.5),
                Document::Integer(1),
                Document::Integer(2),
                Document::Integer(3),
                Document::Number(4.5),
                Document::Number(5.0),
            ]
        );
        let row: Vec<Document> = doc("[1, 2.0, 3, 4]").into_items().unwrap().collect();
        assert_eq!(row[0], Document::Integer(1));
        assert_eq!(row[1], Document::Number(2.0));
        // The 65th number of a row has its mark in the second word.
        let long = format!("[{}1]", "0.5, ".repeat(64));
        let Document::Numbers(v, marks) = doc(&long) else {
            panic!("a packed row")
        };
        assert_eq!(v.len(), 65);
        assert!(marks.get(64) && !marks.get(63) && !marks.get(128));
    }

    #[test]
    fn a_mixed_array_keeps_every_item_in_order() {
        assert_eq!(
            doc(r#"[1, 2, 3, 4.5, "x"]"#),
            Document::Array(vec![
                Document::Integer(1),
                Document::Integer(2),
                Document::Integer(3),
                Document::Number(4.5),
                Document::Text("x".into()),
            ])
        );
        assert_eq!(
            doc("[[0, 0, 0.5], [1, 2]]"),
            Document::Array(vec![
                Document::Triple([0.0, 0.0, 0.5], ints(&[0, 1])),
                Document::Numbers(vec![1.0, 2.0], ints(&[0, 1])),
            ])
        );
        assert_eq!(
            doc("[1, [1, 2, 3]]"),
            Document::Array(vec![
                Document::Integer(1),
                Document::Triple([1.0, 2.0, 3.0], ints(&[0, 1, 2]))
            ])
        );
    }

    #[test]
    fn large_integers_stay_exact_and_objects_keep_their_order() {
        assert_eq!(
            doc("9007199254740993"),
            Document::Integer(9_007_199_254_740_993)
        );
        // Beyond 2⁵³ an integer does not pack into a row of f64s: the row stays general.
        assert_eq!(
            doc("[1, 9007199254740993]"),
            Document::Array(vec![
                Document::Integer(1),
                Document::Integer(9_007_199_254_740_993)
            ])
        );
        assert_eq!(
            doc("-9007199254740992"),
            Document::Integer(-9_007_199_254_740_992)
        );
        assert_eq!(
            doc("18446744073709551615"),
            Document::Number(u64::MAX as f64)
        );
        let Document::Object(o) = doc(r#"{"z": 1, "a": 2, "z": 3}"#) else {
            panic!("an object")
        };
        let fields: Vec<_> = o.iter().map(|(k, v)| (k.as_str(), v.as_f64())).collect();
        assert_eq!(fields, [("z", Some(3.0)), ("a", Some(2.0))]);
    }

    #[test]
    fn a_tree_reads_as_the_same_document_as_its_text() {
        let text =
            r#"{"points": [[0, 1, 2], [3, 4, 5.5]], "closed": true, "w": [1, null], "n": 1e300}"#;
        let tree: serde_json::Value = serde_json::from_str(text).unwrap();
        assert_eq!(Document::from(&tree), doc(text));
    }

    #[test]
    fn deep_nesting_and_trailing_text_are_errors() {
        let deep = "[".repeat(100_000);
        assert!(serde_json::from_str::<Document>(&deep).is_err());
        let err = read_document("[1, 2] x".as_bytes()).unwrap_err();
        assert_eq!((err.line(), err.column()), (1, 8));
    }

    #[test]
    fn a_document_over_its_memory_limit_stops_where_it_is() {
        let numbers = format!("[{}0]", "0.5,\n".repeat(1000));
        assert!(read_document_within(numbers.as_bytes(), 16 * 1001).is_ok());
        let err = read_document_within(numbers.as_bytes(), 16 * 500).unwrap_err();
        assert!(
            err.to_string()
                .contains("more than the memory limit of 8 kB"),
            "{err}"
        );
        // The 501st number (on line 501) is one too many: the error is where the reader stands.
        assert_eq!(err.line(), 502, "{err}");
        let text = format!("{{\"a\": \"{}\"}}", "x".repeat(10_000));
        assert!(read_document_within(text.as_bytes(), 1000).is_err());
        // No limit after a limited read on the same thread.
        assert!(read_document(numbers.as_bytes()).is_ok());
    }
}
