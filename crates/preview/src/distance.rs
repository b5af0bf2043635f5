//! The distance colouring ([`ColorMode::Distance`](crate::ColorMode::Distance)): the reference
//! mesh, the net measured against it, the figures — the fit objective's symmetric, area-weighted
//! measure (`measure.surface_distance`'s `symmetric`, computed by
//! [`cnets_geometry::surface_fit::surface_distances`]) — and the vertex distances the colours
//! show, on the net or on the reference ([`DistanceSide`]). Also the reference a graph offers by
//! default: never a mesh of the net itself.

use std::collections::{HashMap, HashSet};
use std::sync::Arc;

use cnets_engine::{Evaluator, Graph, NodeInstance, Role, Value, ValueType};
use cnets_geometry::PolygonMesh;
use cnets_geometry::mesh_query::MeshQuery;
use cnets_geometry::surface_fit::{Directions, MAX_SAMPLES, SurfaceDistances, surface_distances};

use crate::build::layer_of;
use crate::options::{DistanceSide, Layer};

/// The figures of the distance mode: the symmetric, area-weighted distance between the net (every
/// previewed mesh but the reference's, taken as one surface) and the reference, each direction on
/// its own, and what the colours show.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct DistanceFigures {
    /// The reference node.
    pub reference: String,
    /// The meshes measured against it (the net), `node.output` (`[item]` in a list).
    pub net: Vec<String>,
    /// The root of the symmetric measure, √(½ (to + from)) with to and from the area-weighted
    /// mean squared distances of each direction: the fit objective's `symmetric` as a length, in
    /// model units (metres).
    pub rms: f64,
    /// The sampled Hausdorff distance: the larger of the two directions' largest distances.
    pub max: f64,
    /// Net → reference: root of the area-weighted mean squared distance of the net's faces.
    pub net_rms: f64,
    /// Net → reference: the largest distance (face samples and vertices).
    pub net_max: f64,
    /// Reference → net: root of the area-weighted mean squared distance of the reference's faces.
    pub reference_rms: f64,
    /// Reference → net: the largest distance (a gap where the reference is far from the net).
    pub reference_max: f64,
    /// The caps on sub-triangles per triangle edge on the net and on the reference
    /// ([`samples_for`]).
    pub samples: (usize, usize),
    /// What the colours show: the net's or the reference's vertices.
    pub side: DistanceSide,
    /// Vertices coloured.
    pub vertices: usize,
    /// The largest coloured vertex distance: the top of the colour scale.
    pub colour_max: f64,
}

impl DistanceFigures {
    /// The net's name: its one mesh, or `N meshes`.
    pub fn net_name(&self) -> String {
        match self.net.as_slice() {
            [one] => one.clone(),
            many => format!("{} meshes", many.len()),
        }
    }

    /// The legend's title: `distance to hull` (the net coloured) or `hull: distance to the net`.
    pub fn legend_title(&self) -> String {
        match self.side {
            DistanceSide::Net => format!("distance to {}", self.reference),
            DistanceSide::Reference => format!("{}: distance to the net", self.reference),
        }
    }
}

/// Sub-triangles a side of the figures may be split into at most: the cap on sub-triangles per
/// triangle edge ([`surface_distances`]' `samples`) is chosen so a mesh's triangles give at most
/// about this many (from 2, the fit objective's default, to [`MAX_SAMPLES`]).
pub const SAMPLE_BUDGET: usize = 40_000;

/// The cap on sub-triangles per triangle edge for a mesh of `triangles` fan triangles: the
/// largest n with n² · triangles ≤ [`SAMPLE_BUDGET`], within 2 … [`MAX_SAMPLES`].
pub fn samples_for(triangles: usize) -> usize {
    let n = (SAMPLE_BUDGET as f64 / triangles.max(1) as f64)
        .sqrt()
        .floor() as usize;
    n.clamp(2, MAX_SAMPLES)
}

/// The fan triangles of a polygon mesh.
fn triangle_count(mesh: &PolygonMesh) -> usize {
    mesh.faces().map(|f| f.len().saturating_sub(2)).sum()
}

/// The reference of the distance mode: its node and its first mesh output.
pub(crate) struct DistanceReference {
    /// The node's id.
    pub node: String,
    /// The output the mesh came from.
    pub output: String,
    /// The mesh as its value (a quad grid or a polygon mesh), to draw it.
    pub value: Value,
    /// The mesh as a polygon mesh, to measure it.
    pub mesh: PolygonMesh,
    /// Its payload address (the key of its vertex distances).
    pub key: usize,
}

