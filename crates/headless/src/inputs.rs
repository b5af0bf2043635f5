//! Reading JSON inputs for a node type (decoded and completed by `cnets-host`).
//!
//! The document is read from the file or stdin as a stream into a compact
//! [`Document`](cnets_engine::value::json::Document) (packed number rows and point lists): no text
//! buffer of the whole file and no `serde_json::Value` tree, so the peak memory is about the data.

use cnets_engine::value::json::{Document, read_document_within};
use cnets_engine::{NodeDef, Value};

use crate::failure::Failure;

/// Reads a JSON document from a file or from stdin (`-`), with `file:line:col` on syntax errors;
/// a document that would take more than `limit` bytes is refused where it is in the text.
pub fn read_json(source: &str, limit: u64) -> Result<Document, Failure> {
    let (name, read) = if source == "-" {
        (
            "<stdin>".to_string(),
            read_document_within(std::io::stdin().lock(), limit),
        )
    } else {
        let file = std::fs::File::open(source)
            .map_err(|e| Failure::usage(format!("{source}: cannot read: {e}")))?;
        (source.to_string(), read_document_within(file, limit))
    };
    read.map_err(|e| {
        if e.is_io() {
            Failure::usage(format!("{name}: cannot read: {e}"))
        } else if e.is_data() {
            // Over the memory limit: not a syntax error.
            let message = e.to_string();
            let message = message.split(" at line ").next().unwrap_or_default();
            Failure::usage(format!("{name}:{}:{}: {message}", e.line(), e.column()))
        } else {
            Failure::usage(format!(
                "{name}:{}:{}: invalid JSON: {e}",
                e.line(),
                e.column()
            ))
        }
    })
}

/// The input vector for one evaluation of `def` from a JSON object (`cnets_host::node_inputs`).
pub fn node_inputs(def: &NodeDef, doc: Document) -> Result<Vec<Value>, Failure> {
    Ok(cnets_host::node_inputs(def, doc)?)
}
