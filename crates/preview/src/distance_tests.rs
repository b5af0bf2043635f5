//! The distance mode's figures against an independent dense measure, the reference it picks by
//! itself, and the headline figures naming their mesh.

use std::sync::Arc;

use cnets_engine::{Evaluator, Graph, NodeContext, Value};
use cnets_geometry::{DVec3, QuadGrid};

use crate::{
    ColorMode, DistanceFigures, DistanceSide, LegendInfo, MeshKind, PreviewOptions, build_preview,
    default_distance_reference, legend_rows,
};

/// A flat `rows × cols` grid over `[x0, x1] × [y0, y1]` at height `z`.
fn plane(rows: usize, cols: usize, (x0, x1): (f64, f64), (y0, y1): (f64, f64), z: f64) -> QuadGrid {
    let vertices = (0..rows)
        .flat_map(|i| {
            (0..cols).map(move |j| {
                let (u, v) = (j as f64 / (cols - 1) as f64, i as f64 / (rows - 1) as f64);
                DVec3::new(x0 + u * (x1 - x0), y0 + v * (y1 - y0), z)
            })
        })
        .collect();
    QuadGrid {
        classes: Vec::new(),
        rows,
        cols,
        wrap_rows: false,
        wrap_cols: false,
        vertices,
    }
}

/// An axis-aligned rectangle `[x0, x1] × [y0, y1]` at height `z`.
#[derive(Clone, Copy)]
struct Rect {
    x: (f64, f64),
    y: (f64, f64),
    z: f64,
}

impl Rect {
    /// The exact distance from `p` to the rectangle.
    fn distance(&self, p: DVec3) -> f64 {
        let out = |v: f64, (a, b): (f64, f64)| (a - v).max(0.0).max(v - b);
        let (dx, dy, dz) = (out(p.x, self.x), out(p.y, self.y), p.z - self.z);
        (dx * dx + dy * dy + dz * dz).sqrt()
    }

    /// The mean of d² over the rectangle to `other`, by the midpoint rule on `n × n` cells.
    fn mean_squared_to(&self, other: &Rect, n: usize) -> f64 {
        let mut sum = 0.0;
        for i in 0..n {
            for j in 0..n {
                let x = self.x.0 + (i as f64 + 0.5) / n as f64 * (self.x.1 - self.x.0);
                let y = self.y.0 + (j as f64 + 0.5) / n as f64 * (self.y.1 - self.y.0);
                let d = other.distance(DVec3::new(x, y, self.z));
                sum += d * d;
            }
        }
        sum / (n * n) as f64
    }

    fn grid(&self, rows: usize, cols: usize) -> QuadGrid {
        plane(rows, cols, self.x, self.y, self.z)
    }
}

/// The dense, brute-force symmetric RMS between two rectangles: √(½ (mean d²(net → ref) +
/// mean d²(ref → net))), 1000² points on each.
fn dense_symmetric_rms(net: &Rect, reference: &Rect) -> f64 {
    let n = 1000;
    (0.5 * (net.mean_squared_to(reference, n) + reference.mean_squared_to(net, n))).sqrt()
}

/// A graph with a previewed `net` and a `reference` (previewed or not), each a `mesh.transform`
/// of a literal grid.
fn two_meshes(net: QuadGrid, reference: QuadGrid, reference_previewed: bool) -> (Graph, Evaluator) {
    let mut g = Graph::new(Arc::new(cnets_nodes::registry()));
    for (id, grid) in [("net", net), ("reference", reference)] {
        g.add_node(id, "mesh.transform").unwrap();
        g.set_value(id, "mesh", Value::from(grid)).unwrap();
    }
    g.set_preview("reference", reference_previewed).unwrap();
    let mut eval = Evaluator::new();
    eval.evaluate_all(&g, &NodeContext::new(None, None));
    (g, eval)
}

