//! A node type named by a front end: a registry id (`cnets.construct`) or a graph file used as a
//! node (`cluster:<path.ron>`).

use std::path::PathBuf;
use std::sync::Arc;

use cnets_engine::{NodeDef, Registry};

use crate::{HostError, library};

/// A resolved node type.
#[derive(Debug, Clone)]
pub enum NodeType {
    /// A type of the registry.
    Registered(Arc<NodeDef>),
    /// A graph file's interface, built for this request.
    Cluster(Arc<NodeDef>),
}

impl NodeType {
    /// The node type's definition.
    pub fn def(&self) -> &Arc<NodeDef> {
        match self {
            NodeType::Registered(d) | NodeType::Cluster(d) => d,
        }
    }
}

/// Finds `id` in `registry`, or loads the graph file of `cluster:<path>` (cluster sources also in
/// `library`, files read also under `allow_read`). An unknown id says which ids are close.
pub fn resolve(
    id: &str,
    registry: &Arc<Registry>,
    library: &[PathBuf],
    allow_read: &[PathBuf],
) -> Result<NodeType, HostError> {
    if let Some(path) = id.strip_prefix(library::PREFIX) {
        let def = library::cluster_def(path, registry, library, allow_read)?;
        return Ok(NodeType::Cluster(Arc::new(def)));
    }
    if let Some(def) = registry.get(id) {
        return Ok(NodeType::Registered(def.clone()));
    }
    let hints = registry.similar_ids(id);
    let hint = if hints.is_empty() {
        String::new()
    } else {
        format!(" (did you mean {}?)", hints.join(", "))
    };
    Err(HostError::usage(format!(
        "unknown node type '{}'{hint}; `cnets nodes` lists them",
        cnets_engine::files::excerpt(id, 60)
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unknown_ids_get_hints_and_known_ids_resolve() {
        let registry = Arc::new(cnets_nodes::registry());
        let found = resolve("cnets.construct", &registry, &[], &[]).unwrap();
        assert_eq!(found.def().id, "cnets.construct");
        let err = resolve("cnets.constrct", &registry, &[], &[])
            .unwrap_err()
            .to_string();
        assert!(err.contains("did you mean cnets.construct"), "{err}");
        let err = resolve("cluster:/no/such/file.ron", &registry, &[], &[])
            .unwrap_err()
            .to_string();
        assert!(err.contains("/no/such/file.ron"), "{err}");
    }
}
