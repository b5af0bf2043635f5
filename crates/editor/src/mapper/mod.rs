//! The graph-mapper widget: for `mapper.graph` nodes (Grasshopper's Graph Mapper), a plot of the
//! curve in its unit square whose handles the designer drags, with a picker for the curve kind.
//!
//! The widget shows the truth of what the node runs on ([`node::shown`]): a wired `kind` or wired
//! handles are read from the last evaluation and shown read-only, labelled as coming from a wire;
//! handles given as a tree are shown row by row (a row selector, the other rows faint); with no
//! handles set, the kind's default handles are shown and dragging one writes that row. A drag
//! replaces exactly one point of the stored value ([`node::with_handle_moved`]): the nesting and
//! the number of items never change. The curve is drawn with the same
//! [`GraphMapper`](cnets_geometry::curves::GraphMapper) the node evaluates, so the picture is
//! exact; a kind or handle set the mapper refuses is drawn as far as possible and the node shows
//! the error.

use cnets_engine::{Graph, NodeInstance, Value};
use cnets_geometry::curves::{GraphMapper, MapperKind};
use egui::{Color32, Pos2, Rect, Sense, Stroke, Ui, vec2};
use glam::DVec2;

pub mod node;

pub use node::{Shown, handles, handles_port, is_mapper, kind, kind_port};

/// Samples drawn for the curve.
const SAMPLES: usize = 96;

/// The curve as (u, v) points over the unit square; `None` when the mapper refuses the handles.
pub fn curve(kind: MapperKind, handles: &[DVec2]) -> Option<Vec<DVec2>> {
    let mapper = GraphMapper::new(kind, handles).ok()?;
    let points: Vec<DVec2> = (0..=SAMPLES)
        .map(|k| {
            let u = k as f64 / SAMPLES as f64;
            DVec2::new(u, mapper.eval(u))
        })
        .filter(|p| p.is_finite())
        .collect();
    Some(points)
}

/// What the widget did in one frame.
pub struct MapperResponse {
    /// The inputs to set (a dragged handle, a picked kind).
    pub changes: Option<Vec<(String, Value)>>,
    /// The plot's rectangle (unit square: u to the right, v up), in the ui's coordinates.
    pub plot: Rect,
    /// A handle coordinate picked in the plot's context menu ("Optimize a value").
    pub optimize: Option<crate::request::UiRequest>,
    /// What the plot showed: the kind and handle rows the node runs on, and the row drawn.
    pub shown: Option<(Shown, usize)>,
}

impl MapperResponse {
    fn nothing() -> Self {
        Self {
            changes: None,
            plot: Rect::NOTHING,
            optimize: None,
            shown: None,
        }
    }
}

/// Font size, in screen points, of the value label of a hovered or dragged handle (the same at
/// every canvas zoom).
pub const LABEL_SCREEN_SIZE: f32 = 12.0;

/// The value label of a handle: `u 0.402  v 0.735`.
pub fn handle_label(p: DVec2) -> String {
    format!(
        "u {}  v {}",
        crate::worker::format_number(p.x),
        crate::worker::format_number(p.y)
    )
}

