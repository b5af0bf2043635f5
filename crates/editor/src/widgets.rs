//! Inline editors for the literal values of unconnected inputs: sliders for `param.number`
//! (range and step from the node's own `min`, `max`, `step`), drag values for other numbers and
//! integers, checkboxes, three fields for points and vectors, text fields, a plane picker.
//!
//! Each editor returns the new value when the designer changed it; the caller turns it into a
//! graph edit (one undo step per drag, see [`crate::history::EditKey`]).

use std::sync::Arc;

use cnets_engine::{Access, NodeInstance, PortDef, Value, ValueType, Widget};
use cnets_geometry::{DVec3, Plane};

/// The value an input has when nothing is wired: its literal, else its default.
pub fn effective_value(node: &NodeInstance, k: usize) -> Option<Value> {
    node.value(k)
        .cloned()
        .or_else(|| node.def.inputs.get(k).and_then(|p| p.default.clone()))
}

/// Slider range and step of input `k` of a node, as its port declares them: read from the inputs
/// the port names as holding them (`range_inputs`, `step_input`: a `param.number`'s `min`, `max`
/// and `step`), else the port's declared range (`soft_range`, else `hard_range`) and step, else 0
/// to 1 without a step. A reversed range is put in order.
pub fn slider_range(node: &NodeInstance, k: usize) -> (f64, f64, f64) {
    let Some(port) = node.def.inputs.get(k) else {
        return (0.0, 1.0, 0.0);
    };
    let read = |name: &str| {
        node.def
            .input_index(name)
            .and_then(|i| effective_value(node, i))
            .and_then(|v| v.as_f64())
            .filter(|v| v.is_finite())
    };
    let (lo, hi) = port
        .hint
        .soft_range
        .or(port.hint.hard_range)
        .unwrap_or((0.0, 1.0));
    let (min, max) = match port.hint.range_inputs {
        Some((a, b)) => (read(a).unwrap_or(lo), read(b).unwrap_or(hi)),
        None => (lo, hi),
    };
    let (min, max) = if min <= max { (min, max) } else { (max, min) };
    let step = port
        .hint
        .step_input
        .and_then(read)
        .or(port.hint.step)
        .unwrap_or(0.0);
    (min, max, step.max(0.0))
}

/// The input of `node` that holds the options its choice index picks from (the index port's
/// `options_input` hint: a Value list's `options`).
fn options_input(node: &NodeInstance) -> Option<usize> {
    let name = node.def.inputs.iter().find_map(|p| p.hint.options_input)?;
    node.def.input_index(name)
}

/// The options a choice index of `node` picks from, when the input its hint names holds a
/// literal list of texts.
pub fn choice_options(node: &NodeInstance) -> Option<Vec<String>> {
    let k = options_input(node)?;
    let items = effective_value(node, k)?;
    let list = items.as_list()?;
    list.iter()
        .map(|v| match v {
            Value::Text(t) => Some(t.to_string()),
            _ => None,
        })
        .collect()
}

/// Whether an input gets an inline editor (an item of a simple type, a list / tree port whose
/// current value is a single number, or a `param.choice`'s options: one a line). An item port
/// holding a literal list has none: it shows the list's summary instead
/// ([`crate::list_editor`]), since a single field would replace the list.
pub fn has_editor(node: &NodeInstance, k: usize) -> bool {
    let Some(port) = node.def.inputs.get(k) else {
        return false;
    };
    match port.widget() {
        Widget::MultilineText => return true,
        // Edited by the node's own widget (a mapper's kind in the mapper widget).
        Widget::Hidden => return false,
        _ => {}
    }
    let simple = matches!(
        port.ty,
        ValueType::Number
            | ValueType::Integer
            | ValueType::Boolean
            | ValueType::Text
            | ValueType::Point
            | ValueType::Vector
            | ValueType::Plane
    );
    if !simple {
        return false;
    }
    match port.access {
        Access::Item => !matches!(effective_value(node, k), Some(Value::List(_))),
        _ => {
            matches!(
                effective_value(node, k),
                Some(Value::Number(_) | Value::Integer(_)) | None
            ) && matches!(port.ty, ValueType::Number | ValueType::Integer)
        }
    }
}

/// The value an "unset" optional input gets when the designer sets it: zero, false, empty text,
/// the origin, the XY plane.
pub fn initial_value(ty: &ValueType) -> Option<Value> {
    Some(match ty {
        ValueType::Number => Value::Number(0.0),
        ValueType::Integer => Value::Integer(0),
        ValueType::Boolean => Value::Boolean(false),
        ValueType::Text => Value::text(""),
        ValueType::Point => Value::Point(DVec3::ZERO),
        ValueType::Vector => Value::Vector(DVec3::Z),
        ValueType::Plane => Value::Plane(Arc::new(Plane::XY)),
        _ => return None,
    })
}

