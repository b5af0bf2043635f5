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
//! The overlay ([`overlay`]) shows counts, the legend with its fold entry, and the size of the
//! previewed geometry. The same code runs in the web build. Keys and mouse: docs/editor/3d-view.md,
//! "Drawing and editing in the 3D view".

pub mod colors;
pub mod cplane;
pub mod cplane_make;
pub mod cut_plane;
pub mod distance;
pub mod draw;
pub mod gpu;
pub mod grid;
pub mod handles;
pub mod measure;
pub mod navigation;
pub mod net_drag;
pub mod overlay;
pub mod pick;
pub mod screen;

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

use cnets_engine::{Graph, NodeInstance};
use cnets_geometry::DVec3;
use cnets_render::{Bounds, Camera, Color, Scene, Segment, View};
use eframe::egui_wgpu;
use egui::{Color32, Key, Modifiers, PointerButton, Pos2, Rect, Sense, Ui};

use crate::edit::Edit;
use crate::preview::{Picks, PreviewOptions, PreviewStats};

pub use cplane::CPlane;
pub use cplane_make::ThreePointTool;
pub use draw::{DrawTool, DrawnCurve};
pub use gpu::GpuTarget;
use gpu::{Guides, ViewportCallback};
use grid::{Grid, Spacing};
use handles::{DragPlane, Handle, HandleTool};
pub use measure::MeasureTool;
pub use navigation::NamedView;
pub use net_drag::{NetDragTarget, NetDragTool, NetVertex};
use pick::Hit;
use screen::ScreenMap;

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

