//! Property tests over random cone-nets (built with the kernel's C-tube construction): conical and
//! parallel support layers, the parallel transform and unrolling keep their guarantees.

use crate::fab_common;

use cnets_geometry::conenet::{CtubeInputs, construct_ctube};
use cnets_geometry::fabrication::{
    StripDirection, UnrollOptions, conical_support, parallel_support, parallel_transform,
    unroll_strips,
};
use fab_common::*;
use glam::DVec2;
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn support_layers_transform_and_unroll_hold_on_random_cone_nets(
        (directrix, generatrix, apex) in random_design(),
        lambda in 0.4..1.6f64,
        distance in -0.3..0.5f64,
        factors in prop::collection::vec(0.5..1.5f64, 16),
    ) {
        let net = construct_ctube(&CtubeInputs::new(directrix.clone(), generatrix).apex(apex));
        prop_assume!(net.is_ok());
        let net = net.unwrap();
        let mesh = &net.mesh;
        let size = mesh.size();
        prop_assume!(net.quality.max_planarity <= 1e-12);

        let conical = conical_support(&directrix, mesh, &net.apex, lambda).unwrap();
        for i in 0..mesh.rows {
            for j in 0..mesh.cols {
                let d = distance_to_line(conical.at(i, j), net.directrix[j], mesh.at(i, j));
                prop_assert!(d <= 1e-12 * size, "({}, {}) off its axis by {}", i, j, d);
            }
        }
        prop_assert!(max_planarity(&conical) <= 1e-9);
        for j in 0..mesh.cols - 1 {
            for i in 0..mesh.rows {
                let (a, b) = (conical.at(i, j), conical.at(i, j + 1));
                let s = match net.apices[j] {
                    Some(c) => sine(b - a, c - a),
                    None => sine(b - a, net.directrix[j + 1] - net.directrix[j]),
                };
                prop_assert!(s <= 1e-8, "strip {} row {}: apex missed, sine {}", j, i, s);
            }
        }

        let support = parallel_support(&directrix, mesh, distance).unwrap();
        prop_assert!(max_edge_sine(mesh, &support) <= 1e-9);
        prop_assert!(max_planarity(&support) <= 1e-9);

        let mu = &factors[..mesh.rows - 1];
        let nu = &factors[8..8 + mesh.cols - 1];
        let t = parallel_transform(mesh, mu, nu).unwrap();
        let open = mesh.clone().with_wrap(t.mesh.wrap_rows, t.mesh.wrap_cols);
        prop_assert!(max_edge_sine(&open, &t.mesh) <= 1e-9);
        prop_assert!(max_planarity(&t.mesh) <= 1e-9);

        for direction in [StripDirection::Directrix, StripDirection::Generatrix] {
            let u = unroll_strips(mesh, direction, UnrollOptions::default()).unwrap();
            prop_assert!(u.max_length_error <= 1e-9, "{}", u.max_length_error);
            let polys: Vec<Vec<DVec2>> = u
                .strips
                .iter()
                .map(|s| s.outline.points.iter().map(|p| p.truncate()).collect())
                .collect();
            for a in 0..polys.len() {
                for b in a + 1..polys.len() {
                    prop_assert!(!polygons_overlap(&polys[a], &polys[b]));
                }
            }
        }
    }
}
