//! The commands that the web page, the scripted drivers and the tests give the editor from
//! outside, beside the menu's ([`EditorApp::run`]): each changes one part through that part's
//! own methods.

use web_time::Duration;

use cnets_engine::Graph;

use super::EditorApp;
use crate::list_editor::PasteMode;
use crate::page::{Page, PageRequest};
use crate::viewport::Viewport;
use cnets_engine::file::GraphMeta;
use cnets_host::LibraryEntry;

impl EditorApp {
    /// The 3D view, to move its camera or change its display (its fields are its own: only its
    /// methods change them).
    pub fn viewport_mut(&mut self) -> &mut Viewport {
        &mut self.viewport
    }

    /// Says `text` in the status bar.
    pub fn set_message(&mut self, text: impl Into<String>) {
        self.message = text.into();
    }

    /// Names the untitled document (the title bar and the file a download is given).
    pub fn name_document(&mut self, name: &str) {
        self.doc.name = Some(name.to_string());
    }

    /// Selects `ids` on the canvas (nothing: clears the selection).
    pub fn select_nodes(&mut self, ids: Vec<String>) {
        self.canvas.select(ids);
    }

    /// Gives the canvas's focus to `id` (the node commands act on when nothing is selected).
    pub fn focus_node(&mut self, id: Option<String>) {
        self.canvas.focused = id;
    }

    /// Zooms the canvas to `zoom`, keeping the point `around` (screen) in place.
    pub fn zoom_canvas(&mut self, zoom: f32, around: Option<egui::Pos2>) {
        self.canvas.zoom_to(zoom, around);
    }

    /// Frames the graph on the canvas as a document opens ([`Canvas::fit_later`](crate::canvas::Canvas::fit_later))
    /// and the geometry in the 3D view: the page does so while its size settles.
    pub fn frame_again(&mut self) {
        self.canvas.fit_later();
        self.viewport.fit();
    }

    /// Frames every node on the canvas.
    pub fn fit_canvas(&mut self) {
        self.canvas.fit();
    }

    /// Opens the node palette at `at` (canvas points), as a double-click there does.
    pub fn open_palette_at(&mut self, at: [f32; 2]) {
        self.palette.open_at(at);
    }

    /// Closes the node palette.
    pub fn close_palette(&mut self) {
        self.palette.open = false;
    }

    /// A scripted change to the graph and its settings, as one undo step (nothing changes when
    /// `change` fails). Designers' changes arrive as [`Edit`](crate::edit::Edit)s
    /// ([`EditorApp::edit`]); this is for the drivers and tests that set up a state.
    pub fn edit_graph<R, E>(
        &mut self,
        change: impl FnOnce(&mut Graph, &mut GraphMeta) -> Result<R, E>,
    ) -> Result<R, E> {
        self.doc.edit(None, change)
    }

    /// Lists the library's folders again, as the palette does when it opens.
    pub fn rescan_library(&mut self) -> &[LibraryEntry] {
        self.library.scan(&self.registry)
    }

    /// Where Ctrl+V pastes in the table window of `node`'s `input`.
    pub fn set_paste_mode(&mut self, node: &str, input: &str, mode: PasteMode) {
        self.list_editors.set_paste_mode(node, input, mode);
    }

    /// Undoes the last step; `false` when there is none.
    pub fn undo(&mut self) -> bool {
        self.doc.undo()
    }

    /// Ends the gesture in progress, so the next edit is an undo step of its own (as a pointer's
    /// release does).
    pub fn end_gesture(&mut self) {
        self.doc.history.end_gesture();
    }

    /// Takes the document as saved (its changes are no longer unsaved).
    pub fn mark_saved(&mut self) {
        self.doc.mark_saved();
    }

    /// Shows or hides the parameter panel (View › Parameters).
    pub fn show_parameters(&mut self, open: bool) {
        self.panels.parameters_open = open;
    }

    /// Shows or hides the timings and the busy spinner in the status bar (snapshot tests hide
    /// them: they vary from run to run).
    pub fn set_show_timings(&mut self, shown: bool) {
        self.show_timings = shown;
    }

    /// Closes the window on its next frame, without the unsaved-changes question (a scripted run
    /// ending).
    pub fn quit_now(&mut self) {
        self.quit = true;
    }

    /// Runs the editor inside a web page: downloads, links and file reads become requests for the
    /// page ([`EditorApp::take_page_requests`]).
    pub fn in_page(&mut self) {
        self.page = Some(Page::default());
    }

    /// The requests for the page made since the last call (none on the desktop).
    pub fn take_page_requests(&mut self) -> Vec<PageRequest> {
        self.page.as_mut().map(Page::take).unwrap_or_default()
    }

    /// Waits up to `timeout` for the optimization run to end, taking its reports; whether it
    /// ended.
    pub fn wait_for_optimization(&mut self, timeout: Duration) -> bool {
        self.optimization.wait(timeout)
    }

    /// Takes what the optimization run reported since the last frame; whether anything arrived.
    pub fn poll_optimization(&mut self) -> bool {
        self.optimization.poll()
    }
}
