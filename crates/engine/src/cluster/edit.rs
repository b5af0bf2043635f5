//! Turning a selection into a cluster, and exploding a cluster back into its nodes.

use std::collections::HashSet;
use std::sync::Arc;

use petgraph::stable_graph::NodeIndex;

use super::instance::{Cluster, ClusterSource};
use super::interface::{INPUT_TYPE, OUTPUT_TYPE};
use crate::file::GraphMeta;
use crate::graph::{Graph, GraphError, WireRef};
use crate::value::Value;

/// Why a cluster edit failed.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ClusterEditError {
    /// A graph operation failed.
    #[error(transparent)]
    Graph(#[from] GraphError),
    /// The selection is empty.
    #[error("select at least one node to make a cluster")]
    EmptySelection,
    /// The node is not a cluster.
    #[error("node '{0}' is not a cluster")]
    NotACluster(String),
    /// The subgraph's interface is invalid.
    #[error("invalid cluster interface: {0}")]
    Interface(String),
}

/// Copies a node (type, literal values, flags, position) from one graph into another under `new_id`.
fn copy_node(
    from: &Graph,
    index: NodeIndex,
    to: &mut Graph,
    new_id: &str,
) -> Result<(), GraphError> {
    let Some(node) = from.node_at(index) else {
        return Ok(());
    };
    to.add_node_with_def(new_id, node.def.clone())?;
    for (k, port) in node.def.inputs.iter().enumerate() {
        if let Some(v) = node.value(k) {
            to.set_value(new_id, &port.name, v.clone())?;
        }
    }
    to.set_position(new_id, node.position)?;
    to.set_preview(new_id, node.preview)?;
    to.set_color(new_id, node.color)?;
    to.set_name(new_id, node.name.clone())?;
    to.set_enabled(new_id, node.enabled)?;
    Ok(())
}

/// Port names that say nothing about what a port carries (`value`, `value_2` told a designer
/// nothing): a cluster port is named after the other end of its wire instead.
const GENERIC_NAMES: &[&str] = &["value", "result", "out", "output", "input"];

/// The first of `candidates` that is a valid, meaningful port name (else the first).
fn telling_name<'a>(candidates: &[&'a str]) -> &'a str {
    candidates
        .iter()
        .copied()
        .find(|c| !GENERIC_NAMES.contains(c) && crate::graph::valid_id(c))
        .unwrap_or(candidates[0])
}

fn unique(name: &str, taken: &mut HashSet<String>) -> String {
    let mut candidate = name.to_string();
    let mut k = 2;
    while taken.contains(&candidate) {
        candidate = format!("{name}_{k}");
        k += 1;
    }
    taken.insert(candidate.clone());
    candidate
}

