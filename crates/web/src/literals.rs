//! Large literal values cross to the evaluation worker once (docs/web.md, "Large files").
//!
//! Every evaluation request carries the graph to the worker as RON text. A graph holding a list
//! of millions of numbers would be written out on the page and parsed again in the worker on every
//! edit — seconds each time, most of it on the page's thread. Instead, the page sends each large
//! literal once in the wire's binary value encoding under a key ([`LiteralCache`]); the request's
//! RON leaves that input unset and names the key ([`LiteralRef`]); the worker keeps the values
//! ([`LiteralStore`]) and puts them back into the graph it parsed before evaluating it.
//!
//! A literal is recognised again by its shared payload (the graph's values are reference-counted:
//! an edit elsewhere, a node moved, undo, keep the same list), so an unchanged list is never
//! encoded again. Literals no request refers to any more are forgotten on both sides. Literals
//! inside cluster definitions travel in the RON as before.

use cnets_engine::{Graph, Items, Value};

/// A list or polyline with at least this many items (points) is sent by reference.
pub const LARGE_LITERAL_ITEMS: usize = 10_000;

/// A text of at least this many bytes is sent by reference.
pub const LARGE_LITERAL_TEXT: usize = 64 << 10;

/// Lists nest at most this deep in a literal sent by reference (the wire's own limit).
const MAX_DEPTH: usize = 32;

/// Keys the worker gives the literals of files it reads for the page start here (the page's own
/// keys count from 0).
pub const WORKER_KEYS: u64 = 1 << 63;

/// An input whose literal value the worker holds under `key`.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct LiteralRef {
    /// The node's id.
    pub node: String,
    /// The input's name.
    pub input: String,
    /// The value's key.
    pub key: u64,
}

/// A graph prepared for the worker: its large literals taken out.
pub struct Split {
    /// The graph without its large literals (the RON the request carries); `None`: the graph
    /// has none, send it as it is.
    pub skeleton: Option<Graph>,
    /// Where each large literal goes back.
    pub refs: Vec<LiteralRef>,
    /// Literals the worker does not have yet: send them before the request.
    pub new: Vec<(u64, Value)>,
    /// Keys no request refers to any more: the worker may drop them.
    pub forget: Vec<u64>,
}

/// The page's side: the large literals the worker holds, by key.
#[derive(Default)]
pub struct LiteralCache {
    /// Each value is kept (a handle to its payload), so its payload is not freed and its address
    /// not reused while the key names it.
    held: Vec<(u64, Value)>,
    next_key: u64,
    /// Values encoded and sent so far (for the browser test and the tests below).
    pub sent: u64,
}

impl LiteralCache {
    /// Takes `graph`'s large literals out, naming each by a key the worker knows or will be sent.
    pub fn split(&mut self, graph: &Graph) -> Split {
        let mut refs = Vec::new();
        let mut new = Vec::new();
        let mut used = Vec::new();
        for (_, node) in graph.nodes() {
            for (k, port) in node.def.inputs.iter().enumerate() {
                let Some(value) = node.value(k) else { continue };
                let held = self.held.iter().find(|(_, v)| same_payload(v, value));
                let key = match held {
                    Some((key, _)) => *key,
                    None if is_large(value) && encodable(value, 0) => {
                        let key = self.next_key;
                        self.next_key += 1;
                        self.held.push((key, value.clone()));
                        new.push((key, value.clone()));
                        self.sent += 1;
                        key
                    }
                    None => continue,
                };
                used.push(key);
                refs.push(LiteralRef {
                    node: node.id.clone(),
                    input: port.name.to_string(),
                    key,
                });
            }
        }
        let mut forget = Vec::new();
        self.held.retain(|(key, _)| {
            let keep = used.contains(key);
            if !keep {
                forget.push(*key);
            }
            keep
        });
        let skeleton = (!refs.is_empty()).then(|| {
            let mut skeleton = graph.clone();
            for r in &refs {
                // The node and input were read from this graph: clearing cannot fail.
                let _ = skeleton.clear_value(&r.node, &r.input);
            }
            skeleton
        });
        Split {
            skeleton,
            refs,
            new,
            forget,
        }
    }

    /// Takes on a literal the worker already holds under `key` (from a file it read for the page:
    /// `value` is the one the page's graph holds). A literal no request names is forgotten by the
    /// next request, as usual.
    pub fn adopt(&mut self, key: u64, value: Value) {
        self.held.retain(|(k, _)| *k != key);
        self.held.push((key, value));
    }

    /// Forgets every key (a new worker starts with none).
    pub fn clear(&mut self) {
        self.held.clear();
    }

    /// How many literals the worker holds.
    pub fn len(&self) -> usize {
        self.held.len()
    }

    /// True when the worker holds none.
    pub fn is_empty(&self) -> bool {
        self.held.is_empty()
    }
}

