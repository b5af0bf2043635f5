//! Cone-net construction: C-tube, CNets Construct, Construct Coplanar, encoding.

use cnets_engine::NodeDef;

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![]
}
