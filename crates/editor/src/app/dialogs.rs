//! The dialogs the editor shows over everything: the file dialog's outcome, the unsaved-changes
//! question and the restore offer.

use crate::file_dialog::Outcome;
use crate::file_dialog::Purpose;
use crate::menus::MenuAction;
use crate::unsaved;
use crate::unsaved::Answer;
use crate::unsaved::Replace;

use super::EditorApp;

impl EditorApp {
    pub(super) fn show_dialog(&mut self, ctx: &egui::Context) {
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
                    Purpose::ExportFile(format) => self.export_preview(format, &path),
                    Purpose::RunExports => self.run_exports(&path),
                    Purpose::BrowseInput => self.browsed(&path),
                }
            }
        }
    }

    pub(super) fn show_unsaved_question(&mut self, ctx: &egui::Context) {
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

    pub(super) fn show_restore(&mut self, ctx: &egui::Context) {
        let Some(r) = &self.offer_restore else {
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
