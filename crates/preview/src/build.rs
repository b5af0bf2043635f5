//! Building the render scene (and the figures and pick records shown with it) from the previewed
//! outputs of a graph.

#[cfg(not(target_arch = "wasm32"))]
use std::time::Instant;
// std's clock panics on wasm32-unknown-unknown (the web editor); web-time reads the browser's.
#[cfg(target_arch = "wasm32")]
use web_time::Instant;

use cnets_engine::value::Access;
use cnets_engine::{Evaluator, Graph, PortDef, Value, ValueType};
use cnets_geometry::conenet::quad_planarity;
use cnets_geometry::fabrication::{FaceClass, face_planarity};
use cnets_geometry::{DVec3, PolygonMesh, QuadGrid};
use cnets_render::palette::{self, SequentialMap, ToleranceMap};
use cnets_render::{Color, FaceColors, LineStyle, MeshStyle, PointStyle, Scene};
use std::sync::Arc;

use crate::beside;
use crate::classes::{class_color, face_classes};
use crate::distance::{
    DistanceFigures, DistanceReference, Measured, distance_reference, is_construction, measure,
};
use crate::legend::{APEX_COLOR, LegendInfo};
use crate::options::{ColorMode, DistanceSide, Layer, PreviewOptions};
use crate::picks::{PickCurve, PickGeometry, PickMesh, Picks};

/// What the preview of a graph shows: the scene, its figures and what each drawn thing came from.
#[derive(Clone, Debug, Default)]
pub struct Preview {
    /// The render scene.
    pub scene: Scene,
    /// Figures and legend.
    pub stats: PreviewStats,
    /// The drawn meshes and curves with the nodes that made them.
    pub picks: Picks,
}

/// Where a collected value came from: node, output and item of a list.
#[derive(Clone)]
struct Origin {
    node: String,
    output: String,
    item: Option<usize>,
}

/// A quad mesh waiting for its colours (planarity colours need all meshes first).
struct PendingGrid {
    grid: Arc<QuadGrid>,
    configurations: Option<Value>,
    layer: Layer,
    origin: Origin,
    /// The node's preview colour and depth layer.
    look: Look,
    /// What the mesh is to the figures.
    kind: MeshKind,
}

/// How one node's geometry is drawn: its picked colour (if any) and its depth layer.
#[derive(Clone, Copy, Default)]
struct Look {
    color: Option<Color>,
    depth_layer: u32,
}

/// What a previewed mesh is to the figures.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum MeshKind {
    /// A cone-net: a mesh output of a construction (a node declaring its faces' convexity margins,
    /// [`cnets_engine::Role::FaceMargins`], and with them the configurations).
    ConeNet,
    /// Any other mesh (a cut or mirrored net, a support layer, an imported surface).
    Mesh,
    /// The reference of the distance mode: measured against, never counted in the net's figures.
    Reference,
}

impl MeshKind {
    /// The word for it in figures: `cone-net`, `mesh`, `reference`.
    pub fn word(self) -> &'static str {
        match self {
            MeshKind::ConeNet => "cone-net",
            MeshKind::Mesh => "mesh",
            MeshKind::Reference => "reference",
        }
    }
}

/// The figures of one previewed mesh.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct MeshFigures {
    /// `node.output`, with `[item]` for an item of a list.
    pub name: String,
    /// What it is.
    pub kind: MeshKind,
    /// Its vertices.
    pub vertices: usize,
    /// Its faces.
    pub faces: usize,
    /// Its largest face planarity (`None` without a finite one).
    pub max_planarity: Option<f64>,
}

