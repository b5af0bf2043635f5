//! What the rest of the program, the scripted drivers and the tests read of the editor: a
//! read-only view of its parts. Changes go through commands ([`EditorApp::run`],
//! [`EditorApp::edit`], [`EditorApp::apply`] and those in `control.rs`).

use std::sync::Arc;

use cnets_engine::Registry;

use super::EditorApp;
use crate::canvas::Canvas;
use crate::document::GraphDocument;
use crate::library::Library;
use crate::list_editor::ListEditors;
use crate::optimization::OptimizationPanel;
use crate::page::Page;
use crate::palette::PaletteState;
use crate::settings::Settings;
use crate::viewport::Viewport;

impl EditorApp {
    /// The node types.
    pub fn registry(&self) -> &Arc<Registry> {
        &self.registry
    }

    /// The document being edited: its graph, history, path and settings.
    pub fn doc(&self) -> &GraphDocument {
        &self.doc
    }

    /// The node canvas: its view, selection and focus.
    pub fn canvas(&self) -> &Canvas {
        &self.canvas
    }

    /// The 3D view.
    pub fn viewport(&self) -> &Viewport {
        &self.viewport
    }

    /// The node palette.
    pub fn palette(&self) -> &PaletteState {
        &self.palette
    }

    /// The message in the status bar.
    pub fn message(&self) -> &str {
        &self.message
    }

    /// The recent files and the other per-user settings.
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// The user library and the examples, as listed in the palette.
    pub fn library(&self) -> &Library {
        &self.library
    }

    /// The optimization panel.
    pub fn optimization(&self) -> &OptimizationPanel {
        &self.optimization
    }

    /// The open table windows of literal lists.
    pub fn list_editors(&self) -> &ListEditors {
        &self.list_editors
    }

    /// The window should close (File › Quit, or the unsaved-changes question answered).
    pub fn wants_to_quit(&self) -> bool {
        self.quit
    }

    /// The status bar shows the hint to arrange overlapping nodes.
    pub fn overlap_hint(&self) -> bool {
        self.fresh.overlap_hint
    }

    /// The parameter panel (View › Parameters) is shown.
    pub fn parameters_open(&self) -> bool {
        self.panels.parameters_open
    }

    /// The failed nodes' errors the 3D view listed in the last frame (`id: message`).
    pub fn view_errors_shown(&self) -> &[String] {
        &self.panels.view_errors_shown
    }

    /// Where the parameter panel was drawn in the last frame (`None`: not shown), in points.
    pub fn parameters_rect(&self) -> Option<egui::Rect> {
        self.panels.parameters_rect
    }

    /// Where the parameter panel drew each value editor in the last frame: (node id, rectangle).
    pub fn parameter_editors(&self) -> &[(String, egui::Rect)] {
        &self.panels.parameter_editors
    }

    /// In a web page: its queued requests; `None` on the desktop.
    pub fn page(&self) -> Option<&Page> {
        self.page.as_ref()
    }
}
