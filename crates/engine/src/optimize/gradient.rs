//! The exact gradient of the objective by a reverse (adjoint) pass over the evaluated graph.
//!
//! After an evaluation at x, the nodes on a path from a variable to the objective or a penalty
//! (the *active* nodes) are visited in reverse topological order. Each receives the cotangents of
//! its outputs (∂objective/∂output, accumulated from its consumers), returns those of its active
//! inputs through its vector–Jacobian product ([`super::vjp`]) — exact, or central differences of
//! that one node where it has none — and passes them up the wires (split again where several wires
//! were merged into one input). Cotangents that reach a literal input holding variables are the
//! gradient. One gradient costs one evaluation plus one reverse pass, whatever the number of
//! variables.

use std::collections::HashMap;

use petgraph::stable_graph::NodeIndex;

use super::convexity::{self, Phase};
use super::leaves;
use super::problem::Problem;
use super::setup::PenaltyKind;
use super::vjp::{Wanted, node_vjp};
use crate::node::NodeContext;

/// A gradient and how it was obtained.
#[derive(Debug, Clone, PartialEq)]
pub struct Gradient {
    /// The objective (with penalties) at the point.
    pub value: f64,
    /// ∂objective/∂variable, one per variable.
    pub gradient: Vec<f64>,
    /// Nodes differentiated by finite differences of their own run, with the reason.
    pub finite_differences: Vec<(String, String)>,
    /// Node runs of the reverse pass (finite differences of nodes without a derivative).
    pub node_runs: u64,
    /// The smooth piece each piecewise-smooth node on the path was on
    /// ([`super::branch`]).
    pub branches: Vec<(String, super::branch::Branch)>,
}

impl Problem {
    /// The objective and its exact gradient at `x` (one evaluation and one reverse pass). `Err`
    /// when the objective cannot be evaluated or a value on the path carries no derivative (a
    /// plane, a line set, a record): the caller then uses finite differences of the whole graph.
    pub fn gradient(&mut self, x: &[f64], ctx: &NodeContext) -> Result<Gradient, String> {
        let value = self.value(x, ctx)?;
        let graph = &self.graph;
        // Seeds: the objective, and each penalty's derivative at its value.
        let mut cot: HashMap<(NodeIndex, usize), Vec<f64>> = HashMap::new();
        let mut seed = |path: &super::path::ValuePath, weight: f64| -> Result<(), String> {
            let k = graph.index(&path.node).map_err(|e| e.to_string())?;
            let output = graph
                .node_at(k)
                .and_then(|node| node.def.output_index(&path.port))
                .ok_or_else(|| format!("{path}: no such output"))?;
            let v = self
                .evaluator
                .output(graph, &path.node, &path.port)
                .ok_or_else(|| format!("{path} was not evaluated"))?;
            let leaf = leaves::offset(v, &path.indices)
                .ok_or_else(|| format!("{path} is not a number"))?;
            let c = cot
                .entry((k, output))
                .or_insert_with(|| vec![0.0; leaves::count(v)]);
            c[leaf] += weight;
            Ok(())
        };
        let fitting = self.phase != Phase::Feasibility;
        if fitting {
            seed(&self.setup.objective, 1.0)?;
        }
        for p in self.setup.penalties.iter().filter(|_| fitting) {
            let v = self
                .evaluator
                .output(graph, &p.output.node, &p.output.port)
                .ok_or_else(|| format!("{} was not evaluated", p.output))
                .and_then(|v| p.output.get(v))?;
            let d = match p.kind {
                PenaltyKind::Equal => v - p.target,
                PenaltyKind::AtMost => (v - p.target).max(0.0),
                PenaltyKind::AtLeast => -(p.target - v).max(0.0),
            };
            seed(&p.output, 2.0 * p.weight * d)?;
        }
        // Faces kept convex: the barrier's (or the feasibility phase's) slope by each margin.
        if self.phase != Phase::Off {
            for w in self.watched.iter().filter(|w| w.kept) {
                let slopes = convexity::slopes(self.phase, &self.margins(w)?);
                let c = cot
                    .entry((w.index, w.output))
                    .or_insert_with(|| vec![0.0; slopes.len()]);
                leaves::accumulate(c, &slopes);
            }
        }
        let pass = self.reverse(cot, ctx)?;
        Ok(Gradient {
            value,
            gradient: pass.gradient,
            finite_differences: pass.finite_differences,
            node_runs: pass.node_runs,
            branches: pass.branches,
        })
    }

