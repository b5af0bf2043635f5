//! The node canvas: an egui-snarl view of the graph document.
//!
//! The engine [`Graph`] is the source of truth. Before each frame [`Canvas::sync`] makes the snarl
//! mirror it (nodes, positions, wires); while the snarl is shown, the [`Viewer`] turns the
//! designer's gestures into [`CanvasAction`]s instead of changing anything itself; the app applies
//! them to the document as validated, undoable edits ([`apply`]), so a refused wire (incompatible
//! types, a cycle) never appears. Positions moved on the canvas are written back to the graph.
//!
//! Selection follows egui-snarl: Shift+click adds a node, Shift+drag on the background selects a
//! box, Ctrl+click removes a node. A plain click makes a node the *focused* node, which the
//! commands (Delete, duplicate, copy) use when nothing is selected.

use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::Rc;

use cnets_engine::cluster::Cluster;
use cnets_engine::optimize::ValuePath;
use cnets_engine::{Access, Graph, NodeFlag, PortDef, Value, ValueType};
use egui::emath::TSTransform;
use egui::{Color32, Pos2, Rect, Stroke, Ui};
use egui_snarl::ui::{
    PinInfo, PinShape, PinWireInfo, SnarlPin, SnarlStyle, SnarlViewer, SnarlWidget,
};
use egui_snarl::{InPin, InPinId, NodeId, OutPin, OutPinId, Snarl};
use rustc_hash::{FxHashMap, FxHashSet};

use crate::edit::Edit;
use crate::request::UiRequest;
use crate::worker::{NodeStatus, PANEL_TYPE};
use crate::{list_editor, mapper, widgets};

/// A node on the canvas: the id of the graph node it shows.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CanvasNode {
    /// Graph node id.
    pub id: String,
}

/// What a gesture on the canvas asks for: a change of the document or of the interface only.
#[derive(Clone, Debug, PartialEq)]
pub enum CanvasAction {
    /// Change the document (one undo step; [`crate::edit::apply`]).
    Edit(Edit),
    /// Change only the interface (the app carries it out).
    Request(UiRequest),
}

impl From<Edit> for CanvasAction {
    fn from(edit: Edit) -> Self {
        Self::Edit(edit)
    }
}

impl From<UiRequest> for CanvasAction {
    fn from(request: UiRequest) -> Self {
        Self::Request(request)
    }
}

/// Where a pin is, for tests that drag wires: (node id, is input, port index).
pub type PinKey = (String, bool, usize);

/// The canvas: the snarl mirror of the graph and what the last frame learned about it.
pub struct Canvas {
    snarl: Snarl<CanvasNode>,
    ids: FxHashMap<String, NodeId>,
    /// A fingerprint of the graph's wires when the snarl's wires were last made to match them
    /// ([`Canvas::sync`] diffs the wires only when it changed).
    wires_synced: Option<u64>,
    /// Graph-to-screen transform of the last frame.
    to_global: TSTransform,
    /// Pin centres in canvas coordinates, recorded while drawing (nodes out of view keep theirs).
    pins: Rc<RefCell<FxHashMap<PinKey, Pos2>>>,
    /// Node rectangles in canvas coordinates.
    rects: FxHashMap<String, Rect>,
    /// Each node's position when its rectangle was measured (nodes out of view are not laid out:
    /// their rectangle moves with them).
    drawn_at: FxHashMap<String, [f32; 2]>,
    /// Nodes laid out in the last frame (those in or near the view).
    laid_out: usize,
    /// The node last clicked.
    pub focused: Option<String>,
    /// Nodes selected (Shift+click, box selection, or [`Canvas::select`]) in the last frame.
    pub selected: Vec<String>,
    /// Nodes selected from outside the canvas (a curve drawn in the 3D view, internalised
    /// points): selected until the designer's canvas selection changes.
    chosen: Vec<String>,
    /// The canvas's own selection in the last frame.
    own_selection: Vec<String>,
    widget: SnarlWidget,
    /// Frame the whole graph once its nodes have been measured (after a new document).
    fit_pending: bool,
    /// Frames to wait before framing (the nodes grow when their first results arrive).
    fit_delay: u8,
    /// The pending framing shows the whole graph (down to [`MIN_ZOOM`]: Home, View › Frame
    /// graph, after Arrange) rather than opening it at a readable zoom ([`readable_zoom`]).
    fit_whole: bool,
    /// Screen rectangle of the canvas in the last frame.
    ui_rect: Rect,
    /// Plot rectangles of graph-mapper widgets (canvas coordinates).
    plots: HashMap<String, Rect>,
    /// What each graph-mapper widget showed in the last frame, and the row drawn.
    mapper_views: HashMap<String, (mapper::Shown, usize)>,
    /// Rectangles of the inline value editors, by (node, input) (canvas coordinates).
    editors: HashMap<(String, String), Rect>,
    /// What literal lists show on their nodes, kept while the lists stay the same.
    list_views: list_editor::OnNodeCache,
    /// Readout rectangles of `view.panel` nodes (canvas coordinates).
    panels: HashMap<String, Rect>,
    /// A zoom asked for with [`Canvas::zoom_to`], applied on the next frame.
    zoom_pending: Option<(f32, Option<Pos2>)>,
}

impl Default for Canvas {
    fn default() -> Self {
        Self::new()
    }
}

/// The smallest canvas zoom. Text on the canvas is laid out at its normal size and its glyph
/// quads are scaled with the canvas (egui transform layer); a quad less than one pixel tall can
/// fall between pixel centres and not be drawn at all — which is how the minus sign of `-1`
/// (Ubuntu Light's hyphen is the thinnest glyph the canvas draws: a 2-pixel-tall bitmap at
/// 14 px) disappeared at some zoom levels while the digits stayed. At this zoom and above every
/// glyph quad is at least one pixel tall (`tests/glyphs.rs` checks it for the fonts in use).
pub const MIN_ZOOM: f32 = 0.5;

/// The smallest height, in screen pixels, of node text when a graph opens.
pub const MIN_TEXT_PX: f32 = 10.0;

/// The zoom a graph opens at when it does not fit: the smallest text the nodes use (egui's
/// body, button and monospace styles — 13 points by default) at [`MIN_TEXT_PX`] on screen
/// (a little above, so that rounding never brings it below).
pub fn readable_zoom(style: &egui::Style) -> f32 {
    let smallest = [
        egui::TextStyle::Body,
        egui::TextStyle::Button,
        egui::TextStyle::Monospace,
    ]
    .iter()
    .filter_map(|t| style.text_styles.get(t).map(|f| f.size))
    .fold(f32::INFINITY, f32::min);
    let smallest = if smallest.is_finite() && smallest > 0.0 {
        smallest
    } else {
        13.0
    };
    (MIN_TEXT_PX * 1.001 / smallest).clamp(MIN_ZOOM, 2.0)
}

