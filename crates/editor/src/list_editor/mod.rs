//! Literal lists and tables you can see and edit (issue 25): the points of a literal polyline or
//! of a `points` input, the values of `param.list`, any unconnected input holding a literal list.
//!
//! On the node such an input shows a summary ([`summary`]: `4 points`, `40 × 41 numbers, 0.31 …
//! 0.69`) and an **Edit…** button, which asks the app ([`crate::request::UiRequest::EditList`]) to
//! open a window with the list as a table ([`ListEditors`], one window per input, several may be
//! open): points and vectors as x / y / z columns, a list of single values as one column, a table
//! as rows × columns (rows may differ in length). Cells are typed in with full precision, rows
//! added and removed, tab- or comma-separated text pasted ([`tsv`]) and copied. Every change is
//! one [`crate::edit::Edit::SetValue`] through the one [`crate::edit::apply`] (one undo step), made
//! on the model of [`table`], which keeps everything the designer did not touch bit for bit.
//!
//! - [`table`]: the list as rows of cells and its edits; [`tsv`]: delimited text; [`summary`]:
//!   the text on the node; [`OnNodeCache`]: that text kept while a list stays the same; `grid`: the cells of a window; `window`: one window.

pub mod errors;
mod grid;
mod on_node_cache;
pub mod summary;
pub mod table;
pub mod tsv;
mod window;

use cnets_engine::{Access, Graph, NodeInstance, Value, ValueType};

use crate::document::GraphDocument;
use crate::edit::Edit;
use crate::{mapper, widgets};

pub use errors::{CellError, NotATable, TableEditError};
pub use on_node_cache::OnNodeCache;
pub use table::{ItemType, Layout, Table};
pub use window::PasteMode;
use window::{EditorWindow, Request};

/// Which input a window edits: the graph level (opened clusters), the node and the input.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct EditorKey {
    /// The opened clusters of the level the node is in (empty: the document's own graph).
    pub view: Vec<String>,
    /// Node id.
    pub node: String,
    /// Input name.
    pub input: String,
}

/// What an unconnected input holding a literal list shows on its node.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct OnNode {
    /// The summary ([`summary::summary`]).
    pub summary: String,
    /// Whether the table editor can edit it (an **Edit…** button).
    pub editable: bool,
}

/// What input `k` of `node` shows on the node when it is unconnected and holds a literal list
/// (or its default is one) or a polyline: `None` for inputs with an inline editor of their own
/// (a number field, a `param.choice`'s options, a graph mapper's handles) and for other values.
pub fn on_node(node: &NodeInstance, k: usize) -> Option<OnNode> {
    shown_value(node, k).map(|value| describe(&value))
}

/// The value [`on_node`] describes (cheap: a list is shared, not copied).
fn shown_value(node: &NodeInstance, k: usize) -> Option<Value> {
    let port = node.def.inputs.get(k)?;
    if widgets::has_editor(node, k)
        || (mapper::is_mapper(node) && mapper::handles_port(node) == Some(k))
    {
        return None;
    }
    let value = widgets::effective_value(node, k)?;
    match &value {
        Value::List(_) => {}
        Value::Polyline(_) if port.ty == ValueType::Polyline => {}
        _ => return None,
    }
    Some(value)
}

/// The summary and whether the table editor takes `value` (both walk every item).
fn describe(value: &Value) -> OnNode {
    OnNode {
        summary: summary::summary(value),
        editable: Table::accepts(Some(value)) || parts(value).is_some(),
    }
}

/// The item type of a part ([`parts`]): points.
pub const PART_ITEMS: ItemType = ItemType {
    item: ValueType::Point,
    tables: false,
};

/// How many parts the table shows one at a time when `value` is not a table as a whole but a
/// list of polylines or of lists of points (`facade.ron`'s `profiles`): each part is a table of
/// points, edited on its own while the other parts stay as they are. `None` for other values.
pub fn parts(value: &Value) -> Option<usize> {
    if Table::accepts(Some(value)) {
        return None;
    }
    let list = value.as_list()?;
    let each_points = list.iter().all(|v| {
        matches!(v, Value::Polyline(_) | Value::List(_))
            && Table::new(Some(v), &PART_ITEMS).is_ok_and(|t| t.layout() == Layout::Xyz)
    });
    (!list.is_empty() && each_points).then_some(list.len())
}

/// The item type of input `k` for rows its value does not show: the port's type (or the type
/// its `item_type_input` hint's sibling names: a list of numbers' `item_type`), and whether it
/// takes tables.
pub fn item_type(node: &NodeInstance, k: usize) -> ItemType {
    let Some(port) = node.def.inputs.get(k) else {
        return ItemType {
            item: ValueType::Any,
            tables: false,
        };
    };
    let mut item = port.ty.clone();
    if let Some(name) = port.hint.item_type_input
        && let Some(Value::Text(t)) = node
            .def
            .input_index(name)
            .and_then(|i| widgets::effective_value(node, i))
    {
        item = ValueType::parse(&t.trim().to_ascii_lowercase()).unwrap_or(ValueType::Any);
    }
    ItemType {
        item,
        tables: matches!(port.access, Access::Table | Access::Tree),
    }
}

