//! The 3D view: where designs are watched and made.
//!
//! The preview [`Scene`] is drawn with wgpu ([`gpu`]) over a ground grid and the world axes
//! ([`grid`]), from named views — Top, Front, Right (orthographic) and Perspective
//! ([`navigation`]). Each tool is a small state machine fed by the pointer that returns graph
//! edits, applied by the app through the one `edit::apply`:
//!
//! - select ([`handles`], [`pick`]): grab, box select, nudge and type the points of `param.point`
//!   and `param.points` nodes; hover a mesh for the node, row and column, class and planarity of a
//!   face or vertex, click it to select its node;
//! - Draw curve ([`draw`]): click points on the construction plane → `param.points` + a curve;
//! - CPlane from 3 points ([`cplane_make`]): three clicks snapped to vertices and handles → a new
//!   construction plane ([`cplane`]) for the Perspective view, kept with the graph;
//! - Measure ([`measure`]): two clicks snapped to vertices → their distance;
//! - Drag net ([`net_drag`]): grab a vertex of a cone-net and drag it, the design's inputs solved
//!   to follow (Shift+click pins).
//!
//! The view's state is five owned parts: [`framing`] (where it looks from), [`drawn`] (the scene
//! and what was handed to the GPU), [`display`] (the designer's toggles), [`tools`] (the active
//! tool and what the pointer is over) and [`last_frame`] (where the overlays went). Others read
//! them through [`Viewport::framing`] and its siblings and change them through the view's methods.
//!
//! The overlay ([`overlay`]) shows counts, the legend with its fold entry, and the size of the
//! previewed geometry. The same code runs in the web build. Keys and mouse: docs/editor/3d-view.md,
//! "Drawing and editing in the 3D view".

pub mod colors;
pub mod cplane;
pub mod cplane_make;
pub mod cut_plane;
pub mod display;
pub mod distance;
pub mod draw;
pub mod drawn;
pub mod framing;
pub mod gpu;
pub mod grid;
pub mod handles;
pub mod last_frame;
pub mod measure;
pub mod navigation;
pub mod net_drag;
pub mod overlay;
pub mod pick;
pub mod screen;
pub mod tools;

use std::sync::Arc;

use cnets_engine::{Graph, NodeInstance};
use cnets_geometry::DVec3;
use cnets_render::{Bounds, Scene, Segment};
use eframe::egui_wgpu;
use egui::{Color32, Key, Modifiers, PointerButton, Pos2, Rect, Sense, Ui};

use crate::edit::Edit;
use crate::preview::{Picks, PreviewStats};

pub use cplane::{CPlane, CPlaneError};
pub use cplane_make::ThreePointTool;
pub use display::Display;
pub use draw::{DrawTool, DrawnCurve};
pub use drawn::Drawn;
pub use framing::Framing;
pub use gpu::GpuTarget;
use gpu::{Guides, ViewportCallback};
use grid::{Grid, Spacing};
use handles::{DragPlane, Handle};
pub use last_frame::LastFrame;
pub use measure::MeasureTool;
pub use navigation::NamedView;
pub use net_drag::{NetDragTarget, NetDragTool, NetVertex};
use screen::ScreenMap;
pub use tools::ViewTools;

/// The active tool of the view.
#[derive(Clone, Debug, PartialEq, Default)]
pub enum Tool {
    /// Select, grab and move handles; pick meshes.
    #[default]
    Select,
    /// Draw a curve.
    Draw(DrawTool),
    /// Measure a distance.
    Measure(MeasureTool),
    /// Drag a vertex of a cone-net, the design's inputs solved to follow.
    DragNet(Box<NetDragTool>),
    /// Make a construction plane from three clicked points.
    ThreePoint(ThreePointTool),
}

impl Tool {
    /// Button and menu label.
    pub fn label(&self) -> &'static str {
        match self {
            Tool::Select => "Select",
            Tool::Draw(_) => "Draw curve",
            Tool::Measure(_) => "Measure",
            Tool::DragNet(_) => "Drag net",
            Tool::ThreePoint(_) => "CPlane from 3 points",
        }
    }
}

/// What the view asks the app to do.
#[derive(Clone, Debug, PartialEq)]
pub enum ViewportAction {
    /// Change the document.
    Edit(Edit),
    /// Select this node on the canvas.
    SelectNode(String),
    /// Add a drawn curve as nodes.
    AddCurve(DrawnCurve),
    /// Say this in the status bar.
    Message(String),
    /// Solve the design so a grabbed cone-net vertex reaches a target (the Drag net tool).
    DragNet(NetDragTarget),
    /// The net's drag ended (the pointer was released): commit it as one undo step.
    DragNetEnd,
    /// A construction plane was made in the view: name it, keep it with the graph and make it
    /// the Perspective view's.
    AddCPlane(CPlane),
}

/// What the view needs to know of the rest of the editor each frame.
pub struct ViewportInput<'a> {
    /// The document's graph (the points of its point nodes are handles).
    pub graph: &'a Graph,
    /// The nodes selected (or focused) on the canvas.
    pub selected: &'a [String],
    /// A text field has the keyboard.
    pub typing: bool,
}

