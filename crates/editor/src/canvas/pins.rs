//! The canvas's pins: their colour and shape by the port's type and access, the names drawn
//! beside them, and the pin that records where it was drawn.

use std::cell::RefCell;
use std::rc::Rc;

use cnets_engine::{Access, PortDef, ValueType};
use egui::{Color32, Pos2, Rect, Ui};
use egui_snarl::ui::{PinInfo, PinShape, PinWireInfo, SnarlPin, SnarlStyle};
use rustc_hash::FxHashMap;

/// Where a pin is, for tests that drag wires: (node id, is input, port index).
pub type PinKey = (String, bool, usize);

/// Colour of a pin by its item type.
pub fn type_color(ty: &ValueType) -> Color32 {
    match ty.base() {
        ValueType::Number | ValueType::Integer => Color32::from_rgb(0x4c, 0x8b, 0xd6),
        ValueType::Boolean => Color32::from_rgb(0xd6, 0x4c, 0x8b),
        ValueType::Text => Color32::from_rgb(0x5a, 0xa0, 0x5a),
        ValueType::Point | ValueType::Vector | ValueType::Plane => {
            Color32::from_rgb(0xe0, 0x9a, 0x2b)
        }
        ValueType::Polyline | ValueType::Lines => Color32::from_rgb(0x1f, 0x5f, 0xbf),
        ValueType::QuadMesh | ValueType::Mesh => Color32::from_rgb(0x8a, 0x4f, 0xc8),
        ValueType::Record => Color32::from_rgb(0x80, 0x80, 0x80),
        ValueType::Any | ValueType::List(_) => Color32::from_rgb(0xb0, 0xb0, 0xb0),
    }
}

pub(super) fn pin_info(port: &PortDef) -> PinInfo {
    let shape = match port.access {
        Access::Item => PinShape::Circle,
        Access::List => PinShape::Square,
        // Tree (and any deeper access): a triangle.
        _ => PinShape::Triangle,
    };
    PinInfo::default()
        .with_shape(shape)
        .with_fill(type_color(&port.ty))
}

/// The width of the slot an output's summary (`12 × 9 quad mesh`) is drawn in, in points: the
/// same before and after its data arrives, so the output's pin stays where it is; a longer
/// summary ends in "…" and the hover gives it whole.
pub const SUMMARY_WIDTH: f32 = 110.0;

/// Draws an output's summary right-aligned in a slot of [`SUMMARY_WIDTH`] (empty before its
/// data arrives), cut with "…" to fit.
pub(super) fn summary_slot(ui: &mut Ui, summary: Option<&str>) {
    let height = ui.spacing().interact_size.y;
    let (rect, _) = ui.allocate_exact_size(egui::vec2(SUMMARY_WIDTH, height), egui::Sense::hover());
    if let Some(text) = summary {
        let builder = egui::UiBuilder::new()
            .max_rect(rect)
            .layout(egui::Layout::right_to_left(egui::Align::Center));
        // A child that does not allocate in the row: the slot above is all the row gets.
        let mut slot = ui.new_child(builder);
        slot.add(egui::Label::new(egui::RichText::new(text).weak()).truncate());
    }
}

/// The widest a port's name is drawn on a node, in points: longer names (a cluster's port can be
/// named anything) end in "…" and the hover gives the whole name. Every name of the node library
/// fits (the longest, `from_reference_max`, is about 115 points).
pub const PORT_NAME_WIDTH: f32 = 140.0;

/// A port's name as drawn on its node, cut to [`PORT_NAME_WIDTH`] at a character with "…", and
/// the hover's first line: the whole name when it was cut, else nothing.
pub(super) fn fitted_port_name(ui: &Ui, name: &str) -> (String, String) {
    let width = |text: &str| {
        egui::WidgetText::from(text)
            .into_galley(
                ui,
                Some(egui::TextWrapMode::Extend),
                f32::INFINITY,
                egui::TextStyle::Body,
            )
            .size()
            .x
    };
    if width(name) <= PORT_NAME_WIDTH {
        return (name.to_string(), String::new());
    }
    let chars: Vec<char> = name.chars().collect();
    let mut n = chars.len();
    let mut shown = String::from("…");
    while n > 1 {
        n -= 1;
        let candidate: String = chars[..n].iter().chain(['…'].iter()).collect();
        if width(&candidate) <= PORT_NAME_WIDTH {
            shown = candidate;
            break;
        }
    }
    (shown, format!("{name}\n"))
}

/// A pin that records where it was drawn (for tests that drag wires between pins).
pub struct RecordingPin {
    pub(super) info: PinInfo,
    pub(super) key: PinKey,
    pub(super) sink: Rc<RefCell<FxHashMap<PinKey, Pos2>>>,
}

/// How much wider and taller a pin's hit area is than its drawn size: 16 points for the 9-point
/// pins, so the whole of a triangle (which reaches 5.8 points from its centre) starts a wire, not
/// a drag of the node, and the content beside a pin (12 points from its centre) stays clear.
const PIN_HIT: f32 = 16.0 / 9.0;

impl SnarlPin for RecordingPin {
    fn pin_rect(&self, x: f32, y0: f32, y1: f32, size: f32) -> Rect {
        Rect::from_center_size(
            egui::pos2(x, (y0 + y1) * 0.5),
            egui::vec2(size, size) * PIN_HIT,
        )
    }

    fn draw(
        self,
        snarl_style: &SnarlStyle,
        style: &egui::Style,
        rect: Rect,
        painter: &egui::Painter,
    ) -> PinWireInfo {
        self.sink.borrow_mut().insert(self.key, rect.center());
        // Drawn at its own size inside the larger hit area.
        let drawn = rect.scale_from_center(1.0 / PIN_HIT);
        self.info.draw(snarl_style, style, drawn, painter)
    }
}
