//! The panels beside the canvas and the 3D view: whether the parameter panel is shown, and where
//! the last frame drew it, its value editors and the 3D view's list of failed nodes (tests and
//! the web page read them).

/// The panels' state and their last frame's layout.
#[derive(Default)]
pub struct Panels {
    /// Whether the parameter panel (View › Parameters) is shown.
    pub parameters_open: bool,
    /// Where the parameter panel was drawn in the last frame (`None`: not shown), in points.
    pub parameters_rect: Option<egui::Rect>,
    /// Where the parameter panel drew each value editor in the last frame: (node id, rectangle).
    pub parameter_editors: Vec<(String, egui::Rect)>,
    /// The failed nodes' errors the 3D view listed in the last frame (`id: message`): those off
    /// the canvas's view (crate::view_errors).
    pub view_errors_shown: Vec<String>,
}

impl Panels {
    /// Forgets where the last frame drew the parameter panel (it is drawn again this frame, or
    /// not at all).
    pub fn start_frame(&mut self) {
        self.parameters_rect = None;
        self.parameter_editors.clear();
    }
}
