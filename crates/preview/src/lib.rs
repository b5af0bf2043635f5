//! What a graph shows: the geometry outputs of every node whose preview is on, turned into a render
//! [`Scene`], plus the figures shown with it (vertex count, max planarity, legend). Shared by the
//! editor's viewport and `cnets render`, so both show the same picture.
//!
//! Outputs are sorted into layers by type and port name, so each layer can be toggled:
//! quad / polygon meshes are surfaces (coloured by configuration class, planarity or plainly),
//! polylines and unnamed segment sets are curves (directrix, generatrix…), points named `apices`
//! are apices, segment sets named `…axes…` are torsion-free axes, anything named `…support…` is
//! a support layer. Lists (from nodes run per item) are flattened.

#[cfg(not(target_arch = "wasm32"))]
use std::time::Instant;
// std's clock panics on wasm32-unknown-unknown (the web editor); web-time reads the browser's.
#[cfg(target_arch = "wasm32")]
use web_time::Instant;

use cnets_engine::{Evaluator, Graph, Value};
use cnets_geometry::conenet::quad_planarity;
use cnets_geometry::fabrication::FaceClass;
use cnets_geometry::{DVec3, QuadGrid};
use cnets_render::palette::{self, ToleranceMap};
use cnets_render::{Color, FaceColors, LineStyle, MeshStyle, PointStyle, Scene};

/// How surfaces are coloured.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ColorMode {
    /// By face class (paper Fig. 5b: the configurations of a face's two support-strip quads) from
    /// the construction node's `configurations` output; plain when the node has none.
    #[default]
    Configuration,
    /// By per-face planarity (viridis on a log scale anchored to tolerances: planar below 1e-9
    /// relative, not planar from 1e-3; `ToleranceMap`).
    Planarity,
    /// One colour.
    Plain,
}

impl ColorMode {
    /// All modes, for menus.
    pub const ALL: [ColorMode; 3] = [
        ColorMode::Configuration,
        ColorMode::Planarity,
        ColorMode::Plain,
    ];

    /// Menu label.
    pub fn label(self) -> &'static str {
        match self {
            ColorMode::Configuration => "Configuration class",
            ColorMode::Planarity => "Planarity",
            ColorMode::Plain => "Plain",
        }
    }
}

/// A toggleable group of preview geometry.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Layer {
    /// Meshes.
    Surfaces,
    /// Mesh edges.
    Edges,
    /// Polylines and segment sets (directrix, generatrix, …).
    Curves,
    /// Cone apices.
    Apices,
    /// Torsion-free node axes.
    Axes,
    /// Support layers.
    Supports,
    /// Other points.
    Points,
}

impl Layer {
    /// All layers, for menus.
    pub const ALL: [Layer; 7] = [
        Layer::Surfaces,
        Layer::Edges,
        Layer::Curves,
        Layer::Apices,
        Layer::Axes,
        Layer::Supports,
        Layer::Points,
    ];

    /// Menu label.
    pub fn label(self) -> &'static str {
        match self {
            Layer::Surfaces => "Surfaces",
            Layer::Edges => "Edges",
            Layer::Curves => "Curves (directrix…)",
            Layer::Apices => "Apices",
            Layer::Axes => "Torsion-free axes",
            Layer::Supports => "Support layers",
            Layer::Points => "Points",
        }
    }

    /// Short name for command lines: surfaces, edges, curves, apices, axes, supports, points.
    pub fn name(self) -> &'static str {
        match self {
            Layer::Surfaces => "surfaces",
            Layer::Edges => "edges",
            Layer::Curves => "curves",
            Layer::Apices => "apices",
            Layer::Axes => "axes",
            Layer::Supports => "supports",
            Layer::Points => "points",
        }
    }

    /// The layer with this short name.
    pub fn parse(name: &str) -> Option<Layer> {
        Layer::ALL
            .into_iter()
            .find(|l| l.name().eq_ignore_ascii_case(name.trim()))
    }

    fn bit(self) -> u8 {
        1 << (self as u8)
    }
}

/// Display options of the viewport: colour mode and visible layers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PreviewOptions {
    /// Surface colouring.
    pub color_mode: ColorMode,
    layers: u8,
    /// The top of the planarity scale (see [`PreviewOptions::planarity_limit`]), as `f64` bits
    /// so the options stay `Eq`.
    planarity_limit: u64,
}

impl Default for PreviewOptions {
    fn default() -> Self {
        Self {
            color_mode: ColorMode::default(),
            layers: Layer::ALL.iter().fold(0, |acc, l| acc | l.bit()),
            planarity_limit: ToleranceMap::DEFAULT.limit.to_bits(),
        }
    }
}

