//! Running one node type on raw input values, inside or outside a graph: mapping over lists,
//! catching panics, collecting warnings and written files, and the NaN policy (a non-finite output
//! is the node's error).

use super::{NodeOutputs, OutputMask, panic_guard, run_mapped};
use crate::budget::bytes_of;
use crate::node::{NodeContext, NodeDef, NodeError, PortDef};
use crate::value::{Value, first_non_finite, footprint, is_all_finite};

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
