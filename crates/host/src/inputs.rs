//! Inputs of one node evaluation: values decoded by the port's type, defaults for what is missing,
//! `node.input=value` overrides of a graph.

use cnets_engine::value::json::{Document, from_document};
use cnets_engine::{Graph, NodeDef, Value, ValueType};

use crate::HostError;

/// Decodes one JSON input value for `def` by port name.
pub fn decode_input(def: &NodeDef, name: &str, doc: Document) -> Result<Value, HostError> {
    let Some(k) = def.input_index(name) else {
        return Err(unknown_input(def, name));
    };
    let port = &def.inputs[k];
    from_document(doc, &port.ty)
        .map_err(|e| HostError::usage(format!("input '{name}' ({}): {e}", port.type_name())))
}

/// The error for an input name `def` does not have, listing the valid ones.
pub fn unknown_input(def: &NodeDef, name: &str) -> HostError {
    HostError::usage(format!(
        "unknown input '{name}' for {}; valid inputs: {}",
        def.id,
        def.input_names()
    ))
}

/// The input vector for one evaluation of `def` from a JSON object of inputs (see
/// [`complete_inputs`]).
pub fn node_inputs(def: &NodeDef, doc: Document) -> Result<Vec<Value>, HostError> {
    let Document::Object(given) = doc else {
        return Err(HostError::usage(format!(
            "inputs must be a JSON object {{\"<input>\": <value>, …}}; valid inputs of {}: {}",
            def.id,
            def.input_names()
        )));
    };
    let mut values: Vec<Option<Value>> = vec![None; def.inputs.len()];
    for (name, value) in *given {
        let v = decode_input(def, &name, value)?;
        if let Some(k) = def.input_index(&name) {
            values[k] = Some(v);
        }
    }
    complete_inputs(def, values)
}

/// The input vector for one evaluation of `def` (one value per input port): the given values, else
/// the ports' defaults, else empty (`Null`) for optional inputs. A missing required input is an
/// error naming it and listing the valid inputs.
pub fn complete_inputs(def: &NodeDef, given: Vec<Option<Value>>) -> Result<Vec<Value>, HostError> {
    let mut given = given.into_iter();
    def.inputs
        .iter()
        .map(
            |port| match given.next().flatten().or_else(|| port.default.clone()) {
                Some(v) => Ok(v),
                None if port.optional => Ok(Value::Null),
                None => Err(HostError::usage(format!(
                    "missing required input '{}' for {}; valid inputs: {}",
                    port.name,
                    def.id,
                    def.input_names()
                ))),
            },
        )
        .collect()
}

/// Splits `node.input` into the node id and the input name.
pub fn split_target(target: &str) -> Option<(&str, &str)> {
    target.split_once('.')
}

/// Applies one `node.input=value` override (the value in JSON; plain text for text inputs), as
/// `cnets run --set` does.
pub fn apply_set(graph: &mut Graph, set: &str) -> Result<(), HostError> {
    let bad = || HostError::usage(format!("--set '{set}': expected <node>.<input>=<value>"));
    let (target, raw) = set.split_once('=').ok_or_else(bad)?;
    let (node_id, input) = split_target(target).ok_or_else(bad)?;
    let node = graph
        .node(node_id)
        .ok_or_else(|| HostError::usage(format!("--set '{set}': no node '{node_id}'")))?;
    let def = node.def.clone();
    let port_ty = def.input_index(input).map(|k| def.inputs[k].ty.clone());
    let doc = match serde_json::from_str::<Document>(raw) {
        Ok(d) => d,
        Err(_) if port_ty == Some(ValueType::Text) => Document::Text(raw.to_string()),
        Err(e) => {
            return Err(HostError::usage(format!(
                "--set '{set}': the value is not valid JSON: {e}"
            )));
        }
    };
    let value = decode_input(&def, input, doc)
        .map_err(|e| HostError::usage(format!("--set '{set}': {e}")))?;
    graph
        .set_value(node_id, input, value)
        .map_err(|e| HostError::usage(format!("--set '{set}': {e}")))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn construct() -> std::sync::Arc<NodeDef> {
        cnets_nodes::registry()
            .get("cnets.construct")
            .cloned()
            .expect("cnets.construct is registered")
    }

    #[test]
    fn defaults_fill_what_is_missing_and_required_inputs_are_named() {
        let def = construct();
        let mut given = vec![None; def.inputs.len()];
        let err = complete_inputs(&def, given.clone())
            .unwrap_err()
            .to_string();
        assert!(err.contains("missing required input 'directrix'"), "{err}");
        let d = def.input_index("directrix").unwrap();
        let g = def.input_index("generatrix").unwrap();
        let line = cnets_engine::value::json::from_json(
            &serde_json::json!([[0, 0, 0], [1, 0, 0]]),
            &ValueType::Polyline,
        )
        .unwrap();
        given[d] = Some(line.clone());
        given[g] = Some(line);
        let values = complete_inputs(&def, given).unwrap();
        let r = def.input_index("ratios").unwrap();
        assert_eq!(values[r], Value::Number(0.5));
        let s = def.input_index("scale").unwrap();
        assert!(
            values[s].is_null(),
            "an optional input without default is empty"
        );
    }

    #[test]
    fn json_inputs_name_unknown_ports() {
        let def = construct();
        let err = node_inputs(&def, Document::from(&serde_json::json!({"nope": 1})))
            .unwrap_err()
            .to_string();
        assert!(err.contains("unknown input 'nope'"), "{err}");
        assert!(err.contains("directrix"), "{err}");
    }
}
