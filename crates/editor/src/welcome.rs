//! The first visit's hint (the web page, docs/web.md): a small card in the 3D view's corner that
//! says what to try first, shown until the visitor dismisses it ("Got it", its ×, or Escape).
//! The page remembers the dismissal in the browser's storage, so it is shown once per browser.

use egui::{Align2, Context, Rect, RichText, vec2};

/// What the hint says, one line each.
pub const LINES: &[&str] = &[
    "Drag a slider on a node (or in the parameter panel) to change the design.",
    "3D view: drag to orbit, right-drag to pan, wheel to zoom, F to frame.",
    "Double-click the canvas to add a node.",
    "The gallery: Open example in the File menu.",
];

/// The hint as drawn in one frame.
#[derive(Clone, Copy, Debug)]
pub struct Shown {
    /// Where the card is, in points.
    pub rect: Rect,
    /// The visitor dismissed it in this frame.
    pub dismissed: bool,
}

/// Draws the hint at the right of `view` (the 3D view's rectangle) from `top` down (below the
/// view's labels: statistics and legend).
pub fn show(ctx: &Context, view: Rect, top: f32) -> Shown {
    let mut dismissed = ctx.input(|i| i.key_pressed(egui::Key::Escape));
    let width = (view.width() - 16.0).clamp(160.0, 320.0);
    let area = egui::Area::new(egui::Id::new("cnets-welcome"))
        .order(egui::Order::Foreground)
        .anchor(
            Align2::RIGHT_TOP,
            vec2(
                view.right() - ctx.content_rect().right() - 8.0,
                top.max(view.top()) + 8.0,
            ),
        )
        .show(ctx, |ui| {
            egui::Frame::popup(ui.style()).show(ui, |ui| {
                ui.set_max_width(width);
                ui.horizontal(|ui| {
                    ui.label(RichText::new("Welcome to cnets").strong());
                    ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                        dismissed |= ui.small_button("×").on_hover_text("Close").clicked();
                    });
                });
                for line in LINES {
                    ui.add(egui::Label::new(*line).wrap());
                }
                dismissed |= ui.button("Got it").clicked();
            });
        });
    Shown {
        rect: area.response.rect,
        dismissed,
    }
}
