//! Graph files: loading with library folders and overrides, graph files used as node types
//! (`cluster:<path.ron>`, the graphs of a library folder), and what an editor's library needs:
//! load options for a document and its library folders ([`document_options`]), a folder's graphs
//! with an interface ([`library_entry`]) and the node a `source` of a cluster node loads
//! ([`source_def`]), resolved exactly as a graph file's cluster nodes are.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use cnets_engine::cluster::{Cluster, ClusterSource};
use cnets_engine::file::{Document, LoadOptions, load_cluster_source, load_file_with};
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

/// Load options for a graph file, with library folders (in the order given; a door puts
/// `CNETS_LIBRARY`'s first, [`crate::library_from_env`]).
pub fn options(path: &Path, library: &[PathBuf]) -> LoadOptions {
    library
        .iter()
        .fold(LoadOptions::for_file(path), |o, dir| o.with_library(dir))
}

/// Load options for a document at `doc` (`None`: an untitled document, with no folder of its own)
/// whose cluster sources are also looked up in the folders `library`, each followed by its
/// `library` subfolder ([`library_folders`]), after `CNETS_LIBRARY`'s: the editor's resolution.
/// (The editor's door reads `CNETS_LIBRARY` here, [`crate::library_from_env`], until it hands its
/// library to a [`crate::Session`] itself.)
pub fn document_options(doc: Option<&Path>, library: &[PathBuf]) -> LoadOptions {
    let folders: Vec<PathBuf> = crate::library_from_env()
        .into_iter()
        .chain(library_folders(library))
        .collect();
    let mut options = options(doc.unwrap_or(Path::new("untitled.ron")), &folders);
    if doc.is_none() {
        options.base_dir = None;
    }
    options
}

/// The folders a library is searched in: each of `dirs`, then its `library` subfolder when it has
/// one (the examples folder `graphs/` ships its reusable clusters in `graphs/library/`).
pub fn library_folders(dirs: &[PathBuf]) -> Vec<PathBuf> {
    dirs.iter()
        .flat_map(|d| {
            let sub = d.join("library");
            std::iter::once(d.clone()).chain(sub.is_dir().then_some(sub))
        })
        .collect()
}

/// The graph files (`*.ron`) of a folder, sorted by name.
pub fn graph_files(dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "ron"))
        .collect();
    files.sort();
    Ok(files)
}

/// One graph of a library folder, as a palette lists it.
#[derive(Clone, Debug, PartialEq)]
pub struct LibraryEntry {
    /// Shown name (the file stem).
    pub name: String,
    /// The file.
    pub path: PathBuf,
    /// The `source` a cluster node gets: the path relative to its library folder.
    pub source: String,
    /// The graph's description (or name).
    pub doc: String,
    /// Input and output port names.
    pub ports: (Vec<String>, Vec<String>),
}

/// Reads the graph file `path` of a library folder (its cluster sources resolved with `options`)
/// as a library entry; an error when it does not load or has no interface.
pub fn library_entry(
    path: &Path,
    registry: &Arc<Registry>,
    options: &LoadOptions,
) -> Result<LibraryEntry, HostError> {
    let file_name = |p: &Path| p.file_name().map(|n| n.to_string_lossy().into_owned());
    let source = file_name(path).unwrap_or_else(|| path.display().to_string());
    let cluster = interface_cluster(&source, path, registry, options)?;
    let names = |ports: &[cnets_engine::cluster::InterfacePort]| {
        ports.iter().map(|p| p.port.name.to_string()).collect()
    };
    Ok(LibraryEntry {
        name: path
            .file_stem()
            .map_or_else(|| source.clone(), |s| s.to_string_lossy().into_owned()),
        path: path.to_path_buf(),
        doc: cluster
            .meta
            .description
            .clone()
            .or_else(|| cluster.meta.name.clone())
            .unwrap_or_else(|| "a graph used as a node".to_string()),
        ports: (
            names(&cluster.interface.inputs),
            names(&cluster.interface.outputs),
        ),
        source,
    })
}

/// The node definition of a cluster node with `source: "<source>"` in a graph loaded with
/// `options`: loaded by the graph loader itself (same lookup, read permissions, nesting limit and
/// diagnostics as in a file; [`cnets_engine::file::load_cluster_source`]).
pub fn source_def(
    source: &str,
    registry: &Arc<Registry>,
    options: &LoadOptions,
) -> Result<Arc<NodeDef>, HostError> {
    let cluster = load_cluster_source(source, registry, options)?;
    Ok(Arc::new(cluster.node_def()))
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
    let cluster = interface_cluster(path, file, registry, &options)?;
    let mut def = cluster.node_def();
    def.id = format!("{PREFIX}{path}").into();
    if writes_files(&cluster.template) {
        // Run as one node (`cnets eval cluster:…`, Python, Hops), it needs the output folder.
        def.flags.push(NodeFlag::Export);
    }
    Ok(def)
}

