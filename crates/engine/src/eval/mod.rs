//! Incremental, pull-based evaluation with early cutoff.
//!
//! The model is salsa's: every node has a memo with the revision it was last *verified* at and the
//! revision its outputs last *changed* at. Evaluating a request walks only the requested nodes and
//! what they depend on, skipping nodes already verified at the current revision. A node re-runs only
//! when it was edited or one of its sources changed after it was verified. When a re-run produces
//! outputs equal to the previous ones (same content hash, confirmed bitwise), its `changed_at` is
//! kept — it is *backdated* — so its dependents do not re-run (early cutoff).

mod mapping;
mod panic_guard;
pub mod reads;
mod result;

pub use mapping::run_mapped;
pub use reads::FileStamp;
pub use result::{NodeOutputs, NodeResult};

use std::sync::Arc;
use std::time::Duration;
#[cfg(not(target_arch = "wasm32"))]
use std::time::Instant;
// std's clock panics on wasm32-unknown-unknown (the web editor); web-time reads the browser's.
#[cfg(target_arch = "wasm32")]
use web_time::Instant;

use petgraph::stable_graph::NodeIndex;

use crate::budget::bytes_of;
use crate::graph::{Graph, NodeInstance, Revision};
use crate::node::{NodeContext, NodeDef};
use crate::value::{Value, content_hash, first_non_finite, footprint, is_all_finite};

/// The evaluator's clock: the graph's revision, then a count of the times files read by nodes
/// changed while the graph stood still (ordered lexicographically).
type Tick = (Revision, u64);

/// The memo of one node instance.
#[derive(Debug, Clone)]
struct Memo {
    uid: u64,
    verified_at: Tick,
    changed_at: Tick,
    result: NodeResult,
    hashes: Vec<u64>,
    time: Duration,
    runs: u64,
    /// Files the node read on its last run.
    reads: Vec<FileStamp>,
    /// One of those files changed since: the node must re-run.
    stale: bool,
    /// Bytes the result holds that no other result holds (its share of the live memory).
    owned: u64,
}

/// What one call to [`Evaluator::evaluate`] did.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct EvalSummary {
    /// Nodes looked at (requested plus their out-of-date dependencies).
    pub visited: usize,
    /// Nodes that actually ran.
    pub ran: usize,
    /// Re-runs whose outputs were unchanged (early cutoff stopped propagation there).
    pub cut_off: usize,
    /// The evaluation stopped early because cancellation was requested.
    pub cancelled: bool,
}

/// Memoized evaluation state for one graph. Keep one evaluator per graph and call
/// [`Evaluator::evaluate`] after edits; only what changed re-runs.
#[derive(Debug, Default)]
pub struct Evaluator {
    memos: Vec<Option<Memo>>,
    stack: Vec<(NodeIndex, bool)>,
    order: Vec<NodeIndex>,
    marks: Vec<u32>,
    stamp: u32,
    total_runs: u64,
    swept_at: Revision,
    file_epoch: u64,
    /// Bytes held by all memoized results (the sum of their `owned`).
    live: u64,
}

impl Evaluator {
    /// A fresh evaluator with nothing memoized.
    pub fn new() -> Self {
        Self::default()
    }

    /// Evaluates every node of the graph.
    pub fn evaluate_all(&mut self, graph: &Graph, ctx: &NodeContext) -> EvalSummary {
        let all: Vec<NodeIndex> = graph.nodes().map(|(k, _)| k).collect();
        self.evaluate(graph, &all, ctx, &mut |_, _| {})
    }

