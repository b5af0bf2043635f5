//! Copy, paste and duplicate: nodes with their values, flags, relative positions and wires.

use std::sync::Arc;

use cnets_engine::cluster::Cluster;
use cnets_engine::{Graph, NodeDef, Value};

use crate::document::fresh_id;

/// Copied nodes: definitions, values, flags, relative positions and wires.
#[derive(Clone, Debug, Default)]
pub struct Clipboard {
    nodes: Vec<ClipNode>,
    /// Wires between copied nodes, by index into `nodes`: (from, output, to, input).
    inner: Vec<(usize, String, usize, String)>,
    /// Wires from outside into copied nodes: (from id, output, to index, input).
    incoming: Vec<(String, String, usize, String)>,
}

#[derive(Clone, Debug)]
struct ClipNode {
    id: String,
    def: Arc<NodeDef>,
    values: Vec<(String, Value)>,
    position: [f32; 2],
    preview: bool,
    enabled: bool,
}

impl Clipboard {
    /// Copies the nodes `ids` of `graph` (unknown ids are skipped).
    pub fn copy(graph: &Graph, ids: &[String]) -> Self {
        let nodes: Vec<ClipNode> = ids
            .iter()
            .filter_map(|id| graph.node(id))
            .map(|n| ClipNode {
                id: n.id.clone(),
                def: n.def.clone(),
                values: n
                    .def
                    .inputs
                    .iter()
                    .enumerate()
                    .filter_map(|(k, p)| n.value(k).map(|v| (p.name.to_string(), v.clone())))
                    .collect(),
                position: n.position,
                preview: n.preview,
                enabled: n.enabled,
            })
            .collect();
        let index = |id: &str| nodes.iter().position(|n| n.id == id);
        let mut inner = Vec::new();
        let mut incoming = Vec::new();
        for w in graph.wires() {
            match (index(&w.from), index(&w.to)) {
                (Some(a), Some(b)) => inner.push((a, w.output, b, w.input)),
                (None, Some(b)) => incoming.push((w.from, w.output, b, w.input)),
                _ => {}
            }
        }
        Self {
            nodes,
            inner,
            incoming,
        }
    }

    /// How many nodes were copied.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether nothing was copied.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Adds the copied nodes to `graph` under fresh ids, shifted by `offset`, with their inner
    /// wires (and, when `keep_incoming`, the wires from nodes outside the copy that still exist).
    /// Returns the new ids.
    pub fn paste(
        &self,
        graph: &mut Graph,
        offset: [f32; 2],
        keep_incoming: bool,
    ) -> Result<Vec<String>, String> {
        let err = |e: cnets_engine::GraphError| e.to_string();
        let mut new_ids = Vec::new();
        for n in &self.nodes {
            let id = fresh_id(graph, &n.id);
            // A pasted cluster gets its own instance, so the two cache separately.
            let def = match Cluster::shared(&n.def) {
                Some(c) => Arc::new(c.duplicate().node_def()),
                None => n.def.clone(),
            };
            graph.add_node_with_def(&id, def).map_err(err)?;
            for (input, value) in &n.values {
                graph.set_value(&id, input, value.clone()).map_err(err)?;
            }
            graph
                .set_position(&id, [n.position[0] + offset[0], n.position[1] + offset[1]])
                .map_err(err)?;
            graph.set_preview(&id, n.preview).map_err(err)?;
            graph.set_enabled(&id, n.enabled).map_err(err)?;
            new_ids.push(id);
        }
        for (a, output, b, input) in &self.inner {
            graph
                .connect(&new_ids[*a], output, &new_ids[*b], input)
                .map_err(err)?;
        }
        if keep_incoming {
            for (from, output, b, input) in &self.incoming {
                if graph.node(from).is_some() {
                    graph
                        .connect(from, output, &new_ids[*b], input)
                        .map_err(err)?;
                }
            }
        }
        Ok(new_ids)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::app::DEFAULT_GRAPH;

    #[test]
    fn duplicate_keeps_values_inner_wires_and_incoming_wires() {
        let registry = Arc::new(cnets_nodes::registry());
        let d = cnets_engine::file::load_str(DEFAULT_GRAPH, "default", &registry).unwrap();
        let mut g = d.graph;
        let clip = Clipboard::copy(&g, &["construct".to_string(), "planarity".to_string()]);
        let ids = clip.paste(&mut g, [10.0, 10.0], true).unwrap();
        assert_eq!(
            ids,
            vec!["construct_2".to_string(), "planarity_2".to_string()]
        );
        let wires = g.wires();
        assert!(
            wires
                .iter()
                .any(|w| w.from == "construct_2" && w.to == "planarity_2")
        );
        assert!(
            wires
                .iter()
                .any(|w| w.from == "directrix" && w.to == "construct_2")
        );
        let mut g2 = g.clone();
        let ids = clip.paste(&mut g2, [10.0, 10.0], false).unwrap();
        assert!(
            !g2.wires().iter().any(|w| w.to == ids[0]),
            "paste does not keep incoming wires"
        );
    }

    #[test]
    fn a_pasted_cluster_gets_its_own_instance() {
        let registry = Arc::new(cnets_nodes::registry());
        let d = cnets_engine::file::load_str(DEFAULT_GRAPH, "default", &registry).unwrap();
        let mut g = d.graph;
        cnets_engine::cluster::make_cluster(&mut g, &["apex", "ratio"], "c").unwrap();
        let clip = Clipboard::copy(&g, &["c".to_string()]);
        let ids = clip.paste(&mut g, [10.0, 10.0], false).unwrap();
        let a = Cluster::shared(&g.node("c").unwrap().def).unwrap();
        let b = Cluster::shared(&g.node(&ids[0]).unwrap().def).unwrap();
        assert!(!Arc::ptr_eq(&a, &b), "separate instances (separate caches)");
        assert_eq!(
            cnets_engine::file::to_ron(&a.template, &a.meta),
            cnets_engine::file::to_ron(&b.template, &b.meta)
        );
    }
}
