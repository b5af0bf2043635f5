//! The graph document: the engine [`Graph`] with its [`GraphMeta`] and file path — the single source
//! of truth of the editor. Every edit goes through [`GraphDocument::edit`], which records an undo
//! step (see [`crate::history`]) and marks the document dirty.
//!
//! A cluster can be opened in place ([`GraphDocument::enter`]): the document then edits the
//! cluster's subgraph, with the graphs around it kept on a stack of [`Level`]s (the breadcrumbs).
//! Leaving ([`GraphDocument::leave`]) rebuilds the cluster from the edited subgraph and gives the
//! cluster node the new definition, keeping its wires where the ports still exist. While inside,
//! the worker evaluates a *live* copy of the document's own graph in which the cluster is rebuilt
//! after every edit, so the inner nodes show the values the cluster really receives. Edits inside
//! a cluster loaded from a file make it an inline cluster (its file is left unchanged).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use cnets_engine::cluster::{Cluster, ClusterSource};
use cnets_engine::file::{self, GraphMeta, LoadError, LoadOptions};
use cnets_engine::{Graph, Registry, WireRef};

use crate::cluster_ports::Renames;
pub use crate::document_error::DocumentError;
use crate::history::{EditKey, History};

/// A document state, as the undo history keeps it.
#[derive(Clone, Debug)]
pub struct Snapshot {
    /// The graph being edited (the document's, or a cluster's subgraph opened in place).
    pub graph: Graph,
    /// Its metadata.
    pub meta: GraphMeta,
    /// The clusters opened in place, outermost first (empty at the document's own graph): undo
    /// and redo also restore where the designer was.
    pub stack: Vec<Level>,
}

/// A graph around a cluster opened in place: the graph as it was when the cluster was opened.
#[derive(Clone, Debug)]
pub struct Level {
    /// The graph holding the cluster node.
    pub graph: Graph,
    /// Its metadata.
    pub meta: GraphMeta,
    /// The cluster node's id in `graph`.
    pub node: String,
    /// The cluster as it was opened.
    pub cluster: Arc<Cluster>,
}

impl Level {
    /// The breadcrumb of the opened cluster: its node id and its label (`bay (bay.ron)`).
    pub fn crumb(&self) -> String {
        format!("{} ({})", self.node, self.cluster.label())
    }
}

/// What leaving a cluster (or rebuilding it for evaluation) did to the graph around it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Rebuilt {
    /// Whether the subgraph changed (the cluster node got a new definition).
    pub changed: bool,
    /// Wires of the cluster node dropped because their port no longer exists (or no longer
    /// takes the type).
    pub dropped: Vec<WireRef>,
    /// The cluster came from a file and is now inline (set when its subgraph changed).
    pub made_inline: Option<String>,
}

impl Rebuilt {
    /// A status-bar summary, empty when nothing needs saying.
    pub fn message(&self) -> String {
        let mut parts = Vec::new();
        if let Some(file) = &self.made_inline {
            parts.push(format!(
                "the cluster from '{file}' was edited: it is now inline (the file is unchanged)"
            ));
        }
        if !self.dropped.is_empty() {
            let wires: Vec<String> = self.dropped.iter().map(ToString::to_string).collect();
            parts.push(format!(
                "dropped wires whose ports are gone: {}",
                wires.join(", ")
            ));
        }
        parts.join("; ")
    }
}

/// Whether an edit changed `after` from `before` in anything the graph file stores: its revision
/// (values, wires, nodes, flags — the engine bumps it only for real changes), or a node's canvas
/// position or preview flag (not evaluation edits: they keep the revision). Constant in the text
/// size: a drag of a slider in a graph of thousands of nodes does not write the graph out twice a
/// frame.
pub fn differs(after: &Graph, before: &Graph) -> bool {
    if after.revision() != before.revision() || after.node_count() != before.node_count() {
        return true;
    }
    after.nodes().any(|(_, n)| {
        before.node(&n.id).is_none_or(|b| {
            b.position != n.position
                || b.preview != n.preview
                || b.color != n.color
                || b.name != n.name
        })
    })
}