/// The default options with a colour mode, a distance reference and side.
fn options_with(mode: ColorMode, to: Option<u64>, side: DistanceSide) -> PreviewOptions {
    let mut o = PreviewOptions::default();
    o.color_mode = mode;
    o.distance_to = to;
    o.distance_side = side;
    o
}

fn distance_options(g: &Graph, side: DistanceSide) -> PreviewOptions {
    options_with(
        ColorMode::Distance,
        Some(g.node("reference").unwrap().uid()),
        side,
    )
}

fn figures(g: &Graph, eval: &Evaluator, side: DistanceSide) -> DistanceFigures {
    let p = build_preview(g, eval, &distance_options(g, side));
    p.stats
        .distance
        .clone()
        .unwrap_or_else(|| panic!("no figures: {:?}", p.stats.distance_status))
}

fn within(figure: f64, dense: f64, tolerance: f64) -> bool {
    ((figure - dense) / dense).abs() <= tolerance
}

#[test]
fn the_figure_is_the_symmetric_area_weighted_distance_of_a_dense_measure() {
    // A 1 m net 1 cm above a 2 m × 1 m reference that reaches 0.5 m beyond it on either side
    // (coarse, so the reference's triangles straddle the net's edges).
    let net = Rect {
        x: (0.0, 1.0),
        y: (0.0, 1.0),
        z: 0.01,
    };
    let reference = Rect {
        x: (-0.5, 1.5),
        y: (0.0, 1.0),
        z: 0.0,
    };
    let (g, eval) = two_meshes(net.grid(5, 5), reference.grid(2, 3), false);
    let f = figures(&g, &eval, DistanceSide::Net);
    let dense = dense_symmetric_rms(&net, &reference);
    eprintln!(
        "parallel planes: figure {:.6} m, dense {dense:.6} m ({:+.3} %)",
        f.rms,
        100.0 * (f.rms / dense - 1.0)
    );
    assert!(within(f.rms, dense, 0.05), "{f:?} vs {dense}");
    // The net's side alone is the 1 cm offset; the figure is not (the reference's overhang).
    assert!(
        (f.net_rms - 0.01).abs() < 1e-9 && (f.net_max - 0.01).abs() < 1e-9,
        "{f:?}"
    );
    assert!(f.rms > 3.0 * f.net_rms, "{f:?}");
    // The largest distance: the reference's far corner, 0.5 m beyond the net and 1 cm below.
    assert!(
        (f.reference_max - (0.25f64 + 1e-4).sqrt()).abs() < 1e-6,
        "{f:?}"
    );
    assert_eq!(f.max, f.reference_max);
    assert_eq!(
        (f.reference.as_str(), f.net.as_slice()),
        ("reference", &["net.mesh".to_string()][..])
    );
    // The net's vertices are coloured (25), the scale up to their largest distance (1 cm).
    assert_eq!(f.vertices, 25);
    assert!((f.colour_max - 0.01).abs() < 1e-9, "{f:?}");
}

