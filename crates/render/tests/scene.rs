//! Scene building: counts, edges without diagonals, per-face colours, bounds, bad input.

use std::collections::HashSet;

use cnets_geometry::{DVec3, Line, PolygonMesh, Polyline, QuadGrid};
use cnets_render::{
    Bounds, Color, FaceColors, LineStyle, MAX_DEPTH_LAYER, MeshStyle, PointShape, PointStyle,
    RenderError, Scene, palette,
};
use glam::Vec3;

/// A flat `rows × cols` grid with unit spacing: vertex (i, j) at (j, i, 0).
fn grid(rows: usize, cols: usize) -> QuadGrid {
    let v = (0..rows)
        .flat_map(|i| (0..cols).map(move |j| DVec3::new(j as f64, i as f64, 0.0)))
        .collect();
    QuadGrid::new(rows, cols, v).unwrap()
}

/// Segment ends rounded to integers (the test grids have integer coordinates), ordered.
fn edge_set(scene: &Scene) -> HashSet<([i64; 3], [i64; 3])> {
    scene
        .segments()
        .iter()
        .map(|s| {
            let a = s.a.map(|c| c.round() as i64);
            let b = s.b.map(|c| c.round() as i64);
            if a <= b { (a, b) } else { (b, a) }
        })
        .collect()
}

#[test]
fn quad_grid_counts_and_edges_without_diagonals() {
    let g = grid(3, 4); // 2 × 3 quads
    let mut scene = Scene::new();
    let info = scene
        .add_quad_grid(&g, FaceColors::Uniform(palette::SURFACE))
        .unwrap();
    assert_eq!(info.faces, 6);
    assert_eq!(info.triangles, 12);
    assert_eq!(scene.triangle_count(), 12);
    assert_eq!(
        scene.face_vertices().len(),
        24,
        "four corners per quad (flat shading)"
    );
    // 3 rows × 3 horizontal edges + 4 columns × 2 vertical edges.
    assert_eq!(info.edges, 17);
    assert_eq!(scene.segments().len(), 17);
    let edges = edge_set(&scene);
    assert_eq!(edges.len(), 17, "no edge drawn twice");
    for (a, b) in &edges {
        let d: i64 = (0..3).map(|k| (a[k] - b[k]).abs()).sum();
        assert_eq!(d, 1, "edge {a:?}-{b:?} is not a grid edge (diagonal?)");
    }
    // Every triangle index points at a vertex; normals are +Z or -Z (flat grid).
    assert!(
        scene
            .face_indices()
            .iter()
            .all(|&i| (i as usize) < scene.face_vertices().len())
    );
    for v in scene.face_vertices() {
        assert!((v.normal[2].abs() - 1.0).abs() < 1e-6, "{v:?}");
    }
    assert_eq!(
        scene.bounds(),
        Some(Bounds::new(Vec3::ZERO, Vec3::new(3.0, 2.0, 0.0)))
    );
}

#[test]
fn wrapped_grid_draws_closing_quads_and_edges_once() {
    let g = grid(3, 4).with_wrap(false, true); // columns wrap: 2 × 4 quads
    let mut scene = Scene::new();
    let info = scene.add_quad_grid(&g, FaceColors::default()).unwrap();
    assert_eq!(info.faces, 8);
    assert_eq!(info.edges, 3 * 4 + 4 * 2);
    assert_eq!(edge_set(&scene).len(), info.edges);
    // The closing edge (3, i) - (0, i) exists on every row.
    for i in 0..3 {
        assert!(edge_set(&scene).contains(&([0, i, 0], [3, i, 0])));
    }
}

