//! The subgraphs of cluster nodes: from a `source` file (read once per file, checked against the
//! read permissions, nested at most `MAX_CLUSTER_DEPTH` deep) or an inline `graph`.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use super::diagnostics::LoadError;
use super::load::{LoadOptions, Loader, Unresolved, load_file_with, load_root};
use super::ron::{Node, Pos};
use crate::cluster::{Cluster, ClusterSource};
use crate::registry::Registry;

/// Loads the subgraph of a cluster node, from its `source` file or its inline `graph`.
pub(super) fn load_cluster(
    loader: &mut Loader<'_>,
    id: &str,
    body: &Node,
    registry: Arc<Registry>,
    source: Option<&Node>,
    inline: Option<&Node>,
) -> Option<Arc<Cluster>> {
    match (source, inline) {
        (Some(_), Some(g)) => {
            loader.error(
                g.pos,
                format!("node '{id}': a cluster has either 'source' or 'graph', not both"),
            );
            None
        }
        (None, None) => {
            loader.error(
                body.pos,
                format!(
                    "node '{id}': a cluster needs 'source: \"file.ron\"' or an inline 'graph: (..)'"
                ),
            );
            None
        }
        (Some(s), None) => {
            let Some(written) = s.as_str() else {
                loader.error(
                    s.pos,
                    format!("node '{id}': 'source' must be a string (a graph file path)"),
                );
                return None;
            };
            load_source(
                loader,
                &format!("node '{id}': "),
                Some(s.pos),
                written,
                &registry,
            )
        }
        (None, Some(g)) => {
            let doc = load_root(loader, g, &registry);
            match Cluster::new(
                ClusterSource::Inline,
                doc.graph,
                doc.meta,
                loader.options.base_dir.clone(),
            ) {
                Ok(c) => Some(c),
                Err(e) => {
                    loader.error(g.pos, format!("node '{id}': inline cluster: {e}"));
                    None
                }
            }
        }
    }
}

/// The cluster of a node `(type: "cluster", source: "<source>")` in a graph loaded with
/// `options`, loaded as the graph loader loads it — the same lookup (next to the graph, then in the
/// library folders), read permissions, nesting limit and diagnostics — without a graph around it:
/// what a front end inserting a library graph as a node needs. Problems with the source itself
/// (not found, not readable) are diagnostics without a file; those inside it name their file.
pub fn load_cluster_source(
    source: &str,
    registry: &Arc<Registry>,
    options: &LoadOptions,
) -> Result<Arc<Cluster>, LoadError> {
    let mut loader = Loader {
        file: "",
        diagnostics: Vec::new(),
        warnings: Vec::new(),
        options,
        clusters: HashMap::new(),
    };
    match load_source(&mut loader, "", None, source, registry) {
        Some(cluster) if loader.diagnostics.is_empty() => Ok(cluster),
        _ => Err(LoadError {
            diagnostics: loader.diagnostics,
        }),
    }
}

/// Loads the cluster of the source file `written` (resolved, checked against the read
/// permissions, the chain of files and the nesting limit); problems are reported at `pos` of the
/// loader's file, their messages starting with `prefix` (`node 'id': `).
fn load_source(
    loader: &mut Loader<'_>,
    prefix: &str,
    pos: Option<Pos>,
    written: &str,
    registry: &Arc<Registry>,
) -> Option<Arc<Cluster>> {
    let resolved = match loader.options.resolve(written) {
        Ok(p) => p,
        Err(Unresolved::Outside(e)) => {
            loader.report(pos, format!("{prefix}cluster source '{written}': {e}"));
            return None;
        }
        Err(Unresolved::NotFound(looked)) => {
            let looked: Vec<String> = looked.iter().map(|p| p.display().to_string()).collect();
            loader.report(
                pos,
                format!(
                    "{prefix}cluster source '{written}' not found (looked for: {})",
                    looked.join(", ")
                ),
            );
            return None;
        }
    };
    if let Err(e) = loader.options.read_access().check(&resolved) {
        loader.report(pos, format!("{prefix}cluster source '{written}': {e}"));
        return None;
    }
    let canonical = resolved.canonicalize().unwrap_or_else(|_| resolved.clone());
    if loader.options.stack.contains(&canonical) {
        let mut chain: Vec<String> = loader.options.stack.iter().map(|p| short_name(p)).collect();
        chain.push(short_name(&canonical));
        loader.report(
            pos,
            format!("{prefix}recursive cluster: {}", chain.join(" -> ")),
        );
        return None;
    }
    if loader.options.stack.len() >= crate::node::MAX_CLUSTER_DEPTH {
        let start = loader
            .options
            .stack
            .first()
            .map_or_else(|| loader.file.to_string(), |p| p.display().to_string());
        loader.report(
            pos,
            format!(
                "{prefix}{TOO_DEEP} {} deep: the chain starting at '{start}' reaches '{}' here",
                crate::node::MAX_CLUSTER_DEPTH,
                short_name(&canonical)
            ),
        );
        return None;
    }
    if let Some(loaded) = loader.clusters.get(&canonical).cloned() {
        if loaded.is_none() {
            loader.report(
                pos,
                format!("{prefix}cluster source '{written}' has errors"),
            );
        }
        return loaded.map(|c| c.duplicate());
    }
    let mut options = loader.options.clone();
    options.base_dir = resolved.parent().map(Path::to_path_buf);
    options.stack.push(canonical.clone());
    let cluster = load_cluster_file(loader, prefix, pos, written, resolved, registry, &options);
    loader.clusters.insert(canonical, cluster.clone());
    cluster
}

/// Loads a cluster's source file (once per including file).
fn load_cluster_file(
    loader: &mut Loader<'_>,
    prefix: &str,
    pos: Option<Pos>,
    written: &str,
    resolved: PathBuf,
    registry: &Arc<Registry>,
    options: &LoadOptions,
) -> Option<Arc<Cluster>> {
    match load_file_with(&resolved, registry, options) {
        Ok(doc) => {
            let source = ClusterSource::File {
                written: written.to_string(),
                resolved,
            };
            Cluster::new(source, doc.graph, doc.meta, options.base_dir.clone())
                .map_err(|e| loader.report(pos, format!("{prefix}cluster '{written}': {e}")))
                .ok()
        }
        Err(e) => {
            // Too deep a chain is reported once, where it goes too deep, not once per file.
            if let Some(deep) = e.diagnostics.iter().find(|d| d.message.contains(TOO_DEEP)) {
                loader.diagnostics.push(deep.clone());
                return None;
            }
            loader.report(
                pos,
                format!("{prefix}cluster source '{written}' has errors"),
            );
            loader.diagnostics.extend(e.diagnostics);
            None
        }
    }
}

/// The words of the error for a chain of cluster files nested too deep.
const TOO_DEEP: &str = "clusters nested more than";

fn short_name(p: &Path) -> String {
    p.file_name().map_or_else(
        || p.display().to_string(),
        |n| n.to_string_lossy().to_string(),
    )
}
