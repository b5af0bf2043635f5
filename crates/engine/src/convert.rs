//! Implicit conversions of values into port types, and list depth relative to a port.

use std::sync::Arc;

use cnets_geometry::{PolygonMesh, Polyline};

use crate::value::{Access, Items, Packed, Value, ValueType, walk};

/// Why a value does not convert to a port's type.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ConvertError {
    /// A number that is not a whole number (or too large) for an integer port.
    #[error("expected integer, got the number {0}")]
    NotInteger(f64),
    /// A value of another type with no implicit conversion.
    #[error("expected {expected}, got {got}")]
    Mismatch {
        /// The port's item type.
        expected: String,
        /// The value's type.
        got: String,
    },
    /// An item of a list did not convert.
    #[error("item {index}: {source}")]
    Item {
        /// The item's position in its list.
        index: usize,
        /// Why it did not convert.
        source: Box<ConvertError>,
    },
    /// A value shape the conversion does not handle (not reachable: only lists are not items).
    #[error("internal: value shape")]
    Shape,
}

impl ConvertError {
    /// Wraps the error of the item at `index`.
    fn at(index: usize) -> impl FnOnce(ConvertError) -> ConvertError {
        move |e| ConvertError::Item {
            index,
            source: Box::new(e),
        }
    }
}

/// Converts one item to the item type `ty`, using only the implicit conversions of
/// [`ValueType::converts_to`]. `Null` passes through (the node decides whether it may be empty).
pub fn coerce_item(v: &Value, ty: &ValueType) -> Result<Value, ConvertError> {
    use ValueType as T;
    if is_exact_item(v, ty) {
        return Ok(v.clone());
    }
    Ok(match (ty, v) {
        (T::Number, Value::Integer(i)) => Value::Number(*i as f64),
        (T::Integer, Value::Number(x)) => {
            if x.is_finite() && x.fract() == 0.0 && x.abs() < 9.0e15 {
                Value::Integer(*x as i64)
            } else {
                return Err(ConvertError::NotInteger(*x));
            }
        }
        (T::Point, Value::Vector(p)) => Value::Point(*p),
        (T::Vector, Value::Point(p)) => Value::Vector(*p),
        (T::Polyline, Value::List(items)) if is_point_list(items) => Value::Polyline(Arc::new(
            Polyline::open(items.iter().filter_map(Value::as_vec3).collect()),
        )),
        (T::Mesh, Value::QuadMesh(g)) => Value::Mesh(Arc::new(PolygonMesh::from(g.as_ref()))),
        (T::List(inner), _) => return coerce_item(v, inner),
        _ => {
            // A list is named as such, not by its first item's type: a graph file converts its
            // literal lists when they are set and `cnets eval` when the node runs, and the error
            // must read the same through both.
            let got = match v {
                Value::List(_) => "a list".to_string(),
                other => other.type_name(),
            };
            return Err(ConvertError::Mismatch {
                expected: ty.to_string(),
                got,
            });
        }
    })
}

fn is_point_list(items: &[Value]) -> bool {
    !items.is_empty()
        && items
            .iter()
            .all(|v| matches!(v, Value::Point(_) | Value::Vector(_)))
}

/// True when `v` is a single item for a port of item type `ty` (a list of points is one polyline).
pub fn is_item(v: &Value, ty: &ValueType) -> bool {
    match v {
        Value::List(items) => *ty.base() == ValueType::Polyline && is_point_list(items),
        _ => true,
    }
}

/// Number of list levels above the items of `v`, judged by first elements (an empty list is one
/// level of zero items).
pub fn depth(v: &Value, ty: &ValueType) -> usize {
    if is_item(v, ty) {
        return 0;
    }
    match v {
        // A packed list's items are all of one kind: its first, read without building the rest.
        Value::List(items) => {
            1 + match items.as_packed() {
                Some(packed) if !packed.is_empty() => depth(&packed.value(0), ty),
                Some(_) => 0,
                None => items.first().map_or(0, |first| depth(first, ty)),
            }
        }
        _ => 0,
    }
}

