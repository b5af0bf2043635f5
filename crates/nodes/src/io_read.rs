//! Importing polylines from CSV, JSON, OBJ and SVG files.

use cnets_engine::NodeDef;

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![]
}
