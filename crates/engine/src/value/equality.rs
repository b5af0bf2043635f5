//! Bitwise equality and content hashes of values: the basis of early cutoff.

use std::hash::Hasher;
use std::sync::Arc;

use glam::DVec3;
use rustc_hash::FxHasher;

use super::{Items, Packed, Value};

/// Structural equality with numbers compared by bits. Shared payloads compare by pointer first.
pub(super) fn same(a: &Value, b: &Value) -> bool {
    use Value::*;
    match (a, b) {
        (Null, Null) => true,
        (Number(x), Number(y)) => x.to_bits() == y.to_bits(),
        (Integer(x), Integer(y)) => x == y,
        (Boolean(x), Boolean(y)) => x == y,
        (Text(x), Text(y)) => x == y,
        (Point(x), Point(y)) | (Vector(x), Vector(y)) => same_vec(*x, *y),
        (Plane(x), Plane(y)) => {
            Arc::ptr_eq(x, y)
                || [x.origin, x.x_axis, x.y_axis, x.normal]
                    .iter()
                    .zip([y.origin, y.x_axis, y.y_axis, y.normal])
                    .all(|(p, q)| same_vec(*p, q))
        }
        (Lines(x), Lines(y)) => {
            Arc::ptr_eq(x, y)
                || (x.len() == y.len()
                    && x.iter()
                        .zip(y.iter())
                        .all(|(l, m)| same_vec(l.start, m.start) && same_vec(l.end, m.end)))
        }
        (Polyline(x), Polyline(y)) => {
            Arc::ptr_eq(x, y) || (x.closed == y.closed && same_points(&x.points, &y.points))
        }
        (QuadMesh(x), QuadMesh(y)) => {
            Arc::ptr_eq(x, y)
                || (x.rows == y.rows
                    && x.cols == y.cols
                    && x.wrap_rows == y.wrap_rows
                    && x.wrap_cols == y.wrap_cols
                    && same_points(&x.vertices, &y.vertices))
        }
        (Mesh(x), Mesh(y)) => {
            Arc::ptr_eq(x, y)
                || (x.indices == y.indices
                    && x.face_starts == y.face_starts
                    && x.parts == y.parts
                    && same_points(&x.vertices, &y.vertices))
        }
        (List(x), List(y)) => Items::ptr_eq(x, y) || same_items(x, y),
        (Record(x), Record(y)) => {
            Arc::ptr_eq(x, y)
                || (x.len() == y.len()
                    && x.fields()
                        .iter()
                        .zip(y.fields())
                        .all(|((n, v), (m, w))| n == m && same(v, w)))
        }
        _ => false,
    }
}

/// Lists item by item; two packed lists of the same kind compare their plain data.
fn same_items(x: &Items, y: &Items) -> bool {
    if x.len() != y.len() {
        return false;
    }
    match (x.as_packed(), y.as_packed()) {
        (
            Some(Packed::Vectors { table: a, range: r }),
            Some(Packed::Vectors { table: b, range: s }),
        ) => same_points(&a[r.clone()], &b[s.clone()]),
        (
            Some(Packed::Numbers { table: a, range: r }),
            Some(Packed::Numbers { table: b, range: s }),
        ) => a[r.clone()]
            .iter()
            .zip(&b[s.clone()])
            .all(|(x, y)| x.to_bits() == y.to_bits()),
        (
            Some(Packed::Labels {
                table: a,
                range: r,
                labels: la,
            }),
            Some(Packed::Labels {
                table: b,
                range: s,
                labels: lb,
            }),
        ) if Arc::ptr_eq(la, lb) => a[r.clone()] == b[s.clone()],
        _ => x.iter().zip(y.iter()).all(|(p, q)| same(p, q)),
    }
}

fn same_vec(a: DVec3, b: DVec3) -> bool {
    a.x.to_bits() == b.x.to_bits()
        && a.y.to_bits() == b.y.to_bits()
        && a.z.to_bits() == b.z.to_bits()
}

fn same_points(a: &[DVec3], b: &[DVec3]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(p, q)| same_vec(*p, *q))
}

/// A 64-bit hash of a value's content, consistent with [`Value::same_as`]: equal values hash equally.
pub fn content_hash(value: &Value) -> u64 {
    let mut h = FxHasher::default();
    hash_into(value, &mut h);
    h.finish()
}

