//! The page (wasm32 only): starts the editor on `<canvas id="cnets">` with WebGL2, opens what the
//! URL names (`#graph=…`, else `?example=<name>`, else the default graph), and carries out the
//! editor's [`PageRequest`]s with the browser: the file picker, downloads, the clipboard and the
//! address bar. Files dropped on the page open (`.ron`) or become readable by the nodes that
//! import them. With `window.cnets_testing` set before it starts, `window.cnets_test` reports a few
//! figures for the browser test (`tests/web/browser.test.mjs`; [`test_state`]).

use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::rc::Rc;
use std::sync::Arc;

use cnets_editor::app::{AppOptions, EditorApp};
use cnets_editor::load_failure::LoadFailure;
use cnets_editor::page::PageRequest;
use cnets_editor::recovery::{LimitedStore, Recovery, RecoveryStore};
use cnets_editor::viewport::GpuTarget;
use cnets_editor::worker::Worker;
use eframe::egui_wgpu::{self, wgpu};
use wasm_bindgen::JsCast as _;
use wasm_bindgen::prelude::*;

use crate::opening::{Opening, size_text};

mod test_state;
use crate::remote::WebWorker;

/// Files picked in the browser's file picker, waiting for the next frame: (name, bytes).
type Inbox = Rc<RefCell<Vec<(String, Vec<u8>)>>>;

/// Starts the editor (called by `index.html` once the module is loaded; the evaluation worker
/// loads the same module and calls `worker_start` instead).
#[wasm_bindgen]
pub fn start() {
    eframe::WebLogger::init(log::LevelFilter::Warn).ok();
    wasm_bindgen_futures::spawn_local(async {
        if let Err(e) = run().await {
            let text = e.as_string().unwrap_or_else(|| format!("{e:?}"));
            web_sys::console::error_1(&format!("cnets: cannot start: {text}").into());
            if let Some(el) = document().and_then(|d| d.get_element_by_id("cnets-status")) {
                el.set_text_content(Some(&format!("cnets could not start: {text}")));
            }
        }
    });
}

fn document() -> Option<web_sys::Document> {
    web_sys::window()?.document()
}

async fn run() -> Result<(), JsValue> {
    let window = web_sys::window().ok_or("no window")?;
    let canvas = document()
        .and_then(|d| d.get_element_by_id("cnets"))
        .ok_or("no <canvas id=\"cnets\">")?
        .dyn_into::<web_sys::HtmlCanvasElement>()?;
    let query = window.location().search().unwrap_or_default();
    let mut options = eframe::WebOptions::default();
    // WebGL2 (through wgpu's GL backend) unless `?webgpu=1`: WebGPU is not everywhere yet, and in
    // headless Chromium it never presents (docs/web.md).
    let mut setup = egui_wgpu::WgpuSetupCreateNew::without_display_handle();
    setup.instance_descriptor.backends = if query.contains("webgpu=1") {
        wgpu::Backends::BROWSER_WEBGPU | wgpu::Backends::GL
    } else {
        wgpu::Backends::GL
    };
    options.wgpu_options.wgpu_setup = setup.into();
    eframe::WebRunner::new()
        .start(
            canvas,
            options,
            Box::new(|cc| Ok(Box::new(WebApp::new(cc)))),
        )
        .await?;
    if let Some(el) = document().and_then(|d| d.get_element_by_id("cnets-status")) {
        el.remove();
    }
    Ok(())
}

/// The editor in the page.
struct WebApp {
    app: EditorApp,
    /// The evaluation worker (the editor's `Worker` holds it too).
    remote: WebWorker,
    /// The drag worker (the editor holds it too).
    drag: crate::drag_remote::WebDrag,
    inbox: Inbox,
    ctx: egui::Context,
    frames: u64,
    /// The browser test opened the page (`window.cnets_testing`): the test state is kept
    /// ([`test_state`]).
    testing: bool,
    /// When the first picture was drawn (for the test state).
    first_picture_ms: Option<f64>,
    /// The page's size and the 3D view's in the last frame, the scene version framed, and
    /// whether the designer has touched anything yet.
    last_size: egui::Vec2,
    last_view: egui::Rect,
    framed_scene: u64,
    touched: bool,
    /// The first visit's hint is shown (until dismissed; remembered in local storage).
    welcome: bool,
    /// Where the hint was drawn in the last frame.
    welcome_rect: Option<egui::Rect>,
    /// The browser tab's title as last set.
    tab_title: String,
    /// Files read by the browser, waiting to be opened, and the large graph the worker reads.
    opening: Opening,
}