/// Paints `text` next to the handle at `anchor` of the plot `plot` (both in the ui's
/// coordinates), on a layer above the canvas in screen coordinates: the label is
/// [`LABEL_SCREEN_SIZE`] high on screen at any canvas zoom and is not clipped by the node.
fn show_label(ui: &Ui, plot: Rect, anchor: Pos2, text: &str) {
    let to_global = ui
        .ctx()
        .layer_transform_to_global(ui.layer_id())
        .unwrap_or_default();
    let (anchor, plot) = (to_global * anchor, to_global * plot);
    let painter = ui.ctx().layer_painter(egui::LayerId::new(
        egui::Order::Tooltip,
        egui::Id::new("mapper-handle-label"),
    ));
    let ink = Color32::from_gray(20);
    let galley = painter.layout_no_wrap(
        text.to_string(),
        egui::FontId::proportional(LABEL_SCREEN_SIZE),
        ink,
    );
    let size = galley.size() + vec2(8.0, 4.0);
    // Above and right of the handle; left of it near the plot's right edge, below it near the top.
    let mut min = anchor + vec2(9.0, -9.0 - size.y);
    if min.x + size.x > plot.right() {
        min.x = anchor.x - 9.0 - size.x;
    }
    if min.y < plot.top() {
        min.y = anchor.y + 9.0;
    }
    let screen = ui.ctx().content_rect();
    min.x = min
        .x
        .clamp(screen.left(), (screen.right() - size.x).max(screen.left()));
    min.y = min
        .y
        .clamp(screen.top(), (screen.bottom() - size.y).max(screen.top()));
    let frame = Rect::from_min_size(min, size);
    painter.rect_filled(
        frame,
        3.0,
        Color32::from_rgba_unmultiplied(255, 255, 255, 240),
    );
    painter.rect_stroke(
        frame,
        3.0,
        Stroke::new(1.0, Color32::from_gray(120)),
        egui::StrokeKind::Inside,
    );
    painter.galley(min + vec2(4.0, 2.0), galley, ink);
}

/// A handle coordinate rounded to a thousandth (see `show`), as the shortest decimal.
pub fn snap(x: f64) -> f64 {
    cnets_engine::numbers::snap(x, 0.0, 0.001)
}

/// The row of a tree of handles the widget shows for `node` (kept in egui's memory).
fn row_id(node: &NodeInstance) -> egui::Id {
    egui::Id::new(("mapper-row", &node.id))
}

/// The row selector of a tree of handles: `◀ row 3 / 8 ▶`; returns the row shown.
fn row_selector(ui: &mut Ui, node: &NodeInstance, rows: usize) -> usize {
    let id = row_id(node);
    let mut row = ui
        .data(|d| d.get_temp::<usize>(id))
        .unwrap_or(0)
        .min(rows - 1);
    if rows > 1 {
        ui.horizontal(|ui| {
            if ui.small_button("◀").clicked() {
                row = row.saturating_sub(1);
            }
            ui.label(format!("row {} / {rows}", row + 1))
                .on_hover_text("the handles are a tree: one curve per row (the others in grey)");
            if ui.small_button("▶").clicked() {
                row = (row + 1).min(rows - 1);
            }
        });
    }
    ui.data_mut(|d| d.insert_temp(id, row));
    row
}

