//! The layout of a phone or a narrow window (less than [`NARROW_WIDTH`] points wide): the 3D view
//! on top and the parameters below it, the node canvas behind a tab, and a status bar whose
//! lines wrap. Wider windows keep the side-by-side layout of `EditorApp::ui`.

use egui::Ui;

use crate::app::EditorApp;

/// Below this width (points) the editor stacks the 3D view over the parameters.
pub const NARROW_WIDTH: f32 = 720.0;

/// The share of the height below the tabs that the 3D view (with its one row of controls) takes in
/// a narrow layout; the parameters get the rest.
pub const NARROW_VIEW_SHARE: f32 = 0.76;

/// The tab shown in a narrow layout.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
enum Tab {
    /// The 3D view over the parameters.
    #[default]
    Design,
    /// The node canvas.
    Graph,
}

fn tab_id() -> egui::Id {
    egui::Id::new("cnets-narrow-tab")
}

/// Whether the window is narrow enough for the stacked layout.
pub fn is_narrow(ctx: &egui::Context) -> bool {
    ctx.content_rect().width() < NARROW_WIDTH
}

/// Shows the node canvas's tab (a node picked in the 3D view's list of errors).
pub fn show_canvas(ctx: &egui::Context) {
    ctx.data_mut(|d| d.insert_temp(tab_id(), Tab::Graph));
}

/// The status bar of a narrow layout: the document's title and the message, wrapped.
pub fn status_bar(ui: &mut Ui, title: &str, message: &str) {
    ui.add(egui::Label::new(egui::RichText::new(title).strong()).wrap());
    if !message.is_empty() {
        ui.add(egui::Label::new(message).wrap());
    }
}

/// The panels of a narrow layout (the menu and status bars are drawn already).
pub fn panels(app: &mut EditorApp, ui: &mut Ui) {
    let ctx = ui.ctx().clone();
    let mut tab: Tab = ctx.data(|d| d.get_temp(tab_id())).unwrap_or_default();
    egui::Panel::top("cnets-narrow-tabs").show(ui, |ui| {
        ui.horizontal(|ui| {
            ui.selectable_value(&mut tab, Tab::Design, "3D view · parameters");
            ui.selectable_value(&mut tab, Tab::Graph, "Node graph");
        });
    });
    ctx.data_mut(|d| d.insert_temp(tab_id(), tab));
    match tab {
        Tab::Design => {
            // The 3D view takes most of the screen (its controls one row); the parameters
            // scroll below it.
            let height = (ui.available_height() * NARROW_VIEW_SHARE).max(160.0);
            egui::Panel::top("cnets-narrow-view")
                .exact_size(height)
                .resizable(false)
                .frame(egui::Frame::NONE)
                .show(ui, |ui| app.viewport_contents(ui, false));
            let actions = egui::CentralPanel::default()
                .show(ui, |ui| {
                    egui::ScrollArea::vertical()
                        .show(ui, |ui| app.parameters_contents(ui))
                        .inner
                })
                .inner;
            for a in actions {
                app.apply(a);
            }
        }
        Tab::Graph => {
            egui::CentralPanel::default()
                .frame(egui::Frame::NONE)
                .show(ui, |ui| app.canvas_contents(ui));
        }
    }
}
