//! Incremental, pull-based evaluation with early cutoff.
//!
//! The model is salsa's: every node has a memo with the revision it was last *verified* at and the
//! revision its outputs last *changed* at. Evaluating a request walks only the requested nodes and
//! what they depend on, skipping nodes already verified at the current revision. A node re-runs only
//! when it was edited or one of its sources changed after it was verified. When a re-run produces
//! outputs equal to the previous ones (same content hash, confirmed bitwise), its `changed_at` is
//! kept — it is *backdated* — so its dependents do not re-run (early cutoff).
//!
//! Outputs are lazy: each node is asked only for the outputs the request needs (those wired to a
//! node that runs, and those the caller requests: [`demand`]). A node may skip the others; its memo
//! records which outputs it computed and when each one last changed. A node whose inputs did not
//! change but which is now asked for an output it skipped runs again to *fill in* that output: the
//! outputs it had keep their values and revisions, so their consumers stay verified.

mod mapping;
mod panic_guard;
mod result;

/// What a node saw of a file it read (the node contract's own type, moved down to `node`).
pub use crate::node::FileStamp;
/// Which outputs are requested (the node contract's own type, moved down to `node`).
pub use crate::node::OutputMask;
pub use mapping::run_mapped;
pub use result::{NodeOutputs, NodeResult};

use std::borrow::Cow;
use std::sync::Arc;
use std::time::Duration;
#[cfg(not(target_arch = "wasm32"))]
use std::time::Instant;
// std's clock panics on wasm32-unknown-unknown (the web editor); web-time reads the browser's.
#[cfg(target_arch = "wasm32")]
use web_time::Instant;

use petgraph::stable_graph::NodeIndex;

use crate::budget::bytes_of;
use crate::graph::{Continued, Graph, NodeInstance, Revision};
use crate::node::{NodeContext, NodeDef, NodeError, PortDef};
use crate::value::{Value, content_hash, first_non_finite, footprint, is_all_finite};

/// The evaluator's clock: the graph's revision, then a count of the times files read by nodes
/// changed while the graph stood still (ordered lexicographically).
type Tick = (Revision, u64);

/// The memo of one node instance.
#[derive(Debug, Clone)]
struct Memo {
    uid: u64,
    verified_at: Tick,
    /// The latest of the computed outputs' `changed` (the node's revision of change).
    changed_at: Tick,
    /// Per output: when its value last changed (an output not computed counts as changed at the
    /// run that did not compute it).
    changed: Vec<Tick>,
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

impl Memo {
    /// When output `k` last changed.
    fn changed_of(&self, k: usize) -> Tick {
        self.changed
            .get(k)
            .or(self.changed.last())
            .copied()
            .unwrap_or(self.changed_at)
    }

    /// The outputs this memo holds values for (an error covers every output).
    fn have(&self) -> OutputMask {
        match &self.result {
            NodeResult::Ok(outputs) => OutputMask::ALL.minus(outputs.missing),
            _ => OutputMask::ALL,
        }
    }
}

/// What a planned node needs.
enum Action {
    /// Its memo is valid and holds every requested output.
    UpToDate,
    /// Its inputs did not change, but it lacks these requested outputs.
    Fill(OutputMask),
    /// Its inputs changed (or it never ran): run it for these outputs.
    Run(OutputMask),
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
    /// Runs that only filled in outputs asked for after the node had skipped them (counted in
    /// `ran` too).
    pub filled: usize,
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
    /// The outputs requested of each node in the current plan (valid where `demand_stamp` is the
    /// current stamp).
    demand: Vec<OutputMask>,
    demand_stamp: Vec<u32>,
    /// The node was planned as up to date (not expanded): more demand may expand it.
    satisfied: Vec<bool>,
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

    /// Evaluates the requested nodes (every output of each) and whatever they depend on.
    /// `progress(done, total)` is called before each node that has to run.
    pub fn evaluate(
        &mut self,
        graph: &Graph,
        request: &[NodeIndex],
        ctx: &NodeContext,
        progress: &mut dyn FnMut(usize, usize),
    ) -> EvalSummary {
        self.evaluate_request(graph, request, None, ctx, progress)
    }

