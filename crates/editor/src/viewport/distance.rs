//! The "colour by distance to …" mode's reference picker: in [`ColorMode::Distance`] a small list
//! under the legend names the mesh the other previewed meshes are measured against (any node with
//! a mesh output; it need not be previewed).

use cnets_engine::{Graph, ValueType};
use egui::{Rect, Ui};

use crate::preview::{ColorMode, PreviewOptions};

/// Whether a node gives a mesh (a quad grid or a polygon mesh, or a list of them).
pub fn gives_mesh(node: &cnets_engine::NodeInstance) -> bool {
    node.def
        .outputs
        .iter()
        .any(|p| matches!(p.ty, ValueType::Mesh | ValueType::QuadMesh))
}

/// The nodes that can be the reference, `(uid, id)` in graph order.
pub fn candidates(graph: &Graph) -> Vec<(u64, String)> {
    graph
        .nodes()
        .filter(|(_, n)| gives_mesh(n))
        .map(|(_, n)| (n.uid(), n.id.clone()))
        .collect()
}

/// Picks the first mesh node when none (or a removed one) is the reference, so the mode shows
/// something as soon as it is chosen. Returns whether the options changed.
pub fn ensure_reference(options: &mut PreviewOptions, graph: &Graph) -> bool {
    if options.color_mode != ColorMode::Distance {
        return false;
    }
    let list = candidates(graph);
    if options
        .distance_to
        .is_some_and(|uid| list.iter().any(|(u, _)| *u == uid))
    {
        return false;
    }
    let first = list.first().map(|(u, _)| *u);
    let changed = options.distance_to != first;
    options.distance_to = first;
    changed
}

/// Draws the picker at `top` along the view's right edge; returns the bottom of what it drew.
pub fn picker(
    ui: &mut Ui,
    rect: Rect,
    top: f32,
    options: &mut PreviewOptions,
    graph: &Graph,
) -> f32 {
    if options.color_mode != ColorMode::Distance {
        return top;
    }
    let list = candidates(graph);
    let current = options
        .distance_to
        .and_then(|uid| list.iter().find(|(u, _)| *u == uid))
        .map_or("(no mesh node)".to_string(), |(_, id)| id.clone());
    let at = egui::pos2(rect.right() - 240.0, top + 6.0);
    let response = egui::Area::new(egui::Id::new("cnets-distance-reference"))
        .fixed_pos(at)
        .order(egui::Order::Foreground)
        .show(ui.ctx(), |ui| {
            ui.horizontal(|ui| {
                ui.label("distance to");
                egui::ComboBox::from_id_salt("cnets-distance-reference-combo")
                    .selected_text(current)
                    .width(140.0)
                    .show_ui(ui, |ui| {
                        for (uid, id) in &list {
                            ui.selectable_value(&mut options.distance_to, Some(*uid), id);
                        }
                    })
                    .response
                    .on_hover_text(
                        "the mesh the other previewed meshes are measured against: each vertex \
                         is coloured by its distance to it (legend in metres)",
                    );
            });
        });
    response.response.rect.bottom()
}
