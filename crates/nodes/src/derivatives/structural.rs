//! Nodes that only move numbers around (list selection and reordering, mesh rows and columns):
//! their Jacobian is a 0/1 matrix, found by one run on *tagged* inputs — every wanted number
//! replaced by a code naming its input and leaf — after which every output number names the input
//! number it is a copy of, and the cotangents are scattered back along those codes.

use cnets_engine::node::RunFn;
use cnets_engine::optimize::leaves;
use cnets_engine::optimize::vjp::{VjpArgs, VjpResult};
use cnets_engine::prelude::*;

/// The node types handled here: each output number is a copy of one input number.
pub const IDS: &[&str] = &[
    "list.item",
    "list.reverse",
    "list.repeat",
    "list.slice",
    "list.flatten",
    "list.graft",
    "list.transpose",
    "list.shift",
    "list.partition",
    "list.weave",
    "list.dispatch",
    "list.cull",
    "list.cross_reference",
    "param.list",
    "mesh.row",
    "mesh.column",
];

/// Codes start here (exact in f64, far from design numbers).
const BASE: f64 = 1125899906842624.0; // 2^50
/// Codes of one input span this many leaves.
const SPAN: f64 = 4294967296.0; // 2^32

/// The product of a structural node: one tagged run of `run`.
pub fn product(run: &RunFn, args: &VjpArgs<'_>) -> VjpResult {
    let mut tagged = args.inputs.to_vec();
    for (k, &w) in args.wanted.iter().enumerate() {
        if !w {
            continue;
        }
        if matches!(args.inputs[k], Value::Integer(_)) {
            return Err(NodeError::new("an index does not have a derivative"));
        }
        let n = leaves::count(&args.inputs[k]);
        let updates: Vec<(usize, f64)> = (0..n)
            .map(|i| (i, BASE + k as f64 * SPAN + i as f64))
            .collect();
        tagged[k] = leaves::with_leaves(&args.inputs[k], &updates);
    }
    let outputs = run(args.ctx, &tagged)?;
    let mut result: Vec<Option<Vec<f64>>> = args
        .inputs
        .iter()
        .zip(args.wanted)
        .map(|(v, &w)| w.then(|| vec![0.0; leaves::count(v)]))
        .collect();
    for (o, c) in args.cotangents.iter().enumerate() {
        let Some(c) = c else { continue };
        let codes = leaves::flatten(outputs.get(o).ok_or("internal: missing output")?);
        if codes.len() != c.len() {
            return Err(NodeError::new("the tagged run changed the output's size"));
        }
        for (code, ci) in codes.iter().zip(c) {
            let rel = code - BASE;
            if rel < 0.0 || rel.fract() != 0.0 {
                continue; // a number from an input that does not depend on the variables
            }
            let (k, i) = ((rel / SPAN).floor() as usize, (rel % SPAN) as usize);
            if let Some(Some(slot)) = result.get_mut(k)
                && let Some(x) = slot.get_mut(i)
            {
                *x += ci;
            }
        }
    }
    Ok(result)
}