    /// Evaluates the requested nodes and whatever they depend on. `progress(done, total)` is called
    /// before each node that has to run.
    pub fn evaluate(
        &mut self,
        graph: &Graph,
        request: &[NodeIndex],
        ctx: &NodeContext,
        progress: &mut dyn FnMut(usize, usize),
    ) -> EvalSummary {
        let revision = graph.revision();
        self.prepare(graph, revision);
        if self.mark_changed_files() {
            self.file_epoch += 1;
        }
        let revision: Tick = (revision, self.file_epoch);
        self.plan(graph, request, revision);
        let mut summary = EvalSummary {
            visited: self.order.len(),
            ..EvalSummary::default()
        };
        let order = std::mem::take(&mut self.order);
        // Bytes held outside this evaluator (an enclosing graph's values, for a cluster).
        let outside = ctx.in_use();
        for (done, &node) in order.iter().enumerate() {
            let Some(instance) = graph.node_at(node) else {
                continue;
            };
            if !self.needs_run(graph, node, instance) {
                if let Some(memo) = self.memos[node.index()].as_mut() {
                    memo.verified_at = revision;
                }
                continue;
            }
            if ctx.cancelled() {
                summary.cancelled = true;
                break;
            }
            progress(done, order.len());
            let own = self.memos[node.index()].as_ref().map_or(0, |m| m.owned);
            let held = outside.saturating_add(self.live.saturating_sub(own));
            ctx.take_held();
            ctx.set_in_use(held);
            let start = Instant::now();
            let (result, executed) = self.run_node(graph, node, instance, ctx);
            let (result, owned) = within_budget(result, instance, ctx, held, ctx.take_held());
            let time = start.elapsed();
            summary.ran += usize::from(executed);
            let stored = Stored {
                result,
                time,
                executed,
                owned,
                reads: ctx.take_reads(),
            };
            if self.store(node, instance.uid(), revision, stored) && executed {
                summary.cut_off += 1;
            }
        }
        ctx.set_in_use(outside);
        self.order = order;
        summary
    }

    /// Grows side tables to the graph's index bound and drops memos of removed nodes.
    fn prepare(&mut self, graph: &Graph, revision: Revision) {
        let bound = graph.index_bound();
        if self.memos.len() < bound {
            self.memos.resize_with(bound, || None);
            self.marks.resize(bound, 0);
        }
        if self.swept_at != revision {
            self.swept_at = revision;
            for (k, memo) in self.memos.iter_mut().enumerate() {
                let alive = graph.node_at(NodeIndex::new(k)).map(NodeInstance::uid);
                if let Some(m) = memo.as_ref().filter(|m| Some(m.uid) != alive) {
                    self.live = self.live.saturating_sub(m.owned);
                    *memo = None;
                }
            }
        }
    }

    /// Marks the memos whose read files changed; true when there was one.
    fn mark_changed_files(&mut self) -> bool {
        let mut any = false;
        for memo in self.memos.iter_mut().flatten() {
            if !memo.stale && memo.reads.iter().any(FileStamp::changed) {
                memo.stale = true;
                any = true;
            }
        }
        any
    }

