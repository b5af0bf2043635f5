//! The view's tools and what the pointer is over: the active tool, the handles and their
//! selection, the hovered and last clicked mesh, and where a tool would put a point.

use cnets_geometry::DVec3;
use egui::Pos2;

use super::Tool;
use super::handles::{Handle, HandleTool};
use super::pick::Hit;

/// The state of the view's tools.
#[derive(Default)]
pub struct ViewTools {
    /// The active tool.
    pub tool: Tool,
    /// Handle selection and drags.
    pub handles: HandleTool,
    /// The handles of the last frame.
    pub handle_list: Vec<Handle>,
    /// What the pointer was over in the last frame.
    pub hover: Option<Hit>,
    /// The mesh hit of the last click with the Select tool (a net's row to fit a plane through).
    pub picked: Option<Hit>,
    /// Where a tool would put a point under the pointer (snapped).
    pub tool_point: Option<DVec3>,
    /// Where the pointer was when [`ViewTools::hover`] was found.
    pub(super) hover_at: Option<Pos2>,
}

impl ViewTools {
    /// Switches to `tool`, or back to Select when it is the active one.
    pub fn toggle(&mut self, tool: Tool) {
        let same = std::mem::discriminant(&self.tool) == std::mem::discriminant(&tool);
        self.tool = if same { Tool::Select } else { tool };
    }

    /// Forgets what the pointer was over (the scene changed).
    pub(super) fn forget_hover(&mut self) {
        self.hover = None;
        self.hover_at = None;
    }
}
