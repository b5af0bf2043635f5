//! What a node type may say about its derivative: the vector–Jacobian product of its run for the
//! optimizer's reverse pass, and for a piecewise-smooth node which smooth piece a run was on. Part
//! of the node contract (a leaf: values and the node's context only); the optimizer that calls
//! them is `optimize::vjp` and `optimize::branch`.

use std::sync::Arc;

use super::context::NodeContext;
use crate::error::NodeError;
use crate::value::{Value, leaves};

/// What a node's vector–Jacobian product receives.
pub struct VjpArgs<'a> {
    /// The evaluation context.
    pub ctx: &'a NodeContext,
    /// The inputs the node ran on (one item per item port, converted to the port types).
    pub inputs: &'a [Value],
    /// The outputs it produced.
    pub outputs: &'a [Value],
    /// Per output, the cotangent of each of its leaves (`None`: zero).
    pub cotangents: &'a [Option<Vec<f64>>],
    /// Per input, whether its cotangent is needed.
    pub wanted: &'a [bool],
}

impl VjpArgs<'_> {
    /// The cotangent of output `k`, zeros when none was given.
    pub fn cotangent(&self, k: usize) -> Vec<f64> {
        match self.cotangents.get(k).and_then(|c| c.as_ref()) {
            Some(c) => c.clone(),
            None => vec![0.0; self.outputs.get(k).map_or(0, leaves::count)],
        }
    }
}

/// Per input, the cotangent of each of its leaves (`None`: zero or not asked for); an error when
/// the node cannot differentiate this run exactly (the optimizer then uses finite differences).
pub type VjpResult = Result<Vec<Option<Vec<f64>>>, NodeError>;

/// Per input (or output), the cotangent of each of its leaves (`None`: zero).
pub type Cotangents = Vec<Option<Vec<f64>>>;

/// A node type's vector–Jacobian product.
pub type VjpFn = Arc<dyn Fn(&VjpArgs<'_>) -> VjpResult + Send + Sync>;

/// The smooth piece a node's run was on.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Branch {
    /// Identifies the piece: equal keys, the same piece.
    pub key: u64,
    /// The piece in words, for the report (e.g. "ratios ≥ ½ in 4 812 of 9 900 cells").
    pub summary: String,
}

/// A node type's branch function: the piece of a run, from its inputs and outputs (as the run
/// function saw them); `None` when the run is smooth everywhere.
pub type BranchFn = Arc<dyn Fn(&[Value], &[Value]) -> Option<Branch> + Send + Sync>;