/// The viewport's state.
pub struct Viewport {
    /// The camera.
    pub camera: Camera,
    /// Display options (colour mode, layers).
    pub options: PreviewOptions,
    scene: Arc<Scene>,
    scene_version: u64,
    /// Figures of the current scene.
    pub stats: PreviewStats,
    picks: Arc<Picks>,
    /// The box of the drawn surfaces and curves (markers such as apices left out).
    bounds: Option<Bounds>,
    fit_pending: bool,
    /// The lower edge of the labels in the view's top corners (statistics, legend) in the last
    /// frame: what sits below is free (the web page's first-visit hint goes there).
    pub labels_bottom: f32,
    /// The distance mode found no reference and the status bar said so (said once).
    no_reference_said: bool,
    fitted_once: bool,
    aspect: f32,
    /// Scene versions handed to the GPU (one per frame at most): the app reads it to know when a
    /// change reached the picture.
    pub drawn_version: u64,
    /// Pictures rendered by the GPU (see [`Viewport::pictures_rendered`]).
    pictures: Arc<AtomicU64>,
    /// egui time of the last change of scene or camera.
    last_change: f64,
    /// Resolution factor of the last frame (1 or [`INTERACTIVE_SCALE`]).
    pub render_scale: f32,
    /// Where the view was drawn in the last frame (screen points).
    pub rect: egui::Rect,
    /// The figures drawn over the view in the last frame, by name (statistics, legend, distance
    /// picker, axes, size, grid): they never overlap (tests read them).
    pub overlays: Vec<(&'static str, Rect)>,
    /// The named view shown.
    pub view: NamedView,
    /// The Perspective view's construction plane.
    pub perspective_plane: CPlane,
    /// Its name (`World XY`, `CPlane 1`: the grid's corner says it).
    pub perspective_name: String,
    /// The mesh hit of the last click with the Select tool (a net's row to fit a plane through).
    pub picked: Option<Hit>,
    /// Grid snap (F9; Alt suspends it while held).
    pub snap: bool,
    /// The grid and axes are drawn (F7).
    pub show_grid: bool,
    /// The size of the previewed geometry is shown (W × D × H).
    pub show_dimensions: bool,
    /// Only the selected nodes' previews are drawn (Grasshopper's *Only draw selected*; with
    /// nothing selected, every previewed node).
    pub only_selected: bool,
    /// The active tool.
    pub tool: Tool,
    /// Handle selection and drags.
    pub handles: HandleTool,
    /// The handles of the last frame.
    handle_list: Vec<Handle>,
    /// What the pointer was over in the last frame.
    pub hover: Option<Hit>,
    hover_at: Option<Pos2>,
    /// Where a tool would put a point under the pointer (snapped).
    tool_point: Option<DVec3>,
    /// The folded faces are outlined (the legend's fold entry).
    pub folds_shown: bool,
    highlight: Arc<Vec<Segment>>,
    guides: Guides,
    guides_key: Option<(Camera, [u32; 2], bool, CPlane, usize)>,
    /// The grid spacing of the last frame (the snap step).
    pub spacing: Spacing,
    /// The legend's fold entry in the last frame (screen).
    pub fold_entry: Option<Rect>,
    /// The cuts of the selected nodes drawn in the last frame (plane and kept side).
    cut_overlays: Vec<cut_plane::CutOverlay>,
}

impl Default for Viewport {
    fn default() -> Self {
        Self {
            camera: Camera::new(View::Iso),
            options: PreviewOptions::default(),
            scene: Arc::new(Scene::new()),
            scene_version: 0,
            stats: PreviewStats::default(),
            picks: Arc::new(Picks::default()),
            bounds: None,
            fit_pending: false,
            labels_bottom: 0.0,
            no_reference_said: false,
            fitted_once: false,
            aspect: 1.0,
            drawn_version: 0,
            pictures: Arc::default(),
            last_change: f64::NEG_INFINITY,
            render_scale: 1.0,
            rect: egui::Rect::NOTHING,
            overlays: Vec::new(),
            view: NamedView::Perspective,
            perspective_plane: CPlane::XY,
            perspective_name: CPlane::XY.label().to_string(),
            picked: None,
            snap: true,
            show_grid: true,
            show_dimensions: true,
            only_selected: false,
            tool: Tool::Select,
            handles: HandleTool::default(),
            handle_list: Vec::new(),
            hover: None,
            hover_at: None,
            tool_point: None,
            folds_shown: false,
            highlight: Arc::new(Vec::new()),
            guides: Guides::default(),
            guides_key: None,
            spacing: Spacing {
                minor: 1.0,
                major: 5.0,
            },
            fold_entry: None,
            cut_overlays: Vec::new(),
        }
    }
}

/// The box of a scene's surfaces and curves (point markers such as apices can lie far away; the
/// flat fabrication layer drawn beside the design is not part of it).
fn drawn_bounds(scene: &Scene) -> Option<Bounds> {
    let faces = scene
        .face_vertices()
        .iter()
        .map(|v| glam::Vec3::from(v.position));
    let lines = scene
        .segments()
        .iter()
        .filter(|s| s.flags & cnets_render::FLAG_BESIDE == 0)
        .flat_map(|s| [glam::Vec3::from(s.a), glam::Vec3::from(s.b)]);
    Bounds::from_points(faces.chain(lines).filter(|p| p.is_finite()))
}

/// The colour of fold outlines.
const FOLD_OUTLINE: Color = Color::rgb(0xff, 0x6a, 0x00);

impl Viewport {
    /// Replaces the scene (from a finished evaluation) and what was drawn in it.
    pub fn set_scene(&mut self, scene: Arc<Scene>, stats: PreviewStats, picks: Arc<Picks>) {
        self.bounds = drawn_bounds(&scene);
        self.scene = scene;
        self.stats = stats;
        self.picks = picks;
        self.scene_version += 1;
        self.last_change = f64::NAN; // stamped with egui's time in the next `show`
        self.hover = None;
        self.hover_at = None;
        if self.folds_shown {
            self.highlight = Arc::new(self.fold_outlines());
        }
        if !self.fitted_once && !self.scene.is_empty() {
            self.fit_pending = true;
        }
    }

    /// Clears the scene for a new document (the next geometry is framed again).
    pub fn reset(&mut self) {
        self.set_scene(
            Arc::new(Scene::new()),
            PreviewStats::default(),
            Arc::new(Picks::default()),
        );
        self.fitted_once = false;
        self.folds_shown = false;
        self.highlight = Arc::new(Vec::new());
        self.handles = HandleTool::default();
        self.tool = Tool::Select;
        self.picked = None;
    }

