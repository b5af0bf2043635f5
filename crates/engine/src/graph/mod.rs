//! The graph document: node instances, their literal input values and the wires between them.
//!
//! The document is separate from the executor ([`crate::eval::Evaluator`]): every semantic edit bumps
//! the graph's revision and stamps the edited node, which is all the executor needs to re-run only
//! what changed.

mod error;

pub use error::GraphError;

use std::collections::HashMap;
use std::sync::Arc;

use petgraph::Direction;
use petgraph::stable_graph::{EdgeIndex, NodeIndex, StableDiGraph};
use petgraph::visit::{EdgeRef, IntoEdgeReferences, NodeIndexable};

use crate::convert::coerce_tree;
use crate::node::{NodeDef, PortDef};
use crate::registry::Registry;
use crate::value::Value;

/// A revision number: bumped on every semantic edit of a graph.
pub type Revision = u64;

/// One node in a graph.
#[derive(Debug, Clone)]
pub struct NodeInstance {
    /// Stable, human-readable id (`"torus"`).
    pub id: String,
    /// The node type.
    pub def: Arc<NodeDef>,
    /// Literal values of inputs, by input index (`None` = use the default).
    values: Vec<Option<Value>>,
    /// Position on the editor canvas.
    pub position: [f32; 2],
    /// Whether the editor previews the node's geometry.
    pub preview: bool,
    /// The colour its geometry is previewed in (sRGB), picked on the node; `None`: the default.
    pub color: Option<[u8; 3]>,
    /// The name the designer gave the node (the canvas title, the parameter panel, the 3D view's
    /// labels); `None`: its id. Not an edit for evaluation; wires and `--set` still use the id.
    pub name: Option<String>,
    /// Disabled nodes do not run; their dependents are blocked.
    pub enabled: bool,
    uid: u64,
    edited_at: Revision,
}

impl NodeInstance {
    /// The literal value set on input `k`, if any.
    pub fn value(&self, k: usize) -> Option<&Value> {
        self.values.get(k).and_then(Option::as_ref)
    }

    /// The literal value set on the named input, if any.
    pub fn value_of(&self, input: &str) -> Option<&Value> {
        self.def.input_index(input).and_then(|k| self.value(k))
    }

    /// The name shown to designers: the name given to the node, else its id.
    pub fn label(&self) -> &str {
        self.name.as_deref().unwrap_or(&self.id)
    }

    /// Unique id of this instance across the life of the graph (never reused).
    pub fn uid(&self) -> u64 {
        self.uid
    }

    /// Revision of the last edit of this node's inputs, wires in or flags.
    pub fn edited_at(&self) -> Revision {
        self.edited_at
    }
}

/// A wire from an output port to an input port (by port index).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Wire {
    /// Output port index on the source node.
    pub from_output: usize,
    /// Input port index on the target node.
    pub to_input: usize,
    /// Creation order: several wires into one input are merged in this order.
    order: u64,
}

/// A wire described by node ids and port names.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct WireRef {
    /// Source node id.
    pub from: String,
    /// Source output name.
    pub output: String,
    /// Target node id.
    pub to: String,
    /// Target input name.
    pub input: String,
}

impl std::fmt::Display for WireRef {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}.{} -> {}.{}",
            self.from, self.output, self.to, self.input
        )
    }
}

/// A node of a replaced graph and the node of the replacing graph that continues it (see
/// [`Graph::take_over`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Continued {
    /// Its index in the replaced graph.
    pub previous: NodeIndex,
    /// Its index in the replacing graph.
    pub next: NodeIndex,
    /// Its uid in the replacing graph (a later edit may have reused the index for another node).
    pub uid: u64,
}

/// A dataflow graph of node instances.
#[derive(Debug, Clone)]
pub struct Graph {
    inner: StableDiGraph<NodeInstance, Wire>,
    ids: rustc_hash::FxHashMap<String, NodeIndex>,
    registry: Arc<Registry>,
    revision: Revision,
    next_uid: u64,
    next_order: u64,
}

/// Checks a node id: non-empty; letters, digits, `_` and `-`.
pub fn valid_id(id: &str) -> bool {
    !id.is_empty()
        && id
            .chars()
            .all(|c| c.is_alphanumeric() || c == '_' || c == '-')
}

impl Graph {
    /// An empty graph whose node types come from `registry`.
    pub fn new(registry: Arc<Registry>) -> Self {
        Self {
            inner: StableDiGraph::default(),
            ids: rustc_hash::FxHashMap::default(),
            registry,
            revision: 1,
            next_uid: 1,
            next_order: 0,
        }
    }

