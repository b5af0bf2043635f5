//! The canvas's overview: when the graph does not fit in the canvas at a readable zoom, a small map
//! in the canvas's bottom-right corner shows every node as a box — the previewed ones (what the 3D
//! view shows) in the accent colour, failed ones red — and frames the part in view; a click or a
//! drag there moves the view to that point. So a graph larger than its canvas always shows that
//! more is there, and where.

use std::collections::HashMap;

use cnets_engine::Graph;
use egui::{Color32, Pos2, Rect, Sense, Ui, Vec2, pos2, vec2};

use crate::canvas::Canvas;
use crate::worker::NodeStatus;

/// The overview's largest size in points.
pub const MAX_SIZE: Vec2 = vec2(220.0, 140.0);
/// A node that was never drawn is counted this big (canvas points).
const UNMEASURED: Vec2 = vec2(220.0, 120.0);

/// Every node's rectangle in canvas coordinates: as drawn, else at its position (borrowed ids:
/// called twice a frame over every node of the graph).
pub fn node_rects<'a>(
    canvas: &'a Canvas,
    graph: &'a Graph,
) -> impl Iterator<Item = (&'a str, Rect)> + 'a {
    graph.nodes().map(|(_, n)| {
        let r = canvas
            .node_rect(&n.id)
            .unwrap_or_else(|| Rect::from_min_size(pos2(n.position[0], n.position[1]), UNMEASURED));
        (n.id.as_str(), r)
    })
}

/// Where the overview goes and how canvas points map into it, when the graph does not fit in
/// the canvas's view; `None` when it fits (or nothing is drawn yet).
pub fn placement(canvas: &Canvas, graph: &Graph) -> Option<(Rect, Rect)> {
    let screen = canvas.screen_rect();
    if !screen.is_positive() || graph.node_count() == 0 {
        return None;
    }
    let view = Rect::from_two_pos(canvas.to_canvas(screen.min), canvas.to_canvas(screen.max));
    let all = node_rects(canvas, graph)
        .map(|(_, r)| r)
        .reduce(|a, b| a.union(b))?;
    if view.contains_rect(all) {
        return None;
    }
    let bounds = all.union(view).expand(20.0);
    let max = vec2(
        MAX_SIZE.x.min(screen.width() * 0.45),
        MAX_SIZE.y.min(screen.height() * 0.4),
    );
    let scale = (max.x / bounds.width()).min(max.y / bounds.height());
    let size = bounds.size() * scale;
    let map = Rect::from_min_size(screen.right_bottom() - size - vec2(10.0, 10.0), size);
    Some((map, bounds))
}

/// Shows the overview over the canvas (drawn this frame in `ui`); returns the canvas point to
/// bring to the middle of the view when it was clicked or dragged.
pub fn show(
    ui: &Ui,
    canvas: &Canvas,
    graph: &Graph,
    statuses: &HashMap<String, NodeStatus>,
) -> Option<Pos2> {
    let (map, bounds) = placement(canvas, graph)?;
    let to_map = |p: Pos2| map.min + (p - bounds.min) * (map.width() / bounds.width());
    let to_canvas = |p: Pos2| bounds.min + (p - map.min) * (bounds.width() / map.width());
    let visuals = ui.visuals().clone();
    let mut moved = None;
    egui::Area::new(egui::Id::new("cnets-canvas-overview"))
        .fixed_pos(map.min)
        .show(ui.ctx(), |ui| {
            let (rect, response) = ui.allocate_exact_size(map.size(), Sense::click_and_drag());
            let painter = ui.painter_at(rect);
            painter.rect_filled(rect, 3.0, visuals.extreme_bg_color.gamma_multiply(0.92));
            painter.rect_stroke(
                rect,
                3.0,
                visuals.widgets.noninteractive.bg_stroke,
                egui::StrokeKind::Inside,
            );
            let mut hovered = None;
            let pointer = response.hover_pos();
            // One mesh of plain boxes (two triangles each, no rounding or feathering): a graph of
            // thousands of nodes is drawn in every frame.
            let mut boxes = egui::Mesh::default();
            for (id, r) in node_rects(canvas, graph) {
                // At least a point each way, so a node of a tall graph still shows.
                let boxed = Rect::from_min_max(to_map(r.min), to_map(r.max));
                let boxed =
                    Rect::from_center_size(boxed.center(), boxed.size().max(vec2(1.0, 1.0)));
                let shown = graph.node(id).is_some_and(|n| n.preview && n.enabled);
                let fill = match statuses.get(id) {
                    Some(NodeStatus::Error(_)) => Color32::from_rgb(0xd6, 0x2f, 0x2f),
                    _ if shown => visuals.selection.bg_fill,
                    _ => visuals.widgets.inactive.bg_fill,
                };
                boxes.add_colored_rect(boxed.intersect(rect), fill);
                if pointer.is_some_and(|p| boxed.expand(2.0).contains(p)) {
                    hovered = Some(id.to_string());
                }
            }
            painter.add(boxes);
            let screen = canvas.screen_rect();
            let view = Rect::from_min_max(
                to_map(canvas.to_canvas(screen.min)),
                to_map(canvas.to_canvas(screen.max)),
            );
            painter.rect_stroke(
                view.intersect(rect),
                1.0,
                egui::Stroke::new(1.5, visuals.strong_text_color()),
                egui::StrokeKind::Inside,
            );
            let response = response.on_hover_text(match &hovered {
                Some(id) => format!("'{id}' — click to show it"),
                None => "the whole graph: click or drag to move the view".to_string(),
            });
            if (response.clicked() || response.dragged())
                && let Some(p) = response.interact_pointer_pos()
            {
                moved = Some(to_canvas(p));
            }
        });
    moved
}
