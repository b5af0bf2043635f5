//! Building the render scene (and the figures and pick records shown with it) from the previewed
//! outputs of a graph.

#[cfg(not(target_arch = "wasm32"))]
use std::time::Instant;
// std's clock panics on wasm32-unknown-unknown (the web editor); web-time reads the browser's.
#[cfg(target_arch = "wasm32")]
use web_time::Instant;

use cnets_engine::{Evaluator, Graph, Layer as HintLayer, PortDef, Value};
use cnets_geometry::conenet::quad_planarity;
use cnets_geometry::fabrication::{FaceClass, face_planarity};
use cnets_geometry::mesh_query::MeshQuery;
use cnets_geometry::{DVec3, PolygonMesh, QuadGrid};
use cnets_render::palette::{self, SequentialMap, ToleranceMap};
use cnets_render::{Color, FaceColors, LineStyle, MeshStyle, PointStyle, Scene};
use std::collections::HashMap;
use std::sync::Arc;

use crate::classes::{class_color, face_classes};
use crate::legend::{APEX_COLOR, LegendInfo};
use crate::options::{ColorMode, Layer, PreviewOptions};
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
}

/// How one node's geometry is drawn: its picked colour (if any) and its depth layer.
#[derive(Clone, Copy, Default)]
struct Look {
    color: Option<Color>,
    depth_layer: u32,
}

/// Figures about the previewed geometry.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct PreviewStats {
    /// Vertices of all previewed meshes.
    pub vertices: usize,
    /// Faces of all previewed meshes.
    pub faces: usize,
    /// Largest face planarity over all previewed meshes, quad grids and polygon meshes (`None`
    /// without faces).
    pub max_planarity: Option<f64>,
    /// The mesh `max_planarity` is for (`node.output`, `[item]` in a list), when more than one
    /// mesh is previewed (`None` with one: the figure is plainly its own).
    pub max_planarity_mesh: Option<String>,
    /// Legend of the surface colours.
    pub legend: LegendInfo,
    /// Apex points drawn (the apices layer shown).
    pub apices: usize,
    /// In [`ColorMode::Distance`]: the reference (`node.output`) and the largest and root mean
    /// square distance of the other previewed meshes' vertices to it (`None` in other modes, or
    /// without a reference mesh or other meshes).
    pub distance: Option<DistanceFigures>,
    /// Time spent building the scene, in milliseconds.
    pub build_ms: f64,
}

/// The figures of [`ColorMode::Distance`].
#[derive(Clone, Debug, PartialEq)]
pub struct DistanceFigures {
    /// The reference node.
    pub reference: String,
    /// Largest vertex distance to it, in model units (metres).
    pub max: f64,
    /// Root mean square of the vertex distances.
    pub rms: f64,
    /// Vertices measured.
    pub vertices: usize,
}

/// The reference of the distance mode: its node and the closest-point hierarchy of its mesh.
struct DistanceReference {
    node: String,
    query: MeshQuery,
}

/// Calls `f` on every quad grid and polygon mesh in a value (lists walked).
fn each_mesh(value: &Value, f: &mut dyn FnMut(MeshRef<'_>)) {
    match value {
        Value::List(items) => items.iter().for_each(|v| each_mesh(v, f)),
        Value::QuadMesh(g) => f(MeshRef::Grid(g)),
        Value::Mesh(m) => f(MeshRef::Mesh(m)),
        _ => {}
    }
}

/// A mesh found in an output.
enum MeshRef<'a> {
    Grid(&'a Arc<QuadGrid>),
    Mesh(&'a Arc<PolygonMesh>),
}

impl MeshRef<'_> {
    fn vertices(&self) -> &[DVec3] {
        match self {
            MeshRef::Grid(g) => &g.vertices,
            MeshRef::Mesh(m) => &m.vertices,
        }
    }

    /// The address of the shared payload: the key of its distances.
    fn key(&self) -> usize {
        match self {
            MeshRef::Grid(g) => Arc::as_ptr(g) as usize,
            MeshRef::Mesh(m) => Arc::as_ptr(m) as usize,
        }
    }
}

/// The reference mesh of the distance mode: the first mesh output of the node with uid `uid`.
fn distance_reference(graph: &Graph, eval: &Evaluator, uid: u64) -> Option<DistanceReference> {
    let (index, node) = graph.nodes().find(|(_, n)| n.uid() == uid)?;
    let outputs = eval.result_at(graph, index)?.outputs()?;
    let mut mesh: Option<PolygonMesh> = None;
    for value in &outputs.values {
        each_mesh(value, &mut |m| {
            if mesh.is_none() {
                mesh = Some(match m {
                    MeshRef::Grid(g) => PolygonMesh::from(g.as_ref()),
                    MeshRef::Mesh(m) => m.as_ref().clone(),
                });
            }
        });
    }
    let query = MeshQuery::new(&mesh?).ok()?;
    Some(DistanceReference {
        node: node.id.clone(),
        query,
    })
}

/// A length in metres for legends, to three significant digits (`0 m`, `0.0450 m`, `1.25 m`).
pub fn format_metres(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v} m");
    }
    let digits = (2 - v.abs().log10().floor() as i32).clamp(0, 12) as usize;
    format!("{v:.digits$} m")
}