/// Resolution factor while the picture changes on a software rasterizer.
pub const INTERACTIVE_SCALE: f32 = 0.5;
/// Seconds without changes after which the view is rendered at full resolution again.
const SETTLE_SECONDS: f64 = 0.3;
/// The height (points) of the label rows along the 3D view's top and bottom edges, kept clear
/// of the geometry when the view frames it.
pub const LABEL_BAND: f32 = 40.0;
/// Screen distance (points) within which a measured point snaps to a drawn vertex.
pub const SNAP_RADIUS: f32 = 10.0;

/// The viewport's state, in parts that own their fields.
#[derive(Default)]
pub struct Viewport {
    /// The camera and the named view.
    framing: Framing,
    /// The scene shown and what was handed to the GPU.
    drawn: Drawn,
    /// The designer's display choices.
    display: Display,
    /// The active tool, the handles and what the pointer is over.
    tools: ViewTools,
    /// Where the last frame put its overlays.
    last_frame: LastFrame,
}

impl Viewport {
    /// The camera and the named view (read-only: the view's methods change them).
    pub fn framing(&self) -> &Framing {
        &self.framing
    }

    /// The scene shown, its figures and what was handed to the GPU.
    pub fn drawn(&self) -> &Drawn {
        &self.drawn
    }

    /// The designer's display choices.
    pub fn display(&self) -> &Display {
        &self.display
    }

    /// The display choices, to change (the menus and the layout file).
    pub fn display_mut(&mut self) -> &mut Display {
        &mut self.display
    }

    /// The active tool, the handles and what the pointer is over.
    pub fn tools(&self) -> &ViewTools {
        &self.tools
    }

    /// Where the last frame put its overlays (the grid step, the labels, the fold entry).
    pub fn last_frame(&self) -> &LastFrame {
        &self.last_frame
    }

    /// Replaces the scene (from a finished evaluation) and what was drawn in it.
    pub fn set_scene(&mut self, scene: Arc<Scene>, stats: PreviewStats, picks: Arc<Picks>) {
        self.drawn.set(scene, stats, picks);
        self.framing.last_change = f64::NAN; // stamped with egui's time in the next `show`
        self.tools.forget_hover();
        if !self.framing.fitted_once && !self.drawn.scene.is_empty() {
            self.framing.fit_pending = true;
        }
    }

    /// Clears the scene for a new document (the next geometry is framed again).
    pub fn reset(&mut self) {
        self.set_scene(
            Arc::new(Scene::new()),
            PreviewStats::default(),
            Arc::new(Picks::default()),
        );
        self.framing.fitted_once = false;
        self.drawn.clear_folds();
        self.tools = ViewTools::default();
    }

    /// How many pictures the GPU has rendered into the view's texture so far. A frame in which
    /// the scene, guides, camera and size are unchanged only blits the last one and is not
    /// counted (panning the canvas, typing in a field).
    pub fn pictures_rendered(&self) -> u64 {
        self.drawn.pictures_rendered()
    }

    /// The scene shown.
    pub fn scene(&self) -> &Arc<Scene> {
        &self.drawn.scene
    }

    /// What the scene drew, by node.
    pub fn picks(&self) -> &Arc<Picks> {
        &self.drawn.picks
    }

    /// The figures and legend of the scene shown.
    pub fn stats(&self) -> &PreviewStats {
        &self.drawn.stats
    }

    /// Version of the scene (bumped by [`Viewport::set_scene`]).
    pub fn scene_version(&self) -> u64 {
        self.drawn.version
    }

    /// The newest scene version handed to the GPU: the picture shows a change once this reaches
    /// its [`Viewport::scene_version`].
    pub fn handed_version(&self) -> u64 {
        self.drawn.handed_version
    }

    /// The box of the previewed surfaces and curves (W × D × H).
    pub fn bounds(&self) -> Option<Bounds> {
        self.drawn.bounds
    }

    /// The cuts of the selected nodes drawn in the last frame: their planes and kept sides.
    pub fn cut_overlays(&self) -> &[cut_plane::CutOverlay] {
        &self.last_frame.cut_overlays
    }

    /// The handles shown in the last frame.
    pub fn handle_list(&self) -> &[Handle] {
        &self.tools.handle_list
    }

    /// The active tool.
    pub fn tool(&self) -> &Tool {
        &self.tools.tool
    }

    /// Makes `tool` the active one.
    pub fn set_tool(&mut self, tool: Tool) {
        self.tools.tool = tool;
    }

    /// The screen mapping of the last frame.
    pub fn screen_map(&self) -> ScreenMap {
        self.framing.screen_map()
    }

    /// Where the view was drawn in the last frame (screen points).
    pub fn rect(&self) -> Rect {
        self.framing.rect
    }

    /// The grid step of the last frame (the snap step), in metres.
    pub fn grid_step(&self) -> f64 {
        self.last_frame.spacing.minor
    }

    /// The construction plane of the view shown.
    pub fn cplane(&self) -> CPlane {
        self.framing.cplane()
    }

    /// The name of the construction plane of the view shown.
    pub fn cplane_name(&self) -> String {
        self.framing.cplane_name()
    }

    /// Makes `plane`, called `name`, the Perspective view's construction plane.
    pub fn set_perspective_plane(&mut self, plane: CPlane, name: &str) {
        self.framing.set_perspective_plane(plane, name);
    }

