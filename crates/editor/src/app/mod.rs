//! The editor: state and one frame of UI, the same in the window (`main.rs`) and in tests.
//!
//! One handler a file, as Graphite splits a message from its handler: `files` (open, save,
//! recovery), `commands` (menu actions, shortcuts, edits, UI requests), `clusters`, `cplanes` (the
//! construction planes kept with the graph), `worker` (the
//! evaluation glue), `layout` (one frame's panels) and `dialogs`; this file holds the state.

mod arrivals;
mod clusters;
mod commands;
mod control;
mod cplanes;
mod dialogs;
mod evaluation;
mod exports;
mod files;
mod fresh_document;
mod layout;
mod loading;
mod modals;
mod net_drag;
mod panels;
mod queries;
mod reads;
mod worker;

pub use arrivals::Arrived;
use clusters::Watching;
use evaluation::Evaluation;
pub use evaluation::Latency;
pub use fresh_document::FreshDocument;
pub use modals::{Modal, Modals};
pub use net_drag::NetDragFigures;
use net_drag::NetDrags;
pub use panels::Panels;
pub use reads::{ReadAccess, ReadPrompt};

pub use files::is_example;
pub use loading::LARGE_GRAPH_BYTES;

use crate::canvas::Canvas;
use crate::clipboard::Clipboard;
use crate::document::GraphDocument;
use crate::library::Library;
use crate::list_editor::ListEditors;
use crate::load_failure::LoadFailure;
use crate::menus;
use crate::optimization::OptimizationPanel;
use crate::palette::PaletteState;
use crate::recovery::Recovery;
use crate::settings::Settings;
use crate::viewport::Viewport;
use crate::worker::Worker;
use cnets_engine::Registry;
use std::path::PathBuf;
use std::sync::Arc;
use web_time::Duration;
use web_time::Instant;

pub use crate::viewport::GpuTarget;

/// The graph the editor starts on when no file is given and `graphs/torus-monge.ron` is absent.
pub const DEFAULT_GRAPH: &str = include_str!("../../../../graphs/editor-default.ron");

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

/// The status bar's hint when a document's nodes overlap (shown while they do).
pub const OVERLAP_HINT: &str = "nodes overlap: View › Arrange graph (Ctrl+L) lays them out";

/// The editor.
pub struct EditorApp {
    /// Node types.
    registry: Arc<Registry>,
    /// The document being edited.
    doc: GraphDocument,
    /// The node canvas.
    canvas: Canvas,
    /// The 3D viewport.
    viewport: Viewport,
    /// The node palette.
    palette: PaletteState,
    /// The message in the status bar (e.g. why a wire was refused).
    message: String,
    /// Recent files.
    settings: Settings,
    /// Whether the window should close (set by File › Quit and after the unsaved-changes
    /// question; the window closes when it sees it).
    quit: bool,
    /// The dialogs over the editor, one shown at a time (the unsaved-changes question, the
    /// restore offer, a failed file, the read prompt, the export report, the file dialog).
    modals: Modals,
    /// The designer answered the question: closing is allowed now.
    close_confirmed: bool,
    /// Graph files sent by `cnets-editor FILE` started while this window is open.
    inbox: Option<std::sync::mpsc::Receiver<PathBuf>>,
    last_title: String,
    /// The checks the document opened last still waits for (overlaps, framing on results).
    fresh: FreshDocument,
    /// Show timings and the busy spinner in the status bar (snapshot tests turn them off: they
    /// vary from run to run).
    show_timings: bool,
    /// The evaluation session: the worker, what was sent to it, the statuses it answered and
    /// the latency figures.
    evaluation: Evaluation,
    recovery: Recovery,
    /// What File ▸ Restore kept work names: another document's recovery kept aside (the page).
    kept_recovery: Option<String>,
    /// A large file being read off the UI thread (`loading`).
    loading: Option<loading::Loading>,
    /// A document read elsewhere, waiting for the unsaved-changes question (`arrivals`).
    waiting: Option<arrivals::Waiting>,
    clipboard: Clipboard,
    gpu: Option<GpuTarget>,
    examples: Vec<PathBuf>,
    examples_dir: PathBuf,
    /// The user library (and the examples folder), listed in the palette.
    library: Library,
    /// The files the graph reads (imports, clusters), checked about once a second.
    watching: Watching,
    /// The optimization panel.
    optimization: OptimizationPanel,
    /// The parameter panel and where the last frame drew the panels.
    panels: Panels,
    /// The open table windows of literal lists (a node's **Edit…**).
    list_editors: ListEditors,
    /// The pointer's last position seen by [`EditorApp::raw_input`].
    pointer: Option<egui::Pos2>,
    /// The opened clusters the canvas was showing in the last frame.
    canvas_view: Vec<String>,
    /// Counts the canvases made for graph levels (each gets its own view state).
    canvas_serial: u64,
    palette_was_open: bool,
    /// In a web page: the requests for the page (see [`crate::page`]); `None` on the desktop.
    page: Option<crate::page::Page>,
    /// What the document's reads wait on: the Browse… dialog's input, the declined prompts.
    reads: ReadAccess,
    /// Called when a result is ready off the UI thread (requests a repaint).
    wake: Arc<dyn Fn() + Send + Sync>,
    /// The Drag net tool's drags: the one running, the one closing, where they are solved and
    /// what the last one measured.
    net_drags: NetDrags,
}

/// How often cluster files are checked for changes.
pub const WATCH_INTERVAL: Duration = Duration::from_secs(1);