    /// The registry node types are looked up in.
    pub fn registry(&self) -> &Arc<Registry> {
        &self.registry
    }

    /// The current revision.
    pub fn revision(&self) -> Revision {
        self.revision
    }

    fn bump(&mut self, node: NodeIndex) {
        self.revision += 1;
        if let Some(n) = self.inner.node_weight_mut(node) {
            n.edited_at = self.revision;
        }
    }

    /// Makes this graph — an earlier state being restored (undo, redo) — the successor of
    /// `current`, the graph it replaces: its revision moves past both graphs', and every node that
    /// differs from the node with the same uid in `current` (definition, literal values, enabled
    /// flag, wires in) or that `current` lacks is stamped as edited now, while equal nodes keep
    /// `current`'s stamps. An evaluator that last evaluated `current` then re-runs only the nodes
    /// that differ and what depends on them, as after ordinary edits. Uids handed out later stay
    /// unique across both graphs (an evaluator's memos are keyed by them).
    pub fn succeed(&mut self, current: &Graph) {
        let now = self.revision.max(current.revision) + 1;
        let by_uid: HashMap<u64, NodeIndex> = current
            .inner
            .node_indices()
            .map(|i| (current.inner[i].uid, i))
            .collect();
        let wires_in = |g: &Graph, i: NodeIndex| {
            let mut w: Vec<(u64, usize, usize, u64)> = g
                .inner
                .edges_directed(i, Direction::Incoming)
                .map(|e| {
                    let wire = e.weight();
                    (
                        g.inner[e.source()].uid,
                        wire.from_output,
                        wire.to_input,
                        wire.order,
                    )
                })
                .collect();
            w.sort_unstable();
            w
        };
        let indices: Vec<NodeIndex> = self.inner.node_indices().collect();
        for i in indices {
            let n = &self.inner[i];
            let kept = by_uid.get(&n.uid).and_then(|&j| {
                let m = &current.inner[j];
                let same = Arc::ptr_eq(&n.def, &m.def)
                    && n.values == m.values
                    && n.enabled == m.enabled
                    && wires_in(self, i) == wires_in(current, j);
                same.then_some(m.edited_at)
            });
            self.inner[i].edited_at = kept.unwrap_or(now);
        }
        self.revision = now;
        self.next_uid = self.next_uid.max(current.next_uid);
        self.next_order = self.next_order.max(current.next_order);
    }

    /// Makes this graph — another document replacing `previous` (File › Open, New, Open example)
    /// — the successor of `previous` for an evaluator that last evaluated it. A node *continues*
    /// a node of `previous` when it has the same id, the same definition (the same registered
    /// type), the same literal values and enabled flag and the same wires in (same source ids and
    /// ports, in the same order): it keeps that node's stamp, every other node is stamped as
    /// edited now, and the revision moves past both graphs'. Returns the continued nodes, for
    /// [`crate::Evaluator::carry_over`]: an evaluator given them re-runs only the nodes that
    /// differ and what depends on them.
    pub fn take_over(&mut self, previous: &Graph) -> Vec<Continued> {
        let now = self.revision.max(previous.revision) + 1;
        let wires_in = |g: &Graph, i: NodeIndex| -> Vec<(String, usize, usize)> {
            g.wires_into(i)
                .into_iter()
                .map(|(source, wire)| {
                    let id = g.inner.node_weight(source).map_or("", |n| n.id.as_str());
                    (id.to_string(), wire.from_output, wire.to_input)
                })
                .collect()
        };
        let indices: Vec<NodeIndex> = self.inner.node_indices().collect();
        let mut carried = Vec::new();
        for i in indices {
            let n = &self.inner[i];
            let kept = previous.ids.get(&n.id).and_then(|&j| {
                let m = &previous.inner[j];
                let same = Arc::ptr_eq(&n.def, &m.def)
                    && n.values == m.values
                    && n.enabled == m.enabled
                    && wires_in(self, i) == wires_in(previous, j);
                same.then_some((j, m.edited_at))
            });
            match kept {
                Some((j, stamp)) => {
                    self.inner[i].edited_at = stamp;
                    carried.push(Continued {
                        previous: j,
                        next: i,
                        uid: self.inner[i].uid,
                    });
                }
                None => self.inner[i].edited_at = now,
            }
        }
        self.revision = now;
        carried
    }