    /// The construction plane fitted through the row of the net last clicked (when its node is
    /// selected) or the previewed curve of a selected node, and what it went through; an error
    /// saying what to select.
    pub fn fit_cplane(&self, selected: &[String]) -> Result<(CPlane, String), CPlaneError> {
        let (points, what) =
            cplane_make::fit_points(&self.drawn.picks, self.tools.picked.as_ref(), selected)?;
        let plane = CPlane::fit(&points).map_err(|error| CPlaneError::Through {
            what: what.clone(),
            error: Box::new(error),
        })?;
        Ok((plane, what))
    }

    /// Where the last solve of a net drag left the grabbed vertex and its distance to the target
    /// (drawn as a line to the target when it stopped short).
    pub fn set_net_reached(&mut self, reached: DVec3, distance_left: f64) {
        if let Tool::DragNet(d) = &mut self.tools.tool {
            d.reached = Some((reached, distance_left));
        }
    }

    /// Zooms the camera out by `factor` (in below 1), about the point it looks at.
    pub fn zoom(&mut self, factor: f32) {
        self.framing.camera.zoom(factor);
    }

    /// Turns the camera about the point it looks at by `yaw` and `pitch` (radians).
    pub fn orbit(&mut self, yaw: f32, pitch: f32) {
        self.framing.camera.orbit(yaw, pitch);
    }

    /// Frames everything on the next frame (the F key).
    pub fn fit(&mut self) {
        self.framing.fit_pending = true;
    }

    /// Shows a named view, framing the previewed geometry.
    pub fn set_view(&mut self, view: NamedView) {
        self.framing.set_view(view);
    }

    /// A two-finger gesture: zooms by `zoom` (> 1: the fingers spread, in) about `centre` and
    /// pans by the fingers' common move `moved` (screen points).
    pub fn pinch(&mut self, zoom: f32, moved: egui::Vec2, centre: egui::Pos2) {
        self.framing.pinch(zoom, moved, centre);
    }

    /// Points the camera at the surfaces (apices and other markers can lie far away, even near
    /// infinity, and would shrink the mesh to a dot), or at everything when there are none; with
    /// nothing at all, at 20 m around the origin. Handles are included.
    fn frame_geometry(&mut self) {
        let scene = &self.drawn.scene;
        let mut points: Vec<glam::Vec3> = scene
            .face_vertices()
            .iter()
            .map(|v| glam::Vec3::from(v.position))
            .collect();
        if points.is_empty() {
            points.extend(scene.positions());
        }
        points.extend(self.tools.handle_list.iter().map(|h| h.position.as_vec3()));
        if points.is_empty() {
            let b = Bounds::new(
                glam::Vec3::new(-10.0, -10.0, 0.0),
                glam::Vec3::new(10.0, 10.0, 0.0),
            );
            points.extend(b.corners());
        }
        self.framing.frame_points(&points);
    }

    /// Frames the geometry of the nodes `ids` (their previewed meshes and curves, their handles)
    /// and the selected handles; everything when there is none.
    pub fn frame_selection(&mut self, ids: &[String]) {
        let picks = &self.drawn.picks;
        let mut points: Vec<glam::Vec3> = Vec::new();
        for m in picks.meshes.iter().filter(|m| ids.contains(&m.node)) {
            points.extend(m.geometry.vertices().iter().map(|p| p.as_vec3()));
        }
        for c in picks.curves.iter().filter(|c| ids.contains(&c.node)) {
            points.extend(c.polyline.points.iter().map(|p| p.as_vec3()));
        }
        for h in &self.tools.handle_list {
            if ids.contains(&h.key.node) || self.tools.handles.selected.contains(&h.key) {
                points.push(h.position.as_vec3());
            }
        }
        if points.is_empty() {
            self.fit();
        } else {
            self.framing.frame_points(&points);
        }
    }

    /// The legend's fold entry: frames the faces that are not (++)(++) and outlines them.
    pub fn show_folds(&mut self) {
        let picks = &self.drawn.picks;
        let corners: Vec<glam::Vec3> = picks
            .folded_faces()
            .into_iter()
            .flat_map(|(m, f)| picks.meshes[m].geometry.face_corners(f))
            .map(|p| p.as_vec3())
            .collect();
        if corners.is_empty() {
            return;
        }
        self.framing
            .camera
            .fit_points(&corners, self.framing.aspect);
        self.drawn.outline_folds();
    }

    /// The outline segments drawn for the folds (empty unless shown).
    pub fn highlight(&self) -> &[Segment] {
        &self.drawn.highlight
    }

    /// The snap step, or none while snapping is off or Alt is held.
    fn snap_step(&self, modifiers: Modifiers) -> Option<f64> {
        (self.display.snap && !modifiers.alt).then_some(self.last_frame.spacing.minor)
    }

    /// Where the pointer at `at` puts a point on the construction plane, snapped to the grid.
    pub fn plane_point(&self, map: &ScreenMap, at: Pos2, modifiers: Modifiers) -> Option<DVec3> {
        let plane = self.cplane();
        let hit = plane.world().hit(&map.ray(at))?;
        Some(match self.snap_step(modifiers) {
            Some(step) => plane.snap(hit, step),
            // Unsnapped: a hundredth of the grid step is resolution enough.
            None => plane.snap(hit, self.last_frame.spacing.minor / 100.0),
        })
    }