#[test]
fn polygon_mesh_fans_faces_and_draws_outlines_only() {
    // A pentagon, a quad sharing an edge with it and a triangle sharing an edge with the quad.
    let v = vec![
        DVec3::new(0.0, 0.0, 0.0),  // 0
        DVec3::new(2.0, 0.0, 0.0),  // 1
        DVec3::new(3.0, 2.0, 0.0),  // 2
        DVec3::new(1.0, 3.0, 0.0),  // 3
        DVec3::new(-1.0, 2.0, 0.0), // 4
        DVec3::new(4.0, -1.0, 0.0), // 5
        DVec3::new(5.0, 1.0, 0.0),  // 6
        DVec3::new(6.0, -1.0, 0.0), // 7
    ];
    let faces = [vec![0, 1, 2, 3, 4], vec![1, 5, 6, 2], vec![5, 7, 6]];
    let mesh = PolygonMesh::from_faces(v, &faces).unwrap();
    let mut scene = Scene::new();
    let colors = [palette::SURFACE, Color::hex(0xff0000), Color::hex(0x00ff00)];
    let info = scene
        .add_polygon_mesh(&mesh, FaceColors::PerFace(&colors))
        .unwrap();
    assert_eq!(info.faces, 3);
    assert_eq!(info.triangles, 3 + 2 + 1);
    assert_eq!(scene.triangle_count(), 6);
    assert_eq!(scene.face_vertices().len(), 5 + 4 + 3);
    // 5 + 4 + 3 face sides, 2 shared: 10 distinct edges.
    assert_eq!(info.edges, 10);
    // Each segment joins consecutive corners of some face (no fan diagonal such as 0-2).
    let outline: HashSet<(u32, u32)> = faces
        .iter()
        .flat_map(|f| {
            (0..f.len()).map(move |k| {
                (
                    f[k].min(f[(k + 1) % f.len()]),
                    f[k].max(f[(k + 1) % f.len()]),
                )
            })
        })
        .collect();
    let pos = |k: u32| mesh.vertices[k as usize].as_vec3().to_array();
    let outline_pos: HashSet<([i64; 3], [i64; 3])> = outline
        .iter()
        .map(|&(a, b)| {
            let (a, b) = (pos(a).map(|c| c as i64), pos(b).map(|c| c as i64));
            if a <= b { (a, b) } else { (b, a) }
        })
        .collect();
    assert_eq!(edge_set(&scene), outline_pos);
    // Per-face colours: the corners of face k carry colour k.
    let fv = scene.face_vertices();
    assert!(fv[0..5].iter().all(|v| v.color == colors[0]));
    assert!(fv[5..9].iter().all(|v| v.color == colors[1]));
    assert!(fv[9..12].iter().all(|v| v.color == colors[2]));
    // Triangles of the quad only use the quad's corners.
    let tris = scene.face_indices();
    assert!(tris[9..15].iter().all(|&i| (5..9).contains(&i)));
}

#[test]
fn per_face_colours_follow_quad_order() {
    let g = grid(3, 3); // 2 × 2 quads
    let colors = [
        Color::hex(0x110000),
        Color::hex(0x220000),
        Color::hex(0x330000),
        Color::hex(0x440000),
    ];
    let mut scene = Scene::new();
    scene
        .add_quad_grid(&g, MeshStyle::new(FaceColors::PerFace(&colors)).edges(None))
        .unwrap();
    assert!(scene.segments().is_empty(), "edges switched off");
    for (k, ((i, j), _)) in g.quads().enumerate() {
        let corners = &scene.face_vertices()[k * 4..k * 4 + 4];
        assert!(
            corners.iter().all(|v| v.color == colors[k]),
            "quad ({i}, {j})"
        );
        // The quad's corners are where the grid says.
        let c = corners[0].position;
        assert_eq!((c[0], c[1]), (j as f32, i as f32));
    }
}

