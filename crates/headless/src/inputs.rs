//! Reading JSON inputs for a node type: every input name checked, every value decoded by the port's
//! type, defaults for what is missing.

use std::io::Read;

use cnets_engine::value::json::from_json;
use cnets_engine::{Graph, NodeDef, Value, ValueType};
use serde_json::Value as Json;

use crate::failure::Failure;

/// Reads a JSON document from a file or from stdin (`-`), with `file:line:col` on syntax errors.
pub fn read_json(source: &str) -> Result<Json, Failure> {
    let (name, text) = if source == "-" {
        let mut text = String::new();
        std::io::stdin()
            .read_to_string(&mut text)
            .map_err(|e| Failure::usage(format!("<stdin>: cannot read: {e}")))?;
        ("<stdin>".to_string(), text)
    } else {
        let text = std::fs::read_to_string(source)
            .map_err(|e| Failure::usage(format!("{source}: cannot read: {e}")))?;
        (source.to_string(), text)
    };
    serde_json::from_str(&text).map_err(|e| {
        Failure::usage(format!(
            "{name}:{}:{}: invalid JSON: {e}",
            e.line(),
            e.column()
        ))
    })
}

/// Decodes one input value for `def` by port name.
pub fn decode_input(def: &NodeDef, name: &str, json: &Json) -> Result<Value, Failure> {
    let Some(k) = def.input_index(name) else {
        return Err(Failure::usage(format!(
            "unknown input '{name}' for {}; valid inputs: {}",
            def.id,
            def.input_names()
        )));
    };
    let port = &def.inputs[k];
    from_json(json, &port.ty)
        .map_err(|e| Failure::usage(format!("input '{name}' ({}): {e}", port.type_name())))
}

/// The input vector for one evaluation of `def`: given values, else defaults, else empty for
/// optional inputs. A missing required input is an error naming it and listing the valid inputs.
pub fn node_inputs(def: &NodeDef, json: &Json) -> Result<Vec<Value>, Failure> {
    let Json::Object(given) = json else {
        return Err(Failure::usage(format!(
            "inputs must be a JSON object {{\"<input>\": <value>, …}}; valid inputs of {}: {}",
            def.id,
            def.input_names()
        )));
    };
    let mut values: Vec<Option<Value>> = vec![None; def.inputs.len()];
    for (name, value) in given {
        let v = decode_input(def, name, value)?;
        if let Some(k) = def.input_index(name) {
            values[k] = Some(v);
        }
    }
    def.inputs
        .iter()
        .zip(values)
        .map(
            |(port, value)| match value.or_else(|| port.default.clone()) {
                Some(v) => Ok(v),
                None if port.optional => Ok(Value::Null),
                None => Err(Failure::usage(format!(
                    "missing required input '{}' for {}; valid inputs: {}",
                    port.name,
                    def.id,
                    def.input_names()
                ))),
            },
        )
        .collect()
}

/// Applies one `--set node.input=value`.
pub fn apply_set(graph: &mut Graph, set: &str) -> Result<(), Failure> {
    let bad = || Failure::usage(format!("--set '{set}': expected <node>.<input>=<value>"));
    let (target, raw) = set.split_once('=').ok_or_else(bad)?;
    let (node_id, input) = target.split_once('.').ok_or_else(bad)?;
    let node = graph
        .node(node_id)
        .ok_or_else(|| Failure::usage(format!("--set '{set}': no node '{node_id}'")))?;
    let def = node.def.clone();
    let port_ty = def.input_index(input).map(|k| def.inputs[k].ty.clone());
    let json = match serde_json::from_str::<Json>(raw) {
        Ok(j) => j,
        Err(_) if port_ty == Some(ValueType::Text) => Json::String(raw.to_string()),
        Err(e) => {
            return Err(Failure::usage(format!(
                "--set '{set}': the value is not valid JSON: {e}"
            )));
        }
    };
    let value = decode_input(&def, input, &json)
        .map_err(|f| Failure::usage(format!("--set '{set}': {}", f.messages.join("; "))))?;
    graph
        .set_value(node_id, input, value)
        .map_err(|e| Failure::usage(format!("--set '{set}': {e}")))?;
    Ok(())
}
