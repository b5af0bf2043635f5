//! What the designer chose to see in the view: the preview's options and the toggles (snap,
//! grid, size, only the selected). The menus and the toolbar change them; the layout file keeps
//! them.

use crate::preview::PreviewOptions;

/// The view's display choices.
pub struct Display {
    /// Display options (colour mode, layers).
    pub options: PreviewOptions,
    /// Grid snap (F9; Alt suspends it while held).
    pub snap: bool,
    /// The grid and axes are drawn (F7).
    pub show_grid: bool,
    /// The size of the previewed geometry is shown (W × D × H).
    pub show_dimensions: bool,
    /// Only the selected nodes' previews are drawn (Grasshopper's *Only draw selected*; with
    /// nothing selected, every previewed node).
    pub only_selected: bool,
    /// The distance mode found no reference and the status bar said so (said once).
    pub(super) no_reference_said: bool,
}

impl Default for Display {
    fn default() -> Self {
        Self {
            options: PreviewOptions::default(),
            snap: true,
            show_grid: true,
            show_dimensions: true,
            only_selected: false,
            no_reference_said: false,
        }
    }
}
