//! The menu bar. It only reports what was picked ([`MenuAction`]); the app carries it out, so
//! the same actions serve the menus, the keyboard shortcuts and tests.

use std::path::{Path, PathBuf};

use crate::export::ExportFormat;
use crate::preview::{ColorMode, DistanceSide, Layer, PreviewOptions};
use crate::viewport::screen::CPlane;
use crate::viewport::{DrawTool, MeasureTool, NamedView, Tool};

/// Something picked in a menu (or by a shortcut).
#[derive(Clone, Debug, PartialEq)]
pub enum MenuAction {
    /// New empty graph.
    New,
    /// Show the open dialog.
    Open,
    /// Open this file (recent files).
    OpenPath(PathBuf),
    /// Open an untitled copy of this shipped example.
    OpenExample(PathBuf),
    /// Save (save-as for an untitled graph).
    Save,
    /// Show the save-as dialog.
    SaveAs,
    /// A quick export of the preview in a format, under a name asked next.
    Export(ExportFormat),
    /// Run the graph's own export nodes into a folder chosen next, and list what they wrote.
    RunExports,
    /// Undo.
    Undo,
    /// Redo.
    Redo,
    /// Delete the selected / focused nodes.
    Delete,
    /// Duplicate them.
    Duplicate,
    /// Copy them.
    Copy,
    /// Paste the copied nodes.
    Paste,
    /// Open the node palette.
    AddNode,
    /// Frame the geometry in the viewport.
    Fit,
    /// Frame the whole graph on the canvas.
    FitCanvas,
    /// Lay the graph out in columns by dependency depth.
    Arrange,
    /// Change the viewport's display options.
    SetPreview(PreviewOptions),
    /// Replace the selected nodes by one cluster node.
    MakeCluster,
    /// Replace the focused (or selected) cluster node by its nodes.
    ExplodeCluster,
    /// Open the focused cluster node to edit its subgraph in place.
    OpenCluster,
    /// Go back out to breadcrumb level `n` (0: the document's own graph).
    LeaveTo(usize),
    /// Show or hide the optimization panel.
    ToggleOptimization,
    /// Show or hide the parameter panel.
    ToggleParameters,
    /// Choose the user library folder.
    LibraryFolder,
    /// Put a share link of the graph in the address bar and the clipboard (web page only).
    CopyLink,
    /// Open another document's unsaved work kept aside by the page (File ▸ Restore kept work).
    RestoreKept,
    /// Close the editor.
    Quit,
    /// Show a named view of the 3D view.
    View(NamedView),
    /// Frame the geometry of the selected nodes and handles.
    FrameSelection,
    /// Switch the 3D view's tool (back to Select when it is the active one).
    Tool(Tool),
    /// Turn grid snap on or off.
    ToggleSnap,
    /// Show or hide the grid and axes.
    ToggleGrid,
    /// Show or hide the size of the previewed geometry.
    ToggleDimensions,
    /// Draw only the selected nodes' previews, or every previewed node again.
    ToggleOnlySelected,
    /// Set the Perspective view's construction plane to a world plane.
    PerspectivePlane(CPlane),
    /// Set it to the graph's construction plane of this name.
    NamedCPlane(String),
    /// Start the *CPlane from 3 points* tool.
    CPlaneFromPoints,
    /// Fit a construction plane through the selected curve or the clicked row of a net.
    CPlaneThroughSelection,
}

/// What the menus need to know.
pub struct MenuContext<'a> {
    /// Example graphs (files in `graphs/`).
    pub examples: &'a [PathBuf],
    /// Recent files.
    pub recent: &'a [PathBuf],
    /// Undo possible.
    pub can_undo: bool,
    /// Redo possible.
    pub can_redo: bool,
    /// Something to paste.
    pub can_paste: bool,
    /// Viewport options.
    pub preview: PreviewOptions,
    /// How deep in opened clusters the canvas is.
    pub depth: usize,
    /// Whether the optimization panel is shown.
    pub optimization: bool,
    /// Whether the parameter panel is shown.
    pub parameters: bool,
    /// The user library folder.
    pub library: &'a Path,
    /// In a web page: File ▸ Copy link, downloads instead of save dialogs, no Quit.
    pub web: bool,
    /// The 3D view's state: named view, grid snap, grid, size shown, Perspective plane.
    pub view: ViewMenuState,
    /// How many export nodes the graph has (File › Export › Graph's exports runs them).
    pub exports: usize,
    /// The graph's named construction planes (listed with the world planes).
    pub cplanes: &'a [cnets_engine::file::NamedPlane],
    /// Another document's unsaved work the page kept aside, by name (File ▸ Restore kept work).
    pub kept_recovery: Option<&'a str>,
}

