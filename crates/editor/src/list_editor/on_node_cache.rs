//! What literal lists show on their nodes ([`super::on_node`]), kept per input while the list
//! stays the same: the summary and the table check walk every item, and a canvas frame asks for
//! them again (issue 29's 50 MB file: a `param.list` of 3 million numbers took the UI thread
//! 152 ms a frame; with the cache 0.4 ms).

use std::collections::HashMap;

use cnets_engine::{Items, NodeInstance, Value};

use super::{OnNode, describe, shown_value};

/// [`on_node`] remembered per input while its value stays the same list: the summary and the
/// table check walk every item, 150 ms a frame for a `param.list` of 3 million numbers.
#[derive(Default)]
pub struct OnNodeCache {
    entries: HashMap<(String, usize), CachedOnNode>,
    frame: u64,
    described: u64,
}

struct CachedOnNode {
    value: Value,
    shown: OnNode,
    used: u64,
}

/// Frames an entry of an input not drawn (out of view, removed) is kept.
const KEPT_FRAMES: u64 = 600;

impl OnNodeCache {
    /// Starts a frame: forgets entries not used for [`KEPT_FRAMES`] frames.
    pub fn next_frame(&mut self) {
        self.frame += 1;
        let frame = self.frame;
        self.entries.retain(|_, e| frame - e.used <= KEPT_FRAMES);
    }

    /// [`on_node`], computed again only when the input's value changed.
    pub fn on_node(&mut self, node: &NodeInstance, k: usize) -> Option<OnNode> {
        let value = shown_value(node, k)?;
        let key = (node.id.clone(), k);
        if let Some(e) = self.entries.get_mut(&key)
            && same_value(&e.value, &value)
        {
            e.used = self.frame;
            return Some(e.shown.clone());
        }
        let shown = describe(&value);
        self.described += 1;
        self.entries.insert(
            key,
            CachedOnNode {
                value,
                shown: shown.clone(),
                used: self.frame,
            },
        );
        Some(shown)
    }

    /// How many times a value was described (walked) so far.
    pub fn described(&self) -> u64 {
        self.described
    }
}

/// The same value: the same shared list (held by the cache, so its address is not reused), or
/// equal otherwise (a polyline).
fn same_value(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::List(x), Value::List(y)) => Items::ptr_eq(x, y),
        _ => a == b,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;

    #[test]
    fn a_list_is_described_once_until_it_changes() {
        let text = r#"(version: 1, nodes: {
            "data": (type: "param.list", inputs: {"values": [0.5, 0.25, 2.0], "item_type": "number"}),
            "other": (type: "param.list", inputs: {"values": [1.0], "item_type": "number"}),
        })"#;
        let registry = Arc::new(cnets_nodes::registry());
        let mut g = cnets_engine::file::load_str(text, "t.ron", &registry)
            .unwrap()
            .graph;
        let mut cache = OnNodeCache::default();
        let show = |g: &cnets_engine::Graph, cache: &mut OnNodeCache, id: &str| {
            cache.next_frame();
            let n = g.node(id).unwrap();
            let k = n.def.input_index("values").unwrap();
            let shown = cache.on_node(n, k);
            assert_eq!(
                shown,
                super::super::on_node(n, k),
                "the cache shows what on_node does"
            );
            shown.unwrap().summary
        };
        assert_eq!(show(&g, &mut cache, "data"), "3 numbers, 0.25 … 2");
        for _ in 0..5 {
            assert_eq!(show(&g, &mut cache, "data"), "3 numbers, 0.25 … 2");
        }
        assert_eq!(cache.described(), 1, "the same list is walked once");
        show(&g, &mut cache, "other");
        assert_eq!(cache.described(), 2, "each input has its own entry");

        g.set_value("data", "values", Value::list(vec![Value::Number(7.0); 4]))
            .unwrap();
        assert_eq!(show(&g, &mut cache, "data"), "4 numbers, all 7");
        assert_eq!(cache.described(), 3, "a new list is walked again");
        // What is shown depends on the list alone: another item type keeps it.
        g.set_value("data", "item_type", Value::Text("integer".into()))
            .unwrap();
        assert_eq!(show(&g, &mut cache, "data"), "4 numbers, all 7");
        assert_eq!(cache.described(), 3);
        // An input not drawn for a while is forgotten (a removed node's list is let go).
        for _ in 0..=KEPT_FRAMES {
            cache.next_frame();
        }
        show(&g, &mut cache, "data");
        assert_eq!(cache.described(), 4);
    }
}