/// Figures about the previewed geometry.
#[derive(Clone, Debug, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct PreviewStats {
    /// Vertices of all previewed meshes.
    pub vertices: usize,
    /// Faces of all previewed meshes.
    pub faces: usize,
    /// The headline planarity: the largest face planarity of the previewed cone-nets, or without
    /// any, of the other previewed meshes — never of a distance reference ([`MeshKind`]); `None`
    /// without faces.
    pub max_planarity: Option<f64>,
    /// The mesh `max_planarity` is on (`node.output`, `[item]` in a list).
    pub max_planarity_mesh: Option<String>,
    /// Every previewed mesh with its own figures: cone-nets first, then other meshes, then the
    /// distance reference.
    pub meshes: Vec<MeshFigures>,
    /// Legend of the surface colours.
    pub legend: LegendInfo,
    /// Apex points drawn (the apices layer shown).
    pub apices: usize,
    /// In [`ColorMode::Distance`]: the symmetric distance between the net and the reference, and
    /// what the colours show (`None` in other modes, or when nothing was measured:
    /// [`PreviewStats::distance_status`] says why).
    pub distance: Option<DistanceFigures>,
    /// In [`ColorMode::Distance`] without figures: why (no reference picked, the reference has no
    /// mesh, nothing else previewed…).
    pub distance_status: Option<String>,
    /// Time spent building the scene, in milliseconds.
    pub build_ms: f64,
}

/// A length in metres for legends, to three significant digits (`0 m`, `0.0450 m`, `1.25 m`).
pub fn format_metres(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v} m");
    }
    let digits = (2 - v.abs().log10().floor() as i32).clamp(0, 12) as usize;
    format!("{v:.digits$} m")
}

/// The legend of the distance mode: 0 … `max` in metres, six stops, under `title`.
pub fn distance_legend(title: &str, max: f64) -> cnets_render::Legend {
    let mut legend = SequentialMap::new(0.0, max).legend(title, 6);
    legend.labels = legend
        .stops
        .iter()
        .map(|(v, _)| format_metres(*v))
        .collect();
    legend
}

/// Builds the preview scene from the evaluator's results for `graph`.
pub fn build_scene(
    graph: &Graph,
    eval: &Evaluator,
    opts: &PreviewOptions,
) -> (Scene, PreviewStats) {
    let p = build_preview(graph, eval, opts);
    (p.scene, p.stats)
}