/// The legend of the distance mode: 0 … `max` in metres, six stops.
pub fn distance_legend(reference: &str, max: f64) -> cnets_render::Legend {
    let mut legend = SequentialMap::new(0.0, max).legend(&format!("distance to {reference}"), 6);
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
        planarity_max: None,
        planarity_meshes: 0,
        look: Look::default(),
        distances: HashMap::new(),
        distance_map: None,
    };
    // The distance mode measures every other previewed mesh against the reference first: one
    // scale over all of them.
    if opts.color_mode == ColorMode::Distance
        && let Some(reference) = opts
            .distance_to
            .and_then(|uid| distance_reference(graph, eval, uid))
    {
        b.measure_distances(graph, eval, &reference);
    }
    // Planarity colours need one range over all meshes: collect meshes first.
    let mut meshes: Vec<PendingGrid> = Vec::new();
    let mut next_layer = 0u32;
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
        let configurations = node
            .def
            .output_index("configurations")
            .and_then(|k| outputs.values.get(k))
            .cloned();
        for (port, value) in node.def.outputs.iter().zip(&outputs.values) {
            let layer = layer_of(port);
            let origin = Origin {
                node: node.id.clone(),
                output: port.name.to_string(),
                item: None,
            };
            b.collect(value, layer, &configurations, &origin, &mut meshes);
        }
    }
    // Per-face planarity of every quad mesh (for the figure, and the colours in that mode).
    let planarities: Vec<Vec<f64>> = meshes
        .iter()
        .map(|m| m.grid.quads().map(|(_, q)| quad_planarity(q)).collect())
        .collect();
    for (m, p) in meshes.iter().zip(&planarities) {
        b.note_planarity(p, &m.origin);
    }
    b.stats.max_planarity = b.planarity_max.as_ref().map(|(v, _)| *v);
    if b.planarity_meshes > 1 {
        b.stats.max_planarity_mesh = b.planarity_max.take().map(|(_, name)| name);
    }
    if opts.color_mode == ColorMode::Planarity {
        // Anchored to tolerances, not fitted to the data (rounding noise is not a patchwork).
        b.planarity_range = Some(opts.planarity_map());
    }
    for (pending, planarity) in meshes.into_iter().zip(planarities) {
        b.add_quad_grid(pending, planarity);
    }
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
            Some(d) => LegendInfo::Distance(distance_legend(&d.reference, d.max)),
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

/// The layer an output is drawn in, from the port's declared preview layer
/// ([`cnets_engine::PortHint::layer`]); geometry without one is a surface (curves and points
/// find their own layers by type).
pub fn layer_of(port: &PortDef) -> Layer {
    match port.hint.layer {
        HintLayer::Support => Layer::Supports,
        HintLayer::Axes => Layer::Axes,
        HintLayer::Apices => Layer::Apices,
        HintLayer::Fabrication => Layer::Unrolled,
        HintLayer::Auto => Layer::Surfaces,
    }
}

struct Builder {
    scene: Scene,
    stats: PreviewStats,
    opts: PreviewOptions,
    class_counts: [usize; 5],
    any_classes: bool,
    planarity_range: Option<ToleranceMap>,
    picks: Picks,
    /// The largest face planarity so far and the mesh it is on.
    planarity_max: Option<(f64, String)>,
    /// Meshes with faces whose planarity was noted.
    planarity_meshes: usize,
    /// The colour and depth layer of the node being collected.
    look: Look,
    /// Distance mode: each measured mesh's vertex distances, by payload address.
    distances: HashMap<usize, Vec<f64>>,
    /// Distance mode: the colour scale (0 … the largest distance).
    distance_map: Option<SequentialMap>,
}

