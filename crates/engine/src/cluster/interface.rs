//! A graph's interface: the `graph.input` and `graph.output` nodes that make it usable as a node.

use std::borrow::Cow;

use petgraph::stable_graph::NodeIndex;

use crate::graph::Graph;
use crate::node::{NodeDef, NodeError, PortDef};
use crate::value::{Access, Value, ValueType};
use crate::{kinds as k, node};

/// Node type id of a graph input.
pub const INPUT_TYPE: &str = "graph.input";
/// Node type id of a graph output.
pub const OUTPUT_TYPE: &str = "graph.output";

/// Parses a port type written as `number`, `list<point>` or `tree<number>` into item type and access.
pub fn parse_port_type(text: &str) -> Option<(ValueType, Access)> {
    let text = text.trim();
    if let Some(inner) = text.strip_prefix("tree<").and_then(|r| r.strip_suffix('>')) {
        return Some((ValueType::parse(inner)?, Access::Tree));
    }
    if let Some(inner) = text
        .strip_prefix("table<")
        .and_then(|r| r.strip_suffix('>'))
    {
        return Some((ValueType::parse(inner)?, Access::Table));
    }
    if let Some(inner) = text.strip_prefix("list<").and_then(|r| r.strip_suffix('>')) {
        let ty = ValueType::parse(inner)?;
        if matches!(ty, ValueType::List(_)) {
            return Some((ty.base().clone(), Access::Tree));
        }
        return Some((ty, Access::List));
    }
    Some((ValueType::parse(text)?, Access::Item))
}

fn checked_type(text: &str) -> Result<(ValueType, Access), NodeError> {
    parse_port_type(text).ok_or_else(|| {
        NodeError::new(format!(
            "unknown type '{text}'; use e.g. number, integer, boolean, text, point, vector, plane, \
             polyline, quad_mesh, mesh, lines, record, any, list<number>, tree<number>"
        ))
    })
}

/// Converts a value to a declared port type (per item), with a message naming the port.
fn conform(value: &Value, ty: &ValueType, access: Access, name: &str) -> Result<Value, NodeError> {
    crate::convert::coerce_for_port(value, ty, access)
        .map_err(|e| NodeError::new(format!("graph port '{name}': {e}")))
}

node! {
    /// An input of this graph when it is used as a cluster (a node inside another graph). Its
    /// `name`, `type`, `default` and `doc` become the cluster's input port. Run on its own, the graph
    /// uses `default`.
    #[node(id = "graph.input", category = "Graph")]
    pub fn graph_input(
        /// Port name (letters, digits, `_`).
        name: k::Text = "input",
        /// Port type, e.g. `number`, `polyline`, `list<number>`, `tree<number>`.
        r#type: k::Text = "any",
        /// Value used when the cluster input is not connected (and when the graph runs on its own).
        default: Option<k::Tree<k::Any>>,
        /// One line shown as the port's tooltip.
        doc: k::Text = "",
        /// The value passed in by the enclosing cluster (set by the engine; leave empty).
        value: Option<k::Tree<k::Any>>,
    ) -> (
        /// The input value.
        value: k::Tree<k::Any>,
    ) {
        let _ = doc;
        let (ty, access) = checked_type(&r#type)?;
        match value.or(default) {
            Some(v) => Ok((conform(&v, &ty, access, &name)?,)),
            None => Err(NodeError::new(format!(
                "graph input '{name}' has no value: connect the cluster's input, or give it a default to run this graph on its own"
            ))),
        }
    }
}

node! {
    /// An output of this graph when it is used as a cluster: its `name`, `type` and `doc` become
    /// the cluster's output port, whose value is what is wired into `value`.
    #[node(id = "graph.output", category = "Graph")]
    pub fn graph_output(
        /// Port name (letters, digits, `_`).
        name: k::Text = "output",
        /// Port type, e.g. `number`, `polyline`, `list<number>`, `tree<number>`.
        r#type: k::Text = "any",
        /// One line shown as the port's tooltip.
        doc: k::Text = "",
        /// The value to output.
        value: k::Tree<k::Any>,
    ) -> (
        /// The value, unchanged.
        value: k::Tree<k::Any>,
    ) {
        let _ = doc;
        let (ty, access) = checked_type(&r#type)?;
        Ok((conform(&value, &ty, access, &name)?,))
    }
}

/// The structural node types every registry should contain.
pub fn nodes() -> Vec<NodeDef> {
    vec![graph_input(), graph_output()]
}

/// One port of a graph's interface.
#[derive(Debug, Clone)]
pub struct InterfacePort {
    /// The `graph.input` / `graph.output` node inside the graph.
    pub node: NodeIndex,
    /// The port as the cluster shows it.
    pub port: PortDef,
}

/// The ports a graph shows when used as a cluster, in node order.
#[derive(Debug, Clone, Default)]
pub struct Interface {
    /// From `graph.input` nodes.
    pub inputs: Vec<InterfacePort>,
    /// From `graph.output` nodes.
    pub outputs: Vec<InterfacePort>,
}

fn text_value(graph: &Graph, node: NodeIndex, input: &str, fallback: &str) -> String {
    match graph.node_at(node).and_then(|n| n.value_of(input)) {
        Some(Value::Text(s)) => s.to_string(),
        _ => fallback.to_string(),
    }
}

impl Interface {
    /// Reads the interface of `graph`; errors on bad names, unknown types or duplicate names.
    pub fn of(graph: &Graph) -> Result<Self, String> {
        let mut nodes: Vec<_> = graph.nodes().collect();
        nodes.sort_by_key(|(_, n)| n.uid());
        let mut interface = Interface::default();
        for (index, node) in nodes {
            let is_input = node.def.id == INPUT_TYPE;
            if !is_input && node.def.id != OUTPUT_TYPE {
                continue;
            }
            let fallback = if is_input { "input" } else { "output" };
            let name = text_value(graph, index, "name", fallback);
            if !crate::graph::valid_id(&name) || name.contains('-') {
                return Err(format!(
                    "node '{}': port name '{name}' must use letters, digits and '_'",
                    node.id
                ));
            }
            let type_text = text_value(graph, index, "type", "any");
            let (ty, access) = parse_port_type(&type_text)
                .ok_or_else(|| format!("node '{}': unknown port type '{type_text}'", node.id))?;
            let mut port = PortDef::new(Cow::Owned(name.clone()), ty, access)
                .with_doc(Cow::Owned(text_value(graph, index, "doc", "")));
            if is_input && let Some(default) = node.value_of("default") {
                port = port.with_default(default.clone());
            }
            let list = if is_input {
                &mut interface.inputs
            } else {
                &mut interface.outputs
            };
            if list.iter().any(|p| p.port.name == port.name) {
                return Err(format!(
                    "two graph {}s are named '{name}'",
                    if is_input { "input" } else { "output" }
                ));
            }
            list.push(InterfacePort { node: index, port });
        }
        Ok(interface)
    }

    /// True when the graph declares no ports at all.
    pub fn is_empty(&self) -> bool {
        self.inputs.is_empty() && self.outputs.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn port_types_parse() {
        assert_eq!(
            parse_port_type("number"),
            Some((ValueType::Number, Access::Item))
        );
        assert_eq!(
            parse_port_type("list<point>"),
            Some((ValueType::Point, Access::List))
        );
        assert_eq!(
            parse_port_type("tree<number>"),
            Some((ValueType::Number, Access::Tree))
        );
        assert_eq!(
            parse_port_type("list<list<number>>"),
            Some((ValueType::Number, Access::Tree))
        );
        assert_eq!(parse_port_type("nonsense"), None);
    }
}