/// What the View menu shows of the 3D view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewMenuState {
    /// The named view shown.
    pub view: NamedView,
    /// Grid snap is on.
    pub snap: bool,
    /// The grid is shown.
    pub grid: bool,
    /// The size of the geometry is shown.
    pub dimensions: bool,
    /// Only the selected nodes' previews are drawn.
    pub only_selected: bool,
    /// The Perspective view's construction plane.
    pub perspective_plane: CPlane,
}

fn file_label(p: &Path) -> String {
    p.file_name().map_or_else(
        || p.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

/// Shows the menu bar; returns what was picked.
pub fn menu_bar(ui: &mut egui::Ui, mc: &MenuContext<'_>) -> Option<MenuAction> {
    let mut action = None;
    let mut pick_preview = None;
    let mut pick_plane = None;
    let mut pick_view = None;
    let mut pick =
        |ui: &mut egui::Ui, label: &str, shortcut: &str, a: MenuAction, enabled: bool| {
            let button = egui::Button::new(label).shortcut_text(shortcut);
            let response = ui.add_enabled(enabled, button);
            crate::probe::record(ui.ctx(), label, response.rect);
            if response.clicked() {
                action = Some(a);
                ui.close();
            }
        };
    egui::MenuBar::new().ui(ui, |ui| {
        let file = ui.menu_button("File", |ui| {
            pick(ui, "New", "", MenuAction::New, true);
            pick(ui, "Open…", "Ctrl+O", MenuAction::Open, true);
            ui.menu_button("Open example", |ui| {
                if mc.examples.is_empty() {
                    ui.weak("no graphs/ folder found");
                }
                for p in mc.examples {
                    pick(
                        ui,
                        &file_label(p),
                        "",
                        MenuAction::OpenExample(p.clone()),
                        true,
                    );
                }
            });
            ui.menu_button("Recent files", |ui| {
                if mc.recent.is_empty() {
                    ui.weak("none yet");
                }
                for p in mc.recent {
                    pick(
                        ui,
                        &p.display().to_string(),
                        "",
                        MenuAction::OpenPath(p.clone()),
                        true,
                    );
                }
            });
            ui.separator();
            pick(ui, "Save", "Ctrl+S", MenuAction::Save, true);
            pick(ui, "Save as…", "Ctrl+Shift+S", MenuAction::SaveAs, true);
            let export = ui.menu_button("Export", |ui| {
                // The graph's own export nodes, with their names and settings (as `cnets run`).
                pick(
                    ui,
                    "Graph's exports…",
                    "",
                    MenuAction::RunExports,
                    mc.exports > 0,
                );
                ui.separator();
                ui.weak("the preview, named next:");
                for f in ExportFormat::ALL {
                    pick(
                        ui,
                        &format!("{}…", f.extension().to_uppercase()),
                        "",
                        MenuAction::Export(f),
                        true,
                    );
                }
            });
            crate::probe::record(ui.ctx(), "Export", export.response.rect);
            ui.separator();
            if let Some(kept) = mc.kept_recovery {
                pick(
                    ui,
                    &format!("Restore kept work: {kept}"),
                    "",
                    MenuAction::RestoreKept,
                    true,
                );
            }
            if mc.web {
                pick(ui, "Copy link", "", MenuAction::CopyLink, true);
            } else {
                pick(ui, "Quit", "Ctrl+Q", MenuAction::Quit, true);
            }
        });
        crate::probe::record(ui.ctx(), "File", file.response.rect);
        ui.menu_button("Edit", |ui| {
            pick(ui, "Undo", "Ctrl+Z", MenuAction::Undo, mc.can_undo);
            pick(ui, "Redo", "Ctrl+Shift+Z", MenuAction::Redo, mc.can_redo);
            ui.separator();
            pick(ui, "Copy", "Ctrl+C", MenuAction::Copy, true);
            pick(ui, "Paste", "Ctrl+V", MenuAction::Paste, mc.can_paste);
            pick(ui, "Duplicate", "Ctrl+D", MenuAction::Duplicate, true);
            pick(ui, "Delete", "Delete", MenuAction::Delete, true);
            ui.separator();
            pick(ui, "Make cluster", "Ctrl+G", MenuAction::MakeCluster, true);
            pick(
                ui,
                "Explode cluster",
                "Ctrl+Shift+G",
                MenuAction::ExplodeCluster,
                true,
            );
            pick(
                ui,
                "Open cluster",
                "double-click its title",
                MenuAction::OpenCluster,
                true,
            );
            pick(
                ui,
                "Back out of cluster",
                "Esc",
                MenuAction::LeaveTo(mc.depth.saturating_sub(1)),
                mc.depth > 0,
            );
        });
        let add = ui.menu_button("Add", |ui| {
            pick(
                ui,
                "Node…",
                "double-click canvas",
                MenuAction::AddNode,
                true,
            );
            ui.separator();
            ui.weak(format!("library: {}", mc.library.display()));
            pick(ui, "Library folder…", "", MenuAction::LibraryFolder, true);
        });
        crate::probe::record(ui.ctx(), "Add", add.response.rect);
        let view = ui.menu_button("View", |ui| {
            for v in NamedView::ALL {
                let r = ui.radio(
                    mc.view.view == v,
                    format!("{}   {}", v.label(), v.shortcut()),
                );
                crate::probe::record(ui.ctx(), v.label(), r.rect);
                if r.clicked() {
                    pick_view = Some(MenuAction::View(v));
                    ui.close();
                }
            }
            let planes = ui.menu_button("Construction plane", |ui| {
                ui.weak("the Perspective view's:");
                for p in CPlane::ALL {
                    if ui
                        .radio(mc.view.perspective_plane == p, p.label())
                        .clicked()
                    {
                        pick_plane = Some(MenuAction::PerspectivePlane(p));
                        ui.close();
                    }
                }
                for named in mc.cplanes {
                    let on = CPlane::from_named(named) == Some(mc.view.perspective_plane);
                    let r = ui.radio(on, named.name.as_str());
                    crate::probe::record(ui.ctx(), &named.name, r.rect);
                    if r.clicked() {
                        pick_plane = Some(MenuAction::NamedCPlane(named.name.clone()));
                        ui.close();
                    }
                }
            });
            crate::probe::record(ui.ctx(), "Construction plane", planes.response.rect);
            pick(
                ui,
                "CPlane from 3 points",
                "",
                MenuAction::CPlaneFromPoints,
                true,
            );
            pick(
                ui,
                "CPlane through curve or row",
                "",
                MenuAction::CPlaneThroughSelection,
                true,
            );
            ui.separator();
            pick(ui, "Frame geometry", "F", MenuAction::Fit, true);
            pick(
                ui,
                "Frame selection",
                "Shift+F",
                MenuAction::FrameSelection,
                true,
            );
            pick(ui, "Frame graph", "Home", MenuAction::FitCanvas, true);
            pick(ui, "Arrange graph", "Ctrl+L", MenuAction::Arrange, true);
            let label = if mc.optimization {
                "Hide optimization"
            } else {
                "Optimization"
            };
            pick(ui, label, "", MenuAction::ToggleOptimization, true);
            let label = if mc.parameters {
                "Hide parameters"
            } else {
                "Parameters"
            };
            pick(ui, label, "Ctrl+P", MenuAction::ToggleParameters, true);
            ui.separator();
            pick(
                ui,
                "Draw curve",
                "C",
                MenuAction::Tool(Tool::Draw(DrawTool::default())),
                true,
            );
            pick(
                ui,
                "Measure",
                "M",
                MenuAction::Tool(Tool::Measure(MeasureTool::default())),
                true,
            );
            let check = |on: bool, what: &str| format!("{} {what}", if on { "☑" } else { "☐" });
            pick(
                ui,
                &check(mc.view.snap, "Grid snap"),
                "F9",
                MenuAction::ToggleSnap,
                true,
            );
            pick(
                ui,
                &check(mc.view.grid, "Grid and axes"),
                "F7",
                MenuAction::ToggleGrid,
                true,
            );
            pick(
                ui,
                &check(mc.view.dimensions, "Size (W × D × H)"),
                "",
                MenuAction::ToggleDimensions,
                true,
            );
            pick(
                ui,
                &check(mc.view.only_selected, "Preview only the selected"),
                "",
                MenuAction::ToggleOnlySelected,
                true,
            );
            ui.separator();
            ui.label("Colour faces by");
            for mode in ColorMode::ALL {
                let mut o = mc.preview;
                if ui.radio(o.color_mode == mode, mode.label()).clicked() {
                    o.color_mode = mode;
                    pick_preview = Some(o);
                }
                // The distance mode's side: the net by its distance to the reference, or the
                // reference by its distance to the net (a gap the net's colours cannot show).
                if mode == ColorMode::Distance {
                    for side in [DistanceSide::Net, DistanceSide::Reference] {
                        let mut o = mc.preview;
                        let on = o.color_mode == ColorMode::Distance && o.distance_side == side;
                        if ui.radio(on, format!("    {}", side.label())).clicked() {
                            o.color_mode = ColorMode::Distance;
                            o.distance_side = side;
                            pick_preview = Some(o);
                        }
                    }
                }
            }
            ui.separator();
            for layer in Layer::ALL {
                let mut on = mc.preview.shows(layer);
                if ui.checkbox(&mut on, layer.label()).changed() {
                    let mut o = mc.preview;
                    o.set(layer, on);
                    pick_preview = Some(o);
                }
            }
        });
        crate::probe::record(ui.ctx(), "View", view.response.rect);
    });
    pick_preview
        .map(MenuAction::SetPreview)
        .or(pick_plane)
        .or(pick_view)
        .or(action)
}

/// Graph files of a folder (the examples menu), sorted ([`cnets_host::graph_files`]; none when
/// the folder cannot be read).
pub fn examples_in(dir: &Path) -> Vec<PathBuf> {
    cnets_host::graph_files(dir).unwrap_or_default()
}