/// Rebuilds the cluster of `level` from an edited subgraph: the graph around it with the cluster
/// node's new definition (the level's own graph when the subgraph is unchanged).
pub fn rebuild(
    level: &Level,
    graph: &Graph,
    meta: &GraphMeta,
) -> Result<(Graph, Rebuilt), DocumentError> {
    let template = &level.cluster.template;
    let same_text = file::to_ron(graph, meta) == file::to_ron(template, &level.cluster.meta);
    // The same node definitions too (a cluster inside may have been reloaded from its file).
    let same_defs = graph.nodes().all(|(_, n)| {
        template
            .node(&n.id)
            .is_some_and(|t| Arc::ptr_eq(&t.def, &n.def))
    });
    if same_text && same_defs {
        return Ok((level.graph.clone(), Rebuilt::default()));
    }
    let (source, made_inline) = match &level.cluster.source {
        // Unchanged text: a file cluster stays a reference to its file.
        source if same_text => (source.clone(), None),
        ClusterSource::File { written, .. } => (ClusterSource::Inline, Some(written.clone())),
        ClusterSource::Inline => (ClusterSource::Inline, None),
    };
    let cluster = Cluster::new(
        source,
        graph.clone(),
        meta.clone(),
        level.cluster.base_dir.clone(),
    )
    .map_err(|reason| DocumentError::Cluster {
        node: level.node.clone(),
        reason,
    })?;
    let mut parent = level.graph.clone();
    let dropped = parent.replace_def(&level.node, Arc::new(cluster.node_def()))?;
    // Renamed ports keep their wires and values.
    let dropped =
        Renames::between(template, graph).carry(&mut parent, &level.node, &level.graph, dropped);
    Ok((
        parent,
        Rebuilt {
            changed: true,
            dropped,
            made_inline,
        },
    ))
}

