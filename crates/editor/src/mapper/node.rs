//! A graph-mapper node's data as the editor reads it: which inputs hold the handles and the
//! curve kind (the ports that declare the mapper-handles widget and a choice; nothing matched by
//! name), and what the widget shows — the kind
//! and the handles the node really runs on (a wired input's value comes from the last evaluation),
//! row by row when the handles are a tree — and the one way an edit writes a handle back without
//! changing the nesting or the number of items of the stored value.

use cnets_engine::{Graph, NodeInstance, Value, Widget};
use cnets_geometry::DVec3;
use cnets_geometry::curves::MapperKind;
use glam::DVec2;

use crate::widgets::effective_value;

/// Whether a node gets the graph-mapper widget: it has a handles input and a curve-kind input.
pub fn is_mapper(node: &NodeInstance) -> bool {
    handles_port(node).is_some() && kind_port(node).is_some()
}

/// Index of the handles input: the input whose declared widget is the mapper's handles.
pub fn handles_port(node: &NodeInstance) -> Option<usize> {
    node.def
        .inputs
        .iter()
        .position(|p| p.hint.widget == Widget::MapperHandles)
}

/// Index of the curve-kind input: the first choice input of a node with mapper handles.
pub fn kind_port(node: &NodeInstance) -> Option<usize> {
    handles_port(node)?;
    node.def.inputs.iter().position(|p| p.choices.is_some())
}

/// The kind set on the node (`None` when it is not a known kind; the first one of a list).
pub fn kind(node: &NodeInstance) -> Option<MapperKind> {
    kinds_of(effective_value(node, kind_port(node)?).as_ref())
        .first()
        .copied()
        .flatten()
}

/// The handles of a mapper node's first row: its literal list, else the kind's defaults.
pub fn handles(node: &NodeInstance) -> Vec<DVec2> {
    let stored = handles_port(node).and_then(|k| effective_value(node, k));
    let rows = rows_of(stored.as_ref());
    match rows.rows.into_iter().next() {
        Some(row) if !row.is_empty() => row,
        _ => kind(node)
            .map(MapperKind::default_handles)
            .unwrap_or_default(),
    }
}

/// The kinds a kind value names: one for a text, one per item for a list of texts (`None` for a
/// name that is not a kind).
fn kinds_of(value: Option<&Value>) -> Vec<Option<MapperKind>> {
    match value {
        Some(Value::Text(t)) => vec![MapperKind::parse(t).ok()],
        Some(Value::List(items)) => items
            .iter()
            .map(|v| match v {
                Value::Text(t) => MapperKind::parse(t).ok(),
                _ => None,
            })
            .collect(),
        _ => Vec::new(),
    }
}

/// Handle rows read from a handles value.
struct Rows {
    rows: Vec<Vec<DVec2>>,
    /// The value is a list of rows (a tree), not one list of points.
    nested: bool,
    /// The value nests deeper than rows of points, or holds something else than points: shown,
    /// not edited.
    irregular: bool,
}

fn point_of(v: &Value) -> Option<DVec2> {
    v.as_vec3().map(|p| p.truncate())
}

fn rows_of(value: Option<&Value>) -> Rows {
    let flat = |items: &[Value]| -> (Vec<DVec2>, bool) {
        let points: Vec<DVec2> = items.iter().filter_map(point_of).collect();
        let irregular = points.len() != items.len();
        (points, irregular)
    };
    match value {
        None | Some(Value::Null) => Rows {
            rows: Vec::new(),
            nested: false,
            irregular: false,
        },
        Some(Value::Point(p)) | Some(Value::Vector(p)) => Rows {
            rows: vec![vec![p.truncate()]],
            nested: false,
            irregular: false,
        },
        Some(Value::List(items)) if items.iter().any(|v| matches!(v, Value::List(_))) => {
            let mut irregular = false;
            let rows = items
                .iter()
                .map(|row| match row {
                    Value::List(inner) => {
                        let (points, odd) = flat(inner);
                        irregular |= odd;
                        points
                    }
                    other => {
                        irregular = true;
                        point_of(other).into_iter().collect()
                    }
                })
                .collect();
            Rows {
                rows,
                nested: true,
                irregular,
            }
        }
        Some(Value::List(items)) => {
            let (points, irregular) = flat(items);
            Rows {
                rows: vec![points],
                nested: false,
                irregular,
            }
        }
        Some(_) => Rows {
            rows: Vec::new(),
            nested: false,
            irregular: true,
        },
    }
}

