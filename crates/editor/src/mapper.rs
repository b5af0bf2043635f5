//! The graph-mapper widget: for `mapper.*` nodes (Grasshopper's Graph Mapper), a small plot of
//! y = f(x) whose handles the designer drags, with a picker for the curve type.
//!
//! The mapper node is being written in parallel with the editor, so the widget reads its ports
//! from the registry instead of hard-coding them: the handles are the node's first list-of-points
//! input, the curve type its first text input (the known type names are offered; a name the node
//! refuses shows as the node's error), and the curve drawn is the node itself evaluated on the UI
//! thread with `count` samples (when it has a `count` input), else the polyline through the
//! handles. Handles are edited in the unit square (x and y in 0..1, as the node's domain maps them).

use cnets_engine::eval::evaluate_node;
use cnets_engine::{Access, Graph, NodeContext, NodeInstance, Value, ValueType};
use cnets_geometry::DVec3;
use egui::{Color32, Pos2, Rect, Sense, Stroke, Ui, vec2};

use crate::widgets::effective_value;

/// Curve types offered in the picker (the names of the design-inputs issue).
pub const CURVE_TYPES: [&str; 10] = [
    "linear",
    "bezier",
    "parabola",
    "power",
    "sine",
    "gaussian",
    "sqrt",
    "conic",
    "piecewise",
    "spline",
];

/// Samples drawn for the curve.
const SAMPLES: i64 = 64;

/// Whether a node gets the graph-mapper widget.
pub fn is_mapper(node: &NodeInstance) -> bool {
    node.def.id.starts_with("mapper.") && handles_port(node).is_some()
}

/// Index of the handles input: the first list of points.
pub fn handles_port(node: &NodeInstance) -> Option<usize> {
    node.def
        .inputs
        .iter()
        .position(|p| p.ty == ValueType::Point && p.access != Access::Item)
}

/// Index of the curve-type input: the first text input.
pub fn type_port(node: &NodeInstance) -> Option<usize> {
    node.def.inputs.iter().position(|p| p.ty == ValueType::Text)
}

/// The handles of a mapper node.
pub fn handles(node: &NodeInstance) -> Vec<DVec3> {
    let Some(k) = handles_port(node) else {
        return Vec::new();
    };
    match effective_value(node, k) {
        Some(Value::List(items)) => items.iter().filter_map(Value::as_vec3).collect(),
        Some(Value::Point(p)) => vec![p],
        _ => Vec::new(),
    }
}

/// The curve of a mapper node as y samples over evenly spaced x, by evaluating the node with its
/// literal inputs and `count` = 64; `None` when it has no `count` input or fails.
pub fn sample_curve(node: &NodeInstance) -> Option<Vec<f64>> {
    let count = node.def.input_index("count")?;
    let inputs: Vec<Value> = (0..node.def.inputs.len())
        .map(|k| {
            if k == count {
                Value::Integer(SAMPLES)
            } else if node.def.inputs[k].name == "values" {
                Value::Null
            } else {
                effective_value(node, k).unwrap_or(Value::Null)
            }
        })
        .collect();
    let out = evaluate_node(&node.def, &NodeContext::default(), &inputs).ok()?;
    let ys: Vec<f64> = out
        .values
        .first()?
        .as_list()?
        .iter()
        .filter_map(Value::as_f64)
        .collect();
    (ys.len() >= 2 && ys.iter().all(|y| y.is_finite())).then_some(ys)
}