/// The local-storage key that remembers the first visit's hint was dismissed.
const WELCOMED: &str = "welcomed";

/// The largest design autosaved in local storage (4 MB: browsers keep 5–10 MB a site, counted in
/// UTF-16; larger designs say so in the status bar and are not autosaved).
const AUTOSAVE_MAX_BYTES: usize = 4_000_000;

/// The name of a document opened from a share link.
const SHARED: &str = "shared design";

fn now_ms() -> f64 {
    web_sys::window()
        .and_then(|w| w.performance())
        .map_or(0.0, |p| p.now())
}

impl WebApp {
    fn new(cc: &eframe::CreationContext<'_>) -> Self {
        crate::bundle::provide_all();
        let gpu = cc
            .wgpu_render_state
            .as_ref()
            .map(|rs| GpuTarget::from_render_state(rs, 1, None));
        let ctx = cc.egui_ctx.clone();
        let wake_ctx = ctx.clone();
        let wake: Arc<dyn Fn() + Send + Sync> = Arc::new(move || wake_ctx.request_repaint());
        let mut app = EditorApp::new(AppOptions {
            gpu,
            config_dir: PathBuf::from("/cnets"),
            file: None,
            examples_dir: PathBuf::from("graphs"),
            wake,
        });
        app.in_page();
        // The parameter panel docked at the start: a visitor finds the graph's sliders, toggles,
        // value lists and mappers in one place (narrow windows show it under the 3D view).
        app.show_parameters(true);
        // Evaluation in a Web Worker: the page answers input while a graph evaluates.
        let remote = WebWorker::start(ctx.clone());
        app.set_worker(Worker::remote(Box::new(remote.clone())));
        // Drags of the net solved in a second worker: the frames never wait for a solve.
        let drag = crate::drag_remote::WebDrag::new(ctx.clone(), remote.clone());
        app.set_net_drag_remote(Box::new(drag.clone()));
        // Autosave into the browser's local storage, with the desktop's recovery offer.
        app.set_recovery(Recovery::with_store(
            Path::new("localStorage"),
            Box::new(LimitedStore {
                inner: Box::new(LocalStore),
                max_bytes: AUTOSAVE_MAX_BYTES,
            }),
        ));
        app.set_examples(
            crate::bundle::example_names()
                .into_iter()
                .map(|n| PathBuf::from(format!("graphs/{n}.ron")))
                .collect(),
        );
        let mut me = Self {
            app,
            remote,
            drag,
            inbox: Rc::default(),
            ctx,
            frames: 0,
            testing: test_state::test_flag("cnets_testing"),
            first_picture_ms: None,
            last_size: egui::Vec2::ZERO,
            last_view: egui::Rect::NOTHING,
            framed_scene: 0,
            touched: false,
            welcome: LocalStore.read(WELCOMED).is_none(),
            welcome_rect: None,
            opening: Opening::default(),
            tab_title: String::new(),
        };
        me.open_from_url();
        me
    }

