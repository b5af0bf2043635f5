//! The notice over the middle of the window while a large graph file is read in the background
//! (the desktop's reading thread, `app/loading.rs`; the web page's evaluation worker).

/// A large file's size as the designer reads it: "34.9 MB".
pub fn megabytes(bytes: u64) -> String {
    format!("{:.1} MB", bytes as f64 / 1e6)
}

/// The title of the notice for a file `name` of `bytes` bytes: "Opening big.ron (34.9 MB)".
pub fn title(name: &str, bytes: u64) -> String {
    format!("Opening {name} ({})", megabytes(bytes))
}

/// What the designer should expect meanwhile.
pub const DETAIL: &str = "It is read in the background; it replaces the document when it is ready.";

/// Draws the notice (a spinner, `title` and `detail`) over the middle of the window. egui lays
/// an anchored area out unseen in its first frame: the notice shows from the second.
pub fn show(ctx: &egui::Context, title: &str, detail: &str) {
    egui::Area::new(egui::Id::new("cnets-opening"))
        .order(egui::Order::Foreground)
        .anchor(egui::Align2::CENTER_CENTER, egui::Vec2::ZERO)
        .interactable(false)
        // No fade-in: a file read quickly leaves no time for one.
        .fade_in(false)
        .show(ctx, |ui| {
            egui::Frame::popup(ui.style()).show(ui, |ui| {
                ui.set_max_width(360.0);
                ui.horizontal(|ui| {
                    ui.spinner();
                    ui.strong(title);
                });
                ui.label(detail);
            });
        });
}