    /// Where a measured point at `at` lands: the nearest drawn vertex or handle within
    /// [`SNAP_RADIUS`], else the construction plane.
    fn measure_point(&self, map: &ScreenMap, at: Pos2, modifiers: Modifiers) -> Option<DVec3> {
        let handle = handles::handle_at(&self.tools.handle_list, map, at).map(|h| h.position);
        handle
            .or_else(|| pick::nearest_vertex(&self.drawn.picks, map, at, SNAP_RADIUS))
            .or_else(|| self.plane_point(map, at, modifiers))
    }

    /// The buttons above the view: named views, tools, snap and size toggles.
    pub fn toolbar(&mut self, ui: &mut Ui) {
        for v in NamedView::ALL {
            let label = if v == NamedView::Perspective {
                "Persp"
            } else {
                v.label()
            };
            if ui
                .selectable_label(self.framing.view == v, label)
                .on_hover_text(format!("{} view ({})", v.label(), v.shortcut()))
                .clicked()
            {
                self.set_view(v);
            }
        }
        ui.separator();
        let drawing = matches!(self.tools.tool, Tool::Draw(_));
        if ui
            .selectable_label(drawing, "✏ Draw curve")
            .on_hover_text(
                "click points on the construction plane (C); click the first point to close, \
                 Enter or double-click to finish, Esc to cancel",
            )
            .clicked()
        {
            self.toggle_tool(Tool::Draw(DrawTool::default()));
        }
        if let Tool::Draw(d) = &mut self.tools.tool {
            // The kind of curve drawn, while the tool is active (P switches).
            ui.selectable_value(&mut d.polyline, false, "Spline")
                .on_hover_text("a smooth curve through the points (P switches)");
            ui.selectable_value(&mut d.polyline, true, "Polyline")
                .on_hover_text("straight segments between the points (P switches)");
        }
        let measuring = matches!(self.tools.tool, Tool::Measure(_));
        if ui
            .selectable_label(measuring, "📏 Measure")
            .on_hover_text("click two points (snapping to vertices) for their distance (M)")
            .clicked()
        {
            self.toggle_tool(Tool::Measure(MeasureTool::default()));
        }
        let dragging_net = matches!(self.tools.tool, Tool::DragNet(_));
        if ui
            .selectable_label(dragging_net, "✋ Drag net")
            .on_hover_text(
                "drag a vertex of a cone-net: the sliders, points and handles upstream follow \
                 (G); Shift+click pins a vertex, Esc clears the pins",
            )
            .clicked()
        {
            self.toggle_tool(Tool::DragNet(Box::default()));
        }
        ui.separator();
        ui.toggle_value(&mut self.display.snap, "Snap")
            .on_hover_text("grid snap (F9); hold Alt to suspend it");
        ui.toggle_value(&mut self.display.show_dimensions, "W×D×H")
            .on_hover_text("the size of the previewed geometry in the view's corner");
    }

    /// Switches to `tool`, or back to Select when it is the active one.
    pub fn toggle_tool(&mut self, tool: Tool) {
        self.tools.toggle(tool);
    }

