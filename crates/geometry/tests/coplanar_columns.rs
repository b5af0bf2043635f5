//! The coplanar construction makes every generatrix-aligned polyline G_{:,j} (j ≥ 1) planar: all its
//! points lie in the reported plane Π_j through X_j, and (checked independently of the reported
//! normal) every four of them span no volume.

mod common;

use cnets_geometry::conenet::{CoplanarInputs, construct_coplanar};
use common::design;
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn every_column_is_planar(d in design(7, 9), alpha in prop_oneof![Just(-1.0), Just(0.0), Just(0.5), Just(1.0)]) {
        let inputs = CoplanarInputs::new(d.directrix.clone(), d.generatrix.clone())
            .apex(d.apex.clone())
            .ruling_ratios(d.rho.clone())
            .plane_ratios(d.tau.clone())
            .assistance(alpha);
        let net = construct_coplanar(&inputs).unwrap();
        let mesh = &net.mesh;
        let size = mesh.size();
        prop_assert!(net.normals.is_shared());
        for j in 1..mesh.cols {
            let p = net.normals.get(0, j);
            for i in 0..mesh.rows {
                prop_assert_eq!(net.normals.get(i, j), p);
                let dist = (mesh.at(i, j) - net.directrix[j]).dot(p).abs();
                prop_assert!(dist <= 1e-12 * size, "({i},{j}) off its plane by {dist:e}");
            }
            // Independent check: tetrahedron volumes of (G_0, G_1, G_k, G_l) relative to size³.
            let g = |i: usize| mesh.at(i, j);
            for k in 2..mesh.rows {
                for l in k + 1..mesh.rows {
                    let vol = (g(1) - g(0)).cross(g(k) - g(0)).dot(g(l) - g(0)).abs();
                    prop_assert!(vol <= 1e-11 * size * size * size, "column {j}: volume {vol:e}");
                }
            }
        }
    }
}
