//! Reading JSON inputs for a node type (decoded and completed by `cnets-host`).

use std::io::Read;

use cnets_engine::{NodeDef, Value};
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

/// The input vector for one evaluation of `def` from a JSON object (`cnets_host::node_inputs`).
pub fn node_inputs(def: &NodeDef, json: &Json) -> Result<Vec<Value>, Failure> {
    Ok(cnets_host::node_inputs(def, json)?)
}