/// Support layers are drawn translucent so the surface they support stays visible.
const SUPPORT_COLOR: Color = Color::hex(0xc9a66b).with_alpha(170);
const AXIS_COLOR: Color = Color::hex(0x2a9d5c);
const CURVE_COLOR: Color = palette::LINE;

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
    /// Distance mode: the vertex distances of every previewed mesh but the reference's own, their
    /// figures and the colour scale.
    fn measure_distances(
        &mut self,
        graph: &Graph,
        eval: &Evaluator,
        reference: &DistanceReference,
    ) {
        let (mut max, mut sum2, mut count) = (0.0f64, 0.0f64, 0usize);
        for (index, node) in graph.nodes() {
            if !node.preview || !node.enabled || node.id == reference.node {
                continue;
            }
            let Some(outputs) = eval.result_at(graph, index).and_then(|r| r.outputs()) else {
                continue;
            };
            for (port, value) in node.def.outputs.iter().zip(&outputs.values) {
                if !matches!(layer_of(port), Layer::Surfaces) {
                    continue;
                }
                each_mesh(value, &mut |m| {
                    if self.distances.contains_key(&m.key()) {
                        return;
                    }
                    let Ok(closest) = reference.query.closest_all(m.vertices()) else {
                        return;
                    };
                    let d: Vec<f64> = closest.iter().map(|c| c.distance).collect();
                    for &v in &d {
                        max = max.max(v);
                        sum2 += v * v;
                    }
                    count += d.len();
                    self.distances.insert(m.key(), d);
                });
            }
        }
        if count > 0 {
            self.distance_map = Some(SequentialMap::new(0.0, max));
            self.stats.distance = Some(DistanceFigures {
                reference: reference.node.clone(),
                max,
                rms: (sum2 / count as f64).sqrt(),
                vertices: count,
            });
        }
    }

    /// Counts a mesh's face planarities in the figure (the largest, and which mesh it is on).
    fn note_planarity(&mut self, planarity: &[f64], origin: &Origin) {
        if planarity.is_empty() {
            return;
        }
        self.planarity_meshes += 1;
        let Some(max) = planarity
            .iter()
            .copied()
            .filter(|v| v.is_finite())
            .reduce(f64::max)
        else {
            return;
        };
        if self.planarity_max.as_ref().is_none_or(|(m, _)| max > *m) {
            self.planarity_max = Some((max, origin.name()));
        }
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
                self.note_planarity(&planarity, origin);
                if show {
                    let color = self.uniform_color(layer);
                    let colors: Option<Vec<Color>> = (self.opts.color_mode == ColorMode::Planarity
                        && layer != Layer::Supports
                        && planarity.len() == mesh.face_count())
                    .then(|| {
                        let map = self.opts.planarity_map();
                        planarity.iter().map(|&v| map.color(v)).collect()
                    });
                    let by_distance = match layer {
                        Layer::Supports => None,
                        _ => self.vertex_distance_colors(Arc::as_ptr(mesh) as usize),
                    };
                    let faces = match (&colors, &by_distance) {
                        (_, Some(c)) => FaceColors::PerVertex(c),
                        (Some(c), None) => FaceColors::PerFace(c),
                        (None, None) => FaceColors::Uniform(color),
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
                            classes: None,
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

    /// Distance mode: the vertex colours of a measured mesh (`None`: not measured — the reference
    /// itself — or another mode).
    fn vertex_distance_colors(&self, key: usize) -> Option<Vec<Color>> {
        let map = self.distance_map?;
        let d = self.distances.get(&key)?;
        Some(d.iter().map(|&v| map.color(v)).collect())
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

    fn add_quad_grid(&mut self, pending: PendingGrid, planarity: Vec<f64>) {
        let PendingGrid {
            grid,
            configurations,
            layer,
            origin,
            look,
        } = pending;
        self.look = look;
        self.stats.vertices += grid.vertices.len();
        self.stats.faces += grid.quad_count();
        if !self.opts.shows(layer) {
            return;
        }
        let classes = match layer {
            Layer::Supports => None,
            _ => configurations.as_ref().and_then(|c| face_classes(&grid, c)),
        };
        let colors: Option<Vec<Color>> = match (self.opts.color_mode, layer) {
            (_, Layer::Supports) => None,
            (ColorMode::Configuration, _) => classes.as_ref().map(|classes| {
                self.any_classes = true;
                for class in classes {
                    self.class_counts[class.index()] += 1;
                }
                classes.iter().copied().map(class_color).collect()
            }),
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
            (None, None) => FaceColors::Uniform(uniform),
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