/// List levels in `v` beyond what a port with `access` consumes itself: how deep the node is mapped.
pub fn excess_depth(v: &Value, ty: &ValueType, access: Access) -> usize {
    match access.depth() {
        None => 0,
        Some(own) => depth(v, ty).saturating_sub(own),
    }
}

/// True when the item `v` is already what a port of item type `ty` receives: [`coerce_item`]
/// returns it unchanged.
#[inline]
fn is_exact_item(v: &Value, ty: &ValueType) -> bool {
    use ValueType as T;
    match (ty, v) {
        (_, Value::Null) | (T::Any, _) => true,
        (T::List(inner), _) => is_exact_item(v, inner),
        (T::Number, Value::Number(_))
        | (T::Integer, Value::Integer(_))
        | (T::Boolean, Value::Boolean(_))
        | (T::Text, Value::Text(_))
        | (T::Point, Value::Point(_))
        | (T::Vector, Value::Vector(_))
        | (T::Plane, Value::Plane(_))
        | (T::Lines, Value::Lines(_))
        | (T::Polyline, Value::Polyline(_))
        | (T::QuadMesh, Value::QuadMesh(_))
        | (T::Mesh, Value::Mesh(_))
        | (T::Record, Value::Record(_)) => true,
        _ => false,
    }
}

/// True when every item of the (possibly nested) value `v` is already of item type `ty`: the value
/// can be shared as it is instead of being rebuilt. One walk (large lists on several threads), no
/// allocation.
fn is_exact_tree(v: &Value, ty: &ValueType) -> bool {
    match v {
        // Leaves are tested inline: a table of a million numbers is a million leaves.
        Value::List(items) if !is_item(v, ty) => all_items(items, |item| match item {
            Value::List(_) => is_exact_tree(item, ty),
            leaf => is_exact_item(leaf, ty),
        }),
        _ => is_exact_item(v, ty),
    }
}

/// True when `each` (a test of an item's variant) holds for every item of `items`. A packed list
/// is tested without building its values: its first item stands for all (they share a variant),
/// and each label for the items that carry it.
fn all_items(items: &Items, each: impl Fn(&Value) -> bool + Sync) -> bool {
    match items.as_packed() {
        Some(Packed::Labels { labels, .. }) => labels.iter().all(each),
        Some(packed) => packed.is_empty() || each(&packed.value(0)),
        None => walk::all_items(items, each),
    }
}

/// Converts a value that needs no more mapping into exactly what the port receives: an item, a list
/// of items (a single value becomes a one-element list), or a tree with converted leaves. A value
/// that needs no conversion is shared, not copied.
pub fn coerce_for_port(v: &Value, ty: &ValueType, access: Access) -> Result<Value, ConvertError> {
    match access {
        Access::Item => coerce_item(v, ty),
        Access::List => match v {
            Value::Null => Ok(Value::Null),
            v if is_item(v, ty) => Ok(Value::list(vec![coerce_item(v, ty)?])),
            Value::List(items) if all_items(items, |item| is_exact_item(item, ty)) => Ok(v.clone()),
            Value::List(items) => items
                .iter()
                .enumerate()
                .map(|(k, item)| coerce_item(item, ty).map_err(ConvertError::at(k)))
                .collect::<Result<Vec<_>, _>>()
                .map(Value::list),
            _ => unreachable_shape(),
        },
        Access::Table | Access::Tree => coerce_tree(v, ty),
    }
}

