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

use cnets_engine::Graph;
use egui::emath::TSTransform;
use egui::{Pos2, Rect, Ui};
use egui_snarl::ui::{SnarlStyle, SnarlWidget};
use egui_snarl::{InPinId, NodeId, OutPinId, Snarl};
use rustc_hash::{FxHashMap, FxHashSet};

mod action;
mod pins;
mod viewer;

pub use action::{CanvasAction, CanvasNode};
pub use pins::{PORT_NAME_WIDTH, PinKey, RecordingPin, type_color};
use viewer::Viewer;

use crate::edit::Edit;
use crate::request::UiRequest;
use crate::worker::NodeStatus;
use crate::{list_editor, mapper};

/// The canvas: the snarl mirror of the graph and what the last frame learned about it.
pub struct Canvas {
    /// Nodes locked for dragging the net: the Drag net tool leaves their inputs alone (a node's
    /// context menu; kept for the session, not saved).
    pub drag_locked: std::collections::BTreeSet<String>,
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
    /// graph, after Arrange) rather than opening it ([`Canvas::opening`]).
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
/// glyph quad is at least one pixel tall (`tests/it/glyphs.rs` checks it for the fonts in use).
pub const MIN_ZOOM: f32 = 0.5;

/// The smallest height, in screen pixels, of node text when a graph opens.
pub const MIN_TEXT_PX: f32 = 10.0;

/// How far below the readable zoom a graph too large to show whole may open, so that the 3D
/// view's edge falls between nodes instead of through one ([`Canvas::opening`]): node text of
/// at least 75 % of [`MIN_TEXT_PX`].
pub const OPENING_TEXT_SHARE: f32 = 0.75;

/// The largest zoom a graph too large to show whole opens at when the 3D view's edge is moved
/// before the nodes it would cut ([`Canvas::opening`]).
pub const OPENING_MAX_ZOOM: f32 = 1.5;

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
            drag_locked: Default::default(),
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
    /// (Home, View › Frame graph); a graph larger than that shows its top-left part with the 3D
    /// view's edge between nodes ([`Canvas::opening`] at the smallest zoom).
    pub fn fit(&mut self) {
        self.fit_pending = true;
        self.fit_whole = true;
    }

    /// Frames the graph as it opens, after six more frames (once nodes have their new sizes,
    /// e.g. when the first results of a newly shown graph arrive): the whole graph when it fits
    /// at [`MIN_ZOOM`] or more (no node left under the 3D view), else its top-left corner at a
    /// readable zoom ([`Canvas::opening`]).
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

    /// The transform a graph of node rectangles `nodes` (canvas coordinates) opens with
    /// ([`Canvas::fit_later`]): the whole graph in screen rectangle `ui` when it fits at
    /// [`MIN_ZOOM`] or more, at most zoom 1 (as Home frames it). A graph too large for that
    /// opens on its top-left corner (the sources) at about the `readable` zoom, adjusted so that
    /// the view's right edge — where the 3D view begins — falls between nodes: every node is
    /// either wholly in view or wholly beyond it, none cut in half. The edge moves right past the
    /// nodes it would cut (zooming out) or left before them (zooming in, at most to
    /// [`OPENING_MAX_ZOOM`]), whichever
    /// keeps the zoom nearer the readable one — preferably no lower than [`OPENING_TEXT_SHARE`]
    /// of it, never below [`MIN_ZOOM`].
    pub fn opening(nodes: &[Rect], ui: Rect, readable: f32) -> Option<TSTransform> {
        let bb = nodes.iter().fold(Rect::NOTHING, |a, r| a.union(*r));
        if !(bb.is_positive() && ui.is_positive()) {
            return None;
        }
        let framed = bb.expand(30.0);
        let fits = (ui.width() / framed.width()).min(ui.height() / framed.height());
        if fits >= MIN_ZOOM {
            return Self::framing(bb, ui, MIN_ZOOM);
        }
        let t = Self::framing(bb, ui, readable)?;
        if framed.width() * t.scaling <= ui.width() {
            return Some(t);
        }
        // The canvas x of the view's left edge, and of its right edge moved past every node it
        // would cut (each move may cut another: repeat until none is).
        let left = framed.left();
        let start = left + ui.width() / t.scaling;
        let settle = |outward: bool| {
            let mut edge = start;
            for _ in 0..nodes.len() + 1 {
                let cut = nodes
                    .iter()
                    .filter(|r| r.left() < edge && r.right() > edge)
                    .map(|r| {
                        if outward {
                            r.right() + 20.0
                        } else {
                            r.left() - 20.0
                        }
                    });
                let next = if outward {
                    cut.reduce(f32::max)
                } else {
                    cut.reduce(f32::min)
                };
                match next {
                    Some(e) => edge = e,
                    None => return Some(edge),
                }
            }
            None
        };
        let scale_to = |edge: f32| ui.width() / (edge - left).max(1.0);
        // Of the two, the zoom nearest the readable one — within the text share when one is.
        let lowest = (readable * OPENING_TEXT_SHARE).max(MIN_ZOOM);
        let candidates: Vec<f32> = [settle(true), settle(false)]
            .into_iter()
            .flatten()
            .map(scale_to)
            .filter(|z| (MIN_ZOOM..=OPENING_MAX_ZOOM).contains(z))
            .collect();
        let distance = |z: &f32| (z / readable).ln().abs();
        let nearest = |within: bool| {
            candidates
                .iter()
                .copied()
                .filter(|z| !within || *z >= lowest)
                .min_by(|a, b| distance(a).total_cmp(&distance(b)))
        };
        let Some(scale) = nearest(true).or_else(|| nearest(false)) else {
            return Some(t);
        };
        let y = if framed.height() * scale <= ui.height() {
            ui.center().y - framed.center().y * scale
        } else {
            ui.top() - framed.top() * scale
        };
        Some(TSTransform::new(
            egui::vec2(ui.left() - left * scale, y),
            scale,
        ))
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
            // Home frames as much as the smallest zoom shows, a graph opens near the readable
            // zoom; either way no node is left cut in half by the 3D view's edge.
            let readable = if self.fit_whole {
                MIN_ZOOM
            } else {
                readable_zoom(ui.style())
            };
            let nodes: Vec<Rect> = self.rects.values().copied().collect();
            fit = Self::opening(&nodes, self.ui_rect, readable);
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
            drag_locked: self.drag_locked.clone(),
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::edit::tests::doc;
    use cnets_engine::ValueType;

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
