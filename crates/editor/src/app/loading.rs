//! Large graph files opened during a session (File ▸ Open, Open recent, a file dropped or sent
//! to the window) are read on a thread of their own: parsing 35 MB takes a second or two, and the
//! window keeps answering meanwhile under a notice. The document is replaced when the file is
//! read; a document opened meanwhile wins (the late one is dropped), and a document edited
//! meanwhile is not replaced without the unsaved-changes question (`arrivals`). The start-up file is read the
//! same way: the window opens at once. Files are read in the frame
//! they are opened below [`LARGE_GRAPH_BYTES`], and always in the browser (no threads; its page
//! has its evaluation worker read large files instead).

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::mpsc::{Receiver, RecvTimeoutError, TryRecvError, channel};

use cnets_engine::Registry;
use cnets_engine::file::{LoadError, LoadOptions};
use web_time::{Duration, Instant};

use super::EditorApp;
use super::arrivals::Arrived;
use crate::document::GraphDocument;
use crate::opening_notice::megabytes;

/// A graph file of at least this many bytes is read off the UI thread (4 MiB: about a quarter
/// of a second of parsing).
pub const LARGE_GRAPH_BYTES: u64 = 4 << 20;

/// A large file being read.
pub(crate) struct Loading {
    path: PathBuf,
    bytes: u64,
    since: Instant,
    result: Receiver<Result<GraphDocument, LoadError>>,
    /// The document's [`GraphDocument::version`] when the read began: an edit made while the
    /// file was read is not dropped without asking.
    version_at_start: u64,
    /// Opens as an untitled copy (a shipped example given at start-up).
    untitled_copy: bool,
}

impl Loading {
    /// Starts reading `path` on a thread; `None` when no thread can be started.
    fn start(
        path: &Path,
        bytes: u64,
        registry: Arc<Registry>,
        options: LoadOptions,
        version_at_start: u64,
    ) -> Option<Self> {
        let (report, result) = channel();
        let file = path.to_path_buf();
        std::thread::Builder::new()
            .name("cnets-open".into())
            .spawn(move || {
                let _ = report.send(GraphDocument::open_with(&file, &registry, &options));
            })
            .ok()?;
        Some(Self {
            path: path.to_path_buf(),
            bytes,
            since: Instant::now(),
            result,
            version_at_start,
            untitled_copy: false,
        })
    }
}

/// The size of `path` when it is large enough to be read off the UI thread on the desktop
/// ([`LARGE_GRAPH_BYTES`]), else `None` (and always in the browser).
pub(super) fn large_file(path: &Path) -> Option<u64> {
    if cfg!(target_arch = "wasm32") {
        return None;
    }
    let bytes = std::fs::metadata(path).ok()?.len();
    (bytes >= LARGE_GRAPH_BYTES).then_some(bytes)
}

impl EditorApp {
    /// The size of `path` when it is read off the UI thread when opened (a large file on the
    /// desktop), else `None`.
    pub(super) fn reads_in_background(&self, path: &Path) -> Option<u64> {
        if self.page.is_some() {
            return None;
        }
        large_file(path)
    }

    /// Starts reading a large file (`bytes` long) on a thread; `false` when it could not start
    /// (read it now).
    pub(super) fn open_in_background(
        &mut self,
        path: &Path,
        bytes: u64,
        options: LoadOptions,
    ) -> bool {
        let version = self.doc.version();
        match Loading::start(path, bytes, self.registry.clone(), options, version) {
            Some(loading) => {
                self.message = format!("opening {} ({})…", path.display(), megabytes(bytes));
                self.loading = Some(loading);
                true
            }
            None => false,
        }
    }

    /// Like [`EditorApp::open_in_background`] for the start-up file: the window opens at once
    /// on an empty document, and the file, an untitled copy when `untitled_copy` (a shipped
    /// example), replaces it when read.
    pub(super) fn open_at_start_in_background(
        &mut self,
        path: &Path,
        bytes: u64,
        options: LoadOptions,
        untitled_copy: bool,
    ) -> bool {
        let started = self.open_in_background(path, bytes, options);
        if let Some(loading) = &mut self.loading {
            loading.untitled_copy = untitled_copy;
        }
        started
    }

    /// The file being read off the UI thread, if any: its path.
    pub fn loading(&self) -> Option<&Path> {
        self.loading.as_ref().map(|l| l.path.as_path())
    }

    /// Waits (up to `timeout`) for the file being read and opens it as the next frame would (the
    /// screenshot and benchmark modes, tests). Returns whether a file was still being read after
    /// the timeout.
    pub fn wait_for_loading(&mut self, timeout: Duration) -> bool {
        let Some(loading) = &self.loading else {
            return false;
        };
        match loading.result.recv_timeout(timeout) {
            Ok(result) => {
                self.file_read(result);
                false
            }
            Err(RecvTimeoutError::Timeout) => true,
            Err(RecvTimeoutError::Disconnected) => {
                self.reader_stopped();
                false
            }
        }
    }

    /// Called once a frame: opens the file read off the UI thread once it is read (asking first
    /// when the document was edited meanwhile), else shows the notice and asks for another frame.
    pub(super) fn poll_loading(&mut self, ctx: &egui::Context) {
        let Some(loading) = &self.loading else {
            return;
        };
        match loading.result.try_recv() {
            Ok(result) => self.file_read(result),
            Err(TryRecvError::Empty) => {
                let path = &loading.path;
                let name = path.file_name().map_or_else(
                    || path.display().to_string(),
                    |n| n.to_string_lossy().into_owned(),
                );
                let title = crate::opening_notice::title(&name, loading.bytes);
                crate::opening_notice::show(ctx, &title, crate::opening_notice::DETAIL);
                ctx.request_repaint_after(std::time::Duration::from_millis(50));
            }
            Err(TryRecvError::Disconnected) => self.reader_stopped(),
        }
    }

    /// The reader's answer: the document opens (through [`EditorApp::open_arrived`]: asked about
    /// first when the document was edited while the file was read), or its diagnostics show.
    fn file_read(&mut self, result: Result<GraphDocument, LoadError>) {
        let Some(loading) = self.loading.take() else {
            return;
        };
        match result {
            Ok(doc) if loading.untitled_copy => {
                let opened = format!(
                    "opened a copy of the example {}: saving asks where",
                    loading.path.display()
                );
                let arrived = Arrived {
                    path: loading.path,
                    doc: doc.into_untitled_copy(),
                    opened,
                    recent: false,
                };
                self.open_arrived(arrived, Some(loading.version_at_start));
            }
            Ok(doc) => {
                let opened = format!(
                    "opened {} ({}, read in {:.1} s)",
                    loading.path.display(),
                    megabytes(loading.bytes),
                    loading.since.elapsed().as_secs_f64()
                );
                let arrived = Arrived {
                    path: loading.path,
                    doc,
                    opened,
                    recent: true,
                };
                self.open_arrived(arrived, Some(loading.version_at_start));
            }
            Err(e) => self.fail_load(&loading.path, &e),
        }
    }

    fn reader_stopped(&mut self) {
        let path = self.loading.take().map(|l| l.path).unwrap_or_default();
        self.fail_load(
            &path,
            &LoadError::message("the file could not be read (its reader stopped)"),
        );
    }
}