/// The smallest and largest planarity limit a designer can set (the scale's bottom, 1e-9
/// relative, stays the anchor).
pub const PLANARITY_LIMIT_RANGE: (f64, f64) = (1e-8, 1.0);

impl PreviewOptions {
    /// The user-set top of the planarity colour scale: faces from this relative planarity up are
    /// "not planar" (default 1e-3). The bottom stays anchored at 1e-9 ([`ToleranceMap::DEFAULT`]).
    pub fn planarity_limit(&self) -> f64 {
        f64::from_bits(self.planarity_limit)
    }

    /// Sets the top of the planarity scale; refused (false) unless finite and within
    /// [`PLANARITY_LIMIT_RANGE`].
    pub fn set_planarity_limit(&mut self, limit: f64) -> bool {
        let (lo, hi) = PLANARITY_LIMIT_RANGE;
        if !(limit.is_finite() && (lo..=hi).contains(&limit)) {
            return false;
        }
        self.planarity_limit = limit.to_bits();
        true
    }

    /// The planarity colour scale: planar below 1e-9, not planar from the user-set limit.
    pub fn planarity_map(&self) -> ToleranceMap {
        ToleranceMap {
            planar: ToleranceMap::DEFAULT.planar,
            limit: self.planarity_limit(),
        }
    }

    /// Whether a layer is shown.
    pub fn shows(&self, layer: Layer) -> bool {
        self.layers & layer.bit() != 0
    }

    /// Shows or hides a layer.
    pub fn set(&mut self, layer: Layer, on: bool) {
        if on {
            self.layers |= layer.bit();
        } else {
            self.layers &= !layer.bit();
        }
    }
}

/// The legend to draw next to the viewport.
#[derive(Clone, Debug, PartialEq, Default)]
pub enum LegendInfo {
    /// Nothing coloured.
    #[default]
    None,
    /// Face classes with their face counts (classes that occur).
    Classes(Vec<(FaceClass, usize)>),
    /// A planarity colour scale.
    Planarity(cnets_render::Legend),
}

/// Figures about the previewed geometry.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct PreviewStats {
    /// Vertices of all previewed meshes.
    pub vertices: usize,
    /// Faces of all previewed meshes.
    pub faces: usize,
    /// Largest face planarity over all previewed quad meshes (`None` without quad meshes).
    pub max_planarity: Option<f64>,
    /// Legend of the surface colours.
    pub legend: LegendInfo,
    /// Apex points drawn (the apices layer shown).
    pub apices: usize,
    /// Time spent building the scene, in milliseconds.
    pub build_ms: f64,
}

/// The configuration class of a face in the paper's notation: the (±±) configurations of its two
/// construction planes (CNets, Fig. 4).
pub fn paper_class(class: FaceClass) -> &'static str {
    match class {
        FaceClass::Convex => "(++)(++)",
        FaceClass::NonConvex => "(++)(−−)",
        FaceClass::MinusMinus => "(−−)(−−)",
        FaceClass::NegativeApex => "(+−)/(−+)",
        FaceClass::Unclassified => "—",
    }
}

/// The colour apices are drawn in.
pub const APEX_COLOR: Color = palette::POINT;

/// What an apex point is, for legends.
pub const APEX_LEGEND: &str = "apex of a strip's cone";

/// The surface legend as a title and rows of (swatch colour, words): face classes in the paper's
/// notation with their words and face counts (`(++)(++)  convex  170`), or the planarity scale
/// (`planar (< 1e-9)` … `not planar (≥ 1e-3)`, top row the largest). `None` without one.
pub fn legend_rows(legend: &LegendInfo) -> Option<(String, Vec<(Color, String)>)> {
    match legend {
        LegendInfo::None => None,
        LegendInfo::Classes(classes) => Some((
            "configuration".to_string(),
            classes
                .iter()
                .map(|&(c, n)| {
                    (
                        class_color(c),
                        format!("{}  {}  {n}", paper_class(c), c.name()),
                    )
                })
                .collect(),
        )),
        LegendInfo::Planarity(l) => Some((
            l.title.clone(),
            l.stops
                .iter()
                .enumerate()
                .rev()
                .map(|(k, (v, c))| {
                    (
                        *c,
                        l.labels
                            .get(k)
                            .cloned()
                            .unwrap_or_else(|| format!("{v:.0e}")),
                    )
                })
                .collect(),
        )),
    }
}

