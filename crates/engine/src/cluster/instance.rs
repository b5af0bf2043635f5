//! A cluster instance: a subgraph with its own evaluator, exposed as a node type.

use std::path::PathBuf;
use std::sync::{Arc, Mutex, MutexGuard};

use super::interface::Interface;
use crate::eval::{Evaluator, NodeResult};
use crate::file::GraphMeta;
use crate::graph::Graph;
use crate::node::{NodeContext, NodeDef, NodeError};
use crate::value::Value;

/// Node type id of clusters.
pub const CLUSTER_TYPE: &str = "cluster";

/// The `cluster` node type as listed by `cnets nodes` and in the reference. It is not registered:
/// every cluster node gets its own definition from its subgraph (its ports are the subgraph's
/// `graph.input`s and `graph.output`s); this one only documents the type.
pub fn cluster_type_description() -> NodeDef {
    NodeDef::new(
        CLUSTER_TYPE,
        "Clusters",
        "A graph used as a node: `source: \"file.ron\"` (next to the graph, then in the library \
         folders) or `graph: ( … )` inline. Its inputs and outputs are the subgraph's `graph.input` \
         and `graph.output` nodes, in node order, typed by their `type`; it evaluates incrementally \
         inside. See docs/clusters.md.",
    )
}

/// Where a cluster's subgraph comes from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ClusterSource {
    /// A graph file: the path as written in the including graph, and where it was found.
    File {
        /// As written (`source: "…"`), relative to the including graph or a library folder.
        written: String,
        /// The file that was loaded.
        resolved: PathBuf,
    },
    /// A subgraph embedded in the including graph (`graph: (…)`).
    Inline,
}

struct State {
    graph: Graph,
    evaluator: Evaluator,
}

/// A cluster: the subgraph, its interface, and the instance's evaluation state.
pub struct Cluster {
    /// Where the subgraph came from.
    pub source: ClusterSource,
    /// The subgraph as loaded (the template every run starts from).
    pub template: Graph,
    /// The subgraph's metadata.
    pub meta: GraphMeta,
    /// Its ports.
    pub interface: Interface,
    /// Folder relative paths inside the subgraph resolve against.
    pub base_dir: Option<PathBuf>,
    state: Mutex<State>,
}

impl std::fmt::Debug for Cluster {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Cluster")
            .field("source", &self.source)
            .field("nodes", &self.template.node_count())
            .finish()
    }
}

impl Cluster {
    /// A cluster over `graph`; fails when its interface is invalid.
    pub fn new(
        source: ClusterSource,
        graph: Graph,
        meta: GraphMeta,
        base_dir: Option<PathBuf>,
    ) -> Result<Arc<Self>, String> {
        let interface = Interface::of(&graph)?;
        Ok(Arc::new(Self {
            source,
            state: Mutex::new(State {
                graph: graph.clone(),
                evaluator: Evaluator::new(),
            }),
            template: graph,
            meta,
            interface,
            base_dir,
        }))
    }

    /// A new instance over the same subgraph, with its own (empty) cache.
    pub fn duplicate(&self) -> Arc<Self> {
        Arc::new(Self {
            source: self.source.clone(),
            template: self.template.clone(),
            meta: self.meta.clone(),
            interface: self.interface.clone(),
            base_dir: self.base_dir.clone(),
            state: Mutex::new(State {
                graph: self.template.clone(),
                evaluator: Evaluator::new(),
            }),
        })
    }