    /// How many pictures the GPU has rendered into the view's texture so far. A frame in which
    /// the scene, guides, camera and size are unchanged only blits the last one and is not
    /// counted (panning the canvas, typing in a field).
    pub fn pictures_rendered(&self) -> u64 {
        self.pictures.load(Ordering::Relaxed)
    }

    /// The scene shown.
    pub fn scene(&self) -> &Arc<Scene> {
        &self.scene
    }

    /// What the scene drew, by node.
    pub fn picks(&self) -> &Arc<Picks> {
        &self.picks
    }

    /// The figures and legend of the scene shown.
    pub fn stats(&self) -> &PreviewStats {
        &self.stats
    }

    /// Version of the scene (bumped by [`Viewport::set_scene`]).
    pub fn scene_version(&self) -> u64 {
        self.scene_version
    }

    /// The box of the previewed surfaces and curves (W × D × H).
    pub fn bounds(&self) -> Option<Bounds> {
        self.bounds
    }

    /// The cuts of the selected nodes drawn in the last frame: their planes and kept sides.
    pub fn cut_overlays(&self) -> &[cut_plane::CutOverlay] {
        &self.cut_overlays
    }

    /// The handles shown in the last frame.
    pub fn handle_list(&self) -> &[Handle] {
        &self.handle_list
    }

    /// The screen mapping of the last frame.
    pub fn screen_map(&self) -> ScreenMap {
        ScreenMap {
            rect: self.rect,
            camera: self.camera,
        }
    }

    /// The construction plane of the view shown.
    pub fn cplane(&self) -> CPlane {
        self.view.cplane(self.perspective_plane)
    }

    /// The name of the construction plane of the view shown.
    pub fn cplane_name(&self) -> String {
        match self.view {
            NamedView::Perspective => self.perspective_name.clone(),
            v => v.cplane(self.perspective_plane).label().to_string(),
        }
    }

    /// Makes `plane`, called `name`, the Perspective view's construction plane.
    pub fn set_perspective_plane(&mut self, plane: CPlane, name: &str) {
        self.perspective_plane = plane;
        self.perspective_name = name.to_string();
    }

    /// The construction plane fitted through the row of the net last clicked (when its node is
    /// selected) or the previewed curve of a selected node, and what it went through; an error
    /// saying what to select.
    pub fn fit_cplane(&self, selected: &[String]) -> Result<(CPlane, String), String> {
        let (points, what) = cplane_make::fit_points(&self.picks, self.picked.as_ref(), selected)?;
        let plane = CPlane::fit(&points).map_err(|e| format!("CPlane through {what}: {e}"))?;
        Ok((plane, what))
    }

    /// Where the last solve of a net drag left the grabbed vertex and its distance to the target
    /// (drawn as a line to the target when it stopped short).
    pub fn set_net_reached(&mut self, reached: DVec3, distance_left: f64) {
        if let Tool::DragNet(d) = &mut self.tool {
            d.reached = Some((reached, distance_left));
        }
    }

    /// Frames everything on the next frame (the F key).
    pub fn fit(&mut self) {
        self.fit_pending = true;
    }

    /// Shows a named view, framing the previewed geometry.
    pub fn set_view(&mut self, view: NamedView) {
        self.view = view;
        navigation::turn_to(&mut self.camera, view);
        self.fit();
    }

    /// Points the camera at the surfaces (apices and other markers can lie far away, even near
    /// infinity, and would shrink the mesh to a dot), or at everything when there are none; with
    /// nothing at all, at 20 m around the origin. Handles are included.
    fn frame_geometry(&mut self) {
        let mut points: Vec<glam::Vec3> = self
            .scene
            .face_vertices()
            .iter()
            .map(|v| glam::Vec3::from(v.position))
            .collect();
        if points.is_empty() {
            points.extend(self.scene.positions());
        }
        points.extend(self.handle_list.iter().map(|h| h.position.as_vec3()));
        if points.is_empty() {
            let b = Bounds::new(
                glam::Vec3::new(-10.0, -10.0, 0.0),
                glam::Vec3::new(10.0, 10.0, 0.0),
            );
            points.extend(b.corners());
        }
        self.camera.fit_points(&points, self.aspect);
        self.clear_labels();
    }

