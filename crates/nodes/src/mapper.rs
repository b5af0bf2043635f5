//! Graph mappers: functions y = f(x) given by a curve type and draggable handles.

use cnets_engine::NodeDef;

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![]
}
