//! Points you can grab: the points of `param.point` and `param.points` nodes shown as handles in
//! the 3D view (when the node is selected on the canvas or its preview is on), dragged, box
//! selected, nudged with the arrow keys and typed in an inspector.
//!
//! A drag moves the grabbed handle in a plane through it — the view's plane in the orthographic
//! Top, Front and Right views, the construction plane in Perspective, or along that plane's normal
//! with Ctrl (Rhino's elevator mode) — snapped to the grid unless Alt is held. The other selected
//! handles move by the same amount. Every change is one edit of the nodes' literal values
//! ([`Edit::SetPoints`]): the items not moved stay bit for bit, the list keeps its length, and a
//! whole drag is one undo step.

use std::collections::BTreeSet;

use cnets_engine::{Graph, NodeInstance, Value, Widget};
use cnets_geometry::DVec3;
use egui::{Color32, Painter, Pos2, Rect, Stroke, vec2};

use super::screen::{CPlane, ScreenMap, WorldPlane};
use crate::edit::Edit;
use crate::widgets::effective_value;

/// Screen distance (points) within which the pointer grabs a handle.
pub const GRAB_RADIUS: f32 = 8.0;

/// One handle: a point of a node's literal input.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct HandleKey {
    /// The node.
    pub node: String,
    /// The point's index in the list (0 for a single point).
    pub index: usize,
}

/// A handle and where it is.
#[derive(Clone, Debug, PartialEq)]
pub struct Handle {
    /// Which point.
    pub key: HandleKey,
    /// The index of the input holding it.
    pub input: usize,
    /// Its position.
    pub position: DVec3,
}

/// The input of `node` whose points are handles (a point, or a list of points): the one that
/// declares the point-handles widget (`param.point`'s `value`, `param.points`' `points`).
pub fn point_input(node: &NodeInstance) -> Option<usize> {
    node.def
        .inputs
        .iter()
        .position(|p| p.hint.widget == Widget::PointHandles)
}

/// The handles of `graph`'s point nodes for which `shown` says yes (wired inputs have none: their
/// points come from elsewhere).
pub fn collect(graph: &Graph, shown: impl Fn(&NodeInstance) -> bool) -> Vec<Handle> {
    let mut handles = Vec::new();
    for (_, node) in graph.nodes() {
        let Some(k) = point_input(node) else {
            continue;
        };
        if !shown(node) || crate::mapper::node::is_wired(graph, &node.id, k) {
            continue;
        }
        let points: Vec<DVec3> = match effective_value(node, k) {
            Some(Value::Point(p) | Value::Vector(p)) => vec![p],
            Some(Value::List(items)) => items.iter().filter_map(Value::as_vec3).collect(),
            _ => Vec::new(),
        };
        handles.extend(
            points
                .into_iter()
                .enumerate()
                .map(|(index, position)| Handle {
                    key: HandleKey {
                        node: node.id.clone(),
                        index,
                    },
                    input: k,
                    position,
                }),
        );
    }
    handles
}

/// The edit that moves handles to new positions: per node, its stored value with exactly those
/// points replaced (their kind of value kept; every other item, the length and the nesting
/// untouched). Points that no longer exist are skipped.
pub fn move_edit(graph: &Graph, moves: &[(HandleKey, DVec3)]) -> Option<Edit> {
    let mut values: Vec<(String, String, Value)> = Vec::new();
    let nodes: BTreeSet<&str> = moves.iter().map(|(k, _)| k.node.as_str()).collect();
    for id in nodes {
        let Some(node) = graph.node(id) else { continue };
        let Some(k) = point_input(node) else {
            continue;
        };
        let moved = |old: &Value, to: DVec3| match old {
            Value::Vector(_) => Value::Vector(to),
            _ => Value::Point(to),
        };
        let value = match effective_value(node, k) {
            Some(Value::List(items)) => {
                let mut items = items.to_vec();
                for (key, to) in moves.iter().filter(|(key, _)| key.node == id) {
                    if let Some(item) = items.get_mut(key.index)
                        && item.as_vec3().is_some()
                    {
                        *item = moved(item, *to);
                    }
                }
                Value::list(items)
            }
            Some(old @ (Value::Point(_) | Value::Vector(_))) => {
                match moves
                    .iter()
                    .find(|(key, _)| key.node == id && key.index == 0)
                {
                    Some((_, to)) => moved(&old, *to),
                    None => continue,
                }
            }
            _ => continue,
        };
        values.push((id.to_string(), node.def.inputs[k].name.to_string(), value));
    }
    (!values.is_empty()).then_some(Edit::SetPoints(values))
}

/// How a drag moves the grabbed handle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DragPlane {
    /// In a plane through the handle.
    Plane(WorldPlane, CPlane),
    /// Along the construction plane's normal (elevator mode).
    Normal(CPlane),
}

