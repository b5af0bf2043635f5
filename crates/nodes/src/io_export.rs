//! Exports written into the run's output directory: glTF, OBJ, SVG, DXF, JSON, CSV.

use cnets_engine::NodeDef;

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![]
}
