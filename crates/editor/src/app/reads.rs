//! What a document may read: a path input's Browse… (the file picked stays readable for the
//! document) and the "Allow reading this folder" prompt when a node's read was refused as outside
//! the graph's folder. Both are kept with the document's settings ([`crate::settings::Settings`],
//! never in the graph file) and fed to the engine as `--allow-read` folders are.

use std::path::{Path, PathBuf};

use cnets_engine::Value;

use crate::edit::Edit;
use crate::file_dialog::{FileDialog, Purpose};

use super::EditorApp;

/// A read refused as outside the graph's folder, asked about.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ReadPrompt {
    /// The node that tried to read.
    pub node: String,
    /// The file it was refused.
    pub path: PathBuf,
    /// The folder "Allow reading this folder" allows (the file's folder).
    pub folder: PathBuf,
}

/// What the document's reads are waiting on: the path input whose Browse… dialog is open and
/// the files whose prompt the designer declined (not asked again for this document).
#[derive(Default)]
pub struct ReadAccess {
    /// The path input whose Browse… dialog is open (node id, input name).
    browse_target: Option<(String, String)>,
    /// Files whose prompt the designer declined.
    declined: Vec<PathBuf>,
}

impl ReadAccess {
    /// A new document: nothing declined, no Browse… open.
    pub fn forget(&mut self) {
        *self = ReadAccess::default();
    }

    /// Whether the designer declined the prompt for `path`.
    pub fn declined(&self, path: &Path) -> bool {
        self.declined.iter().any(|p| p == path)
    }
}

impl EditorApp {
    /// What an evaluation of the document may use ([`cnets_host::Session`], as every door makes
    /// its contexts): the folders it was allowed to read and the library folders.
    pub(super) fn session(&self) -> cnets_host::Session {
        cnets_host::Session::new()
            .with_allow_read(self.doc.allowed_reads.iter().cloned())
            .with_library(self.library.dirs.iter().cloned())
    }

    /// Lets the document's nodes read `path` (a file or a folder) from now on: kept with the
    /// document's settings when it has a file (else once it is saved), and the graph is evaluated
    /// afresh (a refused read left no trace to re-run from). Returns whether it was new.
    pub fn allow_read(&mut self, path: &Path) -> bool {
        if self.doc.allowed_reads.iter().any(|p| p == path) {
            return false;
        }
        self.doc.allowed_reads.push(path.to_path_buf());
        if let Some(doc) = self.doc.path.clone() {
            self.settings.allow_read(&doc, path);
        }
        let generation = self.doc.generation();
        self.doc.start_after(generation);
        self.evaluation.last_evaluated = None;
        self.evaluation.submitted = None;
        true
    }

    /// Opens the file dialog for a path input's Browse… (node id, input name), in the folder of
    /// its current file, else the graph's folder.
    pub fn browse(&mut self, node: &str, input: &str) {
        let base = self
            .doc
            .base_dir()
            .unwrap_or_else(|| super::files::user_folder(&self.examples_dir));
        let current = self
            .doc
            .graph
            .node(node)
            .and_then(|n| n.value_of(input))
            .and_then(|v| match v {
                Value::Text(t) if !t.trim().is_empty() => Some(base.join(t.as_ref())),
                _ => None,
            });
        let start = current
            .filter(|p| p.parent().is_some_and(Path::is_dir))
            .unwrap_or(base);
        self.reads.browse_target = Some((node.to_string(), input.to_string()));
        self.modals.open(super::Modal::File(FileDialog::new(
            Purpose::BrowseInput,
            &start,
        )));
    }

    /// The file picked with Browse…: it stays readable for the document when it lies outside the
    /// graph's folder, and becomes the input's value (relative to the graph's folder when inside
    /// it), one undo step.
    pub(super) fn browsed(&mut self, path: &Path) {
        let Some((node, input)) = self.reads.browse_target.take() else {
            return;
        };
        let base = self.doc.base_dir();
        let inside = base
            .as_deref()
            .and_then(|b| path.strip_prefix(b).ok())
            .map(Path::to_path_buf);
        let text = match &inside {
            Some(relative) => relative.display().to_string(),
            None => {
                self.allow_read(path);
                path.display().to_string()
            }
        };
        if self.edit(Edit::SetValue {
            node: node.clone(),
            input,
            value: Value::text(&text),
        }) {
            self.message = match inside {
                Some(_) => format!("'{node}' reads {text}"),
                None => format!("'{node}' reads {text} (readable for this document from now on)"),
            };
        }
    }

    /// After an evaluation: a node refused a file outside the graph's folder (and the designer
    /// has not declined it) opens the "Allow reading this folder" prompt.
    pub(super) fn check_refused_reads(&mut self) {
        if self.modals.read_prompt().is_some() || self.page.is_some() {
            return;
        }
        let mut refused: Vec<(String, PathBuf)> = self
            .statuses()
            .iter()
            .filter_map(|(id, s)| {
                Some((id.clone(), cnets_engine::files::refused_read(s.error()?)?))
            })
            .filter(|(_, p)| !self.reads.declined(p))
            .filter(|(_, p)| !self.doc.allowed_reads.iter().any(|a| p.starts_with(a)))
            .collect();
        refused.sort();
        if let Some((node, path)) = refused.into_iter().next() {
            let folder = path
                .parent()
                .map_or_else(|| path.clone(), Path::to_path_buf);
            self.modals
                .open(super::Modal::ReadPrompt(ReadPrompt { node, path, folder }));
        }
    }

    /// Answers the prompt: `allow` lets the document read the file's folder from now on; else
    /// the file is not asked about again for this document.
    pub fn answer_read_prompt(&mut self, allow: bool) {
        let Some(super::Modal::ReadPrompt(p)) = self
            .modals
            .remove(|m| matches!(m, super::Modal::ReadPrompt(_)))
        else {
            return;
        };
        if allow {
            self.allow_read(&p.folder);
            self.message = format!(
                "this document may read {} from now on (kept with its settings, not in the file)",
                p.folder.display()
            );
        } else {
            self.reads.declined.push(p.path);
        }
    }

    /// The prompt itself: which node, which file, and the two answers.
    pub(super) fn show_read_prompt(&mut self, ctx: &egui::Context) {
        let Some(super::Modal::ReadPrompt(p)) = self.modals.shown() else {
            return;
        };
        let label = self
            .doc
            .graph
            .node(&p.node)
            .map_or(p.node.as_str(), |n| n.label())
            .to_string();
        let mut answer = None;
        let modal = egui::Modal::new(egui::Id::new("cnets-read-prompt")).show(ctx, |ui| {
            ui.set_max_width(460.0);
            ui.heading("Read a file outside the graph's folder?");
            ui.label(format!(
                "'{label}' reads {}, which is outside the graph's folder. A graph reads only \
                 in its own folder unless you allow another one for this document.",
                p.path.display()
            ));
            ui.weak(format!("folder: {}", p.folder.display()));
            ui.horizontal(|ui| {
                let allow = ui.button("Allow reading this folder");
                crate::probe::record(ui.ctx(), "Allow reading this folder", allow.rect);
                if allow.clicked() {
                    answer = Some(true);
                }
                if ui.button("Not now").clicked() {
                    answer = Some(false);
                }
            });
        });
        // Escape (or a click beside it) is "Not now": nothing outside the folder is read.
        if answer.is_none() && modal.should_close() {
            answer = Some(false);
        }
        if let Some(allow) = answer {
            self.answer_read_prompt(allow);
        }
    }
}
