//! Vector–Jacobian products of nodes: the reverse pass's step through one node.
//!
//! A node type may carry an exact product ([`NodeDef::vjp`](crate::NodeDef::vjp)): given the
//! cotangents of its outputs (∂objective/∂output, one number per [leaf](super::leaves) of the
//! output) it returns the cotangents of the inputs asked for. It sees the inputs as its run
//! function does — one item per item port, converted to the port types — and [`node_vjp`] maps it
//! over lists the way the evaluator maps the run function. A node without one, or whose product
//! declines (an error: a branch it cannot differentiate), is differentiated by central finite
//! differences of its own run over the input leaves that matter, and the reason is reported.

use super::leaves;
use crate::broadcast::{self, Level};
use crate::convert::coerce_for_port;
use crate::eval::evaluate_node;
use crate::node::{NodeContext, NodeDef, NodeError};
use crate::value::Value;

pub use crate::node::derivative::{Cotangents, VjpArgs, VjpFn, VjpResult};

/// Which leaves of an input the reverse pass needs.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Wanted {
    /// None: the input does not depend on a variable.
    No,
    /// All of them (a wired input downstream of a variable).
    All,
    /// These (the variables inside a literal input).
    Leaves(Vec<usize>),
}

impl Wanted {
    fn any(&self) -> bool {
        !matches!(self, Wanted::No)
    }
}

/// The input cotangents of one node and how they were obtained.
#[derive(Debug, Default)]
pub struct NodeGradient {
    /// Per input, its leaves' cotangents (`None`: zero or not wanted).
    pub inputs: Vec<Option<Vec<f64>>>,
    /// Why finite differences were used instead of an exact product (`None`: exact).
    pub finite_differences: Option<String>,
    /// Node runs spent on finite differences.
    pub runs: u64,
}

/// The cotangents of `def`'s inputs (`inputs` as gathered for its run, before mapping over lists)
/// from those of its `outputs`: the exact product when the node has one and it applies, else
/// central finite differences of the node's run over the wanted leaves.
pub fn node_vjp(
    def: &NodeDef,
    ctx: &NodeContext,
    inputs: &[Value],
    outputs: &[Value],
    cotangents: &[Option<Vec<f64>>],
    wanted: &[Wanted],
) -> Result<NodeGradient, NodeError> {
    let reason = match &def.vjp {
        Some(vjp) => {
            let flags: Vec<bool> = wanted.iter().map(Wanted::any).collect();
            match mapped(def, vjp, ctx, inputs, outputs, cotangents, &flags) {
                Ok(result) => {
                    return Ok(NodeGradient {
                        inputs: result,
                        finite_differences: None,
                        runs: 0,
                    });
                }
                Err(e) => e.to_string(),
            }
        }
        None => "no exact derivative".to_string(),
    };
    let (result, runs) = finite_differences(def, ctx, inputs, cotangents, wanted)?;
    Ok(NodeGradient {
        inputs: result,
        finite_differences: Some(reason),
        runs,
    })
}

/// The exact product mapped over the list levels the ports do not consume, by the evaluator's own
/// rule ([`crate::broadcast`]).
fn mapped(
    def: &NodeDef,
    vjp: &VjpFn,
    ctx: &NodeContext,
    inputs: &[Value],
    outputs: &[Value],
    cotangents: &[Option<Vec<f64>>],
    wanted: &[bool],
) -> VjpResult {
    let split = match broadcast::level(&def.inputs, inputs) {
        Level::Split(split) => split,
        Level::Run => return product(def, vjp, ctx, inputs, outputs, cotangents, wanted),
    };
    let count = split.count;
    let mut result: Vec<Option<Vec<f64>>> = inputs
        .iter()
        .zip(wanted)
        .map(|(v, &w)| w.then(|| vec![0.0; leaves::count(v)]))
        .collect();
    if split.empty {
        return Ok(result);
    }
    // Item outputs and their cotangents, split by item.
    let mut item_outputs: Vec<&[Value]> = Vec::with_capacity(outputs.len());
    for o in outputs {
        match o.as_list() {
            Some(items) if items.len() == count => item_outputs.push(items),
            _ => return Err(NodeError::new("internal: a mapped output is not a list")),
        }
    }
    let by_item = |c: &Option<Vec<f64>>, items: &[Value]| -> Vec<Option<Vec<f64>>> {
        let Some(c) = c else {
            return vec![None; items.len()];
        };
        let mut at = 0;
        items
            .iter()
            .map(|v| {
                let n = leaves::count(v);
                let part = c.get(at..at + n).map(<[f64]>::to_vec);
                at += n;
                part
            })
            .collect()
    };
    let item_cots: Vec<Vec<Option<Vec<f64>>>> = cotangents
        .iter()
        .zip(&item_outputs)
        .map(|(c, items)| by_item(c, items))
        .collect();
    // Leaf offsets of the items of split inputs.
    let starts: Vec<Option<Vec<usize>>> = split
        .lists
        .iter()
        .map(|l| {
            l.map(|items| {
                let mut at = 0;
                items
                    .iter()
                    .map(|v| {
                        let s = at;
                        at += leaves::count(v);
                        s
                    })
                    .collect()
            })
        })
        .collect();
    let mut item_inputs = inputs.to_vec();
    for k in 0..count {
        if ctx.cancelled() {
            return Err(NodeError::new("cancelled"));
        }
        split.fill(&mut item_inputs, k);
        let outs: Vec<Value> = item_outputs.iter().map(|items| items[k].clone()).collect();
        let cots: Vec<Option<Vec<f64>>> = item_cots.iter().map(|c| c[k].clone()).collect();
        if cots.iter().all(Option::is_none) {
            continue;
        }
        let part = mapped(def, vjp, ctx, &item_inputs, &outs, &cots, wanted)?;
        for (input, (c, total)) in part.into_iter().zip(result.iter_mut()).enumerate() {
            let (Some(c), Some(total)) = (c, total.as_mut()) else {
                continue;
            };
            let at = match (&starts[input], split.index(input, k)) {
                (Some(s), Some(i)) => s[i],
                _ => 0,
            };
            total
                .get_mut(at..at + c.len())
                .ok_or_else(|| NodeError::new("internal: an item's derivative is too long"))?
                .iter_mut()
                .zip(&c)
                .for_each(|(t, x)| *t += x);
        }
    }
    Ok(result)
}

