//! Unrolling the strips of a cut and mirrored cone-net (issue 32): the strips of the polygon mesh are
//! found from its topology (trimmed panels included), every face keeps its edge lengths and angles,
//! the strips do not overlap, and the mirrored half's strips are marked as mirror images.

use crate::fab_common;

use cnets_geometry::fabrication::face_attributes::polygon_planarity;
use cnets_geometry::fabrication::polygon::newell_vector;
use cnets_geometry::fabrication::{
    FabricationError, StripDirection, UnrollOptions, cut_by_plane, grid_of, mesh_strips, mirror,
    strips, unroll_mesh_strips,
};
use cnets_geometry::{DVec3, Plane, PolygonMesh, QuadGrid};
use fab_common::*;
use glam::DVec2;

fn face_points(mesh: &PolygonMesh, f: usize) -> Vec<DVec3> {
    mesh.face(f)
        .iter()
        .map(|&v| mesh.vertices[v as usize])
        .collect()
}

fn area(points: &[DVec3]) -> f64 {
    0.5 * newell_vector(points).length()
}

fn angle(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}

/// The cone-net cut by an oblique plane: whole quads, trimmed quads, pentagons and triangles.
fn cut_net() -> (PolygonMesh, Plane) {
    let net = cone_net(9, 12, false);
    let mesh = PolygonMesh::from(&net.mesh);
    let plane = Plane::from_normal(DVec3::new(6.3, 0.0, 0.0), DVec3::new(1.0, 0.45, 0.2)).unwrap();
    (cut_by_plane(&mesh, &plane, false).unwrap().mesh, plane)
}

/// Checks every placed face against its mesh face and returns the largest planarity and length
/// error found independently.
fn check(mesh: &PolygonMesh, direction: StripDirection) -> (usize, f64) {
    let u = unroll_mesh_strips(mesh, direction, UnrollOptions::default()).unwrap();
    let mut covered = vec![0usize; mesh.face_count()];
    let (mut worst_len, mut worst_angle, mut worst_planarity) = (0.0f64, 0.0f64, 0.0f64);
    for s in &u.strips {
        let mut strip_area = 0.0;
        for (flat, &f) in s.faces.iter().zip(&s.mesh_faces) {
            covered[f] += 1;
            let p = face_points(mesh, f);
            worst_planarity = worst_planarity.max(polygon_planarity(&p));
            strip_area += area(&p);
            let n = p.len();
            assert_eq!(flat.len(), n);
            for k in 0..n {
                assert_eq!(flat[k].z, 0.0);
                let (l3, l2) = (
                    p[k].distance(p[(k + 1) % n]),
                    flat[k].distance(flat[(k + 1) % n]),
                );
                worst_len = worst_len.max((l3 - l2).abs() / l3);
                let a3 = angle(p[(k + 1) % n] - p[k], p[(k + n - 1) % n] - p[k]);
                let a2 = angle(flat[(k + 1) % n] - flat[k], flat[(k + n - 1) % n] - flat[k]);
                worst_angle = worst_angle.max((a3 - a2).abs());
            }
        }
        // The outline bounds the placed faces: its area is theirs (no overlap inside a strip).
        let outline: Vec<DVec3> = s.outline.points.clone();
        assert!(s.outline.closed && outline.iter().all(|p| p.z == 0.0));
        assert!(
            (area(&outline) - strip_area).abs() <= 1e-9 * strip_area,
            "{}: outline area {} vs faces {strip_area}",
            s.label,
            area(&outline)
        );
    }
    assert!(covered.iter().all(|&c| c == 1), "every face in one strip");
    assert!(worst_planarity <= 1e-12, "planarity {worst_planarity:e}");
    assert!(u.max_planarity <= 1e-12, "reported {:e}", u.max_planarity);
    assert!(worst_len <= 1e-9, "edge length changed by {worst_len:e}");
    assert!(
        u.max_length_error <= 1e-9,
        "reported {:e}",
        u.max_length_error
    );
    assert!(worst_angle <= 1e-9, "face angle changed by {worst_angle:e}");
    for a in 0..u.strips.len() {
        for b in a + 1..u.strips.len() {
            let pa: Vec<DVec2> = u.strips[a]
                .outline
                .points
                .iter()
                .map(|p| p.truncate())
                .collect();
            let pb: Vec<DVec2> = u.strips[b]
                .outline
                .points
                .iter()
                .map(|p| p.truncate())
                .collect();
            assert!(!polygons_overlap(&pa, &pb), "strips {a} and {b} overlap");
        }
    }
    (u.strips.len(), u.max_length_error)
}

