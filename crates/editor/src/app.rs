//! The editor: state and one frame of UI, the same in the window (`main.rs`) and in tests.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use web_time::{Duration, Instant};

use cnets_engine::cluster::Cluster;
use cnets_engine::optimize::Variable;
use cnets_engine::{Graph, Registry};
use egui::{Key, KeyboardShortcut, Modifiers, Ui};

use crate::canvas::{Canvas, CanvasAction};
use crate::clipboard::Clipboard;
use crate::document::GraphDocument;
use crate::edit::{self, Edit};
use crate::export;
use crate::file_dialog::{FileDialog, Outcome, Purpose};
use crate::library::{ClusterWatch, Library};
use crate::list_editor::ListEditors;
use crate::load_failure::LoadFailure;
use crate::menus::{self, MenuAction, MenuContext};
use crate::optimization::OptimizationPanel;
use crate::palette::{self, PaletteState, Pick};
use crate::recovery::{Autosave, Recovered, Recovery};
use crate::request::UiRequest;
use crate::settings::Settings;
use crate::unsaved::{self, Answer, Replace};
use crate::viewport::{Viewport, ViewportAction, ViewportInput};
use crate::worker::{Carry, NodeStatus, Worker};
use cnets_host::LibraryEntry;

pub use crate::viewport::GpuTarget;

/// The graph the editor starts on when no file is given and `graphs/torus-monge.ron` is absent.
pub const DEFAULT_GRAPH: &str = include_str!("../../../graphs/editor-default.ron");

/// How the editor starts.
pub struct AppOptions {
    /// GPU formats of the window (`None`: no 3D view).
    pub gpu: Option<GpuTarget>,
    /// Settings folder (recent files, recovery file).
    pub config_dir: PathBuf,
    /// A graph file to open instead of the default.
    pub file: Option<PathBuf>,
    /// The examples folder (`graphs/`).
    pub examples_dir: PathBuf,
    /// Called by the worker when a result is ready (request a repaint).
    pub wake: Arc<dyn Fn() + Send + Sync>,
}

/// Change-to-picture latency figures: from a graph edit to the frame that hands the resulting
/// scene to the GPU.
#[derive(Clone, Debug, Default)]
pub struct Latency {
    /// The last measurement, in milliseconds.
    pub last_ms: f64,
    /// All measurements (capped at 10 000).
    pub samples: Vec<f64>,
    /// The last evaluation time (nodes only), in milliseconds.
    pub eval_ms: f64,
    /// The last scene build time, in milliseconds.
    pub scene_ms: f64,
    /// Nodes that ran in the last evaluation (the evaluation counter: an edit re-runs its
    /// downstream cone, a reopened file nothing).
    pub ran: usize,
}

/// The status bar's hint when a document's nodes overlap (shown while they do).
pub const OVERLAP_HINT: &str = "nodes overlap: View › Arrange graph (Ctrl+L) lays them out";

/// The editor.
pub struct EditorApp {
    /// Node types.
    pub registry: Arc<Registry>,
    /// The document being edited.
    pub doc: GraphDocument,
    /// The node canvas.
    pub canvas: Canvas,
    /// The 3D viewport.
    pub viewport: Viewport,
    /// The node palette.
    pub palette: PaletteState,
    /// Status of every node after the last finished evaluation.
    pub statuses: HashMap<String, NodeStatus>,
    /// The opened clusters `statuses` belong to.
    statuses_view: Vec<String>,
    /// The message in the status bar (e.g. why a wire was refused).
    pub message: String,
    /// Recent files.
    pub settings: Settings,
    /// Latency figures.
    pub latency: Latency,
    /// Whether the window should close (set by File › Quit and after the unsaved-changes
    /// question; the window closes when it sees it).
    pub quit: bool,
    /// The unsaved-changes question being asked: what replaces or closes the document once the
    /// designer answers (see [`crate::unsaved`]).
    pub unsaved_question: Option<Replace>,
    /// Carried out once the Save As dialog opened by the question's "Save" has saved.
    after_save: Option<Replace>,
    /// The designer answered the question: closing is allowed now.
    close_confirmed: bool,
    /// A graph file that failed to load, shown with its diagnostics.
    pub load_failure: Option<LoadFailure>,
    /// Graph files sent by `cnets-editor FILE` started while this window is open.
    inbox: Option<std::sync::mpsc::Receiver<PathBuf>>,
    last_title: String,
    /// Check once the new document's nodes are measured whether they overlap (hint: Arrange).
    check_overlaps: bool,
    /// The status bar shows [`OVERLAP_HINT`]: the document opened with overlapping nodes and they
    /// still overlap.
    pub overlap_hint: bool,
    /// Show timings and the busy spinner in the status bar (snapshot tests turn them off: they
    /// vary from run to run).
    pub show_timings: bool,
    worker: Worker,
    submitted: Option<(u64, u64, crate::preview::PreviewOptions)>,
    /// The last graph sent to the worker, its generation and folder: a graph of a new
    /// generation takes over from it (the evaluator is kept).
    last_evaluated: Option<(u64, Graph, Option<PathBuf>)>,
    pending_change: Option<Instant>,
    awaiting_picture: Option<(u64, Instant)>,
    recovery: Recovery,
    offer_restore: Option<Recovered>,
    dialog: Option<FileDialog>,
    clipboard: Clipboard,
    gpu: Option<GpuTarget>,
    examples: Vec<PathBuf>,
    examples_dir: PathBuf,
    /// The user library (and the examples folder), listed in the palette.
    pub library: Library,
    /// Cluster files of the graph being edited, checked about once a second.
    import_watch: crate::import_watch::ImportWatch,
    watch: ClusterWatch,
    last_watch: Instant,
    /// The optimization panel.
    pub optimization: OptimizationPanel,
    /// Whether the parameter panel (View › Parameters) is shown.
    pub parameters_open: bool,
    /// The failed nodes' errors the 3D view listed in the last frame (`id: message`): those off
    /// the canvas's view (crate::view_errors).
    pub view_errors_shown: Vec<String>,
    /// Where the parameter panel was drawn in the last frame (`None`: not shown), in points.
    pub parameters_rect: Option<egui::Rect>,
    /// Where the parameter panel drew each value editor in the last frame: (node id, rectangle).
    pub parameter_editors: Vec<(String, egui::Rect)>,
    /// The open table windows of literal lists (a node's **Edit…**).
    pub list_editors: ListEditors,
    /// The pointer's last position seen by [`EditorApp::raw_input`].
    pointer: Option<egui::Pos2>,
    /// The opened clusters the canvas was showing in the last frame.
    canvas_view: Vec<String>,
    /// Counts the canvases made for graph levels (each gets its own view state).
    canvas_serial: u64,
    palette_was_open: bool,
    /// Frame the canvas again once the first results of a new document are drawn (nodes grow
    /// when their outputs get summaries).
    refit_on_results: bool,
    /// In a web page: the requests for the page (see [`crate::page`]); `None` on the desktop.
    pub page: Option<crate::page::Page>,
}

/// How often cluster files are checked for changes.
pub const WATCH_INTERVAL: Duration = Duration::from_secs(1);