#[test]
fn a_reference_reaching_beyond_the_net_reads_where_the_vertex_measure_reads_zero() {
    // The net lies on the reference, which runs on for another metre: every net vertex is on it
    // (the one-sided vertex distance is 0), the reference's far half is up to 1 m from the net.
    let net = Rect {
        x: (0.0, 1.0),
        y: (0.0, 1.0),
        z: 0.0,
    };
    let reference = Rect {
        x: (0.0, 2.0),
        y: (0.0, 1.0),
        z: 0.0,
    };
    let (g, eval) = two_meshes(net.grid(4, 4), reference.grid(2, 2), false);
    let f = figures(&g, &eval, DistanceSide::Net);
    let dense = dense_symmetric_rms(&net, &reference);
    eprintln!(
        "overhang: figure {:.6} m, dense {dense:.6} m ({:+.3} %), exact {:.6} m",
        f.rms,
        100.0 * (f.rms / dense - 1.0),
        (1.0f64 / 12.0).sqrt()
    );
    assert!(
        within(dense, (1.0f64 / 12.0).sqrt(), 1e-3),
        "the dense measure: {dense}"
    );
    assert!(within(f.rms, dense, 0.05), "{f:?} vs {dense}");
    assert!(
        f.net_max < 1e-9 && f.colour_max < 1e-9,
        "the net is on the reference: {f:?}"
    );
    assert!((f.reference_max - 1.0).abs() < 1e-9, "{f:?}");
    // Colouring the reference shows the gap: its far vertices 1 m from the net, the scale to 1 m,
    // the net drawn translucent over it; the legend says which side it is.
    let options = distance_options(&g, DistanceSide::Reference);
    let p = build_preview(&g, &eval, &options);
    let r = p.stats.distance.clone().expect("figures");
    assert_eq!(
        (r.rms, r.side, r.vertices),
        (f.rms, DistanceSide::Reference, 4)
    );
    assert!((r.colour_max - 1.0).abs() < 1e-9, "{r:?}");
    let LegendInfo::Distance(legend) = &p.stats.legend else {
        panic!("{:?}", p.stats.legend);
    };
    assert_eq!(legend.title, "reference: distance to the net");
    let (_, rows) = legend_rows(&p.stats.legend).unwrap();
    assert_eq!(rows[0].1, "1.00 m", "{rows:?}");
    // The reference is drawn although not previewed (it is the side coloured), first.
    let names: Vec<(&str, MeshKind)> = p
        .stats
        .meshes
        .iter()
        .map(|m| (m.name.as_str(), m.kind))
        .collect();
    assert_eq!(
        names,
        [
            ("net.mesh", MeshKind::Mesh),
            ("reference.mesh", MeshKind::Reference)
        ]
    );
    assert_eq!(p.picks.meshes[0].node, "reference");
    let alphas: std::collections::HashSet<u8> = p
        .scene
        .face_vertices()
        .iter()
        .map(|v| v.color.0[3])
        .collect();
    assert!(
        alphas.contains(&255) && alphas.iter().any(|a| *a < 255),
        "{alphas:?}"
    );
    // Previewed as well, it is still drawn once.
    let (g, eval) = two_meshes(net.grid(4, 4), reference.grid(2, 2), true);
    let p = build_preview(&g, &eval, &distance_options(&g, DistanceSide::Reference));
    assert_eq!(p.picks.meshes.len(), 2);
    assert_eq!(p.stats.meshes.len(), 2);
}

/// The editor's default graph (a construction previewed) with extra nodes.
fn default_graph() -> Graph {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../graphs/editor-default.ron"
    ))
    .unwrap();
    let registry = Arc::new(cnets_nodes::registry());
    cnets_engine::file::load_str(&text, "editor-default.ron", &registry)
        .unwrap()
        .graph
}

#[test]
fn the_distance_mode_never_takes_the_net_for_its_reference() {
    let mut g = default_graph();
    // Only the net and what it is made of: no reference to pick, and the mode says so.
    assert_eq!(default_distance_reference(&g), None);
    let mut eval = Evaluator::new();
    let ctx = NodeContext::new(None, None);
    eval.evaluate_all(&g, &ctx);
    let options = options_with(ColorMode::Distance, None, DistanceSide::Net);
    let p = build_preview(&g, &eval, &options);
    assert!(p.stats.distance.is_none());
    let status = p.stats.distance_status.clone().expect("a status");
    assert!(status.contains("no reference"), "{status}");
    // Picking the net itself: nothing else to measure, and the status says so.
    let own = options_with(
        ColorMode::Distance,
        Some(g.node("construct").unwrap().uid()),
        DistanceSide::Net,
    );
    let p = build_preview(&g, &eval, &own);
    let status = p.stats.distance_status.clone().expect("a status");
    assert!(status.contains("nothing else is previewed"), "{status}");
    // A mesh made from the net (its polygons) is not a reference either; an independent one is.
    g.add_node("polygons", "mesh.to_polygons").unwrap();
    g.connect("construct", "mesh", "polygons", "mesh").unwrap();
    g.set_preview("polygons", false).unwrap();
    assert_eq!(default_distance_reference(&g), None);
    g.add_node("hull", "mesh.transform").unwrap();
    g.set_value(
        "hull",
        "mesh",
        Value::from(plane(3, 3, (0.0, 6.0), (0.0, 6.0), 1.0)),
    )
    .unwrap();
    g.set_preview("hull", false).unwrap();
    assert_eq!(
        default_distance_reference(&g),
        Some(g.node("hull").unwrap().uid())
    );
    // Previewed too, it is still the reference (not part of the net).
    g.set_preview("hull", true).unwrap();
    assert_eq!(
        default_distance_reference(&g),
        Some(g.node("hull").unwrap().uid())
    );
}