#[test]
fn wrong_colour_count_and_bad_geometry_are_errors() {
    let mut scene = Scene::new();
    let g = grid(3, 3);
    let err = scene
        .add_quad_grid(&g, FaceColors::PerFace(&[palette::SURFACE; 3]))
        .unwrap_err();
    assert!(
        matches!(
            err,
            RenderError::ColorCount {
                expected: 4,
                got: 3
            }
        ),
        "{err}"
    );
    let bad = QuadGrid {
        classes: Vec::new(),
        rows: 3,
        cols: 3,
        vertices: vec![DVec3::ZERO; 5],
        ..QuadGrid::default()
    };
    assert!(matches!(
        scene.add_quad_grid(&bad, FaceColors::default()),
        Err(RenderError::Geometry(_))
    ));
    let bad_mesh = PolygonMesh {
        vertices: vec![DVec3::ZERO; 3],
        indices: vec![0, 1, 7],
        face_starts: vec![0],
        parts: Default::default(),
        classes: Vec::new(),
    };
    assert!(matches!(
        scene.add_polygon_mesh(&bad_mesh, FaceColors::default()),
        Err(RenderError::Geometry(_))
    ));
    assert!(scene.is_empty(), "failed adds leave the scene unchanged");
    assert_eq!(scene.bounds(), None);
}

#[test]
fn non_finite_vertices_are_skipped_not_uploaded() {
    let mut g = grid(3, 3);
    *g.at_mut(1, 1) = DVec3::new(f64::NAN, 0.0, 0.0); // the centre vertex touches all 4 quads
    *g.at_mut(0, 0) = DVec3::new(1e300, 0.0, 0.0); // not representable in f32
    let mut scene = Scene::new();
    let info = scene.add_quad_grid(&g, FaceColors::default()).unwrap();
    assert_eq!(info.faces, 0);
    assert_eq!(info.skipped_faces, 4);
    // 12 grid edges, 4 touch the centre and 2 touch the corner.
    assert_eq!(info.edges, 6);
    assert!(
        scene
            .segments()
            .iter()
            .all(|s| s.a.iter().chain(&s.b).all(|c| c.is_finite()))
    );
    let b = scene.bounds().unwrap();
    assert!(b.min.is_finite() && b.max.is_finite());

    let n = scene.add_points(
        &[DVec3::ZERO, DVec3::splat(f64::INFINITY)],
        PointStyle::default(),
    );
    assert_eq!(n, 1);
    let n = scene.add_lines(
        &[Line::new(DVec3::ZERO, DVec3::new(f64::NAN, 1.0, 1.0))],
        LineStyle::default(),
    );
    assert_eq!(n, 0);
    assert_eq!(scene.skipped(), 4 + 1 + 1);
    assert_eq!(scene.stats().skipped, 6);
}

#[test]
fn lines_points_and_bounds() {
    let mut scene = Scene::new();
    assert!(scene.is_empty());
    assert_eq!(scene.bounds(), None);
    let square = Polyline::closed(vec![
        DVec3::ZERO,
        DVec3::X,
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::Y,
    ]);
    assert_eq!(
        scene.add_polyline(&square, LineStyle::new(palette::LINE, 3.0)),
        4
    );
    assert_eq!(
        scene.add_polyline(&Polyline::open(vec![DVec3::X]), LineStyle::default()),
        0
    );
    let lines = [Line::new(
        DVec3::new(0.0, 0.0, -2.0),
        DVec3::new(0.0, 0.0, 5.0),
    )];
    assert_eq!(scene.add_lines(&lines, LineStyle::default().on_top()), 1);
    let style = PointStyle::new(palette::POINT, 6.0)
        .shape(PointShape::Square)
        .on_top();
    assert_eq!(scene.add_points(&[DVec3::new(-3.0, 0.5, 0.0)], style), 1);
    assert_eq!(scene.segments().len(), 5);
    assert_eq!(scene.segments()[0].width, 3.0);
    assert_eq!(scene.segments()[4].flags, cnets_render::scene::FLAG_ON_TOP);
    assert_eq!(scene.points()[0].flags, cnets_render::scene::FLAG_ON_TOP);
    assert!(
        PointStyle::default().on_top,
        "markers are drawn on top by default"
    );
    assert!(!PointStyle::default().depth_tested().on_top);
    assert_eq!(
        scene.bounds(),
        Some(Bounds::new(
            Vec3::new(-3.0, 0.0, -2.0),
            Vec3::new(1.0, 1.0, 5.0)
        ))
    );
    let stats = scene.stats();
    assert_eq!((stats.triangles, stats.segments, stats.points), (0, 5, 1));
    assert_eq!(scene.positions().count(), 5 * 2 + 1);

    let background = Color::hex(0x101010);
    let mut scene = scene.with_background(background);
    scene.clear();
    assert!(scene.is_empty());
    assert_eq!(scene.bounds(), None);
    assert_eq!(scene.background(), background, "clear keeps the background");
}

