//! The registry of node types, looked up by id.

use std::collections::HashMap;
use std::sync::Arc;

use crate::node::NodeDef;

/// All known node types, in registration order, looked up by id.
#[derive(Debug, Default, Clone)]
pub struct Registry {
    defs: Vec<Arc<NodeDef>>,
    by_id: HashMap<String, usize>,
}

impl Registry {
    /// An empty registry.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a node type; a later registration with the same id replaces the earlier one.
    pub fn register(&mut self, def: NodeDef) -> &mut Self {
        let def = Arc::new(def);
        match self.by_id.get(def.id.as_ref()) {
            Some(&k) => self.defs[k] = def,
            None => {
                self.by_id.insert(def.id.to_string(), self.defs.len());
                self.defs.push(def);
            }
        }
        self
    }

    /// The node type with this id.
    pub fn get(&self, id: &str) -> Option<&Arc<NodeDef>> {
        self.by_id.get(id).map(|&k| &self.defs[k])
    }

    /// All node types in registration order.
    pub fn iter(&self) -> impl Iterator<Item = &Arc<NodeDef>> + '_ {
        self.defs.iter()
    }

    /// Number of node types.
    pub fn len(&self) -> usize {
        self.defs.len()
    }

    /// True when nothing is registered.
    pub fn is_empty(&self) -> bool {
        self.defs.is_empty()
    }

    /// Ids close to `id` (same prefix or small edit distance), for "did you mean" hints. A name
    /// longer than [`MAX_SIMILAR`] characters is like none (the search is bounded: a 10⁷-character
    /// name took minutes and gigabytes of edit-distance tables).
    pub fn similar_ids(&self, id: &str) -> Vec<&str> {
        if id.chars().nth(MAX_SIMILAR).is_some() {
            return Vec::new();
        }
        let mut scored: Vec<(usize, &str)> = self
            .defs
            .iter()
            .map(|d| (edit_distance(id, &d.id), d.id.as_ref()))
            .filter(|(dist, other)| {
                *dist <= (id.chars().count() / 4).max(1) || other.starts_with(id)
            })
            .collect();
        scored.sort();
        scored.into_iter().take(3).map(|(_, s)| s).collect()
    }
}

/// The longest name a "did you mean" search compares (registered ids are far shorter).
pub const MAX_SIMILAR: usize = 64;

/// Edit distance counting insertions, deletions, substitutions and swaps of neighbours (optimal
/// string alignment), so that the common typo `nmu` for `num` counts as one edit.
pub fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let w = b.len() + 1;
    let mut d = vec![0usize; (a.len() + 1) * w];
    for i in 0..=a.len() {
        for j in 0..=b.len() {
            d[i * w + j] = if i == 0 || j == 0 {
                i + j
            } else {
                let cost = usize::from(a[i - 1] != b[j - 1]);
                let mut best = (d[(i - 1) * w + j] + 1)
                    .min(d[i * w + j - 1] + 1)
                    .min(d[(i - 1) * w + j - 1] + cost);
                if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                    best = best.min(d[(i - 2) * w + j - 2] + 1);
                }
                best
            };
        }
    }
    d[a.len() * w + b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lookup_and_suggestions() {
        let mut r = Registry::new();
        r.register(NodeDef::new("curve.arc", "Curves", "An arc."));
        r.register(NodeDef::new("curve.line", "Curves", "A line."));
        assert_eq!(r.get("curve.arc").unwrap().doc, "An arc.");
        assert!(r.get("curve.arcs").is_none());
        assert_eq!(r.similar_ids("curve.arcs"), vec!["curve.arc"]);
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("t.nmu", "t.num"), 1);
        assert!(r.similar_ids(&"curve.arc".repeat(1_000_000)).is_empty());
        r.register(NodeDef::new("curve.arc", "Curves", "Replaced."));
        assert_eq!(r.len(), 2);
        assert_eq!(r.get("curve.arc").unwrap().doc, "Replaced.");
    }
}