/// The snarl style of the canvas.
fn style() -> SnarlStyle {
    let mut s = SnarlStyle::new();
    s.min_scale = Some(MIN_ZOOM);
    s.max_scale = Some(2.0);
    s.centering = Some(false);
    s.collapsible = Some(true);
    s.pin_size = Some(9.0);
    s.wire_width = Some(2.0);
    s.select_rect_contained = Some(false);
    s.bg_pattern = Some(egui_snarl::ui::BackgroundPattern::grid(
        egui::vec2(40.0, 40.0),
        0.0,
    ));
    s
}

impl Canvas {
    /// An empty canvas.
    pub fn new() -> Self {
        Self::with_id(egui::Id::new("cnets-canvas"))
    }

    /// An empty canvas whose view state (selection, node order, zoom) is kept under its own
    /// id, e.g. one per graph level shown (an opened cluster must not inherit the selection of
    /// the graph around it).
    pub fn with_id(id: egui::Id) -> Self {
        Self {
            snarl: Snarl::new(),
            ids: FxHashMap::default(),
            wires_synced: None,
            to_global: TSTransform::IDENTITY,
            pins: Rc::default(),
            rects: FxHashMap::default(),
            drawn_at: FxHashMap::default(),
            laid_out: 0,
            focused: None,
            selected: Vec::new(),
            chosen: Vec::new(),
            own_selection: Vec::new(),
            widget: SnarlWidget::new().id(id).style(style()),
            fit_pending: true,
            fit_whole: false,
            fit_delay: 0,
            ui_rect: Rect::NOTHING,
            plots: HashMap::new(),
            mapper_views: HashMap::new(),
            editors: HashMap::new(),
            list_views: list_editor::OnNodeCache::default(),
            panels: HashMap::new(),
            zoom_pending: None,
        }
    }

    /// Frames the whole graph on the next frames, zooming out as far as [`MIN_ZOOM`] if needed
    /// (Home, View › Frame graph).
    pub fn fit(&mut self) {
        self.fit_pending = true;
        self.fit_whole = true;
    }

    /// Frames the graph as it opens, after six more frames (once nodes have their new sizes,
    /// e.g. when the first results of a newly shown graph arrive): the whole graph when it fits
    /// at a readable zoom, else its top-left corner at that zoom ([`Canvas::framing`]).
    pub fn fit_later(&mut self) {
        self.fit_pending = true;
        self.fit_whole = false;
        self.fit_delay = 6;
    }

    /// Positions of a layered layout of the graph ([`crate::layout::layered`]: sources left,
    /// sinks right, few crossings, no overlaps), using the node sizes measured in the last frame.
    /// Empty until every node has been drawn once.
    pub fn arrangement(&self, graph: &Graph) -> Vec<(String, [f32; 2])> {
        if self.rects.len() < graph.node_count() {
            return Vec::new();
        }
        // In file order (stable), with the measured sizes.
        let ids: Vec<String> = graph.nodes().map(|(_, n)| n.id.clone()).collect();
        let index: HashMap<&str, usize> = ids
            .iter()
            .enumerate()
            .map(|(k, id)| (id.as_str(), k))
            .collect();
        let sizes: Vec<[f32; 2]> = ids
            .iter()
            .map(|id| {
                self.rects
                    .get(id)
                    .map_or([200.0, 100.0], |r| [r.width(), r.height()])
            })
            .collect();
        let edges: Vec<(usize, usize)> = graph
            .wires()
            .iter()
            .filter_map(|w| Some((*index.get(w.from.as_str())?, *index.get(w.to.as_str())?)))
            .collect();
        let pos = crate::layout::layered(&sizes, &edges, [70.0, 36.0]);
        ids.into_iter().zip(pos).collect()
    }

    /// Whether all `count` nodes have been drawn (and measured) at least once.
    pub fn measured(&self, count: usize) -> bool {
        self.rects.len() >= count
    }

    /// Whether two nodes overlap on the canvas (measured in the last frame).
    pub fn has_overlaps(&self) -> bool {
        let rects: Vec<&Rect> = self.rects.values().collect();
        rects.iter().enumerate().any(|(i, a)| {
            rects[i + 1..]
                .iter()
                .any(|b| a.shrink(4.0).intersects(b.shrink(4.0)))
        })
    }

    /// Screen rectangle of the canvas in the last frame.
    pub fn screen_rect(&self) -> Rect {
        self.ui_rect
    }

    /// The transform that frames canvas rectangle `bb` in screen rectangle `ui`: the whole graph
    /// when it fits at a readable zoom (`readable` ..= 1, see [`readable_zoom`]), else its
    /// top-left corner (the sources) at the readable zoom; pan from there.
    pub fn framing(bb: Rect, ui: Rect, readable: f32) -> Option<TSTransform> {
        if !(bb.is_positive() && ui.is_positive()) {
            return None;
        }
        let readable = readable.min(1.0);
        let bb = bb.expand(30.0);
        let fits = (ui.width() / bb.width()).min(ui.height() / bb.height());
        let scale = fits.clamp(readable, 1.0);
        let translation = if fits >= readable {
            ui.center().to_vec2() - bb.center().to_vec2() * scale
        } else {
            // Centred along an axis that fits, the top-left corner otherwise.
            let x = if bb.width() * scale <= ui.width() {
                ui.center().x - bb.center().x * scale
            } else {
                ui.left() - bb.left() * scale
            };
            let y = if bb.height() * scale <= ui.height() {
                ui.center().y - bb.center().y * scale
            } else {
                ui.top() - bb.top() * scale
            };
            egui::vec2(x, y)
        };
        Some(TSTransform::new(translation, scale))
    }

    /// Sets the canvas zoom (clamped to [`MIN_ZOOM`] ..= 2) on the next frame, with the canvas
    /// point `around` at the centre of the view (`None`: the graph's top-left corner at the
    /// view's top-left).
    pub fn zoom_to(&mut self, zoom: f32, around: Option<Pos2>) {
        self.zoom_pending = Some((zoom.clamp(MIN_ZOOM, 2.0), around));
    }