    /// The keys of the view (when no text field has the keyboard): named views, tools, snap,
    /// grid, nudging and the tools' Enter / Backspace / Esc.
    fn keys(
        &mut self,
        ctx: &egui::Context,
        input: &ViewportInput<'_>,
        actions: &mut Vec<ViewportAction>,
    ) {
        if input.typing {
            return;
        }
        if let Some(v) = NamedView::pressed(ctx) {
            self.set_view(v);
        }
        let drawing = matches!(self.tools.tool, Tool::Draw(_));
        let (p, c, m, g, f9, f7, shift_f, enter, backspace, esc) = ctx.input_mut(|i| {
            (
                drawing && i.consume_key(Modifiers::NONE, Key::P),
                i.consume_key(Modifiers::NONE, Key::C),
                i.consume_key(Modifiers::NONE, Key::M),
                i.consume_key(Modifiers::NONE, Key::G),
                i.consume_key(Modifiers::NONE, Key::F9),
                i.consume_key(Modifiers::NONE, Key::F7),
                i.consume_key(Modifiers::SHIFT, Key::F),
                i.key_pressed(Key::Enter),
                i.key_pressed(Key::Backspace),
                i.key_pressed(Key::Escape),
            )
        });
        if p && let Tool::Draw(d) = &mut self.tools.tool {
            d.polyline = !d.polyline;
        }
        if c {
            self.toggle_tool(Tool::Draw(DrawTool::default()));
        }
        if m {
            self.toggle_tool(Tool::Measure(MeasureTool::default()));
        }
        if g {
            self.toggle_tool(Tool::DragNet(Box::default()));
        }
        if f9 {
            self.display.snap = !self.display.snap;
            actions.push(ViewportAction::Message(format!(
                "grid snap {}",
                if self.display.snap { "on" } else { "off" }
            )));
        }
        if f7 {
            self.display.show_grid = !self.display.show_grid;
        }
        if shift_f {
            self.frame_selection(input.selected);
        }
        match &mut self.tools.tool {
            Tool::Draw(d) => {
                if enter && let Some(curve) = d.finish() {
                    actions.push(ViewportAction::AddCurve(curve));
                    // As a Rhino command ends with its curve.
                    self.tools.tool = Tool::Select;
                    return;
                }
                if backspace {
                    d.undo_point();
                }
                if esc {
                    self.tools.tool = Tool::Select;
                }
            }
            Tool::Measure(_) if esc => self.tools.tool = Tool::Select,
            Tool::ThreePoint(t) => {
                if backspace {
                    t.points.pop();
                }
                if esc {
                    self.tools.tool = Tool::Select;
                    actions.push(ViewportAction::Message(
                        "CPlane from 3 points cancelled".into(),
                    ));
                }
            }
            Tool::DragNet(d) if esc => {
                if d.pins.is_empty() {
                    self.tools.tool = Tool::Select;
                } else {
                    d.pins.clear();
                    actions.push(ViewportAction::Message("pins cleared".into()));
                }
            }
            _ if esc => {
                self.tools.handles.selected.clear();
                self.drawn.clear_folds();
            }
            _ => {}
        }
        // Arrow keys nudge the selected handles one grid step in the view's plane (Page Up /
        // Page Down along its normal).
        if !self.tools.handles.selected.is_empty() {
            let (u, v, n) = self.cplane().axes();
            let step = self.last_frame.spacing.minor;
            let delta = ctx.input_mut(|i| {
                let mut d = DVec3::ZERO;
                for (key, dir) in [
                    (Key::ArrowRight, u),
                    (Key::ArrowLeft, -u),
                    (Key::ArrowUp, v),
                    (Key::ArrowDown, -v),
                    (Key::PageUp, n),
                    (Key::PageDown, -n),
                ] {
                    if i.consume_key(Modifiers::NONE, key) {
                        d += dir * step;
                    }
                }
                d
            });
            if delta != DVec3::ZERO
                && let Some(edit) =
                    self.tools
                        .handles
                        .nudge(input.graph, &self.tools.handle_list, delta)
            {
                actions.push(ViewportAction::Edit(edit));
            }
        }
    }

    /// Shows the viewport in the rest of `ui`; returns what the designer asked for.
    pub fn show(
        &mut self,
        ui: &mut Ui,
        gpu: Option<&GpuTarget>,
        input: &ViewportInput<'_>,
    ) -> Vec<ViewportAction> {
        let mut actions = Vec::new();
        let rect = ui.available_rect_before_wrap();
        let response = ui.allocate_rect(rect, Sense::click_and_drag());
        self.framing.place(rect);
        let shown = |n: &NodeInstance| (n.preview && n.enabled) || input.selected.contains(&n.id);
        self.tools.handle_list = handles::collect(input.graph, shown);
        self.tools.handles.retain_existing(&self.tools.handle_list);
        if self.framing.fit_pending {
            self.frame_geometry();
            self.framing.fit_pending = false;
            self.framing.fitted_once = !self.drawn.scene.is_empty();
        }
        self.last_frame.spacing = Spacing::for_scale(self.screen_map().world_per_point());
        let camera_before = self.framing.camera;
        self.keys(ui.ctx(), input, &mut actions);
        self.pointer(ui, &response, input, &mut actions);
        let now = ui.input(|i| i.time);
        if self.framing.camera != camera_before || self.framing.last_change.is_nan() {
            self.framing.last_change = now;
        }
        let changing = now - self.framing.last_change < SETTLE_SECONDS;
        self.framing.render_scale = if changing && gpu.is_some_and(|g| g.software) {
            // Come back for the full-resolution picture once things settle.
            ui.ctx()
                .request_repaint_after(std::time::Duration::from_secs_f64(SETTLE_SECONDS));
            INTERACTIVE_SCALE
        } else {
            1.0
        };
        let map = self.screen_map();
        let grid = self.display.show_grid.then(|| {
            // The perspective view's grid is sized to the geometry shown (the named views are
            // drafting paper: their grid fills the view).
            let around = match self.framing.view {
                NamedView::Perspective => self.drawn.bounds.as_ref(),
                _ => None,
            };
            let mut grid = Grid::new(&map, self.cplane(), around);
            grid.name = self.cplane_name();
            grid
        });
        self.paint_scene(ui, gpu, rect, grid.as_ref());
        let painter = ui.painter_at(rect);
        let gizmo = grid::paint_gizmo(&painter, &map);
        let pointer = ui
            .input(|i| i.pointer.hover_pos())
            .filter(|p| rect.contains(*p));
        self.tools
            .handles
            .paint(&painter, &self.tools.handle_list, &map, pointer);
        // A selected cut's plane and the side it keeps, about half the design's size.
        self.last_frame.cut_overlays = cut_plane::selected_cuts(input.graph, input.selected);
        let half = self
            .drawn
            .bounds
            .map_or(5.0, |b| 0.35 * f64::from((b.max - b.min).length()))
            .max(0.5);
        cut_plane::paint(&painter, &map, &self.last_frame.cut_overlays, half);
        match &self.tools.tool {
            Tool::Draw(d) => d.paint(&painter, &map, self.tools.tool_point),
            Tool::Measure(m) => m.paint(&painter, &map, self.tools.tool_point),
            Tool::DragNet(d) => d.paint(&painter, &map, self.tools.tool_point),
            Tool::ThreePoint(t) => t.paint(&painter, &map, self.tools.tool_point),
            Tool::Select => {}
        }
        // The figures wrap short of the legend's column.
        let stats_width = rect.width() - overlay::LEGEND_WIDTH - 28.0;
        let stats = overlay::paint_stats(ui, rect, &self.drawn.stats, stats_width);
        let folds = self.drawn.picks.folded_faces().len();
        let legend = overlay::legend(ui, rect, stats, &self.drawn.stats, folds);
        self.last_frame.fold_entry = legend.fold_entry;
        self.last_frame.labels_bottom = legend.bottom.max(stats.bottom());
        // Colour by distance: which mesh the others are measured against, and which side is
        // coloured.
        if let Some(message) = distance::ensure_reference(
            &mut self.display.options,
            input.graph,
            &mut self.display.no_reference_said,
        ) {
            actions.push(ViewportAction::Message(message));
        }
        let picker = distance::picker(
            ui,
            rect,
            legend.bottom,
            stats,
            &mut self.display.options,
            input.graph,
        );
        self.last_frame.labels_bottom = self.last_frame.labels_bottom.max(picker.bottom());
        let dimensions = if self.display.show_dimensions {
            overlay::paint_dimensions(ui, rect, self.drawn.bounds.as_ref())
        } else {
            Rect::NOTHING
        };
        // The grid's labels last, clear of the corner figures, the legend, the picker, the gizmo
        // and W × D × H.
        let caption = match &grid {
            Some(grid) => {
                let keep_out = [stats, legend.covers, picker, gizmo, dimensions];
                grid.paint_labels(&painter, &map, &keep_out)
            }
            None => Rect::NOTHING,
        };
        self.last_frame.overlays = [
            ("statistics", stats),
            ("legend", legend.covers),
            ("distance picker", picker),
            ("axes", gizmo),
            ("size", dimensions),
            ("grid", caption),
        ]
        .into_iter()
        .filter(|(_, r)| r.is_positive())
        .collect();
        if legend.clicked {
            self.show_folds();
            actions.push(ViewportAction::Message(format!(
                "{folds} faces are not (++)(++): framed and outlined (Esc clears)"
            )));
        }
        if let Some(edit) = self.inspector(ui, rect, input.graph) {
            actions.push(ViewportAction::Edit(edit));
        }
        if let (Tool::Select, Some(hit), Some(at)) = (&self.tools.tool, &self.tools.hover, pointer)
            && !self.tools.handles.dragging()
        {
            let text = pick::describe(&self.drawn.picks, hit, input.graph);
            egui::Tooltip::always_open(
                ui.ctx().clone(),
                ui.layer_id(),
                egui::Id::new("cnets-viewport-pick"),
                egui::PopupAnchor::Position(at + egui::vec2(14.0, 14.0)),
            )
            .show(|ui| ui.label(text));
        }
        actions
    }