    /// Zooms out after a fit so the geometry clears the labels along the view's top (the
    /// statistics) and bottom (grid, axes, W × D × H): [`LABEL_BAND`] points each.
    fn clear_labels(&mut self) {
        let height = self.rect.height();
        let bands = 2.0 * LABEL_BAND;
        if height.is_finite() && height > 3.0 * bands {
            self.camera.zoom(height / (height - bands));
        }
    }

    /// Frames the geometry of the nodes `ids` (their previewed meshes and curves, their handles)
    /// and the selected handles; everything when there is none.
    pub fn frame_selection(&mut self, ids: &[String]) {
        let picks = self.picks.clone();
        let mut points: Vec<glam::Vec3> = Vec::new();
        for m in picks.meshes.iter().filter(|m| ids.contains(&m.node)) {
            points.extend(m.geometry.vertices().iter().map(|p| p.as_vec3()));
        }
        for c in picks.curves.iter().filter(|c| ids.contains(&c.node)) {
            points.extend(c.polyline.points.iter().map(|p| p.as_vec3()));
        }
        for h in &self.handle_list {
            if ids.contains(&h.key.node) || self.handles.selected.contains(&h.key) {
                points.push(h.position.as_vec3());
            }
        }
        if points.is_empty() {
            self.fit();
        } else {
            self.camera.fit_points(&points, self.aspect);
            self.clear_labels();
        }
    }

    /// Outlines of the faces that are not (++)(++), drawn on top.
    fn fold_outlines(&self) -> Vec<Segment> {
        let f = |p: DVec3| [p.x as f32, p.y as f32, p.z as f32];
        let mut segments = Vec::new();
        for (m, face) in self.picks.folded_faces() {
            let corners = self.picks.meshes[m].geometry.face_corners(face);
            for k in 0..corners.len() {
                segments.push(Segment {
                    a: f(corners[k]),
                    b: f(corners[(k + 1) % corners.len()]),
                    color: FOLD_OUTLINE,
                    width: 2.5,
                    flags: cnets_render::scene::FLAG_ON_TOP,
                });
            }
        }
        segments
    }

    /// The legend's fold entry: frames the faces that are not (++)(++) and outlines them.
    pub fn show_folds(&mut self) {
        let picks = self.picks.clone();
        let corners: Vec<glam::Vec3> = picks
            .folded_faces()
            .into_iter()
            .flat_map(|(m, f)| picks.meshes[m].geometry.face_corners(f))
            .map(|p| p.as_vec3())
            .collect();
        if corners.is_empty() {
            return;
        }
        self.camera.fit_points(&corners, self.aspect);
        self.folds_shown = true;
        self.highlight = Arc::new(self.fold_outlines());
    }

    /// The outline segments drawn for the folds (empty unless shown).
    pub fn highlight(&self) -> &[Segment] {
        &self.highlight
    }

    /// The snap step, or none while snapping is off or Alt is held.
    fn snap_step(&self, modifiers: Modifiers) -> Option<f64> {
        (self.snap && !modifiers.alt).then_some(self.spacing.minor)
    }

    /// Where the pointer at `at` puts a point on the construction plane, snapped to the grid.
    pub fn plane_point(&self, map: &ScreenMap, at: Pos2, modifiers: Modifiers) -> Option<DVec3> {
        let plane = self.cplane();
        let hit = plane.world().hit(&map.ray(at))?;
        Some(match self.snap_step(modifiers) {
            Some(step) => plane.snap(hit, step),
            // Unsnapped: a hundredth of the grid step is resolution enough.
            None => plane.snap(hit, self.spacing.minor / 100.0),
        })
    }

