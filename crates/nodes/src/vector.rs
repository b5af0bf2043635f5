//! Points and vectors: construct and deconstruct.

use cnets_engine::NodeDef;

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![]
}