/// Replaces the `selection` by one inline cluster node `cluster_id`; wires crossing the selection
/// become the cluster's inputs (one per outside source) and outputs (one per inside source),
/// named after what they carry: the inner input fed (an output: the inner output), or — when
/// that name says nothing (`value`, `result`, `out`) — the other end of the wire, made unique.
/// Returns the cluster.
pub fn make_cluster(
    graph: &mut Graph,
    selection: &[&str],
    cluster_id: &str,
) -> Result<Arc<Cluster>, ClusterEditError> {
    if selection.is_empty() {
        return Err(ClusterEditError::EmptySelection);
    }
    if graph.node(cluster_id).is_some() && !selection.contains(&cluster_id) {
        return Err(GraphError::DuplicateId(cluster_id.to_string()).into());
    }
    if !crate::graph::valid_id(cluster_id) {
        return Err(GraphError::InvalidId(cluster_id.to_string()).into());
    }
    let inside: HashSet<String> = selection.iter().map(|s| s.to_string()).collect();
    let mut members: Vec<(NodeIndex, u64)> = Vec::new();
    for id in selection {
        let index = graph.index(id)?;
        members.push((index, graph.node_at(index).map_or(0, |n| n.uid())));
    }
    members.sort_by_key(|m| m.1);

    let mut sub = Graph::new(graph.registry().clone());
    for &(index, _) in &members {
        let id = graph
            .node_at(index)
            .map(|n| n.id.clone())
            .unwrap_or_default();
        copy_node(graph, index, &mut sub, &id)?;
    }
    let wires = graph.wires();
    let (mut x_min, mut x_max, mut y_sum) = (f32::MAX, f32::MIN, 0.0f32);
    for &(index, _) in &members {
        let p = graph.node_at(index).map_or([0.0, 0.0], |n| n.position);
        x_min = x_min.min(p[0]);
        x_max = x_max.max(p[0]);
        y_sum += p[1];
    }
    let y_mean = y_sum / members.len() as f32;

    let mut names_in = HashSet::new();
    let mut names_out = HashSet::new();
    let mut ids: HashSet<String> = inside.clone();
    let mut inputs: Vec<((String, String), String)> = Vec::new(); // (outside source) -> port name
    let mut outputs: Vec<((String, String), String)> = Vec::new(); // (inside source) -> port name
    for w in &wires {
        let (from_in, to_in) = (inside.contains(&w.from), inside.contains(&w.to));
        match (from_in, to_in) {
            (true, true) => {
                sub.connect(&w.from, &w.output, &w.to, &w.input)?;
            }
            (false, true) => {
                let key = (w.from.clone(), w.output.clone());
                let name = match inputs.iter().find(|(k, _)| *k == key) {
                    Some((_, name)) => name.clone(),
                    None => {
                        // Named after the input it feeds, else what feeds it.
                        let base = telling_name(&[&w.input, &w.output, &w.from]);
                        let name = unique(base, &mut names_in);
                        let node_id = unique(&format!("in_{name}"), &mut ids);
                        let at = [x_min - 220.0, y_mean + 80.0 * inputs.len() as f32];
                        add_interface(&mut sub, graph, w, INPUT_TYPE, &node_id, &name, at)?;
                        inputs.push((key, name.clone()));
                        name
                    }
                };
                let node_id = sub_node_named(&sub, INPUT_TYPE, &name);
                sub.connect(&node_id, "value", &w.to, &w.input)?;
            }
            (true, false) => {
                let key = (w.from.clone(), w.output.clone());
                if !outputs.iter().any(|(k, _)| *k == key) {
                    // Named after the output it carries, else the input it feeds outside,
                    // else the node it comes from.
                    let base = telling_name(&[&w.output, &w.input, &w.from]);
                    let name = unique(base, &mut names_out);
                    let node_id = unique(&format!("out_{name}"), &mut ids);
                    let at = [x_max + 220.0, y_mean + 80.0 * outputs.len() as f32];
                    add_interface(&mut sub, graph, w, OUTPUT_TYPE, &node_id, &name, at)?;
                    sub.connect(&w.from, &w.output, &node_id, "value")?;
                    outputs.push((key, name));
                }
            }
            (false, false) => {}
        }
    }
    let meta = GraphMeta {
        name: Some(cluster_id.to_string()),
        ..GraphMeta::default()
    };
    let cluster = Cluster::new(ClusterSource::Inline, sub, meta, None)
        .map_err(ClusterEditError::Interface)?;

    for id in selection {
        graph.remove_node(id)?;
    }
    graph.add_node_with_def(cluster_id, Arc::new(cluster.node_def()))?;
    graph.set_position(cluster_id, [(x_min + x_max) / 2.0, y_mean])?;
    for w in &wires {
        let (from_in, to_in) = (inside.contains(&w.from), inside.contains(&w.to));
        if !from_in && to_in {
            let key = (w.from.clone(), w.output.clone());
            if let Some((_, name)) = inputs.iter().find(|(k, _)| *k == key) {
                let exists = graph.wires().iter().any(|x| {
                    x.from == w.from
                        && x.output == w.output
                        && x.to == cluster_id
                        && x.input == *name
                });
                if !exists {
                    graph.connect(&w.from, &w.output, cluster_id, name)?;
                }
            }
        } else if from_in && !to_in {
            let key = (w.from.clone(), w.output.clone());
            if let Some((_, name)) = outputs.iter().find(|(k, _)| *k == key) {
                graph.connect(cluster_id, name, &w.to, &w.input)?;
            }
        }
    }
    Ok(cluster)
}

/// Adds a `graph.input` or `graph.output` node for the wire `w` crossing the selection, typed like
/// the wire's source output.
fn add_interface(
    sub: &mut Graph,
    graph: &Graph,
    w: &WireRef,
    kind: &str,
    node_id: &str,
    name: &str,
    position: [f32; 2],
) -> Result<(), GraphError> {
    let source = graph
        .node(&w.from)
        .ok_or_else(|| GraphError::UnknownNode(w.from.clone()))?;
    let port = source.def.outputs.iter().find(|p| p.name == w.output);
    let ty = port.map_or("any".to_string(), |p| p.type_name());
    sub.add_node(node_id, kind)?;
    sub.set_value(node_id, "name", Value::text(name))?;
    sub.set_value(node_id, "type", Value::text(ty))?;
    sub.set_position(node_id, position)
}