#[test]
fn strips_of_a_cut_cone_net_unroll_with_their_trimmed_panels() {
    let (mesh, _) = cut_net();
    let sizes: Vec<usize> = mesh.faces().map(<[u32]>::len).collect();
    assert!(
        sizes.contains(&5) && sizes.contains(&3),
        "pentagons and triangles: {sizes:?}"
    );
    let (d, _) = check(&mesh, StripDirection::Directrix);
    let (g, _) = check(&mesh, StripDirection::Generatrix);
    // The net has 8 directrix strips; the oblique cut keeps part of every one of them.
    assert_eq!(d, 8);
    assert!(g >= 5, "{g} generatrix strips");
}

#[test]
fn the_mirrored_half_unrolls_and_its_strips_are_marked_as_mirror_images() {
    let (half, plane) = cut_net();
    let whole = mirror(&half, &plane, 1e-9).unwrap();
    let (count, _) = check(&whole, StripDirection::Directrix);
    let u =
        unroll_mesh_strips(&whole, StripDirection::Directrix, UnrollOptions::default()).unwrap();
    assert_eq!(u.strips.len(), count);
    let marked: Vec<&str> = u
        .strips
        .iter()
        .filter(|s| s.mirror_of.is_some())
        .map(|s| s.label.as_str())
        .collect();
    // Every strip of the half ends at the plane (its last panel is trimmed there), so each has its
    // mirror image in the other half.
    assert_eq!(
        count,
        16,
        "{:?}",
        u.strips.iter().map(|s| &s.label).collect::<Vec<_>>()
    );
    assert_eq!(marked.len(), 8, "{marked:?}");
    assert!(
        marked.iter().all(|l| l.contains("(mirror of D")),
        "{marked:?}"
    );
    for s in u.strips.iter().filter(|s| s.mirror_of.is_some()) {
        let original = &u.strips[s.mirror_of.unwrap()];
        let (a, b) = (area(&s.outline.points), area(&original.outline.points));
        assert!((a - b).abs() <= 1e-9 * a, "{}: {a} vs {b}", s.label);
        assert!(original.mirror_of.is_none() && original.copy_of.is_none());
    }
}

#[test]
fn a_converted_grid_is_recognised_and_gives_the_grid_strips() {
    for closed in [false, true] {
        let net = cone_net(7, 6, closed);
        let mesh = PolygonMesh::from(&net.mesh);
        assert_eq!(grid_of(&mesh).as_ref(), Some(&net.mesh));
        for direction in [StripDirection::Directrix, StripDirection::Generatrix] {
            let from_grid = strips(&net.mesh, direction).unwrap();
            let from_mesh = mesh_strips(&mesh, direction).unwrap();
            assert_eq!(
                from_grid.len(),
                from_mesh.len(),
                "{direction} closed {closed}"
            );
            let qc = net.mesh.quad_cols();
            for (g, m) in from_grid.iter().zip(&from_mesh) {
                let faces: Vec<usize> = (0..g.quad_count())
                    .map(|k| {
                        let (i, j) = g.mesh_quad(k);
                        i * qc + j
                    })
                    .collect();
                assert_eq!(m.faces, faces, "{direction} strip {}", g.index);
                assert_eq!(m.closed, g.closed);
            }
        }
    }
    // A cut grid is no longer one.
    assert!(grid_of(&cut_net().0).is_none());
}

