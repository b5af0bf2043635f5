//! The memory budget after a node ran: its outputs must fit beside the results already held.

use super::NodeResult;
use crate::graph::NodeInstance;
use crate::node::NodeContext;
use crate::value::footprint;

/// The memory budget after a node ran: its outputs must fit beside the `held` bytes of the other
/// results, with the `kept` bytes the node keeps alive elsewhere (a cluster's inner results; a full
/// read of the outputs was checked by [`evaluate_node`]). Over budget, the node fails (its
/// outputs are dropped) and its dependents are blocked. Returns the result and the bytes it holds.
pub(super) fn within_budget(
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
