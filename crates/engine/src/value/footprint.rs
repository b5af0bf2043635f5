//! How much memory values take, for the memory budget (`crate::budget`).
//!
//! Values share their payloads behind `Arc`s, so a list can *read* as far more than it *holds*: a
//! list of the same list twice, 25 times over, reads as 2²⁵ items but holds 26 small lists. A
//! [`Footprint`] tells both:
//!
//! - `owned_bytes`: the memory the values hold and nothing else holds — each shared payload counted
//!   once, and only when every handle to it is inside these values (a node passing its input
//!   through owns none of it: the source node's result does). Summed over an evaluator's results
//!   this is the live memory of the evaluation.
//! - `read_values`: how many values a full read of them visits (a list counts its items, nested
//!   lists theirs, shared lists every time they appear). What reads every value — the JSON writer, a
//!   flatten, an export — needs about that many values' memory.
//!
//! Both walk each shared list once (a memo by address), so the cost is linear in what is held,
//! however far it fans out.

use std::collections::hash_map::Entry;

use rustc_hash::{FxHashMap, FxHashSet};

use super::Value;

/// Memory held and values read by some values.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Footprint {
    /// Bytes held by these values only (shared payloads once, payloads held elsewhere not at all).
    pub owned_bytes: u64,
    /// Values visited by a full read (shared lists counted every time they appear).
    pub read_values: u128,
}

/// One shared payload: handles to it from inside the values, handles in all, and its bytes.
#[derive(Debug, Clone, Copy)]
struct Shared {
    seen: usize,
    strong: usize,
    bytes: u64,
    reads: u128,
}

/// The footprint of `values` (e.g. the outputs of one node run).
pub fn footprint(values: &[Value]) -> Footprint {
    let mut meter = Meter::default();
    let read_values = values
        .iter()
        .fold(0u128, |n, v| n.saturating_add(meter.reads(v)));
    let owned_bytes = values
        .iter()
        .fold(0u64, |b, v| b.saturating_add(meter.owned(v)));
    Footprint {
        owned_bytes,
        read_values,
    }
}

const VALUE: u64 = std::mem::size_of::<Value>() as u64;

#[derive(Default)]
struct Meter {
    /// Keyed by address: a fast hash (addresses are not chosen by an attacker, and a construction's
    /// outputs are thousands of shared rows).
    shared: FxHashMap<usize, Shared>,
    counted: FxHashSet<usize>,
}

impl Meter {
    /// Registers one handle to a shared payload; true on its first sighting. A payload with one
    /// handle (the many rows, texts and meshes a node makes for itself) can only be this one: it
    /// is not recorded.
    fn sight(&mut self, ptr: usize, strong: usize, bytes: u64) -> bool {
        if strong == 1 {
            return true;
        }
        match self.shared.entry(ptr) {
            Entry::Occupied(mut e) => {
                e.get_mut().seen += 1;
                false
            }
            Entry::Vacant(e) => {
                e.insert(Shared {
                    seen: 1,
                    strong,
                    bytes,
                    reads: 0,
                });
                true
            }
        }
    }

    /// First pass: values read under `v`, and every handle to a shared payload registered.
    fn reads(&mut self, v: &Value) -> u128 {
        match v {
            Value::List(items) => {
                let (ptr, strong) = items.sharing();
                if !self.sight(ptr, strong, items.len() as u64 * VALUE) {
                    return 1 + self.shared[&ptr].reads;
                }
                let reads = match items.plain_values() {
                    Some(values) => values
                        .iter()
                        .fold(0u128, |n, v| n.saturating_add(self.reads(v))),
                    None => {
                        if let Some(packed) = items.as_packed() {
                            let (table, strong, bytes) = packed.table_sharing();
                            self.sight(table, strong, bytes);
                        }
                        items.len() as u128
                    }
                };
                if let Some(e) = self.shared.get_mut(&ptr) {
                    e.reads = reads;
                }
                1 + reads
            }
            Value::Record(r) => {
                let ptr = std::sync::Arc::as_ptr(r) as *const u8 as usize;
                let bytes = r.len() as u64 * (VALUE + 32);
                if self.sight(ptr, std::sync::Arc::strong_count(r), bytes) {
                    let reads = r
                        .fields()
                        .iter()
                        .fold(0u128, |n, (_, v)| n.saturating_add(self.reads(v)));
                    if let Some(e) = self.shared.get_mut(&ptr) {
                        e.reads = reads;
                    }
                    return 1 + reads;
                }
                1 + self.shared[&ptr].reads
            }
            other => {
                if let Some((ptr, strong, bytes)) = payload(other) {
                    self.sight(ptr, strong, bytes);
                }
                1
            }
        }
    }