/// Builds the preview scene from the evaluator's results for `graph`.
pub fn build_scene(
    graph: &Graph,
    eval: &Evaluator,
    opts: &PreviewOptions,
) -> (Scene, PreviewStats) {
    let start = Instant::now();
    let mut b = Builder {
        scene: Scene::new(),
        stats: PreviewStats::default(),
        opts: *opts,
        class_counts: [0; 5],
        any_classes: false,
        planarity_range: None,
    };
    // Planarity colours need one range over all meshes: collect meshes first.
    let mut meshes: Vec<(std::sync::Arc<QuadGrid>, Option<Value>, Layer)> = Vec::new();
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
            b.collect(value, layer, &configurations, &mut meshes);
        }
    }
    // Per-face planarity of every quad mesh (for the figure, and the colours in that mode).
    let planarities: Vec<Vec<f64>> = meshes
        .iter()
        .map(|(m, _, _)| m.quads().map(|(_, q)| quad_planarity(q)).collect())
        .collect();
    let max = planarities
        .iter()
        .flatten()
        .copied()
        .filter(|v| v.is_finite())
        .fold(None, |acc: Option<f64>, v| {
            Some(acc.map_or(v, |a| a.max(v)))
        });
    b.stats.max_planarity = max;
    if opts.color_mode == ColorMode::Planarity {
        // Anchored to tolerances, not fitted to the data (rounding noise is not a patchwork).
        b.planarity_range = Some(opts.planarity_map());
    }
    for ((mesh, configurations, layer), planarity) in meshes.iter().zip(&planarities) {
        b.add_quad_grid(mesh, configurations.as_ref(), planarity, *layer);
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
    (b.scene, b.stats)
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
}

/// Support layers are drawn translucent so the surface they support stays visible.
const SUPPORT_COLOR: Color = Color::hex(0xc9a66b).with_alpha(170);
const AXIS_COLOR: Color = Color::hex(0x2a9d5c);
const CURVE_COLOR: Color = palette::LINE;

impl Builder {
    fn edges(&self) -> Option<LineStyle> {
        self.opts.shows(Layer::Edges).then(MeshStyle::default_edges)
    }

