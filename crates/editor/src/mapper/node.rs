//! A graph-mapper node's data as the editor reads it: which inputs hold the handles and the
//! curve kind (found from the node's ports, not hard-coded), the kind set and the handles shown.

use cnets_engine::{Access, NodeInstance, Value, ValueType};
use cnets_geometry::curves::MapperKind;
use glam::DVec2;

use crate::widgets::effective_value;

/// Whether a node gets the graph-mapper widget.
pub fn is_mapper(node: &NodeInstance) -> bool {
    node.def.id.starts_with("mapper.") && handles_port(node).is_some() && kind_port(node).is_some()
}

/// Index of the handles input: the first list of points.
pub fn handles_port(node: &NodeInstance) -> Option<usize> {
    node.def
        .inputs
        .iter()
        .position(|p| p.ty == ValueType::Point && p.access != Access::Item)
}

/// Index of the curve-kind input: the first text input.
pub fn kind_port(node: &NodeInstance) -> Option<usize> {
    node.def.inputs.iter().position(|p| p.ty == ValueType::Text)
}

/// The kind set on the node (`None` when it is not a known kind).
pub fn kind(node: &NodeInstance) -> Option<MapperKind> {
    match effective_value(node, kind_port(node)?) {
        Some(Value::Text(t)) => MapperKind::parse(&t).ok(),
        _ => None,
    }
}

/// The handles of a mapper node: its literal list, else the kind's defaults.
pub fn handles(node: &NodeInstance) -> Vec<DVec2> {
    let set: Vec<DVec2> = match handles_port(node).and_then(|k| effective_value(node, k)) {
        Some(Value::List(items)) => items
            .iter()
            .filter_map(Value::as_vec3)
            .map(|p| p.truncate())
            .collect(),
        Some(Value::Point(p)) => vec![p.truncate()],
        _ => Vec::new(),
    };
    if set.is_empty() {
        kind(node)
            .map(MapperKind::default_handles)
            .unwrap_or_default()
    } else {
        set
    }
}
