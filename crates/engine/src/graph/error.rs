//! Errors of graph edits.

use thiserror::Error;

/// Why a graph edit was refused. The graph is left unchanged.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum GraphError {
    /// No node with this id.
    #[error("no node '{0}'")]
    UnknownNode(String),
    /// A node with this id already exists.
    #[error("a node '{0}' already exists")]
    DuplicateId(String),
    /// Node ids are non-empty and use letters, digits, '_' and '-'.
    #[error("invalid node id '{0}': use letters, digits, '_' and '-'")]
    InvalidId(String),
    /// No node type with this id.
    #[error("unknown node type '{type_id}'{}", did_you_mean(.suggestions))]
    UnknownType {
        /// The requested type.
        type_id: String,
        /// Similar known types.
        suggestions: Vec<String>,
    },
    /// The node has no input with this name.
    #[error("node '{node}' ({type_id}) has no input '{port}'; its inputs are: {valid}")]
    UnknownInput {
        /// Node id.
        node: String,
        /// Node type.
        type_id: String,
        /// Requested port.
        port: String,
        /// Valid names.
        valid: String,
    },
    /// The node has no output with this name.
    #[error("node '{node}' ({type_id}) has no output '{port}'; its outputs are: {valid}")]
    UnknownOutput {
        /// Node id.
        node: String,
        /// Node type.
        type_id: String,
        /// Requested port.
        port: String,
        /// Valid names.
        valid: String,
    },
    /// The output's type cannot flow into the input.
    #[error("type mismatch: {from} gives {from_type} but {to} takes {to_type}")]
    TypeMismatch {
        /// `node.output`.
        from: String,
        /// Output type.
        from_type: String,
        /// `node.input`.
        to: String,
        /// Input type.
        to_type: String,
    },
    /// The connection would close a cycle.
    #[error("connecting {from} -> {to} would create a cycle: {path}")]
    Cycle {
        /// `node.output`.
        from: String,
        /// `node.input`.
        to: String,
        /// The node path that would loop.
        path: String,
    },
    /// The same wire exists already.
    #[error("{from} -> {to} is already connected")]
    AlreadyConnected {
        /// `node.output`.
        from: String,
        /// `node.input`.
        to: String,
    },
    /// No such wire.
    #[error("{from} -> {to} is not connected")]
    NotConnected {
        /// `node.output`.
        from: String,
        /// `node.input`.
        to: String,
    },
    /// A literal value does not fit the input.
    #[error("input '{node}.{port}': {message}")]
    BadValue {
        /// Node id.
        node: String,
        /// Port.
        port: String,
        /// What is wrong.
        message: String,
    },
}

fn did_you_mean(suggestions: &[String]) -> String {
    if suggestions.is_empty() {
        String::new()
    } else {
        format!(
            " (did you mean {}?)",
            suggestions
                .iter()
                .map(|s| format!("'{s}'"))
                .collect::<Vec<_>>()
                .join(", ")
        )
    }
}