    /// Makes the snarl mirror `graph`: adds and removes nodes, copies positions, diffs wires.
    /// Called every frame: without allocating when no node came or went and the wires are the
    /// same (a fingerprint of them), so a graph of thousands of nodes pays a lookup a node.
    pub fn sync(&mut self, graph: &Graph) {
        let (mut known, mut added) = (0, 0);
        let mut nodes_changed = false;
        for (_, node) in graph.nodes() {
            let pos = Pos2::new(node.position[0], node.position[1]);
            match self.ids.get(&node.id) {
                Some(&nid) => {
                    known += 1;
                    if let Some(info) = self.snarl.get_node_info_mut(nid) {
                        info.pos = pos;
                    }
                }
                None => {
                    let nid = self.snarl.insert_node(
                        pos,
                        CanvasNode {
                            id: node.id.clone(),
                        },
                    );
                    self.ids.insert(node.id.clone(), nid);
                    added += 1;
                    nodes_changed = true;
                }
            }
        }
        // Every id the canvas knows is either found above or gone from the graph.
        if self.ids.len() > known + added {
            let gone: Vec<String> = self
                .ids
                .keys()
                .filter(|id| graph.node(id).is_none())
                .cloned()
                .collect();
            for id in gone {
                if let Some(nid) = self.ids.remove(&id) {
                    self.snarl.remove_node(nid);
                }
            }
            nodes_changed = true;
        }
        let fingerprint = {
            use std::hash::{Hash, Hasher};
            // Order-independent: the sum of each wire's hash.
            graph
                .wire_ports()
                .map(|wire| {
                    let mut h = rustc_hash::FxHasher::default();
                    wire.hash(&mut h);
                    h.finish()
                })
                .fold(graph.wire_count() as u64, u64::wrapping_add)
        };
        if !nodes_changed && self.wires_synced == Some(fingerprint) {
            return;
        }
        self.wires_synced = Some(fingerprint);
        let mut wanted: FxHashSet<(OutPinId, InPinId)> = FxHashSet::default();
        for (from, output, to, input) in graph.wire_ports() {
            let (Some(&a), Some(&b)) = (self.ids.get(from), self.ids.get(to)) else {
                continue;
            };
            wanted.insert((OutPinId { node: a, output }, InPinId { node: b, input }));
        }
        let existing: Vec<(OutPinId, InPinId)> = self.snarl.wires().collect();
        for (o, i) in &existing {
            if !wanted.contains(&(*o, *i)) {
                self.snarl.disconnect(*o, *i);
            }
        }
        for (o, i) in wanted {
            self.snarl.connect(o, i);
        }
    }

    /// Number of nodes and wires on the canvas.
    pub fn counts(&self) -> (usize, usize) {
        (self.snarl.nodes().count(), self.snarl.wires().count())
    }

    /// Screen position of a pin after the last frame.
    pub fn pin_screen_pos(&self, node: &str, input: bool, port: usize) -> Option<Pos2> {
        let p = *self.pins.borrow().get(&(node.to_string(), input, port))?;
        Some(self.to_global * p)
    }

    /// Rectangle of a node in canvas coordinates, as measured in the last frame.
    pub fn node_rect(&self, node: &str) -> Option<Rect> {
        self.rects.get(node).copied()
    }

    /// The first place at or below `at` (canvas coordinates) where a box of `size` overlaps no
    /// node drawn in the last frame.
    pub fn free_spot(&self, at: Pos2, size: egui::Vec2) -> Pos2 {
        let mut p = at;
        for _ in 0..200 {
            let area = Rect::from_min_size(p, size).expand(10.0);
            match self
                .rects
                .values()
                .filter(|r| r.intersects(area))
                .map(|r| r.bottom())
                .reduce(f32::max)
            {
                Some(bottom) => p.y = bottom + 20.0,
                None => return p,
            }
        }
        p
    }

    /// The canvas rectangle around the nodes `ids` measured in the last frame.
    pub fn bounds_of(&self, ids: &[String]) -> Option<Rect> {
        ids.iter()
            .filter_map(|n| self.node_rect(n))
            .reduce(|a, b| a.union(b))
    }

    /// Screen rectangle of a node after the last frame.
    pub fn node_screen_rect(&self, node: &str) -> Option<Rect> {
        self.rects.get(node).map(|r| self.to_global * *r)
    }

    /// Screen position of point (u, v) of a graph mapper's unit square, after the last frame.
    pub fn mapper_screen_pos(&self, node: &str, u: f32, v: f32) -> Option<Pos2> {
        let r = self.plots.get(node)?;
        Some(self.to_global * Pos2::new(r.left() + u * r.width(), r.bottom() - v * r.height()))
    }

    /// What the graph-mapper widget of `node` showed in the last frame (kind and handle rows the
    /// node runs on) and the row it drew.
    pub fn mapper_view(&self, node: &str) -> Option<&(mapper::Shown, usize)> {
        self.mapper_views.get(node)
    }

    /// Screen rectangle of a `view.panel` node's readout after the last frame (its bottom-right
    /// corner is the resize handle).
    pub fn panel_screen_rect(&self, node: &str) -> Option<Rect> {
        self.panels.get(node).map(|r| self.to_global * *r)
    }

    /// How many nodes were laid out in the last frame: those in or near the view (the others
    /// keep their last rectangle and pin positions).
    pub fn laid_out(&self) -> usize {
        self.laid_out
    }

    /// The canvas zoom of the last frame (screen points per canvas point).
    pub fn zoom(&self) -> f32 {
        self.to_global.scaling
    }

    /// Screen rectangle of the inline editor of `node`'s `input` after the last frame (e.g. a
    /// `param.number` slider: the rail starts at its left edge, `slider_width` 110 points wide
    /// at zoom 1).
    pub fn editor_screen_rect(&self, node: &str, input: &str) -> Option<Rect> {
        self.editors
            .get(&(node.to_string(), input.to_string()))
            .map(|r| self.to_global * *r)
    }

    /// Screen position of a canvas point (accessibility rectangles of widgets on the canvas are
    /// in canvas coordinates).
    pub fn to_screen(&self, canvas: Pos2) -> Pos2 {
        self.to_global * canvas
    }

    /// Canvas position of a screen point.
    pub fn to_canvas(&self, screen: Pos2) -> Pos2 {
        self.to_global.inverse() * screen
    }

    /// Takes the rectangles of the nodes laid out this frame; the nodes out of view (not laid out:
    /// vendor/egui-snarl culls them) keep their rectangle and pins from the frame they were last
    /// drawn in, moved by as much as the node moved since. The pins of the drawn nodes were
    /// written over their old entries while drawing; the others are left where they are, so a
    /// graph of thousands of nodes pays a lookup a node, not a copy.
    fn carry_over(&mut self, graph: &Graph, drawn: HashMap<String, Rect>) {
        self.laid_out = drawn.len();
        let mut moved: Vec<(&str, egui::Vec2)> = Vec::new();
        for (id, r) in self.rects.iter_mut() {
            if drawn.contains_key(id) {
                continue;
            }
            if let Some(node) = graph.node(id)
                && let Some(at) = self.drawn_at.get_mut(id)
                && *at != node.position
            {
                let d = egui::vec2(node.position[0] - at[0], node.position[1] - at[1]);
                *r = r.translate(d);
                *at = node.position;
                moved.push((id.as_str(), d));
            }
        }
        if !moved.is_empty() {
            // Nodes moved while out of view (undo, Arrange): their pins move with them.
            let moved: FxHashMap<&str, egui::Vec2> = moved.into_iter().collect();
            for ((id, _, _), p) in self.pins.borrow_mut().iter_mut() {
                if let Some(d) = moved.get(id.as_str()) {
                    *p += *d;
                }
            }
        }
        for (id, r) in drawn {
            let position = graph.node(&id).map(|n| n.position);
            match self.drawn_at.get_mut(&id) {
                Some(at) => *at = position.unwrap_or(*at),
                None => {
                    if let Some(p) = position {
                        self.drawn_at.insert(id.clone(), p);
                    }
                }
            }
            self.rects.insert(id, r);
        }
        // Nodes removed from the graph are forgotten (looked for only when the count says some
        // were).
        if self.rects.len() > graph.node_count() {
            self.rects.retain(|id, _| graph.node(id).is_some());
            self.drawn_at.retain(|id, _| graph.node(id).is_some());
            self.pins
                .borrow_mut()
                .retain(|(id, _, _), _| graph.node(id).is_some());
        }
    }