fn browse_key() -> egui::Id {
    egui::Id::new("cnets-browse-request")
}

/// Asks for the file dialog of a path input (node id, input name): its Browse… button was clicked.
pub fn request_browse(ctx: &egui::Context, node: &str, input: &str) {
    ctx.data_mut(|d| d.insert_temp(browse_key(), (node.to_string(), input.to_string())));
}

/// The path input whose Browse… button was clicked since the last call (node id, input name).
pub fn take_browse_request(ctx: &egui::Context) -> Option<(String, String)> {
    ctx.data_mut(|d| d.remove_temp::<(String, String)>(browse_key()))
}

/// Shows the editor of input `k`; returns the new value when it changed.
pub fn input_editor(ui: &mut egui::Ui, node: &NodeInstance, k: usize) -> Option<Value> {
    input_editor_with_rect(ui, node, k).0
}

/// Like [`input_editor`], also returning the rectangle the editor took.
pub fn input_editor_with_rect(
    ui: &mut egui::Ui,
    node: &NodeInstance,
    k: usize,
) -> (Option<Value>, egui::Rect) {
    let Some(port) = node.def.inputs.get(k) else {
        return (None, egui::Rect::NOTHING);
    };
    let r = ui.push_id(ui.id().with((&node.id, k)), |ui| {
        editor_body(ui, node, k, port)
    });
    (r.inner, r.response.rect)
}

/// Whether the secondary (right) button is down or was just released: egui's slider follows any
/// button, but a right-click on a slider locks its node for dragging and never moves it.
fn secondary_button(ui: &egui::Ui) -> bool {
    ui.input(|i| {
        i.pointer.button_down(egui::PointerButton::Secondary)
            || i.pointer.button_released(egui::PointerButton::Secondary)
    })
}