    /// Adds a node of a registered type.
    pub fn add_node(&mut self, id: &str, type_id: &str) -> Result<NodeIndex, GraphError> {
        let def = self
            .registry
            .get(type_id)
            .cloned()
            .ok_or_else(|| GraphError::UnknownType {
                type_id: type_id.to_string(),
                suggestions: self
                    .registry
                    .similar_ids(type_id)
                    .into_iter()
                    .map(String::from)
                    .collect(),
            })?;
        self.add_node_with_def(id, def)
    }

    /// Adds a node with an explicit definition (e.g. a cluster built from a graph file).
    pub fn add_node_with_def(
        &mut self,
        id: &str,
        def: Arc<NodeDef>,
    ) -> Result<NodeIndex, GraphError> {
        if !valid_id(id) {
            return Err(GraphError::InvalidId(id.to_string()));
        }
        if self.ids.contains_key(id) {
            return Err(GraphError::DuplicateId(id.to_string()));
        }
        self.revision += 1;
        let node = NodeInstance {
            id: id.to_string(),
            values: vec![None; def.inputs.len()],
            def,
            position: [0.0, 0.0],
            preview: true,
            color: None,
            name: None,
            enabled: true,
            uid: self.next_uid,
            edited_at: self.revision,
        };
        self.next_uid += 1;
        let index = self.inner.add_node(node);
        self.ids.insert(id.to_string(), index);
        Ok(index)
    }

    /// Removes a node and its wires; its dependents are marked edited.
    pub fn remove_node(&mut self, id: &str) -> Result<NodeInstance, GraphError> {
        let index = self.index(id)?;
        let dependents: Vec<NodeIndex> = self
            .inner
            .neighbors_directed(index, Direction::Outgoing)
            .collect();
        let node = self
            .inner
            .remove_node(index)
            .ok_or_else(|| GraphError::UnknownNode(id.into()))?;
        self.ids.remove(id);
        self.revision += 1;
        for d in dependents {
            self.bump(d);
        }
        Ok(node)
    }

    /// The petgraph index of a node.
    pub fn index(&self, id: &str) -> Result<NodeIndex, GraphError> {
        self.ids
            .get(id)
            .copied()
            .ok_or_else(|| GraphError::UnknownNode(id.to_string()))
    }

    /// The node with this id.
    pub fn node(&self, id: &str) -> Option<&NodeInstance> {
        self.ids.get(id).map(|&k| &self.inner[k])
    }

    /// The node at this index.
    pub fn node_at(&self, index: NodeIndex) -> Option<&NodeInstance> {
        self.inner.node_weight(index)
    }

