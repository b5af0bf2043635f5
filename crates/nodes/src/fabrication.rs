//! Supplementary and fabrication tools: apex from widths, node axes, support layers, parallel transform, strips, unrolling.

use cnets_engine::NodeDef;

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![]
}