    /// The pointer: handle drags and box selection, tool clicks, orbit / pan / zoom, hover picks.
    fn pointer(
        &mut self,
        ui: &Ui,
        response: &egui::Response,
        input: &ViewportInput<'_>,
        actions: &mut Vec<ViewportAction>,
    ) {
        let map = self.screen_map();
        let (modifiers, scroll, press_origin, hover, touches) = ui.input(|i| {
            (
                i.modifiers,
                i.smooth_scroll_delta.y,
                i.pointer.press_origin(),
                i.pointer.hover_pos(),
                i.multi_touch(),
            )
        });
        // Two fingers on the view: a pinch zooms about their centre and their common move pans
        // (one finger orbits, as a primary drag does); nothing else moves meanwhile.
        if let Some(t) =
            touches.filter(|t| t.num_touches >= 2 && self.framing.rect.contains(t.center_pos))
        {
            self.pinch(t.zoom_delta, t.translation_delta, t.center_pos);
            return;
        }
        let hover = hover.filter(|p| self.framing.rect.contains(*p));
        let primary = response.dragged_by(PointerButton::Primary);
        let ortho = self.framing.view.is_orthographic();
        let cplane = self.cplane();
        // A primary drag starting on a handle moves it; on empty space it box-selects in the
        // orthographic views (or with Ctrl in Perspective), else orbits (Shift: pans).
        let elevator = modifiers.command && !ortho;
        // Orthographic views: the view's plane through the grabbed point; Perspective: the
        // construction plane through it, or its normal with Ctrl.
        let how = |at: DVec3| {
            if elevator {
                DragPlane::Normal(cplane)
            } else {
                DragPlane::Plane(cplane.through(at), cplane)
            }
        };
        if response.drag_started_by(PointerButton::Primary)
            && let Some(p0) = press_origin
        {
            match &mut self.tools.tool {
                Tool::Select => {
                    let grabbed = self.tools.handles.press(
                        &self.tools.handle_list,
                        &map,
                        p0,
                        how,
                        modifiers.shift,
                    );
                    if !grabbed && (ortho || modifiers.command) && !modifiers.shift {
                        self.tools.handles.boxing = Some(p0);
                    }
                }
                Tool::DragNet(d) if !modifiers.shift => {
                    d.press(&self.drawn.picks, &map, p0, how);
                }
                _ => {}
            }
        }
        let net_dragging = matches!(&self.tools.tool, Tool::DragNet(d) if d.dragging());
        if primary && net_dragging {
            if let Tool::DragNet(d) = &mut self.tools.tool
                && let Some(at) = response.interact_pointer_pos()
                && let Some(target) = d.drag_to(&map, at)
            {
                actions.push(ViewportAction::DragNet(target));
            }
        } else if primary && self.tools.handles.dragging() {
            if let Some(at) = response.interact_pointer_pos()
                && let Some(edit) =
                    self.tools
                        .handles
                        .drag_to(input.graph, &map, at, self.snap_step(modifiers))
            {
                actions.push(ViewportAction::Edit(edit));
            }
        } else if primary && self.tools.handles.boxing.is_some() {
            // The box is painted with the handles.
        } else {
            let delta = response.drag_delta();
            let orbiting = (primary && !modifiers.shift && !ortho)
                || (response.dragged_by(PointerButton::Secondary) && modifiers.shift);
            if orbiting {
                if ortho {
                    // Orbiting leaves the named orthographic view for Perspective.
                    self.framing.view = NamedView::Perspective;
                    self.framing.camera.projection = cnets_render::Projection::Perspective;
                }
                navigation::orbit(&mut self.framing.camera, delta);
            } else if response.dragged_by(PointerButton::Secondary)
                || response.dragged_by(PointerButton::Middle)
                || (primary && modifiers.shift)
            {
                self.framing
                    .camera
                    .pan(delta.x, delta.y, self.framing.rect.height());
            }
        }
        if response.drag_stopped() {
            if let Tool::DragNet(d) = &mut self.tools.tool
                && d.dragging()
            {
                d.release();
                actions.push(ViewportAction::DragNetEnd);
            }
            self.tools.handles.release();
            if self.tools.handles.boxing.is_some()
                && let Some(at) = response.interact_pointer_pos().or(hover)
            {
                self.tools
                    .handles
                    .select_box(&self.tools.handle_list, &map, at, modifiers.shift);
            }
            self.tools.handles.boxing = None;
        }
        if response.hovered() && scroll != 0.0 {
            let at = hover.unwrap_or(self.framing.rect.center());
            let mut m = map;
            navigation::wheel(&mut m, scroll, at);
            self.framing.camera = m.camera;
        }
        let map = self.screen_map();
        // Where the tools would put a point under the pointer.
        self.tools.tool_point = hover.and_then(|at| match &self.tools.tool {
            Tool::Draw(_) => self.plane_point(&map, at, modifiers),
            Tool::Measure(_) | Tool::ThreePoint(_) => self.measure_point(&map, at, modifiers),
            Tool::DragNet(d) if !d.dragging() => {
                net_drag::vertex_at(&self.drawn.picks, &map, at).map(|v| v.position)
            }
            Tool::DragNet(_) | Tool::Select => None,
        });
        let clicked = response.clicked_by(PointerButton::Primary);
        let at = response.interact_pointer_pos().or(hover);
        match &mut self.tools.tool {
            Tool::Draw(d) => {
                let finished = if response.double_clicked() {
                    d.finish()
                } else if clicked
                    && let Some(at) = at
                    && let Some(p) = self.tools.tool_point
                    && let draw::Click::Finished(curve) = d.click(&map, at, p)
                {
                    Some(curve)
                } else {
                    None
                };
                if let Some(curve) = finished {
                    actions.push(ViewportAction::AddCurve(curve));
                    // As a Rhino command ends with its curve.
                    self.tools.tool = Tool::Select;
                }
            }
            Tool::DragNet(d) => {
                if clicked
                    && modifiers.shift
                    && let Some(at) = at
                    && let Some(text) = d.toggle_pin(&self.drawn.picks, &map, at)
                {
                    actions.push(ViewportAction::Message(text));
                }
            }
            Tool::Measure(m) => {
                if clicked && let Some(p) = self.tools.tool_point {
                    m.click(p);
                    if let Some(text) = m.text() {
                        actions.push(ViewportAction::Message(text));
                    }
                }
            }
            Tool::ThreePoint(t) => {
                if clicked && let Some(p) = self.tools.tool_point {
                    match t.click(p) {
                        cplane_make::ThreePointClick::Added => {
                            actions.push(ViewportAction::Message(t.prompt().into()));
                        }
                        cplane_make::ThreePointClick::Made(plane) => {
                            actions.push(ViewportAction::AddCPlane(plane));
                            self.tools.tool = Tool::Select;
                        }
                        cplane_make::ThreePointClick::Refused(why) => {
                            actions.push(ViewportAction::Message(why.to_string()));
                        }
                    }
                }
            }
            Tool::Select => {
                if response.double_clicked() {
                    self.fit();
                } else if clicked && let Some(at) = at {
                    match handles::handle_at(&self.tools.handle_list, &map, at) {
                        Some(h) => {
                            let key = h.key.clone();
                            if modifiers.shift && self.tools.handles.selected.contains(&key) {
                                self.tools.handles.selected.remove(&key);
                            } else {
                                if !modifiers.shift {
                                    self.tools.handles.selected.clear();
                                }
                                self.tools.handles.selected.insert(key.clone());
                            }
                            actions.push(ViewportAction::SelectNode(key.node));
                        }
                        None => {
                            if !modifiers.shift {
                                self.tools.handles.selected.clear();
                            }
                            self.tools.picked = pick::pick(&self.drawn.picks, &map, at);
                            if let Some(hit) = &self.tools.picked {
                                actions.push(ViewportAction::SelectNode(
                                    self.drawn.picks.meshes[hit.mesh()].node.clone(),
                                ));
                            }
                        }
                    }
                }
                // Hover: what is under the pointer (recomputed when it moves).
                self.tools.handles.hovered = hover
                    .and_then(|p| handles::handle_at(&self.tools.handle_list, &map, p))
                    .map(|h| h.key.clone());
                let busy = ui.input(|i| i.pointer.any_down());
                if busy || self.tools.handles.hovered.is_some() {
                    self.tools.hover = None;
                    self.tools.hover_at = None;
                } else if hover != self.tools.hover_at {
                    self.tools.hover_at = hover;
                    self.tools.hover = hover.and_then(|p| pick::pick(&self.drawn.picks, &map, p));
                }
            }
        }
    }