/// Shows the graph-mapper widget of `node` of `graph`; `ran_on` holds the input values the node
/// last ran on (wired inputs are shown from it, read-only). Returns the changes and the plot
/// rectangle.
pub fn show(
    ui: &mut Ui,
    graph: &Graph,
    node: &NodeInstance,
    ran_on: Option<&[Value]>,
) -> MapperResponse {
    let (Some(kind_k), Some(handles_k), Some(shown)) = (
        kind_port(node),
        handles_port(node),
        node::shown(graph, node, ran_on),
    ) else {
        return MapperResponse::nothing();
    };
    let wire_ink = Color32::from_rgb(0x3a, 0x6e, 0xa5);
    let mut changes: Vec<(String, Value)> = Vec::new();
    let row = row_selector(ui, node, shown.rows.len().max(1));
    let current = shown.kind(row);
    let kind_name = current.map_or("?", MapperKind::name);
    if shown.kind_wired || shown.kinds.len() > 1 {
        let from = if shown.kind_wired {
            "from a wire"
        } else {
            "one per row"
        };
        ui.colored_label(wire_ink, format!("{kind_name}  ({from})"))
            .on_hover_text("the curve kind the node runs on; change it where it comes from");
    } else {
        egui::ComboBox::from_id_salt(("mapper-kind", &node.id))
            .selected_text(kind_name)
            .show_ui(ui, |ui| {
                for k in MapperKind::ALL {
                    if ui.selectable_label(current == Some(k), k.name()).clicked() {
                        changes.push((
                            node.def.inputs[kind_k].name.to_string(),
                            Value::text(k.name()),
                        ));
                        // A new kind starts from its own default handles — unless the handles are
                        // a tree or wired: those are never replaced by a kind change.
                        if !shown.nested && !shown.handles_wired {
                            changes.push((
                                node.def.inputs[handles_k].name.to_string(),
                                Value::list(Vec::new()),
                            ));
                        }
                    }
                }
            });
    }
    let (rect, plot_response) = ui.allocate_exact_size(vec2(180.0, 130.0), Sense::click());
    let mut optimize = None;
    plot_response.context_menu(|ui| {
        let candidates = crate::optimization::variable_candidates(node, handles_k);
        optimize = crate::optimization::variable_menu(ui, &candidates);
    });
    let painter = ui.painter_at(rect.expand(6.0));
    painter.rect_filled(rect, 2.0, Color32::from_gray(245));
    painter.rect_stroke(
        rect,
        2.0,
        Stroke::new(1.0, Color32::from_gray(160)),
        egui::StrokeKind::Inside,
    );
    let to_screen = |p: DVec2| {
        Pos2::new(
            rect.left() + (p.x as f32) * rect.width(),
            rect.bottom() - (p.y.clamp(-0.05, 1.05) as f32) * rect.height(),
        )
    };
    // Dragged handles snap to a thousandth of the unit square (a pixel is ~1/130 of it): the file
    // gets 0.402, not 0.40179139375686646.
    let to_unit = |p: Pos2| {
        DVec2::new(
            snap(f64::from((p.x - rect.left()) / rect.width()).clamp(0.0, 1.0)),
            snap(f64::from((rect.bottom() - p.y) / rect.height()).clamp(0.0, 1.0)),
        )
    };
    if shown.unknown {
        painter.text(
            rect.center(),
            egui::Align2::CENTER_CENTER,
            "waiting for the wired values",
            egui::FontId::proportional(11.0),
            Color32::from_gray(110),
        );
        return MapperResponse {
            changes: (!changes.is_empty()).then_some(changes),
            plot: rect,
            optimize,
            shown: Some((shown, row)),
        };
    }
    let curve_line = |r: usize| -> Vec<Pos2> {
        let handles = &shown.rows[r];
        match shown.kind(r).and_then(|k| curve(k, handles)) {
            Some(points) => points.into_iter().map(to_screen).collect(),
            None => handles.iter().map(|&h| to_screen(h)).collect(),
        }
    };
    // The other rows of a tree, faint behind the one being edited.
    for r in (0..shown.rows.len()).filter(|&r| r != row) {
        painter.add(egui::Shape::line(
            curve_line(r),
            Stroke::new(1.0, Color32::from_gray(200)),
        ));
    }
    painter.add(egui::Shape::line(
        curve_line(row),
        Stroke::new(1.5, Color32::from_rgb(0x1f, 0x5f, 0xbf)),
    ));
    if shown.handles_wired || shown.irregular {
        let why = if shown.handles_wired {
            "handles from a wire"
        } else {
            "handles nest deeper than rows: edit the list"
        };
        painter.text(
            rect.left_top() + vec2(4.0, 3.0),
            egui::Align2::LEFT_TOP,
            why,
            egui::FontId::proportional(10.0),
            wire_ink,
        );
    }
    let handles = shown.rows.get(row).cloned().unwrap_or_default();
    let editable = shown.editable();
    let mut moved: Option<(usize, DVec2)> = None;
    let mut active: Option<DVec2> = None;
    for (k, h) in handles.iter().enumerate() {
        let center = to_screen(*h);
        let sense = if editable {
            Sense::drag()
        } else {
            Sense::hover()
        };
        let r = ui.interact(
            Rect::from_center_size(center, vec2(14.0, 14.0)),
            ui.id().with(("mapper-handle", &node.id, row, k)),
            sense,
        );
        let mut at = *h;
        if r.dragged()
            && let Some(p) = r.interact_pointer_pos()
        {
            at = to_unit(p);
            if at != *h {
                moved = Some((k, at));
            }
        }
        r.widget_info(|| {
            egui::WidgetInfo::labeled(
                egui::WidgetType::Other,
                editable,
                format!("handle {}: {}", k + 1, handle_label(at)),
            )
        });
        if r.hovered() || r.dragged() {
            active = Some(at);
        }
        let (red, grey) = (Color32::from_rgb(0xd0, 0x31, 0x2d), wire_ink);
        let ring = if editable { red } else { grey };
        let fill = if editable && (r.hovered() || r.dragged()) {
            red
        } else {
            Color32::WHITE
        };
        painter.circle(center, 5.0, fill, Stroke::new(1.5, ring));
    }
    if let Some(p) = active {
        show_label(ui, rect, to_screen(p), &handle_label(p));
    }
    if let Some((k, to)) = moved {
        let stored = node.value(handles_k);
        if let Some(value) = node::with_handle_moved(stored, &shown, row, k, to) {
            changes.push((node.def.inputs[handles_k].name.to_string(), value));
        }
    }
    MapperResponse {
        changes: (!changes.is_empty()).then_some(changes),
        plot: rect,
        optimize,
        shown: Some((shown, row)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use cnets_geometry::DVec3;
    use std::sync::Arc;

    fn mapper_graph() -> Graph {
        let mut g = Graph::new(Arc::new(cnets_nodes::registry()));
        g.add_node("m", "mapper.graph").unwrap();
        g
    }

    #[test]
    fn the_registered_mapper_gets_the_widget_with_default_handles() {
        let mut g = mapper_graph();
        let n = g.node("m").unwrap();
        assert!(is_mapper(n));
        assert_eq!(kind(n), Some(MapperKind::Linear));
        assert_eq!(handles(n), MapperKind::Linear.default_handles());
        g.set_value("m", "kind", Value::text("gaussian")).unwrap();
        let n = g.node("m").unwrap();
        assert_eq!(handles(n), MapperKind::Gaussian.default_handles());
        let c = curve(MapperKind::Gaussian, &handles(n)).unwrap();
        assert_eq!(c.len(), SAMPLES + 1);
    }

    #[test]
    fn the_drawn_curve_passes_through_on_curve_handles() {
        let h = vec![DVec2::new(0.1, 0.2), DVec2::new(0.9, 0.7)];
        let c = curve(MapperKind::Linear, &h).unwrap();
        // Linear through A and B: v(u) = 0.2 + (u − 0.1)·0.5/0.8.
        for p in c {
            assert!((p.y - (0.2 + (p.x - 0.1) * 0.625)).abs() < 1e-12);
        }
        assert!(
            curve(
                MapperKind::Linear,
                &[DVec2::new(0.5, 0.0), DVec2::new(0.5, 1.0)]
            )
            .is_none()
        );
    }

    #[test]
    fn handle_labels_are_short() {
        assert_eq!(handle_label(DVec2::new(0.402, 0.5)), "u 0.402  v 0.5");
        assert_eq!(handle_label(DVec2::new(1.0, 0.0)), "u 1  v 0");
    }

    #[test]
    fn set_handles_are_used_and_the_mapper_evaluates_them() {
        let mut g = mapper_graph();
        let pts = [DVec3::new(0.0, 0.0, 0.0), DVec3::new(1.0, 0.5, 0.0)];
        g.set_value(
            "m",
            "handles",
            Value::list(pts.iter().map(|p| Value::Point(*p)).collect()),
        )
        .unwrap();
        let n = g.node("m").unwrap();
        assert_eq!(handles(n), vec![DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.5)]);
    }
}
