//! The numbers of a value in a fixed order — its *leaves* — the coordinates the reverse pass
//! differentiates in.
//!
//! A number or whole number is one leaf; a point or vector three (x, y, z); a polyline its points;
//! a quad mesh or polygon mesh its vertices (row-major for a quad mesh); a list the leaves of its
//! items in order. Text, truth values, planes, line sets and records have no leaves: they carry no
//! derivative ([`opaque`] tells whether a value holds any of the last three, whose numbers the
//! reverse pass cannot follow).

use std::sync::Arc;

use glam::DVec3;

use crate::value::Value;

/// How many leaves `value` has.
pub fn count(value: &Value) -> usize {
    match value {
        Value::Number(_) | Value::Integer(_) => 1,
        Value::Point(_) | Value::Vector(_) => 3,
        Value::Polyline(p) => 3 * p.points.len(),
        Value::QuadMesh(m) => 3 * m.vertices.len(),
        Value::Mesh(m) => 3 * m.vertices.len(),
        Value::List(items) => items.iter().map(count).sum(),
        _ => 0,
    }
}

/// True when `value` holds a plane, line set or record (numbers the reverse pass cannot follow).
pub fn opaque(value: &Value) -> bool {
    match value {
        Value::Plane(_) | Value::Lines(_) | Value::Record(_) => true,
        Value::List(items) => items.iter().any(opaque),
        _ => false,
    }
}

fn push_points(points: &[DVec3], out: &mut Vec<f64>) {
    out.extend(points.iter().flat_map(|p| p.to_array()));
}

/// Appends the leaves of `value` to `out`.
pub fn flatten_into(value: &Value, out: &mut Vec<f64>) {
    match value {
        Value::Number(x) => out.push(*x),
        Value::Integer(i) => out.push(*i as f64),
        Value::Point(p) | Value::Vector(p) => out.extend(p.to_array()),
        Value::Polyline(p) => push_points(&p.points, out),
        Value::QuadMesh(m) => push_points(&m.vertices, out),
        Value::Mesh(m) => push_points(&m.vertices, out),
        Value::List(items) => items.iter().for_each(|v| flatten_into(v, out)),
        _ => {}
    }
}

/// The leaves of `value`.
pub fn flatten(value: &Value) -> Vec<f64> {
    let mut out = Vec::with_capacity(count(value));
    flatten_into(value, &mut out);
    out
}

/// `value` with leaf `index` replaced by `x` (a whole number becomes a number); `value` itself when
/// it has no such leaf.
pub fn with_leaf(value: &Value, index: usize, x: f64) -> Value {
    fn set(points: &[DVec3], index: usize, x: f64) -> Vec<DVec3> {
        let mut points = points.to_vec();
        points[index / 3][index % 3] = x;
        points
    }
    match value {
        Value::Number(_) | Value::Integer(_) if index == 0 => Value::Number(x),
        Value::Point(p) if index < 3 => {
            let mut q = *p;
            q[index] = x;
            Value::Point(q)
        }
        Value::Vector(p) if index < 3 => {
            let mut q = *p;
            q[index] = x;
            Value::Vector(q)
        }
        Value::Polyline(p) if index < 3 * p.points.len() => {
            let mut q = (**p).clone();
            q.points = set(&p.points, index, x);
            Value::Polyline(Arc::new(q))
        }
        Value::QuadMesh(m) if index < 3 * m.vertices.len() => {
            let mut q = (**m).clone();
            q.vertices = set(&m.vertices, index, x);
            Value::QuadMesh(Arc::new(q))
        }
        Value::Mesh(m) if index < 3 * m.vertices.len() => {
            let mut q = (**m).clone();
            q.vertices = set(&m.vertices, index, x);
            Value::Mesh(Arc::new(q))
        }
        Value::List(items) => {
            let mut rest = index;
            for (k, item) in items.iter().enumerate() {
                let n = count(item);
                if rest < n {
                    let mut new = items.to_vec();
                    new[k] = with_leaf(item, rest, x);
                    return Value::list(new);
                }
                rest -= n;
            }
            value.clone()
        }
        _ => value.clone(),
    }
}

/// `value` with the leaves `updates` (leaf index, new value; sorted by index) replaced, rebuilt
/// once; parts without an update are shared, not copied.
pub fn with_leaves(value: &Value, updates: &[(usize, f64)]) -> Value {
    fn walk(value: &Value, start: usize, updates: &[(usize, f64)]) -> Value {
        let n = count(value);
        let lo = updates.partition_point(|u| u.0 < start);
        let hi = updates.partition_point(|u| u.0 < start + n);
        let mine = &updates[lo..hi];
        if mine.is_empty() {
            return value.clone();
        }
        match value {
            Value::List(items) => {
                let mut at = start;
                Value::list(
                    items
                        .iter()
                        .map(|item| {
                            let v = walk(item, at, mine);
                            at += count(item);
                            v
                        })
                        .collect(),
                )
            }
            _ => mine
                .iter()
                .fold(value.clone(), |v, &(i, x)| with_leaf(&v, i - start, x)),
        }
    }
    walk(value, 0, updates)
}

/// The leaf index of the number at `indices` (list items, then a point's component) inside
/// `value`, as [`crate::optimize::ValuePath`] addresses it.
pub fn offset(value: &Value, indices: &[usize]) -> Option<usize> {
    let Some((&i, rest)) = indices.split_first() else {
        return matches!(value, Value::Number(_) | Value::Integer(_) | Value::Null).then_some(0);
    };
    match value {
        Value::List(items) => {
            let before: usize = items.get(..i)?.iter().map(count).sum();
            Some(before + offset(items.get(i)?, rest)?)
        }
        Value::Point(_) | Value::Vector(_) if rest.is_empty() && i < 3 => Some(i),
        _ => None,
    }
}

/// `a += b` element-wise (`a` grows to `b`'s length when shorter).
pub fn accumulate(a: &mut Vec<f64>, b: &[f64]) {
    if a.len() < b.len() {
        a.resize(b.len(), 0.0);
    }
    a.iter_mut().zip(b).for_each(|(x, y)| *x += y);
}

#[cfg(test)]
mod tests {
    use super::*;
    use cnets_geometry::Polyline;

    #[test]
    fn leaves_are_in_order_and_settable() {
        let v = Value::list(vec![
            Value::Number(1.0),
            Value::Point(DVec3::new(2.0, 3.0, 4.0)),
            Value::Polyline(Arc::new(Polyline::open(vec![
                DVec3::new(5.0, 6.0, 7.0),
                DVec3::new(8.0, 9.0, 10.0),
            ]))),
            Value::Boolean(true),
        ]);
        assert_eq!(count(&v), 10);
        assert_eq!(
            flatten(&v),
            (1..=10).map(f64::from).collect::<Vec<_>>(),
            "leaves in order"
        );
        for k in 0..10 {
            let w = with_leaf(&v, k, -1.0);
            let mut expected: Vec<f64> = (1..=10).map(f64::from).collect();
            expected[k] = -1.0;
            assert_eq!(flatten(&w), expected);
        }
        assert_eq!(offset(&v, &[1, 2]), Some(3));
        let w = with_leaves(&v, &[(0, -1.0), (3, -4.0), (9, -10.0)]);
        let mut expected: Vec<f64> = (1..=10).map(f64::from).collect();
        (expected[0], expected[3], expected[9]) = (-1.0, -4.0, -10.0);
        assert_eq!(flatten(&w), expected);
        assert_eq!(offset(&v, &[0]), Some(0));
        assert_eq!(offset(&v, &[7]), None);
        assert!(!opaque(&v));
    }
}