/// The graph file `file` (written as `written`) as a cluster, refused when it has no interface.
fn interface_cluster(
    written: &str,
    file: &Path,
    registry: &Arc<Registry>,
    options: &LoadOptions,
) -> Result<Arc<Cluster>, HostError> {
    let doc = load_file_with(file, registry, options)?;
    let source = ClusterSource::File {
        written: written.to_string(),
        resolved: file.to_path_buf(),
    };
    let cluster = Cluster::new(
        source,
        doc.graph,
        doc.meta,
        file.parent().map(Path::to_path_buf),
    )
    .map_err(|e| HostError::usage(format!("{written}: {e}")))?;
    if cluster.interface.is_empty() {
        return Err(HostError::NoInterface {
            written: written.to_string(),
        });
    }
    Ok(cluster)
}

/// Whether a graph writes files: an export node in it, or in a cluster inside it.
pub fn writes_files(graph: &Graph) -> bool {
    graph.nodes().any(|(_, n)| {
        n.def.has_flag(NodeFlag::Export)
            || Cluster::of(&n.def).is_some_and(|c| writes_files(&c.template))
    })
}

/// Every graph of a folder that declares an interface, as node types (sorted by file name), and a
/// message for each file that does not load (skipped). Their cluster sources resolve next to
/// them, then in `library` (a door passes `CNETS_LIBRARY`'s folders), then in `dir`.
pub fn folder_defs(
    dir: &Path,
    registry: &Arc<Registry>,
    library: &[PathBuf],
) -> Result<(Vec<NodeDef>, Vec<String>), HostError> {
    let files = graph_files(dir).map_err(|e| {
        HostError::usage(format!(
            "{}: cannot read the library folder: {e}",
            dir.display()
        ))
    })?;
    let mut defs = Vec::new();
    let mut skipped = Vec::new();
    for file in files {
        let path = file.display().to_string();
        let folders: Vec<PathBuf> = library
            .iter()
            .chain([&dir.to_path_buf()])
            .cloned()
            .collect();
        match cluster_def(&path, registry, &folders, &[]) {
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

    /// A library graph: half its input.
    const HALF: &str = r#"(version: 1, description: "half its input", nodes: {
        "x": (type: "graph.input", inputs: {"name": "x", "type": "number", "default": 4.0}),
        "half": (type: "math.divide", inputs: {"b": 2.0}),
        "y": (type: "graph.output", inputs: {"name": "half", "type": "number"}),
    }, edges: ["x.value -> half.a", "half.result -> y.value"])"#;

    #[test]
    fn library_graphs_are_entries_and_their_sources_load_as_cluster_nodes() {
        let registry = Arc::new(cnets_nodes::registry());
        let d = std::env::temp_dir().join(format!("cnets-host-entries-{}", std::process::id()));
        let sub = d.join("library");
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&sub).unwrap();
        std::fs::write(sub.join("half.ron"), HALF).unwrap();
        // A graph without an interface, and a file that is not a graph.
        std::fs::write(d.join("plain.ron"), "(version: 1, nodes: {}, edges: [])").unwrap();
        std::fs::write(d.join("notes.txt"), "not a graph").unwrap();
        // A folder's `library` subfolder is searched right after it.
        let folders = library_folders(std::slice::from_ref(&d));
        assert_eq!(folders, vec![d.clone(), sub.clone()]);
        assert_eq!(graph_files(&d).unwrap(), vec![d.join("plain.ron")]);
        let half = sub.join("half.ron");
        let entry = library_entry(
            &half,
            &registry,
            &document_options(Some(&half), std::slice::from_ref(&d)),
        )
        .unwrap();
        assert_eq!(
            entry,
            LibraryEntry {
                name: "half".into(),
                path: half.clone(),
                source: "half.ron".into(),
                doc: "half its input".into(),
                ports: (vec!["x".into()], vec!["half".into()]),
            }
        );
        let plain = d.join("plain.ron");
        let e = library_entry(&plain, &registry, &document_options(Some(&plain), &[]))
            .unwrap_err()
            .to_string();
        assert!(e.contains("no graph.input or graph.output"), "{e}");
        // From an untitled document elsewhere, the source resolves through the library folders.
        let untitled = document_options(None, std::slice::from_ref(&d));
        assert_eq!(untitled.base_dir, None);
        let def = source_def("half.ron", &registry, &untitled).unwrap();
        let c = Cluster::of(&def).unwrap();
        assert!(matches!(&c.source, ClusterSource::File { written, .. } if written == "half.ron"));
        assert_eq!(def.inputs[0].name, "x");
        let e = source_def("nope.ron", &registry, &untitled)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("cluster source 'nope.ron' not found (looked for: "),
            "{e}"
        );
        std::fs::remove_dir_all(&d).unwrap();
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
            folder_defs(Path::new(&shipped("x")).parent().unwrap(), &registry, &[]).unwrap();
        assert!(skipped.is_empty(), "{skipped:?}");
        assert_eq!(defs.len(), 4, "the shipped library's four clusters");
    }
}
