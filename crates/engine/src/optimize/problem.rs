//! The objective as a function of the variables: set the inputs, re-evaluate what depends on them,
//! read the objective and penalties. Counts every objective evaluation and every node run.

use petgraph::stable_graph::NodeIndex;

use super::convexity::{self, Phase, Watched};
use super::leaves;
use super::setup::{Setup, Variable};
use crate::eval::{Evaluator, NodeResult, OutputMask};
use crate::graph::Graph;
use crate::node::{NodeContext, PortDef, Widget};
use crate::value::Value;

/// Why a setup does not fit its graph.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct SetupMismatch(pub String);

/// The variables that live in one literal input: the input's current value and, per variable,
/// its index and the leaf it sets.
#[derive(Debug, Clone)]
pub(super) struct Group {
    pub(super) node: String,
    pub(super) port: String,
    /// The input's index on the node.
    pub(super) input: usize,
    /// The literal value with the values last applied.
    pub(super) base: Value,
    /// (variable index, leaf index inside `base`).
    pub(super) members: Vec<(usize, usize)>,
}

/// A graph with its setup, ready to be evaluated at points of the variable space.
pub struct Problem {
    pub(super) graph: Graph,
    /// The setup with whole-input variables expanded into one variable per number.
    pub(super) setup: Setup,
    pub(super) evaluator: Evaluator,
    incremental: bool,
    /// The active nodes, by index: downstream of a variable and upstream of a requested node
    /// (the reverse pass visits these).
    pub(super) active: Vec<bool>,
    /// The objective's and the penalties' nodes with every output, and the active nodes whose
    /// derivative reads outputs off the path, with those outputs
    /// ([`crate::NodeDef::derivative_outputs`]).
    demand: Vec<(NodeIndex, OutputMask)>,
    /// The literal inputs holding variables.
    pub(super) groups: Vec<Group>,
    /// The constructions on the path (and those `convex` names) whose margins are read.
    pub(super) watched: Vec<Watched>,
    /// What keeping faces convex adds to the objective now.
    pub(super) phase: Phase,
    /// Objective evaluations so far.
    pub evaluations: u64,
    /// Node runs so far (over all evaluations).
    pub node_runs: u64,
}

/// The paths of every number of a literal input, for a whole-input variable (`node.input` naming
/// a list, a table or a point). Graph-mapper handles (a port whose widget is
/// [`Widget::MapperHandles`]) contribute their v only (u orders the handles along the curve, z is
/// unused).
fn expand(variable: &Variable, base: &Value, port: &PortDef) -> Vec<Variable> {
    fn walk(v: &Value, at: &mut Vec<usize>, handles: bool, out: &mut Vec<Vec<usize>>) {
        match v {
            Value::Number(_) | Value::Integer(_) => out.push(at.clone()),
            Value::Point(_) | Value::Vector(_) => {
                let components: &[usize] = if handles { &[1] } else { &[0, 1, 2] };
                for &c in components {
                    at.push(c);
                    out.push(at.clone());
                    at.pop();
                }
            }
            Value::List(items) => {
                for (k, item) in items.iter().enumerate() {
                    at.push(k);
                    walk(item, at, handles, out);
                    at.pop();
                }
            }
            _ => {}
        }
    }
    let handles = port.widget() == Widget::MapperHandles;
    let mut paths = Vec::new();
    let mut at = variable.input.indices.clone();
    let mut inner = base;
    for &i in &variable.input.indices {
        match inner {
            Value::List(items) if i < items.len() => inner = &items[i],
            _ => return vec![variable.clone()],
        }
    }
    walk(inner, &mut at, handles, &mut paths);
    paths
        .into_iter()
        .map(|indices| Variable {
            input: super::path::ValuePath {
                indices,
                ..variable.input.clone()
            },
            ..variable.clone()
        })
        .collect()
}