/// The id of the interface node of `kind` whose `name` literal is `name`.
fn sub_node_named(graph: &Graph, kind: &str, name: &str) -> String {
    graph
        .nodes()
        .find(|(_, n)| {
            n.def.id == kind
                && matches!(n.value_of("name"), Some(Value::Text(s)) if s.as_ref() == name)
        })
        .map(|(_, n)| n.id.clone())
        .unwrap_or_default()
}

/// Replaces the cluster node `cluster_id` by the nodes of its subgraph, rewiring its inputs and
/// outputs; unconnected cluster inputs become literal values (or the inputs' defaults). Returns the
/// ids of the added nodes.
pub fn explode(graph: &mut Graph, cluster_id: &str) -> Result<Vec<String>, ClusterEditError> {
    let node = graph
        .node(cluster_id)
        .ok_or_else(|| GraphError::UnknownNode(cluster_id.to_string()))?;
    let cluster = Cluster::of(&node.def)
        .ok_or_else(|| ClusterEditError::NotACluster(cluster_id.to_string()))?;
    let sub = cluster.template.clone();
    let literals: Vec<(String, Value)> = node
        .def
        .inputs
        .iter()
        .enumerate()
        .filter_map(|(k, p)| Some((p.name.to_string(), node.value(k)?.clone())))
        .collect();
    let wires = graph.wires();
    let outer_in: Vec<&WireRef> = wires.iter().filter(|w| w.to == cluster_id).collect();
    let outer_out: Vec<&WireRef> = wires.iter().filter(|w| w.from == cluster_id).collect();
    graph.remove_node(cluster_id)?;

    let mut members: Vec<_> = sub
        .nodes()
        .filter(|(_, n)| n.def.id != INPUT_TYPE && n.def.id != OUTPUT_TYPE)
        .map(|(k, n)| (k, n.uid(), n.id.clone()))
        .collect();
    members.sort_by_key(|m| m.1);
    let mut taken: HashSet<String> = graph.nodes().map(|(_, n)| n.id.clone()).collect();
    let mut renamed = std::collections::HashMap::new();
    let mut added = Vec::new();
    for (index, _, id) in &members {
        let new_id = if taken.contains(id) {
            unique(&format!("{cluster_id}_{id}"), &mut taken)
        } else {
            unique(id, &mut taken)
        };
        copy_node(&sub, *index, graph, &new_id)?;
        renamed.insert(id.clone(), new_id.clone());
        added.push(new_id);
    }
    let kind_of = |id: &str| {
        sub.node(id)
            .map(|n| n.def.id.to_string())
            .unwrap_or_default()
    };
    let name_of = |id: &str| match sub.node(id).and_then(|n| n.value_of("name")) {
        Some(Value::Text(s)) => s.to_string(),
        _ => String::new(),
    };
    for w in sub.wires() {
        let (from_kind, to_kind) = (kind_of(&w.from), kind_of(&w.to));
        match (from_kind == INPUT_TYPE, to_kind == OUTPUT_TYPE) {
            (false, false) => {
                graph.connect(&renamed[&w.from], &w.output, &renamed[&w.to], &w.input)?;
            }
            (true, false) => {
                let name = name_of(&w.from);
                let target = &renamed[&w.to];
                let sources: Vec<_> = outer_in.iter().filter(|o| o.input == name).collect();
                if sources.is_empty() {
                    let literal = literals
                        .iter()
                        .find(|(n, _)| *n == name)
                        .map(|(_, v)| v.clone());
                    let default = sub
                        .node(&w.from)
                        .and_then(|n| n.value_of("default").cloned());
                    if let Some(v) = literal.or(default) {
                        graph.set_value(target, &w.input, v)?;
                    }
                }
                for o in sources {
                    graph.connect(&o.from, &o.output, target, &w.input)?;
                }
            }
            (false, true) => {
                let name = name_of(&w.to);
                for o in outer_out.iter().filter(|o| o.output == name) {
                    graph.connect(&renamed[&w.from], &w.output, &o.to, &o.input)?;
                }
            }
            (true, true) => {
                let name_in = name_of(&w.from);
                let name_out = name_of(&w.to);
                for o in outer_out.iter().filter(|o| o.output == name_out) {
                    for i in outer_in.iter().filter(|i| i.input == name_in) {
                        graph.connect(&i.from, &i.output, &o.to, &o.input)?;
                    }
                }
            }
        }
    }
    Ok(added)
}
