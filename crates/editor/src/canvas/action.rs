//! What the canvas shows and what it asks for: its nodes (each names a graph node) and the
//! actions its gestures produce, which the app carries out.

use crate::edit::Edit;
use crate::request::UiRequest;

/// A node on the canvas: the id of the graph node it shows.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CanvasNode {
    /// Graph node id.
    pub id: String,
}

/// What a gesture on the canvas asks for: a change of the document or of the interface only.
#[derive(Clone, Debug, PartialEq)]
pub enum CanvasAction {
    /// Change the document (one undo step; [`crate::edit::apply`]).
    Edit(Edit),
    /// Change only the interface (the app carries it out).
    Request(UiRequest),
}

impl From<Edit> for CanvasAction {
    fn from(edit: Edit) -> Self {
        Self::Edit(edit)
    }
}

impl From<UiRequest> for CanvasAction {
    fn from(request: UiRequest) -> Self {
        Self::Request(request)
    }
}