    /// Where a measured point at `at` lands: the nearest drawn vertex or handle within
    /// [`SNAP_RADIUS`], else the construction plane.
    fn measure_point(&self, map: &ScreenMap, at: Pos2, modifiers: Modifiers) -> Option<DVec3> {
        let handle = handles::handle_at(&self.handle_list, map, at).map(|h| h.position);
        handle
            .or_else(|| pick::nearest_vertex(&self.picks, map, at, SNAP_RADIUS))
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
                .selectable_label(self.view == v, label)
                .on_hover_text(format!("{} view ({})", v.label(), v.shortcut()))
                .clicked()
            {
                self.set_view(v);
            }
        }
        ui.separator();
        let drawing = matches!(self.tool, Tool::Draw(_));
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
        if let Tool::Draw(d) = &mut self.tool {
            // The kind of curve drawn, while the tool is active (P switches).
            ui.selectable_value(&mut d.polyline, false, "Spline")
                .on_hover_text("a smooth curve through the points (P switches)");
            ui.selectable_value(&mut d.polyline, true, "Polyline")
                .on_hover_text("straight segments between the points (P switches)");
        }
        let measuring = matches!(self.tool, Tool::Measure(_));
        if ui
            .selectable_label(measuring, "📏 Measure")
            .on_hover_text("click two points (snapping to vertices) for their distance (M)")
            .clicked()
        {
            self.toggle_tool(Tool::Measure(MeasureTool::default()));
        }
        let dragging_net = matches!(self.tool, Tool::DragNet(_));
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
        ui.toggle_value(&mut self.snap, "Snap")
            .on_hover_text("grid snap (F9); hold Alt to suspend it");
        ui.toggle_value(&mut self.show_dimensions, "W×D×H")
            .on_hover_text("the size of the previewed geometry in the view's corner");
    }

