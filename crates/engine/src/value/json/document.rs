//! A JSON document held compactly for decoding into values.
//!
//! A `serde_json::Value` tree spends about 80 bytes on each number and a heap array on each
//! `[x, y, z]`: a 224 MB input of points took 7 GB that way. Here a non-empty array of numbers is one
//! packed `Vec<f64>` row, an `[x, y, z]` triple is stored inline and an array of triples is one packed
//! `Vec<DVec3>`, so a document costs about as much as the numbers it holds (8 bytes each). It is read
//! straight from text or a reader by serde (no tree in between) or from an existing tree, and keeps
//! serde_json's limits (nesting deeper than 128 is a syntax error, not a stack overflow).

use std::fmt;

use glam::DVec3;
use indexmap::IndexMap;
use serde::de::{Deserialize, Deserializer, MapAccess, SeqAccess, Visitor};

/// The largest magnitude up to which every integer is exact as an `f64` (2⁵³).
const EXACT_INTEGER: u64 = 1 << 53;

/// A JSON document: the shapes of JSON with number rows and point lists packed.
#[derive(Debug, Clone, PartialEq)]
pub enum Document {
    /// `null`.
    Null,
    /// `true` / `false`.
    Bool(bool),
    /// A number (an integer of at most 2⁵³ in magnitude is exact here).
    Number(f64),
    /// An integer beyond ±2⁵³ that fits an `i64` (kept exact).
    Integer(i64),
    /// A string.
    Text(String),
    /// An array of exactly three numbers.
    Triple([f64; 3]),
    /// A non-empty array of numbers other than a triple.
    Numbers(Vec<f64>),
    /// A non-empty array of triples.
    Points(Vec<DVec3>),
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
            Document::Triple(_)
            | Document::Numbers(_)
            | Document::Points(_)
            | Document::Array(_) => "an array",
            Document::Object(_) => "an object",
        }
    }

    /// Whether this is an array (of any packing).
    pub fn is_array(&self) -> bool {
        matches!(
            self,
            Document::Triple(_) | Document::Numbers(_) | Document::Points(_) | Document::Array(_)
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
            Document::Triple(t) => Some(DVec3::from_array(*t)),
            _ => None,
        }
    }

    /// The number of items, when this is an array.
    pub fn array_len(&self) -> Option<usize> {
        match self {
            Document::Triple(_) => Some(3),
            Document::Numbers(v) => Some(v.len()),
            Document::Points(v) => Some(v.len()),
            Document::Array(v) => Some(v.len()),
            _ => None,
        }
    }

    /// The items of an array, one document each (a packed row yields its numbers or triples);
    /// `None` when this is not an array.
    pub fn into_items(self) -> Option<Box<dyn ExactSizeIterator<Item = Document>>> {
        Some(match self {
            Document::Triple(t) => Box::new(t.into_iter().map(Document::Number)),
            Document::Numbers(v) => Box::new(v.into_iter().map(Document::Number)),
            Document::Points(v) => Box::new(v.into_iter().map(|p| Document::Triple(p.to_array()))),
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
        Ok(if i.unsigned_abs() <= EXACT_INTEGER {
            Document::Number(i as f64)
        } else {
            Document::Integer(i)
        })
    }

    fn visit_u64<E>(self, u: u64) -> Result<Document, E> {
        Ok(match i64::try_from(u) {
            Ok(i) if u > EXACT_INTEGER => Document::Integer(i),
            _ => Document::Number(u as f64),
        })
    }

    fn visit_f64<E>(self, x: f64) -> Result<Document, E> {
        Ok(Document::Number(x))
    }

    fn visit_str<E>(self, s: &str) -> Result<Document, E> {
        Ok(Document::Text(s.to_owned()))
    }

    fn visit_string<E>(self, s: String) -> Result<Document, E> {
        Ok(Document::Text(s))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Document, A::Error> {
        let mut array = ArrayBuilder::Empty;
        while let Some(item) = seq.next_element::<Document>()? {
            array.push(item);
        }
        Ok(array.finish())
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Document, A::Error> {
        let mut fields = IndexMap::new();
        while let Some((key, value)) = map.next_entry::<String, Document>()? {
            fields.insert(key, value);
        }
        Ok(Document::Object(Box::new(fields)))
    }
}

/// An array being read: packed while its items allow it, general from the first item that does not
/// fit the packing.
enum ArrayBuilder {
    Empty,
    /// Up to three numbers, not yet allocated.
    Short([f64; 3], usize),
    Numbers(Vec<f64>),
    Points(Vec<DVec3>),
    General(Vec<Document>),
}

impl ArrayBuilder {
    fn push(&mut self, item: Document) {
        match (&mut *self, item) {
            (ArrayBuilder::Empty, Document::Number(x)) => {
                *self = ArrayBuilder::Short([x, 0.0, 0.0], 1)
            }
            (ArrayBuilder::Short(t, n), Document::Number(x)) if *n < 3 => {
                t[*n] = x;
                *n += 1;
            }
            (ArrayBuilder::Short(t, _), Document::Number(x)) => {
                *self = ArrayBuilder::Numbers(vec![t[0], t[1], t[2], x]);
            }
            (ArrayBuilder::Numbers(v), Document::Number(x)) => v.push(x),
            (ArrayBuilder::Empty, Document::Triple(t)) => {
                *self = ArrayBuilder::Points(vec![DVec3::from_array(t)]);
            }
            (ArrayBuilder::Points(v), Document::Triple(t)) => v.push(DVec3::from_array(t)),
            (ArrayBuilder::General(v), item) => v.push(item),
            (_, item) => {
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
            ArrayBuilder::Short(t, 3) => Document::Triple(t),
            ArrayBuilder::Short(t, n) => Document::Numbers(t[..n].to_vec()),
            ArrayBuilder::Numbers(v) => Document::Numbers(v),
            ArrayBuilder::Points(v) => Document::Points(v),
            ArrayBuilder::General(v) => Document::Array(v),
        }
    }
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

    #[test]
    fn number_rows_and_point_lists_are_packed() {
        assert_eq!(doc("[1, 2.5, 3]"), Document::Triple([1.0, 2.5, 3.0]));
        assert_eq!(doc("[1, 2]"), Document::Numbers(vec![1.0, 2.0]));
        assert_eq!(
            doc("[1, 2, 3, 4]"),
            Document::Numbers(vec![1.0, 2.0, 3.0, 4.0])
        );
        assert_eq!(
            doc("[[0, 0, 0], [1, 2, 3]]"),
            Document::Points(vec![DVec3::ZERO, DVec3::new(1.0, 2.0, 3.0)])
        );
        assert_eq!(doc("[]"), Document::Array(Vec::new()));
    }

    #[test]
    fn a_mixed_array_keeps_every_item_in_order() {
        assert_eq!(
            doc(r#"[1, 2, 3, 4, "x"]"#),
            Document::Array(vec![
                Document::Number(1.0),
                Document::Number(2.0),
                Document::Number(3.0),
                Document::Number(4.0),
                Document::Text("x".into()),
            ])
        );
        assert_eq!(
            doc("[[0, 0, 0], [1, 2]]"),
            Document::Array(vec![
                Document::Triple([0.0; 3]),
                Document::Numbers(vec![1.0, 2.0]),
            ])
        );
        assert_eq!(
            doc("[1, [1, 2, 3]]"),
            Document::Array(vec![
                Document::Number(1.0),
                Document::Triple([1.0, 2.0, 3.0])
            ])
        );
    }

    #[test]
    fn large_integers_stay_exact_and_objects_keep_their_order() {
        assert_eq!(
            doc("9007199254740993"),
            Document::Integer(9_007_199_254_740_993)
        );
        assert_eq!(
            doc("-9007199254740992"),
            Document::Number(-9_007_199_254_740_992.0)
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
}
