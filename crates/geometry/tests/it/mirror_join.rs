//! Mirroring (reflect and join, welding vertices on the plane), joining and welding.

use cnets_geometry::fabrication::polygon::newell_vector;
use cnets_geometry::fabrication::{FabricationError, join, mirror, weld};
use cnets_geometry::{DVec3, Plane, PolygonMesh, QuadGrid};
use std::collections::HashMap;

fn grid(n: usize, m: usize, origin: DVec3) -> PolygonMesh {
    let v = (0..n)
        .flat_map(|i| {
            (0..m).map(move |j| origin + DVec3::new(j as f64, i as f64, 0.1 * (j * j) as f64))
        })
        .collect();
    PolygonMesh::from(&QuadGrid::new(n, m, v).unwrap())
}

fn edge_uses(mesh: &PolygonMesh) -> HashMap<(u32, u32), usize> {
    let mut uses = HashMap::new();
    for f in mesh.faces() {
        for k in 0..f.len() {
            let (a, b) = (f[k], f[(k + 1) % f.len()]);
            *uses.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    uses
}

#[test]
fn mirror_welds_the_vertices_on_the_plane_and_keeps_orientation() {
    // 3 × 4 grid with x from 0 to 3; mirror in x = 0 (the first column lies on the plane).
    let half = grid(3, 4, DVec3::ZERO);
    let plane = Plane::YZ;
    let whole = mirror(&half, &plane, 1e-9).unwrap();
    assert_eq!(whole.vertices.len(), 12 + 9);
    assert_eq!(whole.face_count(), 12);
    // Every mirrored vertex is the reflection of an original one.
    for p in &whole.vertices[12..] {
        let r = DVec3::new(-p.x, p.y, p.z);
        assert!(half.vertices.iter().any(|q| q.distance(r) < 1e-15));
    }
    // The edges on the plane are now shared by two faces; no edge by more.
    let uses = edge_uses(&whole);
    let on_plane: Vec<_> = uses
        .iter()
        .filter(|((a, b), _)| {
            whole.vertices[*a as usize].x == 0.0 && whole.vertices[*b as usize].x == 0.0
        })
        .collect();
    assert_eq!(on_plane.len(), 2);
    assert!(on_plane.iter().all(|(_, n)| **n == 2));
    assert!(uses.values().all(|&n| n <= 2));
    // Both halves face up (the grid faces +z).
    for f in whole.faces() {
        let pts: Vec<DVec3> = f.iter().map(|&v| whole.vertices[v as usize]).collect();
        assert!(newell_vector(&pts).z > 0.0);
    }
    // A vertex within the tolerance is moved onto the plane and welded.
    let mut near = half.clone();
    near.vertices[0].x = 1e-7;
    let w = mirror(&near, &plane, 1e-6).unwrap();
    assert_eq!(w.vertices[0].x, 0.0);
    assert_eq!(w.vertices.len(), 21);
    assert!(matches!(
        mirror(&half, &plane, -1.0),
        Err(FabricationError::BadParameter { .. })
    ));
    assert!(mirror(&PolygonMesh::new(), &plane, 0.0).is_err());
}

#[test]
fn join_appends_and_weld_merges_coincident_vertices() {
    let a = grid(2, 3, DVec3::ZERO);
    // b starts where a ends: a's last column is x = 2, z = 0.4; b is flat at z = 0.4 from x = 2.
    let mut b = grid(2, 3, DVec3::new(2.0, 0.0, 0.0));
    for p in &mut b.vertices {
        p.z = 0.4;
    }
    let joined = join(&[&a, &b]).unwrap();
    assert_eq!(joined.vertices.len(), 12);
    assert_eq!(joined.face_count(), 4);
    assert_eq!(joined.face(2), &[6, 7, 10, 9]);
    let welded = weld(&joined, 1e-9).unwrap();
    assert_eq!(welded.vertices.len(), 10);
    assert_eq!(welded.face_count(), 4);
    let uses = edge_uses(&welded);
    assert_eq!(uses.values().filter(|&&n| n == 2).count(), 3);
    // Exact welding (tolerance 0) merges the bitwise-equal vertices too.
    assert_eq!(weld(&joined, 0.0).unwrap().vertices.len(), 10);
    // A huge tolerance collapses faces: they are dropped, not kept degenerate.
    let collapsed = weld(&joined, 100.0).unwrap();
    assert_eq!(collapsed.face_count(), 0);
    assert!(join(&[&PolygonMesh::new()]).is_err());
    assert!(weld(&joined, f64::NAN).is_err());
}
