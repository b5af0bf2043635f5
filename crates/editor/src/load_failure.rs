//! A graph file that failed to load: its diagnostics (`file:line:col: message`, with the
//! loader's "did you mean" hints) in a dialog, and the file itself as text on request. The
//! document that was open stays open: a failed load is never shown as if it were loaded.

use std::path::{Path, PathBuf};

use cnets_engine::file::LoadError;

/// A failed load being shown.
#[derive(Clone, Debug)]
pub struct LoadFailure {
    /// The file that was being opened.
    pub path: PathBuf,
    /// The problems, as the loader reported them (each with its place in the file, if any).
    pub error: LoadError,
    /// The file's text, once the designer asked to see it (`None`: not asked, or unreadable).
    pub text: Option<String>,
    /// Scroll the text to the first problem in the next frame.
    scroll_pending: bool,
    /// What the dialog says of the document: kept (a file failed over an open document), or
    /// none opened in its place (the web page's link at start).
    pub kept_document: bool,
    /// Where the dialog was drawn in the last frame (screen points; the page's test reads it).
    pub shown_at: Option<egui::Rect>,
}

impl LoadFailure {
    /// The failure of loading `path` with the loader's error.
    pub fn new(path: &Path, error: &LoadError) -> Self {
        Self {
            path: path.to_path_buf(),
            error: error.clone(),
            text: None,
            scroll_pending: false,
            kept_document: true,
            shown_at: None,
        }
    }

    /// The 1-based line of the first problem that has a place in the file.
    pub fn first_line(&self) -> Option<usize> {
        self.error.first_line()
    }

    /// Shows the dialog; returns false once it is closed.
    pub fn show(&mut self, ctx: &egui::Context) -> bool {
        let mut open = true;
        let name = self.path.display().to_string();
        let modal = egui::Modal::new(egui::Id::new("cnets-load-failure")).show(ctx, |ui| {
            ui.set_max_width(760.0);
            ui.heading(format!("Cannot open {name}"));
            ui.label(if self.kept_document {
                "The graph was not loaded; the document you had open is unchanged."
            } else {
                "The graph was not loaded; nothing was opened in its place."
            });
            ui.add_space(4.0);
            egui::ScrollArea::vertical()
                .id_salt("diagnostics")
                .max_height(180.0)
                .show(ui, |ui| {
                    for d in &self.error.diagnostics {
                        ui.add(
                            egui::Label::new(
                                egui::RichText::new(d.to_string())
                                    .monospace()
                                    .color(ui.visuals().error_fg_color),
                            )
                            .wrap(),
                        );
                    }
                });
            if let Some(text) = &self.text {
                ui.separator();
                let first = self.first_line();
                egui::ScrollArea::both()
                    .id_salt("file-text")
                    .max_height(320.0)
                    .show(ui, |ui| {
                        for (k, line) in text.lines().enumerate() {
                            let mut t =
                                egui::RichText::new(format!("{:>4}  {line}", k + 1)).monospace();
                            if first == Some(k + 1) {
                                t = t.background_color(
                                    ui.visuals().warn_fg_color.gamma_multiply(0.3),
                                );
                            }
                            let r = ui.label(t);
                            if first == Some(k + 1) && self.scroll_pending {
                                r.scroll_to_me(Some(egui::Align::Center));
                            }
                        }
                    });
                self.scroll_pending = false;
            }
            ui.add_space(6.0);
            ui.horizontal(|ui| {
                if self.text.is_none() && ui.button("Show the file as text").clicked() {
                    self.text = Some(
                        std::fs::read_to_string(&self.path)
                            .unwrap_or_else(|e| format!("(cannot read the file: {e})")),
                    );
                    self.scroll_pending = true;
                }
                if ui.button("Close").clicked() {
                    open = false;
                }
            });
        });
        self.shown_at = Some(modal.response.rect);
        // Escape (or a click beside it) closes it too: it only reports.
        open && !modal.should_close()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_problem_with_a_place_gives_the_line() {
        let registry = std::sync::Arc::new(cnets_engine::Registry::new());
        let text =
            "(\n    version: 1,\n    nodes: {\n        \"a\": (type: \"curve.arcc\"),\n    },\n)\n";
        let error = cnets_engine::file::load_str_with(
            text,
            "/a/b.ron",
            &registry,
            &cnets_engine::file::LoadOptions::default(),
        )
        .expect_err("an unknown node type");
        let f = LoadFailure::new(Path::new("/a/b.ron"), &error);
        assert_eq!(f.first_line(), Some(4), "{}", f.error);
        let unplaced = LoadError::message("the link does not decode");
        assert_eq!(
            LoadFailure::new(Path::new("x"), &unplaced).first_line(),
            None
        );
    }
}
