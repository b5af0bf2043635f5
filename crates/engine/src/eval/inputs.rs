//! A node's input values before it runs: wired values (several wires merged into one list within
//! the memory budget), else the literal, else the default; a source that failed, is disabled or
//! skipped the output blocks the node.

use petgraph::stable_graph::NodeIndex;

use super::not_run::{Blocked, InvalidInput};
use super::{Evaluator, NodeResult};
use crate::graph::{Graph, NodeInstance};
use crate::node::NodeContext;
use crate::value::Value;

impl Evaluator {
    /// The input values of a node: wired values (merged when several wires meet), else the literal,
    /// else the default. `Err` carries the result for a node that cannot run.
    pub(super) fn gather_inputs(
        &self,
        graph: &Graph,
        node: NodeIndex,
        instance: &NodeInstance,
        ctx: &NodeContext,
    ) -> Result<Vec<Value>, NodeResult> {
        if !instance.enabled {
            return Err(NodeResult::Disabled);
        }
        let def = &instance.def;
        let mut inputs: Vec<Value> = Vec::with_capacity(def.inputs.len());
        let mut wired: Vec<Vec<Value>> = vec![Vec::new(); def.inputs.len()];
        for (source, wire) in graph.wires_into(node) {
            let port = &def.inputs[wire.to_input].name;
            let source_id = graph.node_at(source).map_or("?", |n| n.id.as_str());
            match self.memos[source.index()].as_ref().map(|m| &m.result) {
                Some(NodeResult::Ok(outputs)) => match outputs.computed(wire.from_output) {
                    Some(v) => wired[wire.to_input].push(v.clone()),
                    None if wire.from_output < outputs.values.len() => {
                        return Err(NodeResult::Blocked(Blocked::NotComputed {
                            port: port.to_string(),
                            upstream: source_id.to_string(),
                        }));
                    }
                    None => {
                        return Err(NodeResult::Blocked(Blocked::NoSuchOutput {
                            port: port.to_string(),
                            upstream: source_id.to_string(),
                        }));
                    }
                },
                Some(NodeResult::Disabled) => {
                    return Err(NodeResult::Blocked(Blocked::UpstreamDisabled {
                        port: port.to_string(),
                        upstream: source_id.to_string(),
                    }));
                }
                Some(_) => {
                    return Err(NodeResult::Blocked(Blocked::UpstreamFailed {
                        port: port.to_string(),
                        upstream: source_id.to_string(),
                    }));
                }
                None => {
                    return Err(NodeResult::Blocked(Blocked::NotEvaluated {
                        port: port.to_string(),
                        upstream: source_id.to_string(),
                    }));
                }
            }
        }
        for (k, (port, mut values)) in def.inputs.iter().zip(wired).enumerate() {
            let value = match values.len() {
                0 => match instance.value(k).or(port.default.as_ref()) {
                    Some(v) => v.clone(),
                    None if port.optional => Value::Null,
                    None => {
                        return Err(NodeResult::Invalid(InvalidInput::Required {
                            port: port.name.to_string(),
                        }));
                    }
                },
                1 => values.pop().unwrap_or_default(),
                _ => {
                    // The merged list is new memory: checked before it is built.
                    let items: usize = values
                        .iter()
                        .map(|v| match v {
                            Value::List(items) => items.len(),
                            _ => 1,
                        })
                        .sum();
                    let what = format!(
                        "input '{}': merging {} wires into a list of {items} items",
                        port.name,
                        values.len()
                    );
                    ctx.reserve_values(items as u128, &what)
                        .map_err(NodeResult::Failed)?;
                    merge(values)
                }
            };
            inputs.push(value);
        }
        Ok(inputs)
    }
}

/// Several wires into one input: their values are concatenated into one list (lists contribute
/// their items, single values themselves), in wire order.
fn merge(values: Vec<Value>) -> Value {
    let mut items = Vec::new();
    for v in values {
        match v {
            Value::List(list) => items.extend(list.iter().cloned()),
            other => items.push(other),
        }
    }
    Value::list(items)
}