/// The worker's side: the literal values the page sent, by key.
#[derive(Default)]
pub struct LiteralStore {
    values: Vec<(u64, Value)>,
    /// The next key for a literal of a file read for the page (after [`WORKER_KEYS`]).
    next_key: u64,
}

impl LiteralStore {
    /// Takes the large literals out of `graph` (a file read for the page), keeping each under a
    /// new key: where each goes and its value, for the page.
    pub fn take_out(&mut self, graph: &mut Graph) -> Vec<(LiteralRef, Value)> {
        let mut taken = Vec::new();
        for (_, node) in graph.nodes() {
            for (k, port) in node.def.inputs.iter().enumerate() {
                let Some(value) = node.value(k) else { continue };
                if !(is_large(value) && encodable(value, 0)) {
                    continue;
                }
                let key = WORKER_KEYS + self.next_key;
                self.next_key += 1;
                let at = LiteralRef {
                    node: node.id.clone(),
                    input: port.name.to_string(),
                    key,
                };
                taken.push((at, value.clone()));
            }
        }
        for (at, value) in &taken {
            // The node and input were read from this graph: clearing cannot fail.
            let _ = graph.clear_value(&at.node, &at.input);
            self.remember(at.key, value.clone());
        }
        taken
    }

    /// Keeps `value` under `key`.
    pub fn remember(&mut self, key: u64, value: Value) {
        self.values.retain(|(k, _)| *k != key);
        self.values.push((key, value));
    }

    /// Drops the values of `keys`.
    pub fn forget(&mut self, keys: &[u64]) {
        self.values.retain(|(k, _)| !keys.contains(k));
    }

    /// How many values are kept.
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// True when none are kept.
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }

    /// Puts the values `refs` name back into `graph` (parsed from a request's RON).
    pub fn restore(&self, graph: &mut Graph, refs: &[LiteralRef]) -> Result<(), String> {
        for r in refs {
            let value = self
                .values
                .iter()
                .find(|(k, _)| *k == r.key)
                .map(|(_, v)| v.clone())
                .ok_or_else(|| {
                    format!(
                        "the value of {}.{} was not received (literal {})",
                        r.node, r.input, r.key
                    )
                })?;
            graph
                .set_value(&r.node, &r.input, value)
                .map_err(|e| e.to_string())?;
        }
        Ok(())
    }
}

/// Whether `a` and `b` share their payload (the same list, text or polyline, not merely equal).
fn same_payload(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::List(x), Value::List(y)) => Items::ptr_eq(x, y),
        (Value::Text(x), Value::Text(y)) => std::sync::Arc::ptr_eq(x, y),
        (Value::Polyline(x), Value::Polyline(y)) => std::sync::Arc::ptr_eq(x, y),
        _ => false,
    }
}

/// Whether a literal is large enough to be sent by reference.
pub fn is_large(value: &Value) -> bool {
    match value {
        Value::Text(t) => t.len() >= LARGE_LITERAL_TEXT,
        Value::Polyline(p) => p.points.len() >= LARGE_LITERAL_ITEMS,
        Value::List(_) => {
            let mut count = 0;
            counts_at_least(value, LARGE_LITERAL_ITEMS, &mut count)
        }
        _ => false,
    }
}

/// Counts `value`'s items (a list's leaves, a polyline's points) until `limit` is reached.
fn counts_at_least(value: &Value, limit: usize, count: &mut usize) -> bool {
    match value {
        Value::List(items) => {
            if let Some(packed) = items.as_packed() {
                *count += packed.len();
                return *count >= limit;
            }
            let items = value.as_list().unwrap_or(&[]);
            items.iter().any(|item| counts_at_least(item, limit, count))
        }
        Value::Polyline(p) => {
            *count += p.points.len();
            *count >= limit
        }
        _ => {
            *count += 1;
            *count >= limit
        }
    }
}

