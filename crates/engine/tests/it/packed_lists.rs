//! A packed list (a row of a shared table of vectors or label codes) is the same list as its
//! values everywhere: type, equality and hash (the early-cutoff test), finiteness, JSON, port
//! conversion (shared without being rebuilt) and item access.

use std::sync::Arc;

use cnets_engine::convert::coerce_for_port;
use cnets_engine::value::json::to_json;
use cnets_engine::value::{content_hash, first_non_finite, is_all_finite};
use cnets_engine::{Access, Items, Value, ValueType};
use glam::DVec3;

fn table() -> Arc<Vec<DVec3>> {
    Arc::new(
        (0..20)
            .map(|k| DVec3::new(k as f64, -0.5 * k as f64, 1.0 / (k as f64 + 1.0)))
            .collect(),
    )
}

/// Rows 0..4 of width 5, packed and as plain values.
fn both(t: &Arc<Vec<DVec3>>) -> (Value, Value) {
    let packed = Value::list(
        (0..4)
            .map(|i| Value::List(Items::vectors(t.clone(), i * 5..i * 5 + 5)))
            .collect(),
    );
    let plain = Value::list(
        (0..4)
            .map(|i| {
                Value::list(
                    t[i * 5..i * 5 + 5]
                        .iter()
                        .map(|&p| Value::Vector(p))
                        .collect(),
                )
            })
            .collect(),
    );
    (packed, plain)
}

fn labels() -> Arc<[Value]> {
    vec![Value::text("++"), Value::text("--")].into()
}

#[test]
fn packed_vectors_equal_and_hash_like_their_values() {
    let t = table();
    let (packed, plain) = both(&t);
    assert_eq!(packed.value_type(), plain.value_type());
    assert_eq!(
        packed.value_type().to_string(),
        plain.value_type().to_string()
    );
    assert!(packed.same_as(&plain) && plain.same_as(&packed));
    assert_eq!(content_hash(&packed), content_hash(&plain));
    // Two packed copies of the same data in different tables.
    let (other, _) = both(&Arc::new((*t).clone()));
    assert!(packed.same_as(&other));
    assert_eq!(content_hash(&packed), content_hash(&other));
    // One changed bit is seen by equality and hash alike.
    let mut changed = (*t).clone();
    changed[7].y = -changed[7].y;
    let (changed, _) = both(&Arc::new(changed));
    assert!(!packed.same_as(&changed));
    assert_ne!(content_hash(&packed), content_hash(&changed));
    assert_eq!(to_json(&packed), to_json(&plain));
}

#[test]
fn packed_labels_equal_hash_and_print_like_their_values() {
    let codes = Arc::new(vec![0u8, 1, 1, 0, 1, 0]);
    let packed = Value::List(Items::labels(codes.clone(), 1..5, labels()));
    let plain = Value::list(["--", "--", "++", "--"].map(Value::text).to_vec());
    assert!(packed.same_as(&plain) && plain.same_as(&packed));
    assert_eq!(content_hash(&packed), content_hash(&plain));
    assert_eq!(to_json(&packed), to_json(&plain));
    assert_eq!(packed.value_type().to_string(), "list<text>");
    let shifted = Value::List(Items::labels(codes, 0..4, labels()));
    assert!(!packed.same_as(&shifted));
    assert_ne!(content_hash(&packed), content_hash(&shifted));
}

#[test]
fn finiteness_is_read_from_the_table() {
    let t = table();
    let (packed, _) = both(&t);
    assert!(is_all_finite(&packed));
    let mut bad = (*t).clone();
    bad[13].z = f64::NAN;
    let (packed, _) = both(&Arc::new(bad));
    assert!(!is_all_finite(&packed));
    assert_eq!(first_non_finite(&packed).as_deref(), Some("item 2, item 3"));
    let big: Arc<Vec<DVec3>> = Arc::new(vec![DVec3::ONE; 200_000]);
    assert!(is_all_finite(&Value::List(Items::vectors(
        big.clone(),
        0..200_000
    ))));
    let mut big = (*big).clone();
    big[150_001].x = f64::INFINITY;
    assert!(!is_all_finite(&Value::List(Items::vectors(
        Arc::new(big),
        0..200_000
    ))));
}

