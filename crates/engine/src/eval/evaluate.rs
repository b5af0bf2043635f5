//! A request's walk: plan the out-of-date part, then run each planned node that must run (or fill
//! in outputs it skipped), within the memory budget, and store what it made.

use std::sync::Arc;
#[cfg(not(target_arch = "wasm32"))]
use std::time::Instant;
// std's clock panics on wasm32-unknown-unknown (the web editor); web-time reads the browser's.
#[cfg(target_arch = "wasm32")]
use web_time::Instant;

use petgraph::stable_graph::NodeIndex;

use super::budget::within_budget;
use super::execute::evaluate_node_outputs;
use super::memo::Stored;
use super::verify::Action;
use super::{EvalSummary, Evaluator, NodeResult, OutputMask, Tick};
use crate::graph::{Graph, NodeInstance};
use crate::node::NodeContext;
use crate::value::Value;

impl Evaluator {
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
            if ctx.cancelled() {
                // A run cut short is not a result: the memo keeps the last complete run (whose
                // time tells the editor that the node is slow), and the node runs again next time.
                summary.cancelled = true;
                break;
            }
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
}
