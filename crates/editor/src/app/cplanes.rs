//! The construction planes of the document: a plane made in the 3D view (three points, or fitted
//! through a curve or a net's row) is named `CPlane 1`, `CPlane 2`, … , kept with the graph (one
//! undo step, saved in its file) and made the Perspective view's plane; the View menu lists
//! them with the world planes to choose from.

use super::EditorApp;
use crate::edit::Edit;
use crate::viewport::{CPlane, NamedView, Tool};

impl EditorApp {
    /// The first `CPlane N` no plane of the document is called yet.
    pub fn next_cplane_name(&self) -> String {
        (1..)
            .map(|k| format!("CPlane {k}"))
            .find(|name| !self.doc.meta.cplanes.iter().any(|p| &p.name == name))
            .unwrap_or_default()
    }

    /// Names `plane`, keeps it with the graph and makes it the Perspective view's construction
    /// plane (showing the Perspective view); `what` says what it was made from.
    pub fn add_cplane(&mut self, plane: CPlane, what: &str) {
        let name = self.next_cplane_name();
        if self.edit(Edit::AddCPlane(plane.named(&name))) {
            self.viewport.set_perspective_plane(plane, &name);
            if self.viewport.framing().view != NamedView::Perspective {
                self.viewport.set_view(NamedView::Perspective);
            }
            self.message = format!(
                "{name} ({what}) is the Perspective view's construction plane: Draw curve and \
                 handle drags use it (View ▸ Construction plane to change)"
            );
        }
    }

    /// Makes the document's plane `name` the Perspective view's construction plane.
    pub fn choose_cplane(&mut self, name: &str) {
        let found = self.doc.meta.cplanes.iter().find(|p| p.name == name);
        match found.and_then(CPlane::from_named) {
            Some(plane) => {
                self.viewport.set_perspective_plane(plane, name);
                self.message = format!("{name} is the Perspective view's construction plane");
            }
            None => self.message = format!("no construction plane called '{name}'"),
        }
    }

    /// Starts the *CPlane from 3 points* tool.
    pub fn start_three_point_cplane(&mut self) {
        let tool = crate::viewport::ThreePointTool::default();
        self.message = tool.prompt().to_string();
        self.viewport.set_tool(Tool::ThreePoint(tool));
    }

    /// Fits a construction plane through the selected node's previewed curve or the clicked row
    /// of a selected net, and adds it ([`EditorApp::add_cplane`]); else says what to select.
    pub fn cplane_through_selection(&mut self) {
        let selected = self.canvas.targets();
        match self.viewport.fit_cplane(&selected) {
            Ok((plane, what)) => self.add_cplane(plane, &format!("through {what}")),
            Err(e) => self.message = e.to_string(),
        }
    }
}