    /// The bytes of a payload (`(address, handles, bytes)`) held only from inside the values, once.
    fn owns(&mut self, (ptr, strong, bytes): (usize, usize, u64)) -> Option<u64> {
        if strong == 1 {
            return Some(bytes);
        }
        let s = *self.shared.get(&ptr)?;
        if s.seen < s.strong || !self.counted.insert(ptr) {
            return None;
        }
        Some(s.bytes)
    }

    /// Second pass: bytes under `v` owned by the values (not descending into payloads held
    /// elsewhere, nor into one already counted).
    fn owned(&mut self, v: &Value) -> u64 {
        match v {
            Value::List(items) => {
                let (ptr, strong) = items.sharing();
                let Some(mut bytes) = self.owns((ptr, strong, items.len() as u64 * VALUE)) else {
                    return 0;
                };
                if let Some(values) = items.plain_values() {
                    for v in values {
                        bytes = bytes.saturating_add(self.owned(v));
                    }
                } else if let Some(packed) = items.as_packed() {
                    bytes = bytes.saturating_add(self.owns(packed.table_sharing()).unwrap_or(0));
                    if items.built_values().is_some() {
                        bytes = bytes.saturating_add(items.len() as u64 * VALUE);
                    }
                }
                bytes
            }
            Value::Record(r) => {
                let record = (
                    std::sync::Arc::as_ptr(r) as *const u8 as usize,
                    std::sync::Arc::strong_count(r),
                    r.len() as u64 * (VALUE + 32),
                );
                let Some(mut bytes) = self.owns(record) else {
                    return 0;
                };
                for (_, v) in r.fields() {
                    bytes = bytes.saturating_add(self.owned(v));
                }
                bytes
            }
            other => payload(other).and_then(|p| self.owns(p)).unwrap_or(0),
        }
    }
}

/// The shared payload of a leaf value: address, handles, bytes.
fn payload(v: &Value) -> Option<(usize, usize, u64)> {
    use std::sync::Arc;
    fn of<T: ?Sized>(a: &Arc<T>, bytes: usize) -> (usize, usize, u64) {
        (
            Arc::as_ptr(a) as *const u8 as usize,
            Arc::strong_count(a),
            bytes as u64,
        )
    }
    const P: usize = std::mem::size_of::<glam::DVec3>();
    Some(match v {
        Value::Text(t) => of(t, t.len()),
        Value::Plane(p) => of(p, std::mem::size_of_val(&**p)),
        Value::Lines(l) => of(
            l,
            l.capacity() * std::mem::size_of::<cnets_geometry::Line>(),
        ),
        Value::Polyline(p) => of(p, p.points.capacity() * P),
        Value::QuadMesh(m) => of(m, m.vertices.capacity() * P),
        Value::Mesh(m) => of(
            m,
            m.vertices.capacity() * P
                + (m.indices.capacity() + m.face_starts.capacity() + m.parts.of_face.capacity())
                    * 4,
        ),
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn a_fresh_list_of_numbers_holds_its_slots() {
        let v = Value::list((0..100).map(|k| Value::Number(k as f64)).collect());
        let f = footprint(std::slice::from_ref(&v));
        assert_eq!(f.owned_bytes, 100 * VALUE);
        assert_eq!(f.read_values, 101);
    }

    #[test]
    fn a_list_shared_many_times_over_is_held_once_and_read_every_time() {
        let mut v = Value::list(vec![Value::Number(1.0); 4]);
        for _ in 0..40 {
            v = Value::list(vec![v.clone(), v]);
        }
        let f = footprint(std::slice::from_ref(&v));
        assert_eq!(f.owned_bytes, 4 * VALUE + 40 * 2 * VALUE);
        assert!(f.read_values > 1u128 << 42, "{}", f.read_values);
    }

    #[test]
    fn payloads_held_elsewhere_are_not_owned() {
        let mesh = Value::Polyline(std::sync::Arc::new(cnets_geometry::Polyline::open(vec![
            DVec3::ZERO;
            1000
        ])));
        let kept = mesh.clone();
        let through = footprint(std::slice::from_ref(&mesh));
        assert_eq!(through.owned_bytes, 0);
        drop(kept);
        let own = footprint(std::slice::from_ref(&mesh));
        assert_eq!(own.owned_bytes, 24_000);
        let twice = footprint(&[mesh.clone(), mesh]);
        assert_eq!(twice.owned_bytes, 24_000);
    }
}
