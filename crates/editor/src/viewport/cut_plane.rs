//! Which side a cut keeps, shown: while a node with a [`Role::CutPlane`] input (`mesh.cut_by_plane`)
//! is selected, the 3D view draws its plane as a translucent square and an arrow from the plane
//! into the kept side — the side the normal points to, the other one when the node's
//! [`Role::FlipsSide`] input is on. A plane given on the node (typed, or its default) is drawn; a
//! wired one is not (its value is the worker's).

use cnets_engine::{Graph, NodeInstance, Role, Value};
use cnets_geometry::DVec3;
use egui::{Color32, Painter, Pos2, Shape, Stroke};

use super::screen::ScreenMap;
use crate::widgets::effective_value;

/// A cut to draw: its plane and the side it keeps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CutOverlay {
    /// A point of the plane.
    pub origin: DVec3,
    /// Two unit axes in the plane.
    pub axes: [DVec3; 2],
    /// The unit normal pointing into the kept side.
    pub kept: DVec3,
}

/// The input of `node` with `role`, when it is not wired.
fn literal_with_role(graph: &Graph, node: &NodeInstance, role: Role) -> Option<Value> {
    let k = node.def.inputs.iter().position(|p| p.hint.role == role)?;
    let index = graph.index(&node.id).ok()?;
    if graph.wires_into(index).iter().any(|(_, w)| w.to_input == k) {
        return None;
    }
    effective_value(node, k)
}

/// The cuts of the selected nodes whose plane is given on the node.
pub fn selected_cuts(graph: &Graph, selected: &[String]) -> Vec<CutOverlay> {
    selected
        .iter()
        .filter_map(|id| graph.node(id))
        .filter_map(|node| {
            let Some(Value::Plane(plane)) = literal_with_role(graph, node, Role::CutPlane) else {
                return None;
            };
            let flipped = matches!(
                literal_with_role(graph, node, Role::FlipsSide),
                Some(Value::Boolean(true))
            );
            let normal = plane.normal.try_normalize()?;
            Some(CutOverlay {
                origin: plane.origin,
                axes: [plane.x_axis, plane.y_axis],
                kept: if flipped { -normal } else { normal },
            })
        })
        .collect()
}

/// The colour of a drawn cut plane (translucent) and of its outline and arrow.
const FILL: Color32 = Color32::from_rgba_premultiplied(0x3a, 0x6e, 0xc8, 0x30);
const INK: Color32 = Color32::from_rgb(0x2a, 0x5a, 0xb0);

/// Draws `cuts` as squares of half-size `half` (model units) around their origins, with an arrow
/// of length `half` into the kept side labelled "kept".
pub fn paint(painter: &Painter, map: &ScreenMap, cuts: &[CutOverlay], half: f64) {
    for cut in cuts {
        let [u, v] = cut.axes;
        let corners: Option<Vec<Pos2>> = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
            .iter()
            .map(|(a, b)| map.to_screen(cut.origin + (u * *a + v * *b) * half))
            .collect();
        if let Some(corners) = corners {
            painter.add(Shape::convex_polygon(
                corners.clone(),
                FILL,
                Stroke::new(1.5, INK),
            ));
        }
        let (Some(from), Some(to)) = (
            map.to_screen(cut.origin),
            map.to_screen(cut.origin + cut.kept * half),
        ) else {
            continue;
        };
        painter.arrow(from, to - from, Stroke::new(2.5, INK));
        painter.text(
            to + (to - from).normalized() * 10.0,
            egui::Align2::CENTER_CENTER,
            "kept",
            egui::FontId::proportional(13.0),
            INK,
        );
    }
}