/// Whether input `input` of node `node` is connected by a wire.
fn is_wired(graph: &Graph, node: &str, k: usize) -> bool {
    graph
        .index(node)
        .is_ok_and(|i| graph.wires_into(i).iter().any(|(_, w)| w.to_input == k))
}

/// The open list editor windows (the app owns them and shows them every frame).
#[derive(Default)]
pub struct ListEditors {
    windows: Vec<EditorWindow>,
    /// The window the pointer was last pressed in: pasted text and copies go to it.
    active: Option<EditorKey>,
    /// Clipboard and key events taken from the frame's input for the active window.
    claimed: Vec<Request>,
}

impl ListEditors {
    /// Opens the window of `node`'s `input` at level `view` (or brings it to the front), at the
    /// screen position `at` when given; it becomes the active window.
    pub fn open(&mut self, view: Vec<String>, node: &str, input: &str, at: Option<egui::Pos2>) {
        let key = EditorKey {
            view,
            node: node.to_string(),
            input: input.to_string(),
        };
        match self.windows.iter_mut().find(|w| w.key == key) {
            Some(w) => w.raise = true,
            None => {
                let at = at.or_else(|| {
                    let k = self.windows.len() as f32;
                    Some(egui::pos2(160.0 + 30.0 * k, 120.0 + 30.0 * k))
                });
                self.windows.push(EditorWindow::new(key.clone(), at));
            }
        }
        self.active = Some(key);
    }

    /// Whether the window of `node`'s `input` is open.
    pub fn is_open(&self, node: &str, input: &str) -> bool {
        self.windows
            .iter()
            .any(|w| w.key.node == node && w.key.input == input)
    }

    /// How many windows are open.
    pub fn len(&self) -> usize {
        self.windows.len()
    }

    /// True when no window is open.
    pub fn is_empty(&self) -> bool {
        self.windows.is_empty()
    }

    /// Where Ctrl+V pastes in the window of `node`'s `input` (tests and scripts set it).
    pub fn set_paste_mode(&mut self, node: &str, input: &str, mode: PasteMode) {
        for w in &mut self.windows {
            if w.key.node == node && w.key.input == input {
                w.paste_mode = mode;
            }
        }
    }

    /// Closes every window (another document).
    pub fn close_all(&mut self) {
        self.windows.clear();
        self.active = None;
        self.claimed.clear();
    }

    /// Before the app's shortcuts, each frame: while a window is active, pasted text (Ctrl+V),
    /// Copy (Ctrl+C) and Delete with rows selected go to it — not to the canvas, which would
    /// paste or delete nodes. Text pasted into a cell being typed in stays the field's, unless it
    /// holds tabs or line breaks (then it is pasted into the table at that cell). `view` is the
    /// graph level being edited (a window of another level is not shown and takes nothing).
    pub fn claim_input(&mut self, ctx: &egui::Context, view: &[String]) {
        self.claimed.clear();
        let Some(window) = self
            .active
            .as_ref()
            .and_then(|key| self.windows.iter().find(|w| &w.key == key))
            .filter(|w| w.key.view == view)
        else {
            return;
        };
        let typing = window.typing();
        let rows_selected = !window.grid.rows.is_empty();
        let claimed = &mut self.claimed;
        ctx.input_mut(|i| {
            i.events.retain(|e| {
                let request = match e {
                    egui::Event::Paste(text) if !typing || text.contains(['\t', '\n']) => {
                        Request::Paste(text.clone())
                    }
                    egui::Event::Copy if !typing => Request::Copy,
                    egui::Event::Key {
                        key: egui::Key::Delete,
                        pressed: true,
                        ..
                    } if !typing && rows_selected => Request::RemoveSelected,
                    _ => return true,
                };
                claimed.push(request);
                false
            });
        });
    }