/// A graph being edited.
pub struct GraphDocument {
    /// The graph (nodes, literal values, wires, canvas positions, preview and enable flags).
    pub graph: Graph,
    /// Name and description written into the file.
    pub meta: GraphMeta,
    /// Where the document was loaded from or last saved to; `None` for a new document (and for
    /// an untitled copy of an example: saving it asks where).
    pub path: Option<PathBuf>,
    /// The shipped example an untitled copy was opened from (File › Open example, the start-up
    /// graph): file paths in the graph resolve next to it, but a save never writes there.
    pub origin: Option<PathBuf>,
    /// The name an unsaved document is shown by when it is not an example's copy: the file's
    /// name for a file opened in the browser, "shared design" for a share link.
    pub name: Option<String>,
    /// Files and folders the document's nodes may read besides its own folder (a file picked with
    /// Browse…, a folder allowed at a prompt): the editor's per-document settings
    /// ([`crate::settings::Settings::allowed_reads`]), never written into the graph file.
    pub allowed_reads: Vec<PathBuf>,
    /// Undo / redo.
    pub history: History<Snapshot>,
    /// Clusters opened in place, outermost first; `graph` is the innermost one's subgraph.
    stack: Vec<Level>,
    /// While inside a cluster: the document's own graph with the opened clusters rebuilt from the
    /// subgraphs being edited (what the worker evaluates).
    live: Option<Graph>,
    /// Why the live graph could not be rebuilt after the last edit (e.g. an invalid port name).
    pub live_error: Option<String>,
    /// Changes since the last save.
    dirty: bool,
    /// Bumped when the graph was replaced wholesale (open, new, leaving a cluster, an undo across
    /// cluster levels): revisions of the new graph are not comparable with the evaluator's
    /// memos, so the new graph first takes over from the last evaluated one
    /// ([`GraphDocument::take_over`]).
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
            origin: None,
            name: None,
            allowed_reads: Vec::new(),
            history: History::default(),
            stack: Vec::new(),
            live: None,
            live_error: None,
            dirty: false,
            generation: 0,
            version: 0,
        }
    }

    /// Loads a graph file. The error has every problem, each with its place in the file.
    pub fn open(path: &Path, registry: &Arc<Registry>) -> Result<Self, LoadError> {
        Self::open_with(path, registry, &LoadOptions::for_file(path))
    }

    /// Loads a graph file with explicit options (library folders for cluster sources).
    pub fn open_with(
        path: &Path,
        registry: &Arc<Registry>,
        options: &LoadOptions,
    ) -> Result<Self, LoadError> {
        let doc = file::load_file_with(path, registry, options)?;
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
    ) -> Result<Self, LoadError> {
        Self::from_text_with(text, name, path, registry, &LoadOptions::default())
    }

    /// Like [`GraphDocument::from_text`], with explicit options (where cluster sources resolve).
    pub fn from_text_with(
        text: &str,
        name: &str,
        path: Option<PathBuf>,
        registry: &Arc<Registry>,
        options: &LoadOptions,
    ) -> Result<Self, LoadError> {
        let doc = file::load_str_with(text, name, registry, options)?;
        Ok(Self::from_parts(doc.graph, doc.meta, path))
    }

    /// Turns the document into an untitled copy of the file it was loaded from (a shipped
    /// example): the file is remembered as [`GraphDocument::origin`], the first save asks where.
    pub fn into_untitled_copy(mut self) -> Self {
        if let Some(p) = self.path.take() {
            self.origin = Some(p);
        }
        self
    }

    /// The file relative paths of the graph resolve against: the document's own path, else the
    /// example it is a copy of.
    pub fn resolve_file(&self) -> Option<&Path> {
        self.path.as_deref().or(self.origin.as_deref())
    }

    /// The folder relative paths of the graph resolve in (see [`GraphDocument::resolve_file`]).
    pub fn base_dir(&self) -> Option<PathBuf> {
        self.resolve_file()
            .and_then(Path::parent)
            .map(Path::to_path_buf)
    }

    /// Saves atomically to `path` (and remembers it as the document's path). Inside a cluster,
    /// the document's own graph is saved with the cluster rebuilt from its edited subgraph.
    pub fn save_as(&mut self, path: &Path) -> Result<(), DocumentError> {
        let (graph, meta, _) = self.compose()?;
        file::save_file(path, &graph, &meta).map_err(|error| DocumentError::Save {
            path: path.to_path_buf(),
            error,
        })?;
        self.path = Some(path.to_path_buf());
        self.dirty = false;
        Ok(())
    }

    /// The canonical file text of the document (inside a cluster: the document's own graph with
    /// the cluster rebuilt from the edited subgraph, as a save would write it; when the subgraph
    /// cannot be rebuilt, the graph as it was when the cluster was opened).
    pub fn to_ron(&self) -> String {
        let (graph, meta) = self.text_parts();
        file::to_ron(&graph, &meta)
    }

    /// The graph and settings [`GraphDocument::to_ron`] writes (cheap: the values are shared,
    /// so the text can be written elsewhere, e.g. on autosave's thread).
    pub fn text_parts(&self) -> (Graph, GraphMeta) {
        match self.compose() {
            Ok((graph, meta, _)) => (graph, meta),
            Err(_) => {
                let root = &self.stack[0];
                (root.graph.clone(), root.meta.clone())
            }
        }
    }

    /// The document's own graph with every opened cluster rebuilt from its edited subgraph.
    pub fn compose(&self) -> Result<(Graph, GraphMeta, Rebuilt), DocumentError> {
        let (mut graph, mut meta) = (self.graph.clone(), self.meta.clone());
        let mut last = Rebuilt::default();
        for level in self.stack.iter().rev() {
            let (parent, rebuilt) = rebuild(level, &graph, &meta)?;
            graph = parent;
            meta = level.meta.clone();
            last = rebuilt;
        }
        Ok((graph, meta, last))
    }

    /// How deep in opened clusters the document is (0: its own graph).
    pub fn depth(&self) -> usize {
        self.stack.len()
    }

    /// The opened clusters, outermost first.
    pub fn levels(&self) -> &[Level] {
        &self.stack
    }

    /// The ids of the opened cluster nodes, outermost first (the path the worker descends).
    pub fn view_path(&self) -> Vec<String> {
        self.stack.iter().map(|l| l.node.clone()).collect()
    }

    /// The breadcrumbs: the document's name, then each opened cluster.
    pub fn breadcrumbs(&self) -> Vec<String> {
        let root = self
            .path
            .as_deref()
            .and_then(Path::file_stem)
            .map_or_else(|| "main".to_string(), |s| s.to_string_lossy().into_owned());
        std::iter::once(root)
            .chain(self.stack.iter().map(Level::crumb))
            .collect()
    }

    /// The graph the worker evaluates: the document's own graph (inside a cluster, the live copy
    /// with the opened clusters rebuilt from their edited subgraphs).
    pub fn eval_graph(&self) -> Graph {
        match &self.live {
            Some(g) if !self.stack.is_empty() => g.clone(),
            _ => self.graph.clone(),
        }
    }

    /// Makes the graph the worker evaluates ([`GraphDocument::eval_graph`]) the successor of
    /// `previous`, the graph it evaluated last — of another document, or of this one before its
    /// graph was replaced wholesale ([`GraphDocument::generation`] changed): the nodes it shares
    /// with `previous` keep their stamps ([`Graph::take_over`]), so the worker carries its
    /// evaluator over and re-runs only what differs.
    pub fn take_over(&mut self, previous: &Graph) -> Vec<cnets_engine::Continued> {
        match &mut self.live {
            Some(live) if !self.stack.is_empty() => live.take_over(previous),
            _ => self.graph.take_over(previous),
        }
    }

    /// Opens the cluster node `id` of the graph being edited: from now on edits apply to its
    /// subgraph. Not an undo step (undo restores where each step was made).
    pub fn enter(&mut self, id: &str) -> Result<(), DocumentError> {
        let node = self
            .graph
            .node(id)
            .ok_or_else(|| DocumentError::NoNode(id.to_string()))?;
        let cluster =
            Cluster::shared(&node.def).ok_or_else(|| DocumentError::NotACluster(id.to_string()))?;
        if self.stack.is_empty() {
            // The live copy starts as the document's graph itself: same revisions, so the worker's
            // results stay valid.
            self.live = Some(self.graph.clone());
        }
        self.stack.push(Level {
            graph: std::mem::replace(&mut self.graph, cluster.template.clone()),
            meta: std::mem::replace(&mut self.meta, cluster.meta.clone()),
            node: id.to_string(),
            cluster,
        });
        self.live_error = None;
        self.version += 1;
        Ok(())
    }

    /// Closes the innermost opened cluster: rebuilds it from the edited subgraph and gives the
    /// cluster node its new definition (one undo step when anything changed). Refused (staying
    /// inside) when the subgraph's interface is invalid.
    pub fn leave(&mut self) -> Result<Rebuilt, DocumentError> {
        let Some(level) = self.stack.last() else {
            return Err(DocumentError::NotInACluster);
        };
        let (parent, rebuilt) = rebuild(level, &self.graph, &self.meta)?;
        let level = self.stack.pop().unwrap_or_else(|| unreachable!());
        if rebuilt.changed {
            let before = Snapshot {
                graph: std::mem::replace(&mut self.graph, parent),
                meta: std::mem::replace(&mut self.meta, level.meta.clone()),
                stack: {
                    let mut s = self.stack.clone();
                    s.push(level);
                    s
                },
            };
            self.history.record(before, None);
            self.dirty = true;
        } else {
            self.graph = parent;
            self.meta = level.meta;
        }
        if self.stack.is_empty() {
            self.live = None;
        } else {
            self.refresh_live();
        }
        self.live_error = None;
        // The rebuilt graph's revisions are not comparable with the live copy the worker saw.
        self.generation += 1;
        self.version += 1;
        Ok(rebuilt)
    }

    /// Rebuilds the live graph after an edit inside a cluster. The live graph keeps increasing
    /// revisions (the worker evaluates it incrementally); wires of the cluster node that were
    /// dropped by an earlier rebuild come back when their ports exist again.
    fn refresh_live(&mut self) {
        if self.stack.is_empty() {
            self.live = None;
            return;
        }
        let (mut graph, mut meta) = (self.graph.clone(), self.meta.clone());
        for level in self.stack[1..].iter().rev() {
            match rebuild(level, &graph, &meta) {
                Ok((parent, _)) => {
                    graph = parent;
                    meta = level.meta.clone();
                }
                Err(e) => {
                    self.live_error = Some(e.to_string());
                    return;
                }
            }
        }
        let root = &self.stack[0];
        let def = match rebuild(root, &graph, &meta) {
            Ok((g, _)) => g.node(&root.node).map(|n| n.def.clone()),
            Err(e) => {
                self.live_error = Some(e.to_string());
                return;
            }
        };
        let Some(def) = def else { return };
        let renames = Renames::between(&root.cluster.template, &graph);
        let live = self.live.get_or_insert_with(|| root.graph.clone());
        if live.replace_def(&root.node, def).is_err() {
            *live = root.graph.clone();
        }
        let present = live.wires();
        for w in root.graph.wires() {
            if w.from != root.node && w.to != root.node {
                continue;
            }
            // A renamed port keeps its wires (and, below, its value).
            let w = renames.rename(&root.node, &w).unwrap_or(w);
            if !present.contains(&w) {
                let _ = live.connect(&w.from, &w.output, &w.to, &w.input);
            }
        }
        if let Some(old) = root.graph.node(&root.node) {
            for (from, to) in &renames.inputs {
                if let Some(v) = old.value_of(from)
                    && live.node(&root.node).and_then(|n| n.value_of(to)) != Some(v)
                {
                    let _ = live.set_value(&root.node, to, v.clone());
                }
            }
        }
        self.live_error = None;
    }

    /// Changes the graph being edited without an undo step (e.g. a cluster file reloaded from
    /// disk: the file text does not change).
    pub fn update_quietly<R>(
        &mut self,
        f: impl FnOnce(&mut Graph) -> Result<R, String>,
    ) -> Result<R, String> {
        let mut graph = self.graph.clone();
        let r = f(&mut graph)?;
        self.graph = graph;
        self.version += 1;
        if !self.stack.is_empty() {
            self.refresh_live();
        }
        Ok(r)
    }

    /// Whether there are unsaved changes.
    pub fn is_dirty(&self) -> bool {
        self.dirty
    }

    /// Marks the document as saved where it has no path (the web page's download of its text).
    pub fn mark_saved(&mut self) {
        self.dirty = false;
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
    /// worker carries its evaluator over to it ([`GraphDocument::take_over`]).
    pub fn start_after(&mut self, previous: u64) {
        self.generation = previous + 1;
    }

    /// Changes whenever anything in the document changed.
    pub fn version(&self) -> u64 {
        self.version
    }

    /// The title shown in the window: file name (else the document's [`GraphDocument::name`],
    /// else "untitled", naming the example an untitled copy came from) and a `*` when dirty.
    pub fn title(&self) -> String {
        let file_name = |p: &Path| {
            p.file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default()
        };
        let name = match (&self.path, &self.origin) {
            (Some(p), _) => file_name(p),
            (None, _) if self.name.is_some() => self.name.clone().unwrap_or_default(),
            (None, Some(o)) => format!("untitled (copy of example {})", file_name(o)),
            (None, None) => "untitled".to_string(),
        };
        format!("{name}{}", if self.dirty { " *" } else { "" })
    }

    fn snapshot(&self) -> Snapshot {
        Snapshot {
            graph: self.graph.clone(),
            meta: self.meta.clone(),
            stack: self.stack.clone(),
        }
    }

    /// Applies an edit as one undo step. `key` merges consecutive edits of one continuous gesture
    /// (a slider drag, a node move) into a single step while the gesture lasts (see
    /// [`History::end_gesture`]). The edit runs on a copy of the graph: when it fails, nothing
    /// changes; when it succeeds but leaves the file text unchanged, no step is recorded.
    pub fn edit<R, E>(
        &mut self,
        key: Option<EditKey>,
        f: impl FnOnce(&mut Graph, &mut GraphMeta) -> Result<R, E>,
    ) -> Result<R, E> {
        let before = self.snapshot();
        let mut graph = self.graph.clone();
        let mut meta = self.meta.clone();
        let result = f(&mut graph, &mut meta)?;
        let changed = differs(&graph, &before.graph) || meta != before.meta;
        if changed {
            self.history.record(before, key);
            self.graph = graph;
            self.meta = meta;
            self.dirty = true;
            self.version += 1;
            if !self.stack.is_empty() {
                self.refresh_live();
            }
        }
        Ok(result)
    }

    /// Restores a snapshot (undo, redo). At the document's own graph the snapshot becomes the
    /// successor of the current graph ([`Graph::succeed`]): a new revision, with only the nodes
    /// that differ stamped as edited, so the worker keeps its evaluator and re-runs only their
    /// downstream cone. Across opened clusters (the levels differ) a new generation starts a
    /// fresh evaluator.
    fn restore(&mut self, snapshot: Snapshot) {
        let same_level = self.stack.is_empty() && snapshot.stack.is_empty();
        let mut graph = snapshot.graph;
        if same_level {
            graph.succeed(&self.graph);
        } else {
            self.generation += 1;
        }
        self.graph = graph;
        self.meta = snapshot.meta;
        self.stack = snapshot.stack;
        self.live = None;
        self.refresh_live();
        self.dirty = true;
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
    fn the_title_names_the_file_then_the_given_name_then_the_example() {
        let mut doc = GraphDocument::new(registry());
        assert_eq!(doc.title(), "untitled");
        doc.origin = Some(PathBuf::from("graphs/facade.ron"));
        assert_eq!(doc.title(), "untitled (copy of example facade.ron)");
        doc.name = Some("shared design".into());
        assert_eq!(doc.title(), "shared design");
        doc.path = Some(PathBuf::from("/work/mine.ron"));
        assert_eq!(doc.title(), "mine.ron");
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
    fn an_edit_is_a_change_exactly_when_the_file_text_changes() {
        let mut doc = GraphDocument::new(registry());
        doc.edit(None, |g, _| {
            g.add_node("n", "param.number").map_err(|e| e.to_string())?;
            g.set_value("n", "value", cnets_engine::Value::Number(0.25))
                .map_err(|e| e.to_string())
        })
        .unwrap();
        let (steps, version, text) = (doc.history.undo_len(), doc.version(), doc.to_ron());
        // The same value again, the same position, the same flag: no step, no new version.
        doc.edit(None, |g, _| {
            g.set_value("n", "value", cnets_engine::Value::Number(0.25))
                .map_err(|e| e.to_string())?;
            let at = g.node("n").unwrap().position;
            g.set_position("n", at).map_err(|e| e.to_string())?;
            g.set_preview("n", true).map_err(|e| e.to_string())
        })
        .unwrap();
        assert_eq!((doc.history.undo_len(), doc.version()), (steps, version));
        assert_eq!(doc.to_ron(), text);
        // A move and a preview toggle change the text (not the evaluation): each a step.
        for edit in [
            |g: &mut Graph| g.set_position("n", [40.0, 50.0]),
            |g: &mut Graph| g.set_preview("n", false),
        ] {
            let before = doc.to_ron();
            doc.edit(None, |g, _| edit(g).map_err(|e| e.to_string()))
                .unwrap();
            assert_ne!(doc.to_ron(), before);
        }
        assert_eq!(doc.history.undo_len(), steps + 2);
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
        assert_eq!(doc.generation(), generation, "the evaluator is kept");
        assert!(doc.redo());
        assert_eq!(doc.to_ron(), two);
    }

    #[test]
    fn undoing_a_slider_change_reruns_only_its_downstream_cone() {
        use cnets_engine::{Evaluator, NodeContext, Value};
        let text = r#"(
    version: 1,
    nodes: {
        "n": (type: "param.number", inputs: {"value": 3.0, "min": 0.0, "max": 10.0}),
        "m": (type: "math.multiply", inputs: {"b": 2.0}),
        "after": (type: "math.add", inputs: {"b": 1.0}),
        "side": (type: "param.number", inputs: {"value": 5.0, "min": 0.0, "max": 10.0}),
        "other": (type: "math.add", inputs: {"b": 1.0}),
    },
    edges: ["n.value -> m.a", "m.result -> after.a", "side.value -> other.a"],
)"#;
        let mut doc = GraphDocument::from_text(text, "t.ron", None, &registry()).unwrap();
        let mut ev = Evaluator::new();
        let ctx = NodeContext::default();
        ev.evaluate_all(&doc.graph, &ctx);
        let generation = doc.generation();
        doc.edit(Some(EditKey::Value("n".into(), "value".into())), |g, _| {
            g.set_value("n", "value", Value::Number(4.0))
                .map(|_| ())
                .map_err(|e| e.to_string())
        })
        .unwrap();
        doc.history.end_gesture();
        ev.evaluate_all(&doc.graph, &ctx);
        let runs = |ev: &Evaluator, doc: &GraphDocument| -> Vec<u64> {
            ["n", "m", "after", "side", "other"]
                .iter()
                .map(|id| ev.runs(&doc.graph, id))
                .collect()
        };
        assert_eq!(runs(&ev, &doc), vec![2, 2, 2, 1, 1], "the edit's cone ran");
        assert!(doc.undo());
        assert_eq!(doc.generation(), generation, "same evaluator");
        let s = ev.evaluate_all(&doc.graph, &ctx);
        assert_eq!(s.ran, 3, "n, m and after re-run; side and other do not");
        assert_eq!(runs(&ev, &doc), vec![3, 3, 3, 1, 1]);
        assert_eq!(
            ev.output(&doc.graph, "after", "result"),
            Some(&Value::Number(7.0)),
            "the undone value's result: 3 × 2 + 1"
        );
        assert!(doc.redo());
        assert_eq!(ev.evaluate_all(&doc.graph, &ctx).ran, 3);
        assert_eq!(
            ev.output(&doc.graph, "after", "result"),
            Some(&Value::Number(9.0))
        );
    }

    const SUB: &str = r#"(
    version: 1,
    nodes: {
        "x": (type: "graph.input", inputs: {"name": "x", "type": "number", "default": 1.0}),
        "m": (type: "math.multiply", inputs: {"b": 2.0}),
        "y": (type: "graph.output", inputs: {"name": "y", "type": "number"}),
    },
    edges: ["x.value -> m.a", "m.result -> y.value"],
)"#;

    const MAIN: &str = r#"(
    version: 1,
    nodes: {
        "n": (type: "param.number", inputs: {"value": 3.0, "min": 0.0, "max": 10.0}),
        "c": (type: "cluster", source: "sub.ron"),
        "after": (type: "math.add"),
    },
    edges: ["n.value -> c.x", "c.y -> after.a"],
)"#;

    fn file_doc(name: &str) -> (GraphDocument, PathBuf) {
        let dir = std::env::temp_dir().join(format!("cnets-doc-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("sub.ron"), SUB).unwrap();
        std::fs::write(dir.join("main.ron"), MAIN).unwrap();
        let doc = GraphDocument::open(&dir.join("main.ron"), &registry()).unwrap();
        (doc, dir)
    }

    #[test]
    fn editing_a_file_cluster_in_place_makes_it_inline_and_leaves_the_file_alone() {
        let (mut doc, dir) = file_doc("inline");
        let before = doc.to_ron();
        doc.enter("c").unwrap();
        assert_eq!(doc.depth(), 1);
        assert_eq!(doc.to_ron(), before, "entering changes nothing");
        let r = doc.leave().unwrap();
        assert!(!r.changed, "leaving without edits keeps the file cluster");
        assert_eq!(doc.to_ron(), before);
        doc.enter("c").unwrap();
        doc.edit(None, |g, _| {
            g.set_value("m", "b", cnets_engine::Value::Number(5.0))
                .map(|_| ())
                .map_err(|e| e.to_string())
        })
        .unwrap();
        let live = doc.eval_graph();
        let inner = Cluster::of(&live.node("c").unwrap().def).unwrap();
        assert!(
            file::to_ron(&inner.template, &inner.meta).contains("5.0"),
            "the live graph follows the edit"
        );
        let r = doc.leave().unwrap();
        assert!(r.changed);
        assert_eq!(r.made_inline.as_deref(), Some("sub.ron"));
        assert!(r.message().contains("now inline"), "{}", r.message());
        let text = doc.to_ron();
        assert!(
            text.contains("graph: (") && !text.contains("source:"),
            "{text}"
        );
        assert_eq!(std::fs::read_to_string(dir.join("sub.ron")).unwrap(), SUB);
        assert!(
            doc.graph.wires().iter().any(|w| w.from == "c"),
            "wires kept"
        );
        assert!(doc.undo(), "leaving was one step");
        assert_eq!(doc.depth(), 1, "undo goes back inside");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn an_invalid_interface_keeps_the_designer_inside() {
        let (mut doc, dir) = file_doc("invalid");
        doc.enter("c").unwrap();
        doc.edit(None, |g, _| {
            g.set_value("y", "name", cnets_engine::Value::text("not valid"))
                .map(|_| ())
                .map_err(|e| e.to_string())
        })
        .unwrap();
        assert!(doc.live_error.is_some(), "the live graph says why");
        let e = doc.leave().unwrap_err();
        assert!(matches!(e, DocumentError::Cluster { .. }), "{e}");
        assert!(e.to_string().contains("port name"), "{e}");
        assert_eq!(doc.depth(), 1);
        assert!(
            doc.save_as(&dir.join("out.ron")).is_err(),
            "nothing half-built is saved"
        );
        // A renamed output keeps its outer wire (ports are followed by their node, see
        // `cluster_ports`): nothing is dropped.
        doc.edit(None, |g, _| {
            g.set_value("y", "name", cnets_engine::Value::text("z"))
                .map(|_| ())
                .map_err(|e| e.to_string())
        })
        .unwrap();
        assert!(doc.live_error.is_none());
        let r = doc.leave().unwrap();
        assert!(r.dropped.is_empty(), "{}", r.message());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