impl EditorApp {
    /// The editor on the given file, the gallery's `torus-monge.ron`, or the built-in default.
    pub fn new(options: AppOptions) -> Self {
        let registry = Arc::new(cnets_nodes::registry());
        let settings = Settings::load(&options.config_dir);
        let recovery = Recovery::new(&options.config_dir);
        let offer_restore = recovery.find();
        let message = String::new();
        let library_dirs = vec![settings.library_dir(), options.examples_dir.clone()];
        let torus = options.examples_dir.join("torus-monge.ron");
        let mut load_failure = None;
        // The start-up graph: the file given (an untitled copy when it is a shipped example), else
        // an untitled copy of the gallery's torus-monge.ron, else the built-in default.
        let (start, copy) = match &options.file {
            Some(f) => (Some(f.as_path()), is_example(&options.examples_dir, f)),
            None => (torus.is_file().then_some(torus.as_path()), true),
        };
        let doc = match start {
            Some(path) => match GraphDocument::open_with(
                path,
                &registry,
                &cnets_host::document_options(Some(path), &library_dirs),
            ) {
                Ok(d) if copy => Some(d.into_untitled_copy()),
                Ok(d) => Some(d),
                Err(e) => {
                    // Not the default graph in its place: that would look like the file.
                    load_failure = Some(LoadFailure::new(path, &e));
                    Some(GraphDocument::new(registry.clone()))
                }
            },
            None => None,
        };
        let doc = doc.unwrap_or_else(|| {
            GraphDocument::from_text(DEFAULT_GRAPH, "editor-default.ron", None, &registry)
                .unwrap_or_else(|_| GraphDocument::new(registry.clone()))
        });
        let mut app = Self {
            registry,
            doc,
            canvas: Canvas::new(),
            viewport: Viewport::default(),
            palette: PaletteState::default(),
            statuses: HashMap::new(),
            statuses_view: Vec::new(),
            message,
            settings,
            latency: Latency::default(),
            quit: false,
            unsaved_question: None,
            after_save: None,
            close_confirmed: false,
            load_failure,
            inbox: None,
            last_title: String::new(),
            check_overlaps: true,
            overlap_hint: false,
            show_timings: true,
            worker: Worker::spawn(options.wake.clone()),
            submitted: None,
            last_evaluated: None,
            pending_change: Some(Instant::now()),
            awaiting_picture: None,
            recovery,
            offer_restore,
            dialog: None,
            clipboard: Clipboard::default(),
            gpu: options.gpu,
            examples: menus::examples_in(&options.examples_dir),
            examples_dir: options.examples_dir,
            library: Library::new(library_dirs),
            import_watch: crate::import_watch::ImportWatch::default(),
            watch: ClusterWatch::default(),
            last_watch: Instant::now(),
            optimization: OptimizationPanel::new(options.wake),
            parameters_open: false,
            parameters_rect: None,
            parameter_editors: Vec::new(),
            view_errors_shown: Vec::new(),
            list_editors: ListEditors::default(),
            pointer: None,
            canvas_view: Vec::new(),
            canvas_serial: 0,
            palette_was_open: false,
            refit_on_results: true,
            page: None,
        };
        if let Some(limit) = app.settings.planarity_limit() {
            app.viewport.options.set_planarity_limit(limit);
        }
        app.watch.changed(&app.doc.graph);
        app.submit_if_changed();
        app
    }

    /// The GPU target of the 3D view (`None`: no wgpu renderer).
    pub fn gpu(&self) -> Option<&GpuTarget> {
        self.gpu.as_ref()
    }

    /// Before a frame, on the raw input (the window calls it from eframe's `raw_input_hook`,
    /// tests directly): over the canvas, the mouse wheel zooms — as in Grasshopper and as in
    /// the 3D view — instead of scrolling (Shift+wheel still pans; dragging the background
    /// pans too).
    pub fn raw_input(&mut self, raw: &mut egui::RawInput) {
        let canvas = self.canvas.screen_rect();
        for e in &mut raw.events {
            match e {
                egui::Event::PointerMoved(p) => self.pointer = Some(*p),
                egui::Event::PointerGone => self.pointer = None,
                egui::Event::MouseWheel {
                    unit,
                    delta,
                    modifiers,
                    ..
                } if modifiers.is_none() && self.pointer.is_some_and(|p| canvas.contains(p)) => {
                    let points = match unit {
                        egui::MouseWheelUnit::Point => delta.y,
                        egui::MouseWheelUnit::Line => delta.y * 40.0,
                        egui::MouseWheelUnit::Page => delta.y * 400.0,
                    };
                    // Wheel up (away from you) zooms in.
                    *e = egui::Event::Zoom((points / 200.0).exp());
                }
                _ => {}
            }
        }
    }

    /// The file dialog being shown, if any (tests type a path into it).
    pub fn dialog_mut(&mut self) -> Option<&mut FileDialog> {
        self.dialog.as_mut()
    }

    /// Whether a restore from a previous session's recovery file is being offered.
    pub fn restore_offered(&self) -> bool {
        self.offer_restore.is_some()
    }

    /// Restores the recovery file (the crash-restore dialog's "Restore").
    pub fn restore(&mut self) {
        if let Some(r) = self.offer_restore.take() {
            let resolve = r.path.as_deref().or(r.origin.as_deref());
            let options = cnets_host::document_options(resolve, &self.library.dirs);
            match GraphDocument::from_text_with(
                &r.text,
                "recovery",
                r.path.clone(),
                &self.registry,
                &options,
            ) {
                Ok(mut d) => {
                    d.origin = r.origin.clone();
                    d.mark_dirty();
                    self.replace_doc(d);
                    self.message = if self.page.is_some() {
                        "restored the unsaved work this browser kept".into()
                    } else {
                        "restored unsaved work from the last session".into()
                    };
                }
                Err(e) => self.message = format!("cannot restore: {e}"),
            }
        }
    }

    /// Keeps the recovery texts in `recovery` from now on (the web page: the browser's local
    /// storage) and offers to restore what a previous session left there.
    pub fn set_recovery(&mut self, recovery: Recovery) {
        self.offer_restore = recovery.find();
        self.recovery = recovery;
    }

    /// Declines the restore and removes the recovery file.
    pub fn discard_recovery(&mut self) {
        self.offer_restore = None;
        self.recovery.clear();
    }

    fn replace_doc(&mut self, doc: GraphDocument) {
        let previous = self.doc.generation();
        self.doc = doc;
        // A new document is a new evaluation generation (fresh evaluator).
        self.doc.start_after(previous);
        self.canvas = Canvas::new();
        self.canvas_view.clear();
        self.check_overlaps = true;
        self.overlap_hint = false;
        self.refit_on_results = true;
        self.statuses.clear();
        self.viewport.reset();
        self.pending_change = Some(Instant::now());
        self.optimization.reset();
        self.list_editors.close_all();
        self.watch.clear();
        self.import_watch.clear();
        self.watch.changed(&self.doc.graph);
    }

    /// The folders library graphs come from: the user library, then the examples folder.
    pub fn library_dirs(&self) -> Vec<PathBuf> {
        self.library.dirs.clone()
    }

    /// Load options for the document (its folder, then the library folders).
    fn load_options(&self) -> cnets_engine::file::LoadOptions {
        cnets_host::document_options(self.doc.resolve_file(), &self.library.dirs)
    }