    /// All nodes, in index order.
    pub fn nodes(&self) -> impl Iterator<Item = (NodeIndex, &NodeInstance)> + '_ {
        self.inner.node_indices().map(move |k| (k, &self.inner[k]))
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.inner.node_count()
    }

    /// Number of wires.
    pub fn wire_count(&self) -> usize {
        self.inner.edge_count()
    }

    /// Upper bound of node indices (for index-keyed side tables).
    pub fn index_bound(&self) -> usize {
        self.inner.node_bound()
    }

    /// The underlying petgraph graph (read-only).
    pub fn petgraph(&self) -> &StableDiGraph<NodeInstance, Wire> {
        &self.inner
    }

    /// Wires into `node`, ordered by creation, as (source node, wire).
    pub fn wires_into(&self, node: NodeIndex) -> Vec<(NodeIndex, Wire)> {
        let mut wires: Vec<(NodeIndex, Wire)> = self
            .inner
            .edges_directed(node, Direction::Incoming)
            .map(|e| (e.source(), *e.weight()))
            .collect();
        wires.sort_by_key(|(_, w)| w.order);
        wires
    }

    /// The wires into `node` as (source node, source output index), in no particular order and
    /// without allocating (see [`Graph::wires_into`] for the merge order).
    pub fn inputs_of(&self, node: NodeIndex) -> impl Iterator<Item = (NodeIndex, usize)> + '_ {
        self.inner
            .edges_directed(node, Direction::Incoming)
            .map(|e| (e.source(), e.weight().from_output))
    }

    /// Source nodes feeding `node` (with repeats when several wires come from one node).
    pub fn sources(&self, node: NodeIndex) -> impl Iterator<Item = NodeIndex> + '_ {
        self.inner.neighbors_directed(node, Direction::Incoming)
    }

    /// Nodes fed by `node`.
    pub fn targets(&self, node: NodeIndex) -> impl Iterator<Item = NodeIndex> + '_ {
        self.inner.neighbors_directed(node, Direction::Outgoing)
    }

    /// Every wire as (source id, output index, target id, input index), in no particular order
    /// and without allocating (the canvas mirrors them each frame; [`Graph::wires`] has names).
    pub fn wire_ports(&self) -> impl Iterator<Item = (&str, usize, &str, usize)> + '_ {
        self.inner.edge_references().map(|e| {
            let w = e.weight();
            (
                self.inner[e.source()].id.as_str(),
                w.from_output,
                self.inner[e.target()].id.as_str(),
                w.to_input,
            )
        })
    }

    /// All wires by ids and port names, ordered by creation.
    pub fn wires(&self) -> Vec<WireRef> {
        let mut wires: Vec<(u64, WireRef)> = self
            .inner
            .edge_references()
            .map(|e| {
                let (from, to) = (&self.inner[e.source()], &self.inner[e.target()]);
                let w = e.weight();
                (
                    w.order,
                    WireRef {
                        from: from.id.clone(),
                        output: from.def.outputs[w.from_output].name.to_string(),
                        to: to.id.clone(),
                        input: to.def.inputs[w.to_input].name.to_string(),
                    },
                )
            })
            .collect();
        wires.sort_by_key(|(order, _)| *order);
        wires.into_iter().map(|(_, w)| w).collect()
    }

    fn input_port(&self, node: NodeIndex, input: &str) -> Result<usize, GraphError> {
        let n = &self.inner[node];
        n.def
            .input_index(input)
            .ok_or_else(|| GraphError::UnknownInput {
                node: n.id.clone(),
                type_id: n.def.id.to_string(),
                port: input.to_string(),
                valid: n.def.input_names(),
            })
    }

    fn output_port(&self, node: NodeIndex, output: &str) -> Result<usize, GraphError> {
        let n = &self.inner[node];
        n.def
            .output_index(output)
            .ok_or_else(|| GraphError::UnknownOutput {
                node: n.id.clone(),
                type_id: n.def.id.to_string(),
                port: output.to_string(),
                valid: n.def.output_names(),
            })
    }

    /// Sets the literal value of an input. The value is converted to the port's type (integer ↔
    /// number, point ↔ vector, …) and refused when it cannot be. Returns whether anything changed:
    /// setting an equal value is not an edit.
    pub fn set_value(&mut self, id: &str, input: &str, value: Value) -> Result<bool, GraphError> {
        let index = self.index(id)?;
        let k = self.input_port(index, input)?;
        let port = &self.inner[index].def.inputs[k];
        let value = coerce_tree(&value, &port.ty).map_err(|e| GraphError::BadValue {
            node: id.to_string(),
            port: input.to_string(),
            message: e.to_string(),
        })?;
        check_choices(port, &value).map_err(|message| GraphError::BadValue {
            node: id.to_string(),
            port: input.to_string(),
            message,
        })?;
        if self.inner[index].values[k]
            .as_ref()
            .is_some_and(|old| old.same_as(&value))
        {
            return Ok(false);
        }
        self.inner[index].values[k] = Some(value);
        self.bump(index);
        Ok(true)
    }

    /// Removes the literal value of an input (the default applies again).
    pub fn clear_value(&mut self, id: &str, input: &str) -> Result<bool, GraphError> {
        let index = self.index(id)?;
        let k = self.input_port(index, input)?;
        if self.inner[index].values[k].take().is_none() {
            return Ok(false);
        }
        self.bump(index);
        Ok(true)
    }

    /// Connects `from.output` to `to.input`, checking ports, types and cycles.
    pub fn connect(
        &mut self,
        from: &str,
        output: &str,
        to: &str,
        input: &str,
    ) -> Result<EdgeIndex, GraphError> {
        let (a, b) = (self.index(from)?, self.index(to)?);
        let (o, i) = (self.output_port(a, output)?, self.input_port(b, input)?);
        let out_port = &self.inner[a].def.outputs[o];
        let in_port = &self.inner[b].def.inputs[i];
        let label_from = format!("{from}.{output}");
        let label_to = format!("{to}.{input}");
        if !out_port.ty.converts_to(&in_port.ty) {
            return Err(GraphError::TypeMismatch {
                from: label_from,
                from_type: out_port.type_name(),
                to: label_to,
                to_type: in_port.type_name(),
            });
        }
        if self.find_wire(a, o, b, i).is_some() {
            return Err(GraphError::AlreadyConnected {
                from: label_from,
                to: label_to,
            });
        }
        if let Some(path) = self.path(b, a) {
            let mut names: Vec<&str> = path.iter().map(|&k| self.inner[k].id.as_str()).collect();
            names.push(&self.inner[b].id);
            return Err(GraphError::Cycle {
                from: label_from,
                to: label_to,
                path: names.join(" -> "),
            });
        }
        let wire = Wire {
            from_output: o,
            to_input: i,
            order: self.next_order,
        };
        self.next_order += 1;
        let edge = self.inner.add_edge(a, b, wire);
        self.bump(b);
        Ok(edge)
    }

    /// Removes the wire `from.output -> to.input`.
    pub fn disconnect(
        &mut self,
        from: &str,
        output: &str,
        to: &str,
        input: &str,
    ) -> Result<(), GraphError> {
        let (a, b) = (self.index(from)?, self.index(to)?);
        let (o, i) = (self.output_port(a, output)?, self.input_port(b, input)?);
        let edge = self
            .find_wire(a, o, b, i)
            .ok_or_else(|| GraphError::NotConnected {
                from: format!("{from}.{output}"),
                to: format!("{to}.{input}"),
            })?;
        self.inner.remove_edge(edge);
        self.bump(b);
        Ok(())
    }

    /// Removes every wire into `to.input`; returns how many there were.
    pub fn disconnect_input(&mut self, to: &str, input: &str) -> Result<usize, GraphError> {
        let b = self.index(to)?;
        let i = self.input_port(b, input)?;
        let edges: Vec<EdgeIndex> = self
            .inner
            .edges_directed(b, Direction::Incoming)
            .filter(|e| e.weight().to_input == i)
            .map(|e| e.id())
            .collect();
        for &e in &edges {
            self.inner.remove_edge(e);
        }
        if !edges.is_empty() {
            self.bump(b);
        }
        Ok(edges.len())
    }

    /// Removes every wire out of `from.output`; returns how many there were.
    pub fn disconnect_output(&mut self, from: &str, output: &str) -> Result<usize, GraphError> {
        let a = self.index(from)?;
        let o = self.output_port(a, output)?;
        let wires: Vec<(EdgeIndex, NodeIndex)> = self
            .inner
            .edges_directed(a, Direction::Outgoing)
            .filter(|e| e.weight().from_output == o)
            .map(|e| (e.id(), e.target()))
            .collect();
        for &(e, _) in &wires {
            self.inner.remove_edge(e);
        }
        for &(_, b) in &wires {
            self.bump(b);
        }
        Ok(wires.len())
    }

    fn find_wire(&self, a: NodeIndex, o: usize, b: NodeIndex, i: usize) -> Option<EdgeIndex> {
        self.inner
            .edges_connecting(a, b)
            .find(|e| e.weight().from_output == o && e.weight().to_input == i)
            .map(|e| e.id())
    }

    /// A path of nodes from `start` to `goal` along wires (both included), if one exists.
    fn path(&self, start: NodeIndex, goal: NodeIndex) -> Option<Vec<NodeIndex>> {
        let mut parent: HashMap<NodeIndex, NodeIndex> = HashMap::new();
        let mut stack = vec![start];
        let mut seen = std::collections::HashSet::from([start]);
        while let Some(n) = stack.pop() {
            if n == goal {
                let mut path = vec![n];
                let mut cur = n;
                while let Some(&p) = parent.get(&cur) {
                    path.push(p);
                    cur = p;
                }
                path.reverse();
                return Some(path);
            }
            for next in self.inner.neighbors_directed(n, Direction::Outgoing) {
                if seen.insert(next) {
                    parent.insert(next, n);
                    stack.push(next);
                }
            }
        }
        None
    }

    /// Enables or disables a node.
    pub fn set_enabled(&mut self, id: &str, enabled: bool) -> Result<(), GraphError> {
        let index = self.index(id)?;
        if self.inner[index].enabled != enabled {
            self.inner[index].enabled = enabled;
            self.bump(index);
        }
        Ok(())
    }

    /// Turns the editor preview of a node on or off (not an edit for evaluation).
    pub fn set_preview(&mut self, id: &str, preview: bool) -> Result<(), GraphError> {
        let index = self.index(id)?;
        self.inner[index].preview = preview;
        Ok(())
    }

    /// Sets the colour a node's geometry is previewed in (`None`: the default; not an edit for
    /// evaluation).
    pub fn set_color(&mut self, id: &str, color: Option<[u8; 3]>) -> Result<(), GraphError> {
        let index = self.index(id)?;
        self.inner[index].color = color;
        Ok(())
    }

    /// Names a node for designers (`None` or a blank name: shown by its id again; surrounding
    /// white space is dropped). Not an edit for evaluation: wires and `--set` keep using the id.
    pub fn set_name(&mut self, id: &str, name: Option<String>) -> Result<(), GraphError> {
        let index = self.index(id)?;
        self.inner[index].name = name.map(|n| n.trim().to_string()).filter(|n| !n.is_empty());
        Ok(())
    }

    /// Moves a node on the canvas (not an edit for evaluation).
    pub fn set_position(&mut self, id: &str, position: [f32; 2]) -> Result<(), GraphError> {
        let index = self.index(id)?;
        self.inner[index].position = position;
        Ok(())
    }

    /// Gives node `id` a new definition (e.g. a cluster rebuilt from its edited subgraph), keeping
    /// its id, creation order, position and flags. Literal values are kept for inputs of the same
    /// name that accept them; wires are kept where a port of the same name still exists and the
    /// types still connect (in their original order). Returns the wires that were dropped.
    pub fn replace_def(&mut self, id: &str, def: Arc<NodeDef>) -> Result<Vec<WireRef>, GraphError> {
        let index = self.index(id)?;
        let old = self.inner[index].def.clone();
        let old_values = std::mem::take(&mut self.inner[index].values);
        let mut values = vec![None; def.inputs.len()];
        for (k, port) in def.inputs.iter().enumerate() {
            let kept = old
                .input_index(&port.name)
                .and_then(|j| old_values.get(j).cloned().flatten())
                .and_then(|v| coerce_tree(&v, &port.ty).ok());
            values[k] = kept;
        }
        let edges: Vec<(EdgeIndex, NodeIndex, NodeIndex, Wire)> = self
            .inner
            .edges_directed(index, Direction::Incoming)
            .chain(self.inner.edges_directed(index, Direction::Outgoing))
            .map(|e| (e.id(), e.source(), e.target(), *e.weight()))
            .collect();
        let mut dropped = Vec::new();
        let mut kept = Vec::new();
        for (edge, a, b, wire) in edges {
            let (from, to) = (&self.inner[a], &self.inner[b]);
            let reference = WireRef {
                from: from.id.clone(),
                output: from.def.outputs[wire.from_output].name.to_string(),
                to: to.id.clone(),
                input: to.def.inputs[wire.to_input].name.to_string(),
            };
            let (out_def, in_def) = (
                if a == index { &def } else { &from.def },
                if b == index { &def } else { &to.def },
            );
            let ports = out_def
                .output_index(&reference.output)
                .zip(in_def.input_index(&reference.input))
                .filter(|&(o, i)| out_def.outputs[o].ty.converts_to(&in_def.inputs[i].ty));
            match ports {
                Some((o, i)) => kept.push((
                    edge,
                    Wire {
                        from_output: o,
                        to_input: i,
                        order: wire.order,
                    },
                )),
                None => {
                    self.inner.remove_edge(edge);
                    dropped.push(reference);
                }
            }
        }
        for (edge, wire) in kept {
            if let Some(w) = self.inner.edge_weight_mut(edge) {
                *w = wire;
            }
        }
        let dependents: Vec<NodeIndex> = self
            .inner
            .neighbors_directed(index, Direction::Outgoing)
            .collect();
        let node = &mut self.inner[index];
        node.def = def;
        node.values = values;
        self.bump(index);
        for d in dependents {
            self.bump(d);
        }
        Ok(dropped)
    }

    /// Node indices in a topological order (sources first).
    pub fn topological_order(&self) -> Vec<NodeIndex> {
        petgraph::algo::toposort(&self.inner, None)
            .unwrap_or_else(|_| self.inner.node_indices().collect())
    }
}

/// Checks every text of a value set on a choice port against the port's words (a list of choices
/// item by item); other ports and values pass.
fn check_choices(port: &PortDef, value: &Value) -> Result<(), String> {
    if port.choices.is_none() {
        return Ok(());
    }
    match value {
        Value::Text(t) => port.check_choice(t),
        Value::List(items) => items.iter().try_for_each(|v| check_choices(port, v)),
        _ => Ok(()),
    }
}
