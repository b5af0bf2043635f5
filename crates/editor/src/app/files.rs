//! Files and documents: open, open an example, save, what the unsaved-changes question replaces
//! the document with, recovery.

use crate::document::GraphDocument;
use crate::file_dialog::FileDialog;
use crate::load_failure::LoadFailure;
use crate::recovery::{Recovered, Recovery};
use crate::unsaved::Replace;
use cnets_engine::file::LoadError;
use std::path::Path;
use std::path::PathBuf;

use super::{EditorApp, Modal};

impl EditorApp {
    /// The file dialog being shown, if any (tests type a path into it).
    pub fn dialog_mut(&mut self) -> Option<&mut FileDialog> {
        self.modals.file_dialog_mut()
    }

    /// The file dialog being shown, if any.
    pub fn dialog(&self) -> Option<&FileDialog> {
        self.modals.file_dialog()
    }

    /// Whether a restore from a previous session's recovery file is being offered.
    pub fn restore_offered(&self) -> bool {
        self.modals.restore_offer().is_some()
    }

    /// Takes the restore offer out of the dialogs (answered, or put aside).
    fn take_restore_offer(&mut self) -> Option<Modal> {
        self.modals.remove(|m| matches!(m, Modal::Restore(_)))
    }

    /// Whether autosave has written the document as it is now (its version) to the recovery file.
    pub fn autosaved(&self) -> bool {
        self.recovery.saved_version() == Some(self.doc.version())
    }

