//! Analysis: planarity, cone check, configuration classes, face attributes.

use cnets_engine::NodeDef;

pub mod faces;

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    let mut nodes = vec![];
    nodes.extend(faces::nodes());
    nodes
}