    /// Opens what the address names: a shared graph (`#graph=…`), else `?example=<name>`, else the
    /// gallery's torus-monge (as the desktop editor starts).
    fn open_from_url(&mut self) {
        let Some(location) = web_sys::window().map(|w| w.location()) else {
            return;
        };
        let hash = location.hash().unwrap_or_default();
        if let Some(shared) = crate::link::from_fragment(&hash) {
            match shared {
                Ok(ron) => {
                    if self.app.open_text(&ron, Path::new("shared-link.ron")) {
                        self.app.name_document(SHARED);
                        self.app.set_message("opened the shared design of the link");
                    } else {
                        // The dialog lists the graph's problems; no other graph stands in.
                        self.app.open_empty(&format!("{SHARED} (not opened)"));
                        if let Some(f) = self.app.load_failure_mut() {
                            f.kept_document = false;
                        }
                    }
                }
                Err(e) => {
                    self.app.open_empty(&format!("{SHARED} (not opened)"));
                    let mut failure = LoadFailure::new(
                        Path::new("the shared link"),
                        &cnets_engine::file::LoadError::message(format!("{e}.")),
                    );
                    failure.kept_document = false;
                    self.app.show_load_failure(failure);
                    self.app.set_message(format!("cannot open the link: {e}"));
                }
            }
            // A link is its own document: another one's unsaved work is kept, not offered.
            self.app.offer_recovery_for(None);
            return;
        }
        let query = location.search().unwrap_or_default();
        let name = crate::link::example_of_query(&query).unwrap_or("torus-monge");
        let path = PathBuf::from(format!("graphs/{name}.ron"));
        match crate::bundle::example(name) {
            Some(ron) => {
                self.app.open_text(ron, &path);
            }
            None => self.app.set_message(format!(
                "no example named '{name}': File › Open example lists them"
            )),
        }
        // The restore offer belongs to the document it was saved from: another example's
        // unsaved work is kept aside (File ▸ Restore kept work), never offered over this one.
        self.app.offer_recovery_for(Some(&path));
    }

    /// Files picked or dropped: a graph opens as the document; other files become readable by
    /// the nodes that import them (by file name) and the graph is evaluated again.
    fn receive(&mut self, files: Vec<(String, Vec<u8>)>) {
        for (name, bytes) in files {
            if crate::opening::is_large_graph(&name, bytes.len()) {
                // Read by the worker: the page keeps answering (docs/web.md, "Large files").
                let library = self.app.library().dirs.iter();
                let library = library.map(|d| d.to_string_lossy().into_owned()).collect();
                let len = bytes.len();
                let token = self.remote.read_file(&name, library, bytes);
                self.opening.start_reading(token, &name, len, now_ms());
            } else if name.ends_with(".ron") {
                let text = String::from_utf8_lossy(&bytes).into_owned();
                // The latest file wins over a large one still being read; unsaved changes are
                // asked about first.
                self.opening.cancel_reading();
                self.app.receive_text(&text, Path::new(&name));
            } else {
                let len = bytes.len();
                // The nodes that import it read it in the worker (the page keeps a copy for
                // exports).
                self.remote.provide(&name, bytes.clone());
                cnets_engine::files::memory::provide(&name, bytes);
                self.app.reevaluate();
                self.app.set_message(format!(
                    "{name} ({len} bytes) is readable by the nodes that import it"
                ));
            }
        }
    }

    /// Opens the large graphs the worker has read (the latest one dropped or picked).
    fn open_read_files(&mut self) {
        for (token, result) in self.remote.take_read() {
            let started = now_ms();
            let name = self.opening.answered(token, started);
            if let Ok(parsed) = &result {
                // The worker keeps these literals: requests name them (and forget them once no
                // document holds them: a late answer's, a file that did not load).
                for (at, value) in &parsed.literals {
                    self.remote.adopt_literal(at.key, value.clone());
                }
            }
            // An answer for a file no longer to open (another was opened meanwhile) is dropped.
            let Some(name) = name else { continue };
            let origin = PathBuf::from(&name);
            let loaded = result.and_then(|parsed| {
                let library = &self.app.library().dirs;
                crate::opening::document_of(parsed, &origin, self.app.registry(), library)
            });
            self.app.receive_document(loaded, &origin);
            if let Some(large) = self.opening.last_large.as_mut() {
                large.page_ms = Some(now_ms() - started);
            }
        }
    }

    fn carry_out(&mut self, request: PageRequest) {
        let done = match request {
            PageRequest::PickFile => pick_file(self.inbox.clone(), self.ctx.clone()),
            PageRequest::Download { name, bytes } => download(&name, &bytes),
            PageRequest::CopyLink { ron } => {
                let fragment = crate::link::fragment(&ron);
                copy_link(&fragment).map(|url| {
                    // The whole link's length, as the address bar shows it.
                    self.app.set_message(format!(
                        "link copied ({} characters): it is in the address bar too",
                        url.chars().count()
                    ));
                })
            }
        };
        if let Err(e) = done {
            let text = e.as_string().unwrap_or_else(|| format!("{e:?}"));
            self.app.set_message(format!("the browser refused: {text}"));
        }
    }
}