    /// Fills `self.order` with the out-of-date part of the request, sources before targets.
    fn plan(&mut self, graph: &Graph, request: &[NodeIndex], revision: Tick) {
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.marks.iter_mut().for_each(|m| *m = 0);
            self.stamp = 1;
        }
        self.order.clear();
        self.stack.clear();
        self.stack.extend(request.iter().rev().map(|&n| (n, false)));
        while let Some((node, expanded)) = self.stack.pop() {
            if expanded {
                self.order.push(node);
                continue;
            }
            let k = node.index();
            if k >= self.marks.len() || self.marks[k] == self.stamp || graph.node_at(node).is_none()
            {
                continue;
            }
            self.marks[k] = self.stamp;
            if self.memos[k]
                .as_ref()
                .is_some_and(|m| m.verified_at == revision)
            {
                continue;
            }
            self.stack.push((node, true));
            for source in graph.sources(node) {
                if self.marks[source.index()] != self.stamp {
                    self.stack.push((source, false));
                }
            }
        }
    }

    fn needs_run(&self, graph: &Graph, node: NodeIndex, instance: &NodeInstance) -> bool {
        let Some(memo) = &self.memos[node.index()] else {
            return true;
        };
        if memo.uid != instance.uid() || memo.stale || instance.edited_at() > memo.verified_at.0 {
            return true;
        }
        graph.sources(node).any(|s| {
            self.memos[s.index()]
                .as_ref()
                .is_none_or(|m| m.changed_at > memo.verified_at)
        })
    }

    /// Stores a new result; returns true when it equals the previous one (backdated).
    fn store(&mut self, node: NodeIndex, uid: u64, revision: Tick, stored: Stored) -> bool {
        let Stored {
            result,
            time,
            executed,
            owned,
            reads,
        } = stored;
        let ran = u64::from(executed);
        self.total_runs += ran;
        let hashes = match &result {
            NodeResult::Ok(outputs) => outputs.values.iter().map(content_hash).collect(),
            _ => Vec::new(),
        };
        let slot = &mut self.memos[node.index()];
        let unchanged = slot.as_ref().is_some_and(|old| {
            old.uid == uid && old.hashes == hashes && old.result.same_as(&result)
        });
        self.live = self
            .live
            .saturating_sub(slot.as_ref().map_or(0, |m| m.owned))
            .saturating_add(owned);
        let (changed_at, runs) = match slot.as_ref() {
            Some(old) if old.uid == uid && unchanged => (old.changed_at, old.runs + ran),
            Some(old) if old.uid == uid => (revision, old.runs + ran),
            _ => (revision, ran),
        };
        *slot = Some(Memo {
            uid,
            verified_at: revision,
            changed_at,
            result,
            hashes,
            time,
            runs,
            reads,
            stale: false,
            owned,
        });
        unchanged
    }

    /// Bytes held by the memoized results (each shared payload counted once, by the result that
    /// made it).
    pub fn live_bytes(&self) -> u64 {
        self.live
    }

    /// Gathers the inputs of a node and runs it (catching panics). The flag tells whether the node's
    /// function was called (not when it is disabled, blocked or missing inputs).
    fn run_node(
        &self,
        graph: &Graph,
        node: NodeIndex,
        instance: &NodeInstance,
        ctx: &NodeContext,
    ) -> (NodeResult, bool) {
        match self.gather_inputs(graph, node, instance, ctx) {
            Ok(inputs) => (self.call(instance, &inputs, ctx), true),
            Err(result) => (result, false),
        }
    }

    fn call(&self, instance: &NodeInstance, inputs: &[Value], ctx: &NodeContext) -> NodeResult {
        match evaluate_node(&instance.def, ctx, inputs) {
            Ok(outputs) => NodeResult::Ok(Arc::new(outputs)),
            Err(message) => NodeResult::Failed(message),
        }
    }

    /// The input values of a node: wired values (merged when several wires meet), else the literal,
    /// else the default. `Err` carries the result for a node that cannot run.
    fn gather_inputs(
        &self,
        graph: &Graph,
        node: NodeIndex,
        instance: &NodeInstance,
        ctx: &NodeContext,
    ) -> Result<Vec<Value>, NodeResult> {
        if !instance.enabled {
            return Err(NodeResult::Disabled);
        }
        let def = &instance.def;
        let mut inputs: Vec<Value> = Vec::with_capacity(def.inputs.len());
        let mut wired: Vec<Vec<Value>> = vec![Vec::new(); def.inputs.len()];
        for (source, wire) in graph.wires_into(node) {
            let port = &def.inputs[wire.to_input].name;
            let source_id = graph.node_at(source).map_or("?", |n| n.id.as_str());
            match self.memos[source.index()].as_ref().map(|m| &m.result) {
                Some(NodeResult::Ok(outputs)) => match outputs.values.get(wire.from_output) {
                    Some(v) => wired[wire.to_input].push(v.clone()),
                    None => {
                        return Err(NodeResult::Blocked(format!(
                            "input '{port}': '{source_id}' has no such output"
                        )));
                    }
                },
                Some(NodeResult::Disabled) => {
                    return Err(NodeResult::Blocked(format!(
                        "input '{port}' comes from '{source_id}', which is disabled"
                    )));
                }
                Some(_) => {
                    return Err(NodeResult::Blocked(format!(
                        "input '{port}' comes from '{source_id}', which failed"
                    )));
                }
                None => {
                    return Err(NodeResult::Blocked(format!(
                        "input '{port}': '{source_id}' was not evaluated"
                    )));
                }
            }
        }
        for (k, (port, mut values)) in def.inputs.iter().zip(wired).enumerate() {
            let value = match values.len() {
                0 => match instance.value(k).or(port.default.as_ref()) {
                    Some(v) => v.clone(),
                    None if port.optional => Value::Null,
                    None => {
                        return Err(NodeResult::Invalid(format!(
                            "input '{}' is required: connect it or set a value",
                            port.name
                        )));
                    }
                },
                1 => values.pop().unwrap_or_default(),
                _ => {
                    // The merged list is new memory: checked before it is built.
                    let items: usize = values
                        .iter()
                        .map(|v| match v {
                            Value::List(items) => items.len(),
                            _ => 1,
                        })
                        .sum();
                    let what = format!(
                        "input '{}': merging {} wires into a list of {items} items",
                        port.name,
                        values.len()
                    );
                    ctx.reserve_values(items as u128, &what)
                        .map_err(|e| NodeResult::Failed(e.message))?;
                    merge(values)
                }
            };
            inputs.push(value);
        }
        Ok(inputs)
    }

    /// The last result of a node.
    pub fn result(&self, graph: &Graph, id: &str) -> Option<&NodeResult> {
        let index = graph.index(id).ok()?;
        self.result_at(graph, index)
    }

    /// The last result of the node at `index` (if it is still the same node).
    pub fn result_at(&self, graph: &Graph, index: NodeIndex) -> Option<&NodeResult> {
        let uid = graph.node_at(index)?.uid();
        let memo = self.memos.get(index.index())?.as_ref()?;
        (memo.uid == uid).then_some(&memo.result)
    }

    /// The value of a named output after the last evaluation.
    pub fn output(&self, graph: &Graph, id: &str, output: &str) -> Option<&Value> {
        let node = graph.node(id)?;
        let k = node.def.output_index(output)?;
        self.result(graph, id)?.outputs()?.values.get(k)
    }

    /// How many times the node has run since it was added (or since this evaluator was created).
    pub fn runs(&self, graph: &Graph, id: &str) -> u64 {
        self.memo(graph, id).map_or(0, |m| m.runs)
    }

    /// Duration of the node's last run.
    pub fn time(&self, graph: &Graph, id: &str) -> Option<Duration> {
        self.memo(graph, id).map(|m| m.time)
    }

    /// Content hashes of the node's outputs after its last successful run.
    pub fn output_hashes(&self, graph: &Graph, id: &str) -> Option<&[u64]> {
        self.memo(graph, id).map(|m| m.hashes.as_slice())
    }

    /// Revision at which the node's outputs last changed.
    pub fn changed_at(&self, graph: &Graph, id: &str) -> Option<Revision> {
        self.memo(graph, id).map(|m| m.changed_at.0)
    }

    /// Every file read by the memoized nodes.
    pub fn all_reads(&self) -> Vec<FileStamp> {
        self.memos
            .iter()
            .flatten()
            .flat_map(|m| m.reads.iter().cloned())
            .collect()
    }

    /// The files the node read on its last run.
    pub fn reads(&self, graph: &Graph, id: &str) -> &[FileStamp] {
        self.memo(graph, id).map_or(&[], |m| m.reads.as_slice())
    }

    /// Total node runs over the life of this evaluator.
    pub fn total_runs(&self) -> u64 {
        self.total_runs
    }

    fn memo(&self, graph: &Graph, id: &str) -> Option<&Memo> {
        let index = graph.index(id).ok()?;
        let uid = graph.node_at(index)?.uid();
        self.memos
            .get(index.index())?
            .as_ref()
            .filter(|m| m.uid == uid)
    }
}