    /// Evaluates the requested outputs (`request`: a node and the outputs asked of it; an empty
    /// mask still runs the node, e.g. to report its errors) and whatever they depend on. Upstream
    /// nodes are asked only for their outputs wired into nodes that run. `progress(done, total)`
    /// is called before each node that has to run.
    pub fn evaluate_outputs(
        &mut self,
        graph: &Graph,
        request: &[(NodeIndex, OutputMask)],
        ctx: &NodeContext,
        progress: &mut dyn FnMut(usize, usize),
    ) -> EvalSummary {
        let (nodes, masks): (Vec<NodeIndex>, Vec<OutputMask>) = request.iter().copied().unzip();
        self.evaluate_request(graph, &nodes, Some(&masks), ctx, progress)
    }

    fn evaluate_request(
        &mut self,
        graph: &Graph,
        request: &[NodeIndex],
        masks: Option<&[OutputMask]>,
        ctx: &NodeContext,
        progress: &mut dyn FnMut(usize, usize),
    ) -> EvalSummary {
        let revision = graph.revision();
        self.prepare(graph, revision);
        if self.mark_changed_files() {
            self.file_epoch += 1;
        }
        let revision: Tick = (revision, self.file_epoch);
        self.plan(graph, request, masks, revision);
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
            let demand = self.demand_at(node.index());
            let (mask, fill) = match self.action(graph, node, instance, demand) {
                Action::UpToDate => {
                    if let Some(memo) = self.memos[node.index()].as_mut() {
                        memo.verified_at = revision;
                    }
                    continue;
                }
                Action::Fill(missing) => (missing, true),
                Action::Run(demand) => (demand, false),
            };
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
            let (result, executed) = self.run_node(graph, node, instance, ctx, mask);
            let (result, fill) = if fill {
                self.fill_in(node, result)
            } else {
                (result, false)
            };
            let (result, owned) = within_budget(result, instance, ctx, held, ctx.take_held());
            let time = start.elapsed();
            summary.ran += usize::from(executed);
            summary.filled += usize::from(fill);
            let stored = Stored {
                result,
                time,
                executed,
                fill,
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
            self.demand.resize(bound, OutputMask::NONE);
            self.demand_stamp.resize(bound, 0);
            self.satisfied.resize(bound, false);
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

    /// Fills `self.order` with the out-of-date part of the request, sources before targets, and
    /// `self.demand` with the outputs asked of each planned node: the request's, and those wired
    /// into a node that is expanded (may run). A node already verified at `revision` and holding
    /// its demand is not expanded — unless a later consumer asks it for an output it lacks.
    fn plan(
        &mut self,
        graph: &Graph,
        request: &[NodeIndex],
        masks: Option<&[OutputMask]>,
        revision: Tick,
    ) {
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.marks.iter_mut().for_each(|m| *m = 0);
            self.demand_stamp.iter_mut().for_each(|m| *m = 0);
            self.stamp = 1;
        }
        self.order.clear();
        self.stack.clear();
        for (k, &node) in request.iter().enumerate().rev() {
            self.add_demand(node, masks.map_or(OutputMask::ALL, |m| m[k]));
            self.stack.push((node, false));
        }
        while let Some((node, expanded)) = self.stack.pop() {
            if expanded {
                self.order.push(node);
                continue;
            }
            let k = node.index();
            if k >= self.marks.len() || graph.node_at(node).is_none() {
                continue;
            }
            if self.marks[k] == self.stamp {
                // Planned already: expanded (its demand is read when it runs), or up to date and
                // still holding everything asked of it.
                if !self.satisfied[k] || self.covered(k) {
                    continue;
                }
            } else {
                self.marks[k] = self.stamp;
                if self.memos[k]
                    .as_ref()
                    .is_some_and(|m| m.verified_at == revision)
                    && self.covered(k)
                {
                    self.satisfied[k] = true;
                    continue;
                }
            }
            self.satisfied[k] = false;
            self.stack.push((node, true));
            for (source, output) in graph.inputs_of(node) {
                self.add_demand(source, OutputMask::one(output));
                let s = source.index();
                if s < self.marks.len() && (self.marks[s] != self.stamp || self.satisfied[s]) {
                    self.stack.push((source, false));
                }
            }
        }
    }

    /// Adds outputs to what the current plan asks of `node`.
    fn add_demand(&mut self, node: NodeIndex, mask: OutputMask) {
        let k = node.index();
        if k >= self.demand.len() {
            return;
        }
        if self.demand_stamp[k] != self.stamp {
            self.demand_stamp[k] = self.stamp;
            self.demand[k] = OutputMask::NONE;
        }
        self.demand[k] = self.demand[k].union(mask);
    }

    /// The outputs the current plan asks of the node at index `k`.
    fn demand_at(&self, k: usize) -> OutputMask {
        if self.demand_stamp.get(k) == Some(&self.stamp) {
            self.demand[k]
        } else {
            OutputMask::NONE
        }
    }

    /// True when the node's memo holds every output the current plan asks of it.
    fn covered(&self, k: usize) -> bool {
        self.memos[k]
            .as_ref()
            .is_some_and(|m| m.have().covers(self.demand_at(k)))
    }

    /// Whether a planned node must run, fill in outputs, or is up to date.
    fn action(
        &self,
        graph: &Graph,
        node: NodeIndex,
        instance: &NodeInstance,
        demand: OutputMask,
    ) -> Action {
        let Some(memo) = &self.memos[node.index()] else {
            return Action::Run(demand);
        };
        if memo.uid != instance.uid() || memo.stale || instance.edited_at() > memo.verified_at.0 {
            return Action::Run(demand);
        }
        let sources_changed = graph.inputs_of(node).any(|(s, output)| {
            self.memos[s.index()]
                .as_ref()
                .is_none_or(|m| m.changed_of(output) > memo.verified_at)
        });
        if sources_changed {
            return Action::Run(demand);
        }
        let have = memo.have();
        if have.covers(demand) {
            Action::UpToDate
        } else {
            Action::Fill(demand.minus(have))
        }
    }

    /// Merges a fill-in run's result into the memo's: the outputs the memo had keep their values
    /// (their consumers stay verified), the newly computed ones are added. Returns the merged
    /// result and whether it was a fill-in (not when either run failed: then the new result stands
    /// as a full run's).
    fn fill_in(&self, node: NodeIndex, result: NodeResult) -> (NodeResult, bool) {
        let old = match self.memos[node.index()].as_ref().map(|m| &m.result) {
            Some(NodeResult::Ok(old)) => old,
            _ => return (result, false),
        };
        let NodeResult::Ok(new) = &result else {
            return (result, false);
        };
        let values: Vec<Value> = old
            .values
            .iter()
            .zip(&new.values)
            .enumerate()
            .map(|(k, (o, n))| if old.missing.contains(k) { n } else { o }.clone())
            .collect();
        let merged = NodeOutputs {
            footprint: footprint(&values),
            values,
            warnings: new.warnings.clone(),
            files: new.files.clone(),
            missing: old.missing.intersection(new.missing),
        };
        (NodeResult::Ok(Arc::new(merged)), true)
    }

    /// Stores a new result; returns true when it equals the previous one (backdated).
    fn store(&mut self, node: NodeIndex, uid: u64, revision: Tick, stored: Stored) -> bool {
        let Stored {
            result,
            time,
            executed,
            fill,
            owned,
            reads,
        } = stored;
        let ran = u64::from(executed);
        self.total_runs += ran;
        let hashes: Vec<u64> = match &result {
            NodeResult::Ok(outputs) => outputs.values.iter().map(content_hash).collect(),
            _ => Vec::new(),
        };
        let slot = &mut self.memos[node.index()];
        let old = slot.as_ref().filter(|old| old.uid == uid);
        let (changed, changed_at, unchanged) = match (old, &result) {
            // A fill-in: the kept outputs keep their revisions, and the new ones count as changed
            // at the run that skipped them (when the inputs they come from last changed).
            (Some(old), NodeResult::Ok(_)) if fill => (old.changed.clone(), old.changed_at, false),
            (Some(old), NodeResult::Ok(new)) => match &old.result {
                NodeResult::Ok(prev) => {
                    let mut changed = Vec::with_capacity(new.values.len());
                    let mut latest = None;
                    let mut all_same = prev.missing == new.missing;
                    for (k, value) in new.values.iter().enumerate() {
                        let same = !new.missing.contains(k)
                            && !prev.missing.contains(k)
                            && old.hashes.get(k) == hashes.get(k)
                            && prev.values.get(k).is_some_and(|p| p.same_as(value));
                        let tick = if same { old.changed_of(k) } else { revision };
                        if !new.missing.contains(k) {
                            all_same &= same;
                            latest = latest.max(Some(tick));
                        }
                        changed.push(tick);
                    }
                    let latest = latest.unwrap_or(if all_same { old.changed_at } else { revision });
                    (changed, latest, all_same)
                }
                _ => (vec![revision; new.values.len()], revision, false),
            },
            (Some(old), _) if old.result.same_as(&result) => {
                (old.changed.clone(), old.changed_at, true)
            }
            _ => {
                let count = result.outputs().map_or(1, |o| o.values.len());
                (vec![revision; count], revision, false)
            }
        };
        let runs = old.map_or(0, |m| m.runs) + ran;
        self.live = self
            .live
            .saturating_sub(slot.as_ref().map_or(0, |m| m.owned))
            .saturating_add(owned);
        *slot = Some(Memo {
            uid,
            verified_at: revision,
            changed_at,
            changed,
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

    /// Moves the memos over to `next`, a graph replacing the one this evaluator last evaluated
    /// (another document opened in its place), given the nodes that continue one another
    /// ([`Graph::take_over`]; `next` may have been edited since): each continued node still in
    /// `next` keeps its result, run count and stamps; every other memo is dropped. When
    /// `same_folder` is false (relative paths of `next` resolve in another folder) the memos of
    /// nodes that read files are dropped too, since the same path may name another file.
    pub fn carry_over(&mut self, next: &Graph, carried: &[Continued], same_folder: bool) {
        let mut old = std::mem::take(&mut self.memos);
        let bound = next.index_bound();
        self.memos = Vec::new();
        self.memos.resize_with(bound, || None);
        self.marks = vec![0; bound];
        // Every side table follows the new graph's bound (prepare only grows them with the memos).
        self.demand = vec![OutputMask::NONE; bound];
        self.demand_stamp = vec![0; bound];
        self.satisfied = vec![false; bound];
        self.stamp = 0;
        self.live = 0;
        for c in carried {
            let Some(slot) = old.get_mut(c.previous.index()) else {
                continue;
            };
            if next.node_at(c.next).map(NodeInstance::uid) != Some(c.uid) {
                continue;
            }
            let Some(mut memo) = slot.take() else {
                continue;
            };
            if !same_folder && !memo.reads.is_empty() {
                continue;
            }
            memo.uid = c.uid;
            self.live = self.live.saturating_add(memo.owned);
            self.memos[c.next.index()] = Some(memo);
        }
        self.swept_at = 0;
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
        outputs: OutputMask,
    ) -> (NodeResult, bool) {
        match self.gather_inputs(graph, node, instance, ctx) {
            Ok(inputs) => (self.call(instance, &inputs, ctx, outputs), true),
            Err(result) => (result, false),
        }
    }

    fn call(
        &self,
        instance: &NodeInstance,
        inputs: &[Value],
        ctx: &NodeContext,
        outputs: OutputMask,
    ) -> NodeResult {
        match evaluate_node_outputs(&instance.def, ctx, inputs, outputs) {
            Ok(outputs) => NodeResult::Ok(Arc::new(outputs)),
            Err(error) => NodeResult::Failed(error),
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
                Some(NodeResult::Ok(outputs)) => match outputs.computed(wire.from_output) {
                    Some(v) => wired[wire.to_input].push(v.clone()),
                    None if wire.from_output < outputs.values.len() => {
                        return Err(NodeResult::Blocked(format!(
                            "input '{port}': '{source_id}' did not compute this output"
                        )));
                    }
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
                        .map_err(NodeResult::Failed)?;
                    merge(values)
                }
            };
            inputs.push(value);
        }
        Ok(inputs)
    }

    /// The input values the node at `index` last ran on (wired values from the memoized results,
    /// merged as for a run, else the literal or default): the optimizer's reverse pass reads them.
    pub fn inputs_of(
        &self,
        graph: &Graph,
        index: NodeIndex,
        ctx: &NodeContext,
    ) -> Result<Vec<Value>, String> {
        let instance = graph.node_at(index).ok_or("no such node")?;
        self.gather_inputs(graph, index, instance, ctx)
            .map_err(|r| {
                r.error()
                    .map_or_else(|| "the node cannot run".to_string(), Cow::into_owned)
            })
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

    /// The value of a named output after the last evaluation (`None` also when the node was not
    /// asked for it and skipped it).
    pub fn output(&self, graph: &Graph, id: &str, output: &str) -> Option<&Value> {
        let node = graph.node(id)?;
        let k = node.def.output_index(output)?;
        self.result(graph, id)?.outputs()?.computed(k)
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
    /// A fill-in run (see [`Evaluator::fill_in`]).
    fill: bool,
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
        return (NodeResult::Failed(e.into()), 0);
    }
    (result, owned)
}

/// Runs one node type on raw input values (one per input port, `Null` for empty), as a graph run
/// does and outside any graph: maps over lists, catches panics, collects warnings and written
/// files, and fails the node when an output holds a non-finite number. Every output is asked for,
/// or those named in `ctx.requested`.
pub fn evaluate_node(
    def: &NodeDef,
    ctx: &NodeContext,
    inputs: &[Value],
) -> Result<NodeOutputs, NodeError> {
    let outputs = match &ctx.requested {
        Some(names) => OutputMask::of_names(def.outputs.iter().map(|p| p.name.as_ref()), names),
        None => OutputMask::ALL,
    };
    evaluate_node_outputs(def, ctx, inputs, outputs)
}

/// [`evaluate_node`] asking the node for the outputs in `outputs` only: the node may skip the
/// others (see [`NodeContext::wants`]); those it skipped are marked in [`NodeOutputs::missing`].
pub fn evaluate_node_outputs(
    def: &NodeDef,
    ctx: &NodeContext,
    inputs: &[Value],
    outputs: OutputMask,
) -> Result<NodeOutputs, NodeError> {
    ctx.ask_outputs(def.outputs.iter().map(|p| p.name.clone()), outputs);
    let outcome = panic_guard::catch(|| run_mapped(def, ctx, inputs));
    let vouched = ctx.take_vouched();
    let missing = ctx.skipped_outputs();
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
            ctx.budget.check(read, 0, &what)?;
            match non_finite_output(def, &values, &vouched) {
                Some(message) => Err(NodeError::new(message)),
                None => Ok(NodeOutputs {
                    values,
                    warnings,
                    files,
                    footprint,
                    missing,
                }),
            }
        }
        Ok(Err(e)) => Err(e),
        Err(panic) => Err(NodeError::Panicked(panic)),
    }
}

/// NaN or ±∞ in an output (an overflow, a division by zero, NaN passed along) is the node's error:
/// downstream nodes are blocked with a reason instead of computing on garbage, and no non-finite
/// number reaches a file or the JSON output.
fn non_finite_output(def: &NodeDef, values: &[Value], vouched: &[String]) -> Option<String> {
    let scanned = |port: &PortDef| {
        let vouched = vouched.iter().any(|v| *v == port.name);
        !vouched || cfg!(debug_assertions)
    };
    let finite = |port: &PortDef, value: &Value| !scanned(port) || is_all_finite(value);
    if def.outputs.iter().zip(values).all(|(p, v)| finite(p, v)) {
        return None;
    }
    def.outputs.iter().zip(values).find_map(|(port, value)| {
        if !scanned(port) {
            return None;
        }
        let at = first_non_finite(value)?;
        debug_assert!(
            !vouched.iter().any(|v| *v == port.name),
            "{}: output '{}' was vouched finite but is not (at {at})",
            def.id,
            port.name
        );
        let at = if at.is_empty() { at } else { format!(" at {at}") };
        Some(format!(
            "output '{}' is not a finite number{at} (an overflow or an undefined result: check the inputs' values and scale)",
            port.name
        ))
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
