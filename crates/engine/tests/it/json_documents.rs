//! The compact JSON document (`value::json::Document`) reads any JSON text as the same document as
//! serde_json's tree of it, and values round-trip through it: `to_json` then decoding by the type
//! gives the value back (packed rows and point lists included), for random inputs.

use cnets_engine::value::json::{Document, from_document, from_json, to_json};
use cnets_engine::{Value, ValueType};
use cnets_geometry::{Polyline, QuadGrid};
use glam::DVec3;
use proptest::prelude::*;
use serde_json::Value as Json;

/// Any JSON tree, numbers of every kind (small and huge integers, fractions, negative zero).
fn json() -> impl Strategy<Value = Json> {
    let number = prop_oneof![
        any::<i64>().prop_map(Json::from),
        any::<u64>().prop_map(Json::from),
        (-1e6..1e6f64).prop_map(Json::from),
        Just(Json::from(-0.0)),
        (-3i64..=3).prop_map(Json::from),
    ];
    let leaf = prop_oneof![
        Just(Json::Null),
        any::<bool>().prop_map(Json::Bool),
        number.clone(),
        "[a-z\"\\\\]{0,4}".prop_map(Json::String),
    ];
    leaf.prop_recursive(5, 64, 6, move |inner| {
        prop_oneof![
            prop::collection::vec(inner.clone(), 0..6).prop_map(Json::Array),
            prop::collection::vec(number.clone(), 0..6).prop_map(Json::Array),
            prop::collection::vec(prop::collection::vec(number.clone(), 3), 0..5)
                .prop_map(|ps| Json::Array(ps.into_iter().map(Json::Array).collect())),
            prop::collection::vec(("[a-c]{1,2}", inner), 0..4)
                .prop_map(|fields| Json::Object(fields.into_iter().collect())),
        ]
    })
}

fn point() -> impl Strategy<Value = DVec3> {
    prop::array::uniform3(-1e3..1e3f64).prop_map(DVec3::from_array)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn text_and_tree_read_as_the_same_document(tree in json()) {
        let text = serde_json::to_string(&tree).unwrap();
        let doc: Document = serde_json::from_str(&text).unwrap();
        prop_assert_eq!(&doc, &Document::from(&tree));
        // A document decodes as `Any` exactly like its tree does.
        let a = from_document(doc, &ValueType::Any);
        let b = from_json(&tree, &ValueType::Any);
        prop_assert_eq!(a.is_ok(), b.is_ok());
        if let (Ok(a), Ok(b)) = (a, b) {
            prop_assert!(a.same_as(&b), "{:?} vs {:?}", a, b);
        }
    }

    #[test]
    fn values_round_trip_through_documents(
        numbers in prop::collection::vec(-1e9..1e9f64, 0..40),
        points in prop::collection::vec(point(), 1..40),
        closed in any::<bool>(),
        cols in 1usize..5,
    ) {
        let cases = [
            (Value::list(numbers.iter().map(|&x| Value::Number(x)).collect()), ValueType::Number),
            (Value::list(points.iter().map(|&p| Value::Point(p)).collect()), ValueType::Point),
            (Value::from(Polyline { points: points.clone(), closed }), ValueType::Polyline),
        ];
        for (value, ty) in cases {
            let text = to_json(&value).to_string();
            let doc: Document = serde_json::from_str(&text).unwrap();
            let back = from_document(doc, &ty).unwrap();
            prop_assert!(back.same_as(&value), "{:?}: {} → {:?}", ty, text, back);
        }
        let rows = points.len() / cols;
        if rows > 0 {
            let grid = Value::from(QuadGrid::new(rows, cols, points[..rows * cols].to_vec()).unwrap());
            let doc: Document = serde_json::from_str(&to_json(&grid).to_string()).unwrap();
            prop_assert_eq!(from_document(doc, &ValueType::QuadMesh).unwrap(), grid);
        }
    }
}