/// Builds the preview of `graph` from the evaluator's results: the scene, its figures and the pick
/// records of what was drawn.
pub fn build_preview(graph: &Graph, eval: &Evaluator, opts: &PreviewOptions) -> Preview {
    let start = Instant::now();
    let mut b = Builder {
        scene: Scene::new(),
        stats: PreviewStats::default(),
        opts: *opts,
        class_counts: [0; 5],
        any_classes: false,
        planarity_range: None,
        picks: Picks::default(),
        look: Look::default(),
        kind: MeshKind::Mesh,
        measured: None,
        distance_map: None,
        reference: None,
        skip_key: None,
        flat: Vec::new(),
    };
    // Planarity colours need one range over all meshes: quad grids are collected first.
    let mut meshes: Vec<PendingGrid> = Vec::new();
    let mut next_layer = 0u32;
    // The distance mode measures the net (every other previewed mesh) against the reference
    // first: one scale over all of them.
    if opts.color_mode == ColorMode::Distance {
        let reference = opts
            .distance_to
            .ok_or_else(|| {
                "no reference picked: the distance colouring needs a mesh other than the net \
                 (import one, e.g. with io.read_mesh)"
                    .to_string()
            })
            .and_then(|uid| distance_reference(graph, eval, uid));
        match reference.and_then(|r| Ok((measure(graph, eval, &r, opts.distance_side)?, r))) {
            Ok((measured, reference)) => {
                b.distance_map = Some(SequentialMap::new(0.0, measured.figures.colour_max));
                b.stats.distance = Some(measured.figures.clone());
                b.measured = Some(measured);
                // Colouring the reference: drawn first (even when not previewed), so the net's
                // translucent faces blend over it.
                if opts.distance_side == DistanceSide::Reference {
                    b.look = Look {
                        color: None,
                        depth_layer: next_layer,
                    };
                    next_layer += 1;
                    b.kind = MeshKind::Reference;
                    let origin = Origin {
                        node: reference.node.clone(),
                        output: reference.output.clone(),
                        item: None,
                    };
                    b.collect(
                        &reference.value,
                        Layer::Surfaces,
                        &None,
                        &origin,
                        &mut meshes,
                    );
                    // A quad grid is drawn now too, before the net.
                    if let Some(grid) = meshes.pop() {
                        let planarity: Vec<f64> =
                            grid.grid.quads().map(|(_, q)| quad_planarity(q)).collect();
                        b.note_mesh(
                            grid.kind,
                            &grid.origin,
                            grid.grid.vertices.len(),
                            &planarity,
                        );
                        b.add_quad_grid(grid, planarity);
                    }
                    // Not drawn again with its node.
                    b.skip_key = Some(reference.key);
                }
                b.reference = Some(reference);
            }
            Err(why) => b.stats.distance_status = Some(why),
        }
    }
    for (index, node) in graph.nodes() {
        if !node.preview || !node.enabled {
            continue;
        }
        let Some(outputs) = eval.result_at(graph, index).and_then(|r| r.outputs()) else {
            continue;
        };
        // Each previewed node draws its surfaces on its own depth layer (coincident surfaces of
        // two nodes do not flicker: the later node wins), in its picked colour.
        b.look = Look {
            color: node.color.map(|[r, g, bl]| Color::rgb(r, g, bl)),
            depth_layer: next_layer,
        };
        next_layer += 1;
        // A construction's configurations: its table of labels (a tree of texts), read by type.
        let construction = is_construction(node);
        let configurations = construction
            .then(|| {
                node.def
                    .outputs
                    .iter()
                    .position(|p| p.ty == ValueType::Text && p.access == Access::Tree)
            })
            .flatten()
            .and_then(|k| outputs.values.get(k))
            .cloned();
        let is_reference = b.reference.as_ref().is_some_and(|r| r.node == node.id);
        for (port, value) in node.def.outputs.iter().zip(&outputs.values) {
            let layer = layer_of(port);
            b.kind = if is_reference {
                MeshKind::Reference
            } else if construction && layer == Layer::Surfaces {
                MeshKind::ConeNet
            } else {
                MeshKind::Mesh
            };
            let origin = Origin {
                node: node.id.clone(),
                output: port.name.to_string(),
                item: None,
            };
            if layer == Layer::Unrolled {
                // Drawn beside the design once the design is known.
                if opts.shows(Layer::Unrolled) {
                    b.flat.push((value.clone(), origin, b.look));
                }
                continue;
            }
            b.collect(value, layer, &configurations, &origin, &mut meshes);
        }
    }
    // Per-face planarity of every quad mesh (for the figure, and the colours in that mode).
    let planarities: Vec<Vec<f64>> = meshes
        .iter()
        .map(|m| m.grid.quads().map(|(_, q)| quad_planarity(q)).collect())
        .collect();
    for (m, p) in meshes.iter().zip(&planarities) {
        b.note_mesh(m.kind, &m.origin, m.grid.vertices.len(), p);
    }
    b.headline();
    if opts.color_mode == ColorMode::Planarity {
        // Anchored to tolerances, not fitted to the data (rounding noise is not a patchwork).
        b.planarity_range = Some(opts.planarity_map());
    }
    for (pending, planarity) in meshes.into_iter().zip(planarities) {
        b.add_quad_grid(pending, planarity);
    }
    b.add_flat_beside();
    b.stats.legend = match opts.color_mode {
        _ if b.stats.faces == 0 || !opts.shows(Layer::Surfaces) => LegendInfo::None,
        ColorMode::Configuration if b.any_classes => LegendInfo::Classes(
            FaceClass::ALL
                .iter()
                .map(|&c| (c, b.class_counts[c.index()]))
                .filter(|&(c, n)| n > 0 || c == FaceClass::Convex)
                .collect(),
        ),
        ColorMode::Planarity => b
            .planarity_range
            .map_or(LegendInfo::None, |m| LegendInfo::Planarity(m.legend())),
        ColorMode::Distance => match &b.stats.distance {
            Some(d) => LegendInfo::Distance(distance_legend(&d.legend_title(), d.colour_max)),
            None => LegendInfo::None,
        },
        _ => LegendInfo::None,
    };
    b.stats.build_ms = start.elapsed().as_secs_f64() * 1e3;
    Preview {
        scene: b.scene,
        stats: b.stats,
        picks: b.picks,
    }
}