/// What the mapper widget shows for a node: the truth of what the node runs on.
#[derive(Clone, Debug, PartialEq)]
pub struct Shown {
    /// The kind of each row (one entry when all rows share it); `None` where it is not a kind.
    pub kinds: Vec<Option<MapperKind>>,
    /// The kind comes from a wire (read-only in the widget).
    pub kind_wired: bool,
    /// The handle rows (one row for a flat list).
    pub rows: Vec<Vec<DVec2>>,
    /// The handles are a tree: one row per branch.
    pub nested: bool,
    /// The handles come from a wire (read-only in the widget).
    pub handles_wired: bool,
    /// No handles are set: the rows are the kind's defaults (a drag writes them).
    pub defaults: bool,
    /// A wired value has not been evaluated yet (or its source failed): nothing true to show.
    pub unknown: bool,
    /// The stored value nests deeper than rows or holds other values: shown, not edited.
    pub irregular: bool,
}

impl Shown {
    /// The kind of row `r` (longest-list matching: the last kind repeats).
    pub fn kind(&self, r: usize) -> Option<MapperKind> {
        self.kinds
            .get(r.min(self.kinds.len().saturating_sub(1)))
            .copied()
            .flatten()
    }

    /// Whether the handles may be dragged.
    pub fn editable(&self) -> bool {
        !self.handles_wired && !self.unknown && !self.irregular
    }
}

/// Whether input `k` of the node `id` has a wire in `graph`.
pub fn is_wired(graph: &Graph, id: &str, k: usize) -> bool {
    graph
        .index(id)
        .is_ok_and(|index| graph.wires_into(index).iter().any(|(_, w)| w.to_input == k))
}

/// What the widget shows for `node` of `graph`; `ran_on` is the input values the node last ran on
/// (from the evaluation; wired inputs are read from it).
pub fn shown(graph: &Graph, node: &NodeInstance, ran_on: Option<&[Value]>) -> Option<Shown> {
    let (kind_k, handles_k) = (kind_port(node)?, handles_port(node)?);
    let value = |k: usize, wired: bool| -> (Option<Value>, bool) {
        if wired {
            match ran_on.and_then(|v| v.get(k)) {
                Some(v) => (Some(v.clone()), false),
                None => (None, true),
            }
        } else {
            (effective_value(node, k), false)
        }
    };
    let kind_wired = is_wired(graph, &node.id, kind_k);
    let handles_wired = is_wired(graph, &node.id, handles_k);
    let (kind_value, kind_unknown) = value(kind_k, kind_wired);
    let (handles_value, handles_unknown) = value(handles_k, handles_wired);
    let kinds = kinds_of(kind_value.as_ref());
    let Rows {
        mut rows,
        nested,
        irregular,
    } = rows_of(handles_value.as_ref());
    let empty = rows.iter().all(Vec::is_empty);
    let defaults = empty && !handles_unknown;
    if defaults {
        // The node runs each kind on its default handles (one row per kind of a list).
        let count = kinds.len().max(1);
        rows = (0..count)
            .map(|r| {
                kinds
                    .get(r)
                    .copied()
                    .flatten()
                    .map(MapperKind::default_handles)
                    .unwrap_or_default()
            })
            .collect();
    }
    Some(Shown {
        kinds,
        kind_wired,
        rows,
        nested,
        handles_wired,
        defaults,
        unknown: kind_unknown || handles_unknown,
        irregular: irregular && !defaults,
    })
}

/// The stored handles value with handle `k` of row `row` moved to `to` (its z and its kind of
/// value kept): the nesting and the number of items stay exactly as stored. With no handles set,
/// the shown default row is written whole (a flat list). `None` when the position does not exist.
pub fn with_handle_moved(
    stored: Option<&Value>,
    shown: &Shown,
    row: usize,
    k: usize,
    to: DVec2,
) -> Option<Value> {
    let moved = |p: &Value| -> Option<Value> {
        match p {
            Value::Point(q) => Some(Value::Point(DVec3::new(to.x, to.y, q.z))),
            Value::Vector(q) => Some(Value::Vector(DVec3::new(to.x, to.y, q.z))),
            _ => None,
        }
    };
    let replace = |items: &[Value], k: usize, with: Value| -> Value {
        let mut items = items.to_vec();
        items[k] = with;
        Value::list(items)
    };
    if shown.defaults {
        let mut points = shown.rows.get(row)?.clone();
        *points.get_mut(k)? = to;
        return Some(Value::list(
            points
                .into_iter()
                .map(|p| Value::Point(DVec3::new(p.x, p.y, 0.0)))
                .collect(),
        ));
    }
    match stored? {
        single @ (Value::Point(_) | Value::Vector(_)) if row == 0 && k == 0 => moved(single),
        Value::List(rows) if shown.nested => {
            let Value::List(items) = rows.get(row)? else {
                return None;
            };
            let point = moved(items.get(k)?)?;
            Some(replace(rows, row, replace(items, k, point)))
        }
        Value::List(items) if row == 0 => {
            let point = moved(items.get(k)?)?;
            Some(replace(items, k, point))
        }
        _ => None,
    }
}

