//! A built-in path dialog: a path field plus the listing of its folder (folders first, then graph
//! files — every file for a path input's Browse…). It needs no desktop portal or GTK, so it works
//! the same under Xvfb and in tests.

use std::path::{Path, PathBuf};

/// What the dialog is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Purpose {
    /// Pick a graph file to open.
    Open,
    /// Pick where to save the graph.
    SaveAs,
    /// Name the file a quick export of the preview writes (folder and name).
    ExportFile(crate::export::ExportFormat),
    /// Pick the folder the graph's own export nodes write into (File › Export › Graph's exports).
    RunExports,
    /// Pick the file a path input reads (its Browse… button).
    BrowseInput,
    /// Pick the user library folder.
    LibraryFolder,
}

impl Purpose {
    fn title(self) -> &'static str {
        match self {
            Purpose::Open => "Open graph",
            Purpose::SaveAs => "Save graph as",
            Purpose::ExportFile(_) => "Export the preview as",
            Purpose::RunExports => "Run the graph's exports into folder",
            Purpose::BrowseInput => "Pick the file to read",
            Purpose::LibraryFolder => "Library folder",
        }
    }

    fn wants_folder(self) -> bool {
        matches!(self, Purpose::RunExports | Purpose::LibraryFolder)
    }

    /// Whether the listing shows every file (a path input reads any kind), not only graphs.
    fn lists_every_file(self) -> bool {
        matches!(self, Purpose::BrowseInput | Purpose::ExportFile(_))
    }
}

/// What happened in the dialog this frame.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Still open.
    Open,
    /// Closed without a choice.
    Cancelled,
    /// A path was chosen.
    Chosen(PathBuf),
}

/// The dialog's state.
#[derive(Clone, Debug)]
pub struct FileDialog {
    /// Its purpose.
    pub purpose: Purpose,
    /// The path typed or picked.
    pub path: String,
    /// A problem to show (e.g. the file does not exist).
    pub error: Option<String>,
}

/// Entries of a folder: sub-folders, then `.ron` files (or only folders), sorted by name.
pub fn list_dir(dir: &Path, folders_only: bool) -> Vec<(String, bool)> {
    list_entries(dir, folders_only, false)
}

/// Entries of a folder: sub-folders, then files (`.ron` only unless `every_file`; none when
/// `folders_only`), sorted by name; hidden entries left out.
pub fn list_entries(dir: &Path, folders_only: bool, every_file: bool) -> Vec<(String, bool)> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut out: Vec<(String, bool)> = entries
        .filter_map(Result::ok)
        .filter_map(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            let is_dir = e.file_type().ok()?.is_dir();
            let keep = !name.starts_with('.')
                && (is_dir || (!folders_only && (every_file || name.ends_with(".ron"))));
            keep.then_some((name, is_dir))
        })
        .collect();
    out.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    out
}

/// The height of the dialog's listing of the folder, whatever it holds.
const LISTING_HEIGHT: f32 = 240.0;

impl FileDialog {
    /// A dialog starting at `start` (a folder, or a file whose folder is listed).
    pub fn new(purpose: Purpose, start: &Path) -> Self {
        Self {
            purpose,
            path: start.display().to_string(),
            error: None,
        }
    }

    /// The folder being listed: the path itself when it is a folder, else its parent.
    pub fn folder(&self) -> PathBuf {
        let p = PathBuf::from(&self.path);
        if p.is_dir() {
            p
        } else {
            p.parent()
                .map(Path::to_path_buf)
                .unwrap_or_else(|| PathBuf::from("."))
        }
    }

    /// Checks the typed path for the purpose; the chosen path or a message.
    pub fn validate(&self) -> Result<PathBuf, String> {
        let p = PathBuf::from(self.path.trim());
        match self.purpose {
            Purpose::Open if p.is_file() => Ok(p),
            Purpose::Open => Err(format!("{} is not a file", p.display())),
            Purpose::SaveAs if p.is_dir() => Err("type a file name".into()),
            Purpose::SaveAs => {
                let p = if p.extension().is_none() {
                    p.with_extension("ron")
                } else {
                    p
                };
                match p.parent() {
                    Some(d) if d.as_os_str().is_empty() || d.is_dir() => Ok(p),
                    _ => Err(format!("the folder of {} does not exist", p.display())),
                }
            }
            Purpose::ExportFile(_) if p.is_dir() || p.file_name().is_none() => {
                Err("type the file's name".into())
            }
            Purpose::ExportFile(format) => {
                let p = if p.extension().is_none() {
                    p.with_extension(format.extension())
                } else {
                    p
                };
                match p.parent() {
                    Some(d) if d.as_os_str().is_empty() || d.is_dir() => Ok(p),
                    _ => Err(format!("the folder of {} does not exist", p.display())),
                }
            }
            Purpose::BrowseInput if p.is_file() => Ok(p),
            Purpose::BrowseInput => Err(format!("{} is not a file", p.display())),
            Purpose::RunExports if p.is_dir() || p.parent().is_some_and(Path::is_dir) => Ok(p),
            Purpose::RunExports => Err(format!("{} is not a folder", p.display())),
            Purpose::LibraryFolder if p.is_dir() || p.parent().is_some_and(Path::is_dir) => Ok(p),
            Purpose::LibraryFolder => Err(format!("{} is not a folder", p.display())),
        }
    }

