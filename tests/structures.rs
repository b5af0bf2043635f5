//! Several cone-nets, one structure: each junction recipe (docs/structures.md) meets with an exact
//! seam, measured by `measure.seam`, and every face stays planar.

use cnets_engine::eval::evaluate_node;
use cnets_engine::{NodeContext, Value};
use cnets_geometry::seam::{diagonal, seam};
use cnets_geometry::{DVec3, PolygonMesh, QuadGrid};
use cnets_tests::{Evaluated, load};

fn grid<'a>(e: &'a Evaluated, node: &str) -> &'a QuadGrid {
    match e.output(node, "mesh") {
        Value::QuadMesh(g) => g,
        other => panic!("{node}.mesh: {}", other.type_name()),
    }
}

/// Planar to rounding and entirely (++).
fn assert_clean(e: &Evaluated, node: &str) {
    let Value::Record(q) = e.output(node, "quality") else {
        panic!("{node}.quality")
    };
    let planarity = q.get("max_planarity").and_then(Value::as_f64).unwrap();
    assert!(planarity <= 1e-12, "{node}: planarity {planarity}");
    let Some(Value::Record(counts)) = q.get("configurations") else {
        panic!("{node}: configurations")
    };
    for bad in ["--", "+-", "-+"] {
        assert_eq!(counts.get(bad), Some(&Value::Integer(0)), "{node}: {bad}");
    }
}

/// The seam node's gap, asserted within 1e-9 of the meshes' size, and its length.
fn exact_seam(e: &Evaluated, a: &str, b: &str) -> f64 {
    let size =
        diagonal(&PolygonMesh::from(grid(e, a))).max(diagonal(&PolygonMesh::from(grid(e, b))));
    let gap = e.number("seam", "max_gap");
    assert!(gap <= 1e-9 * size, "seam gap {gap} (size {size})");
    e.number("seam", "length")
}

fn translated(mesh: &QuadGrid, by: DVec3) -> PolygonMesh {
    let mut moved = PolygonMesh::from(mesh);
    moved.vertices.iter_mut().for_each(|p| *p += by);
    moved
}

#[test]
fn a_corner_facade_shares_its_profile_exactly() {
    let e = Evaluated::new(load("corner-facade"));
    assert_clean(&e, "front");
    assert_clean(&e, "side");
    let (front, side) = (grid(&e, "front"), grid(&e, "side"));
    let profile = front.column(0);
    assert_eq!(profile.points, side.column(0).points, "the same vertices");
    let length = exact_seam(&e, "front", "side");
    assert!(
        (length - profile.length()).abs() < 1e-12 * length,
        "{length}"
    );
    assert_eq!(e.number("seam", "max_gap"), 0.0);
    // Moved 1 cm apart (across the profile's plane x = y), the seam reads 1 cm.
    let away = DVec3::new(1.0, -1.0, 0.0).normalize() * 0.01;
    let s = seam(&PolygonMesh::from(front), &translated(side, away), None).unwrap();
    assert!((s.max_gap - 0.01).abs() < 1e-12, "{}", s.max_gap);
}

#[test]
fn a_canopy_continued_from_the_walls_top_row_meets_it_exactly() {
    let e = Evaluated::new(load("wall-canopy"));
    assert_clean(&e, "wall");
    assert_clean(&e, "canopy");
    let (wall, canopy) = (grid(&e, "wall"), grid(&e, "canopy"));
    let top = wall.row(wall.rows - 1);
    assert_eq!(
        top.points,
        canopy.column(0).points,
        "the top row, vertex for vertex"
    );
    let length = exact_seam(&e, "wall", "canopy");
    assert!(
        (length - top.length()).abs() < 1e-9 * length,
        "{length} vs {}",
        top.length()
    );
    // The canopy lifted 1 cm off the wall: the seam reads 1 cm, to the top row's slope.
    let s = seam(
        &PolygonMesh::from(wall),
        &translated(canopy, DVec3::Z * 0.01),
        None,
    )
    .unwrap();
    assert!((s.max_gap - 0.01).abs() < 1e-5, "{}", s.max_gap);
}

