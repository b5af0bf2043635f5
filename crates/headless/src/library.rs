//! Graph files used as node types: `cluster:<path.ron>` and library folders (the logic lives in
//! `cnets-host`, shared with the Python package).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use cnets_engine::file::Document;
use cnets_engine::{NodeDef, Registry};

use crate::failure::Failure;

pub use cnets_host::PREFIX;

/// Loads a graph file (cluster sources next to it, then in the library folders) and applies the
/// `--set node.input=value` overrides.
pub fn load_graph(path: &Path, library: &[PathBuf], sets: &[String]) -> Result<Document, Failure> {
    load_graph_allowing(path, library, sets, &[])
}

/// [`load_graph`] with further folders cluster files may be read from (`--allow-read`).
pub fn load_graph_allowing(
    path: &Path,
    library: &[PathBuf],
    sets: &[String],
    allow_read: &[PathBuf],
) -> Result<Document, Failure> {
    Ok(cnets_host::load_graph(path, library, sets, allow_read)?)
}

/// The node type of a graph file used as a cluster.
pub fn cluster_def(
    path: &str,
    registry: &Arc<Registry>,
    library: &[PathBuf],
    allow_read: &[PathBuf],
) -> Result<NodeDef, Failure> {
    Ok(cnets_host::cluster_def(
        path, registry, library, allow_read,
    )?)
}

/// Every graph of a folder that declares an interface, as node types (sorted by file name).
/// Files that do not load are reported on stderr and skipped.
pub fn folder_defs(dir: &Path, registry: &Arc<Registry>) -> Result<Vec<NodeDef>, Failure> {
    let (defs, skipped) = cnets_host::folder_defs(dir, registry)?;
    for m in skipped {
        crate::errln!("warning: skipped {m}");
    }
    Ok(defs)
}