/// Converts every item of a (possibly nested) value to the item type `ty`, keeping the nesting.
pub fn coerce_tree(v: &Value, ty: &ValueType) -> Result<Value, ConvertError> {
    if is_item(v, ty) {
        return coerce_item(v, ty);
    }
    if is_exact_tree(v, ty) {
        return Ok(v.clone());
    }
    match v {
        Value::List(items) => items
            .iter()
            .enumerate()
            .map(|(k, item)| coerce_tree(item, ty).map_err(ConvertError::at(k)))
            .collect::<Result<Vec<_>, _>>()
            .map(Value::list),
        _ => unreachable_shape(),
    }
}

/// Only lists are not items, so the callers' non-list arms cannot be reached; answer with an error
/// instead of panicking all the same.
fn unreachable_shape() -> Result<Value, ConvertError> {
    Err(ConvertError::Shape)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn depth_counts_list_levels_and_points_form_polylines() {
        let pts = Value::list(vec![Value::Point(DVec3::ZERO), Value::Point(DVec3::X)]);
        assert_eq!(depth(&pts, &ValueType::Point), 1);
        assert_eq!(depth(&pts, &ValueType::Polyline), 0);
        let nested = Value::list(vec![pts.clone(), pts.clone()]);
        assert_eq!(depth(&nested, &ValueType::Polyline), 1);
        assert_eq!(depth(&nested, &ValueType::Number), 2);
        assert_eq!(excess_depth(&nested, &ValueType::Number, Access::List), 1);
        assert_eq!(excess_depth(&nested, &ValueType::Number, Access::Tree), 0);
        assert_eq!(depth(&Value::list(vec![]), &ValueType::Number), 1);
    }

    #[test]
    fn coercions() {
        assert_eq!(
            coerce_item(&Value::Integer(3), &ValueType::Number).unwrap(),
            Value::Number(3.0)
        );
        assert_eq!(
            coerce_item(&Value::Number(3.0), &ValueType::Integer).unwrap(),
            Value::Integer(3)
        );
        assert!(coerce_item(&Value::Number(3.5), &ValueType::Integer).is_err());
        assert!(
            coerce_item(&Value::text("a"), &ValueType::Number)
                .unwrap_err()
                .to_string()
                .contains("expected number")
        );
        let single =
            coerce_for_port(&Value::Number(0.5), &ValueType::Number, Access::List).unwrap();
        assert_eq!(single, Value::list(vec![Value::Number(0.5)]));
    }

    fn same_list(a: &Value, b: &Value) -> bool {
        matches!((a, b), (Value::List(x), Value::List(y)) if Items::ptr_eq(x, y))
    }

    #[test]
    fn values_of_the_port_type_are_shared_not_rebuilt() {
        let row = Value::list(vec![Value::Number(0.25), Value::Number(0.5)]);
        let table = Value::list(vec![row.clone(), row]);
        for access in [Access::Table, Access::Tree] {
            let got = coerce_for_port(&table, &ValueType::Number, access).unwrap();
            assert!(same_list(&got, &table), "{access:?}");
        }
        let list = Value::list(vec![Value::Number(1.0), Value::Null]);
        let got = coerce_for_port(&list, &ValueType::Number, Access::List).unwrap();
        assert!(same_list(&got, &list));
        // One item needing a conversion rebuilds the value, converting only that item.
        let mixed = Value::list(vec![
            Value::list(vec![Value::Number(0.25)]),
            Value::list(vec![Value::Integer(1)]),
        ]);
        let got = coerce_for_port(&mixed, &ValueType::Number, Access::Table).unwrap();
        assert!(!same_list(&got, &mixed));
        let expected = Value::list(vec![
            Value::list(vec![Value::Number(0.25)]),
            Value::list(vec![Value::Number(1.0)]),
        ]);
        assert_eq!(got, expected);
        // A list of points for a polyline port is one item and is still converted.
        let points = Value::list(vec![Value::Point(DVec3::ZERO), Value::Point(DVec3::X)]);
        let got = coerce_for_port(&points, &ValueType::Polyline, Access::Tree).unwrap();
        assert!(matches!(got, Value::Polyline(_)));
    }
}
