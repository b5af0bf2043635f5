//! Analysis: planarity, cone check, configuration classes, face attributes.

use cnets_engine::NodeDef;

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![]
}
