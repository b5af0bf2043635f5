//! Clusters: make, open and leave them, insert library graphs, reload cluster files changed on disk.

use crate::edit::Edit;
use cnets_engine::cluster::Cluster;
use cnets_host::LibraryEntry;
use web_time::Instant;

use super::EditorApp;
use crate::import_watch::ImportWatch;
use crate::library::ClusterWatch;

/// The files the graph being edited reads, watched for changes on disk.
pub(super) struct Watching {
    /// Files the graph's nodes import.
    pub(super) import_watch: ImportWatch,
    /// The graph's cluster files.
    pub(super) watch: ClusterWatch,
    /// When they were last checked (about once a second).
    pub(super) last_watch: Instant,
}

impl Default for Watching {
    fn default() -> Self {
        Self {
            import_watch: ImportWatch::default(),
            watch: ClusterWatch::default(),
            last_watch: Instant::now(),
        }
    }
}

impl EditorApp {
    /// The first cluster node among the nodes commands act on (selection, else focus).
    pub(super) fn targeted_cluster(&self) -> Option<String> {
        self.canvas.targets().into_iter().find(|id| {
            self.doc
                .graph
                .node(id)
                .is_some_and(|n| Cluster::of(&n.def).is_some())
        })
    }

    /// Replaces the nodes `ids` by one inline cluster node (one undo step). Inside the cluster,
    /// its `graph.input` nodes are placed left of the nodes and its `graph.output` nodes right of
    /// them, using the node sizes measured on the canvas. Returns whether it was made.
    pub fn make_cluster(&mut self, ids: &[String]) -> bool {
        let around = self.canvas.bounds_of(ids);
        self.edit(Edit::MakeCluster {
            nodes: ids.to_vec(),
            around,
        })
    }

    /// Opens the cluster node `id` in place (the canvas shows its subgraph).
    pub fn open_cluster(&mut self, id: &str) {
        match self.doc.enter(id) {
            Ok(()) => {
                self.message = format!("inside cluster '{id}' — Esc or the breadcrumbs go back")
            }
            Err(e) => self.message = e.to_string(),
        }
    }

    /// Goes back out of opened clusters to breadcrumb level `depth` (0: the document's graph),
    /// rebuilding each cluster from its edited subgraph.
    pub fn leave_to(&mut self, depth: usize) {
        let mut notes = Vec::new();
        while self.doc.depth() > depth {
            let id = self.doc.view_path().last().cloned().unwrap_or_default();
            match self.doc.leave() {
                Ok(r) => {
                    let m = r.message();
                    if !m.is_empty() {
                        notes.push(format!("'{id}': {m}"));
                    }
                }
                Err(e) => {
                    self.message = format!("cannot leave the cluster: {e}");
                    return;
                }
            }
        }
        self.message = if notes.is_empty() {
            "back".to_string()
        } else {
            notes.join("; ")
        };
    }

    /// Inserts a library graph as a cluster node at a canvas position; returns its id.
    pub fn add_library_cluster(&mut self, entry: &LibraryEntry, at: [f32; 2]) -> Option<String> {
        let def = match cnets_host::source_def(&entry.source, &self.registry, &self.load_options())
        {
            Ok(d) => d,
            Err(e) => {
                self.message = format!("cannot insert {}: {e}", entry.name);
                return None;
            }
        };
        let id = self.doc.fresh_id(&entry.name);
        let r = self.doc.edit(None, |g, _| {
            g.add_node_with_def(&id, def).map_err(|e| e.to_string())?;
            g.set_position(&id, at).map_err(|e| e.to_string())
        });
        match r {
            Ok(()) => {
                self.canvas.focused = Some(id.clone());
                self.watching.watch.changed(&self.doc.graph);
                Some(id)
            }
            Err(e) => {
                self.message = e;
                None
            }
        }
    }

    /// Checks the files of the graph's file clusters now and reloads the cluster nodes whose file
    /// changed (new definition, wires kept where the ports still exist; no undo step: the graph's
    /// text does not change). Returns whether anything was reloaded.
    pub fn check_cluster_files(&mut self) -> bool {
        self.watching.last_watch = Instant::now();
        let changed = self.watching.watch.changed(&self.doc.graph);
        if changed.is_empty() {
            return false;
        }
        let options = self.load_options();
        let nodes: Vec<(String, String)> = crate::library::file_clusters(&self.doc.graph)
            .into_iter()
            .filter(|(_, _, path)| changed.contains(path))
            .map(|(id, written, _)| (id, written))
            .collect();
        let mut notes = Vec::new();
        let registry = self.registry.clone();
        for (id, written) in nodes {
            match cnets_host::source_def(&written, &registry, &options) {
                Ok(def) => {
                    match self
                        .doc
                        .update_quietly(|g| g.replace_def(&id, def).map_err(|e| e.to_string()))
                    {
                        Ok(dropped) if dropped.is_empty() => {
                            notes.push(format!("reloaded '{id}' from {written}"))
                        }
                        Ok(dropped) => notes.push(format!(
                            "reloaded '{id}' from {written}; dropped wires: {}",
                            dropped
                                .iter()
                                .map(ToString::to_string)
                                .collect::<Vec<_>>()
                                .join(", ")
                        )),
                        Err(e) => notes.push(format!("cannot reload '{id}': {e}")),
                    }
                }
                Err(e) => notes.push(format!("cannot reload '{id}' from {written}: {e}")),
            }
        }
        self.message = notes.join("; ");
        true
    }
}
