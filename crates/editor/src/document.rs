//! The graph document: the engine [`Graph`] with its [`GraphMeta`] and file path — the single source
//! of truth of the editor. Every edit goes through [`GraphDocument::edit`], which records an undo
//! step (see [`crate::history`]) and marks the document dirty.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use cnets_engine::file::{self, GraphMeta};
use cnets_engine::{Graph, Registry};

use crate::history::{EditKey, History, Snapshot};

/// A graph being edited.
pub struct GraphDocument {
    /// The graph (nodes, literal values, wires, canvas positions, preview and enable flags).
    pub graph: Graph,
    /// Name and description written into the file.
    pub meta: GraphMeta,
    /// Where the document was loaded from or last saved to; `None` for a new document.
    pub path: Option<PathBuf>,
    /// Undo / redo.
    pub history: History,
    /// Changes since the last save.
    dirty: bool,
    /// Bumped when the graph was replaced wholesale (open, new, undo, redo): the evaluator must
    /// start afresh, since revisions of a restored graph are not comparable with its memos.
    generation: u64,
    /// Bumped on every change (semantic or not); cheap "did anything change" check.
    version: u64,
}

impl GraphDocument {
    /// An empty, untitled document.
    pub fn new(registry: Arc<Registry>) -> Self {
        Self::from_parts(Graph::new(registry), GraphMeta::default(), None)
    }

    /// A document from a loaded graph.
    pub fn from_parts(graph: Graph, meta: GraphMeta, path: Option<PathBuf>) -> Self {
        Self {
            graph,
            meta,
            path,
            history: History::default(),
            dirty: false,
            generation: 0,
            version: 0,
        }
    }

    /// Loads a graph file. The error text lists every diagnostic (`file:line:col: message`).
    pub fn open(path: &Path, registry: &Arc<Registry>) -> Result<Self, String> {
        let doc = file::load_file(path, registry).map_err(|e| e.to_string())?;
        Ok(Self::from_parts(
            doc.graph,
            doc.meta,
            Some(path.to_path_buf()),
        ))
    }

    /// Parses graph text (e.g. a recovery file) into a document with the given path.
    pub fn from_text(
        text: &str,
        name: &str,
        path: Option<PathBuf>,
        registry: &Arc<Registry>,
    ) -> Result<Self, String> {
        let doc = file::load_str(text, name, registry).map_err(|e| e.to_string())?;
        Ok(Self::from_parts(doc.graph, doc.meta, path))
    }

    /// Saves atomically to `path` (and remembers it as the document's path).
    pub fn save_as(&mut self, path: &Path) -> Result<(), String> {
        file::save_file(path, &self.graph, &self.meta)
            .map_err(|e| format!("cannot save {}: {e}", path.display()))?;
        self.path = Some(path.to_path_buf());
        self.dirty = false;
        Ok(())
    }

    /// The canonical file text of the current graph.
    pub fn to_ron(&self) -> String {
        file::to_ron(&self.graph, &self.meta)
    }

    /// Whether there are unsaved changes.
    pub fn is_dirty(&self) -> bool {
        self.dirty
    }

    /// Marks the document as changed (e.g. after a restore from a recovery file).
    pub fn mark_dirty(&mut self) {
        self.dirty = true;
        self.version += 1;
    }

    /// Changes whenever the graph was replaced wholesale (see the field docs).
    pub fn generation(&self) -> u64 {
        self.generation
    }

    /// Makes this document's generation follow `previous` (the document it replaces), so the
    /// worker starts a fresh evaluator for it.
    pub fn start_after(&mut self, previous: u64) {
        self.generation = previous + 1;
    }

    /// Changes whenever anything in the document changed.
    pub fn version(&self) -> u64 {
        self.version
    }

    /// The title shown in the window: file name (or "untitled") and a `*` when dirty.
    pub fn title(&self) -> String {
        let name = self.path.as_deref().and_then(Path::file_name).map_or_else(
            || "untitled".to_string(),
            |n| n.to_string_lossy().into_owned(),
        );
        format!("{name}{}", if self.dirty { " *" } else { "" })
    }

    fn snapshot(&self) -> Snapshot {
        Snapshot {
            graph: self.graph.clone(),
            meta: self.meta.clone(),
        }
    }

