//! Ratios r = ½ everywhere, and the coplanar construction with ρ = τ = ½, both reproduce the default
//! (Monge, bisecting-plane) C-tube construction to rounding error (notes §3, §4).

use crate::common;

use cnets_geometry::conenet::{
    ConstructInputs, CoplanarInputs, CtubeInputs, construct, construct_coplanar, construct_ctube,
};
use common::{design, max_vertex_distance};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn half_ratios_and_half_coplanar_equal_monge(d in design(6, 10)) {
        let monge = construct_ctube(
            &CtubeInputs::new(d.directrix.clone(), d.generatrix.clone()).apex(d.apex.clone()),
        )
        .unwrap();
        let size = monge.mesh.size();
        let ratios = construct(
            &ConstructInputs::new(d.directrix.clone(), d.generatrix.clone()).apex(d.apex.clone()).ratios(0.5),
        )
        .unwrap();
        let dev = max_vertex_distance(&monge.mesh, &ratios.mesh);
        prop_assert!(dev <= 1e-12 * size, "ratios ½: deviation {dev:e}");
        let n = monge.mesh.rows;
        // An explicit per-vertex table of ½ takes the same path as the broadcast number.
        let table = construct(
            &ConstructInputs::new(d.directrix.clone(), d.generatrix.clone())
                .apex(d.apex.clone())
                .ratios(vec![vec![0.5; d.apex.len()]; n]),
        )
        .unwrap();
        prop_assert_eq!(&table.mesh, &ratios.mesh);
        let coplanar = construct_coplanar(
            &CoplanarInputs::new(d.directrix.clone(), d.generatrix.clone()).apex(d.apex.clone()),
        )
        .unwrap();
        let dev = max_vertex_distance(&monge.mesh, &coplanar.mesh);
        prop_assert!(dev <= 1e-12 * size, "coplanar ½ ½: deviation {dev:e}");
        // The coplanar ½ ½ planes are the bisecting planes themselves.
        for j in 1..monge.mesh.cols {
            let (a, b) = (monge.normals.get(0, j), coplanar.normals.get(0, j));
            prop_assert!((a - b).length() <= 1e-12, "plane {j}: {a} vs {b}");
        }
    }
}