/// A drag in progress.
#[derive(Clone, Debug)]
struct Drag {
    /// The handle grabbed and where it started.
    grabbed: HandleKey,
    origin: DVec3,
    /// Where the pointer's ray met the drag plane at the press.
    grab: DVec3,
    how: DragPlane,
    /// Every moving handle and its start.
    starts: Vec<(HandleKey, DVec3)>,
}

/// The handles' interaction state: selection, a drag, a box selection.
#[derive(Default)]
pub struct HandleTool {
    /// Selected handles.
    pub selected: BTreeSet<HandleKey>,
    drag: Option<Drag>,
    /// A box selection in progress: where it started (screen).
    pub boxing: Option<Pos2>,
    /// The handle under the pointer.
    pub hovered: Option<HandleKey>,
}

/// The handle nearest the screen point within [`GRAB_RADIUS`].
pub fn handle_at<'a>(handles: &'a [Handle], map: &ScreenMap, at: Pos2) -> Option<&'a Handle> {
    handles
        .iter()
        .filter_map(|h| Some((h, map.to_screen(h.position)?.distance(at))))
        .filter(|(_, d)| *d <= GRAB_RADIUS)
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(h, _)| h)
}

/// Where a drag that grabbed at `grab` puts the handle that started at `origin`, with the
/// pointer's ray now `ray`; snapped to `step` in the drag's plane (or along its normal) when
/// `step` is given.
pub(super) fn dragged_to(
    how: DragPlane,
    origin: DVec3,
    grab: DVec3,
    map: &ScreenMap,
    at: Pos2,
    step: Option<f64>,
) -> Option<DVec3> {
    let ray = map.ray(at);
    match how {
        DragPlane::Plane(plane, snap_plane) => {
            let hit = plane.hit(&ray)?;
            let p = origin + (hit - grab);
            Some(step.map_or(p, |s| snap_plane.snap(p, s)))
        }
        DragPlane::Normal(cplane) => {
            // The plane containing the normal through the handle that faces the camera best.
            let n = cplane.normal();
            let side = map.back() - n * map.back().dot(n);
            if side.length() < 1e-9 {
                return None;
            }
            let plane = WorldPlane {
                origin,
                normal: side.normalize(),
            };
            let hit = plane.hit(&ray)?;
            let p = origin + n * (hit - grab).dot(n);
            Some(step.map_or(p, |s| cplane.snap_normal(p, s)))
        }
    }
}

impl HandleTool {
    /// Whether a handle drag is in progress.
    pub fn dragging(&self) -> bool {
        self.drag.is_some()
    }

    /// Starts a drag of the handle under `at` (selecting it, unless it is already selected with
    /// others); `how` is the plane to move in. Returns whether a handle was grabbed.
    pub fn press(
        &mut self,
        handles: &[Handle],
        map: &ScreenMap,
        at: Pos2,
        how: impl Fn(DVec3) -> DragPlane,
        add: bool,
    ) -> bool {
        let Some(h) = handle_at(handles, map, at) else {
            return false;
        };
        if add {
            self.selected.insert(h.key.clone());
        } else if !self.selected.contains(&h.key) {
            self.selected = [h.key.clone()].into();
        }
        let how = how(h.position);
        let grab = match how {
            DragPlane::Plane(plane, _) => plane.hit(&map.ray(at)),
            DragPlane::Normal(_) => Some(h.position),
        };
        let Some(grab) = grab else {
            return false;
        };
        let grab = match how {
            DragPlane::Normal(cplane) => {
                // Where the ray meets the elevator plane, so the first move does not jump.
                let n = cplane.normal();
                let side = map.back() - n * map.back().dot(n);
                WorldPlane {
                    origin: h.position,
                    normal: side.normalize(),
                }
                .hit(&map.ray(at))
                .unwrap_or(grab)
            }
            DragPlane::Plane(..) => grab,
        };
        let starts = handles
            .iter()
            .filter(|o| self.selected.contains(&o.key))
            .map(|o| (o.key.clone(), o.position))
            .collect();
        self.drag = Some(Drag {
            grabbed: h.key.clone(),
            origin: h.position,
            grab,
            how,
            starts,
        });
        true
    }

    /// Moves the drag to `at`: the edit that puts every moving handle there (`None` when nothing
    /// moves).
    pub fn drag_to(
        &self,
        graph: &Graph,
        map: &ScreenMap,
        at: Pos2,
        step: Option<f64>,
    ) -> Option<Edit> {
        let d = self.drag.as_ref()?;
        let to = dragged_to(d.how, d.origin, d.grab, map, at, step)?;
        let delta = to - d.origin;
        let moves: Vec<(HandleKey, DVec3)> = d
            .starts
            .iter()
            .map(|(k, start)| {
                let p = if *k == d.grabbed { to } else { *start + delta };
                (k.clone(), p)
            })
            .collect();
        move_edit(graph, &moves)
    }

