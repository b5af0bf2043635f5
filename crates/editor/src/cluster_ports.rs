//! Ports renamed inside an opened cluster.
//!
//! A cluster's ports are its `graph.input` / `graph.output` nodes, named by their `name` input.
//! Renaming one (Rename port in the node's context menu, or typing in its `name` field) is an
//! ordinary edit of the subgraph; when the cluster is rebuilt, the renamed port is recognised by
//! its node's id (stable inside the subgraph) and the cluster node's wires and literal value on
//! the old name move to the new one instead of being dropped.

use std::collections::HashMap;

use cnets_engine::cluster::Interface;
use cnets_engine::{Graph, WireRef};

/// Port names changed between a cluster's subgraph as opened and as edited: old name → new.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Renames {
    /// Renamed inputs.
    pub inputs: HashMap<String, String>,
    /// Renamed outputs.
    pub outputs: HashMap<String, String>,
}

impl Renames {
    /// The ports whose `graph.input` / `graph.output` node (same id) has another name in
    /// `edited` than in `opened`. Empty when either interface is invalid.
    pub fn between(opened: &Graph, edited: &Graph) -> Self {
        let (Ok(before), Ok(after)) = (Interface::of(opened), Interface::of(edited)) else {
            return Self::default();
        };
        let named = |g: &Graph, ports: &[cnets_engine::cluster::InterfacePort]| {
            ports
                .iter()
                .filter_map(|p| Some((g.node_at(p.node)?.id.clone(), p.port.name.to_string())))
                .collect::<HashMap<String, String>>()
        };
        let pairs = |b: HashMap<String, String>, a: HashMap<String, String>| {
            b.into_iter()
                .filter_map(|(id, old)| {
                    let new = a.get(&id)?;
                    (*new != old).then(|| (old, new.clone()))
                })
                .collect::<HashMap<String, String>>()
        };
        Self {
            inputs: pairs(named(opened, &before.inputs), named(edited, &after.inputs)),
            outputs: pairs(
                named(opened, &before.outputs),
                named(edited, &after.outputs),
            ),
        }
    }

    /// Whether no port was renamed.
    pub fn is_empty(&self) -> bool {
        self.inputs.is_empty() && self.outputs.is_empty()
    }

    /// The wire `w` of cluster node `node` with its port renamed, if it was.
    pub fn rename(&self, node: &str, w: &WireRef) -> Option<WireRef> {
        let mut w = w.clone();
        let mut renamed = false;
        if w.to == node
            && let Some(new) = self.inputs.get(&w.input)
        {
            w.input = new.clone();
            renamed = true;
        }
        if w.from == node
            && let Some(new) = self.outputs.get(&w.output)
        {
            w.output = new.clone();
            renamed = true;
        }
        renamed.then_some(w)
    }

    /// After cluster node `node` of `parent` got its new definition: reconnects the `dropped`
    /// wires whose port was renamed and copies the literal values of renamed inputs from
    /// `before` (the graph around the cluster before the rebuild). Returns the wires still
    /// dropped.
    pub fn carry(
        &self,
        parent: &mut Graph,
        node: &str,
        before: &Graph,
        dropped: Vec<WireRef>,
    ) -> Vec<WireRef> {
        if self.is_empty() {
            return dropped;
        }
        if let Some(old) = before.node(node) {
            for (from, to) in &self.inputs {
                if let Some(v) = old.value_of(from) {
                    let _ = parent.set_value(node, to, v.clone());
                }
            }
        }
        dropped
            .into_iter()
            .filter(|w| match self.rename(node, w) {
                Some(r) => parent.connect(&r.from, &r.output, &r.to, &r.input).is_err(),
                None => true,
            })
            .collect()
    }
}

/// Whether `name` can name a cluster port (letters, digits and `_`).
pub fn valid_port_name(name: &str) -> bool {
    cnets_engine::graph::valid_id(name) && !name.contains('-')
}
