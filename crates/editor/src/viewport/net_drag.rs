//! The Drag net tool (G): grab a vertex of a previewed cone-net and drag it; the design's free
//! inputs are solved so the vertex follows the pointer ([`crate::net_drag`] solves, off the UI
//! thread). Shift+click pins a vertex (pins hold still while another is dragged); Esc clears the
//! pins, and with none leaves the tool.
//!
//! The grabbed vertex moves as a handle does: in the view's plane through it (Top, Front,
//! Right), in the construction plane through it (Perspective), or along that plane's normal with
//! Ctrl. Where the inputs cannot take it, the view draws a line from where the vertex stopped to
//! the pointer's target and the status bar gives the distance left.

use cnets_geometry::DVec3;
use egui::{Color32, Painter, Pos2, Stroke, vec2};

use super::handles::{DragPlane, dragged_to};
use super::pick::{self, Hit};
use super::screen::ScreenMap;
use crate::preview::Picks;
use crate::worker::format_number;

/// A vertex of a previewed quad mesh: its node, its (row i, column j) and where it is.
#[derive(Clone, Debug, PartialEq)]
pub struct NetVertex {
    /// The node whose mesh it belongs to.
    pub node: String,
    /// Which of the node's nets when its output is a list of them.
    pub item: Option<usize>,
    /// (i along the generatrix, j along the directrix).
    pub vertex: (usize, usize),
    /// Its position.
    pub position: DVec3,
}

/// A drag in progress.
#[derive(Clone, Debug, PartialEq)]
struct Grab {
    vertex: NetVertex,
    /// Where the pointer's ray met the drag plane at the press.
    grab: DVec3,
    how: DragPlane,
    /// Where the pointer asks the vertex to be.
    target: DVec3,
}

/// What the view asks the solver for while a vertex is dragged.
#[derive(Clone, Debug, PartialEq)]
pub struct NetDragTarget {
    /// The grabbed vertex (its position at the press).
    pub grabbed: NetVertex,
    /// Where it should go.
    pub target: DVec3,
    /// The pins on the same net: vertex and where it must stay.
    pub pins: Vec<((usize, usize), DVec3)>,
}

/// The Drag net tool's state: its pins and the drag in progress.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NetDragTool {
    /// Pinned vertices.
    pub pins: Vec<NetVertex>,
    grab: Option<Grab>,
    /// Where the last solve left the grabbed vertex, and its distance to the target.
    pub reached: Option<(DVec3, f64)>,
}

/// The vertex of a previewed quad mesh under `at`: a picked vertex, or the picked face's corner
/// nearest the pointer on screen (quad meshes only, one of a list included).
pub fn vertex_at(picks: &Picks, map: &ScreenMap, at: Pos2) -> Option<NetVertex> {
    let hit = pick::pick(picks, map, at)?;
    let mesh = &picks.meshes[hit.mesh()];
    let index = match hit {
        Hit::Vertex { vertex, .. } => vertex,
        Hit::Face { face, .. } => {
            pick::face_vertex_indices(&mesh.geometry, face)
                .into_iter()
                .filter_map(|v| {
                    let p = map.to_screen(*mesh.geometry.vertices().get(v)?)?;
                    Some((v, p.distance(at)))
                })
                .min_by(|a, b| a.1.total_cmp(&b.1))?
                .0
        }
    };
    Some(NetVertex {
        node: mesh.node.clone(),
        item: mesh.item,
        vertex: mesh.geometry.vertex_row_col(index)?,
        position: *mesh.geometry.vertices().get(index)?,
    })
}

impl NetDragTool {
    /// Whether a vertex is being dragged.
    pub fn dragging(&self) -> bool {
        self.grab.is_some()
    }

    /// The vertex being dragged.
    pub fn grabbed(&self) -> Option<&NetVertex> {
        self.grab.as_ref().map(|g| &g.vertex)
    }

    /// Starts dragging the vertex under `at` (`how`: the plane it moves in, given its
    /// position). Returns whether one was grabbed.
    pub fn press(
        &mut self,
        picks: &Picks,
        map: &ScreenMap,
        at: Pos2,
        how: impl Fn(DVec3) -> DragPlane,
    ) -> bool {
        let Some(vertex) = vertex_at(picks, map, at) else {
            return false;
        };
        let how = how(vertex.position);
        let grab = match how {
            DragPlane::Plane(plane, _) => plane.hit(&map.ray(at)),
            DragPlane::Normal(_) => Some(vertex.position),
        };
        let Some(grab) = grab else {
            return false;
        };
        self.reached = Some((vertex.position, 0.0));
        self.grab = Some(Grab {
            target: vertex.position,
            vertex,
            grab,
            how,
        });
        true
    }

