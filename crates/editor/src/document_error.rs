//! Why a document refused to open a cluster, to leave one or to be saved. Shown in the status bar
//! (and, for a cluster that cannot be rebuilt, on the canvas while its subgraph is edited).

use std::path::PathBuf;

use cnets_engine::GraphError;
use thiserror::Error;

/// Why the document could not do what was asked; nothing changed.
#[derive(Debug, Error)]
pub enum DocumentError {
    /// No node has the id.
    #[error("no node '{0}'")]
    NoNode(String),
    /// The node is not a cluster (it cannot be opened in place).
    #[error("node '{0}' is not a cluster")]
    NotACluster(String),
    /// Leaving asked at the document's own level.
    #[error("not inside a cluster")]
    NotInACluster,
    /// The edited subgraph does not make a valid cluster (a port's name, a cycle …).
    #[error("cluster '{node}': {reason}")]
    Cluster {
        /// The cluster node.
        node: String,
        /// What the cluster's interface said.
        reason: String,
    },
    /// The rebuilt cluster's node did not fit the graph around it.
    #[error(transparent)]
    Graph(#[from] GraphError),
    /// The file could not be written.
    #[error("cannot save {}: {error}", .path.display())]
    Save {
        /// The file.
        path: PathBuf,
        /// The system's reason.
        error: std::io::Error,
    },
}