#[test]
fn a_mesh_that_is_no_grid_is_refused_with_its_faces_named() {
    // Three quads around one corner of a cube: edge families cannot alternate around it.
    let v = vec![
        DVec3::ZERO,
        DVec3::X,
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::Y,
        DVec3::new(0.0, 1.0, 1.0),
        DVec3::Z,
        DVec3::new(1.0, 0.0, 1.0),
    ];
    let mesh = PolygonMesh::from_faces(v, &[vec![0, 1, 2, 3], vec![0, 3, 4, 5], vec![0, 5, 6, 1]])
        .unwrap();
    let err = mesh_strips(&mesh, StripDirection::Directrix).unwrap_err();
    assert!(matches!(
        err,
        FabricationError::DegenerateFace { what: "strips", .. }
    ));
    assert!(err.to_string().contains("disagree"), "{err}");
    // A non-planar face is refused, naming the strip and face.
    let mut bent = PolygonMesh::from(
        &QuadGrid::new(
            2,
            3,
            vec![
                DVec3::ZERO,
                DVec3::X,
                DVec3::new(2.0, 0.0, 0.0),
                DVec3::Y,
                DVec3::new(1.0, 1.0, 0.3),
                DVec3::new(2.0, 1.0, 0.0),
            ],
        )
        .unwrap(),
    );
    bent.vertices.push(DVec3::ZERO); // not a converted grid any more
    let err =
        unroll_mesh_strips(&bent, StripDirection::Directrix, UnrollOptions::default()).unwrap_err();
    assert!(
        matches!(err, FabricationError::NonPlanarPolygon { strip: 0, .. }),
        "{err}"
    );
}

/// The cut net closed along the plane by one face through every vertex on it (a transom).
fn with_transom() -> (PolygonMesh, usize) {
    let (mut mesh, plane) = cut_net();
    let on = |v: u32| plane.signed_distance(mesh.vertices[v as usize]).abs() < 1e-9;
    // The boundary edges on the plane, chained from an end of the section.
    let mut count = std::collections::HashMap::new();
    for face in mesh.faces() {
        for k in 0..face.len() {
            let (a, b) = (face[k], face[(k + 1) % face.len()]);
            *count.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    let edges: Vec<(u32, u32)> = count
        .into_iter()
        .filter(|&((a, b), n)| n == 1 && on(a) && on(b))
        .map(|(e, _)| e)
        .collect();
    let mut degree = std::collections::HashMap::new();
    for &(a, b) in &edges {
        *degree.entry(a).or_insert(0) += 1;
        *degree.entry(b).or_insert(0) += 1;
    }
    let mut chain = vec![*degree.iter().find(|(_, d)| **d == 1).unwrap().0];
    while chain.len() <= edges.len() {
        let here = *chain.last().unwrap();
        let next = edges.iter().find_map(|&(a, b)| {
            let other = if a == here {
                b
            } else if b == here {
                a
            } else {
                return None;
            };
            (!chain.contains(&other)).then_some(other)
        });
        match next {
            Some(v) => chain.push(v),
            None => break,
        }
    }
    assert_eq!(chain.len(), edges.len() + 1, "one open section");
    mesh.push_face(&chain).unwrap();
    (mesh, chain.len())
}

#[test]
fn a_transom_closing_the_cut_is_unrolled_as_a_panel_of_its_own() {
    let (mesh, corners) = with_transom();
    assert!(corners > 5, "{corners} corners");
    let transom = mesh.face_count() - 1;
    for direction in [StripDirection::Directrix, StripDirection::Generatrix] {
        // Every face once, lengths and angles kept, nothing overlapping (`check`).
        let (count, _) = check(&mesh, direction);
        let u = unroll_mesh_strips(&mesh, direction, UnrollOptions::default()).unwrap();
        assert_eq!(count, u.strips.len());
        let panel = u
            .strips
            .iter()
            .find(|s| s.mesh_faces.contains(&transom))
            .unwrap();
        assert_eq!(panel.mesh_faces, [transom], "the transom alone");
        assert_eq!(panel.label.split_whitespace().next(), Some("P0"));
        assert_eq!(panel.faces[0].len(), corners);
        // The strips are those of the cut net without it.
        let (without, _) = cut_net();
        let strips = mesh_strips(&without, direction).unwrap();
        assert_eq!(u.strips.len(), strips.len() + 1);
    }
}
