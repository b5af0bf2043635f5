//! Unrolling strips: edge lengths and face angles preserved, strips flat in XY, no two strips
//! overlap, closed strips cut open, non-planar faces rejected (or, above the tolerance, reported).

use crate::fab_common;

use cnets_geometry::conenet::{CtubeInputs, construct_ctube};
use cnets_geometry::fabrication::{FabricationError, StripDirection, UnrollOptions, unroll_strips};
use cnets_geometry::{DVec3, Polyline, QuadGrid};
use fab_common::*;
use glam::DVec2;

fn angle(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}

/// Checks lengths, angles, flatness and overlap of an unrolled mesh.
fn check(mesh: &QuadGrid, direction: StripDirection) {
    let u = unroll_strips(mesh, direction, UnrollOptions::default()).unwrap();
    let expected = match direction {
        StripDirection::Directrix => mesh.quad_rows(),
        StripDirection::Generatrix => mesh.quad_cols(),
    };
    assert_eq!(u.strips.len(), expected);
    assert!(u.max_length_error <= 1e-9, "{}", u.max_length_error);
    let mut worst_len = 0.0f64;
    let mut worst_angle = 0.0f64;
    for s in &u.strips {
        assert_eq!(s.quads.len(), s.mesh_quads.len());
        for (flat, &(i, j)) in s.quads.iter().zip(&s.mesh_quads) {
            let q = mesh.quad(i, j);
            for k in 0..4 {
                assert_eq!(flat[k].z, 0.0);
                let (l3, l2) = (
                    q[k].distance(q[(k + 1) % 4]),
                    flat[k].distance(flat[(k + 1) % 4]),
                );
                worst_len = worst_len.max((l3 - l2).abs() / l3);
                let a3 = angle(q[(k + 1) % 4] - q[k], q[(k + 3) % 4] - q[k]);
                let a2 = angle(flat[(k + 1) % 4] - flat[k], flat[(k + 3) % 4] - flat[k]);
                worst_angle = worst_angle.max((a3 - a2).abs());
            }
        }
        assert!(s.outline.closed);
        assert!(s.outline.points.iter().all(|p| p.z == 0.0));
        let rungs = s.quads.len() + 1;
        assert_eq!(s.outline.points.len(), 2 * rungs);
        let poly: Vec<DVec2> = s.outline.points.iter().map(|p| p.truncate()).collect();
        assert!(
            inside(s.label_point.truncate(), &poly),
            "label of {} outside",
            s.label
        );
    }
    assert!(worst_len <= 1e-9, "edge length changed by {worst_len}");
    assert!(worst_angle <= 1e-9, "face angle changed by {worst_angle}");
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
    let labels: Vec<&str> = u.strips.iter().map(|s| s.label.as_str()).collect();
    let prefix = if direction == StripDirection::Directrix {
        "D"
    } else {
        "G"
    };
    assert_eq!(labels[1], format!("{prefix}1"));
}

#[test]
fn lengths_and_angles_are_kept_and_strips_do_not_overlap() {
    for closed in [false, true] {
        let net = cone_net(6, 9, closed);
        check(&net.mesh, StripDirection::Directrix);
        check(&net.mesh, StripDirection::Generatrix);
    }
}

