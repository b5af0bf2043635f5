//! Where the last frame put things: the grid step, the figures drawn over the view and the cuts
//! shown. Read by the app (the web page's hint goes below the labels) and by tests.

use egui::Rect;

use super::cut_plane::CutOverlay;
use super::grid::Spacing;

/// The layout of the last frame's overlays.
pub struct LastFrame {
    /// The grid spacing of the last frame (the snap step).
    pub spacing: Spacing,
    /// The lower edge of the labels in the view's top corners (statistics, legend): what sits
    /// below is free (the web page's first-visit hint goes there).
    pub labels_bottom: f32,
    /// The figures drawn over the view, by name (statistics, legend, distance picker, axes,
    /// size, grid): they never overlap (tests read them).
    pub overlays: Vec<(&'static str, Rect)>,
    /// The legend's fold entry (screen).
    pub fold_entry: Option<Rect>,
    /// The cuts of the selected nodes drawn (plane and kept side).
    pub cut_overlays: Vec<CutOverlay>,
}

impl Default for LastFrame {
    fn default() -> Self {
        Self {
            spacing: Spacing {
                minor: 1.0,
                major: 5.0,
            },
            labels_bottom: 0.0,
            overlays: Vec::new(),
            fold_entry: None,
            cut_overlays: Vec::new(),
        }
    }
}