    /// The reverse pass from the cotangents `cot` of node outputs (`(node, output)` → one number
    /// per leaf) at the last evaluation: the cotangents that reach the variables.
    pub(super) fn reverse(
        &mut self,
        mut cot: HashMap<(NodeIndex, usize), Vec<f64>>,
        ctx: &NodeContext,
    ) -> Result<Reverse, String> {
        let graph = &self.graph;
        let active = |k: NodeIndex| self.active.get(k.index()).copied().unwrap_or(false);
        let mut gradient = vec![0.0; self.dimension()];
        let mut finite_differences = Vec::new();
        let mut branches = Vec::new();
        let mut node_runs = 0;
        let order = graph.topological_order();
        for &k in order.iter().rev() {
            if !active(k) {
                continue;
            }
            let Some(instance) = graph.node_at(k) else {
                continue;
            };
            let def = &instance.def;
            let cotangents: Vec<Option<Vec<f64>>> = (0..def.outputs.len())
                .map(|o| cot.remove(&(k, o)))
                .collect();
            if cotangents.iter().all(Option::is_none) {
                continue;
            }
            let outputs = &self
                .evaluator
                .result_at(graph, k)
                .and_then(|r| r.outputs())
                .ok_or_else(|| format!("node '{}' has no outputs", instance.id))?
                .values;
            if outputs
                .iter()
                .zip(&cotangents)
                .any(|(v, c)| c.is_some() && leaves::opaque(v))
            {
                return Err(format!(
                    "node '{}': an output on the path to the objective carries no derivative",
                    instance.id
                ));
            }
            let inputs = self.evaluator.inputs_of(graph, k, ctx)?;
            let wires = graph.wires_into(k);
            let wanted: Vec<Wanted> = (0..def.inputs.len())
                .map(|input| {
                    if wires.iter().any(|(s, w)| w.to_input == input && active(*s)) {
                        Wanted::All
                    } else if let Some(g) = self
                        .groups
                        .iter()
                        .find(|g| g.node == instance.id && g.input == input)
                    {
                        Wanted::Leaves(g.members.iter().map(|m| m.1).collect())
                    } else {
                        Wanted::No
                    }
                })
                .collect();
            for (input, w) in wanted.iter().enumerate() {
                if *w != Wanted::No && leaves::opaque(&inputs[input]) {
                    return Err(format!(
                        "node '{}': input '{}' on the path to the objective carries no derivative",
                        instance.id, def.inputs[input].name
                    ));
                }
            }
            let result = node_vjp(def, ctx, &inputs, outputs, &cotangents, &wanted)
                .map_err(|e| format!("node '{}': {e}", instance.id))?;
            node_runs += result.runs;
            if let Some(reason) = result.finite_differences {
                finite_differences.push((instance.id.clone(), reason));
            }
            if let Some(piece) = def.branch.as_ref().and_then(|b| b(&inputs, outputs)) {
                branches.push((instance.id.clone(), piece));
            }
            for (input, c) in result.inputs.into_iter().enumerate() {
                let Some(c) = c else { continue };
                let from: Vec<_> = wires.iter().filter(|(_, w)| w.to_input == input).collect();
                if from.is_empty() {
                    if let Some(g) = self
                        .groups
                        .iter()
                        .find(|g| g.node == instance.id && g.input == input)
                    {
                        for &(v, leaf) in &g.members {
                            gradient[v] += c.get(leaf).copied().unwrap_or(0.0);
                        }
                    }
                    continue;
                }
                // Merged wires: the input's leaves are the sources' leaves in wire order.
                let mut at = 0;
                for (s, w) in from {
                    let len = self
                        .evaluator
                        .result_at(graph, *s)
                        .and_then(|r| r.outputs())
                        .and_then(|o| o.values.get(w.from_output))
                        .map_or(0, leaves::count);
                    let part = c.get(at..at + len).ok_or_else(|| {
                        format!(
                            "node '{}': the derivative of input '{}' does not match its wires",
                            instance.id, def.inputs[input].name
                        )
                    })?;
                    at += len;
                    if active(*s) {
                        leaves::accumulate(cot.entry((*s, w.from_output)).or_default(), part);
                    }
                }
            }
        }
        self.node_runs += node_runs;
        Ok(Reverse {
            gradient,
            finite_differences,
            node_runs,
            branches,
        })
    }
}

/// What one reverse pass gives.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Reverse {
    /// The cotangents of the variables.
    pub(super) gradient: Vec<f64>,
    /// Nodes differentiated by finite differences of their own run, with the reason.
    pub(super) finite_differences: Vec<(String, String)>,
    /// Node runs spent on those.
    pub(super) node_runs: u64,
    /// The smooth pieces of the piecewise-smooth nodes on the path.
    pub(super) branches: Vec<(String, super::branch::Branch)>,
}