    /// Selects `ids` (nodes made outside the canvas: a drawn curve, internalised points) until the
    /// designer selects something else on the canvas.
    pub fn select(&mut self, ids: Vec<String>) {
        self.selected = ids.clone();
        self.chosen = ids;
    }

    /// The nodes commands act on: the selection, else the focused node.
    pub fn targets(&self) -> Vec<String> {
        if self.selected.is_empty() {
            self.focused.iter().cloned().collect()
        } else {
            self.selected.clone()
        }
    }

    /// Shows the canvas; returns the actions of the designer.
    pub fn show(
        &mut self,
        ui: &mut Ui,
        graph: &Graph,
        statuses: &HashMap<String, NodeStatus>,
    ) -> Vec<CanvasAction> {
        self.sync(graph);
        self.ui_rect = ui.available_rect_before_wrap();
        // Frame the graph once every node has been measured in an earlier frame.
        let mut fit = None;
        if self.fit_delay > 0 {
            self.fit_delay -= 1;
        } else if self.fit_pending
            && !self.rects.is_empty()
            && self.rects.len() == graph.node_count()
        {
            let bb = self.rects.values().fold(Rect::NOTHING, |a, r| a.union(*r));
            let readable = if self.fit_whole {
                MIN_ZOOM
            } else {
                readable_zoom(ui.style())
            };
            fit = Self::framing(bb, self.ui_rect, readable);
            self.fit_pending = false;
        } else if self.fit_pending && graph.node_count() == 0 {
            self.fit_pending = false;
        }
        if let Some((z, around)) = self.zoom_pending.take() {
            let translation = match around {
                Some(p) => self.ui_rect.center().to_vec2() - p.to_vec2() * z,
                None => {
                    let bb = self.rects.values().fold(Rect::NOTHING, |a, r| a.union(*r));
                    let corner = if bb.is_positive() {
                        bb.min - egui::vec2(20.0, 20.0)
                    } else {
                        Pos2::ZERO
                    };
                    self.ui_rect.min.to_vec2() - corner.to_vec2() * z
                }
            };
            fit = Some(TSTransform::new(translation, z));
        }
        self.list_views.next_frame();
        let mut viewer = Viewer {
            graph,
            statuses,
            list_views: std::mem::take(&mut self.list_views),
            actions: Vec::new(),
            shift: ui.input(|i| i.modifiers.shift),
            pins: self.pins.clone(),
            to_global: self.to_global,
            rects: HashMap::new(),
            focused: self.focused.clone(),
            pressed_node: None,
            fit,
            plots: HashMap::new(),
            mapper_views: HashMap::new(),
            editors: HashMap::new(),
            panels: HashMap::new(),
            selected: self.selected.clone(),
            chosen: self.chosen.clone(),
        };
        let response = self.widget.show(&mut self.snarl, &mut viewer, ui);
        self.to_global = viewer.to_global;
        self.list_views = viewer.list_views;
        // Nodes out of view are not laid out (vendor/egui-snarl culls them): they keep the size
        // they had when last drawn, at their position now.
        self.carry_over(graph, viewer.rects);
        self.plots = viewer.plots;
        self.mapper_views = viewer.mapper_views;
        self.editors = viewer.editors;
        self.panels = viewer.panels;
        if let Some(id) = &viewer.pressed_node {
            self.focused = Some(id.clone());
        } else if response.clicked() && !response.double_clicked() {
            self.focused = None;
        }

        let mut actions = viewer.actions;
        for action in &mut actions {
            if let CanvasAction::Edit(Edit::MakeCluster { nodes, around }) = action
                && around.is_none()
            {
                *around = self.bounds_of(nodes);
            }
        }
        // The canvas response lives in the transformed layer: its pointer position is already in
        // canvas coordinates.
        if response.double_clicked()
            && let Some(p) = response.interact_pointer_pos()
        {
            actions.push(CanvasAction::Request(UiRequest::OpenPalette([p.x, p.y])));
        }
        let own: Vec<String> = self
            .widget
            .get_selected_nodes_at(ui.id(), ui.ctx())
            .into_iter()
            .filter_map(|nid| self.snarl.get_node(nid).map(|n| n.id.clone()))
            .collect();
        if own != self.own_selection || response.clicked() {
            // The designer selected on the canvas: that selection takes over.
            self.chosen.clear();
        }
        self.chosen.retain(|id| graph.node(id).is_some());
        self.own_selection = own.clone();
        self.selected = own;
        for id in &self.chosen {
            if !self.selected.contains(id) {
                self.selected.push(id.clone());
            }
        }
        // Positions moved by dragging, written back to the graph.
        let moves: Vec<(String, [f32; 2])> = self
            .snarl
            .nodes_pos()
            .filter_map(|(pos, n)| {
                let node = graph.node(&n.id)?;
                (node.position != [pos.x, pos.y]).then(|| (n.id.clone(), [pos.x, pos.y]))
            })
            .collect();
        if !moves.is_empty() {
            actions.push(CanvasAction::Edit(Edit::Move(moves)));
        }
        actions
    }
}

/// The readout of a `view.panel` node: its text (selectable, monospace, every line) in a
/// scrolling box the designer resizes by its bottom-right corner (the size is kept per node for
/// the session). Returns the box's rectangle.
fn panel_readout(ui: &mut Ui, id: &str, text: Option<&str>) -> Rect {
    let frame = egui::Frame::new()
        .fill(ui.visuals().extreme_bg_color)
        .inner_margin(egui::Margin::same(4));
    ui.scope(|ui| {
        egui::Resize::default()
            .id_salt(("cnets-panel", id))
            .default_size([220.0, 110.0])
            .min_size([90.0, 40.0])
            .max_size([1200.0, 1600.0])
            .show(ui, |ui| {
                frame.show(ui, |ui| {
                    egui::ScrollArea::both()
                        .id_salt(("cnets-panel-scroll", id))
                        .auto_shrink(false)
                        .show(ui, |ui| match text {
                            Some(t) => {
                                ui.add(
                                    egui::Label::new(egui::RichText::new(t).monospace())
                                        .selectable(true)
                                        .extend(),
                                );
                            }
                            None => {
                                ui.weak("(no value yet)");
                            }
                        });
                });
            });
    })
    .response
    .rect
}

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