/// Shows the widget; returns the inputs to set when the designer dragged a handle or picked a
/// type.
pub fn show(ui: &mut Ui, _graph: &Graph, node: &NodeInstance) -> Option<Vec<(String, Value)>> {
    let mut changes: Vec<(String, Value)> = Vec::new();
    if let Some(k) = type_port(node) {
        let current = match effective_value(node, k) {
            Some(Value::Text(t)) => t.to_string(),
            _ => String::new(),
        };
        egui::ComboBox::from_id_salt(("mapper-type", &node.id))
            .selected_text(if current.is_empty() {
                "type"
            } else {
                current.as_str()
            })
            .show_ui(ui, |ui| {
                for t in CURVE_TYPES {
                    if ui.selectable_label(current == t, t).clicked() {
                        changes.push((node.def.inputs[k].name.to_string(), Value::text(t)));
                    }
                }
            });
    }
    let size = vec2(160.0, 120.0);
    let (rect, _) = ui.allocate_exact_size(size, Sense::hover());
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect, 2.0, Color32::from_gray(245));
    painter.rect_stroke(
        rect,
        2.0,
        Stroke::new(1.0, Color32::from_gray(160)),
        egui::StrokeKind::Inside,
    );
    let to_screen = |p: DVec3| {
        Pos2::new(
            rect.left() + (p.x.clamp(0.0, 1.0) as f32) * rect.width(),
            rect.bottom() - (p.y.clamp(0.0, 1.0) as f32) * rect.height(),
        )
    };
    let to_unit = |p: Pos2| {
        DVec3::new(
            f64::from((p.x - rect.left()) / rect.width()).clamp(0.0, 1.0),
            f64::from((rect.bottom() - p.y) / rect.height()).clamp(0.0, 1.0),
            0.0,
        )
    };
    let handles = handles(node);
    let curve: Vec<Pos2> = match sample_curve(node) {
        Some(ys) => {
            let n = ys.len() - 1;
            ys.iter()
                .enumerate()
                .map(|(k, &y)| to_screen(DVec3::new(k as f64 / n as f64, y, 0.0)))
                .collect()
        }
        None => handles.iter().map(|&h| to_screen(h)).collect(),
    };
    painter.add(egui::Shape::line(
        curve,
        Stroke::new(1.5, Color32::from_rgb(0x1f, 0x5f, 0xbf)),
    ));
    let mut moved = handles.clone();
    let mut any = false;
    for (k, h) in handles.iter().enumerate() {
        let center = to_screen(*h);
        let r = ui.interact(
            Rect::from_center_size(center, vec2(12.0, 12.0)),
            ui.id().with(("mapper-handle", &node.id, k)),
            Sense::drag(),
        );
        if r.dragged()
            && let Some(p) = r.interact_pointer_pos()
        {
            moved[k] = to_unit(p);
            any = true;
        }
        let fill = if r.hovered() || r.dragged() {
            Color32::from_rgb(0xd0, 0x31, 0x2d)
        } else {
            Color32::WHITE
        };
        painter.circle(
            center,
            5.0,
            fill,
            Stroke::new(1.5, Color32::from_rgb(0xd0, 0x31, 0x2d)),
        );
    }
    if any && let Some(k) = handles_port(node) {
        changes.push((
            node.def.inputs[k].name.to_string(),
            Value::list(moved.into_iter().map(Value::Point).collect()),
        ));
    }
    (!changes.is_empty()).then_some(changes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use cnets_engine::{NodeDef, PortDef, Registry};
    use std::sync::Arc;

    /// A stand-in with the documented shape of `mapper.graph`: type, handles, count → values.
    fn stand_in() -> NodeDef {
        NodeDef::new("mapper.test", "Mappers", "A linear test mapper.")
            .input(
                PortDef::new("type", ValueType::Text, Access::Item)
                    .with_default(Value::text("linear")),
            )
            .input(
                PortDef::new("handles", ValueType::Point, Access::List).with_default(Value::list(
                    vec![
                        Value::Point(DVec3::new(0.0, 0.2, 0.0)),
                        Value::Point(DVec3::new(1.0, 0.8, 0.0)),
                    ],
                )),
            )
            .input(
                PortDef::new("count", ValueType::Integer, Access::Item)
                    .with_default(Value::Integer(10)),
            )
            .output(PortDef::new("values", ValueType::Number, Access::List))
            .run(|_, inputs| {
                let h = inputs[1]
                    .as_list()
                    .unwrap_or(&[])
                    .iter()
                    .filter_map(Value::as_vec3)
                    .collect::<Vec<_>>();
                let n = match inputs[2] {
                    Value::Integer(n) => n,
                    _ => 0,
                };
                let (a, b) = (
                    h.first().map_or(0.0, |p| p.y),
                    h.last().map_or(1.0, |p| p.y),
                );
                let ys = (0..n)
                    .map(|k| Value::Number(a + (b - a) * k as f64 / (n - 1).max(1) as f64))
                    .collect();
                Ok(vec![Value::list(ys)])
            })
    }

    #[test]
    fn ports_are_found_and_the_node_is_sampled() {
        let mut r = Registry::new();
        r.register(stand_in());
        let mut g = Graph::new(Arc::new(r));
        g.add_node("m", "mapper.test").unwrap();
        let n = g.node("m").unwrap();
        assert!(is_mapper(n));
        assert_eq!(handles(n).len(), 2);
        let ys = sample_curve(n).unwrap();
        assert_eq!(ys.len(), SAMPLES as usize);
        assert!((ys[0] - 0.2).abs() < 1e-12 && (ys[63] - 0.8).abs() < 1e-12);
    }
}