/// A node's new result, what it cost, and the files it read.
struct Stored {
    result: NodeResult,
    time: Duration,
    executed: bool,
    owned: u64,
    reads: Vec<FileStamp>,
}

/// The memory budget after a node ran: its outputs must fit beside the `held` bytes of the other
/// results, with the `kept` bytes the node keeps alive elsewhere (a cluster's inner results; a full
/// read of the outputs was checked by [`evaluate_node`]). Over budget, the node fails (its
/// outputs are dropped) and its dependents are blocked. Returns the result and the bytes it holds.
fn within_budget(
    result: NodeResult,
    instance: &NodeInstance,
    ctx: &NodeContext,
    held: u64,
    kept: u64,
) -> (NodeResult, u64) {
    let NodeResult::Ok(outputs) = &result else {
        return (result, 0);
    };
    // Measured again now that the inputs are gone: a list the evaluator merged and the node passed
    // through is held by this result alone.
    let owned = footprint(&outputs.values).owned_bytes.saturating_add(kept);
    let what = format!("the outputs of '{}'", instance.id);
    if let Err(e) = ctx.budget.check(owned, held, &what) {
        return (NodeResult::Failed(e.to_string()), 0);
    }
    (result, owned)
}

/// Runs one node type on raw input values (one per input port, `Null` for empty), as a graph run
/// does and outside any graph: maps over lists, catches panics, collects warnings and written
/// files, and fails the node when an output holds a non-finite number.
pub fn evaluate_node(
    def: &NodeDef,
    ctx: &NodeContext,
    inputs: &[Value],
) -> Result<NodeOutputs, String> {
    let outcome = panic_guard::catch(|| run_mapped(def, ctx, inputs));
    let warnings = ctx.take_warnings();
    let files = ctx.take_files();
    match outcome {
        Ok(Ok(values)) => {
            // Measured before anything reads every value (the finiteness scan, hashing, JSON):
            // a list shared many times over may read as more values than memory holds.
            let footprint = footprint(&values);
            let read = bytes_of(footprint.read_values, std::mem::size_of::<Value>());
            let what = format!(
                "reading the outputs ({} values: lists shared many times over)",
                footprint.read_values
            );
            ctx.budget
                .check(read, 0, &what)
                .map_err(|e| e.to_string())?;
            match non_finite_output(def, &values) {
                Some(message) => Err(message),
                None => Ok(NodeOutputs {
                    values,
                    warnings,
                    files,
                    footprint,
                }),
            }
        }
        Ok(Err(e)) => Err(e.message),
        Err(panic) => Err(panic),
    }
}

/// NaN or ±∞ in an output (an overflow, a division by zero, NaN passed along) is the node's error:
/// downstream nodes are blocked with a reason instead of computing on garbage, and no non-finite
/// number reaches a file or the JSON output.
fn non_finite_output(def: &NodeDef, values: &[Value]) -> Option<String> {
    if values.iter().all(is_all_finite) {
        return None;
    }
    def.outputs.iter().zip(values).find_map(|(port, value)| {
        first_non_finite(value).map(|at| {
            let at = if at.is_empty() { at } else { format!(" at {at}") };
            format!(
                "output '{}' is not a finite number{at} (an overflow or an undefined result: check the inputs' values and scale)",
                port.name
            )
        })
    })
}

/// Several wires into one input: their values are concatenated into one list (lists contribute
/// their items, single values themselves), in wire order.
fn merge(values: Vec<Value>) -> Value {
    let mut items = Vec::new();
    for v in values {
        match v {
            Value::List(list) => items.extend(list.iter().cloned()),
            other => items.push(other),
        }
    }
    Value::list(items)
}