#[test]
fn rebuilding_reuses_and_matches_a_fresh_build() {
    let g = grid(20, 30);
    let mut a = Scene::new();
    a.add_quad_grid(&g, FaceColors::default()).unwrap();
    a.clear();
    a.add_quad_grid(&g, FaceColors::default()).unwrap();
    let mut b = Scene::new();
    b.add_quad_grid(&g, FaceColors::default()).unwrap();
    assert_eq!(a.face_vertices(), b.face_vertices());
    assert_eq!(a.face_indices(), b.face_indices());
    assert_eq!(a.segments(), b.segments());
    assert_eq!(a.triangle_count(), 19 * 29 * 2);
}

#[test]
fn degenerate_grids_do_not_panic() {
    let mut scene = Scene::new();
    for (r, c) in [(0, 0), (1, 5), (5, 1), (2, 2)] {
        let info = scene
            .add_quad_grid(&grid(r, c), FaceColors::default())
            .unwrap();
        assert_eq!(info.faces, (r.max(1) - 1) * (c.max(1) - 1));
    }
    // A zero-area quad gets a zero normal (lit as facing the viewer), not NaN.
    let g = QuadGrid::new(2, 2, vec![DVec3::ZERO; 4]).unwrap();
    scene.add_quad_grid(&g, FaceColors::default()).unwrap();
    assert!(
        scene
            .face_vertices()
            .iter()
            .all(|v| v.normal.iter().all(|c| c.is_finite()))
    );
}

#[test]
fn gpu_types_can_live_in_egui_callback_resources() {
    // egui-wgpu's CallbackResources (a concurrent type map) and its callbacks need Send + Sync.
    fn send_sync<T: Send + Sync + 'static>() {}
    send_sync::<cnets_render::SceneRenderer>();
    send_sync::<cnets_render::Blitter>();
    send_sync::<cnets_render::BlitSource>();
    send_sync::<cnets_render::Offscreen>();
    send_sync::<Scene>();
    send_sync::<cnets_render::Camera>();
}

#[test]
fn per_vertex_colours_go_to_each_corner_and_depth_layers_to_each_face() {
    let v = (0..2)
        .flat_map(|i| (0..3).map(move |j| DVec3::new(j as f64, i as f64, 0.0)))
        .collect();
    let grid = QuadGrid::new(2, 3, v).unwrap();
    let colors: Vec<Color> = (0..6).map(|k| Color::rgb(10 * k as u8, 0, 0)).collect();
    let mut scene = Scene::new();
    scene
        .add_quad_grid(
            &grid,
            MeshStyle::new(FaceColors::PerVertex(&colors)).depth_layer(3),
        )
        .unwrap();
    let mesh = cnets_geometry::PolygonMesh::from(&grid);
    scene
        .add_polygon_mesh(
            &mesh,
            MeshStyle::new(FaceColors::PerVertex(&colors)).depth_layer(1000),
        )
        .unwrap();
    let fv = scene.face_vertices();
    assert_eq!(fv.len(), 16);
    // Quad (0, 0) has corners 0, 1, 4, 3 in both meshes.
    for half in [&fv[..8], &fv[8..]] {
        let red: Vec<u8> = half[..4].iter().map(|c| c.color.0[0]).collect();
        assert_eq!(red, vec![0, 10, 40, 30]);
    }
    assert!(fv[..8].iter().all(|c| c.depth_layer == 3));
    assert!(
        fv[8..].iter().all(|c| c.depth_layer == MAX_DEPTH_LAYER),
        "clamped"
    );
    let err = scene
        .add_quad_grid(&grid, FaceColors::PerVertex(&colors[..5]))
        .unwrap_err();
    assert!(err.to_string().contains("5 colours"), "{err}");
}