    /// The first cluster node among the nodes commands act on (selection, else focus).
    fn targeted_cluster(&self) -> Option<String> {
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
            Err(e) => self.message = e,
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
                self.watch.changed(&self.doc.graph);
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
        self.last_watch = Instant::now();
        let changed = self.watch.changed(&self.doc.graph);
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

    /// Checks the files the graph's importing nodes read; when one changed, submits the graph
    /// again so the worker re-runs the nodes that read it (and only what depends on them).
    /// Returns whether a file changed.
    pub fn check_imported_files(&mut self) -> bool {
        let base = self.doc.base_dir();
        let changed = self.import_watch.changed(&self.doc.graph, base.as_deref());
        if changed {
            self.submitted = None;
        }
        changed
    }

    /// Asks to replace or close the document: carried out at once when everything is saved,
    /// else after the Save / Don't save / Cancel question (see [`crate::unsaved`]).
    pub fn request(&mut self, r: Replace) {
        if self.doc.is_dirty() && !(r == Replace::Quit && self.close_confirmed) {
            self.unsaved_question = Some(r);
        } else {
            self.perform(r);
        }
    }

    /// Carries out a replacement without asking.
    fn perform(&mut self, r: Replace) {
        match r {
            Replace::New => {
                self.replace_doc(GraphDocument::new(self.registry.clone()));
                self.message = "new graph".into();
            }
            Replace::Open(p) => {
                self.open(&p);
            }
            Replace::Example(p) => {
                self.open_example(&p);
            }
            Replace::Quit => {
                self.close_confirmed = true;
                self.quit = true;
            }
        }
    }

    /// Whether `path` is one of the shipped examples (a file in the examples folder).
    pub fn is_example(&self, path: &Path) -> bool {
        is_example(&self.examples_dir, path)
    }

    /// Opens a graph file without asking (see [`EditorApp::request`]); a shipped example opens
    /// as an untitled copy. When the file does not load, the current document stays and the
    /// diagnostics are shown. Returns whether it opened.
    pub fn open(&mut self, path: &Path) -> bool {
        if self.is_example(path) {
            return self.open_example(path);
        }
        let options = cnets_host::document_options(Some(path), &self.library.dirs);
        match GraphDocument::open_with(path, &self.registry, &options) {
            Ok(d) => {
                self.replace_doc(d);
                self.settings.add_recent(path);
                self.message = format!("opened {}", path.display());
                true
            }
            Err(e) => {
                self.fail_load(path, &e);
                false
            }
        }
    }

    /// Opens an untitled copy of a shipped example (its first save asks where). Returns whether
    /// it opened.
    pub fn open_example(&mut self, path: &Path) -> bool {
        // In the browser the gallery is bundled: the engine's in-memory files (`crate::page`).
        if !path.is_file()
            && let Some(bytes) = cnets_engine::files::memory::read(path)
        {
            return self.open_text(&String::from_utf8_lossy(&bytes), path);
        }
        let options = cnets_host::document_options(Some(path), &self.library.dirs);
        match GraphDocument::open_with(path, &self.registry, &options) {
            Ok(d) => {
                self.replace_doc(d.into_untitled_copy());
                self.message = format!(
                    "opened a copy of the example {}: saving asks where",
                    path.display()
                );
                true
            }
            Err(e) => {
                self.fail_load(path, &e);
                false
            }
        }
    }

    fn fail_load(&mut self, path: &Path, error: &str) {
        self.message = format!("cannot open {}: the document is unchanged", path.display());
        self.load_failure = Some(LoadFailure::new(path, error));
    }

    /// Receives graph files to open from elsewhere (`cnets-editor FILE` started while this
    /// window is open): each goes through [`EditorApp::request`].
    pub fn set_inbox(&mut self, inbox: std::sync::mpsc::Receiver<PathBuf>) {
        self.inbox = Some(inbox);
    }

    /// Saves to `path` (atomic) and clears the recovery file.
    pub fn save_as(&mut self, path: &Path) {
        match self.doc.save_as(path) {
            Ok(()) => {
                self.settings.add_recent(path);
                self.recovery.clear();
                self.message = format!("saved {}", path.display());
            }
            Err(e) => self.message = e,
        }
        if !self.doc.is_dirty()
            && let Some(r) = self.after_save.take()
        {
            self.perform(r);
        }
    }

    /// Adds a node of type `type_id` at a canvas position; returns its id.
    pub fn add_node(&mut self, type_id: &str, at: [f32; 2]) -> Option<String> {
        let id = self.doc.fresh_id(type_id);
        let r = self.doc.edit(None, |g, _| {
            g.add_node(&id, type_id).map_err(|e| e.to_string())?;
            g.set_position(&id, at).map_err(|e| e.to_string())
        });
        match r {
            Ok(()) => {
                self.canvas.focused = Some(id.clone());
                Some(id)
            }
            Err(e) => {
                self.message = e;
                None
            }
        }
    }

    /// In a web page: the actions the page carries out instead of files and dialogs (open by the
    /// browser's picker, save and export as downloads, copy a share link). Returns whether
    /// `action` was one of them.
    fn run_in_page(&mut self, action: &MenuAction) -> bool {
        let name = self
            .doc
            .resolve_file()
            .and_then(Path::file_stem)
            .map_or_else(
                || "cone-net".to_string(),
                |s| s.to_string_lossy().into_owned(),
            );
        let request = match action {
            MenuAction::Open => crate::page::PageRequest::PickFile,
            MenuAction::Save | MenuAction::SaveAs => {
                let ron = self.doc.to_ron();
                self.recovery.clear();
                self.message = format!("downloaded {name}.ron");
                crate::page::PageRequest::Download {
                    name: format!("{name}.ron"),
                    bytes: ron.into_bytes(),
                }
            }
            MenuAction::CopyLink => crate::page::PageRequest::CopyLink {
                ron: self.doc.to_ron(),
            },
            MenuAction::Export(format) => {
                let base = self.doc.base_dir();
                let folder = Path::new("/downloads");
                match export::export(&self.doc.graph, base, *format, folder, &name) {
                    Ok(files) => {
                        let mut written = cnets_engine::files::memory::take_written();
                        written.retain(|(p, _)| files.contains(p));
                        self.message = format!("exported {} file(s)", written.len());
                        if let Some(page) = &mut self.page {
                            for (p, bytes) in written {
                                let name = p.file_name().map_or_else(
                                    || "export".to_string(),
                                    |n| n.to_string_lossy().into_owned(),
                                );
                                page.requests
                                    .push(crate::page::PageRequest::Download { name, bytes });
                            }
                        }
                    }
                    Err(e) => self.message = format!("export failed: {e}"),
                }
                return true;
            }
            MenuAction::LibraryFolder | MenuAction::Quit => {
                self.message = "not in the browser: there is no file system here".into();
                return true;
            }
            _ => return false,
        };
        if let Some(page) = &mut self.page {
            page.requests.push(request);
        }
        true
    }

    /// Opens graph text as an untitled document (the web page: a bundled example, a file picked
    /// or dropped, a share link); `origin` names where it came from (relative imports resolve
    /// against its folder). When it does not load, the document stays and the diagnostics are
    /// shown. Returns whether it opened.
    pub fn open_text(&mut self, text: &str, origin: &Path) -> bool {
        let options = cnets_host::document_options(Some(origin), &self.library.dirs);
        let name = origin.display().to_string();
        match GraphDocument::from_text_with(text, &name, None, &self.registry, &options) {
            Ok(mut d) => {
                d.origin = Some(origin.to_path_buf());
                self.replace_doc(d);
                self.message = format!("opened {name}");
                true
            }
            Err(e) => {
                self.fail_load(origin, &e);
                false
            }
        }
    }

    /// Replaces the document by an empty one shown as `name` (the web page, when a link gives no
    /// graph: its dialog says why, and no unrelated graph stands in for the link's).
    pub fn open_empty(&mut self, name: &str) {
        let mut doc = GraphDocument::new(self.registry.clone());
        doc.name = Some(name.to_string());
        self.replace_doc(doc);
    }

    /// Sets the graphs File ▸ Open example lists (the web page: the bundled gallery, opened
    /// through [`EditorApp::open_text`] by the page when their files are not on disk).
    pub fn set_examples(&mut self, examples: Vec<PathBuf>) {
        self.examples = examples;
    }

    /// Evaluates the graph again at the next frame (the web page: after a file was opened that a
    /// node imports).
    pub fn reevaluate(&mut self) {
        self.submitted = None;
    }

    /// Carries out a canvas action (an edit or a UI request); a refusal becomes the status
    /// message. Returns whether it applied.
    pub fn apply(&mut self, action: CanvasAction) -> bool {
        match action {
            CanvasAction::Edit(e) => self.edit(e),
            CanvasAction::Request(r) => self.handle(r),
        }
    }

    /// Applies a document edit ([`edit::apply`]); a refusal becomes the status message. Returns
    /// whether it applied.
    pub fn edit(&mut self, edit: Edit) -> bool {
        let made_cluster = matches!(edit, Edit::MakeCluster { .. });
        match edit::apply(&mut self.doc, edit) {
            Ok(created) => {
                if made_cluster && let Some(id) = created.first() {
                    self.canvas.selected.clear();
                    self.canvas.focused = Some(id.clone());
                    self.message =
                        format!("made cluster '{id}': double-click its title to open it");
                }
                true
            }
            Err(e) => {
                self.message = format!("refused: {e}");
                false
            }
        }
    }

    /// Carries out what the 3D view asked for: an edit, selecting a node, a drawn curve.
    pub fn apply_view(&mut self, action: ViewportAction) {
        match action {
            ViewportAction::Edit(e) => {
                self.edit(e);
            }
            ViewportAction::SelectNode(id) => {
                self.canvas.focused = Some(id.clone());
                self.canvas.select(vec![id.clone()]);
                self.message = format!("selected '{id}'");
            }
            ViewportAction::AddCurve(curve) => self.add_curve(curve),
            ViewportAction::Message(m) => self.message = m,
        }
    }

    /// Adds a drawn curve as a `param.points` node wired into a `curve.spline` (or
    /// `curve.polyline`), placed on the canvas below the selection (else in the middle of the
    /// canvas), and selects both (one undo step).
    pub fn add_curve(&mut self, curve: crate::viewport::DrawnCurve) {
        // Below the selection (the curve drawn before: curves stack up on the left, as
        // parameters do in Grasshopper), else in the middle of the canvas.
        let at = match self.canvas.bounds_of(&self.canvas.targets()) {
            Some(r) => {
                let p = self.canvas.free_spot(
                    egui::pos2(r.left(), r.bottom() + 40.0),
                    egui::vec2(460.0, 140.0),
                );
                [p.x, p.y]
            }
            None => self.new_node_place(),
        };
        if let Some(created) = self.edit_created(Edit::AddCurves {
            curves: vec![curve],
            at,
        }) {
            self.message = format!(
                "added {}: wire its curve into a construction",
                created.join(" and ")
            );
            self.canvas.focused = created.last().cloned();
            self.canvas.select(created);
        }
    }

    /// Most curves one "Internalise" turns into points.
    pub const MAX_INTERNALISED: usize = 64;

    /// Turns the curves node `id` outputs into `param.points` + `curve.polyline` pairs right of
    /// it (one undo step): the node is evaluated now, on the document's graph and folder.
    pub fn internalise(&mut self, id: &str) -> Result<String, String> {
        let graph = self.doc.eval_graph();
        let index = graph.index(id).map_err(|e| e.to_string())?;
        let ctx = cnets_engine::NodeContext::new(None, self.doc.base_dir());
        let mut evaluator = cnets_engine::Evaluator::new();
        evaluator.evaluate(&graph, &[index], &ctx, &mut |_, _| {});
        let result = evaluator
            .result(&graph, id)
            .ok_or_else(|| format!("'{id}' did not run"))?;
        let outputs = result.outputs().ok_or_else(|| {
            result
                .error()
                .map_or("it failed".into(), |e| e.into_owned())
        })?;
        let mut curves = Vec::new();
        fn gather(v: &cnets_engine::Value, into: &mut Vec<crate::viewport::DrawnCurve>) {
            match v {
                cnets_engine::Value::Polyline(p) => into.push(crate::viewport::DrawnCurve {
                    points: p.points.clone(),
                    closed: p.closed,
                    spline: false,
                }),
                cnets_engine::Value::List(items) => items.iter().for_each(|i| gather(i, into)),
                _ => {}
            }
        }
        for v in &outputs.values {
            gather(v, &mut curves);
        }
        if curves.is_empty() {
            return Err(format!("'{id}' outputs no curves"));
        }
        let total = curves.len();
        curves.truncate(Self::MAX_INTERNALISED);
        let at = match self.canvas.node_rect(id) {
            Some(r) => [r.right() + 60.0, r.top()],
            None => self.new_node_place(),
        };
        let created = self
            .edit_created(Edit::AddCurves { curves, at })
            .ok_or_else(|| self.message.clone())?;
        self.canvas.select(created.clone());
        Ok(if total > Self::MAX_INTERNALISED {
            format!(
                "internalised the first {} of {total} curves of '{id}'",
                Self::MAX_INTERNALISED
            )
        } else {
            format!("internalised {total} curve(s) of '{id}' as editable points")
        })
    }

    /// Where new nodes go on the canvas: right of the selected (or focused) nodes, else the
    /// middle of the visible canvas — moved down past any node there.
    pub fn new_node_place(&self) -> [f32; 2] {
        let start = match self.canvas.bounds_of(&self.canvas.targets()) {
            Some(r) => egui::pos2(r.right() + 60.0, r.top()),
            None => self.canvas.to_canvas(self.canvas.screen_rect().center()),
        };
        let p = self.canvas.free_spot(start, egui::vec2(460.0, 140.0));
        [p.x, p.y]
    }

    /// Applies an edit and returns the nodes it created (`None` when refused: the message says
    /// why).
    pub fn edit_created(&mut self, edit: Edit) -> Option<Vec<String>> {
        match edit::apply(&mut self.doc, edit) {
            Ok(created) => Some(created),
            Err(e) => {
                self.message = format!("refused: {e}");
                None
            }
        }
    }

    /// Carries out a UI request; a refusal becomes the status message. Returns whether it was
    /// carried out.
    pub fn handle(&mut self, request: UiRequest) -> bool {
        let handled = match request {
            UiRequest::OpenPalette(at) => {
                // At the click: the canvas point on screen.
                let screen = self.canvas.to_screen(egui::pos2(at[0], at[1]));
                self.palette.open_at_screen(at, screen);
                return true;
            }
            UiRequest::OpenCluster(id) => {
                self.open_cluster(&id);
                return true;
            }
            UiRequest::Optimize {
                path,
                min,
                max,
                prepare,
            } => {
                let variable = Variable {
                    input: path,
                    min,
                    max,
                };
                self.optimization.open = true;
                self.optimization
                    .add_variable(&mut self.doc, variable, prepare)
            }
            UiRequest::Minimize(path) => {
                self.optimization.open = true;
                self.optimization.set_objective(&mut self.doc, path)
            }
            UiRequest::Penalize(path) => {
                self.optimization.open = true;
                self.optimization.add_penalty(&mut self.doc, path)
            }
            UiRequest::Internalise(id) => self.internalise(&id),
            UiRequest::EditList { node, input } => {
                // Beside the Edit… button clicked (else the pointer).
                let at = self
                    .canvas
                    .editor_screen_rect(&node, &input)
                    .map(|r| r.right_top() + egui::vec2(16.0, -8.0))
                    .or(self.pointer);
                self.list_editors
                    .open(self.doc.view_path(), &node, &input, at);
                return true;
            }
        };
        match handled {
            Ok(m) => {
                self.message = m;
                true
            }
            Err(e) => {
                self.message = format!("refused: {e}");
                false
            }
        }
    }

    /// Carries out a menu action or shortcut.
    pub fn run(&mut self, action: MenuAction) {
        if self.page.is_some() && self.run_in_page(&action) {
            return;
        }
        match action {
            MenuAction::New => self.request(Replace::New),
            MenuAction::Open => {
                let start = self
                    .doc
                    .path
                    .as_deref()
                    .and_then(Path::parent)
                    .map_or_else(|| self.examples_dir.clone(), Path::to_path_buf);
                self.dialog = Some(FileDialog::new(Purpose::Open, &start));
            }
            MenuAction::OpenPath(p) => self.request(Replace::Open(p)),
            MenuAction::OpenExample(p) => self.request(Replace::Example(p)),
            MenuAction::Save => match self.doc.path.clone() {
                Some(p) => self.save_as(&p),
                None => self.run(MenuAction::SaveAs),
            },
            MenuAction::SaveAs => {
                let start = self.doc.path.clone().unwrap_or_else(|| {
                    // An untitled copy of an example is saved into the designer's own folder
                    // (never next to the shipped file), under the example's name.
                    let name = self
                        .doc
                        .origin
                        .as_deref()
                        .and_then(Path::file_name)
                        .map_or_else(|| "untitled.ron".into(), |n| n.to_os_string());
                    user_folder(&self.examples_dir).join(name)
                });
                self.dialog = Some(FileDialog::new(Purpose::SaveAs, &start));
            }
            MenuAction::Export(format) => {
                if export::export_node(&self.registry, format).is_none() {
                    self.message = format!(
                        "no {} export node is registered in this build",
                        format.extension()
                    );
                } else {
                    let start = self.doc.path.as_deref().and_then(Path::parent).map_or_else(
                        || std::env::current_dir().unwrap_or_default(),
                        Path::to_path_buf,
                    );
                    self.dialog = Some(FileDialog::new(Purpose::ExportFolder(format), &start));
                }
            }
            MenuAction::Undo => {
                if !self.doc.undo() {
                    self.message = "nothing to undo".into();
                }
            }
            MenuAction::Redo => {
                if !self.doc.redo() {
                    self.message = "nothing to redo".into();
                }
            }
            MenuAction::Delete => {
                let targets = self.canvas.targets();
                if !targets.is_empty() {
                    self.edit(Edit::Remove(targets));
                    self.canvas.focused = None;
                }
            }
            MenuAction::Duplicate => {
                let targets = self.canvas.targets();
                if !targets.is_empty() {
                    self.edit(Edit::Duplicate(targets));
                }
            }
            MenuAction::Copy => {
                self.clipboard = Clipboard::copy(&self.doc.graph, &self.canvas.targets());
                self.message = format!("copied {} nodes", self.clipboard.len());
            }
            MenuAction::Paste => {
                let clip = self.clipboard.clone();
                if !clip.is_empty() {
                    let r = self
                        .doc
                        .edit(None, |g, _| clip.paste(g, [40.0, 40.0], false));
                    if let Err(e) = r {
                        self.message = e;
                    }
                }
            }
            MenuAction::AddNode => {
                let at = self.new_node_place();
                self.palette.open_at(at);
            }
            MenuAction::Fit => self.viewport.fit(),
            MenuAction::FitCanvas => self.canvas.fit(),
            MenuAction::Arrange => {
                let moves = self.canvas.arrangement(&self.doc.graph);
                if !moves.is_empty() && self.edit(Edit::Move(moves)) {
                    self.doc.history.end_gesture();
                    self.canvas.fit();
                }
            }
            MenuAction::SetPreview(o) => self.viewport.options = o,
            MenuAction::MakeCluster => {
                let targets = self.canvas.targets();
                if targets.is_empty() {
                    self.message =
                        "select the nodes to put in a cluster (Shift+click, Shift+drag)".into();
                } else {
                    self.make_cluster(&targets);
                }
            }
            MenuAction::ExplodeCluster => match self.targeted_cluster() {
                Some(id) => {
                    self.edit(Edit::ExplodeCluster(id));
                }
                None => self.message = "focus a cluster node to explode it".into(),
            },
            MenuAction::OpenCluster => match self.targeted_cluster() {
                Some(id) => self.open_cluster(&id),
                None => self.message = "focus a cluster node to open it".into(),
            },
            MenuAction::LeaveTo(depth) => self.leave_to(depth),
            MenuAction::ToggleOptimization => self.optimization.open = !self.optimization.open,
            MenuAction::ToggleParameters => self.parameters_open = !self.parameters_open,
            MenuAction::LibraryFolder => {
                let start = self.settings.library_dir();
                self.dialog = Some(FileDialog::new(Purpose::LibraryFolder, &start));
            }
            MenuAction::Quit => self.request_close(),
            MenuAction::CopyLink => {
                self.message = "share links are made by the web page (cnets in the browser)".into()
            }
            MenuAction::View(v) => self.viewport.set_view(v),
            MenuAction::FrameSelection => {
                let targets = self.canvas.targets();
                self.viewport.frame_selection(&targets);
            }
            MenuAction::Tool(t) => self.viewport.toggle_tool(t),
            MenuAction::ToggleSnap => self.viewport.snap = !self.viewport.snap,
            MenuAction::ToggleGrid => self.viewport.show_grid = !self.viewport.show_grid,
            MenuAction::ToggleDimensions => {
                self.viewport.show_dimensions = !self.viewport.show_dimensions
            }
            MenuAction::PerspectivePlane(p) => self.viewport.perspective_plane = p,
        }
    }

    /// Asks to close: closes at once when everything is saved, else asks first.
    pub fn request_close(&mut self) {
        self.request(Replace::Quit);
    }

    fn shortcuts(&mut self, ctx: &egui::Context) {
        let typing = ctx.egui_wants_keyboard_input();
        let cmd = Modifiers::COMMAND;
        let shift_cmd = Modifiers::COMMAND | Modifiers::SHIFT;
        let mut actions = Vec::new();
        ctx.input_mut(|i| {
            // Longer shortcuts first, so Ctrl+Shift+Z is not taken as Ctrl+Z.
            let mut take = |m: Modifiers, k: Key, a: MenuAction| {
                if i.consume_shortcut(&KeyboardShortcut::new(m, k)) {
                    actions.push(a);
                }
            };
            take(shift_cmd, Key::Z, MenuAction::Redo);
            take(shift_cmd, Key::G, MenuAction::ExplodeCluster);
            take(shift_cmd, Key::S, MenuAction::SaveAs);
            take(cmd, Key::S, MenuAction::Save);
            take(cmd, Key::O, MenuAction::Open);
            take(cmd, Key::Q, MenuAction::Quit);
            if !typing {
                take(cmd, Key::Z, MenuAction::Undo);
                take(cmd, Key::Y, MenuAction::Redo);
                take(cmd, Key::D, MenuAction::Duplicate);
                take(cmd, Key::L, MenuAction::Arrange);
                take(cmd, Key::P, MenuAction::ToggleParameters);
                take(cmd, Key::G, MenuAction::MakeCluster);
                take(cmd, Key::C, MenuAction::Copy);
                take(cmd, Key::V, MenuAction::Paste);
                take(Modifiers::NONE, Key::Delete, MenuAction::Delete);
                take(Modifiers::NONE, Key::F, MenuAction::Fit);
                take(Modifiers::NONE, Key::Home, MenuAction::FitCanvas);
            }
        });
        // Esc backs out of an opened cluster (the palette and dialogs take it first).
        let depth = self.doc.depth();
        if depth > 0
            && !typing
            && !self.palette.open
            && self.dialog.is_none()
            && ctx.input(|i| i.key_pressed(Key::Escape))
        {
            actions.push(MenuAction::LeaveTo(depth - 1));
        }
        // Copy and paste arrive as events, not key presses, on some platforms.
        if !typing {
            ctx.input(|i| {
                for e in &i.events {
                    match e {
                        egui::Event::Copy => actions.push(MenuAction::Copy),
                        egui::Event::Paste(_) => actions.push(MenuAction::Paste),
                        _ => {}
                    }
                }
            });
        }
        for a in actions {
            self.run(a);
        }
    }

    fn poll_worker(&mut self) {
        if let Some(r) = self.worker.poll() {
            self.take_response(r);
        }
    }

    /// Takes an evaluation's results: node statuses, the scene and its figures.
    fn take_response(&mut self, r: crate::worker::EvalResponse) {
        self.statuses = r.statuses;
        if r.view != self.statuses_view || std::mem::take(&mut self.refit_on_results) {
            // The first results of a document or of another graph level: frame it once they are
            // drawn.
            self.canvas.fit_later();
        }
        self.statuses_view = r.view;
        self.latency.eval_ms = r.eval_ms;
        self.latency.scene_ms = r.stats.build_ms;
        self.latency.ran = r.ran;
        // The rest of the graph finished after the preview: the same scene, nothing to upload.
        if !Arc::ptr_eq(&r.scene, self.viewport.scene()) {
            self.viewport.set_scene(r.scene, r.stats, r.picks);
            self.awaiting_picture = Some((self.viewport.scene_version(), r.changed_at));
        }
    }

    /// Sends the graph to the worker when it (or the display options) changed since the last
    /// submission.
    pub fn submit_if_changed(&mut self) {
        let key = (
            self.doc.generation(),
            self.doc.version(),
            self.viewport.options,
        );
        if self.submitted == Some(key) {
            return;
        }
        let changed_at = self.pending_change.take().unwrap_or_else(Instant::now);
        let base = self.doc.base_dir();
        let generation = self.doc.generation();
        if let Some((from, previous, previous_base)) = self
            .last_evaluated
            .take()
            .filter(|(g, ..)| *g != generation)
        {
            // Another document (or this one replaced wholesale): it continues the graph the
            // worker evaluated last, which keeps its evaluator and the results of shared nodes.
            let continued = self.doc.take_over(&previous);
            self.worker.set_carry(Some(Carry {
                from_generation: from,
                continued: Arc::new(continued),
                same_folder: previous_base == base,
            }));
        }
        let graph = self.doc.eval_graph();
        self.last_evaluated = Some((generation, graph.clone(), base.clone()));
        self.worker.submit_view(
            graph,
            self.doc.view_path(),
            generation,
            self.viewport.options,
            base,
            changed_at,
        );
        self.submitted = Some(key);
    }

    /// Evaluates with `worker` from now on (the web page: its Web Worker, [`Worker::remote`]);
    /// the graph is submitted to it at the next frame.
    pub fn set_worker(&mut self, worker: Worker) {
        self.worker = worker;
        self.submitted = None;
        self.last_evaluated = None;
    }

    /// Whether an evaluation is in progress.
    pub fn busy(&self) -> bool {
        self.worker.busy()
    }

    /// Waits (up to `timeout`) for the worker to answer the latest submission and takes the
    /// result, as the next frame would. For tests and the screenshot mode.
    pub fn wait_for_worker(&mut self, timeout: Duration) {
        self.submit_if_changed();
        if let Some(r) = self.worker.wait(timeout) {
            self.take_response(r);
        }
    }

    /// One frame of the editor.
    pub fn ui(&mut self, ui: &mut Ui) {
        let ctx = ui.ctx().clone();
        self.poll_worker();
        self.optimization.poll();
        // An active list editor window takes pasted text, Copy and Delete before the shortcuts.
        self.list_editors.claim_input(&ctx, &self.doc.view_path());
        self.shortcuts(&ctx);
        if self.last_watch.elapsed() >= WATCH_INTERVAL {
            self.check_cluster_files();
            self.check_imported_files();
        }
        let version_before = self.doc.version();

        egui::Panel::top("cnets-menu").show(ui, |ui| {
            let mc = MenuContext {
                examples: &self.examples,
                recent: &self.settings.recent,
                can_undo: self.doc.history.can_undo(),
                can_redo: self.doc.history.can_redo(),
                can_paste: !self.clipboard.is_empty(),
                preview: self.viewport.options,
                depth: self.doc.depth(),
                optimization: self.optimization.open,
                parameters: self.parameters_open,
                library: &self.library.dirs[0],
                web: self.page.is_some(),
                view: menus::ViewMenuState {
                    view: self.viewport.view,
                    snap: self.viewport.snap,
                    grid: self.viewport.show_grid,
                    dimensions: self.viewport.show_dimensions,
                    perspective_plane: self.viewport.perspective_plane,
                },
            };
            if let Some(a) = menus::menu_bar(ui, &mc) {
                self.run(a);
            }
        });
        // Below a width threshold (a phone, a narrow window): the 3D view over the parameters,
        // the canvas behind a tab (crate::narrow).
        let narrow = crate::narrow::is_narrow(&ctx);
        self.parameters_rect = None;
        self.parameter_editors.clear();
        egui::Panel::bottom("cnets-status").show(ui, |ui| {
            if narrow {
                crate::narrow::status_bar(ui, &self.doc.title(), &self.message);
                return;
            }
            ui.horizontal(|ui| {
                ui.label(self.doc.title());
                ui.separator();
                if self.show_timings {
                    if self.worker.busy() {
                        ui.spinner();
                    }
                    ui.weak(format!(
                        "eval {:.1} ms · scene {:.1} ms · change-to-picture {:.1} ms",
                        self.latency.eval_ms, self.latency.scene_ms, self.latency.last_ms
                    ));
                }
                ui.separator();
                ui.label(&self.message);
                if self.overlap_hint {
                    ui.separator();
                    ui.label(OVERLAP_HINT);
                }
            });
        });
        if self.optimization.open {
            let base = self.doc.base_dir();
            egui::Panel::bottom("cnets-optimization")
                .resizable(true)
                .default_size(270.0)
                .min_size(120.0)
                .show(ui, |ui| {
                    if let Some(m) = self.optimization.show(ui, &mut self.doc, base)
                        && !m.is_empty()
                    {
                        self.message = m;
                    }
                });
        }
        if narrow {
            crate::narrow::panels(self, ui);
        } else {
            if self.parameters_open {
                let actions = egui::Panel::left("cnets-parameters")
                    .resizable(true)
                    .default_size(260.0)
                    .min_size(180.0)
                    .show(ui, |ui| self.parameters_contents(ui))
                    .inner;
                for a in actions {
                    self.apply(a);
                }
            }
            egui::Panel::right("cnets-viewport")
                .resizable(true)
                .default_size(ui.available_width() * 0.45)
                .min_size(200.0)
                .frame(egui::Frame::NONE)
                .show(ui, |ui| self.viewport_contents(ui, true));
            egui::CentralPanel::default()
                .frame(egui::Frame::NONE)
                .show(ui, |ui| self.canvas_contents(ui));
        }
        if let Some(m) = self.list_editors.show(&ctx, &mut self.doc) {
            self.message = m;
        }

        if self.palette.open && !self.palette_was_open {
            self.library.scan(&self.registry);
        }
        self.palette_was_open = self.palette.open;
        match palette::show(
            &ctx,
            &mut self.palette,
            &self.registry,
            self.library.entries(),
        ) {
            Some(Pick::Type(type_id)) => {
                let at = self.palette.at;
                self.add_node(&type_id, at);
            }
            Some(Pick::Library(entry)) => {
                let at = self.palette.at;
                self.add_library_cluster(&entry, at);
            }
            None => {}
        }
        if self.check_overlaps && self.canvas.measured(self.doc.graph.node_count()) {
            self.check_overlaps = false;
            self.overlap_hint = self.canvas.has_overlaps();
        } else if self.overlap_hint && !self.canvas.has_overlaps() {
            // The hint goes once the nodes no longer overlap (arranged, or moved apart).
            self.overlap_hint = false;
        }
        self.show_dialog(&ctx);
        self.show_restore(&ctx);

        // A gesture ends when the pointer is released and no text field is being typed in (so a
        // drag, or typing a name, is one undo step).
        if !ctx.input(|i| i.pointer.any_down()) && !ctx.egui_wants_keyboard_input() {
            self.doc.history.end_gesture();
        }
        // The window's close button: ask first when there are unsaved changes.
        if ctx.input(|i| i.viewport().close_requested()) && !self.quit {
            if self.doc.is_dirty() && !self.close_confirmed {
                ctx.send_viewport_cmd(egui::ViewportCommand::CancelClose);
            }
            self.request(Replace::Quit);
        }
        // A graph file dropped on the window, or sent by `cnets-editor FILE` (in a web page the
        // page reads dropped files: they have no path there).
        let in_page = self.page.is_some();
        let dropped: Vec<PathBuf> = ctx.input(|i| {
            i.raw
                .dropped_files
                .iter()
                .map(|f| f.path().to_path_buf())
                .filter(|p| !in_page && !p.as_os_str().is_empty())
                .collect()
        });
        let sent: Vec<PathBuf> = self
            .inbox
            .as_ref()
            .map(|r| r.try_iter().collect())
            .unwrap_or_default();
        if let Some(p) = dropped.into_iter().chain(sent).last() {
            self.request(Replace::Open(p));
        }
        self.show_unsaved_question(&ctx);
        if let Some(f) = &mut self.load_failure
            && !f.show(&ctx)
        {
            self.load_failure = None;
        }
        if self.doc.version() != version_before && self.pending_change.is_none() {
            self.pending_change = Some(Instant::now());
        }
        self.submit_if_changed();
        // The frame that hands a new scene to the GPU closes a change-to-picture measurement.
        if let Some((version, changed_at)) = self.awaiting_picture
            && self.viewport.drawn_version >= version
        {
            self.latency.last_ms = changed_at.elapsed().as_secs_f64() * 1e3;
            if self.latency.samples.len() < 10_000 {
                self.latency.samples.push(self.latency.last_ms);
            }
            self.awaiting_picture = None;
        }
        // Autosave: a committed edit (no gesture in progress) at once, a gesture within 1 s.
        let committed = !self.doc.history.in_gesture();
        let doc = &self.doc;
        let autosave = self.recovery.tick(
            doc.is_dirty(),
            doc.version(),
            committed,
            (doc.path.as_deref(), doc.origin.as_deref()),
            || doc.to_ron(),
        );
        match autosave {
            Autosave::Due(after) => ctx.request_repaint_after(after),
            Autosave::Failed => {
                self.message = "cannot write the recovery file (autosave)".into();
                ctx.request_repaint_after(crate::recovery::AUTOSAVE_WITHIN);
            }
            Autosave::Idle | Autosave::Wrote => {}
        }
        let title = format!("{} — cnets editor", self.doc.title());
        if title != self.last_title {
            ctx.send_viewport_cmd(egui::ViewportCommand::Title(title.clone()));
            self.last_title = title;
        }
        if self.worker.busy() {
            ctx.request_repaint_after(Duration::from_millis(30));
        }
        let base = self.doc.base_dir();
        if !crate::library::file_clusters(&self.doc.graph).is_empty()
            || !crate::import_watch::imported_files(&self.doc.graph, base.as_deref()).is_empty()
        {
            // Keep checking cluster and imported files while idle.
            ctx.request_repaint_after(WATCH_INTERVAL);
        }
    }

    /// The parameter panel's contents; returns the edits made in it.
    pub(crate) fn parameters_contents(&mut self, ui: &mut Ui) -> Vec<CanvasAction> {
        self.parameters_rect = Some(ui.clip_rect().intersect(ui.max_rect()));
        ui.heading("Parameters");
        let (actions, rects) =
            crate::parameters::show_with_rects(ui, &self.doc.graph, &self.statuses);
        self.parameter_editors = rects;
        actions
    }

    /// The 3D view with its toolbar, and what it asked for carried out. `canvas_shown`: the
    /// canvas is on screen too (else every failed node's error is listed in the view).
    pub(crate) fn viewport_contents(&mut self, ui: &mut Ui, canvas_shown: bool) {
        ui.horizontal(|ui| {
            let mut o = self.viewport.options;
            egui::ComboBox::from_id_salt("color-mode")
                .selected_text(o.color_mode.label())
                .show_ui(ui, |ui| {
                    for m in crate::preview::ColorMode::ALL {
                        ui.selectable_value(&mut o.color_mode, m, m.label());
                    }
                });
            if o.color_mode == crate::preview::ColorMode::Planarity {
                // The top of the scale (planar below 1e-9 stays the anchor).
                let (lo, hi) = crate::preview::PLANARITY_LIMIT_RANGE;
                let mut limit = o.planarity_limit();
                let r = ui
                    .add(
                        egui::Slider::new(&mut limit, lo..=hi)
                            .logarithmic(true)
                            .text("not planar from")
                            .custom_formatter(|v, _| format!("{v:.0e}")),
                    )
                    .on_hover_text(
                        "the top of the planarity colour scale: faces from this relative \
                         planarity up are not planar (saved with the editor settings)",
                    );
                if r.changed() && o.set_planarity_limit(limit) && !r.dragged() {
                    self.settings.set_planarity_limit(o.planarity_limit());
                }
                if r.drag_stopped() {
                    self.settings.set_planarity_limit(o.planarity_limit());
                }
            }
            if ui.button("Fit (F)").clicked() {
                self.viewport.fit();
            }
            self.viewport.options = o;
        });
        ui.horizontal_wrapped(|ui| self.viewport.toolbar(ui));
        let selected = self.canvas.targets();
        let input = ViewportInput {
            graph: &self.doc.graph,
            selected: &selected,
            typing: ui.ctx().egui_wants_keyboard_input(),
        };
        let actions = self.viewport.show(ui, self.gpu.as_ref(), &input);
        for a in actions {
            self.apply_view(a);
        }
        let on_canvas = |id: &str| canvas_shown && crate::view_errors::in_view(&self.canvas, id);
        self.view_errors_shown =
            crate::view_errors::hidden_failures(&self.doc.graph, &self.statuses, &on_canvas)
                .into_iter()
                .map(|(id, message)| format!("{id}: {message}"))
                .collect();
        if let Some(id) = crate::view_errors::show(
            ui,
            self.viewport.rect,
            &self.doc.graph,
            &self.statuses,
            &on_canvas,
        ) {
            self.show_node(ui.ctx(), &id);
        }
    }

    /// Selects node `id` and brings it into the canvas's view (narrow layouts: shows the canvas).
    fn show_node(&mut self, ctx: &egui::Context, id: &str) {
        self.canvas.focused = Some(id.to_string());
        self.canvas.select(vec![id.to_string()]);
        if let Some(r) = self.canvas.node_rect(id) {
            self.canvas.zoom_to(self.canvas.zoom(), Some(r.center()));
        }
        crate::narrow::show_canvas(ctx);
        self.message = format!("selected '{id}'");
    }

    /// The node canvas, with the breadcrumbs inside opened clusters.
    pub(crate) fn canvas_contents(&mut self, ui: &mut Ui) {
        if self.canvas_view != self.doc.view_path() {
            // Another graph level: a fresh canvas framing it.
            self.canvas_serial += 1;
            self.canvas = Canvas::with_id(egui::Id::new(("cnets-canvas", self.canvas_serial)));
            self.canvas.fit_later();
            self.canvas_view = self.doc.view_path();
        }
        if self.doc.depth() > 0
            && let Some(to) = breadcrumbs(ui, &self.doc)
        {
            self.leave_to(to);
        }
        // Statuses of another level (the worker has not answered yet) are not shown.
        let none = HashMap::new();
        let statuses = if self.statuses_view == self.canvas_view {
            &self.statuses
        } else {
            &none
        };
        let actions = self.canvas.show(ui, &self.doc.graph, statuses);
        for a in actions {
            self.apply(a);
        }
        if self.page.is_some()
            && let Some(at) =
                crate::overview::show(ui, &self.canvas, &self.doc.graph, &self.statuses)
        {
            self.canvas.zoom_to(self.canvas.zoom(), Some(at));
        }
    }

    fn show_dialog(&mut self, ctx: &egui::Context) {
        let Some(dialog) = &mut self.dialog else {
            return;
        };
        match dialog.show(ctx) {
            Outcome::Open => {}
            Outcome::Cancelled => {
                if dialog.purpose == Purpose::SaveAs {
                    // "Save" in the unsaved-changes question, then Cancel here: nothing happens.
                    self.after_save = None;
                }
                self.dialog = None;
            }
            Outcome::Chosen(path) => {
                let purpose = dialog.purpose;
                self.dialog = None;
                match purpose {
                    Purpose::Open => self.request(Replace::Open(path)),
                    Purpose::LibraryFolder => {
                        let _ = std::fs::create_dir_all(&path);
                        self.settings.set_library(&path);
                        self.library.dirs[0] = path.clone();
                        self.library.scan(&self.registry);
                        self.message = format!(
                            "library folder: {} ({} graphs with an interface)",
                            path.display(),
                            self.library.entries().len()
                        );
                    }
                    Purpose::SaveAs => self.save_as(&path),
                    Purpose::ExportFolder(format) => {
                        let name = self
                            .doc
                            .resolve_file()
                            .and_then(Path::file_stem)
                            .map_or_else(
                                || "cone-net".to_string(),
                                |s| s.to_string_lossy().into_owned(),
                            );
                        let base = self.doc.base_dir();
                        self.message =
                            match export::export(&self.doc.graph, base, format, &path, &name) {
                                Ok(files) => format!(
                                    "exported {}",
                                    files
                                        .iter()
                                        .map(|f| f.display().to_string())
                                        .collect::<Vec<_>>()
                                        .join(", ")
                                ),
                                Err(e) => format!("export failed: {e}"),
                            };
                    }
                }
            }
        }
    }

    fn show_unsaved_question(&mut self, ctx: &egui::Context) {
        let Some(pending) = &self.unsaved_question else {
            return;
        };
        let title = self.doc.title().trim_end_matches(" *").to_string();
        let Some(answer) = unsaved::ask(ctx, &title, pending) else {
            return;
        };
        let Some(pending) = self.unsaved_question.take() else {
            return;
        };
        match answer {
            Answer::Save => match self.doc.path.clone() {
                Some(p) => {
                    self.save_as(&p);
                    if !self.doc.is_dirty() {
                        self.perform(pending);
                    }
                }
                None => {
                    self.after_save = Some(pending);
                    self.run(MenuAction::SaveAs);
                }
            },
            Answer::Discard => self.perform(pending),
            Answer::Cancel => {}
        }
    }

    fn show_restore(&mut self, ctx: &egui::Context) {
        let Some(r) = &self.offer_restore else {
            return;
        };
        let what = r.path.as_ref().map_or_else(
            || "an untitled graph".to_string(),
            |p| p.display().to_string(),
        );
        let mut choice = None;
        let in_browser = self.page.is_some();
        egui::Modal::new(egui::Id::new("cnets-restore")).show(ctx, |ui| {
            ui.heading("Restore unsaved work?");
            // In the browser there are no sessions to speak of: the page was closed or reloaded.
            ui.label(if in_browser {
                format!(
                    "This page was closed or reloaded without saving {what}. Restore it from \
                     this browser's storage?"
                )
            } else {
                format!(
                    "The last session ended without saving {what}. Restore it from the recovery \
                     file?"
                )
            });
            ui.horizontal(|ui| {
                if ui.button("Restore").clicked() {
                    choice = Some(true);
                }
                if ui.button("Discard").clicked() {
                    choice = Some(false);
                }
            });
        });
        match choice {
            Some(true) => self.restore(),
            Some(false) => self.discard_recovery(),
            None => {}
        }
    }

    /// Called when the window closes normally: the recovery file is removed (unsaved changes
    /// are the designer's choice then, not a crash).
    pub fn on_exit(&mut self) {
        self.recovery.clear();
    }
}

/// Whether `path` is a file of the examples folder (compared canonically).
pub fn is_example(examples_dir: &Path, path: &Path) -> bool {
    let canon = |p: &Path| std::fs::canonicalize(p).ok();
    match (canon(examples_dir), path.parent().and_then(canon)) {
        (Some(dir), Some(parent)) => dir == parent,
        _ => false,
    }
}

/// The folder an untitled document is first saved into: the working folder, unless that is the
/// examples folder (or inside the source tree's `graphs/`), then the home folder.
fn user_folder(examples_dir: &Path) -> PathBuf {
    let cwd = std::env::current_dir().unwrap_or_default();
    let examples = std::fs::canonicalize(examples_dir).ok();
    let inside =
        examples.is_some_and(|e| std::fs::canonicalize(&cwd).is_ok_and(|c| c.starts_with(e)));
    if inside || cwd.as_os_str().is_empty() {
        std::env::var_os("HOME").map_or(cwd, PathBuf::from)
    } else {
        cwd
    }
}

/// The breadcrumb bar above the canvas inside an opened cluster: `main › bay (inline)`; returns
/// the level clicked (0: the document's own graph).
fn breadcrumbs(ui: &mut Ui, doc: &GraphDocument) -> Option<usize> {
    let mut picked = None;
    let crumbs = doc.breadcrumbs();
    egui::Frame::new()
        .fill(ui.visuals().faint_bg_color)
        .inner_margin(egui::Margin::symmetric(8, 4))
        .show(ui, |ui| {
            ui.set_width(ui.available_width());
            ui.horizontal(|ui| {
                let last = crumbs.len() - 1;
                for (k, crumb) in crumbs.iter().enumerate() {
                    if k > 0 {
                        ui.weak("›");
                    }
                    if k == last {
                        ui.strong(crumb);
                    } else if ui
                        .link(crumb)
                        .on_hover_text("go back to this graph (the cluster is rebuilt)")
                        .clicked()
                    {
                        picked = Some(k);
                    }
                }
                ui.weak("   Esc: back");
                if let Some(e) = &doc.live_error {
                    ui.colored_label(egui::Color32::from_rgb(0xd6, 0x2f, 0x2f), e);
                }
            });
        });
    picked
}