    /// The inspector of the one selected handle: its coordinates, typed or dragged.
    fn inspector(&mut self, ui: &mut Ui, rect: Rect, graph: &Graph) -> Option<Edit> {
        if self.tools.handles.selected.len() != 1 || self.tools.handles.dragging() {
            return None;
        }
        let key = self.tools.handles.selected.iter().next()?.clone();
        let handle = self
            .tools
            .handle_list
            .iter()
            .find(|h| h.key == key)?
            .clone();
        let area = Rect::from_min_size(
            rect.left_top() + egui::vec2(8.0, 44.0),
            egui::vec2(330.0, 26.0),
        );
        let mut p = handle.position;
        let speed = self.last_frame.spacing.minor / 10.0;
        let mut changed = false;
        ui.scope_builder(egui::UiBuilder::new().max_rect(area), |ui| {
            egui::Frame::popup(ui.style()).show(ui, |ui| {
                ui.horizontal(|ui| {
                    // A handle of a list of points is named with its index.
                    let listed = graph.node(&key.node).is_some_and(|n| {
                        n.def.inputs.iter().any(|p| {
                            p.widget() == cnets_engine::Widget::PointHandles
                                && p.access != cnets_engine::Access::Item
                        })
                    });
                    let name = if listed {
                        format!("{} [{}]", key.node, key.index)
                    } else {
                        key.node.clone()
                    };
                    ui.label(name);
                    for (axis, value) in [("x", &mut p.x), ("y", &mut p.y), ("z", &mut p.z)] {
                        ui.label(axis);
                        changed |= ui
                            .add(egui::DragValue::new(value).speed(speed).max_decimals(6))
                            .changed();
                    }
                });
            });
        });
        changed
            .then(|| handles::move_edit(graph, &[(key, p)]))
            .flatten()
    }