/// The payload address of a mesh value (`None` for anything else).
pub(crate) fn mesh_key(value: &Value) -> Option<usize> {
    match value {
        Value::QuadMesh(g) => Some(Arc::as_ptr(g) as usize),
        Value::Mesh(m) => Some(Arc::as_ptr(m) as usize),
        _ => None,
    }
}

/// The first mesh in a value (lists walked).
fn first_mesh(value: &Value) -> Option<&Value> {
    match value {
        Value::List(items) if items.as_packed().is_none() => items.iter().find_map(first_mesh),
        Value::QuadMesh(_) | Value::Mesh(_) => Some(value),
        _ => None,
    }
}

/// Every mesh in a value with its item number in the innermost list (`None` outside lists).
fn each_mesh<'a>(
    value: &'a Value,
    item: Option<usize>,
    f: &mut dyn FnMut(&'a Value, Option<usize>),
) {
    match value {
        Value::List(items) if items.as_packed().is_none() => {
            for (k, v) in items.iter().enumerate() {
                each_mesh(v, Some(k), f);
            }
        }
        Value::QuadMesh(_) | Value::Mesh(_) => f(value, item),
        _ => {}
    }
}

fn polygon_mesh(value: &Value) -> Option<PolygonMesh> {
    match value {
        Value::QuadMesh(g) => Some(PolygonMesh::from(g.as_ref())),
        Value::Mesh(m) => Some(m.as_ref().clone()),
        _ => None,
    }
}

/// The reference mesh of the distance mode: the first mesh output of the node with uid `uid`; the
/// status text saying why there is none.
pub(crate) fn distance_reference(
    graph: &Graph,
    eval: &Evaluator,
    uid: u64,
) -> Result<DistanceReference, String> {
    let (index, node) = graph
        .nodes()
        .find(|(_, n)| n.uid() == uid)
        .ok_or("the reference node is gone: pick another mesh")?;
    let missing = || {
        format!(
            "the reference '{}' has no mesh (not evaluated yet, failed, or no mesh output)",
            node.id
        )
    };
    let outputs = eval
        .result_at(graph, index)
        .and_then(|r| r.outputs())
        .ok_or_else(missing)?;
    let (output, value) = node
        .def
        .outputs
        .iter()
        .zip(&outputs.values)
        .find_map(|(p, v)| Some((p.name.to_string(), first_mesh(v)?.clone())))
        .ok_or_else(missing)?;
    let mesh = polygon_mesh(&value).ok_or_else(missing)?;
    Ok(DistanceReference {
        node: node.id.clone(),
        output,
        key: mesh_key(&value).unwrap_or_default(),
        value,
        mesh,
    })
}

/// What the distance mode measured.
pub(crate) struct Measured {
    /// The figures.
    pub figures: DistanceFigures,
    /// The vertex distances of every coloured mesh, by payload address.
    pub colours: HashMap<usize, Vec<f64>>,
    /// The payload addresses of the net's meshes.
    pub net: HashSet<usize>,
}

