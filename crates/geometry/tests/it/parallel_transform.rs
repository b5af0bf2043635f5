//! The parallel (Combescure) transform: boundary edges scaled by μ and ν, every edge parallel to its
//! counterpart, planar faces; closure of wrapped meshes.

use crate::fab_common;

use cnets_geometry::fabrication::{FabricationError, parallel_transform};
use fab_common::*;

#[test]
fn edges_are_parallel_and_faces_planar() {
    let net = cone_net(6, 8, false);
    let mu = [1.0, 1.3, 0.8, 1.1, 0.9];
    let nu = [0.7, 1.2, 1.0, 1.4, 0.9, 1.1, 1.25];
    let t = parallel_transform(&net.mesh, &mu, &nu).unwrap();
    let h = &t.mesh;
    let s = max_edge_sine(&net.mesh, h);
    assert!(s <= 1e-9, "sine {s}");
    let p = max_planarity(h);
    assert!(p <= 1e-10, "planarity {p}");
    assert_eq!(h.at(0, 0), net.mesh.at(0, 0));
    for (i, m) in mu.iter().enumerate() {
        let want = (net.mesh.at(i + 1, 0) - net.mesh.at(i, 0)) * *m;
        assert!((h.at(i + 1, 0) - h.at(i, 0) - want).length() <= 1e-14);
    }
    for (j, n) in nu.iter().enumerate() {
        let want = (net.mesh.at(0, j + 1) - net.mesh.at(0, j)) * *n;
        assert!((h.at(0, j + 1) - h.at(0, j) - want).length() <= 1e-14);
    }
    // Non-uniform factors change the shape.
    assert!(
        h.vertices
            .iter()
            .zip(&net.mesh.vertices)
            .any(|(a, b)| a.distance(*b) > 0.05)
    );
}

#[test]
fn uniform_factors_scale_the_mesh_and_keep_a_closed_generatrix_closed() {
    let net = cone_net(7, 6, true);
    let t = parallel_transform(&net.mesh, &[1.5], &[1.5]).unwrap();
    assert!(t.mesh.wrap_rows);
    assert_eq!(t.dropped_wrap, (false, false));
    let o = net.mesh.at(0, 0);
    for (a, b) in t.mesh.vertices.iter().zip(&net.mesh.vertices) {
        assert!(a.distance(o + (*b - o) * 1.5) <= 1e-12 * net.mesh.size());
    }
    // Uneven μ on a closed generatrix cannot close: the closing quads are dropped.
    let mu = [1.0, 1.4, 1.0, 0.8, 1.2, 1.0];
    let open = parallel_transform(&net.mesh, &mu, &[1.0]).unwrap();
    assert!(!open.mesh.wrap_rows);
    assert_eq!(open.dropped_wrap, (true, false));
    assert!(max_edge_sine(&net.mesh.clone().with_wrap(false, false), &open.mesh) <= 1e-9);
}

#[test]
fn bad_factors_and_degenerate_meshes_are_reported() {
    let net = cone_net(4, 5, false);
    assert!(matches!(
        parallel_transform(&net.mesh, &[1.0, 2.0], &[1.0]),
        Err(FabricationError::WrongLength {
            what: "mu",
            got: 2,
            ..
        })
    ));
    assert!(matches!(
        parallel_transform(&net.mesh, &[1.0], &[1.0, 0.0, 1.0, 1.0]),
        Err(FabricationError::BadEntry {
            what: "nu",
            index: 1,
            ..
        })
    ));
    assert!(matches!(
        parallel_transform(&net.mesh, &[f64::NAN], &[1.0]),
        Err(FabricationError::BadEntry {
            what: "mu",
            index: 0,
            ..
        })
    ));
    let mut dup = net.mesh.clone();
    *dup.at_mut(2, 3) = dup.at(2, 2);
    assert!(matches!(
        parallel_transform(&dup, &[1.0], &[1.0]),
        Err(FabricationError::ZeroEdge { .. })
    ));
    let tiny = cnets_geometry::QuadGrid::new(1, 3, vec![cnets_geometry::DVec3::ZERO; 3]).unwrap();
    assert!(matches!(
        parallel_transform(&tiny, &[1.0], &[1.0]),
        Err(FabricationError::TooSmall { .. })
    ));
}