    /// Switches to `tool`, or back to Select when it is the active one.
    pub fn toggle_tool(&mut self, tool: Tool) {
        let same = std::mem::discriminant(&self.tool) == std::mem::discriminant(&tool);
        self.tool = if same { Tool::Select } else { tool };
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
        let drawing = matches!(self.tool, Tool::Draw(_));
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
        if p && let Tool::Draw(d) = &mut self.tool {
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
            self.snap = !self.snap;
            actions.push(ViewportAction::Message(format!(
                "grid snap {}",
                if self.snap { "on" } else { "off" }
            )));
        }
        if f7 {
            self.show_grid = !self.show_grid;
        }
        if shift_f {
            self.frame_selection(input.selected);
        }
        match &mut self.tool {
            Tool::Draw(d) => {
                if enter && let Some(curve) = d.finish() {
                    actions.push(ViewportAction::AddCurve(curve));
                    // As a Rhino command ends with its curve.
                    self.tool = Tool::Select;
                    return;
                }
                if backspace {
                    d.undo_point();
                }
                if esc {
                    self.tool = Tool::Select;
                }
            }
            Tool::Measure(_) if esc => self.tool = Tool::Select,
            Tool::ThreePoint(t) => {
                if backspace {
                    t.points.pop();
                }
                if esc {
                    self.tool = Tool::Select;
                    actions.push(ViewportAction::Message(
                        "CPlane from 3 points cancelled".into(),
                    ));
                }
            }
            Tool::DragNet(d) if esc => {
                if d.pins.is_empty() {
                    self.tool = Tool::Select;
                } else {
                    d.pins.clear();
                    actions.push(ViewportAction::Message("pins cleared".into()));
                }
            }
            _ if esc => {
                self.handles.selected.clear();
                self.folds_shown = false;
                self.highlight = Arc::new(Vec::new());
            }
            _ => {}
        }
        // Arrow keys nudge the selected handles one grid step in the view's plane (Page Up /
        // Page Down along its normal).
        if !self.handles.selected.is_empty() {
            let (u, v, n) = self.cplane().axes();
            let step = self.spacing.minor;
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
                && let Some(edit) = self.handles.nudge(input.graph, &self.handle_list, delta)
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
        self.rect = rect;
        self.aspect = rect.width().max(1.0) / rect.height().max(1.0);
        let shown = |n: &NodeInstance| (n.preview && n.enabled) || input.selected.contains(&n.id);
        self.handle_list = handles::collect(input.graph, shown);
        self.handles.retain_existing(&self.handle_list);
        if self.fit_pending {
            self.frame_geometry();
            self.fit_pending = false;
            self.fitted_once = !self.scene.is_empty();
        }
        self.spacing = Spacing::for_scale(self.screen_map().world_per_point());
        let camera_before = self.camera;
        self.keys(ui.ctx(), input, &mut actions);
        self.pointer(ui, &response, input, &mut actions);
        let now = ui.input(|i| i.time);
        if self.camera != camera_before || self.last_change.is_nan() {
            self.last_change = now;
        }
        let changing = now - self.last_change < SETTLE_SECONDS;
        self.render_scale = if changing && gpu.is_some_and(|g| g.software) {
            // Come back for the full-resolution picture once things settle.
            ui.ctx()
                .request_repaint_after(std::time::Duration::from_secs_f64(SETTLE_SECONDS));
            INTERACTIVE_SCALE
        } else {
            1.0
        };
        let map = self.screen_map();
        let grid = self.show_grid.then(|| {
            // The perspective view's grid is sized to the geometry shown (the named views are
            // drafting paper: their grid fills the view).
            let around = match self.view {
                NamedView::Perspective => self.bounds.as_ref(),
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
        self.handles
            .paint(&painter, &self.handle_list, &map, pointer);
        // A selected cut's plane and the side it keeps, about half the design's size.
        self.cut_overlays = cut_plane::selected_cuts(input.graph, input.selected);
        let half = self
            .bounds
            .map_or(5.0, |b| 0.35 * f64::from((b.max - b.min).length()))
            .max(0.5);
        cut_plane::paint(&painter, &map, &self.cut_overlays, half);
        match &self.tool {
            Tool::Draw(d) => d.paint(&painter, &map, self.tool_point),
            Tool::Measure(m) => m.paint(&painter, &map, self.tool_point),
            Tool::DragNet(d) => d.paint(&painter, &map, self.tool_point),
            Tool::ThreePoint(t) => t.paint(&painter, &map, self.tool_point),
            Tool::Select => {}
        }
        // The figures wrap short of the legend's column.
        let stats_width = rect.width() - overlay::LEGEND_WIDTH - 28.0;
        let stats = overlay::paint_stats(ui, rect, &self.stats, stats_width);
        let folds = self.picks.folded_faces().len();
        let legend = overlay::legend(ui, rect, stats, &self.stats, folds);
        self.fold_entry = legend.fold_entry;
        self.labels_bottom = legend.bottom.max(stats.bottom());
        // Colour by distance: which mesh the others are measured against, and which side is
        // coloured.
        if let Some(message) =
            distance::ensure_reference(&mut self.options, input.graph, &mut self.no_reference_said)
        {
            actions.push(ViewportAction::Message(message));
        }
        let picker = distance::picker(
            ui,
            rect,
            legend.bottom,
            stats,
            &mut self.options,
            input.graph,
        );
        self.labels_bottom = self.labels_bottom.max(picker.bottom());
        let dimensions = if self.show_dimensions {
            overlay::paint_dimensions(ui, rect, self.bounds.as_ref())
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
        self.overlays = [
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
        if let (Tool::Select, Some(hit), Some(at)) = (&self.tool, &self.hover, pointer)
            && !self.handles.dragging()
        {
            let text = pick::describe(&self.picks, hit, input.graph);
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

    /// A two-finger gesture: zooms by `zoom` (> 1: the fingers spread, in) about `centre` and
    /// pans by the fingers' common move `moved` (screen points).
    pub fn pinch(&mut self, zoom: f32, moved: egui::Vec2, centre: egui::Pos2) {
        if zoom.is_finite() && zoom > 0.0 && (zoom - 1.0).abs() > 1e-6 {
            let r = self.rect;
            let ndc_x = 2.0 * (centre.x - r.left()) / r.width().max(1.0) - 1.0;
            let ndc_y = 1.0 - 2.0 * (centre.y - r.top()) / r.height().max(1.0);
            self.camera.zoom_at(1.0 / zoom, ndc_x, ndc_y, self.aspect);
        }
        if moved != egui::Vec2::ZERO {
            self.camera.pan(moved.x, moved.y, self.rect.height());
        }
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
        if let Some(t) = touches.filter(|t| t.num_touches >= 2 && self.rect.contains(t.center_pos))
        {
            self.pinch(t.zoom_delta, t.translation_delta, t.center_pos);
            return;
        }
        let hover = hover.filter(|p| self.rect.contains(*p));
        let primary = response.dragged_by(PointerButton::Primary);
        let ortho = self.view.is_orthographic();
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
            match &mut self.tool {
                Tool::Select => {
                    let grabbed =
                        self.handles
                            .press(&self.handle_list, &map, p0, how, modifiers.shift);
                    if !grabbed && (ortho || modifiers.command) && !modifiers.shift {
                        self.handles.boxing = Some(p0);
                    }
                }
                Tool::DragNet(d) if !modifiers.shift => {
                    d.press(&self.picks, &map, p0, how);
                }
                _ => {}
            }
        }
        let net_dragging = matches!(&self.tool, Tool::DragNet(d) if d.dragging());
        if primary && net_dragging {
            if let Tool::DragNet(d) = &mut self.tool
                && let Some(at) = response.interact_pointer_pos()
                && let Some(target) = d.drag_to(&map, at)
            {
                actions.push(ViewportAction::DragNet(target));
            }
        } else if primary && self.handles.dragging() {
            if let Some(at) = response.interact_pointer_pos()
                && let Some(edit) =
                    self.handles
                        .drag_to(input.graph, &map, at, self.snap_step(modifiers))
            {
                actions.push(ViewportAction::Edit(edit));
            }
        } else if primary && self.handles.boxing.is_some() {
            // The box is painted with the handles.
        } else {
            let delta = response.drag_delta();
            let orbiting = (primary && !modifiers.shift && !ortho)
                || (response.dragged_by(PointerButton::Secondary) && modifiers.shift);
            if orbiting {
                if ortho {
                    // Orbiting leaves the named orthographic view for Perspective.
                    self.view = NamedView::Perspective;
                    self.camera.projection = cnets_render::Projection::Perspective;
                }
                navigation::orbit(&mut self.camera, delta);
            } else if response.dragged_by(PointerButton::Secondary)
                || response.dragged_by(PointerButton::Middle)
                || (primary && modifiers.shift)
            {
                self.camera.pan(delta.x, delta.y, self.rect.height());
            }
        }
        if response.drag_stopped() {
            if let Tool::DragNet(d) = &mut self.tool
                && d.dragging()
            {
                d.release();
                actions.push(ViewportAction::DragNetEnd);
            }
            self.handles.release();
            if self.handles.boxing.is_some()
                && let Some(at) = response.interact_pointer_pos().or(hover)
            {
                self.handles
                    .select_box(&self.handle_list, &map, at, modifiers.shift);
            }
            self.handles.boxing = None;
        }
        if response.hovered() && scroll != 0.0 {
            let at = hover.unwrap_or(self.rect.center());
            let mut m = map;
            navigation::wheel(&mut m, scroll, at);
            self.camera = m.camera;
        }
        let map = self.screen_map();
        // Where the tools would put a point under the pointer.
        self.tool_point = hover.and_then(|at| match &self.tool {
            Tool::Draw(_) => self.plane_point(&map, at, modifiers),
            Tool::Measure(_) | Tool::ThreePoint(_) => self.measure_point(&map, at, modifiers),
            Tool::DragNet(d) if !d.dragging() => {
                net_drag::vertex_at(&self.picks, &map, at).map(|v| v.position)
            }
            Tool::DragNet(_) | Tool::Select => None,
        });
        let clicked = response.clicked_by(PointerButton::Primary);
        let at = response.interact_pointer_pos().or(hover);
        match &mut self.tool {
            Tool::Draw(d) => {
                let finished = if response.double_clicked() {
                    d.finish()
                } else if clicked
                    && let Some(at) = at
                    && let Some(p) = self.tool_point
                    && let draw::Click::Finished(curve) = d.click(&map, at, p)
                {
                    Some(curve)
                } else {
                    None
                };
                if let Some(curve) = finished {
                    actions.push(ViewportAction::AddCurve(curve));
                    // As a Rhino command ends with its curve.
                    self.tool = Tool::Select;
                }
            }
            Tool::DragNet(d) => {
                if clicked
                    && modifiers.shift
                    && let Some(at) = at
                    && let Some(text) = d.toggle_pin(&self.picks, &map, at)
                {
                    actions.push(ViewportAction::Message(text));
                }
            }
            Tool::Measure(m) => {
                if clicked && let Some(p) = self.tool_point {
                    m.click(p);
                    if let Some(text) = m.text() {
                        actions.push(ViewportAction::Message(text));
                    }
                }
            }
            Tool::ThreePoint(t) => {
                if clicked && let Some(p) = self.tool_point {
                    match t.click(p) {
                        cplane_make::ThreePointClick::Added => {
                            actions.push(ViewportAction::Message(t.prompt().into()));
                        }
                        cplane_make::ThreePointClick::Made(plane) => {
                            actions.push(ViewportAction::AddCPlane(plane));
                            self.tool = Tool::Select;
                        }
                        cplane_make::ThreePointClick::Refused(why) => {
                            actions.push(ViewportAction::Message(why));
                        }
                    }
                }
            }
            Tool::Select => {
                if response.double_clicked() {
                    self.fit();
                } else if clicked && let Some(at) = at {
                    match handles::handle_at(&self.handle_list, &map, at) {
                        Some(h) => {
                            let key = h.key.clone();
                            if modifiers.shift && self.handles.selected.contains(&key) {
                                self.handles.selected.remove(&key);
                            } else {
                                if !modifiers.shift {
                                    self.handles.selected.clear();
                                }
                                self.handles.selected.insert(key.clone());
                            }
                            actions.push(ViewportAction::SelectNode(key.node));
                        }
                        None => {
                            if !modifiers.shift {
                                self.handles.selected.clear();
                            }
                            self.picked = pick::pick(&self.picks, &map, at);
                            if let Some(hit) = &self.picked {
                                actions.push(ViewportAction::SelectNode(
                                    self.picks.meshes[hit.mesh()].node.clone(),
                                ));
                            }
                        }
                    }
                }
                // Hover: what is under the pointer (recomputed when it moves).
                self.handles.hovered = hover
                    .and_then(|p| handles::handle_at(&self.handle_list, &map, p))
                    .map(|h| h.key.clone());
                let busy = ui.input(|i| i.pointer.any_down());
                if busy || self.handles.hovered.is_some() {
                    self.hover = None;
                    self.hover_at = None;
                } else if hover != self.hover_at {
                    self.hover_at = hover;
                    self.hover = hover.and_then(|p| pick::pick(&self.picks, &map, p));
                }
            }
        }
    }

    /// The inspector of the one selected handle: its coordinates, typed or dragged.
    fn inspector(&mut self, ui: &mut Ui, rect: Rect, graph: &Graph) -> Option<Edit> {
        if self.handles.selected.len() != 1 || self.handles.dragging() {
            return None;
        }
        let key = self.handles.selected.iter().next()?.clone();
        let handle = self.handle_list.iter().find(|h| h.key == key)?.clone();
        let area = Rect::from_min_size(
            rect.left_top() + egui::vec2(8.0, 44.0),
            egui::vec2(330.0, 26.0),
        );
        let mut p = handle.position;
        let speed = self.spacing.minor / 10.0;
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
        let ppp = ui.ctx().pixels_per_point() * self.render_scale;
        let size_px = [
            (rect.width() * ppp).round().max(1.0) as u32,
            (rect.height() * ppp).round().max(1.0) as u32,
        ];
        let key = (
            self.camera,
            size_px,
            grid.is_some(),
            self.cplane(),
            Arc::as_ptr(&self.highlight) as usize,
        );
        if self.guides_key != Some(key) {
            let mut segments = grid.map(|g| g.segments.clone()).unwrap_or_default();
            segments.extend(self.highlight.iter().copied());
            self.guides = Guides {
                segments: Arc::new(segments),
                points: Arc::new(Vec::new()),
                version: self.guides.version + 1,
            };
            self.guides_key = Some(key);
        }
        match gpu {
            Some(target) => {
                ui.painter().add(egui_wgpu::Callback::new_paint_callback(
                    rect,
                    ViewportCallback {
                        scene: self.scene.clone(),
                        version: self.scene_version,
                        guides: self.guides.clone(),
                        camera: self.camera,
                        size_px,
                        target: *target,
                        pictures: self.pictures.clone(),
                    },
                ));
                self.drawn_version = self.scene_version;
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
