//! The objective as a function of the variables: set the inputs, re-evaluate what depends on them,
//! read the objective and penalties. Counts every objective evaluation and every node run.

use petgraph::stable_graph::NodeIndex;

use super::setup::Setup;
use crate::eval::Evaluator;
use crate::graph::Graph;
use crate::node::NodeContext;
use crate::value::Value;

/// Why a setup does not fit its graph.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct SetupMismatch(pub String);

/// A graph with its setup, ready to be evaluated at points of the variable space.
pub struct Problem {
    graph: Graph,
    setup: Setup,
    evaluator: Evaluator,
    incremental: bool,
    request: Vec<NodeIndex>,
    /// Current literal values of the variables' inputs, by variable.
    bases: Vec<Value>,
    /// Objective evaluations so far.
    pub evaluations: u64,
    /// Node runs so far (over all evaluations).
    pub node_runs: u64,
}

impl Problem {
    /// Prepares `graph` for optimization. With `incremental` false every evaluation starts from a
    /// fresh evaluator (the full re-evaluation baseline for comparisons).
    pub fn new(graph: Graph, setup: Setup, incremental: bool) -> Result<Self, SetupMismatch> {
        let mut bases = Vec::new();
        for v in &setup.variables {
            let node = graph.node(&v.input.node).ok_or_else(|| {
                SetupMismatch(format!("variable {}: no node '{}'", v.input, v.input.node))
            })?;
            let k = node.def.input_index(&v.input.port).ok_or_else(|| {
                SetupMismatch(format!(
                    "variable {}: node '{}' has no input '{}'; its inputs are: {}",
                    v.input,
                    v.input.node,
                    v.input.port,
                    node.def.input_names()
                ))
            })?;
            let index = graph
                .index(&v.input.node)
                .map_err(|e| SetupMismatch(e.to_string()))?;
            if graph.wires_into(index).iter().any(|(_, w)| w.to_input == k) {
                return Err(SetupMismatch(format!(
                    "variable {}: the input is connected; a variable must be a value set on the input",
                    v.input
                )));
            }
            let base = node
                .value(k)
                .or(node.def.inputs[k].default.as_ref())
                .cloned()
                .unwrap_or(Value::Null);
            v.input
                .get(&base)
                .map_err(|e| SetupMismatch(format!("variable {e}")))?;
            bases.push(base);
        }
        let mut request = Vec::new();
        for p in std::iter::once(&setup.objective).chain(setup.penalties.iter().map(|p| &p.output))
        {
            let node = graph
                .node(&p.node)
                .ok_or_else(|| SetupMismatch(format!("{p}: no node '{}'", p.node)))?;
            if node.def.output_index(&p.port).is_none() {
                return Err(SetupMismatch(format!(
                    "{p}: node '{}' has no output '{}'; its outputs are: {}",
                    p.node,
                    p.port,
                    node.def.output_names()
                )));
            }
            request.push(
                graph
                    .index(&p.node)
                    .map_err(|e| SetupMismatch(e.to_string()))?,
            );
        }
        Ok(Self {
            graph,
            setup,
            evaluator: Evaluator::new(),
            incremental,
            request,
            bases,
            evaluations: 0,
            node_runs: 0,
        })
    }

    /// Number of variables.
    pub fn dimension(&self) -> usize {
        self.setup.variables.len()
    }

    /// The setup.
    pub fn setup(&self) -> &Setup {
        &self.setup
    }

    /// The variables' current values in the graph.
    pub fn start(&self) -> Vec<f64> {
        self.setup
            .variables
            .iter()
            .zip(&self.bases)
            .map(|(v, b)| v.input.get(b).unwrap_or(0.0))
            .collect()
    }

    /// Lower and upper bounds.
    pub fn bounds(&self) -> (Vec<f64>, Vec<f64>) {
        (
            self.setup.variables.iter().map(|v| v.min).collect(),
            self.setup.variables.iter().map(|v| v.max).collect(),
        )
    }

    /// Writes `x` into the graph's inputs (only changed values are edits).
    pub fn apply(&mut self, x: &[f64]) -> Result<(), String> {
        for (k, v) in self.setup.variables.iter().enumerate() {
            // Variables may share one input (e.g. several items of a list): update the shared base.
            let base = self
                .setup
                .variables
                .iter()
                .zip(&self.bases)
                .position(|(w, _)| w.input.node == v.input.node && w.input.port == v.input.port)
                .unwrap_or(k);
            let updated = v.input.set(&self.bases[base], x[k])?;
            for (j, w) in self.setup.variables.iter().enumerate() {
                if w.input.node == v.input.node && w.input.port == v.input.port {
                    self.bases[j] = updated.clone();
                }
            }
        }
        let mut done: Vec<(&str, &str)> = Vec::new();
        for (v, base) in self.setup.variables.iter().zip(&self.bases) {
            let key = (v.input.node.as_str(), v.input.port.as_str());
            if done.contains(&key) {
                continue;
            }
            done.push(key);
            self.graph
                .set_value(&v.input.node, &v.input.port, base.clone())
                .map_err(|e| e.to_string())?;
        }
        Ok(())
    }

    /// The objective plus penalties at `x`; `Err` when a node fails or a value is not a number.
    pub fn value(&mut self, x: &[f64], ctx: &NodeContext) -> Result<f64, String> {
        self.apply(x)?;
        if !self.incremental {
            self.evaluator = Evaluator::new();
        }
        let summary = self
            .evaluator
            .evaluate(&self.graph, &self.request, ctx, &mut |_, _| {});
        self.evaluations += 1;
        self.node_runs += summary.ran as u64;
        if summary.cancelled {
            return Err("cancelled".into());
        }
        let mut total = self.read(&self.setup.objective.clone())?;
        for p in self.setup.penalties.clone() {
            total += p.value(self.read(&p.output)?);
        }
        if total.is_finite() {
            Ok(total)
        } else {
            Err(format!("the objective is not finite ({total})"))
        }
    }

    fn read(&self, path: &super::path::ValuePath) -> Result<f64, String> {
        let result = self
            .evaluator
            .result(&self.graph, &path.node)
            .ok_or_else(|| format!("{path} was not evaluated"))?;
        let outputs = result.outputs().ok_or_else(|| {
            format!(
                "node '{}': {}",
                path.node,
                result.error().unwrap_or("failed")
            )
        })?;
        let k = self
            .graph
            .node(&path.node)
            .and_then(|n| n.def.output_index(&path.port))
            .ok_or_else(|| format!("{path}: no such output"))?;
        path.get(&outputs.values[k])
    }

    /// The graph with the values last applied.
    pub fn graph(&self) -> &Graph {
        &self.graph
    }

    /// Takes the graph out.
    pub fn into_graph(self) -> Graph {
        self.graph
    }
}
