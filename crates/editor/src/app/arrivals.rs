//! Documents that arrive while the designer may be editing: a large file read off the UI thread
//! (`loading`), a graph file dropped on or picked in the web page (read there or by its worker).
//! An arrived document replaces the document at once unless that would drop unsaved edits; then
//! it waits while the unsaved-changes question ([`Replace::Loaded`]) is asked, and is let go when
//! the answer is Cancel.

use std::path::{Path, PathBuf};

use super::EditorApp;
use crate::document::GraphDocument;
use crate::unsaved::Replace;
use cnets_engine::file::LoadError;

/// A document read elsewhere, to replace the one being edited.
pub struct Arrived {
    /// The file it was read from (named by the question and the status bar).
    pub path: PathBuf,
    /// The document.
    pub doc: GraphDocument,
    /// The status bar's line once it is open.
    pub opened: String,
    /// Whether its file goes into Open recent.
    pub recent: bool,
}

/// An arrived document held while the question about it is asked.
pub(crate) struct Waiting {
    arrived: Arrived,
    /// Whether the question was asked (it is asked once no other question is up).
    asked: bool,
}

impl EditorApp {
    /// Opens `arrived` in place of the document, unless the document has unsaved changes the
    /// designer was not asked about: with `edited_since` `None`, any unsaved change; with
    /// `Some(version)`, changes made after that [`GraphDocument::version`] (the question was
    /// asked before the file was read). Then it waits for the unsaved-changes question.
    pub fn open_arrived(&mut self, arrived: Arrived, edited_since: Option<u64>) {
        let edited = self.doc.is_dirty() && edited_since.is_none_or(|v| self.doc.version() != v);
        if edited {
            self.message = format!(
                "{} is read: the document has unsaved changes",
                arrived.path.display()
            );
            self.waiting = Some(Waiting {
                arrived,
                asked: false,
            });
        } else {
            self.install(arrived);
        }
    }

    /// Opens a graph file's text received in the web page (dropped or picked): as
    /// [`EditorApp::open_arrived`] when it loads (untitled, named by the file), else the
    /// diagnostics are shown and the document stays. Returns whether it loaded.
    pub fn receive_text(&mut self, text: &str, origin: &Path) -> bool {
        let loaded = self.read_text(text, origin);
        self.receive_document(loaded, origin)
    }

    /// Like [`EditorApp::receive_text`] for a document read elsewhere (the page's worker).
    pub fn receive_document(
        &mut self,
        loaded: Result<GraphDocument, LoadError>,
        origin: &Path,
    ) -> bool {
        match loaded {
            Ok(mut doc) => {
                let name = origin.display().to_string();
                doc.origin = Some(origin.to_path_buf());
                doc.name = Some(name.clone());
                let arrived = Arrived {
                    path: origin.to_path_buf(),
                    doc,
                    opened: format!("opened {name}"),
                    recent: false,
                };
                self.open_arrived(arrived, None);
                true
            }
            Err(e) => {
                self.fail_load(origin, &e);
                false
            }
        }
    }

    /// The arrived document waiting for the question's answer, if any: its file.
    pub fn waiting(&self) -> Option<&Path> {
        self.waiting.as_ref().map(|w| w.arrived.path.as_path())
    }

    /// Opens the waiting document the question was about ([`Replace::Loaded`]).
    pub(super) fn open_waiting(&mut self, path: &Path) {
        match self.waiting.take() {
            Some(w) if w.arrived.path == path => self.install(w.arrived),
            other => self.waiting = other,
        }
    }

    /// Called once a frame: asks about the waiting document once no other question is up, and
    /// lets it go once the question was answered without opening it (Cancel).
    pub(super) fn poll_waiting(&mut self) {
        let question_up =
            self.modals.unsaved_question().is_some() || self.modals.after_save.is_some();
        let Some(waiting) = &mut self.waiting else {
            return;
        };
        if question_up {
            return;
        }
        if waiting.asked {
            let path = waiting.arrived.path.display().to_string();
            self.waiting = None;
            self.message = format!("{path} was not opened: the document stays");
        } else {
            waiting.asked = true;
            self.modals.open(super::Modal::Unsaved(Replace::Loaded(
                waiting.arrived.path.clone(),
            )));
        }
    }

    fn install(&mut self, arrived: Arrived) {
        self.replace_doc(arrived.doc);
        if arrived.recent {
            self.settings.add_recent(&arrived.path);
        }
        self.message = arrived.opened;
    }
}