fn editor_body(ui: &mut egui::Ui, node: &NodeInstance, k: usize, port: &PortDef) -> Option<Value> {
    let current = effective_value(node, k);
    match port.widget() {
        Widget::Choice if port.ty == ValueType::Integer => {
            if let Some(options) = choice_options(node).filter(|o| !o.is_empty()) {
                return choice_editor(ui, &options, current.as_ref());
            }
        }
        Widget::MultilineText if options_input(node) == Some(k) => {
            return options_editor(ui, node);
        }
        _ => {}
    }
    if let Some(choices) = &port.choices
        && port.access == Access::Item
    {
        return word_choice_editor(ui, choices.options, current.as_ref());
    }
    match port.ty {
        ValueType::Number => {
            let mut x = current.as_ref().and_then(Value::as_f64).unwrap_or(0.0);
            let changed = if port.widget() == Widget::Slider {
                let (min, max, step) = slider_range(node, k);
                let mut slider =
                    egui::Slider::new(&mut x, min..=max).clamping(egui::SliderClamping::Never);
                if step > 0.0 {
                    slider = slider.step_by(step);
                }
                let changed = ui.add(slider).changed() && !secondary_button(ui);
                if changed {
                    // The node's own rule: multiples of the step from min, as short decimals; no
                    // step: a thousandth of the slider's range (a pixel is about a hundredth), so
                    // the file gets 1.234, not 1.2340169334411621.
                    x = if step > 0.0 {
                        cnets_engine::numbers::snap(x, min, step)
                    } else {
                        cnets_engine::numbers::snap_to_range(x, max - min)
                    };
                }
                changed
            } else {
                ui.add(number_drag(&mut x)).changed()
            };
            (changed && x.is_finite()).then_some(Value::Number(x))
        }
        ValueType::Integer => {
            let mut i = match current {
                Some(Value::Integer(i)) => i,
                Some(v) => v.as_f64().map_or(0, |x| x as i64),
                None => 0,
            };
            if port.widget() == Widget::Slider {
                // An integer slider (Grasshopper's): its value stays in its own `min`..`max`
                // (the node would clamp it anyway, with a warning), whole numbers only.
                let (min, max, _) = slider_range(node, k);
                let slider = egui::Slider::new(&mut i, min as i64..=max as i64)
                    .clamping(egui::SliderClamping::Always);
                return (ui.add(slider).changed() && !secondary_button(ui))
                    .then_some(Value::Integer(i));
            }
            let drag = egui::DragValue::new(&mut i).speed(0.1);
            ui.add(drag).changed().then_some(Value::Integer(i))
        }
        ValueType::Boolean => {
            let mut b = matches!(current, Some(Value::Boolean(true)));
            ui.checkbox(&mut b, "")
                .changed()
                .then_some(Value::Boolean(b))
        }
        ValueType::Text => {
            let mut s = match &current {
                Some(Value::Text(t)) => t.to_string(),
                _ => String::new(),
            };
            if port.widget() == cnets_engine::Widget::FilePath {
                // A path the node reads: typed, or picked with Browse… (the app opens the file
                // dialog; a file picked there stays readable for the document).
                return ui
                    .horizontal(|ui| {
                        let changed = ui
                            .add(egui::TextEdit::singleline(&mut s).desired_width(110.0))
                            .changed();
                        if ui
                            .small_button("Browse…")
                            .on_hover_text(
                                "pick the file; a file outside the graph's folder stays \
                                 readable for this document",
                            )
                            .clicked()
                        {
                            request_browse(ui.ctx(), &node.id, &port.name);
                        }
                        changed.then(|| Value::text(&s))
                    })
                    .inner;
            }
            ui.add(egui::TextEdit::singleline(&mut s).desired_width(110.0))
                .changed()
                .then(|| Value::text(&s))
        }
        ValueType::Point | ValueType::Vector => {
            let v = current
                .as_ref()
                .and_then(Value::as_vec3)
                .unwrap_or(DVec3::ZERO);
            let mut xyz = [v.x, v.y, v.z];
            let mut changed = false;
            ui.horizontal(|ui| {
                for c in &mut xyz {
                    changed |= ui
                        .add(egui::DragValue::new(c).speed(0.05).max_decimals(4))
                        .changed();
                }
            });
            let v = DVec3::from_array(xyz);
            (changed && v.is_finite()).then_some(if port.ty == ValueType::Point {
                Value::Point(v)
            } else {
                Value::Vector(v)
            })
        }
        ValueType::Plane => {
            let current_name = match &current {
                Some(Value::Plane(p)) => plane_name(p),
                _ => "custom",
            };
            let mut picked = None;
            egui::ComboBox::from_id_salt("plane")
                .selected_text(current_name)
                .width(70.0)
                .show_ui(ui, |ui| {
                    for (name, plane) in [("XY", Plane::XY), ("YZ", Plane::YZ), ("ZX", Plane::ZX)] {
                        if ui.selectable_label(current_name == name, name).clicked() {
                            picked = Some(Value::Plane(Arc::new(plane)));
                        }
                    }
                });
            picked
        }
        _ => None,
    }
}

/// A drop-down of a choice port's words (`end_planes`, a mapper's `kind`, …). The stored text is
/// shown as it is (an alias such as `line` stays until another word is picked); a pick stores
/// the word.
fn word_choice_editor(
    ui: &mut egui::Ui,
    options: &[&'static str],
    current: Option<&Value>,
) -> Option<Value> {
    let shown = match current {
        Some(Value::Text(t)) => t.to_string(),
        Some(other) => other.type_name(),
        None => String::new(),
    };
    let mut picked = None;
    egui::ComboBox::from_id_salt("word choice")
        .selected_text(shown.as_str())
        .width(110.0)
        .show_ui(ui, |ui| {
            for option in options {
                let selected = shown.trim().eq_ignore_ascii_case(option);
                if ui.selectable_label(selected, *option).clicked() && !selected {
                    picked = Some(Value::text(*option));
                }
            }
        });
    picked
}

/// A drop-down of `options` picking the index (an index outside them shows as such).
fn choice_editor(ui: &mut egui::Ui, options: &[String], current: Option<&Value>) -> Option<Value> {
    let index = match current {
        Some(Value::Integer(i)) => *i,
        Some(v) => v.as_f64().map_or(0, |x| x as i64),
        None => 0,
    };
    let shown = usize::try_from(index)
        .ok()
        .and_then(|k| options.get(k))
        .cloned()
        .unwrap_or_else(|| format!("(index {index})"));
    let mut picked = None;
    egui::ComboBox::from_id_salt("choice")
        .selected_text(shown)
        .width(120.0)
        .show_ui(ui, |ui| {
            for (k, option) in options.iter().enumerate() {
                let k = k as i64;
                if ui.selectable_label(k == index, option).clicked() && k != index {
                    picked = Some(Value::Integer(k));
                }
            }
        });
    picked
}

/// The options of a `param.choice`, one a line (empty lines are dropped). While the field has
/// the focus its own text is kept (so a new empty line survives until an option is typed on it).
fn options_editor(ui: &mut egui::Ui, node: &NodeInstance) -> Option<Value> {
    let current = choice_options(node).unwrap_or_default();
    let id = ui.make_persistent_id("choice-options");
    let mut text = ui
        .data(|d| d.get_temp::<String>(id))
        .unwrap_or_else(|| current.join("\n"));
    let r = ui.add(
        egui::TextEdit::multiline(&mut text)
            .id(id)
            .desired_rows(2)
            .desired_width(120.0)
            .hint_text("one option a line"),
    );
    if r.has_focus() {
        ui.data_mut(|d| d.insert_temp(id, text.clone()));
    } else {
        ui.data_mut(|d| d.remove::<String>(id));
    }
    let options: Vec<String> = text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .map(str::to_string)
        .collect();
    (r.changed() && options != current)
        .then(|| Value::list(options.iter().map(Value::text).collect()))
}

fn plane_name(p: &Plane) -> &'static str {
    for (name, q) in [("XY", Plane::XY), ("YZ", Plane::YZ), ("ZX", Plane::ZX)] {
        if *p == q {
            return name;
        }
    }
    "custom"
}

