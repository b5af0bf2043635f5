//! The parallel support layer: every edge parallel to its counterpart, planar faces, vertices on the
//! node axes, the start vertex at the requested distance.

use crate::fab_common;

use cnets_geometry::fabrication::{FabricationError, parallel_support};
use fab_common::*;

#[test]
fn edges_are_parallel_faces_planar_and_vertices_on_axes() {
    for (closed, distance) in [(false, 0.3), (true, -0.25), (false, 1.5)] {
        let net = cone_net(6, 8, closed);
        let h = parallel_support(&directrix(8), &net.mesh, distance).unwrap();
        assert_eq!(h.wrap_rows, closed);
        let s = max_edge_sine(&net.mesh, &h);
        assert!(s <= 1e-9, "edges not parallel: sine {s}");
        let p = max_planarity(&h);
        assert!(p <= 1e-10, "planarity {p}");
        let size = net.mesh.size();
        for i in 0..6 {
            for j in 0..8 {
                let dist = distance_to_line(h.at(i, j), net.directrix[j], net.mesh.at(i, j));
                assert!(dist <= 1e-12 * size, "({i}, {j}) off its axis by {dist}");
                assert!(h.at(i, j).distance(net.mesh.at(i, j)) > 1e-3);
            }
        }
        let start = h.at(0, 0) - net.mesh.at(0, 0);
        assert!((start.length() - distance.abs()).abs() <= 1e-14);
        // Positive distance moves away from the directrix.
        let outward = net.mesh.at(0, 0) - net.directrix[0];
        assert_eq!(start.dot(outward) > 0.0, distance > 0.0);
    }
}

#[test]
fn bad_inputs_are_reported() {
    let net = cone_net(4, 5, false);
    assert!(matches!(
        parallel_support(&directrix(5), &net.mesh, f64::INFINITY),
        Err(FabricationError::BadParameter {
            what: "distance",
            ..
        })
    ));
    let mut dup = net.mesh.clone();
    *dup.at_mut(1, 2) = dup.at(1, 1);
    assert!(parallel_support(&directrix(5), &dup, 0.2).is_err());
    assert!(matches!(
        parallel_support(&directrix(3), &net.mesh, 0.2),
        Err(FabricationError::DirectrixMismatch { .. })
    ));
}
