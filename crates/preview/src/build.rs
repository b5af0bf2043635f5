//! Building the render scene (and the figures and pick records shown with it) from the previewed
//! outputs of a graph.

#[cfg(not(target_arch = "wasm32"))]
use std::time::Instant;
// std's clock panics on wasm32-unknown-unknown (the web editor); web-time reads the browser's.
#[cfg(target_arch = "wasm32")]
use web_time::Instant;

use cnets_engine::{Evaluator, Graph, Value};
use cnets_geometry::conenet::quad_planarity;
use cnets_geometry::fabrication::{FaceClass, face_planarity};
use cnets_geometry::{DVec3, QuadGrid};
use cnets_render::palette::{self, ToleranceMap};
use cnets_render::{Color, FaceColors, LineStyle, MeshStyle, PointStyle, Scene};
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
    /// Time spent building the scene, in milliseconds.
    pub build_ms: f64,
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
    };
    // Planarity colours need one range over all meshes: collect meshes first.
    let mut meshes: Vec<PendingGrid> = Vec::new();
    for (index, node) in graph.nodes() {
        if !node.preview || !node.enabled {
            continue;
        }
        let Some(outputs) = eval.result_at(graph, index).and_then(|r| r.outputs()) else {
            continue;
        };
        let configurations = node
            .def
            .output_index("configurations")
            .and_then(|k| outputs.values.get(k))
            .cloned();
        // Support-layer nodes (e.g. `cnets.conical_support`) name their output just `mesh`.
        let support_node = node.def.id.contains("support");
        for (port, value) in node.def.outputs.iter().zip(&outputs.values) {
            let layer = if support_node {
                Layer::Supports
            } else {
                layer_of(&port.name)
            };
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
        _ => LegendInfo::None,
    };
    b.stats.build_ms = start.elapsed().as_secs_f64() * 1e3;
    Preview {
        scene: b.scene,
        stats: b.stats,
        picks: b.picks,
    }
}

/// The layer an output belongs to, by its port name.
pub fn layer_of(name: &str) -> Layer {
    let n = name.to_ascii_lowercase();
    if n.contains("support") {
        Layer::Supports
    } else if n.contains("axes") || n.contains("axis") {
        Layer::Axes
    } else if n.contains("apex") || n.contains("apices") {
        Layer::Apices
    } else {
        Layer::Surfaces
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
}

/// Support layers are drawn translucent so the surface they support stays visible.
const SUPPORT_COLOR: Color = Color::hex(0xc9a66b).with_alpha(170);
const AXIS_COLOR: Color = Color::hex(0x2a9d5c);
const CURVE_COLOR: Color = palette::LINE;

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
                    let color = if layer == Layer::Supports {
                        SUPPORT_COLOR
                    } else {
                        palette::SURFACE
                    };
                    let colors: Option<Vec<Color>> = (self.opts.color_mode == ColorMode::Planarity
                        && layer != Layer::Supports
                        && planarity.len() == mesh.face_count())
                    .then(|| {
                        let map = self.opts.planarity_map();
                        planarity.iter().map(|&v| map.color(v)).collect()
                    });
                    let faces = match &colors {
                        Some(c) => FaceColors::PerFace(c),
                        None => FaceColors::Uniform(color),
                    };
                    let style = MeshStyle::new(faces).edges(self.edges());
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
            _ => (Layer::Curves, CURVE_COLOR),
        }
    }

    fn add_points(&mut self, points: &[DVec3], layer: Layer) {
        let layer = match layer {
            Layer::Apices => Layer::Apices,
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
        } = pending;
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
            (ColorMode::Plain, _) => None,
        };
        let uniform = if layer == Layer::Supports {
            SUPPORT_COLOR
        } else {
            palette::SURFACE
        };
        let faces = match &colors {
            Some(c) => FaceColors::PerFace(c),
            None => FaceColors::Uniform(uniform),
        };
        if self
            .scene
            .add_quad_grid(&grid, MeshStyle::new(faces).edges(self.edges()))
            .is_ok()
        {
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
