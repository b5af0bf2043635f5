//! The dialogs the editor shows over everything ([`Modals`], one at a time): the file dialog's
//! outcome, the unsaved-changes question and the restore offer (the read prompt's is in
//! `reads.rs`), and the read-only queries tests and the page ask of them.

use crate::file_dialog::Outcome;
use crate::file_dialog::Purpose;
use crate::menus::MenuAction;
use crate::unsaved;
use crate::unsaved::Answer;
use crate::unsaved::Replace;

use super::{EditorApp, Modal, Modals};

impl EditorApp {
    /// Shows the dialog at the front of [`Modals`] and carries out its answer.
    pub(super) fn show_modal(&mut self, ctx: &egui::Context) {
        // The reports close themselves; the others are answered in their handlers.
        let report_open = match self.modals.shown_mut() {
            None => return,
            Some(Modal::ExportReport(report)) => report.show(ctx),
            Some(Modal::LoadFailure(failure)) => failure.show(ctx),
            Some(Modal::File(_)) => {
                self.show_file_dialog(ctx);
                return;
            }
            Some(Modal::Unsaved(_)) => {
                self.show_unsaved_question(ctx);
                return;
            }
            Some(Modal::Restore(_)) => {
                self.show_restore(ctx);
                return;
            }
            Some(Modal::ReadPrompt(_)) => {
                self.show_read_prompt(ctx);
                return;
            }
        };
        if !report_open {
            self.modals.close_shown();
        }
    }

    fn show_file_dialog(&mut self, ctx: &egui::Context) {
        let Some(Modal::File(dialog)) = self.modals.shown_mut() else {
            return;
        };
        match dialog.show(ctx) {
            Outcome::Open => {}
            Outcome::Cancelled => {
                if dialog.purpose == Purpose::SaveAs {
                    // "Save" in the unsaved-changes question, then Cancel here: nothing happens.
                    self.modals.after_save = None;
                }
                self.modals.close_shown();
            }
            Outcome::Chosen(path) => {
                let purpose = dialog.purpose;
                self.modals.close_shown();
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
                    Purpose::ExportFile(format) => self.export_preview(format, &path),
                    Purpose::RunExports => self.run_exports(&path),
                    Purpose::BrowseInput => self.browsed(&path),
                }
            }
        }
    }

    fn show_unsaved_question(&mut self, ctx: &egui::Context) {
        let Some(Modal::Unsaved(pending)) = self.modals.shown() else {
            return;
        };
        let title = self.doc.title().trim_end_matches(" *").to_string();
        let Some(answer) = unsaved::ask(ctx, &title, pending) else {
            return;
        };
        let Some(Modal::Unsaved(pending)) = self.modals.close_shown() else {
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
                    self.modals.after_save = Some(pending);
                    self.run(MenuAction::SaveAs);
                }
            },
            Answer::Discard => self.perform(pending),
            Answer::Cancel => {}
        }
    }

    fn show_restore(&mut self, ctx: &egui::Context) {
        let Some(Modal::Restore(r)) = self.modals.shown() else {
            return;
        };
        let what = r.path.as_ref().map_or_else(
            || "an untitled graph".to_string(),
            |p| p.display().to_string(),
        );
        let mut choice = None;
        let in_browser = self.page.is_some();
        let modal = egui::Modal::new(egui::Id::new("cnets-restore")).show(ctx, |ui| {
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
            // Escape (or a click beside it) decides nothing: the work is kept aside, not
            // deleted, and File › Restore kept work opens it later.
            None if modal.should_close() => self.keep_recovery_for_later(),
            None => {}
        }
    }
}

impl EditorApp {
    /// The dialogs asked for (the one shown first).
    pub fn modals(&self) -> &Modals {
        &self.modals
    }

    /// The unsaved-changes question, when asked.
    pub fn unsaved_question(&self) -> Option<&Replace> {
        self.modals.unsaved_question()
    }

    /// The report of a graph file that failed to load, when shown or waiting.
    pub fn load_failure(&self) -> Option<&crate::load_failure::LoadFailure> {
        self.modals.load_failure()
    }

    /// The failed file's report, to add to it (the web page: what the link held).
    pub fn load_failure_mut(&mut self) -> Option<&mut crate::load_failure::LoadFailure> {
        self.modals.load_failure_mut()
    }

    /// Shows a failed file's report (the web page's link that does not load).
    pub fn show_load_failure(&mut self, failure: crate::load_failure::LoadFailure) {
        self.modals.open(Modal::LoadFailure(failure));
    }

    /// The "Allow reading this folder" prompt, when asked.
    pub fn read_prompt(&self) -> Option<&super::ReadPrompt> {
        self.modals.read_prompt()
    }

    /// What the last export wrote, while its report is open.
    pub fn export_report(&self) -> Option<&crate::export::ExportReport> {
        self.modals.export_report()
    }
}