/// The shape of a value: nesting and item counts (a leaf is `None`), for checks that an edit kept
/// it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Shape {
    /// Not a list.
    Leaf,
    /// A list of items of these shapes.
    List(Vec<Shape>),
}

/// The shape of `value`.
pub fn shape(value: &Value) -> Shape {
    match value {
        Value::List(items) => Shape::List(items.iter().map(shape).collect()),
        _ => Shape::Leaf,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;

    fn p(u: f64, v: f64) -> Value {
        Value::Point(DVec3::new(u, v, 0.25))
    }

    fn graph_with(handles: Value) -> Graph {
        let mut g = Graph::new(Arc::new(cnets_nodes::registry()));
        g.add_node("m", "mapper.graph").unwrap();
        g.set_value("m", "kind", Value::text("piecewise")).unwrap();
        g.set_value("m", "handles", handles).unwrap();
        g
    }

    #[test]
    fn a_tree_of_handles_is_shown_row_by_row_and_a_drag_keeps_its_shape() {
        let tree = Value::list(vec![
            Value::list(vec![p(0.0, 0.1), p(0.5, 0.5), p(1.0, 0.9)]),
            Value::list(vec![p(0.0, 0.2), p(1.0, 0.3)]),
        ]);
        let g = graph_with(tree.clone());
        let node = g.node("m").unwrap();
        let s = shown(&g, node, None).unwrap();
        assert!(s.nested && s.editable() && !s.defaults);
        assert_eq!(s.rows.len(), 2);
        assert_eq!(s.rows[1], vec![DVec2::new(0.0, 0.2), DVec2::new(1.0, 0.3)]);
        let stored = node.value_of("handles");
        let after = with_handle_moved(stored, &s, 1, 1, DVec2::new(0.9, 0.4)).unwrap();
        assert_eq!(shape(&after), shape(&tree));
        let Value::List(rows) = &after else { panic!() };
        assert_eq!(rows[0], tree.as_list().unwrap()[0], "row 0 untouched");
        assert_eq!(
            rows[1].as_list().unwrap()[1],
            Value::Point(DVec3::new(0.9, 0.4, 0.25)),
            "z kept"
        );
    }

    #[test]
    fn no_handles_shows_the_kind_defaults_and_a_drag_writes_that_row() {
        let mut g = Graph::new(Arc::new(cnets_nodes::registry()));
        g.add_node("m", "mapper.graph").unwrap();
        g.set_value("m", "kind", Value::text("bezier")).unwrap();
        let node = g.node("m").unwrap();
        let s = shown(&g, node, None).unwrap();
        assert!(s.defaults && !s.nested);
        assert_eq!(s.rows[0], MapperKind::Bezier.default_handles());
        let after = with_handle_moved(None, &s, 0, 0, DVec2::new(0.1, 0.1)).unwrap();
        assert_eq!(after.as_list().unwrap().len(), 4);
    }

    #[test]
    fn a_wired_kind_is_read_from_the_values_the_node_ran_on() {
        let mut g = Graph::new(Arc::new(cnets_nodes::registry()));
        g.add_node("m", "mapper.graph").unwrap();
        g.add_node("t", "param.text").unwrap();
        g.connect("t", "value", "m", "kind").unwrap();
        let node = g.node("m").unwrap();
        let s = shown(&g, node, None).unwrap();
        assert!(
            s.kind_wired && s.unknown,
            "not evaluated yet: nothing to claim"
        );
        let mut ran_on: Vec<Value> = node
            .def
            .inputs
            .iter()
            .map(|p| p.default.clone().unwrap_or_default())
            .collect();
        ran_on[kind_port(node).unwrap()] = Value::text("bezier");
        let s = shown(&g, node, Some(&ran_on)).unwrap();
        assert_eq!(s.kind(0), Some(MapperKind::Bezier));
        assert_eq!(s.rows[0], MapperKind::Bezier.default_handles());
        assert!(!s.unknown);
    }
}
