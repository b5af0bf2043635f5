//! UI requests: what a gesture asks of the editor's interface rather than of the document (open
//! the palette, open a cluster in place, pick an optimization variable or objective, open a list
//! editor). The app
//! carries them out (`EditorApp::handle`); graph changes are [`crate::edit::Edit`]s instead.

use cnets_engine::Value;
use cnets_engine::optimize::ValuePath;

/// A request to the editor's interface.
#[derive(Clone, Debug, PartialEq)]
pub enum UiRequest {
    /// Open the node palette at a canvas position.
    OpenPalette([f32; 2]),
    /// Open a cluster node to edit its subgraph in place.
    OpenCluster(String),
    /// Make a number inside an input's literal value an optimization variable.
    Optimize {
        /// The number (`node.input[...]`).
        path: ValuePath,
        /// Lower bound.
        min: f64,
        /// Upper bound.
        max: f64,
        /// A literal to set on the input first (a graph mapper's default handles, which have no
        /// literal yet).
        prepare: Option<Value>,
    },
    /// Make a number output the optimization objective.
    Minimize(ValuePath),
    /// Add a number output as an optimization penalty (kept at most at its current value).
    Penalize(ValuePath),
    /// Turn the curves a node outputs (e.g. read from a file) into editable points: a
    /// `param.points` node per curve wired into a `curve.polyline` (Grasshopper's "Internalise
    /// data").
    Internalise(String),
    /// Lock a node for dragging the net (its inputs stay put while a cone-net is dragged), or
    /// unlock it.
    ToggleDragLock(String),
    /// Open the table editor of an input's literal list (its **Edit…** button on the node; see
    /// [`crate::list_editor`]).
    EditList {
        /// Node id.
        node: String,
        /// Input name.
        input: String,
    },
}