    fn lock(&self) -> MutexGuard<'_, State> {
        self.state
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    }

    /// A short label: the file name, or "inline".
    pub fn label(&self) -> String {
        match &self.source {
            ClusterSource::File { written, .. } => written.clone(),
            ClusterSource::Inline => "inline".to_string(),
        }
    }

    /// The node type of this instance: id `cluster`, ports from the interface.
    pub fn node_def(self: &Arc<Self>) -> NodeDef {
        let title = self.meta.name.clone().unwrap_or_else(|| self.label());
        let doc = match &self.meta.description {
            Some(d) => format!("Cluster '{title}': {d}"),
            None => format!("Cluster '{title}': a graph used as a node."),
        };
        let mut def = NodeDef::new(CLUSTER_TYPE, "Clusters", doc);
        def.inputs = self
            .interface
            .inputs
            .iter()
            .map(|p| p.port.clone())
            .collect();
        def.outputs = self
            .interface
            .outputs
            .iter()
            .map(|p| p.port.clone())
            .collect();
        let me = Arc::clone(self);
        def = def.run(move |ctx, inputs| me.run(ctx, inputs));
        def.extension = Some(Arc::clone(self) as Arc<dyn std::any::Any + Send + Sync>);
        def
    }

    /// The cluster behind a node type, if it is one.
    pub fn of(def: &NodeDef) -> Option<&Cluster> {
        def.extension.as_ref()?.downcast_ref::<Cluster>()
    }

    /// A shared handle to the cluster behind a node type, if it is one.
    pub fn shared(def: &NodeDef) -> Option<Arc<Cluster>> {
        def.extension.clone()?.downcast::<Cluster>().ok()
    }

    /// Runs `f` on this instance's working copy of the subgraph (its `graph.input` values as the
    /// last run set them) and its evaluator, e.g. for an editor showing the inner nodes' results.
    pub fn inspect<R>(&self, f: impl FnOnce(&Graph, &mut Evaluator) -> R) -> R {
        let mut guard = self.lock();
        let state = &mut *guard;
        f(&state.graph, &mut state.evaluator)
    }

    /// Runs of one inner node so far.
    pub fn inner_node_runs(&self, id: &str) -> u64 {
        let state = self.lock();
        state.evaluator.runs(&state.graph, id)
    }

    /// Evaluates the subgraph on the given input values (one per interface input).
    fn run(&self, ctx: &NodeContext, inputs: &[Value]) -> Result<Vec<Value>, NodeError> {
        let mut guard = self.lock();
        let state = &mut *guard;
        for (port, value) in self.interface.inputs.iter().zip(inputs) {
            let id = state
                .graph
                .node_at(port.node)
                .map(|n| n.id.clone())
                .unwrap_or_default();
            let result = if value.is_null() {
                state.graph.clear_value(&id, "value")
            } else {
                state.graph.set_value(&id, "value", value.clone())
            };
            result
                .map_err(|e| NodeError::new(format!("cluster input '{}': {e}", port.port.name)))?;
        }
        // Only the outputs asked of the cluster node are evaluated inside (lazy outputs).
        let wanted: Vec<bool> = self
            .interface
            .outputs
            .iter()
            .map(|p| ctx.wants(&p.port.name))
            .collect();
        let request: Vec<_> = self
            .interface
            .outputs
            .iter()
            .zip(&wanted)
            .filter(|(_, w)| **w)
            .map(|(p, _)| p.node)
            .collect();
        let inner = ctx
            .child(self.base_dir.clone())
            .map_err(|e| NodeError::new(format!("cluster '{}': {e}", self.label())))?;
        let summary = state
            .evaluator
            .evaluate(&state.graph, &request, &inner, &mut |_, _| {});
        ctx.hold(state.evaluator.live_bytes());
        if summary.cancelled {
            return Err(NodeError::new("cancelled"));
        }
        // The files inner nodes read count as the cluster node's reads: a change re-runs it (and,
        // inside, only the nodes that read the file and what depends on them).
        ctx.record_reads(state.evaluator.all_reads());
        for (_, node) in state.graph.nodes() {
            if let Some(outputs) = state
                .evaluator
                .result(&state.graph, &node.id)
                .and_then(NodeResult::outputs)
            {
                for w in &outputs.warnings {
                    ctx.warn(format!("in '{}': {w}", node.id));
                }
                for f in &outputs.files {
                    ctx.record_file(f.clone());
                }
            }
        }
        let mut values = Vec::with_capacity(wanted.len());
        for (port, wanted) in self.interface.outputs.iter().zip(wanted) {
            if !wanted {
                values.push(Value::Null);
                continue;
            }
            match state.evaluator.result_at(&state.graph, port.node) {
                Some(NodeResult::Ok(outputs)) => {
                    values.push(outputs.values.first().cloned().unwrap_or_default())
                }
                _ => {
                    return Err(NodeError::new(self.failure(
                        &state.graph,
                        &state.evaluator,
                        &port.port.name,
                    )));
                }
            }
        }
        Ok(values)
    }

    /// Explains why an output has no value: the first failing inner node, else the output's state.
    fn failure(&self, graph: &Graph, evaluator: &Evaluator, output: &str) -> String {
        let mut nodes: Vec<_> = graph.nodes().collect();
        nodes.sort_by_key(|(_, n)| n.uid());
        for (index, node) in nodes {
            if let Some(r) = evaluator.result_at(graph, index).filter(|r| r.is_failure()) {
                return format!(
                    "inside cluster '{}': node '{}' ({}) failed: {}",
                    self.label(),
                    node.id,
                    node.def.id,
                    r.error().as_deref().unwrap_or("")
                );
            }
        }
        format!(
            "inside cluster '{}': output '{output}' has no value",
            self.label()
        )
    }
}
