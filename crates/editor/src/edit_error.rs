//! Why an edit of the document was refused (the graph is unchanged then). The status bar shows
//! it after "refused: ".

use cnets_engine::GraphError;
use cnets_engine::cluster::edit::ClusterEditError;
use thiserror::Error;

/// Why an [`Edit`](crate::edit::Edit) was refused.
#[derive(Debug, Error)]
pub enum EditError {
    /// The graph refused a change (an unknown node or port, a wire that would make a cycle …).
    #[error(transparent)]
    Graph(#[from] GraphError),
    /// Making or exploding a cluster failed.
    #[error(transparent)]
    Cluster(#[from] ClusterEditError),
    /// The laid-out cluster's interface was refused.
    #[error("{0}")]
    Interface(String),
    /// The copied nodes could not be pasted.
    #[error("{0}")]
    Paste(String),
    /// A construction plane of that name exists.
    #[error("a construction plane is already called '{0}'")]
    CPlaneNameTaken(String),
}