/// Measures the net — every previewed, enabled surface mesh of a node other than the reference's
/// — against the reference: the symmetric figures, and the vertex distances of the side coloured.
/// `Err` is the status text saying why nothing was measured.
pub(crate) fn measure(
    graph: &Graph,
    eval: &Evaluator,
    reference: &DistanceReference,
    side: DistanceSide,
) -> Result<Measured, String> {
    let mut net = PolygonMesh::new();
    let mut names = Vec::new();
    let mut parts: Vec<(usize, Value)> = Vec::new();
    let mut keys = HashSet::new();
    for (index, node) in graph.nodes() {
        if !node.preview || !node.enabled || node.id == reference.node {
            continue;
        }
        let Some(outputs) = eval.result_at(graph, index).and_then(|r| r.outputs()) else {
            continue;
        };
        for (port, value) in node.def.outputs.iter().zip(&outputs.values) {
            if layer_of(port) != Layer::Surfaces {
                continue;
            }
            each_mesh(value, None, &mut |m, item| {
                let Some(key) = mesh_key(m) else { return };
                if key == reference.key || !keys.insert(key) {
                    return;
                }
                let Some(mesh) = polygon_mesh(m) else { return };
                if mesh.face_count() == 0 {
                    return;
                }
                net.append(&mesh);
                names.push(match item {
                    Some(k) => format!("{}.{}[{k}]", node.id, port.name),
                    None => format!("{}.{}", node.id, port.name),
                });
                parts.push((key, m.clone()));
            });
        }
    }
    if names.is_empty() {
        return Err(format!(
            "nothing else is previewed to measure against '{}'",
            reference.node
        ));
    }
    let cannot = |e: cnets_geometry::GeometryError| {
        format!("cannot measure against '{}': {e}", reference.node)
    };
    let samples = (
        samples_for(triangle_count(&net)),
        samples_for(triangle_count(&reference.mesh)),
    );
    let one_way = |to_reference: bool, n: usize| {
        surface_distances(
            &net,
            &reference.mesh,
            n,
            Directions {
                to_reference,
                from_reference: !to_reference,
            },
        )
    };
    let to = one_way(true, samples.0).map_err(cannot)?;
    let from = one_way(false, samples.1).map_err(cannot)?;
    let d = SurfaceDistances {
        to_reference: to.to_reference,
        to_reference_max: to.to_reference_max,
        from_reference: from.from_reference,
        from_reference_max: from.from_reference_max,
    };
    let mut colours = HashMap::new();
    match side {
        DistanceSide::Net => {
            let query = MeshQuery::new(&reference.mesh).map_err(cannot)?;
            for (key, value) in &parts {
                let vertices = match value {
                    Value::QuadMesh(g) => &g.vertices,
                    Value::Mesh(m) => &m.vertices,
                    _ => continue,
                };
                let hits = query.closest_all(vertices).map_err(cannot)?;
                colours.insert(*key, hits.iter().map(|h| h.distance).collect::<Vec<_>>());
            }
        }
        DistanceSide::Reference => {
            let query = MeshQuery::new(&net).map_err(cannot)?;
            let hits = query
                .closest_all(&reference.mesh.vertices)
                .map_err(cannot)?;
            colours.insert(reference.key, hits.iter().map(|h| h.distance).collect());
        }
    }
    let vertices = colours.values().map(Vec::len).sum();
    let colour_max = colours
        .values()
        .flatten()
        .copied()
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max);
    Ok(Measured {
        figures: DistanceFigures {
            reference: reference.node.clone(),
            net: names,
            rms: d.symmetric().sqrt(),
            max: d.hausdorff(),
            net_rms: d.to_reference.sqrt(),
            net_max: d.to_reference_max,
            reference_rms: d.from_reference.sqrt(),
            reference_max: d.from_reference_max,
            samples,
            side,
            vertices,
            colour_max,
        },
        colours,
        net: parts.into_iter().map(|(k, _)| k).collect(),
    })
}

/// Whether a node gives a mesh (a quad grid or a polygon mesh, or a list of them).
pub fn gives_mesh(node: &NodeInstance) -> bool {
    node.def
        .outputs
        .iter()
        .any(|p| matches!(p.ty, ValueType::Mesh | ValueType::QuadMesh))
}

/// Whether a node is a cone-net construction: it declares its faces' convexity margins
/// ([`Role::FaceMargins`]), and with them its configurations.
pub fn is_construction(node: &NodeInstance) -> bool {
    node.def
        .outputs
        .iter()
        .any(|p| p.hint.role == Role::FaceMargins)
}

/// The reference the distance mode picks by itself: the first mesh node (graph order) that is
/// neither the net nor made from it nor one of its makings. The net is every previewed, enabled
/// mesh node made from a construction ([`is_construction`]) — or, without any, every previewed
/// mesh node. `None` when no such mesh exists: the mode then says so instead of measuring a mesh
/// against itself.
pub fn default_distance_reference(graph: &Graph) -> Option<u64> {
    // The nodes reached from `start` along wires, upstream (`up`) or downstream, `start` included.
    let reach = |start: Vec<_>, up: bool| {
        let mut seen = HashSet::new();
        let mut stack = start;
        while let Some(k) = stack.pop() {
            if !seen.insert(k) {
                continue;
            }
            if up {
                stack.extend(graph.sources(k));
            } else {
                stack.extend(graph.targets(k));
            }
        }
        seen
    };
    let constructions = graph
        .nodes()
        .filter(|(_, n)| is_construction(n))
        .map(|(k, _)| k)
        .collect();
    let made_from_constructions = reach(constructions, false);
    let previewed: Vec<_> = graph
        .nodes()
        .filter(|(_, n)| n.preview && n.enabled && gives_mesh(n))
        .map(|(k, _)| k)
        .collect();
    let nets: Vec<_> = match previewed
        .iter()
        .copied()
        .filter(|k| made_from_constructions.contains(k))
        .collect::<Vec<_>>()
    {
        from_constructions if !from_constructions.is_empty() => from_constructions,
        _ => previewed,
    };
    let mut related = reach(nets.clone(), true);
    related.extend(reach(nets, false));
    graph
        .nodes()
        .find(|(k, n)| gives_mesh(n) && !related.contains(k))
        .map(|(_, n)| n.uid())
}