impl EditorApp {
    /// The editor on the given file, the gallery's `torus-monge.ron`, or the built-in default.
    pub fn new(options: AppOptions) -> Self {
        let registry = Arc::new(cnets_nodes::registry());
        let settings = Settings::load(&options.config_dir);
        let recovery = Recovery::new(&options.config_dir);
        // Written on a thread of its own: a large design's text does not stop the window.
        #[cfg(not(target_arch = "wasm32"))]
        let recovery = recovery.in_background(options.wake.clone());
        let mut modals = Modals::default();
        if let Some(offer) = recovery.find() {
            modals.open(Modal::Restore(offer));
        }
        let kept_recovery = recovery.held().map(|h| files::kept_label(&h));
        let message = String::new();
        let library_dirs = vec![settings.library_dir(), options.examples_dir.clone()];
        let torus = options.examples_dir.join("torus-monge.ron");
        // The start-up graph: the file given (an untitled copy when it is a shipped example), else
        // an untitled copy of the gallery's torus-monge.ron, else the built-in default.
        let (start, copy) = match &options.file {
            Some(f) => (Some(f.as_path()), is_example(&options.examples_dir, f)),
            None => (torus.is_file().then_some(torus.as_path()), true),
        };
        let start_options = |path: &std::path::Path| {
            let mut options = cnets_host::document_options(Some(path), &library_dirs);
            // Cluster files the document was allowed to read (its per-document settings).
            options.allow_read.extend(settings.allowed_reads(path));
            options
        };
        // A large start-up file is read off the UI thread: the window opens at once, on an empty
        // document the file replaces when it is read.
        let read_later = start
            .and_then(|path| Some((path, loading::large_file(path)?)))
            .map(|(path, bytes)| (path, bytes, start_options(path)));
        let doc = match start {
            Some(_) if read_later.is_some() => Some(GraphDocument::new(registry.clone())),
            Some(path) => match GraphDocument::open_with(path, &registry, &start_options(path)) {
                Ok(d) if copy => Some(d.into_untitled_copy()),
                Ok(d) => Some(d),
                Err(e) => {
                    // Not the default graph in its place: that would look like the file.
                    modals.open(Modal::LoadFailure(LoadFailure::new(path, &e)));
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
            message,
            settings,
            quit: false,
            modals,
            close_confirmed: false,
            inbox: None,
            last_title: String::new(),
            fresh: FreshDocument::default(),
            show_timings: true,
            evaluation: Evaluation::new(Worker::spawn(options.wake.clone())),
            recovery,
            kept_recovery,
            loading: None,
            waiting: None,
            clipboard: Clipboard::default(),
            gpu: options.gpu,
            examples: menus::examples_in(&options.examples_dir),
            examples_dir: options.examples_dir,
            library: Library::new(library_dirs),
            watching: Watching::default(),
            optimization: OptimizationPanel::new(options.wake.clone()),
            wake: options.wake,
            net_drags: NetDrags::default(),
            panels: Panels::default(),
            list_editors: ListEditors::default(),
            pointer: None,
            canvas_view: Vec::new(),
            canvas_serial: 0,
            palette_was_open: false,
            page: None,
            reads: ReadAccess::default(),
        };
        if let Some(p) = app.doc.path.clone() {
            app.doc.allowed_reads = app.settings.allowed_reads(&p);
        }
        if let Some(limit) = app.settings.planarity_limit() {
            app.viewport
                .display_mut()
                .options
                .set_planarity_limit(limit);
        }
        if let Some((path, bytes, options)) = read_later
            && !app.open_at_start_in_background(path, bytes, options.clone(), copy)
        {
            // No thread to read it on: read it now.
            let loaded = GraphDocument::open_with(path, &app.registry, &options);
            match loaded {
                Ok(d) if copy => app.replace_doc(d.into_untitled_copy()),
                Ok(d) => app.replace_doc(d),
                Err(e) => app
                    .modals
                    .open(Modal::LoadFailure(LoadFailure::new(path, &e))),
            }
        }
        app.watching.watch.changed(&app.doc.graph);
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

    fn replace_doc(&mut self, doc: GraphDocument) {
        // A file still being read, or one read and waiting, no longer opens: this document came
        // after it.
        self.loading = None;
        self.waiting = None;
        let previous = self.doc.generation();
        self.doc = doc;
        // What this document may read besides its folder (the editor's per-document settings).
        if let Some(p) = self.doc.path.clone() {
            self.doc.allowed_reads = self.settings.allowed_reads(&p);
        }
        self.modals.remove(|m| matches!(m, Modal::ReadPrompt(_)));
        self.reads.forget();
        // A new document is a new evaluation generation (fresh evaluator).
        self.doc.start_after(previous);
        self.canvas = Canvas::new();
        self.canvas_view.clear();
        self.fresh.opened();
        self.evaluation.statuses.clear();
        self.viewport.reset();
        self.evaluation.pending_change = Some(Instant::now());
        self.optimization.reset();
        self.list_editors.close_all();
        self.watching.watch.clear();
        self.watching.import_watch.clear();
        self.watching.watch.changed(&self.doc.graph);
    }

    /// The folders library graphs come from: the user library, then the examples folder.
    pub fn library_dirs(&self) -> Vec<PathBuf> {
        self.library.dirs.clone()
    }

    /// Load options for the document (its folder, then the library folders).
    fn load_options(&self) -> cnets_engine::file::LoadOptions {
        let mut options = cnets_host::document_options(self.doc.resolve_file(), &self.library.dirs);
        options
            .allow_read
            .extend(self.doc.allowed_reads.iter().cloned());
        options
    }
}