    /// Moves the drag to the pointer at `at`: what to solve for (`None` when the pointer's ray
    /// misses the drag plane or the target did not change).
    pub fn drag_to(&mut self, map: &ScreenMap, at: Pos2) -> Option<NetDragTarget> {
        let g = self.grab.as_mut()?;
        let target = dragged_to(g.how, g.vertex.position, g.grab, map, at, None)?;
        if target == g.target {
            return None;
        }
        g.target = target;
        let pins = self
            .pins
            .iter()
            .filter(|p| {
                p.node == g.vertex.node && p.item == g.vertex.item && p.vertex != g.vertex.vertex
            })
            .map(|p| (p.vertex, p.position))
            .collect();
        Some(NetDragTarget {
            grabbed: g.vertex.clone(),
            target,
            pins,
        })
    }

    /// Ends the drag.
    pub fn release(&mut self) {
        self.grab = None;
    }

    /// Pins the vertex under `at`, or unpins it when it is pinned. Returns the status text.
    pub fn toggle_pin(&mut self, picks: &Picks, map: &ScreenMap, at: Pos2) -> Option<String> {
        let v = vertex_at(picks, map, at)?;
        let (i, j) = v.vertex;
        if let Some(k) = self
            .pins
            .iter()
            .position(|p| p.node == v.node && p.item == v.item && p.vertex == v.vertex)
        {
            self.pins.remove(k);
            return Some(format!("unpinned {} (i {i}, j {j})", v.node));
        }
        let text = format!(
            "pinned {} (i {i}, j {j}): it stays put while another vertex is dragged (Esc clears \
             the pins)",
            v.node
        );
        self.pins.push(v);
        Some(text)
    }

    /// The status bar's line for the drag in progress.
    pub fn status(&self) -> Option<String> {
        let g = self.grab.as_ref()?;
        let (i, j) = g.vertex.vertex;
        let left = self.reached.map_or(0.0, |r| r.1);
        Some(if left > REACHED {
            format!(
                "dragging {} (i {i}, j {j}): the inputs cannot take it further, {} m left",
                g.vertex.node,
                format_number(left)
            )
        } else {
            format!("dragging {} (i {i}, j {j})", g.vertex.node)
        })
    }

    /// Paints the pins, the grabbed vertex and, when it stopped short, the line to the target.
    pub fn paint(&self, painter: &Painter, map: &ScreenMap, hover: Option<DVec3>) {
        let ink = Color32::from_rgb(0xc0, 0x1c, 0x28);
        for pin in &self.pins {
            if let Some(p) = map.to_screen(pin.position) {
                paint_pin(painter, p, ink);
            }
        }
        let Some(g) = &self.grab else {
            if let Some(h) = hover.and_then(|h| map.to_screen(h)) {
                painter.circle_stroke(h, 5.0, Stroke::new(1.5, GRAB_INK));
            }
            return;
        };
        let (at, left) = self.reached.unwrap_or((g.vertex.position, 0.0));
        let Some(sa) = map.to_screen(at) else {
            return;
        };
        if left > REACHED
            && let Some(st) = map.to_screen(g.target)
        {
            painter.line_segment([sa, st], Stroke::new(1.5, ink));
            painter.circle_stroke(st, 4.0, Stroke::new(1.5, ink));
        }
        painter.circle(sa, 5.0, GRAB_INK, Stroke::new(1.5, Color32::WHITE));
    }
}

/// Distance (m) under which the grabbed vertex counts as at its target.
const REACHED: f64 = 1e-4;

/// The grabbed vertex's colour.
const GRAB_INK: Color32 = Color32::from_rgb(0x1f, 0x6f, 0xd1);

/// A pin: a needle with a round head above the vertex.
fn paint_pin(painter: &Painter, at: Pos2, ink: Color32) {
    let head = at + vec2(0.0, -11.0);
    painter.line_segment([at, head], Stroke::new(2.0, ink));
    painter.circle(head, 4.5, ink, Stroke::new(1.0, Color32::WHITE));
    painter.circle_filled(at, 2.0, ink);
}