#[test]
fn a_prism_ring_unrolls_to_a_rectangle_of_its_perimeter() {
    // Regular octagon of radius 1 swept straight along x by 2 (a = 1): each generatrix strip is a
    // closed ring of 8 rectangles 2 sin(π/8) wide and 1 long.
    let octagon = Polyline::closed(
        (0..8)
            .map(|i| {
                let t = std::f64::consts::TAU * i as f64 / 8.0;
                DVec3::new(0.0, t.cos(), t.sin())
            })
            .collect(),
    );
    let line = Polyline::open(vec![DVec3::ZERO, DVec3::X, DVec3::X * 2.0]);
    let net = construct_ctube(&CtubeInputs::new(line, octagon)).unwrap();
    let u = unroll_strips(
        &net.mesh,
        StripDirection::Generatrix,
        UnrollOptions::default(),
    )
    .unwrap();
    assert_eq!(u.strips.len(), 2);
    let perimeter = 16.0 * (std::f64::consts::PI / 8.0).sin();
    for s in &u.strips {
        assert_eq!(s.quads.len(), 8);
        let (lo, hi) = cnets_geometry::quad_grid::bounds_of(&s.outline.points).unwrap();
        let size = hi - lo;
        assert!((size.x - perimeter).abs() < 1e-12, "{size}");
        assert!((size.y - 1.0).abs() < 1e-12, "{size}");
    }
    // Stacked with the default gap: a tenth of the tallest strip.
    let lo1 = cnets_geometry::quad_grid::bounds_of(&u.strips[1].outline.points)
        .unwrap()
        .0;
    assert!((lo1.y - 1.1).abs() < 1e-12);
}

#[test]
fn non_planar_faces_are_rejected_with_their_indices_or_reported_when_allowed() {
    let net = cone_net(5, 6, false);
    let mut bent = net.mesh.clone();
    *bent.at_mut(2, 3) += DVec3::new(0.0, 0.0, 0.05);
    let err =
        unroll_strips(&bent, StripDirection::Directrix, UnrollOptions::default()).unwrap_err();
    // Vertex (2, 3) is a corner of quads (1, 2), (1, 3), (2, 2), (2, 3): strip 1 fails first, at quad 2.
    match &err {
        FabricationError::NonPlanarFace {
            strip,
            quad,
            row,
            column,
            ..
        } => {
            assert_eq!((*strip, *quad, *row, *column), (1, 2, 1, 2));
        }
        other => panic!("unexpected {other:?}"),
    }
    assert!(err.to_string().contains("strip 1, quad 2"), "{err}");
    let loose = UnrollOptions {
        tolerance: 1.0,
        spacing: Some(0.5),
    };
    let u = unroll_strips(&bent, StripDirection::Directrix, loose).unwrap();
    assert!(u.max_length_error > 1e-5, "{}", u.max_length_error);
    assert!(u.max_length_error < 0.1);
}

#[test]
fn bad_options_and_meshes_are_reported() {
    let net = cone_net(4, 5, false);
    let bad = UnrollOptions {
        tolerance: f64::NAN,
        spacing: None,
    };
    assert!(unroll_strips(&net.mesh, StripDirection::Directrix, bad).is_err());
    let bad = UnrollOptions {
        tolerance: 1e-6,
        spacing: Some(-1.0),
    };
    assert!(unroll_strips(&net.mesh, StripDirection::Directrix, bad).is_err());
    let empty = QuadGrid::default();
    assert!(matches!(
        unroll_strips(&empty, StripDirection::Generatrix, UnrollOptions::default()),
        Err(FabricationError::Empty("mesh"))
    ));
    let mut collapsed = net.mesh.clone();
    let p = collapsed.at(1, 1);
    *collapsed.at_mut(2, 1) = p;
    assert!(
        unroll_strips(
            &collapsed,
            StripDirection::Directrix,
            UnrollOptions::default()
        )
        .is_err()
    );
    assert!("sideways".parse::<StripDirection>().is_err());
    assert_eq!(
        " Generatrix ".parse::<StripDirection>().unwrap(),
        StripDirection::Generatrix
    );
}

#[test]
fn the_overlap_check_itself_detects_overlap() {
    let square = |x: f64, y: f64| {
        vec![
            DVec2::new(x, y),
            DVec2::new(x + 1.0, y),
            DVec2::new(x + 1.0, y + 1.0),
            DVec2::new(x, y + 1.0),
        ]
    };
    assert!(polygons_overlap(&square(0.0, 0.0), &square(0.5, 0.5)));
    assert!(polygons_overlap(
        &square(0.0, 0.0),
        &[
            DVec2::new(0.2, 0.2),
            DVec2::new(0.4, 0.2),
            DVec2::new(0.3, 0.4)
        ]
    ));
    assert!(!polygons_overlap(&square(0.0, 0.0), &square(0.0, 1.1)));
}