    /// Applies an edit as one undo step. `key` merges consecutive edits of one continuous gesture
    /// (a slider drag, a node move) into a single step while the gesture lasts (see
    /// [`History::end_gesture`]). The edit runs on a copy of the graph: when it fails, nothing
    /// changes; when it succeeds but leaves the file text unchanged, no step is recorded.
    pub fn edit<R>(
        &mut self,
        key: Option<EditKey>,
        f: impl FnOnce(&mut Graph, &mut GraphMeta) -> Result<R, String>,
    ) -> Result<R, String> {
        let before = self.snapshot();
        let mut graph = self.graph.clone();
        let mut meta = self.meta.clone();
        let result = f(&mut graph, &mut meta)?;
        let changed = file::to_ron(&graph, &meta) != file::to_ron(&before.graph, &before.meta);
        if changed {
            self.history.record(before, key);
            self.graph = graph;
            self.meta = meta;
            self.dirty = true;
            self.version += 1;
        }
        Ok(result)
    }

    /// Replaces the graph wholesale with a snapshot (undo, redo).
    fn restore(&mut self, snapshot: Snapshot) {
        self.graph = snapshot.graph;
        self.meta = snapshot.meta;
        self.dirty = true;
        self.generation += 1;
        self.version += 1;
    }

    /// Undoes the last step; false when there is none.
    pub fn undo(&mut self) -> bool {
        let current = self.snapshot();
        match self.history.undo(current) {
            Some(s) => {
                self.restore(s);
                true
            }
            None => false,
        }
    }

    /// Redoes the last undone step; false when there is none.
    pub fn redo(&mut self) -> bool {
        let current = self.snapshot();
        match self.history.redo(current) {
            Some(s) => {
                self.restore(s);
                true
            }
            None => false,
        }
    }

    /// A node id not used yet, from a type id (`curve.arc` → `arc`, `arc_2`, …).
    pub fn fresh_id(&self, base: &str) -> String {
        fresh_id(&self.graph, base)
    }
}

/// A node id not used in `graph`, derived from `base` (the part after the last `.` of a type id,
/// with invalid characters replaced): `arc`, `arc_2`, `arc_3`, …
pub fn fresh_id(graph: &Graph, base: &str) -> String {
    let stem: String = base
        .rsplit('.')
        .next()
        .unwrap_or(base)
        .chars()
        .map(|c| {
            if c.is_alphanumeric() || c == '_' || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect();
    let stem = if stem.is_empty() {
        "node".to_string()
    } else {
        stem
    };
    // Strip a numeric suffix so that copies of `arc_2` become `arc_3`, not `arc_2_2`.
    let root = match stem.rsplit_once('_') {
        Some((root, n)) if !root.is_empty() && n.parse::<u32>().is_ok() => root.to_string(),
        _ => stem.clone(),
    };
    if graph.node(&root).is_none() {
        return root;
    }
    (2..)
        .map(|k| format!("{root}_{k}"))
        .find(|id| graph.node(id).is_none())
        .unwrap_or(root)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn registry() -> Arc<Registry> {
        Arc::new(cnets_nodes::registry())
    }

    #[test]
    fn fresh_ids_count_up() {
        let mut doc = GraphDocument::new(registry());
        assert_eq!(doc.fresh_id("curve.arc"), "arc");
        doc.edit(None, |g, _| {
            g.add_node("arc", "curve.arc").map_err(|e| e.to_string())
        })
        .unwrap();
        assert_eq!(doc.fresh_id("curve.arc"), "arc_2");
        assert_eq!(doc.fresh_id("arc_2"), "arc_2");
    }

    #[test]
    fn failed_edits_change_nothing_and_record_nothing() {
        let mut doc = GraphDocument::new(registry());
        let before = doc.to_ron();
        let r = doc.edit(None, |g, _| {
            g.add_node("a", "curve.arc").map_err(|e| e.to_string())?;
            g.add_node("a", "curve.arc").map_err(|e| e.to_string())
        });
        assert!(r.is_err());
        assert_eq!(doc.to_ron(), before);
        assert!(!doc.history.can_undo());
        assert!(!doc.is_dirty());
    }

    #[test]
    fn undo_and_redo_restore_exact_text() {
        let mut doc = GraphDocument::new(registry());
        doc.edit(None, |g, _| {
            g.add_node("n", "param.number").map_err(|e| e.to_string())
        })
        .unwrap();
        let one = doc.to_ron();
        doc.edit(None, |g, _| {
            g.set_value("n", "value", cnets_engine::Value::Number(0.25))
                .map_err(|e| e.to_string())
        })
        .unwrap();
        let two = doc.to_ron();
        assert_ne!(one, two);
        let generation = doc.generation();
        assert!(doc.undo());
        assert_eq!(doc.to_ron(), one);
        assert!(doc.generation() > generation);
        assert!(doc.redo());
        assert_eq!(doc.to_ron(), two);
    }
}