    fn collect(
        &mut self,
        value: &Value,
        layer: Layer,
        configurations: &Option<Value>,
        meshes: &mut Vec<(std::sync::Arc<QuadGrid>, Option<Value>, Layer)>,
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
                        self.collect(item, layer, &confs, meshes);
                    }
                }
            }
            Value::QuadMesh(grid) => {
                let layer = if layer == Layer::Supports {
                    layer
                } else {
                    Layer::Surfaces
                };
                meshes.push((grid.clone(), configurations.clone(), layer));
            }
            Value::Mesh(mesh) => {
                let show = if layer == Layer::Supports {
                    self.opts.shows(Layer::Supports)
                } else {
                    self.opts.shows(Layer::Surfaces)
                };
                self.stats.vertices += mesh.vertices.len();
                self.stats.faces += mesh.face_count();
                if show {
                    let color = if layer == Layer::Supports {
                        SUPPORT_COLOR
                    } else {
                        palette::SURFACE
                    };
                    let style = MeshStyle::new(FaceColors::Uniform(color)).edges(self.edges());
                    let _ = self.scene.add_polygon_mesh(mesh, style);
                }
            }
            Value::Polyline(p) => {
                let (layer, color) = self.line_layer(layer);
                if self.opts.shows(layer) {
                    self.scene.add_polyline(p, LineStyle::new(color, 2.5));
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

    fn add_quad_grid(
        &mut self,
        grid: &QuadGrid,
        configurations: Option<&Value>,
        planarity: &[f64],
        layer: Layer,
    ) {
        self.stats.vertices += grid.vertices.len();
        self.stats.faces += grid.quad_count();
        if !self.opts.shows(layer) {
            return;
        }
        let colors: Option<Vec<Color>> = match (self.opts.color_mode, layer) {
            (_, Layer::Supports) => None,
            (ColorMode::Configuration, _) => configurations.and_then(|c| {
                let classes = face_classes(grid, c)?;
                self.any_classes = true;
                for class in &classes {
                    self.class_counts[class.index()] += 1;
                }
                Some(classes.into_iter().map(class_color).collect())
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
        let _ = self
            .scene
            .add_quad_grid(grid, MeshStyle::new(faces).edges(self.edges()));
    }
}

/// The render colour of a face class (the same colours the glTF export uses).
pub fn class_color(class: FaceClass) -> Color {
    let c = class.colour();
    Color::from_f32([c.x as f32, c.y as f32, c.z as f32, 1.0])
}

/// The class of every face of `grid` (row-major over quads) from a construction node's
/// `configurations` output (N lists of M−1 labels), as [`cnets_geometry::fabrication::face_classes`]
/// defines it. `None` when the value is not such a table or does not fit the grid.
pub fn face_classes(grid: &QuadGrid, configurations: &Value) -> Option<Vec<FaceClass>> {
    let labels: Vec<Vec<String>> = configurations
        .as_list()?
        .iter()
        .map(|row| {
            row.as_list()?
                .iter()
                .map(|v| match v {
                    Value::Text(t) => Some(t.to_string()),
                    _ => None,
                })
                .collect()
        })
        .collect::<Option<_>>()?;
    cnets_geometry::fabrication::face_classes(grid, &labels).ok()
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_planarity_limit_is_user_set_and_named_in_the_legend() {
        let mut o = PreviewOptions::default();
        assert_eq!(o.planarity_limit(), 1e-3);
        assert!(o.set_planarity_limit(1e-4));
        assert!(!o.set_planarity_limit(f64::NAN) && !o.set_planarity_limit(2.0));
        assert!(!o.set_planarity_limit(1e-12), "below the planar anchor");
        let m = o.planarity_map();
        assert_eq!((m.planar, m.limit), (1e-9, 1e-4));
        assert_eq!(m.normalize(1e-4), 1.0);
        assert!(m.normalize(1e-5) < 1.0 && m.normalize(1e-5) > 0.0);
        let (title, rows) = legend_rows(&LegendInfo::Planarity(m.legend())).unwrap();
        assert!(!title.is_empty());
        assert!(rows[0].1.contains("1e-4"), "top row: {:?}", rows[0]);
        assert!(rows.last().unwrap().1.starts_with("planar"), "{rows:?}");
        let (_, classes) = legend_rows(&LegendInfo::Classes(vec![
            (FaceClass::Convex, 3),
            (FaceClass::NegativeApex, 1),
        ]))
        .unwrap();
        assert_eq!(classes[0].1, "(++)(++)  convex  3");
        assert!(classes[1].1.starts_with("(+−)/(−+)"), "{classes:?}");
    }

    use super::*;

    fn grid(rows: usize, cols: usize) -> QuadGrid {
        let vertices = (0..rows)
            .flat_map(|i| (0..cols).map(move |j| DVec3::new(j as f64, i as f64, 0.0)))
            .collect();
        QuadGrid {
            rows,
            cols,
            wrap_rows: false,
            wrap_cols: false,
            vertices,
        }
    }

    fn table(rows: usize, labels: &[&str]) -> Value {
        Value::list(
            (0..rows)
                .map(|_| Value::list(labels.iter().map(Value::text).collect()))
                .collect(),
        )
    }

    #[test]
    fn faces_are_classed_by_their_two_support_strip_quads() {
        let g = grid(3, 4); // interior vertex columns 1 and 2
        let classes = face_classes(&g, &table(3, &["++", "--"])).unwrap();
        assert_eq!(classes.len(), 2 * 3);
        // An older table without column 0 (M − 2 labels): quad column 0 is unclassified; column 1
        // pairs (++, ++); column 2 pairs (--, --).
        assert_eq!(
            classes[..3],
            [
                FaceClass::Unclassified,
                FaceClass::Convex,
                FaceClass::MinusMinus
            ]
        );
        assert!(
            face_classes(&g, &table(2, &["++", "--"])).is_none(),
            "row count must match"
        );
        // The constructions' full tables (M − 1 labels) class column 0 as well.
        let full = face_classes(&g, &table(3, &["--", "++", "--"])).unwrap();
        assert_eq!(
            full[..3],
            [
                FaceClass::MinusMinus,
                FaceClass::Convex,
                FaceClass::MinusMinus
            ]
        );
        assert_eq!(class_color(FaceClass::NonConvex), {
            let c = FaceClass::NonConvex.colour();
            Color::from_f32([c.x as f32, c.y as f32, c.z as f32, 1.0])
        });
    }

    #[test]
    fn layers_by_port_name_and_toggles() {
        assert_eq!(layer_of("apices"), Layer::Apices);
        assert_eq!(layer_of("node_axes"), Layer::Axes);
        assert_eq!(layer_of("support_layers"), Layer::Supports);
        assert_eq!(layer_of("mesh"), Layer::Surfaces);
        let mut o = PreviewOptions::default();
        assert!(Layer::ALL.iter().all(|&l| o.shows(l)));
        o.set(Layer::Apices, false);
        assert!(!o.shows(Layer::Apices) && o.shows(Layer::Axes));
    }
}