/// The layer an output is drawn in: the port's declared preview layer
/// ([`cnets_engine::PortHint::layer`]); geometry without one is a surface (curves and points
/// find their own layers by type).
pub fn layer_of(port: &PortDef) -> Layer {
    port.hint.layer.unwrap_or(Layer::Surfaces)
}

struct Builder {
    scene: Scene,
    stats: PreviewStats,
    opts: PreviewOptions,
    class_counts: [usize; 5],
    any_classes: bool,
    planarity_range: Option<ToleranceMap>,
    picks: Picks,
    /// The colour and depth layer of the node being collected.
    look: Look,
    /// What the meshes of the output being collected are to the figures.
    kind: MeshKind,
    /// Distance mode: what was measured (the vertex distances coloured, the net's meshes).
    measured: Option<Measured>,
    /// Distance mode: the colour scale (0 … the largest coloured distance).
    distance_map: Option<SequentialMap>,
    /// Distance mode: the reference (drawn first when it is the side coloured).
    reference: Option<DistanceReference>,
    /// The payload address of a mesh already drawn (the reference, drawn first): not drawn again.
    skip_key: Option<usize>,
    /// The flat fabrication layer's outputs, drawn last, beside the design ([`crate::beside`]).
    flat: Vec<(Value, Origin, Look)>,
}

/// Support layers are drawn translucent so the surface they support stays visible.
const SUPPORT_COLOR: Color = Color::hex(0xc9a66b).with_alpha(170);
const AXIS_COLOR: Color = Color::hex(0x2a9d5c);
const CURVE_COLOR: Color = palette::LINE;
/// The alpha of the net's faces drawn over a reference coloured by its distance to them.
const NET_OVER_REFERENCE_ALPHA: u8 = 90;

/// Whether `value` can show anything in the 3D view (what [`Builder::collect`] draws).
fn may_show(value: &Value) -> bool {
    matches!(
        value,
        Value::List(_)
            | Value::QuadMesh(_)
            | Value::Mesh(_)
            | Value::Polyline(_)
            | Value::Lines(_)
            | Value::Point(_)
    )
}

impl Origin {
    /// `node.output`, with `[item]` for an item of a list.
    fn name(&self) -> String {
        match self.item {
            Some(k) => format!("{}.{}[{k}]", self.node, self.output),
            None => format!("{}.{}", self.node, self.output),
        }
    }
}

impl Builder {
    /// Notes a mesh's figures (its kind, size and largest face planarity).
    fn note_mesh(&mut self, kind: MeshKind, origin: &Origin, vertices: usize, planarity: &[f64]) {
        let max_planarity = planarity
            .iter()
            .copied()
            .filter(|v| v.is_finite())
            .reduce(f64::max);
        self.stats.meshes.push(MeshFigures {
            name: origin.name(),
            kind,
            vertices,
            faces: planarity.len(),
            max_planarity,
        });
    }

    /// Notes the figures of each named part of a joined mesh (`node.output: part`), so the figures
    /// say which net a face came from.
    fn note_parts(&mut self, origin: &Origin, mesh: &PolygonMesh, planarity: &[f64]) {
        for (name, faces) in mesh.parts.names.iter().zip(mesh.parts.faces_of_each()) {
            if faces.is_empty() {
                continue;
            }
            let mut corners: Vec<u32> = faces
                .iter()
                .flat_map(|&f| mesh.face(f).iter().copied())
                .collect();
            corners.sort_unstable();
            corners.dedup();
            let part_planarity: Vec<f64> = faces.iter().map(|&f| planarity[f]).collect();
            let part = Origin {
                node: origin.node.clone(),
                output: format!("{}: {name}", origin.output),
                item: origin.item,
            };
            self.note_mesh(self.kind, &part, corners.len(), &part_planarity);
        }
    }

