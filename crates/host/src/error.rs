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
}

impl HostError {
    /// A usage error with this message.
    pub fn usage(message: impl Into<String>) -> Self {
        Self::Usage(message.into())
    }
}