fn pin_info(port: &PortDef) -> PinInfo {
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

/// The widest a port's name is drawn on a node, in points: longer names (a cluster's port can be
/// named anything) end in "…" and the hover gives the whole name. Every name of the node library
/// fits (the longest, `from_reference_max`, is about 115 points).
pub const PORT_NAME_WIDTH: f32 = 140.0;

/// A port's name as drawn on its node, cut to [`PORT_NAME_WIDTH`] at a character with "…", and
/// the hover's first line: the whole name when it was cut, else nothing.
fn fitted_port_name(ui: &Ui, name: &str) -> (String, String) {
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
    info: PinInfo,
    key: PinKey,
    sink: Rc<RefCell<FxHashMap<PinKey, Pos2>>>,
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

/// The snarl viewer: draws nodes from the graph and collects actions.
struct Viewer<'a> {
    graph: &'a Graph,
    statuses: &'a HashMap<String, NodeStatus>,
    /// The canvas's, lent for the frame.
    list_views: list_editor::OnNodeCache,
    actions: Vec<CanvasAction>,
    shift: bool,
    pins: Rc<RefCell<FxHashMap<PinKey, Pos2>>>,
    to_global: TSTransform,
    rects: HashMap<String, Rect>,
    focused: Option<String>,
    pressed_node: Option<String>,
    fit: Option<TSTransform>,
    plots: HashMap<String, Rect>,
    mapper_views: HashMap<String, (mapper::Shown, usize)>,
    editors: HashMap<(String, String), Rect>,
    panels: HashMap<String, Rect>,
    selected: Vec<String>,
    /// Nodes selected from outside the canvas (outlined here: the snarl does not know them).
    chosen: Vec<String>,
}

impl Viewer<'_> {
    fn names(
        &self,
        snarl: &Snarl<CanvasNode>,
        from: &OutPin,
        to: &InPin,
    ) -> Option<(String, String, String, String)> {
        let a = snarl.get_node(from.id.node)?;
        let b = snarl.get_node(to.id.node)?;
        let na = self.graph.node(&a.id)?;
        let nb = self.graph.node(&b.id)?;
        Some((
            a.id.clone(),
            na.def.outputs.get(from.id.output)?.name.to_string(),
            b.id.clone(),
            nb.def.inputs.get(to.id.input)?.name.to_string(),
        ))
    }

    /// "Rename port" in the context menu of a `graph.input` / `graph.output` node: a field with
    /// the port's name and a Rename button, which sets the node's `name` (one undo step; the
    /// cluster node keeps its wires on the renamed port, see [`crate::cluster_ports`]).
    fn rename_port_menu(&mut self, ui: &mut Ui, id: &str) {
        let current = match self.graph.node(id).and_then(|n| n.value_of("name")) {
            Some(Value::Text(t)) => t.to_string(),
            _ => String::new(),
        };
        let key = egui::Id::new(("rename-port", id));
        let mut name: String = ui.data_mut(|d| d.get_temp(key)).unwrap_or(current.clone());
        ui.label("Rename port");
        let field = ui.add(
            egui::TextEdit::singleline(&mut name)
                .desired_width(140.0)
                .id(key.with("field")),
        );
        let valid = crate::cluster_ports::valid_port_name(&name);
        if !valid {
            ui.weak("letters, digits and _ only");
        }
        let enter = field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
        let clicked = ui
            .add_enabled(valid && name != current, egui::Button::new("Rename"))
            .clicked();
        if valid && name != current && (clicked || enter) {
            self.actions.push(CanvasAction::Edit(Edit::SetValue {
                node: id.to_string(),
                input: "name".into(),
                value: Value::text(name.clone()),
            }));
            ui.data_mut(|d| d.remove::<String>(key));
            ui.close();
        } else {
            ui.data_mut(|d| d.insert_temp(key, name));
        }
    }

    /// "Name" in a node's context menu: a field with the node's name (its id when it has none)
    /// and a "Rename node" button (Enter too): one undo step, saved with the graph; an empty name shows
    /// the id again. The id itself never changes (wires, `--set` and scripts use it).
    fn rename_node_menu(&mut self, ui: &mut Ui, id: &str) {
        let Some(node) = self.graph.node(id) else {
            return;
        };
        let current = node.label().to_string();
        let key = egui::Id::new(("rename-node", id));
        let mut name: String = ui.data_mut(|d| d.get_temp(key)).unwrap_or(current.clone());
        ui.horizontal(|ui| {
            ui.label("Name");
            let field = ui.add(
                egui::TextEdit::singleline(&mut name)
                    .desired_width(140.0)
                    .hint_text(id)
                    .id(key.with("field")),
            );
            let enter = field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
            let changed = name.trim() != current;
            let clicked = ui
                .add_enabled(changed, egui::Button::new("Rename node"))
                .on_hover_text(
                    "the name shown on the canvas, in the parameter panel and the 3D view (the \
                     id stays: wires and --set use it)",
                )
                .clicked();
            if changed && (clicked || enter) {
                let name = name.trim();
                let name = (!name.is_empty() && name != id).then(|| name.to_string());
                self.actions
                    .push(CanvasAction::Edit(Edit::Rename(id.to_string(), name)));
                ui.data_mut(|d| d.remove::<String>(key));
                ui.close();
            } else {
                ui.data_mut(|d| d.insert_temp(key, name));
            }
        });
    }
}

const ERROR_COLOR: Color32 = Color32::from_rgb(0xd6, 0x2f, 0x2f);
const WARNING_COLOR: Color32 = Color32::from_rgb(0xe0, 0x9a, 0x2b);

