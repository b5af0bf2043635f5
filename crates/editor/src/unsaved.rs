//! The unsaved-changes guard: every way of replacing or closing the document (File › New, Open…,
//! Open recent, Open example, a file dropped on the window, a graph sent from the command line,
//! Quit, the window's close button) is a [`Replace`] request; while the document has unsaved
//! changes the app holds it and asks Save / Don't save / Cancel ([`ask`]) before carrying it out.

use std::path::PathBuf;

/// Something that replaces or closes the document.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Replace {
    /// File › New: an empty untitled graph.
    New,
    /// Open a graph file (File › Open…, Open recent, a dropped file, the command line).
    Open(PathBuf),
    /// File › Open example: an untitled copy of a shipped graph.
    Example(PathBuf),
    /// Open a large graph file read off the UI thread while the document was being edited.
    Loaded(PathBuf),
    /// Close the editor (File › Quit, Ctrl+Q, the window's close button).
    Quit,
}

impl Replace {
    /// What the question says is about to happen.
    pub fn describe(&self) -> String {
        let name = |p: &PathBuf| {
            p.file_name()
                .map_or_else(|| p.display().to_string(), |n| n.to_string_lossy().into())
        };
        match self {
            Self::New => "Starting a new graph".into(),
            Self::Open(p) => format!("Opening {}", name(p)),
            Self::Example(p) => format!("Opening the example {}", name(p)),
            Self::Loaded(p) => format!("Opening {}", name(p)),
            Self::Quit => "Closing the editor".into(),
        }
    }
}

/// The designer's answer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Answer {
    /// Save first (Save As when the document has no file yet), then go on.
    Save,
    /// Go on and drop the changes.
    Discard,
    /// Keep the document as it is.
    Cancel,
}

/// Shows the question for `pending` about the document `title`; returns the answer once given.
pub fn ask(ctx: &egui::Context, title: &str, pending: &Replace) -> Option<Answer> {
    let mut answer = None;
    let modal = egui::Modal::new(egui::Id::new("cnets-unsaved")).show(ctx, |ui| {
        ui.set_max_width(420.0);
        ui.heading("Save changes?");
        ui.label(format!(
            "{title} has unsaved changes. {} will drop them.",
            pending.describe()
        ));
        ui.add_space(6.0);
        ui.horizontal(|ui| {
            if ui.button("Save").clicked() {
                answer = Some(Answer::Save);
            }
            if ui.button("Don't save").clicked() {
                answer = Some(Answer::Discard);
            }
            if ui.button("Cancel").clicked() {
                answer = Some(Answer::Cancel);
            }
        });
    });
    if answer.is_none() && modal.should_close() {
        // Esc or a click outside: the safe answer.
        answer = Some(Answer::Cancel);
    }
    answer
}