    /// Shows the windows of the level being edited and applies their changes to `doc`, each as
    /// its own undo step. Windows whose node or input is gone close. Returns a message for the
    /// status bar when something changed.
    pub fn show(&mut self, ctx: &egui::Context, doc: &mut GraphDocument) -> Option<String> {
        let view = doc.view_path();
        let pressed_at = ctx.input(|i| {
            i.pointer
                .any_pressed()
                .then(|| i.pointer.interact_pos())
                .flatten()
        });
        let pressed_layer = pressed_at.and_then(|p| ctx.layer_id_at(p));
        let mut pressed_in = None;
        let mut message = None;
        let mut requests = std::mem::take(&mut self.claimed);
        let active = self.active.clone();
        self.windows.retain_mut(|w| {
            if w.key.view != view {
                // Another level: kept for when the designer comes back.
                return true;
            }
            let Some(node) = doc.graph.node(&w.key.node) else {
                return false;
            };
            let Some(k) = node.def.input_index(&w.key.input) else {
                return false;
            };
            let wired = is_wired(&doc.graph, &w.key.node, k);
            let mine = if active.as_ref() == Some(&w.key) {
                std::mem::take(&mut requests)
            } else {
                Vec::new()
            };
            let shown = w.show(ctx, node, k, wired, mine);
            if shown.layer.is_some() && shown.layer == pressed_layer {
                pressed_in = Some(w.key.clone());
            }
            if let Some((value, what)) = shown.value {
                let edit = Edit::SetValue {
                    node: w.key.node.clone(),
                    input: w.key.input.clone(),
                    value,
                };
                // One undo step per change: a gesture of its own, never merged with another.
                doc.history.end_gesture();
                let result = crate::edit::apply(doc, edit);
                doc.history.end_gesture();
                match result {
                    Ok(_) => {
                        message = Some(format!("{}.{}: {what}", w.key.node, w.key.input));
                        w.note(what, false);
                    }
                    Err(e) => w.note(format!("refused: {e}"), true),
                }
                ctx.request_repaint();
            }
            !shown.closed
        });
        if pressed_layer.is_some() || pressed_at.is_some() {
            self.active = pressed_in;
        }
        if let Some(key) = &self.active
            && !self.windows.iter().any(|w| &w.key == key)
        {
            self.active = None;
        }
        message
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;

    fn graph() -> Graph {
        let text = r#"(
            version: 1,
            nodes: {
                "curve": (type: "curve.spline", inputs: {
                    "points": [(0.0, -0.5, 0.0), (8.0, 0.7, 0.0), (16.0, 0.0, 0.0)],
                }),
                "table": (type: "param.list", inputs: {
                    "values": [[0.5, 0.25, 1.0, 2.0], [0.5, 0.25, 1.0, 2.0]],
                    "item_type": "number",
                }),
                "profiles": (type: "param.list", inputs: {
                    "values": [(points: [(0.0, 0.0, 0.0), (0.0, 0.3, 3.0)], closed: false)],
                    "item_type": "any",
                }),
                "mapper": (type: "mapper.graph"),
                "construct": (type: "cnets.construct"),
            },
        )"#;
        let registry = Arc::new(cnets_nodes::registry());
        cnets_engine::file::load_str(text, "t.ron", &registry)
            .unwrap()
            .graph
    }

    fn input(g: &Graph, node: &str, input: &str) -> Option<OnNode> {
        let n = g.node(node).unwrap();
        on_node(n, n.def.input_index(input).unwrap())
    }

    #[test]
    fn literal_lists_show_a_summary_and_edit_only_what_a_table_holds() {
        let g = graph();
        assert_eq!(
            input(&g, "curve", "points"),
            Some(OnNode {
                summary: "3 points".into(),
                editable: true
            })
        );
        assert_eq!(
            input(&g, "table", "values"),
            Some(OnNode {
                summary: "2 × 4 numbers, 0.25 … 2".into(),
                editable: true
            })
        );
        assert_eq!(
            input(&g, "profiles", "values"),
            Some(OnNode {
                summary: "1 polyline".into(),
                editable: true
            }),
            "one polyline at a time"
        );
        assert_eq!(
            input(&g, "mapper", "handles"),
            None,
            "the mapper widget edits them"
        );
        assert_eq!(input(&g, "construct", "apex"), None, "a number field");
        assert_eq!(input(&g, "curve", "count"), None);
    }

    #[test]
    fn lists_of_polylines_or_point_lists_are_edited_a_part_at_a_time() {
        let g = graph();
        let profiles = g.node("profiles").unwrap().value_of("values").unwrap();
        assert_eq!(parts(profiles), Some(1));
        let point = Value::Point(cnets_geometry::DVec3::ZERO);
        let rows = Value::list(vec![
            Value::list(vec![point.clone(); 2]),
            Value::list(vec![]),
        ]);
        assert_eq!(parts(&rows), Some(2));
        let table = g.node("table").unwrap().value_of("values").unwrap();
        assert_eq!(parts(table), None, "a table is edited whole");
        let mixed = Value::list(vec![Value::list(vec![point]), Value::Number(1.0)]);
        assert_eq!(parts(&mixed), None);
    }

    #[test]
    fn param_list_rows_take_its_item_type() {
        let g = graph();
        let n = g.node("table").unwrap();
        let k = n.def.input_index("values").unwrap();
        assert_eq!(
            item_type(n, k),
            ItemType {
                item: ValueType::Number,
                tables: true
            }
        );
        let n = g.node("curve").unwrap();
        let k = n.def.input_index("points").unwrap();
        assert_eq!(
            item_type(n, k),
            ItemType {
                item: ValueType::Point,
                tables: false
            }
        );
    }
}
