//! The runner's JSON encoding of values.
//!
//! number/integer → number; boolean; text → string; point/vector → `[x, y, z]`; list → array;
//! polyline → `{ "points": [[x,y,z], …], "closed": bool }` (a bare array of points is accepted as an
//! open polyline on input); quad mesh → `{ "rows", "cols", "wrap_rows", "wrap_cols", "vertices" }`;
//! polygon mesh → `{ "vertices", "faces": [[i, …], …] }`; plane → `{ "origin", "x_axis", "y_axis",
//! "normal" }`; lines → `[[[x,y,z],[x,y,z]], …]`; record → object; null and non-finite numbers → `null`.

//!
//! Decoding does not build a `serde_json::Value` tree of the input: the text is read into a compact
//! [`Document`] (packed number rows and point lists, about the size of the data itself), which is
//! then decoded by the port's type, moving those packed rows into the values without a copy.

mod decode;
mod document;
mod encode;

pub use decode::{from_document, from_json};
pub use document::{Document, read_document, read_document_within};
pub use encode::{JsonOut, to_json, write_json};

/// Why a JSON document does not decode into a value of a port's type.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum JsonError {
    /// A JSON value of another kind than the type needs.
    #[error("expected {expected}, got {found}")]
    Expected {
        /// The type asked for.
        expected: String,
        /// What the JSON holds ("a string", "an object", …).
        found: &'static str,
    },
    /// A number with a fraction (or too large) where an integer is needed.
    #[error("expected integer, got the non-integral number {0}")]
    NotIntegral(String),
    /// A geometry object with a missing or malformed field.
    #[error("{0}")]
    Malformed(String),
    /// The geometry the object describes is invalid.
    #[error(transparent)]
    Geometry(#[from] cnets_geometry::GeometryError),
    /// Inside array item `index`: `[2]: …`, nested `[0][2]: …`.
    #[error("[{index}]{}{source}", separator(.source))]
    At {
        /// The item's position.
        index: usize,
        /// What went wrong inside it.
        source: Box<JsonError>,
    },
    /// Inside an object field of a record.
    #[error("{field}: {source}")]
    Field {
        /// The field name.
        field: String,
        /// What went wrong inside it.
        source: Box<JsonError>,
    },
}

/// `[0][2]: …` for nested positions, `[2]: …` before a message.
fn separator(inner: &JsonError) -> &'static str {
    if matches!(inner, JsonError::At { .. }) {
        ""
    } else {
        ": "
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use cnets_geometry::{Line, Plane, PolygonMesh, Polyline, QuadGrid};
    use glam::DVec3;
    use serde_json::{Value as Json, json};

    use super::*;
    use crate::value::{Items, Record, Value, ValueType};

    #[test]
    fn encodes_contract_shapes() {
        let p = Value::from(Polyline::open(vec![DVec3::ZERO, DVec3::X]));
        assert_eq!(
            to_json(&p),
            json!({"points": [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], "closed": false})
        );
        let g = QuadGrid::new(1, 2, vec![DVec3::ZERO, DVec3::Y]).unwrap();
        assert_eq!(
            to_json(&Value::from(g)),
            json!({"rows": 1, "cols": 2, "wrap_rows": false, "wrap_cols": false,
                   "vertices": [[0.0, 0.0, 0.0], [0.0, 1.0, 0.0]]})
        );
        assert_eq!(to_json(&Value::Number(f64::INFINITY)), Json::Null);
        assert_eq!(
            to_json(&Value::list(vec![Value::Null, Value::Integer(3)])),
            json!([null, 3])
        );
    }

    #[test]
    fn decodes_by_port_type() {
        assert!(
            from_json(&json!([1, 2, 3]), &ValueType::Point)
                .unwrap()
                .same_as(&Value::Point(DVec3::new(1.0, 2.0, 3.0)))
        );
        let list = from_json(&json!([1, 2, 3]), &ValueType::Number).unwrap();
        assert_eq!(list.as_list().unwrap().len(), 3);
        let bare = from_json(&json!([[0, 0, 0], [1, 0, 0]]), &ValueType::Polyline).unwrap();
        assert!(matches!(bare, Value::Polyline(p) if p.points.len() == 2 && !p.closed));
        assert!(
            from_json(&json!("x"), &ValueType::Number)
                .unwrap_err()
                .to_string()
                .contains("expected number")
        );
        assert_eq!(
            from_json(&json!([[0.5, "x"], [0.5, 0.5]]), &ValueType::Number)
                .unwrap_err()
                .to_string(),
            "[0][1]: expected number, got a string"
        );
        assert!(from_json(&json!(1.5), &ValueType::Integer).is_err());
        assert_eq!(
            from_json(&json!(2.0), &ValueType::Integer).unwrap(),
            Value::Integer(2)
        );
    }

    #[test]
    fn round_trips_meshes() {
        let g = QuadGrid::new(2, 2, vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE])
            .unwrap()
            .with_wrap(true, false);
        let v = Value::from(g);
        assert_eq!(from_json(&to_json(&v), &ValueType::QuadMesh).unwrap(), v);
        let m = Value::from(
            PolygonMesh::from_faces(vec![DVec3::ZERO, DVec3::X, DVec3::Y], &[vec![0, 1, 2]])
                .unwrap(),
        );
        assert_eq!(from_json(&to_json(&m), &ValueType::Mesh).unwrap(), m);
    }

    #[test]
    fn streamed_output_equals_the_tree_output() {
        let grid = QuadGrid::new(
            2,
            2,
            vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, -0.0)],
        )
        .unwrap();
        let mesh = PolygonMesh::from_faces(vec![DVec3::ZERO, DVec3::X, DVec3::Y], &[vec![0, 1, 2]])
            .unwrap();
        let values = vec![
            Value::Null,
            Value::Number(0.1),
            Value::Number(3.0),
            Value::Number(f64::NAN),
            Value::Number(f64::NEG_INFINITY),
            Value::Number(1e300),
            Value::Integer(-7),
            Value::Boolean(true),
            Value::text("a \"quoted\"\n text"),
            Value::Point(DVec3::new(1.5, -2.0, 1e-12)),
            Value::Vector(DVec3::Z),
            Value::Plane(Arc::new(Plane::from_normal(DVec3::X, DVec3::Z).unwrap())),
            Value::Lines(Arc::new(vec![Line::new(DVec3::ZERO, DVec3::X)])),
            Value::Polyline(Arc::new(Polyline::open(vec![DVec3::ZERO, DVec3::Y]))),
            Value::QuadMesh(Arc::new(grid.with_wrap(true, false))),
            Value::Mesh(Arc::new(mesh)),
            Value::List(Items::numbers(Arc::new(vec![0.5, f64::NAN, 2.0]), 1..3)),
            Value::list(vec![
                Value::list(vec![Value::Number(1.0), Value::Null]),
                Value::list(vec![]),
            ]),
            Value::Record(Arc::new(
                Record::new()
                    .with("z", 1.0)
                    .with("a", Value::list(vec![Value::text("x")])),
            )),
        ];
        for v in values {
            let mut bytes = Vec::new();
            write_json(&mut bytes, &v).unwrap();
            assert_eq!(
                String::from_utf8(bytes).unwrap(),
                to_json(&v).to_string(),
                "{v:?}"
            );
        }
    }
}