impl WebApp {
    /// The browser tab's title follows the document's ("facade.ron * — cnets").
    fn mirror_title(&mut self) {
        let title = format!("{} — cnets", self.app.doc().title());
        if title != self.tab_title
            && let Some(d) = document()
        {
            d.set_title(&title);
            self.tab_title = title;
        }
    }
}

impl eframe::App for WebApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let picked = std::mem::take(&mut *self.inbox.borrow_mut());
        if !picked.is_empty() {
            self.opening.arrive(picked);
        }
        crate::backing::keep_device_pixels(ui.ctx());
        // (`window.cnets_hold_opening = true`: the browser test keeps the notice up to picture it.)
        let due = if self.testing && test_state::test_flag("cnets_hold_opening") {
            Vec::new()
        } else {
            self.opening.due()
        };
        if !due.is_empty() {
            self.receive(due);
        }
        self.open_read_files();
        self.opening.frame();
        // Files dropped on the page are read like picked ones (the browser reads asynchronously).
        let dropped: Vec<web_sys::File> = ui.ctx().input(|i| {
            i.raw
                .dropped_files
                .iter()
                .filter_map(|f| f.web_file().cloned())
                .collect()
        });
        for file in dropped {
            self.app.set_message(format!(
                "reading {} ({})…",
                file.name(),
                size_text(file.size() as usize)
            ));
            read_into(file, self.inbox.clone(), self.ctx.clone());
        }
        if self.testing {
            self.test_request();
        }
        if let Some(notice) = self.remote.take_notice() {
            self.app.set_message(notice);
        }
        // The canvas element gets its CSS size, and the panels theirs, over the first frames:
        // frame the graph and the geometry again while the page settles (and when the first
        // scene of a document arrives), until the designer touches something.
        let size = ui.ctx().content_rect().size();
        self.touched |= ui
            .ctx()
            .input(|i| i.pointer.any_down() || !i.keys_down.is_empty());
        if !self.touched {
            if size != self.last_size {
                self.last_size = size;
                self.app.frame_again();
            }
            let view = self.app.viewport().rect();
            let scene = self.app.viewport().scene_version();
            if view != self.last_view || (scene != self.framed_scene && self.frames < 60) {
                self.last_view = view;
                self.framed_scene = scene;
                self.app.viewport_mut().fit();
            }
        }
        if !self.touched && self.frames < 60 {
            // egui paints on events only: give the framing its frames.
            ui.ctx().request_repaint();
        }
        // A drag's requests keep their slow rest in the worker until the pointer is released.
        self.remote
            .set_held(ui.ctx().input(|i| i.pointer.any_down()));
        self.app.ui(ui);
        if let Some(notice) = self.opening.notice() {
            cnets_editor::opening_notice::show(ui.ctx(), &notice.title, &notice.detail);
            self.app.set_message(notice.sentence());
        }
        if self.opening.pending() {
            ui.ctx().request_repaint();
        }
        self.welcome_rect = None;
        // The hint waits while a dialog asks or reports something: it would cover it.
        let dialog = self.app.modals().shown().is_some();
        if self.welcome && !dialog {
            let shown = cnets_editor::welcome::show(
                ui.ctx(),
                self.app.viewport().rect(),
                self.app.viewport().last_frame().labels_bottom,
            );
            self.welcome_rect = Some(shown.rect);
            if shown.dismissed {
                self.welcome = false;
                let _ = LocalStore.write(WELCOMED, "1");
            }
        }
        self.mirror_title();
        let requests = self.app.take_page_requests();
        for r in requests {
            self.carry_out(r);
        }
        self.frames += 1;
        if self.testing {
            self.report();
        }
    }

    fn raw_input_hook(&mut self, _ctx: &egui::Context, raw_input: &mut egui::RawInput) {
        self.app.raw_input(raw_input);
    }
}

/// The recovery texts in the page's local storage (`cnets.recovery.ron`, `cnets.recovery.path`):
/// they outlive a closed tab or a crashed page, per site, as the desktop's recovery files do.
struct LocalStore;

