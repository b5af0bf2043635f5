//! The errors of failed nodes in the 3D view: when a node fails and its badge is not in view on
//! the canvas (scrolled away, behind the narrow layout's tab), the view lists it above its
//! bottom-left corner — "⚠ construct: a table of 100000 × 100000 numbers needs 320 GB…" — so a
//! picture that did not change is never silent. Clicking an entry shows the node.

use std::collections::HashMap;

use cnets_engine::Graph;
use egui::{Color32, Rect, Ui};

use crate::canvas::Canvas;
use crate::worker::NodeStatus;

/// Entries listed at most (then "and N more").
pub const MAX_SHOWN: usize = 3;
/// Characters of a message shown (the node's badge has all of it).
const MAX_CHARS: usize = 160;

/// Whether node `id` was drawn inside the canvas's rectangle in the last frame (its badge is in
/// view).
pub fn in_view(canvas: &Canvas, id: &str) -> bool {
    canvas
        .node_screen_rect(id)
        .is_some_and(|r| canvas.screen_rect().contains_rect(r.shrink(8.0)))
}

/// The failed nodes of `graph` that `on_canvas` says are not in view, in graph order, with
/// their messages.
pub fn hidden_failures<'a>(
    graph: &'a Graph,
    statuses: &'a HashMap<String, NodeStatus>,
    on_canvas: &dyn Fn(&str) -> bool,
) -> Vec<(&'a str, &'a str)> {
    graph
        .nodes()
        .filter_map(|(_, n)| Some((n.id.as_str(), statuses.get(&n.id)?.error()?)))
        .filter(|(id, _)| !on_canvas(id))
        .collect()
}

/// Lists the failed nodes that are not on the canvas in `view` (the 3D view's rectangle);
/// returns the node whose entry was clicked.
pub fn show(
    ui: &Ui,
    view: Rect,
    graph: &Graph,
    statuses: &HashMap<String, NodeStatus>,
    on_canvas: &dyn Fn(&str) -> bool,
) -> Option<String> {
    let failed = hidden_failures(graph, statuses, on_canvas);
    if failed.is_empty() || !view.is_positive() {
        return None;
    }
    let mut clicked = None;
    let width = (view.width() - 16.0).clamp(120.0, 460.0);
    // Above the axes gizmo of the bottom-left corner.
    egui::Area::new(egui::Id::new("cnets-view-errors"))
        .fixed_pos(view.left_bottom() + egui::vec2(8.0, -76.0))
        .pivot(egui::Align2::LEFT_BOTTOM)
        .constrain_to(view)
        .show(ui.ctx(), |ui| {
            egui::Frame::new()
                .fill(Color32::from_rgba_unmultiplied(255, 240, 238, 235))
                .stroke(egui::Stroke::new(1.0, Color32::from_rgb(0xd6, 0x2f, 0x2f)))
                .corner_radius(4.0)
                .inner_margin(6.0)
                .show(ui, |ui| {
                    ui.set_max_width(width);
                    let ink = Color32::from_rgb(0x9b, 0x1c, 0x1c);
                    for (id, message) in failed.iter().take(MAX_SHOWN) {
                        let short: String = message
                            .lines()
                            .next()
                            .unwrap_or_default()
                            .chars()
                            .take(MAX_CHARS)
                            .collect();
                        // The node's name when it was given one.
                        let label = graph.node(id).map_or(*id, |n| n.label());
                        let text = egui::RichText::new(format!("⚠ {label}: {short}")).color(ink);
                        if ui
                            .add(egui::Label::new(text).wrap().sense(egui::Sense::click()))
                            .on_hover_text(format!(
                                "{message}\n\nclick to show '{id}' on the canvas"
                            ))
                            .clicked()
                        {
                            clicked = Some(id.to_string());
                        }
                    }
                    if failed.len() > MAX_SHOWN {
                        ui.colored_label(
                            ink,
                            format!("and {} more failed nodes", failed.len() - MAX_SHOWN),
                        );
                    }
                });
        });
    clicked
}