#[test]
fn the_headline_is_the_cone_nets_and_names_its_mesh_never_the_reference() {
    let mut g = default_graph();
    // A far from planar reference, previewed.
    let mut bumpy = plane(3, 3, (0.0, 6.0), (0.0, 6.0), 1.0);
    bumpy.vertices[4].z += 2.0;
    bumpy.vertices[0].z -= 1.0;
    g.add_node("hull", "mesh.transform").unwrap();
    g.set_value("hull", "mesh", Value::from(bumpy)).unwrap();
    let mut eval = Evaluator::new();
    eval.evaluate_all(&g, &NodeContext::new(None, None));
    for options in [
        options_with(ColorMode::Planarity, None, DistanceSide::Net),
        options_with(
            ColorMode::Distance,
            default_distance_reference(&g),
            DistanceSide::Net,
        ),
    ] {
        let s = build_preview(&g, &eval, &options).stats;
        assert_eq!(
            s.max_planarity_mesh.as_deref(),
            Some("construct.mesh"),
            "{s:?}"
        );
        assert!(s.max_planarity.unwrap() < 1e-9, "{s:?}");
        assert_eq!(s.meshes[0].kind, MeshKind::ConeNet);
        assert_eq!(s.meshes[0].name, "construct.mesh");
        let hull = s.meshes.iter().find(|m| m.name == "hull.mesh").unwrap();
        assert!(hull.max_planarity.unwrap() > 1e-2, "{hull:?}");
        let expected = if options.color_mode == ColorMode::Distance {
            MeshKind::Reference
        } else {
            MeshKind::Mesh
        };
        assert_eq!(hull.kind, expected);
        assert_eq!(s.meshes.last().unwrap().name, "hull.mesh");
        assert_eq!(
            s.vertices,
            s.meshes.iter().map(|m| m.vertices).sum::<usize>()
        );
    }
    // Without a cone-net previewed, the other meshes lead — still not the distance reference.
    g.set_preview("construct", false).unwrap();
    g.add_node("net", "mesh.transform").unwrap();
    g.set_value(
        "net",
        "mesh",
        Value::from(plane(3, 3, (0.0, 1.0), (0.0, 1.0), 0.0)),
    )
    .unwrap();
    eval.evaluate_all(&g, &NodeContext::new(None, None));
    let s = build_preview(
        &g,
        &eval,
        &options_with(
            ColorMode::Distance,
            Some(g.node("hull").unwrap().uid()),
            DistanceSide::Net,
        ),
    )
    .stats;
    assert_eq!(s.max_planarity_mesh.as_deref(), Some("net.mesh"), "{s:?}");
    assert!(s.max_planarity.unwrap() < 1e-9, "{s:?}");
    // The planarity mode: the bumpy mesh leads (no cone-net), named.
    let s = build_preview(
        &g,
        &eval,
        &options_with(ColorMode::Planarity, None, DistanceSide::Net),
    )
    .stats;
    assert_eq!(s.max_planarity_mesh.as_deref(), Some("hull.mesh"), "{s:?}");
}
