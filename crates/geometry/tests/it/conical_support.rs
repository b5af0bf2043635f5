//! The conical support layer: every new vertex on its node axis, planar quads, the same cone apices
//! as the mesh, and the same result as rerunning the construction with the same planes.

use crate::fab_common;

use cnets_geometry::conenet::{CtubeInputs, construct_ctube};
use cnets_geometry::fabrication::{FabricationError, conical_support};
use cnets_geometry::{DVec3, Polyline};
use fab_common::*;

#[test]
fn vertices_lie_on_their_node_axes_and_quads_are_planar() {
    for closed in [false, true] {
        let net = cone_net(6, 8, closed);
        let d = directrix(8);
        let support = conical_support(&d, &net.mesh, &net.apex, 0.8).unwrap();
        let size = net.mesh.size();
        assert_eq!((support.rows, support.cols), (6, 8));
        assert_eq!(support.wrap_rows, closed);
        for i in 0..6 {
            for j in 0..8 {
                let dist = distance_to_line(support.at(i, j), net.directrix[j], net.mesh.at(i, j));
                assert!(dist <= 1e-12 * size, "({i}, {j}) off its axis by {dist}");
                // The new layer is really a different one.
                assert!(support.at(i, j).distance(net.mesh.at(i, j)) > 1e-3);
            }
        }
        let p = max_planarity(&support);
        assert!(p <= 1e-10, "planarity {p}");
        // λ scales the first column about X_0.
        for i in 0..6 {
            let expected = net.directrix[0] + (net.mesh.at(i, 0) - net.directrix[0]) * 0.8;
            assert!(support.at(i, 0).distance(expected) <= 1e-15 * size);
        }
    }
}

#[test]
fn apices_of_both_layers_coincide() {
    let net = cone_net(5, 7, false);
    let support = conical_support(&directrix(7), &net.mesh, &net.apex, 0.6).unwrap();
    let size = net.mesh.size();
    for j in 0..6 {
        for i in 0..5 {
            let (a, b) = (support.at(i, j), support.at(i, j + 1));
            match net.apices[j] {
                Some(c) => {
                    let dist = distance_to_line(c, a, b);
                    assert!(
                        dist <= 1e-10 * (size + c.length()),
                        "strip {j}, row {i}: apex off by {dist}"
                    );
                }
                None => {
                    let e = net.directrix[j + 1] - net.directrix[j];
                    assert!(sine(b - a, e) <= 1e-10, "strip {j}: not a translation");
                }
            }
        }
    }
}

#[test]
fn equals_the_construction_rerun_with_the_same_planes() {
    let net = cone_net(5, 7, false);
    let d = directrix(7);
    let lambda = 1.3;
    let support = conical_support(&d, &net.mesh, &net.apex, lambda).unwrap();
    let scaled = Polyline::open(
        (0..5)
            .map(|i| d.points[0] + (net.mesh.at(i, 0) - d.points[0]) * lambda)
            .collect(),
    );
    let rerun = construct_ctube(
        &CtubeInputs::new(d, scaled)
            .apex(net.apex.clone())
            .normals(net.normals.to_rows()),
    )
    .unwrap();
    let size = net.mesh.size();
    for (p, q) in support.vertices.iter().zip(&rerun.mesh.vertices) {
        assert!(p.distance(*q) <= 1e-11 * size, "{p} vs {q}");
    }
}

#[test]
fn factor_one_reproduces_the_mesh_and_bad_inputs_are_reported() {
    let net = cone_net(4, 5, false);
    let d = directrix(5);
    let same = conical_support(&d, &net.mesh, &net.apex, 1.0).unwrap();
    for (p, q) in same.vertices.iter().zip(&net.mesh.vertices) {
        assert!(p.distance(*q) <= 1e-12 * net.mesh.size());
    }
    assert!(matches!(
        conical_support(&d, &net.mesh, &net.apex[1..], 0.8),
        Err(FabricationError::WrongLength {
            what: "apex",
            got: 3,
            ..
        })
    ));
    assert!(matches!(
        conical_support(&directrix(6), &net.mesh, &net.apex, 0.8),
        Err(FabricationError::DirectrixMismatch { columns: 5, .. })
    ));
    assert!(matches!(
        conical_support(&d, &net.mesh, &net.apex, f64::NAN),
        Err(FabricationError::BadParameter { what: "factor", .. })
    ));
    // A mesh that is not this construction: vertex (2, 3) moved off its support plane, so the step
    // towards the apex misses its axis.
    let mut moved = net.mesh.clone();
    let s = (net.directrix[3] - net.directrix[2])
        .cross(net.mesh.at(2, 2) - net.directrix[2])
        .normalize();
    *moved.at_mut(2, 3) += s * 0.05;
    assert!(matches!(
        conical_support(&d, &moved, &net.apex, 0.8),
        Err(FabricationError::Inconsistent {
            row: 2,
            column: 3,
            ..
        })
    ));
    // A vertex on its directrix point has no axis.
    let mut bad = net.mesh.clone();
    *bad.at_mut(2, 3) = net.directrix[3];
    assert!(matches!(
        conical_support(&d, &bad, &net.apex, 0.8),
        Err(FabricationError::DegenerateAxis { row: 2, column: 3 })
    ));
    let mut nan = net.mesh.clone();
    *nan.at_mut(1, 1) = DVec3::NAN;
    assert!(conical_support(&d, &nan, &net.apex, 0.8).is_err());
}