    /// Orders the meshes' figures (cone-nets, other meshes, the reference) and takes the headline
    /// planarity from the cone-nets, or without any from the other meshes: never the reference's.
    fn headline(&mut self) {
        let rank = |k: MeshKind| match k {
            MeshKind::ConeNet => 0,
            MeshKind::Mesh => 1,
            MeshKind::Reference => 2,
        };
        self.stats.meshes.sort_by_key(|m| rank(m.kind));
        let lead = self
            .stats
            .meshes
            .iter()
            .map(|m| m.kind)
            .find(|k| *k != MeshKind::Reference);
        let best = self
            .stats
            .meshes
            .iter()
            .filter(|m| Some(m.kind) == lead)
            .filter_map(|m| Some((m.max_planarity?, &m.name)))
            .fold(None::<(f64, &String)>, |acc, (p, name)| match acc {
                Some((q, _)) if q >= p => acc,
                _ => Some((p, name)),
            });
        self.stats.max_planarity = best.map(|(p, _)| p);
        self.stats.max_planarity_mesh = best.map(|(_, name)| name.clone());
    }

    fn edges(&self) -> Option<LineStyle> {
        self.opts.shows(Layer::Edges).then(MeshStyle::default_edges)
    }

    fn collect(
        &mut self,
        value: &Value,
        layer: Layer,
        configurations: &Option<Value>,
        origin: &Origin,
        meshes: &mut Vec<PendingGrid>,
    ) {
        match value {
            // Packed lists hold numbers, vectors or labels: nothing to show (and their items are
            // not built for it).
            Value::List(items) if items.as_packed().is_some() => {}
            Value::List(items) => {
                // A list of points is one point set; other lists are flattened.
                if items.iter().any(|v| matches!(v, Value::Point(_))) {
                    let points: Vec<DVec3> = items
                        .iter()
                        .filter_map(|v| match v {
                            Value::Point(p) => Some(*p),
                            _ => None,
                        })
                        .collect();
                    self.add_points(&points, layer);
                } else {
                    // A node run per item gives lists of meshes and, alongside, lists of their
                    // configuration tables: pair them item by item.
                    let paired = match configurations {
                        Some(Value::List(confs)) if confs.len() == items.len() => Some(confs),
                        _ => None,
                    };
                    for (k, item) in items.iter().enumerate() {
                        if !may_show(item) {
                            // A list of millions of numbers: no origin or configuration copied
                            // for each.
                            continue;
                        }
                        let confs = match paired {
                            Some(c) => Some(c[k].clone()),
                            None => configurations.clone(),
                        };
                        let origin = Origin {
                            item: Some(k),
                            ..origin.clone()
                        };
                        self.collect(item, layer, &confs, &origin, meshes);
                    }
                }
            }
            Value::QuadMesh(grid) if self.skip_key == Some(Arc::as_ptr(grid) as usize) => {}
            Value::Mesh(mesh) if self.skip_key == Some(Arc::as_ptr(mesh) as usize) => {}
            Value::QuadMesh(grid) => {
                let layer = if layer == Layer::Supports {
                    layer
                } else {
                    Layer::Surfaces
                };
                meshes.push(PendingGrid {
                    grid: grid.clone(),
                    configurations: configurations.clone(),
                    layer,
                    origin: origin.clone(),
                    look: self.look,
                    kind: self.kind,
                });
            }
            Value::Mesh(mesh) => {
                let show = if layer == Layer::Supports {
                    self.opts.shows(Layer::Supports)
                } else {
                    self.opts.shows(Layer::Surfaces)
                };
                self.stats.vertices += mesh.vertices.len();
                self.stats.faces += mesh.face_count();
                // Every polygon mesh counts in the planarity figure and is coloured by it in that
                // mode (an imported reference, a cut and mirrored net), not only quad grids.
                let planarity = face_planarity(mesh).unwrap_or_default();
                if mesh.parts.is_empty() || planarity.len() != mesh.face_count() {
                    self.note_mesh(self.kind, origin, mesh.vertices.len(), &planarity);
                } else {
                    self.note_parts(origin, mesh, &planarity);
                }
                if show {
                    let color = self.uniform_color(layer);
                    // The classes the faces kept from their cone-net (through cuts, mirrors and
                    // joins).
                    let classes = match layer {
                        Layer::Supports => None,
                        _ => mesh.face_classes().map(<[FaceClass]>::to_vec),
                    };
                    let colors: Option<Vec<Color>> = match self.opts.color_mode {
                        ColorMode::Configuration => self.class_colors(classes.as_deref()),
                        ColorMode::Planarity
                            if layer != Layer::Supports && planarity.len() == mesh.face_count() =>
                        {
                            let map = self.opts.planarity_map();
                            Some(planarity.iter().map(|&v| map.color(v)).collect())
                        }
                        _ => None,
                    };
                    let key = Arc::as_ptr(mesh) as usize;
                    let by_distance = match layer {
                        Layer::Supports => None,
                        _ => self.vertex_distance_colors(key),
                    };
                    let faces = match (&colors, &by_distance) {
                        (_, Some(c)) => FaceColors::PerVertex(c),
                        (Some(c), None) => FaceColors::PerFace(c),
                        (None, None) => FaceColors::Uniform(self.net_color(key, color)),
                    };
                    let style = MeshStyle::new(faces)
                        .edges(self.edges())
                        .depth_layer(self.look.depth_layer);
                    if self.scene.add_polygon_mesh(mesh, style).is_ok() {
                        self.picks.meshes.push(PickMesh {
                            node: origin.node.clone(),
                            output: origin.output.clone(),
                            item: origin.item,
                            geometry: PickGeometry::Mesh(mesh.clone()),
                            classes,
                            planarity: Vec::new(),
                        });
                    }
                }
            }
            Value::Polyline(p) => {
                let (layer, color) = self.line_layer(layer);
                let color = self.curve_color(layer, color);
                if self.opts.shows(layer) {
                    self.scene.add_polyline(p, LineStyle::new(color, 2.5));
                    self.picks.curves.push(PickCurve {
                        node: origin.node.clone(),
                        output: origin.output.clone(),
                        polyline: p.clone(),
                    });
                }
            }
            Value::Lines(lines) => {
                let (layer, color) = self.line_layer(layer);
                let color = self.curve_color(layer, color);
                if self.opts.shows(layer) {
                    self.scene.add_lines(lines, LineStyle::new(color, 1.5));
                }
            }
            Value::Point(p) => self.add_points(&[*p], layer),
            _ => {}
        }
    }

