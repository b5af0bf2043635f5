//! What a node's evaluation produced.

use std::borrow::Cow;
use std::path::PathBuf;
use std::sync::Arc;

use super::OutputMask;
use super::not_run::{Blocked, InvalidInput};
use crate::error::NodeError;
use crate::value::{Footprint, Value};

/// Outputs of a successful run.
#[derive(Debug, Clone, Default)]
pub struct NodeOutputs {
    /// One value per output port.
    pub values: Vec<Value>,
    /// Warnings the node reported (it still produced outputs).
    pub warnings: Vec<String>,
    /// Files the node wrote.
    pub files: Vec<PathBuf>,
    /// The memory the values hold and the values a full read visits (for the memory budget).
    pub footprint: Footprint,
    /// Outputs the node was not asked for and did not compute: their values are placeholders
    /// (see [`NodeContext::wants`](crate::NodeContext::wants)).
    pub missing: OutputMask,
}

impl NodeOutputs {
    /// The value of output `k` when it was computed (not a placeholder).
    pub fn computed(&self, k: usize) -> Option<&Value> {
        self.values.get(k).filter(|_| !self.missing.contains(k))
    }
}

/// The state of a node after evaluation.
#[derive(Debug, Clone)]
pub enum NodeResult {
    /// The node ran and produced outputs.
    Ok(Arc<NodeOutputs>),
    /// The node ran and failed (or panicked): its error, typed (a reader's line and column are
    /// fields of [`NodeError::Located`]).
    Failed(NodeError),
    /// An upstream node failed or is disabled; the node did not run.
    Blocked(Blocked),
    /// The node is disabled.
    Disabled,
    /// A required input is missing: the node could not start.
    Invalid(InvalidInput),
}

impl NodeResult {
    /// The outputs when the node ran successfully.
    pub fn outputs(&self) -> Option<&NodeOutputs> {
        match self {
            NodeResult::Ok(o) => Some(o),
            _ => None,
        }
    }

    /// The error message, for failed, invalid and blocked nodes.
    pub fn error(&self) -> Option<Cow<'_, str>> {
        match self {
            NodeResult::Failed(e) => Some(Cow::Owned(e.to_string())),
            NodeResult::Blocked(b) => Some(Cow::Owned(b.to_string())),
            NodeResult::Invalid(i) => Some(Cow::Owned(i.to_string())),
            NodeResult::Disabled => Some(Cow::Borrowed("disabled")),
            NodeResult::Ok(_) => None,
        }
    }

    /// The node's own error when it ran and failed.
    pub fn failure(&self) -> Option<&NodeError> {
        match self {
            NodeResult::Failed(e) => Some(e),
            _ => None,
        }
    }

    /// True when the node itself failed (not merely blocked or disabled).
    pub fn is_failure(&self) -> bool {
        matches!(self, NodeResult::Failed(_) | NodeResult::Invalid(_))
    }

    /// Equality used for early cutoff: outputs compared bitwise, errors by value.
    pub(crate) fn same_as(&self, other: &NodeResult) -> bool {
        match (self, other) {
            (NodeResult::Ok(a), NodeResult::Ok(b)) => {
                Arc::ptr_eq(a, b)
                    || (a.values.len() == b.values.len()
                        && a.values.iter().zip(&b.values).all(|(x, y)| x.same_as(y)))
            }
            (NodeResult::Failed(a), NodeResult::Failed(b)) => a == b,
            (NodeResult::Blocked(a), NodeResult::Blocked(b)) => a == b,
            (NodeResult::Invalid(a), NodeResult::Invalid(b)) => a == b,
            (NodeResult::Disabled, NodeResult::Disabled) => true,
            _ => false,
        }
    }
}
