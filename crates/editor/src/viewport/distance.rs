//! The "colour by distance to …" mode's reference picker: in [`ColorMode::Distance`] a small list
//! under the legend names the mesh the net is measured against (any node with a mesh output; it
//! need not be previewed) and which side is coloured: the net by its distance to the reference,
//! or the reference by its distance to the net. The mode picks a reference by itself only among
//! meshes that are not the net nor made from it ([`default_distance_reference`]); with none, it
//! says so.

use cnets_engine::Graph;
use egui::{Rect, Ui};

use crate::preview::{
    ColorMode, DistanceSide, PreviewOptions, default_distance_reference, gives_mesh,
};

/// The nodes that can be the reference, `(uid, id)` in graph order.
pub fn candidates(graph: &Graph) -> Vec<(u64, String)> {
    graph
        .nodes()
        .filter(|(_, n)| gives_mesh(n))
        .map(|(_, n)| (n.uid(), n.id.clone()))
        .collect()
}

/// What the status bar says when the mode finds no mesh to measure the net against.
pub const NO_REFERENCE: &str = "Distance to a reference: no mesh besides the net and what it is \
                                made from — import or build a reference mesh (e.g. io.read_mesh), \
                                or pick a node in the list under the legend";

/// Picks a reference when none (or a removed one) is set — never the net itself or a mesh made
/// from it ([`default_distance_reference`]) — so the mode shows something as soon as it is
/// chosen. Returns a status message when there is none to pick, once (`said` remembers it until
/// a reference is set or the mode left).
pub fn ensure_reference(
    options: &mut PreviewOptions,
    graph: &Graph,
    said: &mut bool,
) -> Option<String> {
    let valid = |uid: u64| graph.nodes().any(|(_, n)| n.uid() == uid && gives_mesh(n));
    if options.color_mode != ColorMode::Distance || options.distance_to.is_some_and(valid) {
        *said = false;
        return None;
    }
    options.distance_to = default_distance_reference(graph);
    if options.distance_to.is_some() || *said {
        *said = options.distance_to.is_none();
        return None;
    }
    *said = true;
    Some(NO_REFERENCE.to_string())
}

/// The room the picker takes from the view's right edge (points).
const PICKER_WIDTH: f32 = 240.0;

/// Draws the picker at `top` along the view's right edge (the reference, and which side is
/// coloured), below `clear_of` (the statistics) too where the view is too narrow to hold both
/// side by side; returns the rectangle it covers (`Rect::NOTHING` outside the mode).
pub fn picker(
    ui: &mut Ui,
    rect: Rect,
    top: f32,
    clear_of: Rect,
    options: &mut PreviewOptions,
    graph: &Graph,
) -> Rect {
    if options.color_mode != ColorMode::Distance {
        return Rect::NOTHING;
    }
    let list = candidates(graph);
    let current = options
        .distance_to
        .and_then(|uid| list.iter().find(|(u, _)| *u == uid))
        .map_or("(none: pick a mesh)".to_string(), |(_, id)| id.clone());
    let left = rect.right() - PICKER_WIDTH;
    let top = if clear_of.is_positive() && left < clear_of.right() {
        top.max(clear_of.bottom())
    } else {
        top
    };
    let at = egui::pos2(left, top + 6.0);
    let response = egui::Area::new(egui::Id::new("cnets-distance-reference"))
        .fixed_pos(at)
        .order(egui::Order::Foreground)
        .show(ui.ctx(), |ui| {
            // On a plate of its own: the view behind is light, the theme's words may not be.
            egui::Frame::popup(ui.style()).show(ui, |ui| picker_body(ui, options, &list, current));
        });
    response.response.rect
}

/// The picker's rows: the reference list and the side checkbox.
fn picker_body(ui: &mut Ui, options: &mut PreviewOptions, list: &[(u64, String)], current: String) {
    ui.horizontal(|ui| {
        ui.label("distance to");
        egui::ComboBox::from_id_salt("cnets-distance-reference-combo")
            .selected_text(current)
            .width(140.0)
            .show_ui(ui, |ui| {
                for (uid, id) in list {
                    ui.selectable_value(&mut options.distance_to, Some(*uid), id);
                }
            })
            .response
            .on_hover_text(
                "the mesh the net (every other previewed mesh) is measured against; the \
                         figures are the symmetric, area-weighted distance (the fit objective's), \
                         the colours each vertex's distance (legend in metres)",
            );
    });
    let mut reference = options.distance_side == DistanceSide::Reference;
    if ui
        .checkbox(&mut reference, "colour the reference")
        .on_hover_text(
            "colour the reference by its distance to the net (the net translucent over \
                     it): shows where the reference is far from the net, which the net's own \
                     colours cannot",
        )
        .changed()
    {
        options.distance_side = if reference {
            DistanceSide::Reference
        } else {
            DistanceSide::Net
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn without_a_reference_the_mode_says_so_once_and_never_picks_the_net() {
        let text = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../graphs/editor-default.ron"
        ))
        .unwrap();
        let registry = std::sync::Arc::new(cnets_nodes::registry());
        let graph = cnets_engine::file::load_str(&text, "default.ron", &registry)
            .unwrap()
            .graph;
        let mut o = PreviewOptions::default();
        let mut said = false;
        assert_eq!(
            ensure_reference(&mut o, &graph, &mut said),
            None,
            "not in the mode"
        );
        o.color_mode = ColorMode::Distance;
        let first = ensure_reference(&mut o, &graph, &mut said);
        assert!(first.is_some_and(|m| m.contains("no mesh besides the net")));
        assert_eq!(o.distance_to, None, "the net is not its own reference");
        assert_eq!(
            ensure_reference(&mut o, &graph, &mut said),
            None,
            "said once"
        );
        // Picked by hand, it is kept.
        let uid = graph.node("construct").unwrap().uid();
        o.distance_to = Some(uid);
        assert_eq!(ensure_reference(&mut o, &graph, &mut said), None);
        assert_eq!(o.distance_to, Some(uid));
    }
}
