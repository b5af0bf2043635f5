//! Per-node preview colours: the menu that picks one (the node's eye, right-click) and the
//! swatches it offers. The colour is saved with the graph (`color: "#rrggbb"`) and used by the 3D
//! view and `cnets render` for the node's surfaces and curves.

use egui::{Color32, Ui};

/// Swatches offered first: distinct on the light background, readable under the headlight.
pub const SWATCHES: [(&str, [u8; 3]); 8] = [
    ("blue", [0x3a, 0x6e, 0xc8]),
    ("orange", [0xe0, 0x8a, 0x2c]),
    ("green", [0x3f, 0x9e, 0x5a]),
    ("red", [0xc8, 0x3c, 0x3c]),
    ("purple", [0x8a, 0x5c, 0xc0]),
    ("teal", [0x2c, 0xa3, 0xa3]),
    ("sand", [0xc9, 0xb2, 0x7c]),
    ("graphite", [0x5a, 0x60, 0x6a]),
];

/// The colour menu: swatches, a free colour and "Default". Returns `Some(new colour)` when one was
/// picked (`Some(None)`: back to the default).
pub fn pick(ui: &mut Ui, current: Option<[u8; 3]>) -> Option<Option<[u8; 3]>> {
    let mut picked = None;
    ui.label("Preview colour");
    ui.horizontal_wrapped(|ui| {
        for (name, [r, g, b]) in SWATCHES {
            let swatch = egui::Button::new("  ").fill(Color32::from_rgb(r, g, b));
            let selected = current == Some([r, g, b]);
            if ui
                .add(swatch.selected(selected))
                .on_hover_text(name)
                .clicked()
            {
                picked = Some(Some([r, g, b]));
                ui.close();
            }
        }
    });
    let mut rgb = current.unwrap_or([0xb8, 0xc6, 0xd6]);
    ui.horizontal(|ui| {
        ui.label("Other");
        if ui.color_edit_button_srgb(&mut rgb).changed() {
            picked = Some(Some(rgb));
        }
    });
    if ui
        .add_enabled(current.is_some(), egui::Button::new("Default (grey)"))
        .clicked()
    {
        picked = Some(None);
        ui.close();
    }
    picked
}