    /// Draws the flat fabrication layer beside what is drawn so far (the design), flagged
    /// [`cnets_render::FLAG_BESIDE`] so the design's size leaves it out.
    fn add_flat_beside(&mut self) {
        let flat = std::mem::take(&mut self.flat);
        let Some(extent) = beside::bounds_of(flat.iter().map(|(v, _, _)| v)) else {
            return;
        };
        let by = beside::offset_beside(self.scene.bounds(), extent);
        let (segments, points) = (self.scene.segments().len(), self.scene.points().len());
        let mut meshes = Vec::new();
        for (value, origin, look) in flat {
            self.look = look;
            let moved = beside::translated(&value, by);
            self.collect(&moved, Layer::Unrolled, &None, &origin, &mut meshes);
        }
        self.scene
            .flag_since(segments, points, cnets_render::FLAG_BESIDE);
    }

    fn line_layer(&self, layer: Layer) -> (Layer, Color) {
        match layer {
            Layer::Axes => (Layer::Axes, AXIS_COLOR),
            Layer::Supports => (Layer::Supports, SUPPORT_COLOR),
            Layer::Unrolled => (Layer::Unrolled, CURVE_COLOR),
            _ => (Layer::Curves, CURVE_COLOR),
        }
    }

    /// A curve's colour: the node's picked colour for curves and unrolled outlines.
    fn curve_color(&self, layer: Layer, color: Color) -> Color {
        match (layer, self.look.color) {
            (Layer::Curves | Layer::Unrolled, Some(c)) => c,
            _ => color,
        }
    }

    /// The colour of a surface drawn in one colour: support layers translucent, else the node's
    /// picked colour or the default grey.
    fn uniform_color(&self, layer: Layer) -> Color {
        if layer == Layer::Supports {
            SUPPORT_COLOR
        } else {
            self.look.color.unwrap_or(palette::SURFACE)
        }
    }

