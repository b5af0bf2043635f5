//! Several cone-nets, one structure: each junction recipe (docs/structures.md) meets with an exact
//! seam, measured by `measure.seam`, and every face stays planar.

use cnets_engine::Value;
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