#[test]
fn a_mirror_joint_meets_its_reflection_exactly() {
    let e = Evaluated::new(load("catamaran-hull"));
    let Value::Mesh(half) = e.output("half", "mesh") else {
        panic!("half.mesh")
    };
    let mut reflected = (**half).clone();
    reflected.vertices.iter_mut().for_each(|p| p.y = -p.y);
    let s = seam(half, &reflected, None).unwrap();
    let size = diagonal(half);
    assert!(s.max_gap <= 1e-9 * size, "{} (size {size})", s.max_gap);
    assert!(s.length > 0.5 * size, "the keel line: {}", s.length);
    let Value::Mesh(whole) = e.output("whole", "mesh") else {
        panic!("whole.mesh")
    };
    let worst = cnets_geometry::fabrication::face_attributes::face_planarity(whole)
        .unwrap()
        .into_iter()
        .fold(0.0, f64::max);
    assert!(worst <= 1e-9, "mirror joint planarity {worst}");
}

/// Runs one node with named inputs (the others empty or their defaults) in `ctx`.
fn run_node(ctx: &NodeContext, id: &str, named: &[(&str, Value)]) -> Vec<Value> {
    let registry = cnets_tests::registry();
    let def = registry.get(id).unwrap_or_else(|| panic!("{id}"));
    let inputs: Vec<Value> = def
        .inputs
        .iter()
        .map(|p| {
            named
                .iter()
                .find(|(n, _)| *n == p.name)
                .map(|(_, v)| v.clone())
                .or_else(|| p.default.clone())
                .unwrap_or(Value::Null)
        })
        .collect();
    evaluate_node(def, ctx, &inputs)
        .unwrap_or_else(|e| panic!("{id}: {e}"))
        .values
}

fn texts(v: &Value) -> Vec<String> {
    v.as_list()
        .expect("a list")
        .iter()
        .map(|t| match t {
            Value::Text(t) => t.to_string(),
            other => panic!("a text, not {}", other.type_name()),
        })
        .collect()
}