    /// Distance mode: the vertex colours of a coloured mesh (`None`: not coloured — the side
    /// not coloured — or another mode).
    fn vertex_distance_colors(&self, key: usize) -> Option<Vec<Color>> {
        let map = self.distance_map?;
        let d = self.measured.as_ref()?.colours.get(&key)?;
        Some(d.iter().map(|&v| map.color(v)).collect())
    }

    /// The one colour of a mesh: translucent for the net when the reference is the side coloured
    /// (the reference stays visible through it), else `color`.
    fn net_color(&self, key: usize, color: Color) -> Color {
        match &self.measured {
            Some(m) if m.figures.side == DistanceSide::Reference && m.net.contains(&key) => {
                color.with_alpha(NET_OVER_REFERENCE_ALPHA)
            }
            _ => color,
        }
    }

    fn add_points(&mut self, points: &[DVec3], layer: Layer) {
        let layer = match layer {
            Layer::Apices => Layer::Apices,
            Layer::Unrolled => Layer::Unrolled,
            _ => Layer::Points,
        };
        if !self.opts.shows(layer) {
            return;
        }
        if layer == Layer::Apices {
            self.stats.apices += points.len();
        }
        let style = match layer {
            Layer::Apices => PointStyle::new(APEX_COLOR, 7.0),
            Layer::Unrolled => PointStyle::new(self.look.color.unwrap_or(CURVE_COLOR), 5.0),
            _ => PointStyle::new(Color::hex(0x333333), 5.0),
        };
        self.scene.add_points(points, style);
    }

    /// The faces' colours by class (counted for the legend), when the classes are known.
    fn class_colors(&mut self, classes: Option<&[FaceClass]>) -> Option<Vec<Color>> {
        let classes = classes?;
        self.any_classes = true;
        for class in classes {
            self.class_counts[class.index()] += 1;
        }
        Some(classes.iter().copied().map(class_color).collect())
    }

    fn add_quad_grid(&mut self, pending: PendingGrid, planarity: Vec<f64>) {
        let PendingGrid {
            grid,
            configurations,
            layer,
            origin,
            look,
            kind: _,
        } = pending;
        self.look = look;
        self.stats.vertices += grid.vertices.len();
        self.stats.faces += grid.quad_count();
        if !self.opts.shows(layer) {
            return;
        }
        // The construction's configurations beside the net, else the classes the net kept.
        let classes = match layer {
            Layer::Supports => None,
            _ => configurations
                .as_ref()
                .and_then(|c| face_classes(&grid, c))
                .or_else(|| grid.face_classes().map(<[FaceClass]>::to_vec)),
        };
        let colors: Option<Vec<Color>> = match (self.opts.color_mode, layer) {
            (_, Layer::Supports) => None,
            (ColorMode::Configuration, _) => self.class_colors(classes.as_deref()),
            (ColorMode::Planarity, _) => {
                let map = self.planarity_range.unwrap_or(self.opts.planarity_map());
                Some(planarity.iter().map(|&v| map.color(v)).collect())
            }
            (ColorMode::Plain | ColorMode::Distance, _) => None,
        };
        let uniform = self.uniform_color(layer);
        let by_distance = match layer {
            Layer::Supports => None,
            _ => self.vertex_distance_colors(Arc::as_ptr(&grid) as usize),
        };
        let faces = match (&colors, &by_distance) {
            (_, Some(c)) => FaceColors::PerVertex(c),
            (Some(c), None) => FaceColors::PerFace(c),
            (None, None) => {
                FaceColors::Uniform(self.net_color(Arc::as_ptr(&grid) as usize, uniform))
            }
        };
        let style = MeshStyle::new(faces)
            .edges(self.edges())
            .depth_layer(look.depth_layer);
        if self.scene.add_quad_grid(&grid, style).is_ok() {
            self.picks.meshes.push(PickMesh {
                node: origin.node,
                output: origin.output,
                item: origin.item,
                geometry: PickGeometry::Grid(grid),
                classes,
                planarity,
            });
        }
    }
}
