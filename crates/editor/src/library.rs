//! The user library: folders of graph files with an interface (`graph.input` / `graph.output`
//! nodes), shown in the palette's "Library" category and inserted as `cluster` nodes whose
//! `source` is the file. Reading a library graph, the load options of a document with its library
//! folders and the cluster node of a `source` come from the host ([`cnets_host::library_entry`],
//! [`cnets_host::document_options`], [`cnets_host::source_def`]): resolved as a graph file's
//! cluster nodes are — next to the graph first, then each library folder, then `CNETS_LIBRARY`.
//! A library folder's `library` subfolder is a library folder too (right after it): the examples
//! folder `graphs/` ships its reusable clusters in `graphs/library/`. This module keeps what the
//! editor adds: the scan cached by modification time and the watch on cluster files.
//!
//! The watch on cluster files: [`ClusterWatch`] remembers the content of every file a cluster
//! node of the graph being edited comes from and reports the files that changed, so the editor
//! reloads those cluster nodes (new definition, wires kept where the ports still exist).

use std::collections::HashMap;
use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::SystemTime;

use cnets_engine::cluster::{Cluster, ClusterSource};
use cnets_engine::{Graph, Registry};
use cnets_host::LibraryEntry;

/// The default user library folder: `$XDG_DATA_HOME/cnets/library`, else
/// `~/.local/share/cnets/library`.
pub fn default_library_dir() -> PathBuf {
    if let Some(dir) = std::env::var_os("XDG_DATA_HOME").filter(|d| !d.is_empty()) {
        return PathBuf::from(dir).join("cnets").join("library");
    }
    let home = std::env::var_os("HOME").map_or_else(|| PathBuf::from("."), PathBuf::from);
    home.join(".local/share/cnets/library")
}

/// The graphs with an interface in the library folders, scanned on demand and cached by file
/// modification time.
#[derive(Default)]
pub struct Library {
    /// The folders, searched in order.
    pub dirs: Vec<PathBuf>,
    cache: HashMap<PathBuf, (Option<SystemTime>, Option<LibraryEntry>)>,
    entries: Vec<LibraryEntry>,
}

impl Library {
    /// A library over `dirs` (not scanned yet).
    pub fn new(dirs: Vec<PathBuf>) -> Self {
        Self {
            dirs,
            ..Self::default()
        }
    }

    /// The entries found by the last [`Library::scan`].
    pub fn entries(&self) -> &[LibraryEntry] {
        &self.entries
    }

    /// Lists the folders' graph files again (files unchanged since the last scan are not
    /// re-read); a file that does not load or has no interface is skipped.
    pub fn scan(&mut self, registry: &Arc<Registry>) -> &[LibraryEntry] {
        let mut entries = Vec::new();
        let mut seen = std::collections::HashSet::new();
        for dir in cnets_host::library_folders(&self.dirs) {
            for path in cnets_host::graph_files(&dir).unwrap_or_default() {
                let Some(name) = path.file_stem().map(|s| s.to_string_lossy().into_owned()) else {
                    continue;
                };
                if !seen.insert(name) {
                    continue; // an earlier folder has a graph of that name: it wins, as on load
                }
                let modified = std::fs::metadata(&path).and_then(|m| m.modified()).ok();
                let cached = self
                    .cache
                    .get(&path)
                    .filter(|(m, _)| *m == modified && modified.is_some())
                    .map(|(_, e)| e.clone());
                let entry = match cached {
                    Some(e) => e,
                    None => {
                        let options = cnets_host::document_options(Some(&path), &self.dirs);
                        let e = cnets_host::library_entry(&path, registry, &options).ok();
                        self.cache.insert(path.clone(), (modified, e.clone()));
                        e
                    }
                };
                entries.extend(entry);
            }
        }
        self.entries = entries;
        &self.entries
    }
}