impl SnarlViewer<CanvasNode> for Viewer<'_> {
    fn title(&mut self, node: &CanvasNode) -> String {
        self.graph
            .node(&node.id)
            .map_or_else(|| node.id.clone(), |n| n.label().to_string())
    }

    fn node_frame(
        &mut self,
        default: egui::Frame,
        node: NodeId,
        _inputs: &[InPin],
        _outputs: &[OutPin],
        snarl: &Snarl<CanvasNode>,
    ) -> egui::Frame {
        let Some(n) = snarl.get_node(node) else {
            return default;
        };
        let mut frame = default;
        if self
            .statuses
            .get(&n.id)
            .and_then(NodeStatus::error)
            .is_some()
        {
            frame.stroke = Stroke::new(2.0, ERROR_COLOR);
        }
        if self.focused.as_deref() == Some(n.id.as_str()) {
            frame.stroke = Stroke::new(2.0, Color32::from_rgb(0x3a, 0x8e, 0xe6));
        }
        if self.graph.node(&n.id).is_some_and(|g| !g.enabled) {
            frame.fill = frame.fill.gamma_multiply(0.6);
        }
        frame
    }

    fn show_header(
        &mut self,
        node: NodeId,
        _inputs: &[InPin],
        _outputs: &[OutPin],
        ui: &mut Ui,
        snarl: &mut Snarl<CanvasNode>,
    ) {
        let Some(id) = snarl.get_node(node).map(|n| n.id.clone()) else {
            return;
        };
        let Some(instance) = self.graph.node(&id) else {
            return;
        };
        let cluster = Cluster::of(&instance.def);
        ui.horizontal(|ui| {
            // The header's texts are not selectable and take no clicks: a click (Shift+click:
            // select, Ctrl+click: deselect) or a drag on the title goes to the node itself.
            ui.style_mut().interaction.selectable_labels = false;
            let title = ui
                .add(
                    egui::Label::new(egui::RichText::new(instance.label()).strong())
                        .sense(egui::Sense::hover()),
                )
                .on_hover_ui(|ui| {
                    ui.set_max_width(360.0);
                    if instance.name.is_some() {
                        // A named node: its id is what wires, `--set` and scripts use.
                        ui.label(format!("id: {id}"));
                    }
                    ui.strong(instance.def.id.as_ref());
                    ui.label(instance.def.doc.as_ref());
                    if cluster.is_some() {
                        ui.weak("double-click to open it");
                    }
                });
            let double_clicked = title.contains_pointer()
                && ui.input(|i| {
                    i.pointer
                        .button_double_clicked(egui::PointerButton::Primary)
                });
            if cluster.is_some() && double_clicked {
                self.actions
                    .push(CanvasAction::Request(UiRequest::OpenCluster(id.clone())));
            }
            match cluster {
                Some(c) => {
                    ui.weak(format!("cluster · {}", c.label()))
                        .on_hover_text(instance.def.doc.as_ref());
                }
                None => {
                    ui.weak(instance.def.id.as_ref());
                }
            }
            let mut preview = instance.preview;
            // The eye takes the node's preview colour; right-click it to pick one.
            let eye = match instance.color {
                Some([r, g, b]) => egui::RichText::new("👁").color(Color32::from_rgb(r, g, b)),
                None => egui::RichText::new("👁"),
            };
            let toggle = ui.toggle_value(&mut preview, eye).on_hover_text(
                "preview this node's geometry in the viewport (right-click: its colour)",
            );
            if toggle.changed() {
                self.actions
                    .push(CanvasAction::Edit(Edit::SetPreview(id.clone(), preview)));
            }
            toggle.context_menu(|ui| {
                if let Some(color) = crate::viewport::colors::pick(ui, instance.color) {
                    self.actions
                        .push(CanvasAction::Edit(Edit::SetColor(id.clone(), color)));
                }
            });
            let mut enabled = instance.enabled;
            if ui
                .toggle_value(&mut enabled, "✔")
                .on_hover_text("enable / disable this node (disabled nodes do not run)")
                .changed()
            {
                self.actions
                    .push(CanvasAction::Edit(Edit::SetEnabled(id.clone(), enabled)));
            }
            match self.statuses.get(&id) {
                Some(NodeStatus::Error(m)) => {
                    ui.colored_label(ERROR_COLOR, "⛔").on_hover_text(m);
                }
                Some(NodeStatus::Blocked(m)) => {
                    ui.colored_label(Color32::GRAY, "⏸").on_hover_text(m);
                }
                Some(s @ NodeStatus::Ok { .. }) if !s.warnings().is_empty() => {
                    ui.colored_label(WARNING_COLOR, "⚠")
                        .on_hover_text(s.warnings().join("\n"));
                }
                Some(NodeStatus::Running { last_ms }) => {
                    ui.spinner().on_hover_text(if *last_ms > 0.0 {
                        format!(
                            "running after the 3D view was updated (last run {})",
                            crate::worker::format_ms(*last_ms)
                        )
                    } else {
                        "running after the 3D view was updated".to_string()
                    });
                }
                _ => {}
            }
        });
    }

    fn inputs(&mut self, node: &CanvasNode) -> usize {
        self.graph.node(&node.id).map_or(0, |n| n.def.inputs.len())
    }

    fn outputs(&mut self, node: &CanvasNode) -> usize {
        self.graph.node(&node.id).map_or(0, |n| n.def.outputs.len())
    }

    #[allow(refining_impl_trait)]
    fn show_input(
        &mut self,
        pin: &InPin,
        ui: &mut Ui,
        snarl: &mut Snarl<CanvasNode>,
    ) -> RecordingPin {
        let id = snarl
            .get_node(pin.id.node)
            .map(|n| n.id.clone())
            .unwrap_or_default();
        let key = (id.clone(), true, pin.id.input);
        let Some(instance) = self.graph.node(&id) else {
            return RecordingPin {
                info: PinInfo::circle(),
                key,
                sink: self.pins.clone(),
            };
        };
        let Some(port) = instance.def.inputs.get(pin.id.input) else {
            return RecordingPin {
                info: PinInfo::circle(),
                key,
                sink: self.pins.clone(),
            };
        };
        let wired = !pin.remotes.is_empty();
        let missing = !wired && port.required() && instance.value(pin.id.input).is_none();
        ui.horizontal(|ui| {
            let (shown, full) = fitted_port_name(ui, &port.name);
            let mut text = egui::RichText::new(shown);
            if missing {
                text = text.color(ERROR_COLOR);
            }
            let k = pin.id.input;
            let label = ui
                .add(egui::Label::new(text).sense(egui::Sense::click()))
                .on_hover_text(format!(
                    "{full}{} — {}{}",
                    port.type_name(),
                    port.doc,
                    if missing {
                        "\n(required: connect it or set a value)"
                    } else {
                        ""
                    }
                ));
            if !wired {
                let candidates = crate::optimization::variable_candidates(instance, k);
                if !candidates.is_empty() {
                    label.context_menu(|ui| {
                        if let Some(c) = crate::optimization::variable_menu(ui, &candidates) {
                            self.actions.push(c.into());
                        }
                    });
                }
            }
            let unset_optional =
                port.optional && port.default.is_none() && instance.value(k).is_none();
            if !wired && unset_optional && widgets::has_editor(instance, k) {
                // An optional input left empty: the node sees "none", which differs from any value
                // an editor would show. Offer to set one.
                if ui
                    .small_button("set")
                    .on_hover_text("give this optional input a value")
                    .clicked()
                    && let Some(value) = widgets::initial_value(&port.ty)
                {
                    self.actions.push(CanvasAction::Edit(Edit::SetValue {
                        node: id.clone(),
                        input: port.name.to_string(),
                        value,
                    }));
                }
            } else if !wired && widgets::has_editor(instance, k) {
                ui.spacing_mut().slider_width = 110.0;
                let (changed, rect) = widgets::input_editor_with_rect(ui, instance, k);
                self.editors
                    .insert((id.clone(), port.name.to_string()), rect);
                if let Some(value) = changed {
                    self.actions.push(CanvasAction::Edit(Edit::SetValue {
                        node: id.clone(),
                        input: port.name.to_string(),
                        value,
                    }));
                }
                if port.optional
                    && port.default.is_none()
                    && ui
                        .small_button("×")
                        .on_hover_text("clear: leave this optional input empty")
                        .clicked()
                {
                    self.actions.push(CanvasAction::Edit(Edit::ClearValue {
                        node: id.clone(),
                        input: port.name.to_string(),
                    }));
                }
            } else if !wired && let Some(list) = self.list_views.on_node(instance, k) {
                // A literal list: its summary, and a button opening it as a table.
                ui.weak(&list.summary);
                if list.editable {
                    let button = ui.small_button("Edit…").on_hover_text(
                        "edit the list as a table: cells, rows, paste from a spreadsheet",
                    );
                    self.editors
                        .insert((id.clone(), port.name.to_string()), button.rect);
                    if button.clicked() {
                        self.actions
                            .push(CanvasAction::Request(UiRequest::EditList {
                                node: id.clone(),
                                input: port.name.to_string(),
                            }));
                    }
                }
            }
        });
        RecordingPin {
            info: pin_info(port),
            key,
            sink: self.pins.clone(),
        }
    }

    #[allow(refining_impl_trait)]
    fn show_output(
        &mut self,
        pin: &OutPin,
        ui: &mut Ui,
        snarl: &mut Snarl<CanvasNode>,
    ) -> RecordingPin {
        let id = snarl
            .get_node(pin.id.node)
            .map(|n| n.id.clone())
            .unwrap_or_default();
        let key = (id.clone(), false, pin.id.output);
        let Some(port) = self
            .graph
            .node(&id)
            .and_then(|n| n.def.outputs.get(pin.id.output))
        else {
            return RecordingPin {
                info: PinInfo::circle(),
                key,
                sink: self.pins.clone(),
            };
        };
        let summary = match self.statuses.get(&id) {
            Some(NodeStatus::Ok { outputs, .. }) => outputs.get(pin.id.output).cloned(),
            _ => None,
        };
        ui.horizontal(|ui| {
            if let Some(s) = summary {
                ui.weak(s);
            }
            let (shown, full) = fitted_port_name(ui, &port.name);
            let label = ui
                .add(egui::Label::new(shown).sense(egui::Sense::click()))
                .on_hover_text(format!("{full}{} — {}", port.type_name(), port.doc));
            if crate::optimization::minimizable(port) {
                label.context_menu(|ui| {
                    let path = ValuePath {
                        node: id.clone(),
                        port: port.name.to_string(),
                        indices: Vec::new(),
                    };
                    if ui
                        .button("Minimize this output")
                        .on_hover_text("make it the optimization objective")
                        .clicked()
                    {
                        self.actions
                            .push(CanvasAction::Request(UiRequest::Minimize(path.clone())));
                        ui.close();
                    }
                    if ui
                        .button("Add as penalty")
                        .on_hover_text(
                            "a soft constraint of the optimization (edit it in the panel)",
                        )
                        .clicked()
                    {
                        self.actions
                            .push(CanvasAction::Request(UiRequest::Penalize(path)));
                        ui.close();
                    }
                });
            }
        });
        RecordingPin {
            info: pin_info(port),
            key,
            sink: self.pins.clone(),
        }
    }

    fn has_body(&mut self, node: &CanvasNode) -> bool {
        self.graph
            .node(&node.id)
            .is_some_and(|n| mapper::is_mapper(n) || n.def.id == PANEL_TYPE)
    }

    fn show_body(
        &mut self,
        node: NodeId,
        _inputs: &[InPin],
        _outputs: &[OutPin],
        ui: &mut Ui,
        snarl: &mut Snarl<CanvasNode>,
    ) {
        let Some(id) = snarl.get_node(node).map(|n| n.id.clone()) else {
            return;
        };
        if self.graph.node(&id).is_some_and(|n| n.def.id == PANEL_TYPE) {
            let text = match self.statuses.get(&id) {
                Some(NodeStatus::Ok { readout, .. }) => readout.clone(),
                _ => None,
            };
            let rect = panel_readout(ui, &id, text.as_deref());
            self.panels.insert(id, rect);
            return;
        }
        if let Some(instance) = self.graph.node(&id) {
            let ran_on = self.statuses.get(&id).and_then(NodeStatus::ran_on);
            let r = mapper::show(ui, self.graph, instance, ran_on);
            self.plots.insert(id.clone(), r.plot);
            if let Some(shown) = r.shown {
                self.mapper_views.insert(id.clone(), shown);
            }
            if let Some(values) = r.changes {
                self.actions
                    .push(CanvasAction::Edit(Edit::SetValues { node: id, values }));
            }
            if let Some(a) = r.optimize {
                self.actions.push(a.into());
            }
        }
    }

    fn final_node_rect(
        &mut self,
        node: NodeId,
        rect: Rect,
        ui: &mut Ui,
        snarl: &mut Snarl<CanvasNode>,
    ) {
        let Some(id) = snarl.get_node(node).map(|n| n.id.clone()) else {
            return;
        };
        // The pointer is in screen coordinates, the node rectangle in canvas coordinates.
        let pressed_at = ui.input(|i| {
            i.pointer
                .primary_pressed()
                .then(|| i.pointer.interact_pos())
                .flatten()
        });
        if pressed_at.is_some_and(|p| rect.contains(self.to_global.inverse() * p)) {
            self.pressed_node = Some(id.clone());
        }
        if self.chosen.contains(&id) {
            ui.painter().rect_stroke(
                rect.expand(3.0),
                6.0,
                Stroke::new(2.0, Color32::from_rgb(0x3a, 0x8e, 0xe6)),
                egui::StrokeKind::Outside,
            );
        }
        self.rects.insert(id, rect);
    }

    fn has_node_menu(&mut self, _node: &CanvasNode) -> bool {
        true
    }

    fn show_node_menu(
        &mut self,
        node: NodeId,
        _inputs: &[InPin],
        _outputs: &[OutPin],
        ui: &mut Ui,
        snarl: &mut Snarl<CanvasNode>,
    ) {
        let Some(id) = snarl.get_node(node).map(|n| n.id.clone()) else {
            return;
        };
        if ui.button("Duplicate").clicked() {
            self.actions
                .push(CanvasAction::Edit(Edit::Duplicate(vec![id.clone()])));
            ui.close();
        }
        if ui.button("Delete").clicked() {
            self.actions
                .push(CanvasAction::Edit(Edit::Remove(vec![id.clone()])));
            ui.close();
        }
        self.rename_node_menu(ui, &id);
        if self
            .graph
            .node(&id)
            .is_some_and(|n| n.def.outputs.iter().any(|p| p.ty == ValueType::Polyline))
            && ui
                .button("Internalise as editable points")
                .on_hover_text(
                    "insert a param.points node per curve, holding its points, wired into a \
                 curve.polyline: drag them in the 3D view",
                )
                .clicked()
        {
            self.actions
                .push(CanvasAction::Request(UiRequest::Internalise(id.clone())));
            ui.close();
        }
        ui.separator();
        let group = if self.selected.contains(&id) {
            self.selected.clone()
        } else {
            vec![id.clone()]
        };
        if ui
            .button(format!("Make cluster ({} nodes)", group.len()))
            .on_hover_text("replace the selected nodes by one cluster node (Ctrl+G)")
            .clicked()
        {
            self.actions.push(CanvasAction::Edit(Edit::MakeCluster {
                nodes: group,
                around: None,
            }));
            ui.close();
        }
        if self
            .graph
            .node(&id)
            .is_some_and(|n| Cluster::of(&n.def).is_some())
        {
            if ui.button("Open cluster").clicked() {
                self.actions
                    .push(CanvasAction::Request(UiRequest::OpenCluster(id.clone())));
                ui.close();
            }
            if ui
                .button("Explode cluster")
                .on_hover_text("put the cluster's nodes back in its place (Ctrl+Shift+G)")
                .clicked()
            {
                self.actions
                    .push(CanvasAction::Edit(Edit::ExplodeCluster(id.clone())));
                ui.close();
            }
        }
        if let Some(n) = self.graph.node(&id)
            && (n.def.id == cnets_engine::cluster::INPUT_TYPE
                || n.def.id == cnets_engine::cluster::OUTPUT_TYPE)
        {
            ui.separator();
            self.rename_port_menu(ui, &id);
        }
        if let Some(n) = self.graph.node(&id)
            && n.def.has_flag(NodeFlag::Export)
        {
            ui.weak("runs on File › Export");
        }
    }

    fn has_graph_menu(&mut self, _pos: Pos2, _snarl: &mut Snarl<CanvasNode>) -> bool {
        true
    }

    fn show_graph_menu(&mut self, pos: Pos2, ui: &mut Ui, _snarl: &mut Snarl<CanvasNode>) {
        if ui.button("Add node…").clicked() {
            self.actions
                .push(CanvasAction::Request(UiRequest::OpenPalette([
                    pos.x, pos.y,
                ])));
            ui.close();
        }
    }

    fn connect(&mut self, from: &OutPin, to: &InPin, snarl: &mut Snarl<CanvasNode>) {
        if let Some((from, output, to, input)) = self.names(snarl, from, to) {
            self.actions.push(CanvasAction::Edit(Edit::Connect {
                from,
                output,
                to,
                input,
                replace: !self.shift,
            }));
        }
    }

    fn disconnect(&mut self, from: &OutPin, to: &InPin, snarl: &mut Snarl<CanvasNode>) {
        if let Some((from, output, to, input)) = self.names(snarl, from, to) {
            self.actions.push(CanvasAction::Edit(Edit::Disconnect {
                from,
                output,
                to,
                input,
            }));
        }
    }

    fn drop_inputs(&mut self, pin: &InPin, snarl: &mut Snarl<CanvasNode>) {
        let Some(id) = snarl.get_node(pin.id.node).map(|n| n.id.clone()) else {
            return;
        };
        if let Some(port) = self
            .graph
            .node(&id)
            .and_then(|n| n.def.inputs.get(pin.id.input))
        {
            self.actions.push(CanvasAction::Edit(Edit::DropInputs {
                node: id,
                input: port.name.to_string(),
            }));
        }
    }

    fn drop_outputs(&mut self, pin: &OutPin, snarl: &mut Snarl<CanvasNode>) {
        let Some(id) = snarl.get_node(pin.id.node).map(|n| n.id.clone()) else {
            return;
        };
        if let Some(port) = self
            .graph
            .node(&id)
            .and_then(|n| n.def.outputs.get(pin.id.output))
        {
            self.actions.push(CanvasAction::Edit(Edit::DropOutputs {
                node: id,
                output: port.name.to_string(),
            }));
        }
    }

    fn current_transform(&mut self, to_global: &mut TSTransform, _snarl: &mut Snarl<CanvasNode>) {
        if let Some(fit) = self.fit.take() {
            *to_global = fit;
        }
        self.to_global = *to_global;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::edit::tests::doc;

    #[test]
    fn sync_mirrors_nodes_and_wires() {
        let d = doc();
        let mut c = Canvas::new();
        c.sync(&d.graph);
        assert_eq!(c.counts(), (3, 2));
        let mut g = d.graph.clone();
        g.remove_node("len").unwrap();
        c.sync(&g);
        assert_eq!(c.counts(), (2, 1));
    }

    /// The wires are diffed only when their fingerprint changes: a wire moved to another input
    /// (same counts of nodes and wires) is still followed, and syncing again changes nothing.
    #[test]
    fn a_rewired_input_with_the_same_counts_is_followed() {
        let d = doc();
        let mut c = Canvas::new();
        c.sync(&d.graph);
        let input_of_wire = |c: &Canvas| {
            let arc = c.ids["arc"];
            c.snarl
                .wires()
                .filter(|(_, i)| i.node == arc)
                .map(|(_, i)| i.input)
                .collect::<Vec<_>>()
        };
        let arc = d.graph.node("arc").unwrap();
        let radius = arc.def.input_index("radius").unwrap();
        assert_eq!(input_of_wire(&c), vec![radius]);
        let other = arc
            .def
            .inputs
            .iter()
            .position(|p| p.name != "radius" && p.ty == ValueType::Number)
            .expect("curve.arc has a second number input");
        let mut g = d.graph.clone();
        g.disconnect("n", "value", "arc", "radius").unwrap();
        g.connect("n", "value", "arc", &arc.def.inputs[other].name)
            .unwrap();
        c.sync(&g);
        assert_eq!(c.counts(), (3, 2));
        assert_eq!(input_of_wire(&c), vec![other]);
        c.sync(&g);
        assert_eq!(input_of_wire(&c), vec![other]);
        // Back to the first graph (an undo): the first wiring again.
        c.sync(&d.graph);
        assert_eq!(input_of_wire(&c), vec![radius]);
    }
}