fn local_storage() -> Option<web_sys::Storage> {
    web_sys::window()?.local_storage().ok().flatten()
}

impl RecoveryStore for LocalStore {
    fn read(&self, name: &str) -> Option<String> {
        local_storage()?
            .get_item(&format!("cnets.{name}"))
            .ok()
            .flatten()
    }

    fn write(&mut self, name: &str, text: &str) -> std::io::Result<()> {
        let refused = |what: &str| std::io::Error::other(what.to_string());
        local_storage()
            .ok_or_else(|| refused("not available"))?
            .set_item(&format!("cnets.{name}"), text)
            .map_err(|_| refused("full or refused"))
    }

    fn remove(&mut self, name: &str) {
        if let Some(s) = local_storage() {
            let _ = s.remove_item(&format!("cnets.{name}"));
        }
    }

    fn place(&self) -> &str {
        "the page's local storage"
    }
}

/// Shows the browser's file picker; the chosen files arrive in `inbox` (and wake the UI).
fn pick_file(inbox: Inbox, ctx: egui::Context) -> Result<(), JsValue> {
    let doc = document().ok_or("no document")?;
    let input = doc
        .create_element("input")?
        .dyn_into::<web_sys::HtmlInputElement>()?;
    input.set_type("file");
    input.set_multiple(true);
    input.set_accept(".ron,.csv,.svg,.obj,.stl,.ply,.glb,.gltf,.txt,.json");
    let chosen = input.clone();
    let on_change = Closure::<dyn FnMut()>::new(move || {
        let Some(files) = chosen.files() else { return };
        for k in 0..files.length() {
            if let Some(file) = files.get(k) {
                read_into(file, inbox.clone(), ctx.clone());
            }
        }
    });
    input.set_onchange(Some(on_change.as_ref().unchecked_ref()));
    // The input lives as long as the page holds the closure: one picker at a time.
    on_change.forget();
    input.click();
    Ok(())
}

/// Reads a browser file into `inbox` (asynchronously) and wakes the UI.
fn read_into(file: web_sys::File, inbox: Inbox, ctx: egui::Context) {
    wasm_bindgen_futures::spawn_local(async move {
        let name = file.name();
        match wasm_bindgen_futures::JsFuture::from(file.array_buffer()).await {
            Ok(buffer) => {
                let bytes = js_sys::Uint8Array::new(&buffer).to_vec();
                inbox.borrow_mut().push((name, bytes));
                ctx.request_repaint();
            }
            Err(_) => web_sys::console::warn_1(&format!("cnets: cannot read {name}").into()),
        }
    });
}

/// Offers `bytes` as a download named `name`.
fn download(name: &str, bytes: &[u8]) -> Result<(), JsValue> {
    let doc = document().ok_or("no document")?;
    let array = js_sys::Uint8Array::from(bytes);
    let parts = js_sys::Array::of1(&array);
    let options = web_sys::BlobPropertyBag::new();
    options.set_type("application/octet-stream");
    let blob = web_sys::Blob::new_with_u8_array_sequence_and_options(&parts, &options)?;
    let url = web_sys::Url::create_object_url_with_blob(&blob)?;
    let a = doc
        .create_element("a")?
        .dyn_into::<web_sys::HtmlAnchorElement>()?;
    a.set_href(&url);
    a.set_download(name);
    a.click();
    web_sys::Url::revoke_object_url(&url)?;
    Ok(())
}

/// Puts the share link into the address bar (without reloading) and, where the browser allows
/// it, on the clipboard; returns the link.
fn copy_link(fragment: &str) -> Result<String, JsValue> {
    let window = web_sys::window().ok_or("no window")?;
    let location = window.location();
    let base = format!(
        "{}{}{}",
        location.origin()?,
        location.pathname()?,
        location.search()?
    );
    let url = format!("{base}{fragment}");
    window
        .history()?
        .replace_state_with_url(&JsValue::NULL, "", Some(&url))?;
    // The clipboard needs a secure context and the page's focus: a refusal leaves the address bar.
    let promise = window.navigator().clipboard().write_text(&url);
    wasm_bindgen_futures::spawn_local(async move {
        let _ = wasm_bindgen_futures::JsFuture::from(promise).await;
    });
    Ok(url)
}