/// A number's drag value: shown with all its significant digits ([`exact_number`]: `1e-6`,
/// `1.124e-16`, `0.01`, `12.5`, `1.5e9`, never rounded to `0.00`), typed in any form Rust reads
/// (`1e-6`, `0.000001`, `−2`), dragged by a hundredth of its size a point (0.01 at zero) so a
/// small tolerance stays small.
pub fn number_drag(x: &mut f64) -> egui::DragValue<'_> {
    let speed = if *x == 0.0 || !x.is_finite() {
        0.01
    } else {
        x.abs() * 0.01
    };
    egui::DragValue::new(x)
        .speed(speed)
        .custom_formatter(|x, _| exact_number(x))
        .custom_parser(parse_number)
}

/// `x` as the shortest text that reads back as the same number: decimal from 0.001 to a million
/// (`0.01`, `12.5`), scientific outside (`1e-6`, `1.124e-16`, `1.5e9`). Committing a field
/// without typing never changes its value.
pub fn exact_number(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    if !x.is_finite() || (1e-3..1e6).contains(&x.abs()) {
        return x.to_string();
    }
    format!("{x:e}")
}

/// A typed number: whitespace ignored, the minus sign (U+2212) read as `-`, `1e-6` and `1E-6`.
fn parse_number(text: &str) -> Option<f64> {
    let text: String = text
        .chars()
        .filter(|c| !c.is_whitespace())
        .map(|c| if c == '\u{2212}' { '-' } else { c })
        .collect();
    text.parse().ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use cnets_engine::Graph;

    #[test]
    fn slider_range_comes_from_the_node() {
        let mut g = Graph::new(Arc::new(cnets_nodes::registry()));
        g.add_node("n", "param.number").unwrap();
        let k = g.node("n").unwrap().def.input_index("value").unwrap();
        assert_eq!(slider_range(g.node("n").unwrap(), k), (0.0, 1.0, 0.0));
        g.set_value("n", "min", Value::Number(2.0)).unwrap();
        g.set_value("n", "max", Value::Number(-1.0)).unwrap();
        g.set_value("n", "step", Value::Number(0.5)).unwrap();
        assert_eq!(slider_range(g.node("n").unwrap(), k), (-1.0, 2.0, 0.5));
    }

    #[test]
    fn editors_for_simple_inputs_only() {
        let mut g = Graph::new(Arc::new(cnets_nodes::registry()));
        g.add_node("c", "cnets.construct").unwrap();
        let n = g.node("c").unwrap();
        let k = |name| n.def.input_index(name).unwrap();
        assert!(
            !has_editor(n, k("directrix")),
            "polylines have no inline editor"
        );
        assert!(
            has_editor(n, k("apex")),
            "a list port holding one number gets a number field"
        );
        assert!(has_editor(n, k("normalized")));
    }

    #[test]
    fn numbers_keep_their_significant_digits() {
        for (x, text) in [
            (1e-6, "1e-6"),
            (1.124e-16, "1.124e-16"),
            (0.01, "0.01"),
            (12.5, "12.5"),
            (1.5e9, "1.5e9"),
            (0.0, "0"),
            (-0.25, "-0.25"),
        ] {
            assert_eq!(exact_number(x), text);
            assert_eq!(parse_number(text), Some(x), "{text} reads back");
        }
        assert_eq!(parse_number(" \u{2212}2 "), Some(-2.0));
        assert_eq!(parse_number("1E-6"), Some(1e-6));
    }
}