#[test]
fn a_packed_input_of_the_port_type_is_shared_and_otherwise_converted() {
    let (packed, plain) = both(&table());
    let tree = coerce_for_port(&packed, &ValueType::Vector, Access::Tree).unwrap();
    let (Value::List(a), Value::List(b)) = (&tree, &packed) else {
        panic!("a list")
    };
    assert!(Items::ptr_eq(a, b), "shared, not rebuilt");
    // Vectors convert to points item by item (the packed row is read as values).
    let points = coerce_for_port(&packed, &ValueType::Point, Access::Tree).unwrap();
    let expected = coerce_for_port(&plain, &ValueType::Point, Access::Tree).unwrap();
    assert!(points.same_as(&expected));
    assert_eq!(
        points.as_list().unwrap()[1].as_list().unwrap()[2].value_type(),
        ValueType::Point
    );
    // A packed row where a number is expected is an error, as its values would be.
    assert!(coerce_for_port(&packed, &ValueType::Number, Access::Tree).is_err());
    assert!(coerce_for_port(&plain, &ValueType::Number, Access::Tree).is_err());
}

#[test]
fn items_read_through_the_slice() {
    let (packed, plain) = both(&table());
    let row = &packed.as_list().unwrap()[3];
    assert_eq!(row.as_list().unwrap().len(), 5);
    assert_eq!(
        row.as_list().unwrap()[4],
        plain.as_list().unwrap()[3].as_list().unwrap()[4]
    );
    assert_eq!(
        row.as_list().unwrap()[4].as_vec3(),
        Some(DVec3::new(19.0, -9.5, 1.0 / 20.0))
    );
}

mod properties {
    use super::*;
    use proptest::prelude::*;

    /// Numbers including the ones bitwise equality must tell apart: ±0, NaN, ±∞.
    fn number() -> impl Strategy<Value = f64> {
        prop_oneof![
            4 => -1e6..1e6f64,
            1 => Just(0.0),
            1 => Just(-0.0),
            1 => Just(f64::NAN),
            1 => Just(f64::INFINITY),
            1 => Just(f64::NEG_INFINITY),
        ]
    }

    fn numbers_row(x: &[f64]) -> (Value, Value) {
        (
            Value::List(Items::numbers(Arc::new(x.to_vec()), 0..x.len())),
            Value::list(x.iter().map(|&v| Value::Number(v)).collect()),
        )
    }

    fn vectors_row(x: &[f64]) -> (Value, Value) {
        let points: Vec<DVec3> = x
            .chunks_exact(3)
            .map(|c| DVec3::new(c[0], c[1], c[2]))
            .collect();
        let plain = Value::list(points.iter().map(|&p| Value::Vector(p)).collect());
        let len = points.len();
        (Value::List(Items::vectors(Arc::new(points), 0..len)), plain)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(500))]

        /// Packed and plain rows agree on equality, hash, finiteness, JSON and type; changing one
        /// bit of one number is seen by equality, packed against packed and against plain.
        #[test]
        fn packed_rows_behave_as_their_values(
            x in prop::collection::vec(number(), 0..40),
            flip in any::<prop::sample::Index>(),
        ) {
            for (packed, plain) in [numbers_row(&x), vectors_row(&x)] {
                prop_assert!(packed.same_as(&plain) && plain.same_as(&packed));
                prop_assert_eq!(content_hash(&packed), content_hash(&plain));
                prop_assert_eq!(is_all_finite(&packed), is_all_finite(&plain));
                prop_assert_eq!(first_non_finite(&packed), first_non_finite(&plain));
                prop_assert_eq!(to_json(&packed), to_json(&plain));
                prop_assert_eq!(packed.value_type(), plain.value_type());
            }
            if x.len() >= 3 {
                let mut y = x.clone();
                let k = flip.index(x.len() / 3 * 3);
                y[k] = f64::from_bits(y[k].to_bits() ^ 1);
                for ((a, _), (b, b_plain)) in [
                    (numbers_row(&x), numbers_row(&y)),
                    (vectors_row(&x), vectors_row(&y)),
                ] {
                    prop_assert!(!a.same_as(&b) && !a.same_as(&b_plain));
                }
            }
        }
    }
}
