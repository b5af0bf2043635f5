//! List tools: item, length, reverse, repeat, slice, flatten, graft, transpose, tables.

use cnets_engine::NodeDef;

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![]
}