    /// Restores the recovery file (the crash-restore dialog's "Restore").
    pub fn restore(&mut self) {
        if let Some(Modal::Restore(r)) = self.take_restore_offer() {
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
        self.take_restore_offer();
        if let Some(offer) = recovery.find() {
            self.modals.open(Modal::Restore(offer));
        }
        self.kept_recovery = recovery.held().map(|h| kept_label(&h));
        self.recovery = recovery;
    }

    /// Offers the recovery only with its own document: the web page calls this once it opened
    /// what its address asks for (`opened`: an example's path; `None` for a shared link, which
    /// is never offered another document's work). Another document's recovery is kept aside
    /// (File ▸ Restore kept work), not offered over this one nor overwritten by its autosave; a
    /// kept recovery of `opened` itself is brought back and offered.
    pub fn offer_recovery_for(&mut self, opened: Option<&Path>) {
        let identity = |r: &Recovered| r.path.clone().or_else(|| r.origin.clone());
        let belongs = |r: &Recovered| opened.is_some() && identity(r).as_deref() == opened;
        match self.modals.restore_offer() {
            Some(r) if !belongs(r) => {
                self.take_restore_offer();
                if let Err(e) = self.recovery.hold() {
                    self.message =
                        format!("the unsaved work of another page could not be kept: {e}");
                }
            }
            Some(_) => {}
            None => {
                if self.recovery.held().is_some_and(|h| belongs(&h))
                    && self.recovery.unhold().is_ok()
                    && let Some(offer) = self.recovery.find()
                {
                    self.modals.open(Modal::Restore(offer));
                }
            }
        }
        self.kept_recovery = self.recovery.held().map(|h| kept_label(&h));
    }

    /// What File ▸ Restore kept work names, when another document's recovery is kept.
    pub fn kept_recovery(&self) -> Option<&str> {
        self.kept_recovery.as_deref()
    }

    /// File ▸ Restore kept work: opens the kept recovery as the document (unsaved, as a restore
    /// does). Refused while the document has unsaved changes (save or discard them first: their
    /// own recovery would be replaced).
    pub fn restore_kept(&mut self) {
        if self.doc.is_dirty() {
            self.message =
                "save the open document first (File › Save): restoring kept work replaces it"
                    .into();
            return;
        }
        let Some(kept) = self.recovery.held() else {
            self.kept_recovery = None;
            return;
        };
        self.modals.open(Modal::Restore(kept));
        self.restore();
        if self.modals.restore_offer().is_none() {
            self.recovery.clear_held();
            self.kept_recovery = None;
        }
    }

    /// Closes the restore offer without deciding (Escape): the work is kept aside, listed as
    /// File › Restore kept work, and not overwritten by this session's autosave.
    pub fn keep_recovery_for_later(&mut self) {
        self.take_restore_offer();
        match self.recovery.hold() {
            Ok(()) => {
                self.message = "the unsaved work is kept: File › Restore kept work opens it".into()
            }
            Err(e) => self.message = format!("the unsaved work could not be kept aside: {e}"),
        }
        self.kept_recovery = self.recovery.held().map(|h| kept_label(&h));
    }

    /// Declines the restore and removes the recovery file.
    pub fn discard_recovery(&mut self) {
        self.take_restore_offer();
        self.recovery.clear();
    }

    /// Asks to replace or close the document: carried out at once when everything is saved,
    /// else after the Save / Don't save / Cancel question (see [`crate::unsaved`]).
    pub fn request(&mut self, r: Replace) {
        if self.doc.is_dirty() && !(r == Replace::Quit && self.close_confirmed) {
            self.modals.open(Modal::Unsaved(r));
        } else {
            self.perform(r);
        }
    }

    /// Carries out a replacement without asking.
    pub(super) fn perform(&mut self, r: Replace) {
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
            Replace::Loaded(p) => self.open_waiting(&p),
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
    /// diagnostics are shown. Returns whether it opened — or, for a large file, began to be read
    /// off the UI thread (it opens in a later frame: [`EditorApp::loading`]).
    pub fn open(&mut self, path: &Path) -> bool {
        if self.is_example(path) {
            return self.open_example(path);
        }
        let mut options = cnets_host::document_options(Some(path), &self.library.dirs);
        // Cluster files the document was allowed to read (its per-document settings).
        options.allow_read.extend(self.settings.allowed_reads(path));
        if let Some(bytes) = self.reads_in_background(path)
            && self.open_in_background(path, bytes, options.clone())
        {
            return true;
        }
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

    pub(super) fn fail_load(&mut self, path: &Path, error: &LoadError) {
        self.message = format!("cannot open {}: the document is unchanged", path.display());
        self.modals
            .open(Modal::LoadFailure(LoadFailure::new(path, error)));
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
                // The reads allowed for the document go with it to its (new) file.
                for allowed in &self.doc.allowed_reads {
                    self.settings.allow_read(path, allowed);
                }
                self.recovery.clear();
                self.message = format!("saved {}", path.display());
            }
            Err(e) => self.message = e.to_string(),
        }
        if !self.doc.is_dirty()
            && let Some(r) = self.modals.after_save.take()
        {
            self.perform(r);
        }
    }

    /// Opens graph text as an untitled document (the web page: a bundled example, a file picked
    /// or dropped, a share link); `origin` names where it came from (relative imports resolve
    /// against its folder). When it does not load, the document stays and the diagnostics are
    /// shown. Returns whether it opened.
    pub fn open_text(&mut self, text: &str, origin: &Path) -> bool {
        let loaded = self.read_text(text, origin);
        self.open_loaded(loaded, origin)
    }

    /// Reads graph text that came from `origin` (its relative imports resolve against its
    /// folder) with the library's clusters.
    pub(super) fn read_text(&self, text: &str, origin: &Path) -> Result<GraphDocument, LoadError> {
        let options = cnets_host::document_options(Some(origin), &self.library.dirs);
        let name = origin.display().to_string();
        GraphDocument::from_text_with(text, &name, None, &self.registry, &options)
    }

    /// Opens a loaded document as [`EditorApp::open_text`] opens text: untitled, or the
    /// diagnostics shown when it did not load. Returns whether it opened.
    fn open_loaded(&mut self, loaded: Result<GraphDocument, LoadError>, origin: &Path) -> bool {
        let name = origin.display().to_string();
        match loaded {
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

    /// Asks to close: closes at once when everything is saved, else asks first.
    pub fn request_close(&mut self) {
        self.request(Replace::Quit);
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
pub(super) fn user_folder(examples_dir: &Path) -> PathBuf {
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

/// How File ▸ Restore kept work names a kept recovery: its file, the example it copies, or
/// "untitled".
pub(super) fn kept_label(r: &Recovered) -> String {
    let name = |p: &Path| {
        p.file_name()
            .map_or_else(|| p.display().to_string(), |n| n.to_string_lossy().into())
    };
    match (&r.path, &r.origin) {
        (Some(p), _) => name(p),
        (None, Some(o)) => format!("untitled (copy of {})", name(o)),
        (None, None) => "untitled".into(),
    }
}
