//! Cutting by a plane: the kept side only, faces split exactly at the plane with shared new vertices,
//! areas conserved, non-convex faces split into several pieces.

use crate::fab_common;

use cnets_geometry::fabrication::cut_by_plane;
use cnets_geometry::fabrication::face_attributes::polygon_planarity;
use cnets_geometry::fabrication::polygon::newell_vector;
use cnets_geometry::{DVec3, Plane, PolygonMesh, QuadGrid};
use fab_common::*;

fn area(mesh: &PolygonMesh) -> f64 {
    mesh.faces()
        .map(|f| {
            let pts: Vec<DVec3> = f.iter().map(|&v| mesh.vertices[v as usize]).collect();
            0.5 * newell_vector(&pts).length()
        })
        .sum()
}

fn flat_grid(n: usize) -> PolygonMesh {
    let v = (0..n)
        .flat_map(|i| (0..n).map(move |j| DVec3::new(j as f64, i as f64, 0.0)))
        .collect();
    PolygonMesh::from(&QuadGrid::new(n, n, v).unwrap())
}

#[test]
fn a_flat_grid_is_split_exactly_at_the_plane() {
    let grid = flat_grid(5);
    let plane = Plane::from_normal(DVec3::new(1.5, 0.0, 0.0), DVec3::X).unwrap();
    let right = cut_by_plane(&grid, &plane, true).unwrap();
    let left = cut_by_plane(&grid, &plane, false).unwrap();
    assert!((area(&right.mesh) - 10.0).abs() < 1e-12);
    assert!((area(&left.mesh) - 6.0).abs() < 1e-12);
    // 16 faces: column 1 is split into two halves, one per side.
    assert_eq!(right.mesh.face_count(), 4 * 3);
    assert_eq!(left.mesh.face_count(), 4 * 2);
    assert!(right.mesh.vertices.iter().all(|p| p.x >= 1.5));
    assert!(left.mesh.vertices.iter().all(|p| p.x <= 1.5));
    // The five crossings of the plane are shared by the faces on either side of them.
    let on: Vec<&DVec3> = right.mesh.vertices.iter().filter(|p| p.x == 1.5).collect();
    assert_eq!(on.len(), 5);
    assert_eq!(right.mesh.vertices.len(), 5 * 3 + 5);
    assert_eq!(right.section.len(), 4);
    for s in &right.section {
        assert_eq!((s.start.x, s.end.x), (1.5, 1.5));
        assert!((s.length() - 1.0).abs() < 1e-15);
    }
}

#[test]
fn an_oblique_cut_of_a_cone_net_conserves_area_and_planarity() {
    let net = cone_net(7, 9, false);
    let mesh = PolygonMesh::from(&net.mesh);
    let plane = Plane::from_normal(DVec3::new(3.3, 0.1, 0.2), DVec3::new(1.0, 0.4, -0.3)).unwrap();
    let a = cut_by_plane(&mesh, &plane, true).unwrap();
    let b = cut_by_plane(&mesh, &plane, false).unwrap();
    let total = area(&mesh);
    assert!(
        (area(&a.mesh) + area(&b.mesh) - total).abs() <= 1e-12 * total,
        "{} + {} vs {total}",
        area(&a.mesh),
        area(&b.mesh)
    );
    let size = net.mesh.size();
    for p in &a.mesh.vertices {
        assert!(plane.signed_distance(*p) >= -1e-12 * size);
    }
    for p in &b.mesh.vertices {
        assert!(plane.signed_distance(*p) <= 1e-12 * size);
    }
    assert!(!a.section.is_empty());
    for s in &a.section {
        assert!(plane.signed_distance(s.start).abs() <= 1e-12 * size);
        assert!(plane.signed_distance(s.end).abs() <= 1e-12 * size);
    }
    // Pieces of planar faces are planar; some faces have five corners now.
    let mut corners = Vec::new();
    for f in a.mesh.faces() {
        corners.clear();
        corners.extend(f.iter().map(|&v| a.mesh.vertices[v as usize]));
        assert!(polygon_planarity(&corners) <= 1e-10);
    }
    assert!(a.mesh.faces().any(|f| f.len() != 4));
}

#[test]
fn a_non_convex_face_crossing_four_times_splits_into_two_pieces() {
    // A U opening upwards: arms x ∈ [0,1] and [2,3], bottom y ∈ [0,1], height 3.
    let pts = vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(3.0, 0.0, 0.0),
        DVec3::new(3.0, 3.0, 0.0),
        DVec3::new(2.0, 3.0, 0.0),
        DVec3::new(2.0, 1.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(1.0, 3.0, 0.0),
        DVec3::new(0.0, 3.0, 0.0),
    ];
    let u = PolygonMesh::from_faces(pts, &[(0..8).collect()]).unwrap();
    let plane = Plane::from_normal(DVec3::new(0.0, 2.0, 0.0), DVec3::Y).unwrap();
    let top = cut_by_plane(&u, &plane, true).unwrap();
    assert_eq!(top.mesh.face_count(), 2);
    assert!((area(&top.mesh) - 2.0).abs() < 1e-14);
    for f in top.mesh.faces() {
        assert_eq!(f.len(), 4);
    }
    let bottom = cut_by_plane(&u, &plane, false).unwrap();
    assert_eq!(bottom.mesh.face_count(), 1);
    assert_eq!(bottom.mesh.face(0).len(), 8);
    assert!((area(&bottom.mesh) - 5.0).abs() < 1e-14);
    assert_eq!(bottom.section.len(), 2);
    // Orientation is kept: the Newell normal still points along +z.
    let f: Vec<DVec3> = bottom
        .mesh
        .face(0)
        .iter()
        .map(|&v| bottom.mesh.vertices[v as usize])
        .collect();
    assert!(newell_vector(&f).z > 0.0);
}

#[test]
fn planes_through_vertices_and_bad_inputs() {
    let grid = flat_grid(3);
    // The plane x = 1 runs through a column of vertices: nothing is split, faces on it are kept.
    let plane = Plane::from_normal(DVec3::X, DVec3::X).unwrap();
    let right = cut_by_plane(&grid, &plane, true).unwrap();
    assert_eq!(right.mesh.face_count(), 2);
    assert_eq!(right.mesh.vertices.len(), 6);
    assert!(right.section.is_empty());
    // Everything on the other side: an empty mesh, not an error.
    let far = Plane::from_normal(DVec3::X * 10.0, DVec3::X).unwrap();
    assert_eq!(
        cut_by_plane(&grid, &far, true).unwrap().mesh.face_count(),
        0
    );
    assert!(cut_by_plane(&PolygonMesh::new(), &plane, true).is_err());
    let mut nan = plane;
    nan.origin.x = f64::NAN;
    assert!(cut_by_plane(&grid, &nan, true).is_err());
}