/// The cluster nodes of `graph` loaded from files: (node id, source as written, file).
pub fn file_clusters(graph: &Graph) -> Vec<(String, String, PathBuf)> {
    let mut out: Vec<(u64, (String, String, PathBuf))> = graph
        .nodes()
        .filter_map(|(_, n)| match &Cluster::of(&n.def)?.source {
            ClusterSource::File { written, resolved } => {
                Some((n.uid(), (n.id.clone(), written.clone(), resolved.clone())))
            }
            ClusterSource::Inline => None,
        })
        .collect();
    out.sort_by_key(|(uid, _)| *uid);
    out.into_iter().map(|(_, c)| c).collect()
}

fn content_hash(path: &Path) -> Option<u64> {
    let bytes = std::fs::read(path).ok()?;
    let mut h = std::collections::hash_map::DefaultHasher::new();
    bytes.hash(&mut h);
    Some(h.finish())
}

/// Remembers the content of cluster files and tells which changed.
#[derive(Default)]
pub struct ClusterWatch {
    seen: HashMap<PathBuf, Option<u64>>,
}

impl ClusterWatch {
    /// Forgets every file (a new document).
    pub fn clear(&mut self) {
        self.seen.clear();
    }

    /// Checks the files of `graph`'s file clusters; returns those whose content changed since
    /// they were first seen (a file seen for the first time is only remembered).
    pub fn changed(&mut self, graph: &Graph) -> Vec<PathBuf> {
        let mut changed = Vec::new();
        for (_, _, path) in file_clusters(graph) {
            if changed.contains(&path) {
                continue;
            }
            let now = content_hash(&path);
            match self.seen.insert(path.clone(), now) {
                Some(before) if before != now => changed.push(path),
                _ => {}
            }
        }
        changed
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SUB: &str = r#"(
    version: 1,
    description: "twice its input",
    nodes: {
        "x": (type: "graph.input", inputs: {"name": "x", "type": "number", "default": 2.0}),
        "n": (type: "param.number", inputs: {"value": 1.0}),
        "out": (type: "graph.output", inputs: {"name": "y", "type": "number"}),
    },
    edges: ["x.value -> out.value"],
)"#;

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("cnets-library-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn graphs_with_an_interface_are_listed() {
        let registry = Arc::new(cnets_nodes::registry());
        let d = dir("scan");
        std::fs::write(d.join("twice.ron"), SUB).unwrap();
        std::fs::write(
            d.join("plain.ron"),
            "(version: 1, nodes: {\"n\": (type: \"param.number\")}, edges: [])",
        )
        .unwrap();
        std::fs::write(d.join("broken.ron"), "(version: ").unwrap();
        let mut lib = Library::new(vec![d.clone()]);
        let entries = lib.scan(&registry).to_vec();
        assert_eq!(entries.len(), 1, "{entries:?}");
        assert_eq!(entries[0].name, "twice");
        assert_eq!(entries[0].ports, (vec!["x".into()], vec!["y".into()]));
        // A changed file is read again (the cache is keyed by modification time).
        std::fs::write(
            d.join("twice.ron"),
            SUB.replace("twice its input", "doubled"),
        )
        .unwrap();
        let later = std::time::SystemTime::now() + std::time::Duration::from_secs(5);
        std::fs::File::options()
            .write(true)
            .open(d.join("twice.ron"))
            .and_then(|f| f.set_modified(later))
            .unwrap();
        assert_eq!(lib.scan(&registry)[0].doc, "doubled");
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn the_watch_reports_changed_files_once() {
        let registry = Arc::new(cnets_nodes::registry());
        let d = dir("watch");
        std::fs::write(d.join("twice.ron"), SUB).unwrap();
        let mut g = Graph::new(registry.clone());
        let def = cnets_host::source_def(
            "twice.ron",
            &registry,
            &cnets_host::document_options(None, std::slice::from_ref(&d)),
        )
        .unwrap();
        g.add_node_with_def("c", def).unwrap();
        let mut w = ClusterWatch::default();
        assert!(w.changed(&g).is_empty(), "first seen");
        assert!(w.changed(&g).is_empty());
        std::fs::write(d.join("twice.ron"), SUB.replace("2.0", "3.0")).unwrap();
        assert_eq!(w.changed(&g).len(), 1);
        assert!(w.changed(&g).is_empty(), "reported once");
        std::fs::remove_dir_all(&d).unwrap();
    }
}
