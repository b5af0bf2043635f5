//! A graph file that failed to load: its diagnostics (`file:line:col: message`, with the
//! loader's "did you mean" hints) in a dialog, and the file itself as text on request. The
//! document that was open stays open: a failed load is never shown as if it were loaded.

use std::path::{Path, PathBuf};

/// A failed load being shown.
#[derive(Clone, Debug)]
pub struct LoadFailure {
    /// The file that was being opened.
    pub path: PathBuf,
    /// One line per problem, as the loader reported them.
    pub diagnostics: Vec<String>,
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
    /// The failure of loading `path` with the loader's error text (one diagnostic a line).
    pub fn new(path: &Path, error: &str) -> Self {
        Self {
            path: path.to_path_buf(),
            diagnostics: error.lines().map(str::to_string).collect(),
            text: None,
            scroll_pending: false,
            kept_document: true,
            shown_at: None,
        }
    }

    /// The 1-based line of the first diagnostic that names one (`file:line:col: …`).
    pub fn first_line(&self) -> Option<usize> {
        self.diagnostics.iter().find_map(|d| {
            // The file name may itself contain ':'; the position is the first `:N:N:` run.
            let parts: Vec<&str> = d.split(':').collect();
            parts.windows(2).find_map(|w| {
                let line = w[0].trim().parse::<usize>().ok()?;
                w[1].trim().parse::<usize>().ok()?;
                Some(line)
            })
        })
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
                    for d in &self.diagnostics {
                        ui.add(
                            egui::Label::new(
                                egui::RichText::new(d)
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
    fn the_first_diagnostic_with_a_position_gives_the_line() {
        let f = LoadFailure::new(
            Path::new("/a/b.ron"),
            "/a/b.ron: 2 problems\n/a/b.ron:7:18: unknown node type 'curve.arcc' (did you mean curve.arc?)",
        );
        assert_eq!(f.diagnostics.len(), 2);
        assert_eq!(f.first_line(), Some(7));
        assert_eq!(
            LoadFailure::new(Path::new("x"), "x: unreadable").first_line(),
            None
        );
    }
}