/// Whether the wire's value encoding carries `value` exactly (it carries numbers, integers,
/// truth values, texts, points, vectors, polylines and lists of them).
pub fn encodable(value: &Value, depth: usize) -> bool {
    match value {
        Value::Null
        | Value::Number(_)
        | Value::Integer(_)
        | Value::Boolean(_)
        | Value::Text(_)
        | Value::Point(_)
        | Value::Vector(_)
        | Value::Polyline(_) => true,
        Value::List(_) => {
            depth < MAX_DEPTH
                && value
                    .as_list()
                    .unwrap_or(&[])
                    .iter()
                    .all(|item| encodable(item, depth + 1))
        }
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;

    fn numbers(n: usize) -> Value {
        Value::list((0..n).map(|k| Value::Number(k as f64 * 0.5)).collect())
    }

    fn graph_with(values: Value) -> Graph {
        let mut g = Graph::new(Arc::new(cnets_nodes::registry()));
        g.add_node("big", "param.list").unwrap();
        g.set_value("big", "values", values).unwrap();
        g.add_node("small", "param.list").unwrap();
        g.set_value("small", "values", numbers(3)).unwrap();
        g
    }

    #[test]
    fn a_large_list_is_sent_once_and_referred_to_afterwards() {
        let mut cache = LiteralCache::default();
        let mut g = graph_with(numbers(LARGE_LITERAL_ITEMS));
        let first = cache.split(&g);
        assert_eq!(first.new.len(), 1, "the large list is sent");
        assert_eq!(
            first.refs,
            [LiteralRef {
                node: "big".into(),
                input: "values".into(),
                key: 0
            }]
        );
        let skeleton = first.skeleton.expect("a skeleton");
        assert!(skeleton.node("big").unwrap().value_of("values").is_none());
        assert_eq!(
            skeleton.node("small").unwrap().value_of("values"),
            Some(&numbers(3)),
            "small literals stay in the RON"
        );
        // An edit elsewhere and a node moved keep the list: nothing is sent again.
        g.set_value("small", "values", numbers(4)).unwrap();
        g.set_position("big", [40.0, 0.0]).unwrap();
        let again = cache.split(&g);
        assert!(again.new.is_empty() && again.forget.is_empty());
        assert_eq!(again.refs, first.refs);
        assert_eq!(cache.sent, 1);
        // A changed list is a new literal; the old key is forgotten.
        g.set_value("big", "values", numbers(LARGE_LITERAL_ITEMS + 1))
            .unwrap();
        let changed = cache.split(&g);
        assert_eq!(changed.new.len(), 1);
        assert_eq!(changed.forget, [0]);
        assert_eq!(changed.refs[0].key, 1);
        assert_eq!(cache.len(), 1);
    }

    #[test]
    fn a_graph_without_large_literals_is_sent_as_it_is() {
        let mut cache = LiteralCache::default();
        let split = cache.split(&graph_with(numbers(LARGE_LITERAL_ITEMS - 1)));
        assert!(split.skeleton.is_none() && split.refs.is_empty() && split.new.is_empty());
        assert!(cache.is_empty());
    }

    #[test]
    fn nested_lists_count_their_leaves() {
        let rows = |n: usize| Value::list((0..n).map(|_| numbers(100)).collect());
        assert!(is_large(&rows(LARGE_LITERAL_ITEMS / 100)));
        assert!(!is_large(&rows(LARGE_LITERAL_ITEMS / 100 - 1)));
        assert!(is_large(&Value::text("x".repeat(LARGE_LITERAL_TEXT))));
        assert!(!is_large(&Value::Number(1.0)));
    }

    #[test]
    fn a_file_read_by_the_worker_hands_its_literals_to_the_page_once() {
        let big = numbers(LARGE_LITERAL_ITEMS);
        let mut read = graph_with(big.clone());
        let mut store = LiteralStore::default();
        let taken = store.take_out(&mut read);
        assert_eq!(taken.len(), 1);
        assert!(taken[0].0.key >= WORKER_KEYS);
        assert!(read.node("big").unwrap().value_of("values").is_none());
        assert!(read.node("small").unwrap().value_of("values").is_some());
        // The page puts the value into its graph and adopts the key: its first request names the
        // literal and sends nothing.
        let mut page = read.clone();
        let (at, value) = taken.into_iter().next().unwrap();
        page.set_value(&at.node, &at.input, value).unwrap();
        let mut cache = LiteralCache::default();
        cache.adopt(
            at.key,
            page.node("big")
                .unwrap()
                .value_of("values")
                .unwrap()
                .clone(),
        );
        let split = cache.split(&page);
        assert!(split.new.is_empty() && split.forget.is_empty());
        assert_eq!(split.refs, [at]);
        let mut worker = split.skeleton.unwrap();
        store.restore(&mut worker, &split.refs).unwrap();
        assert_eq!(worker.node("big").unwrap().value_of("values"), Some(&big));
    }

    #[test]
    fn the_store_puts_the_values_back_and_names_a_missing_one() {
        let big = numbers(LARGE_LITERAL_ITEMS);
        let g = graph_with(big.clone());
        let mut cache = LiteralCache::default();
        let split = cache.split(&g);
        let mut store = LiteralStore::default();
        for (key, value) in split.new {
            store.remember(key, value);
        }
        let mut parsed = split.skeleton.unwrap();
        store.restore(&mut parsed, &split.refs).unwrap();
        assert_eq!(parsed.node("big").unwrap().value_of("values"), Some(&big));
        store.forget(&[0]);
        assert!(store.is_empty());
        let e = store.restore(&mut parsed, &split.refs).unwrap_err();
        assert!(e.contains("big.values"), "{e}");
    }
}
