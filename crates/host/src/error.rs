//! The error of a host operation: bad usage (an unknown node type or input, a value that does not
//! fit) or a graph file that cannot be loaded.

use cnets_engine::file::LoadError;

/// Why a host operation failed.
#[derive(Debug, Clone, thiserror::Error)]
pub enum HostError {
    /// Bad usage: an unknown node type, input or node, a value of the wrong type, an unreadable
    /// folder. One line.
    #[error("{0}")]
    Usage(String),
    /// A graph file could not be loaded: every problem, with `file:line:col`.
    #[error("{0}")]
    Load(#[from] LoadError),
    /// A graph file named as a node (`cluster:…`) has no `graph.input` or `graph.output` node: it
    /// is a graph, not a component (Hops lists it as none).
    #[error(
        "{written}: the graph has no graph.input or graph.output nodes, so it cannot be used as a node"
    )]
    NoInterface {
        /// The file as it was written.
        written: String,
    },
}

impl HostError {
    /// A usage error with this message.
    pub fn usage(message: impl Into<String>) -> Self {
        Self::Usage(message.into())
    }
}
