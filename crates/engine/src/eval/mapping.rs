//! Running a node over lists: item ports fed lists run the node once per item, with longest-list
//! matching (the last item of a shorter list repeats), as Grasshopper does.
//!
//! When inputs are nested to different depths, the deeper ones are split first and the shallower
//! ones are matched, whole, against every branch of the deeper ones (Grasshopper's rule for trees: a
//! flat list is one branch, matched against every branch of a grafted input). So a grafted list of 9
//! numbers times a flat list of 13 gives 9 lists of 13 products. Inputs of equal depth are matched
//! branch by branch, the last branch repeating.

use crate::broadcast::{self, Level};
use crate::convert::coerce_for_port;
use crate::node::{NodeContext, NodeDef, NodeError};
use crate::value::Value;

/// Items run between two looks at the process's memory ([`NodeContext::check_memory`]).
const CHECK_EVERY: usize = 4096;

/// Runs `def` on raw input values (one per input port, `Null` for empty), mapping over list levels
/// the ports do not consume themselves. Outputs of a mapped run are lists (nested as deep as the
/// mapping). An empty list on a mapped port gives empty lists on every output.
pub fn run_mapped(
    def: &NodeDef,
    ctx: &NodeContext,
    inputs: &[Value],
) -> Result<Vec<Value>, NodeError> {
    let split = match broadcast::level(&def.inputs, inputs) {
        Level::Run => {
            let prepared = inputs
                .iter()
                .zip(&def.inputs)
                .map(|(v, port)| {
                    coerce_for_port(v, &port.ty, port.access)
                        .map_err(|e| NodeError::new(format!("input '{}': {e}", port.name)))
                })
                .collect::<Result<Vec<_>, _>>()?;
            let outputs = (def.run)(ctx, &prepared)?;
            if outputs.len() != def.outputs.len() {
                return Err(NodeError::new(format!(
                    "internal: node produced {} outputs, declares {}",
                    outputs.len(),
                    def.outputs.len()
                )));
            }
            return Ok(outputs);
        }
        Level::Split(split) => split,
    };
    let (count, empty) = (split.count, split.empty);
    if !empty {
        let slots = (count as u128).saturating_mul(def.outputs.len() as u128);
        ctx.reserve_values(slots, &format!("running '{}' on {count} items", def.id))?;
    }
    let mut columns: Vec<Vec<Value>> =
        vec![Vec::with_capacity(if empty { 0 } else { count }); def.outputs.len()];
    if !empty {
        let mut item_inputs = inputs.to_vec();
        for k in 0..count {
            if ctx.cancelled() {
                return Err(NodeError::new("cancelled"));
            }
            if k % CHECK_EVERY == CHECK_EVERY - 1 {
                ctx.check_memory(&format!("running '{}' on {count} items", def.id))?;
            }
            split.fill(&mut item_inputs, k);
            let outputs = run_mapped(def, ctx, &item_inputs)
                .map_err(|e| NodeError::new(format!("item {k}: {e}")))?;
            for (column, value) in columns.iter_mut().zip(outputs) {
                column.push(value);
            }
        }
    }
    Ok(columns.into_iter().map(Value::list).collect())
}