fn hash_into(value: &Value, h: &mut FxHasher) {
    use Value::*;
    match value {
        Null => h.write_u8(0),
        Number(x) => {
            h.write_u8(1);
            h.write_u64(x.to_bits());
        }
        Integer(i) => {
            h.write_u8(2);
            h.write_i64(*i);
        }
        Boolean(b) => {
            h.write_u8(3);
            h.write_u8(*b as u8);
        }
        Text(s) => {
            h.write_u8(4);
            h.write(s.as_bytes());
            h.write_u8(0xff);
        }
        Point(p) => {
            h.write_u8(5);
            hash_vec(*p, h);
        }
        Vector(v) => {
            h.write_u8(6);
            hash_vec(*v, h);
        }
        Plane(p) => {
            h.write_u8(7);
            for v in [p.origin, p.x_axis, p.y_axis, p.normal] {
                hash_vec(v, h);
            }
        }
        Lines(lines) => {
            h.write_u8(8);
            h.write_usize(lines.len());
            for l in lines.iter() {
                hash_vec(l.start, h);
                hash_vec(l.end, h);
            }
        }
        Polyline(p) => {
            h.write_u8(9);
            h.write_u8(p.closed as u8);
            hash_points(&p.points, h);
        }
        QuadMesh(g) => {
            h.write_u8(10);
            h.write_usize(g.rows);
            h.write_usize(g.cols);
            h.write_u8(g.wrap_rows as u8 | (g.wrap_cols as u8) << 1);
            hash_points(&g.vertices, h);
        }
        Mesh(m) => {
            h.write_u8(11);
            hash_points(&m.vertices, h);
            h.write_usize(m.indices.len());
            for &i in &m.indices {
                h.write_u32(i);
            }
            h.write_usize(m.face_starts.len());
            for &s in &m.face_starts {
                h.write_u32(s);
            }
            h.write_usize(m.parts.names.len());
            for name in &m.parts.names {
                h.write(name.as_bytes());
                h.write_u8(0xff);
            }
            for &p in &m.parts.of_face {
                h.write_u32(p);
            }
        }
        List(items) => {
            h.write_u8(12);
            h.write_usize(items.len());
            // A packed list hashes exactly as its values would, without building them.
            match items.as_packed() {
                Some(Packed::Vectors { table, range }) => {
                    for &p in &table[range.clone()] {
                        hash_into(&Vector(p), h);
                    }
                }
                Some(Packed::Numbers { table, range }) => {
                    for &x in &table[range.clone()] {
                        hash_into(&Number(x), h);
                    }
                }
                Some(Packed::Labels {
                    table,
                    range,
                    labels,
                }) => {
                    for &code in &table[range.clone()] {
                        hash_into(labels.get(code as usize).unwrap_or(&Null), h);
                    }
                }
                None => {
                    for item in items.iter() {
                        hash_into(item, h);
                    }
                }
            }
        }
        Record(r) => {
            h.write_u8(13);
            h.write_usize(r.len());
            for (name, v) in r.fields() {
                h.write(name.as_bytes());
                h.write_u8(0xff);
                hash_into(v, h);
            }
        }
    }
}

fn hash_vec(v: DVec3, h: &mut FxHasher) {
    h.write_u64(v.x.to_bits());
    h.write_u64(v.y.to_bits());
    h.write_u64(v.z.to_bits());
}

fn hash_points(points: &[DVec3], h: &mut FxHasher) {
    h.write_usize(points.len());
    for p in points {
        hash_vec(*p, h);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equal_values_hash_equal_and_bits_matter() {
        let a = Value::list(vec![Value::Number(1.0), Value::Point(DVec3::ONE)]);
        let b = Value::list(vec![Value::Number(1.0), Value::Point(DVec3::ONE)]);
        assert!(a.same_as(&b));
        assert_eq!(content_hash(&a), content_hash(&b));
        let nan = Value::Number(f64::NAN);
        assert!(nan.same_as(&nan.clone()));
        assert!(!Value::Number(0.0).same_as(&Value::Number(-0.0)));
        assert_ne!(
            content_hash(&Value::Number(1.0)),
            content_hash(&Value::Integer(1))
        );
        assert!(!Value::Point(DVec3::ONE).same_as(&Value::Vector(DVec3::ONE)));
    }
}
