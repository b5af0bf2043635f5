//! Math on numbers and lists: arithmetic, remapping, min/max, clamping.

use cnets_engine::NodeDef;

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![]
}
