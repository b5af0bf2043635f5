//! Graph files: loading with library folders and overrides, and graph files used as node types
//! (`cluster:<path.ron>`, the graphs of a library folder).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use cnets_engine::cluster::{Cluster, ClusterSource};
use cnets_engine::file::{Document, LoadOptions, load_file_with};
use cnets_engine::{Graph, NodeDef, NodeFlag, Registry};

use crate::HostError;

/// The prefix that names a graph file as a node type (`cnets eval cluster:path.ron`).
pub const PREFIX: &str = "cluster:";

/// Loads a graph file with every node of the library (cluster sources next to it, then in the
/// `library` folders; cluster files read only there and under `allow_read`) and applies the
/// `node.input=value` overrides.
pub fn load_graph(
    path: &Path,
    library: &[PathBuf],
    sets: &[String],
    allow_read: &[PathBuf],
) -> Result<Document, HostError> {
    let registry = Arc::new(cnets_nodes::registry());
    let mut options = options(path, library);
    options.allow_read = allow_read.to_vec();
    let mut doc = load_file_with(path, &registry, &options)?;
    for set in sets {
        crate::inputs::apply_set(&mut doc.graph, set)?;
    }
    Ok(doc)
}

/// Load options for a graph file, with extra library folders.
pub fn options(path: &Path, library: &[PathBuf]) -> LoadOptions {
    library
        .iter()
        .fold(LoadOptions::for_file(path), |o, dir| o.with_library(dir))
}

/// The node type of a graph file used as a cluster; its id is `cluster:<path>`.
pub fn cluster_def(
    path: &str,
    registry: &Arc<Registry>,
    library: &[PathBuf],
    allow_read: &[PathBuf],
) -> Result<NodeDef, HostError> {
    let file = Path::new(path);
    let mut options = options(file, library);
    options.allow_read = allow_read.to_vec();
    let doc = load_file_with(file, registry, &options)?;
    let source = ClusterSource::File {
        written: path.to_string(),
        resolved: file.to_path_buf(),
    };
    let cluster = Cluster::new(
        source,
        doc.graph,
        doc.meta,
        file.parent().map(Path::to_path_buf),
    )
    .map_err(|e| HostError::usage(format!("{path}: {e}")))?;
    if cluster.interface.is_empty() {
        return Err(HostError::usage(format!(
            "{path}: the graph has no graph.input or graph.output nodes, so it cannot be used as a node"
        )));
    }
    let mut def = cluster.node_def();
    def.id = format!("{PREFIX}{path}").into();
    if writes_files(&cluster.template) {
        // Run as one node (`cnets eval cluster:…`, Python, Hops), it needs the output folder.
        def.flags.push(NodeFlag::Export);
    }
    Ok(def)
}

/// Whether a graph writes files: an export node in it, or in a cluster inside it.
pub fn writes_files(graph: &Graph) -> bool {
    graph.nodes().any(|(_, n)| {
        n.def.has_flag(NodeFlag::Export)
            || Cluster::of(&n.def).is_some_and(|c| writes_files(&c.template))
    })
}

/// Every graph of a folder that declares an interface, as node types (sorted by file name), and a
/// message for each file that does not load (skipped).
pub fn folder_defs(
    dir: &Path,
    registry: &Arc<Registry>,
) -> Result<(Vec<NodeDef>, Vec<String>), HostError> {
    let entries = std::fs::read_dir(dir).map_err(|e| {
        HostError::usage(format!(
            "{}: cannot read the library folder: {e}",
            dir.display()
        ))
    })?;
    let mut files: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "ron"))
        .collect();
    files.sort();
    let mut defs = Vec::new();
    let mut skipped = Vec::new();
    for file in files {
        let path = file.display().to_string();
        match cluster_def(&path, registry, &[dir.to_path_buf()], &[]) {
            Ok(def) => defs.push(def),
            Err(e) => skipped.extend(e.to_string().lines().map(str::to_string)),
        }
    }
    Ok((defs, skipped))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shipped(name: &str) -> String {
        format!(
            "{}/../../graphs/library/{name}.ron",
            env!("CARGO_MANIFEST_DIR")
        )
    }

    #[test]
    fn a_cluster_that_writes_files_is_an_export_node() {
        let registry = Arc::new(cnets_nodes::registry());
        let strips = cluster_def(&shipped("strip-fabrication"), &registry, &[], &[]).unwrap();
        assert!(
            strips.has_flag(NodeFlag::Export),
            "it writes the cutting sheets"
        );
        let support = cluster_def(&shipped("support-structure"), &registry, &[], &[]).unwrap();
        assert!(!support.has_flag(NodeFlag::Export));
        let (defs, skipped) =
            folder_defs(Path::new(&shipped("x")).parent().unwrap(), &registry).unwrap();
        assert!(skipped.is_empty(), "{skipped:?}");
        assert_eq!(defs.len(), 4, "the shipped library's four clusters");
    }
}
