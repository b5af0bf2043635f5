//! Errors of graph edits.

use thiserror::Error;

/// Why a graph edit was refused. The graph is left unchanged.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum GraphError {
    /// No node with this id.
    #[error("no node '{}'", q(.0))]
    UnknownNode(String),
    /// A node with this id already exists.
    #[error("a node '{}' already exists", q(.0))]
    DuplicateId(String),
    /// Node ids are non-empty and use letters, digits, '_' and '-'.
    #[error("invalid node id '{}': use letters, digits, '_' and '-'", q(.0))]
    InvalidId(String),
    /// No node type with this id.
    #[error("unknown node type '{}'{}", q(.type_id), did_you_mean(.suggestions))]
    UnknownType {
        /// The requested type.
        type_id: String,
        /// Similar known types.
        suggestions: Vec<String>,
    },
    /// The node has no input with this name.
    #[error("node '{}' ({type_id}) has no input '{}'; its inputs are: {valid}", q(.node), q(.port))]
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
    #[error("node '{}' ({type_id}) has no output '{}'; its outputs are: {valid}", q(.node), q(.port))]
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
    #[error("type mismatch: {} gives {from_type} but {} takes {to_type}", q(.from), q(.to))]
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
    #[error("connecting {} -> {} would create a cycle: {}", q(.from), q(.to), q(.path))]
    Cycle {
        /// `node.output`.
        from: String,
        /// `node.input`.
        to: String,
        /// The node path that would loop.
        path: String,
    },
    /// The same wire exists already.
    #[error("{} -> {} is already connected", q(.from), q(.to))]
    AlreadyConnected {
        /// `node.output`.
        from: String,
        /// `node.input`.
        to: String,
    },
    /// No such wire.
    #[error("{} -> {} is not connected", q(.from), q(.to))]
    NotConnected {
        /// `node.output`.
        from: String,
        /// `node.input`.
        to: String,
    },
    /// A literal value does not fit the input.
    #[error("input '{}.{}': {message}", q(.node), q(.port))]
    BadValue {
        /// Node id.
        node: String,
        /// Port.
        port: String,
        /// What is wrong.
        message: String,
    },
}

/// A name as an error quotes it: at most 60 characters (a 10⁷-character id is not echoed whole).
fn q(name: &str) -> String {
    crate::files::excerpt(name, 60)
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
