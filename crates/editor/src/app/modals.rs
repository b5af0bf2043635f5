//! The dialogs that ask or report over the editor, as one state: [`Modal`] names each, and
//! [`Modals`] shows one at a time. A dialog asked for while another is up waits its turn (none is
//! dropped: a restore offer behind a failed file is still offered once the report is closed); a
//! second dialog of the same kind replaces the first where it stands (a newer question, report or
//! failure supersedes the older).

use std::collections::VecDeque;

use crate::export::ExportReport;
use crate::file_dialog::FileDialog;
use crate::load_failure::LoadFailure;
use crate::recovery::Recovered;
use crate::unsaved::Replace;

use super::reads::ReadPrompt;

/// A dialog over the editor.
pub enum Modal {
    /// The unsaved-changes question: what replaces or closes the document once the designer
    /// answers (see [`crate::unsaved`]).
    Unsaved(Replace),
    /// The offer to restore the unsaved work a previous session (or page) left.
    Restore(Recovered),
    /// A graph file that failed to load, shown with its diagnostics.
    LoadFailure(LoadFailure),
    /// A read refused as outside the graph's folder, asked about ("Allow reading this folder").
    ReadPrompt(ReadPrompt),
    /// What the last File › Export wrote.
    ExportReport(ExportReport),
    /// The file dialog (open, save, export, a folder, a path input's Browse…).
    File(FileDialog),
}

impl Modal {
    /// Whether `self` and `other` are the same kind of dialog.
    fn same_kind(&self, other: &Modal) -> bool {
        std::mem::discriminant(self) == std::mem::discriminant(other)
    }
}

/// The dialogs asked for: the first is shown, the rest wait in order.
#[derive(Default)]
pub struct Modals {
    queue: VecDeque<Modal>,
    /// Carried out once the Save As opened by the question's "Save" has saved.
    pub(super) after_save: Option<Replace>,
}

/// Finds the dialog of one kind, shown or waiting: `find!(self, Variant)`.
macro_rules! find {
    ($queue:expr, $variant:ident) => {
        $queue.iter().find_map(|m| match m {
            Modal::$variant(x) => Some(x),
            _ => None,
        })
    };
}

impl Modals {
    /// Asks for `modal`: shown when nothing else is, else after those before it; it replaces a
    /// dialog of its kind already asked for.
    pub fn open(&mut self, modal: Modal) {
        match self.queue.iter_mut().find(|m| m.same_kind(&modal)) {
            Some(slot) => *slot = modal,
            None => self.queue.push_back(modal),
        }
    }

    /// The dialog shown.
    pub fn shown(&self) -> Option<&Modal> {
        self.queue.front()
    }

    /// The dialog shown, to draw it.
    pub(super) fn shown_mut(&mut self) -> Option<&mut Modal> {
        self.queue.front_mut()
    }

    /// Closes the dialog shown; the next waiting one is shown from the next frame.
    pub(super) fn close_shown(&mut self) -> Option<Modal> {
        self.queue.pop_front()
    }

    /// Takes out the dialog of the kind `is_kind` picks, shown or waiting.
    pub(super) fn remove(&mut self, is_kind: impl Fn(&Modal) -> bool) -> Option<Modal> {
        let at = self.queue.iter().position(is_kind)?;
        self.queue.remove(at)
    }

    /// The unsaved-changes question, shown or waiting.
    pub fn unsaved_question(&self) -> Option<&Replace> {
        find!(self.queue, Unsaved)
    }

    /// The restore offer, shown or waiting.
    pub fn restore_offer(&self) -> Option<&Recovered> {
        find!(self.queue, Restore)
    }

    /// The failed file's report, shown or waiting.
    pub fn load_failure(&self) -> Option<&LoadFailure> {
        find!(self.queue, LoadFailure)
    }

    /// The failed file's report, to change it (the page adds what it learns).
    pub fn load_failure_mut(&mut self) -> Option<&mut LoadFailure> {
        self.queue.iter_mut().find_map(|m| match m {
            Modal::LoadFailure(x) => Some(x),
            _ => None,
        })
    }

    /// The read prompt, shown or waiting.
    pub fn read_prompt(&self) -> Option<&ReadPrompt> {
        find!(self.queue, ReadPrompt)
    }

    /// The export report, shown or waiting.
    pub fn export_report(&self) -> Option<&ExportReport> {
        find!(self.queue, ExportReport)
    }

    /// The file dialog, shown or waiting.
    pub fn file_dialog(&self) -> Option<&FileDialog> {
        find!(self.queue, File)
    }

    /// The file dialog, to type into it.
    pub fn file_dialog_mut(&mut self) -> Option<&mut FileDialog> {
        self.queue.iter_mut().find_map(|m| match m {
            Modal::File(x) => Some(x),
            _ => None,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    fn failure(name: &str) -> Modal {
        Modal::LoadFailure(LoadFailure::new(
            &PathBuf::from(name),
            &cnets_engine::file::LoadError::message("bad"),
        ))
    }

    #[test]
    fn one_is_shown_the_others_wait_in_order_and_none_is_dropped() {
        let mut m = Modals::default();
        m.open(Modal::Unsaved(Replace::New));
        m.open(failure("a.ron"));
        assert!(matches!(m.shown(), Some(Modal::Unsaved(Replace::New))));
        assert!(m.load_failure().is_some(), "the failure waits");
        assert!(m.close_shown().is_some());
        assert!(matches!(m.shown(), Some(Modal::LoadFailure(_))));
        assert!(m.close_shown().is_some());
        assert!(m.shown().is_none());
    }

    #[test]
    fn a_dialog_of_the_same_kind_replaces_the_first_where_it_stands() {
        let mut m = Modals::default();
        m.open(failure("a.ron"));
        m.open(Modal::Unsaved(Replace::New));
        m.open(failure("b.ron"));
        assert_eq!(m.queue.len(), 2);
        let Some(Modal::LoadFailure(f)) = m.shown() else {
            panic!("the failure stays first");
        };
        assert_eq!(f.path, PathBuf::from("b.ron"));
        assert!(m.remove(|d| matches!(d, Modal::Unsaved(_))).is_some());
        assert_eq!(m.queue.len(), 1);
    }
}