    /// Hands the scene and the guides to the GPU (or says there is no renderer).
    fn paint_scene(
        &mut self,
        ui: &mut Ui,
        gpu: Option<&GpuTarget>,
        rect: Rect,
        grid: Option<&Grid>,
    ) {
        let ppp = ui.ctx().pixels_per_point() * self.framing.render_scale;
        let size_px = [
            (rect.width() * ppp).round().max(1.0) as u32,
            (rect.height() * ppp).round().max(1.0) as u32,
        ];
        let key = (
            self.framing.camera,
            size_px,
            grid.is_some(),
            self.cplane(),
            Arc::as_ptr(&self.drawn.highlight) as usize,
        );
        if self.drawn.guides_key != Some(key) {
            let mut segments = grid.map(|g| g.segments.clone()).unwrap_or_default();
            segments.extend(self.drawn.highlight.iter().copied());
            self.drawn.guides = Guides {
                segments: Arc::new(segments),
                points: Arc::new(Vec::new()),
                version: self.drawn.guides.version + 1,
            };
            self.drawn.guides_key = Some(key);
        }
        match gpu {
            Some(target) => {
                ui.painter().add(egui_wgpu::Callback::new_paint_callback(
                    rect,
                    ViewportCallback {
                        scene: self.drawn.scene.clone(),
                        version: self.drawn.version,
                        guides: self.drawn.guides.clone(),
                        camera: self.framing.camera,
                        size_px,
                        target: *target,
                        pictures: self.drawn.pictures.clone(),
                    },
                ));
                self.drawn.handed_version = self.drawn.version;
            }
            None => {
                ui.painter().rect_filled(rect, 0.0, Color32::from_gray(60));
                ui.painter().text(
                    rect.center(),
                    egui::Align2::CENTER_CENTER,
                    "no wgpu renderer: the 3D view needs the wgpu backend",
                    egui::FontId::proportional(14.0),
                    Color32::WHITE,
                );
            }
        }
    }
}

/// The configuration class of a face in the paper's notation: the (±±) configurations of its two
/// construction planes (CNets, Fig. 4).
pub fn paper_class(class: cnets_geometry::fabrication::FaceClass) -> &'static str {
    crate::preview::paper_class(class)
}