/// The mesh names of a GLB file (its JSON chunk).
fn glb_mesh_names(bytes: &[u8]) -> Vec<String> {
    let length = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let json: serde_json::Value = serde_json::from_slice(&bytes[20..20 + length]).unwrap();
    json["meshes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m["name"].as_str().unwrap().to_string())
        .collect()
}

#[test]
fn a_joined_structure_keeps_the_names_of_its_nets() {
    let e = Evaluated::new(load("wall-canopy"));
    let (wall, canopy) = (grid(&e, "wall"), grid(&e, "canopy"));
    let parts = Value::list(vec![
        Value::from(PolygonMesh::from(wall)),
        Value::from(PolygonMesh::from(canopy)),
    ]);
    let ctx = NodeContext::default();
    // Named by the designer, welded along the seam.
    let joined = run_node(
        &ctx,
        "mesh.join",
        &[
            ("meshes", parts.clone()),
            ("weld", Value::Number(1e-9)),
            (
                "names",
                Value::list(vec![Value::text("wall"), Value::text("canopy")]),
            ),
        ],
    );
    let Value::Mesh(structure) = &joined[0] else {
        panic!("a mesh")
    };
    let seam_vertices = wall.cols;
    assert_eq!(
        structure.vertices.len(),
        wall.vertices.len() + canopy.vertices.len() - seam_vertices,
        "welded along the seam"
    );
    assert_eq!(structure.parts.names, ["wall", "canopy"]);
    let wall_faces = wall.quad_count();
    assert!(
        structure.parts.of_face[..wall_faces]
            .iter()
            .all(|&p| p == 0)
    );
    assert!(
        structure.parts.of_face[wall_faces..]
            .iter()
            .all(|&p| p == 1)
    );
    // Strips are each net's own, numbered within it, named after it: the canopy's generatrix
    // strips end at the seam although the weld joined their faces to the wall's.
    for (direction, per_wall, per_canopy) in [
        ("directrix", wall.quad_rows(), canopy.quad_rows()),
        ("generatrix", wall.quad_cols(), canopy.quad_cols()),
    ] {
        let out = run_node(
            &ctx,
            "pq.unroll_strips",
            &[
                ("mesh", joined[0].clone()),
                ("direction", Value::text(direction)),
            ],
        );
        let labels = texts(&out[2]);
        let short = if direction == "directrix" { "D" } else { "G" };
        let mut want: Vec<String> = (0..per_wall).map(|k| format!("wall-{short}{k}")).collect();
        want.extend((0..per_canopy).map(|k| format!("canopy-{short}{k}")));
        let names: Vec<String> = labels
            .iter()
            .map(|l| l.split_whitespace().next().unwrap().to_string())
            .collect();
        assert_eq!(names, want, "{direction}: {labels:?}");
        assert!(out[1].as_f64().unwrap() <= 1e-9, "max_length_error");
    }
    // Unnamed, the nets are lettered; joining the structure again keeps its parts.
    let lettered = run_node(&ctx, "mesh.join", &[("meshes", parts)]);
    let Value::Mesh(m) = &lettered[0] else {
        panic!("a mesh")
    };
    assert_eq!(m.parts.names, ["A", "B"]);
    let again = run_node(
        &ctx,
        "mesh.join",
        &[(
            "meshes",
            Value::list(vec![
                joined[0].clone(),
                Value::from(PolygonMesh::from(wall)),
            ]),
        )],
    );
    let Value::Mesh(m) = &again[0] else {
        panic!("a mesh")
    };
    assert_eq!(m.parts.names, ["wall", "canopy", "B"]);
    // Cut and mirrored, each face keeps its net.
    let middle = structure.vertices.iter().sum::<DVec3>() / structure.vertices.len() as f64;
    let plane = Value::from(cnets_geometry::Plane::from_normal(middle, DVec3::X).unwrap());
    let cut = run_node(
        &ctx,
        "mesh.cut_by_plane",
        &[("mesh", joined[0].clone()), ("plane", plane.clone())],
    );
    let mirrored = run_node(
        &ctx,
        "mesh.mirror",
        &[("mesh", cut[0].clone()), ("plane", plane)],
    );
    let Value::Mesh(m) = &mirrored[0] else {
        panic!("a mesh")
    };
    assert_eq!(m.parts.names, ["wall", "canopy"]);
    assert_eq!(m.parts.of_face.len(), m.face_count());
    for f in 0..m.face_count() {
        let centre = m
            .face(f)
            .iter()
            .map(|&v| m.vertices[v as usize])
            .sum::<DVec3>()
            / m.face(f).len() as f64;
        let near_wall = structure
            .faces()
            .enumerate()
            .filter(|(_, face)| {
                let c = face
                    .iter()
                    .map(|&v| structure.vertices[v as usize])
                    .sum::<DVec3>()
                    / face.len() as f64;
                let mirrored = DVec3::new(2.0 * middle.x - c.x, c.y, c.z);
                (c - centre).length() < 1e-9 || (mirrored - centre).length() < 1e-9
            })
            .map(|(g, _)| structure.parts.of_face[g])
            .next();
        if let Some(part) = near_wall {
            assert_eq!(m.parts.of_face[f], part, "face {f}");
        }
    }
    // The GLB writes one mesh a net, named after the structure and the net.
    let dir = std::env::temp_dir().join(format!("cnets-structure-glb-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let write = NodeContext::new(Some(dir.clone()), None);
    run_node(
        &write,
        "io.export_gltf",
        &[
            ("name", Value::text("structure.glb")),
            ("meshes", Value::list(vec![joined[0].clone()])),
            ("names", Value::list(vec![Value::text("structure")])),
        ],
    );
    let names = glb_mesh_names(&std::fs::read(dir.join("structure.glb")).unwrap());
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(names, ["structure: wall", "structure: canopy"]);
    // Through the JSON door and back, the parts are kept.
    let json = cnets_engine::value::json::to_json(&joined[0]);
    assert_eq!(json["parts"], serde_json::json!(["wall", "canopy"]));
}