    /// Ends the drag.
    pub fn release(&mut self) {
        self.drag = None;
    }

    /// Finishes a box selection from the press point to `to`: the handles inside are selected
    /// (added to the selection with `add`).
    pub fn select_box(&mut self, handles: &[Handle], map: &ScreenMap, to: Pos2, add: bool) {
        let Some(from) = self.boxing.take() else {
            return;
        };
        let rect = Rect::from_two_pos(from, to);
        if !add {
            self.selected.clear();
        }
        for h in handles {
            if map.to_screen(h.position).is_some_and(|p| rect.contains(p)) {
                self.selected.insert(h.key.clone());
            }
        }
    }

    /// Drops selected handles that no longer exist.
    pub fn retain_existing(&mut self, handles: &[Handle]) {
        self.selected
            .retain(|k| handles.iter().any(|h| &h.key == k));
        if self
            .drag
            .as_ref()
            .is_some_and(|d| !handles.iter().any(|h| h.key == d.grabbed))
        {
            self.drag = None;
        }
    }

    /// The edit that moves the selected handles by `delta`.
    pub fn nudge(&self, graph: &Graph, handles: &[Handle], delta: DVec3) -> Option<Edit> {
        let moves: Vec<(HandleKey, DVec3)> = handles
            .iter()
            .filter(|h| self.selected.contains(&h.key))
            .map(|h| (h.key.clone(), h.position + delta))
            .collect();
        if moves.is_empty() {
            return None;
        }
        move_edit(graph, &moves)
    }

    /// Paints the handles (selected filled, hovered larger) and a box selection in progress.
    pub fn paint(
        &self,
        painter: &Painter,
        handles: &[Handle],
        map: &ScreenMap,
        pointer: Option<Pos2>,
    ) {
        let ink = Color32::from_rgb(0x20, 0x24, 0x2c);
        let selected_fill = Color32::from_rgb(0xf2, 0xb1, 0x1b);
        for h in handles {
            let Some(p) = map.to_screen(h.position) else {
                continue;
            };
            if !map.rect.expand(GRAB_RADIUS).contains(p) {
                continue;
            }
            let hot = self.hovered.as_ref() == Some(&h.key);
            let half = if hot { 5.5 } else { 4.0 };
            let fill = if self.selected.contains(&h.key) {
                selected_fill
            } else {
                Color32::WHITE
            };
            let r = Rect::from_center_size(p, vec2(2.0 * half, 2.0 * half));
            painter.rect_filled(r, 1.0, fill);
            painter.rect_stroke(r, 1.0, Stroke::new(1.5, ink), egui::StrokeKind::Middle);
        }
        if let (Some(from), Some(to)) = (self.boxing, pointer) {
            let r = Rect::from_two_pos(from, to);
            painter.rect_filled(r, 0.0, Color32::from_rgba_unmultiplied(80, 140, 230, 30));
            painter.rect_stroke(
                r,
                0.0,
                Stroke::new(1.0, Color32::from_rgb(80, 140, 230)),
                egui::StrokeKind::Middle,
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;

    fn graph() -> Graph {
        let mut g = Graph::new(Arc::new(cnets_nodes::registry()));
        g.add_node("pts", "param.points").unwrap();
        g.set_value(
            "pts",
            "points",
            Value::list(vec![
                Value::Point(DVec3::new(0.1, 0.2, 0.3)),
                Value::Point(DVec3::new(1.0, 2.0, 3.0)),
                Value::Point(DVec3::new(-1.0, 0.5, 0.0)),
            ]),
        )
        .unwrap();
        g.add_node("p", "param.point").unwrap();
        g
    }

    #[test]
    fn handles_come_from_point_nodes_and_a_move_replaces_only_its_point() {
        let g = graph();
        let handles = collect(&g, |_| true);
        assert_eq!(handles.len(), 4, "three points and the single point");
        let key = HandleKey {
            node: "pts".into(),
            index: 1,
        };
        let Some(Edit::SetPoints(values)) = move_edit(&g, &[(key, DVec3::new(5.0, 5.0, 5.0))])
        else {
            panic!("an edit")
        };
        let (node, input, value) = &values[0];
        assert_eq!((node.as_str(), input.as_str()), ("pts", "points"));
        let items = value.as_list().unwrap();
        assert_eq!(items.len(), 3);
        assert_eq!(
            items[0],
            Value::Point(DVec3::new(0.1, 0.2, 0.3)),
            "untouched"
        );
        assert_eq!(items[1], Value::Point(DVec3::new(5.0, 5.0, 5.0)));
        assert!(collect(&g, |n| n.id == "p").len() == 1);
    }
}