impl Problem {
    /// Prepares `graph` for optimization. With `incremental` false every evaluation starts from a
    /// fresh evaluator (the full re-evaluation baseline for comparisons). A variable naming a
    /// whole list, table or point (`ratios.values`) stands for every number in it.
    pub fn new(graph: Graph, mut setup: Setup, incremental: bool) -> Result<Self, SetupMismatch> {
        let mut groups: Vec<Group> = Vec::new();
        let mut variables = Vec::new();
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
            let expanded = if v.input.get(&base).is_ok() {
                vec![v.clone()]
            } else {
                let all = expand(v, &base, &node.def.inputs[k]);
                if all.is_empty() {
                    return Err(SetupMismatch(format!(
                        "variable {}: the input holds no numbers",
                        v.input
                    )));
                }
                all
            };
            let g = match groups
                .iter()
                .position(|g| g.node == v.input.node && g.port == v.input.port)
            {
                Some(g) => g,
                None => {
                    groups.push(Group {
                        node: v.input.node.clone(),
                        port: v.input.port.clone(),
                        input: k,
                        base: base.clone(),
                        members: Vec::new(),
                    });
                    groups.len() - 1
                }
            };
            for e in expanded {
                e.input
                    .get(&base)
                    .map_err(|e| SetupMismatch(format!("variable {e}")))?;
                let leaf = leaves::offset(&base, &e.input.indices).ok_or_else(|| {
                    SetupMismatch(format!("variable {}: not a number of the input", e.input))
                })?;
                groups[g].members.push((variables.len(), leaf));
                variables.push(e);
            }
        }
        setup.variables = variables;
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
        let mut kept = Vec::new();
        for id in &setup.convex {
            let index = graph
                .index(id)
                .map_err(|_| SetupMismatch(format!("convex: no node '{id}'")))?;
            if convexity::margins_output(&graph, index).is_none() {
                let ty = graph.node_at(index).map_or("?", |n| n.def.id.as_ref());
                return Err(SetupMismatch(format!(
                    "convex: node '{id}' ({ty}) reports no convexity margins; name a \
                     construction (cnets.construct, cnets.construct_coplanar, ctube.construct)"
                )));
            }
            kept.push(index);
        }
        let targets: Vec<NodeIndex> = request.iter().chain(&kept).copied().collect();
        let active = active_nodes(&graph, &targets, &groups);
        let mut demand = derivative_demand(&graph, &request, &active);
        // Every construction on the path is watched (its folded faces are reported); those
        // `convex` names are kept convex.
        let mut watched = Vec::new();
        for (k, node) in graph.nodes() {
            let is_kept = kept.contains(&k);
            if !(is_kept || active[k.index()]) {
                continue;
            }
            let Some(output) = convexity::margins_output(&graph, k) else {
                continue;
            };
            watched.push(Watched {
                node: node.id.clone(),
                index: k,
                output,
                kept: is_kept,
            });
            match demand.iter_mut().find(|(d, _)| *d == k) {
                Some((_, mask)) => *mask = mask.union(OutputMask::one(output)),
                None => demand.push((k, OutputMask::one(output))),
            }
        }
        Ok(Self {
            graph,
            setup,
            evaluator: Evaluator::new(),
            incremental,
            active,
            demand,
            groups,
            watched,
            phase: Phase::Off,
            evaluations: 0,
            node_runs: 0,
        })
    }

    /// Number of variables (whole-input variables counted by their numbers).
    pub fn dimension(&self) -> usize {
        self.setup.variables.len()
    }

    /// The setup, whole-input variables expanded.
    pub fn setup(&self) -> &Setup {
        &self.setup
    }

    /// The variables' current values in the graph.
    pub fn start(&self) -> Vec<f64> {
        let mut x = vec![0.0; self.dimension()];
        for g in &self.groups {
            let flat = leaves::flatten(&g.base);
            for &(v, leaf) in &g.members {
                x[v] = flat.get(leaf).copied().unwrap_or(0.0);
            }
        }
        x
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
        for g in &mut self.groups {
            let mut updates: Vec<(usize, f64)> =
                g.members.iter().map(|&(v, leaf)| (leaf, x[v])).collect();
            updates.sort_by_key(|u| u.0);
            g.base = leaves::with_leaves(&g.base, &updates);
            self.graph
                .set_value(&g.node, &g.port, g.base.clone())
                .map_err(|e| e.to_string())?;
        }
        Ok(())
    }

    /// The objective plus penalties at `x`; `Err` when a node fails or a value is not a number.
    pub fn value(&mut self, x: &[f64], ctx: &NodeContext) -> Result<f64, String> {
        self.evaluate(x, ctx)?;
        let mut total = if self.phase == Phase::Feasibility {
            0.0
        } else {
            let mut total = self.read(&self.setup.objective.clone())?;
            for p in self.setup.penalties.clone() {
                total += p.value(self.read(&p.output)?);
            }
            total
        };
        if self.phase != Phase::Off {
            for w in self.watched.iter().filter(|w| w.kept) {
                let m = self.margins(w)?;
                total += convexity::term(self.phase, &m);
            }
        }
        if total.is_finite() {
            Ok(total)
        } else {
            Err(format!("the objective is not finite ({total})"))
        }
    }

    /// Writes `x` into the inputs and evaluates what the setup reads (counted).
    pub(super) fn evaluate(&mut self, x: &[f64], ctx: &NodeContext) -> Result<(), String> {
        self.apply(x)?;
        if !self.incremental {
            self.evaluator = Evaluator::new();
        }
        let summary =
            self.evaluator
                .evaluate_outputs(&self.graph, &self.demand, ctx, &mut |_, _| {});
        self.evaluations += 1;
        self.node_runs += summary.ran as u64;
        if summary.cancelled {
            return Err("cancelled".into());
        }
        Ok(())
    }

    /// An output of a node at the last evaluation (`Err` naming why it has none).
    pub(super) fn output_at(&self, index: NodeIndex, output: usize) -> Result<&Value, String> {
        let node = self.graph.node_at(index).map_or("?", |n| n.id.as_str());
        let result = self
            .evaluator
            .result_at(&self.graph, index)
            .ok_or_else(|| format!("node '{node}' was not evaluated"))?;
        let outputs = result
            .outputs()
            .ok_or_else(|| self.failure_message(node, result))?;
        outputs
            .values
            .get(output)
            .ok_or_else(|| format!("node '{node}' has no output {output}"))
    }

    /// The margins of a watched construction at the last evaluation.
    pub(super) fn margins(&self, w: &Watched) -> Result<Vec<f64>, String> {
        let result = self
            .evaluator
            .result_at(&self.graph, w.index)
            .ok_or_else(|| format!("node '{}' was not evaluated", w.node))?;
        let outputs = result
            .outputs()
            .ok_or_else(|| self.failure_message(&w.node, result))?;
        Ok(convexity::numbers(&outputs.values[w.output]))
    }

    /// Per watched construction, its faces that are not (++)(++) at the last evaluation (a
    /// construction that failed there counts all of its faces as unknown: `None`).
    pub fn not_convex(&self) -> Vec<(String, Option<usize>)> {
        self.watched
            .iter()
            .map(|w| {
                (
                    w.node.clone(),
                    self.margins(w).ok().map(|m| convexity::folded_faces(&m)),
                )
            })
            .collect()
    }

    /// Whether a construction named in `convex` has a folded face at the last evaluation.
    pub(super) fn kept_folded(&self) -> bool {
        self.watched.iter().filter(|w| w.kept).any(|w| {
            self.margins(w)
                .map_or(true, |m| convexity::folded_faces(&m) > 0)
        })
    }

    /// Whether the setup keeps faces convex.
    pub(super) fn keeps_convex(&self) -> bool {
        self.watched.iter().any(|w| w.kept)
    }

    fn read(&self, path: &super::path::ValuePath) -> Result<f64, String> {
        let result = self
            .evaluator
            .result(&self.graph, &path.node)
            .ok_or_else(|| format!("{path} was not evaluated"))?;
        let outputs = result
            .outputs()
            .ok_or_else(|| self.failure_message(&path.node, result))?;
        let k = self
            .graph
            .node(&path.node)
            .and_then(|n| n.def.output_index(&path.port))
            .ok_or_else(|| format!("{path}: no such output"))?;
        path.get(&outputs.values[k])
    }

    /// Why `node` has no outputs: its own error, and when a failed node upstream blocked it, that
    /// node's own message (the nearest failed nodes on every path, in the order found), so
    /// "comes from 'reference_hull', which failed" is followed by why it failed.
    fn failure_message(&self, node: &str, result: &NodeResult) -> String {
        let mut message = format!(
            "node '{node}': {}",
            result.error().as_deref().unwrap_or("failed")
        );
        if !matches!(result, NodeResult::Blocked(_)) {
            return message;
        }
        let Ok(start) = self.graph.index(node) else {
            return message;
        };
        let mut seen = vec![false; self.graph.index_bound()];
        let mut queue = std::collections::VecDeque::from([start]);
        seen[start.index()] = true;
        while let Some(k) = queue.pop_front() {
            for s in self.graph.sources(k) {
                if std::mem::replace(&mut seen[s.index()], true) {
                    continue;
                }
                match self.evaluator.result_at(&self.graph, s) {
                    Some(r) if r.is_failure() => {
                        let id = self.graph.node_at(s).map_or("?", |n| n.id.as_str());
                        let why = r.error().map(|e| e.into_owned()).unwrap_or_default();
                        message.push_str(&format!("; '{id}' failed: {why}"));
                    }
                    Some(NodeResult::Blocked(_)) => queue.push_back(s),
                    _ => {}
                }
            }
        }
        message
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

/// The nodes downstream of a variable (a literal input holding one) and upstream of a requested
/// node, by index.
fn active_nodes(graph: &Graph, request: &[NodeIndex], groups: &[Group]) -> Vec<bool> {
    let n = graph.index_bound();
    let walk = |mut stack: Vec<NodeIndex>, forward: bool| {
        let mut seen = vec![false; n];
        for k in &stack {
            seen[k.index()] = true;
        }
        while let Some(k) = stack.pop() {
            let next: Vec<NodeIndex> = if forward {
                graph.targets(k).collect()
            } else {
                graph.sources(k).collect()
            };
            for t in next {
                if !seen[t.index()] {
                    seen[t.index()] = true;
                    stack.push(t);
                }
            }
        }
        seen
    };
    let starts = groups
        .iter()
        .filter_map(|g| graph.index(&g.node).ok())
        .collect();
    let down = walk(starts, true);
    let up = walk(request.to_vec(), false);
    down.iter().zip(&up).map(|(d, u)| *d && *u).collect()
}

/// The outputs one evaluation asks for: every output of the requested nodes, and the outputs the
/// derivatives of the active nodes read off the path.
fn derivative_demand(
    graph: &Graph,
    request: &[NodeIndex],
    active: &[bool],
) -> Vec<(NodeIndex, OutputMask)> {
    let mut demand: Vec<(NodeIndex, OutputMask)> =
        request.iter().map(|&k| (k, OutputMask::ALL)).collect();
    for (k, node) in graph.nodes() {
        let needs = node.def.derivative_outputs;
        if needs.is_empty() || !active[k.index()] || request.contains(&k) {
            continue;
        }
        let names: Vec<&str> = node.def.outputs.iter().map(|p| p.name.as_ref()).collect();
        demand.push((k, OutputMask::of_names(names, needs)));
    }
    demand
}