    /// Shows the dialog window.
    pub fn show(&mut self, ctx: &egui::Context) -> Outcome {
        let mut outcome = Outcome::Open;
        let mut open = true;
        egui::Window::new(self.purpose.title())
            .id(egui::Id::new("cnets-file-dialog"))
            .open(&mut open)
            .collapsible(false)
            .default_width(460.0)
            .default_height(360.0)
            .anchor(egui::Align2::CENTER_CENTER, egui::Vec2::ZERO)
            .show(ctx, |ui| {
                let field =
                    ui.add(egui::TextEdit::singleline(&mut self.path).desired_width(f32::INFINITY));
                let enter = field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
                let folder = self.folder();
                ui.horizontal(|ui| {
                    ui.weak(folder.display().to_string());
                    if ui.small_button("⬆ up").clicked()
                        && let Some(parent) = folder.parent()
                    {
                        self.path = parent.display().to_string();
                    }
                });
                // A listing of fixed height: the buttons below stay where they are while files
                // come and go in the folder (a click aimed at Save must not land elsewhere).
                egui::ScrollArea::vertical()
                    .min_scrolled_height(LISTING_HEIGHT)
                    .max_height(LISTING_HEIGHT)
                    .auto_shrink([false, false])
                    .show(ui, |ui| {
                        for (name, is_dir) in list_entries(
                            &folder,
                            self.purpose.wants_folder(),
                            self.purpose.lists_every_file(),
                        ) {
                            let label = if is_dir {
                                format!("📁 {name}")
                            } else {
                                name.clone()
                            };
                            let r = ui.selectable_label(false, label);
                            if r.clicked() {
                                self.path = folder.join(&name).display().to_string();
                            }
                            if r.double_clicked() && !is_dir {
                                outcome = Outcome::Chosen(folder.join(&name));
                            }
                        }
                    });
                if let Some(e) = &self.error {
                    ui.colored_label(egui::Color32::from_rgb(0xd6, 0x2f, 0x2f), e);
                }
                ui.horizontal(|ui| {
                    let ok = match self.purpose {
                        Purpose::Open => "Open",
                        Purpose::SaveAs => "Save",
                        Purpose::ExportFile(_) => "Export file",
                        Purpose::RunExports => "Export here",
                        Purpose::BrowseInput => "Pick",
                        Purpose::LibraryFolder => "Use this folder",
                    };
                    let ok_button = ui.button(ok);
                    crate::probe::record(ui.ctx(), ok, ok_button.rect);
                    if ok_button.clicked() || enter {
                        match self.validate() {
                            Ok(p) => outcome = Outcome::Chosen(p),
                            Err(e) => self.error = Some(e),
                        }
                    }
                    if ui.button("Cancel").clicked() {
                        outcome = Outcome::Cancelled;
                    }
                });
            });
        // Escape cancels, as the Cancel button does.
        let escape = ctx.input(|i| i.key_pressed(egui::Key::Escape));
        if !open || (escape && matches!(outcome, Outcome::Open)) {
            Outcome::Cancelled
        } else {
            outcome
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn listing_and_validation() {
        let dir = std::env::temp_dir().join(format!("cnets-dialog-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        std::fs::write(dir.join("b.ron"), "x").unwrap();
        std::fs::write(dir.join("a.txt"), "x").unwrap();
        let l = list_dir(&dir, false);
        assert_eq!(
            l,
            vec![("sub".to_string(), true), ("b.ron".to_string(), false)]
        );
        assert_eq!(list_dir(&dir, true).len(), 1);
        let mut d = FileDialog::new(Purpose::Open, &dir);
        assert!(d.validate().is_err());
        d.path = dir.join("b.ron").display().to_string();
        assert_eq!(d.validate().unwrap(), dir.join("b.ron"));
        let mut s = FileDialog::new(Purpose::SaveAs, &dir);
        s.path = dir.join("new").display().to_string();
        assert_eq!(s.validate().unwrap(), dir.join("new.ron"));
        s.path = dir.join("missing/new.ron").display().to_string();
        assert!(s.validate().is_err());
        // A path input's Browse… lists and picks any file; a quick export names its file.
        assert_eq!(list_entries(&dir, false, true).len(), 3);
        let mut b = FileDialog::new(Purpose::BrowseInput, &dir);
        assert!(b.validate().is_err(), "a folder is not a file to read");
        b.path = dir.join("a.txt").display().to_string();
        assert_eq!(b.validate().unwrap(), dir.join("a.txt"));
        let mut e = FileDialog::new(Purpose::ExportFile(crate::export::ExportFormat::Svg), &dir);
        assert!(e.validate().is_err(), "a folder is not a name");
        e.path = dir.join("sheet").display().to_string();
        assert_eq!(e.validate().unwrap(), dir.join("sheet.svg"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