/// The node's own product on inputs that need no more mapping, checked for its shape.
fn product(
    def: &NodeDef,
    vjp: &VjpFn,
    ctx: &NodeContext,
    inputs: &[Value],
    outputs: &[Value],
    cotangents: &[Option<Vec<f64>>],
    wanted: &[bool],
) -> VjpResult {
    let prepared = inputs
        .iter()
        .zip(&def.inputs)
        .map(|(v, port)| coerce_for_port(v, &port.ty, port.access).map_err(NodeError::from))
        .collect::<Result<Vec<_>, _>>()?;
    for (k, (raw, p)) in inputs.iter().zip(&prepared).enumerate() {
        if wanted[k] && leaves::count(raw) != leaves::count(p) {
            return Err(NodeError::new(format!(
                "input '{}' changes its numbers when converted to the port type",
                def.inputs[k].name
            )));
        }
    }
    let result = vjp(&VjpArgs {
        ctx,
        inputs: &prepared,
        outputs,
        cotangents,
        wanted,
    })?;
    for (k, c) in result.iter().enumerate() {
        if let Some(c) = c
            && c.len() != leaves::count(&inputs[k])
        {
            return Err(NodeError::new(format!(
                "internal: the derivative of input '{}' has {} numbers, the input {}",
                def.inputs.get(k).map_or("?", |p| p.name.as_ref()),
                c.len(),
                leaves::count(&inputs[k])
            )));
        }
    }
    Ok(result)
}

/// Central differences of the node's run over the wanted leaves: 2 runs per leaf.
fn finite_differences(
    def: &NodeDef,
    ctx: &NodeContext,
    inputs: &[Value],
    cotangents: &[Option<Vec<f64>>],
    wanted: &[Wanted],
) -> Result<(Cotangents, u64), NodeError> {
    let mut runs = 0;
    let mut result = Vec::with_capacity(inputs.len());
    let mut probe = inputs.to_vec();
    let mut run = |probe: &[Value]| -> Result<Vec<f64>, NodeError> {
        runs += 1;
        let out = evaluate_node(def, ctx, probe)?;
        let mut flat = Vec::new();
        for (v, c) in out.values.iter().zip(cotangents) {
            if let Some(c) = c {
                let f = leaves::flatten(v);
                if f.len() != c.len() {
                    return Err(NodeError::new(
                        "the output changes its size under a small change of the input",
                    ));
                }
                flat.push(f);
            } else {
                flat.push(Vec::new());
            }
        }
        Ok(flat.concat())
    };
    let seed: Vec<f64> = cotangents.iter().flatten().flatten().copied().collect();
    for (k, w) in wanted.iter().enumerate() {
        let n = leaves::count(&inputs[k]);
        let which: Vec<usize> = match w {
            Wanted::No => {
                result.push(None);
                continue;
            }
            Wanted::All => (0..n).collect(),
            Wanted::Leaves(l) => l.iter().copied().filter(|&i| i < n).collect(),
        };
        let base = leaves::flatten(&inputs[k]);
        let mut c = vec![0.0; n];
        for i in which {
            let x = base[i];
            let h = 1e-6 * x.abs().max(1.0);
            probe[k] = leaves::with_leaf(&inputs[k], i, x + h);
            let up = run(&probe)?;
            probe[k] = leaves::with_leaf(&inputs[k], i, x - h);
            let down = run(&probe)?;
            c[i] = seed
                .iter()
                .zip(up.iter().zip(&down))
                .map(|(s, (u, d))| s * (u - d))
                .sum::<f64>()
                / (2.0 * h);
        }
        probe[k] = inputs[k].clone();
        result.push(Some(c));
    }
    Ok((result, runs))
}
