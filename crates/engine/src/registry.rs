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

    /// Ids close to `id` (same prefix or small edit distance), for "did you mean" hints.
    pub fn similar_ids(&self, id: &str) -> Vec<&str> {
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

/// Levenshtein distance between two short strings.
pub fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let cur = row[j + 1];
            row[j + 1] = (prev + usize::from(ca != *cb)).min(row[j] + 1).min(cur + 1);
            prev = cur;
        }
    }
    row[b.len()]
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
        r.register(NodeDef::new("curve.arc", "Curves", "Replaced."));
        assert_eq!(r.len(), 2);
        assert_eq!(r.get("curve.arc").unwrap().doc, "Replaced.");
    }
}
