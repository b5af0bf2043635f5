//! Large graph files opened during a session (File ▸ Open, Open recent, a file dropped or sent
//! to the window) are read on a thread of their own: parsing 35 MB takes a second or two, and the
//! window keeps answering meanwhile under a notice. The document is replaced when the file is
//! read; a document opened meanwhile wins (the late one is dropped). Files are read in the frame
//! they are opened below [`LARGE_GRAPH_BYTES`], and always in the browser (no threads; its page
//! has its evaluation worker read large files instead).

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::mpsc::{Receiver, TryRecvError, channel};

use cnets_engine::Registry;
use cnets_engine::file::LoadOptions;
use web_time::Instant;

use super::EditorApp;
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
    result: Receiver<Result<GraphDocument, String>>,
}

impl Loading {
    /// Starts reading `path` on a thread; `None` when no thread can be started.
    fn start(
        path: &Path,
        bytes: u64,
        registry: Arc<Registry>,
        options: LoadOptions,
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
        })
    }
}

impl EditorApp {
    /// The size of `path` when it is read off the UI thread when opened (a large file on the
    /// desktop), else `None`.
    pub(super) fn reads_in_background(&self, path: &Path) -> Option<u64> {
        if self.page.is_some() || cfg!(target_arch = "wasm32") {
            return None;
        }
        let bytes = std::fs::metadata(path).ok()?.len();
        (bytes >= LARGE_GRAPH_BYTES).then_some(bytes)
    }

    /// Starts reading a large file (`bytes` long) on a thread; `false` when it could not start
    /// (read it now).
    pub(super) fn open_in_background(
        &mut self,
        path: &Path,
        bytes: u64,
        options: LoadOptions,
    ) -> bool {
        match Loading::start(path, bytes, self.registry.clone(), options) {
            Some(loading) => {
                self.message = format!("opening {} ({})…", path.display(), megabytes(bytes));
                self.loading = Some(loading);
                true
            }
            None => false,
        }
    }

    /// The file being read off the UI thread, if any: its path.
    pub fn loading(&self) -> Option<&Path> {
        self.loading.as_ref().map(|l| l.path.as_path())
    }

    /// Called once a frame: opens the file read off the UI thread once it is read, else shows
    /// the notice and asks for another frame.
    pub(super) fn poll_loading(&mut self, ctx: &egui::Context) {
        let Some(loading) = &self.loading else { return };
        match loading.result.try_recv() {
            Ok(result) => {
                let Some(loading) = self.loading.take() else {
                    return;
                };
                let path = loading.path;
                match result {
                    Ok(d) => {
                        self.replace_doc(d);
                        self.settings.add_recent(&path);
                        self.message = format!(
                            "opened {} ({}, read in {:.1} s)",
                            path.display(),
                            megabytes(loading.bytes),
                            loading.since.elapsed().as_secs_f64()
                        );
                    }
                    Err(e) => self.fail_load(&path, &e),
                }
            }
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
            Err(TryRecvError::Disconnected) => {
                let path = self.loading.take().map(|l| l.path).unwrap_or_default();
                self.fail_load(&path, "the file could not be read (its reader stopped)");
            }
        }
    }
}
