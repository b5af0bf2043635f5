//! The coplanar construction makes every generatrix-aligned polyline G_{:,j} (j ≥ 1) planar: all its
//! points lie in the reported plane Π_j through X_j, and (checked independently of the reported
//! normal) every four of them span no volume.

use crate::common;

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

/// On a straight directrix the outgoing edge lies in the support plane of strip 0, so the flip of
/// n_in is undefined; the kernel then takes ψ_out = π: τ = ½ is the plane perpendicular to the
/// directrix (the Monge plane) and τ ≠ ½ tilts the plane about the ruling of strip 0, the same way
/// for every column.
#[test]
fn straight_directrix_uses_psi_out_pi() {
    use cnets_geometry::conenet::{CtubeInputs, construct_ctube};
    use cnets_geometry::{DVec3, Polyline};
    let directrix = Polyline::open((0..5).map(|j| DVec3::new(j as f64, 0.0, 0.0)).collect());
    let generatrix = Polyline::open(vec![
        DVec3::new(0.0, 1.0, 0.0),
        DVec3::new(0.0, 1.2, 0.8),
        DVec3::new(0.0, 0.8, 1.5),
    ]);
    let monge = construct_ctube(&CtubeInputs::new(directrix.clone(), generatrix.clone())).unwrap();
    let half =
        construct_coplanar(&CoplanarInputs::new(directrix.clone(), generatrix.clone())).unwrap();
    assert!(common::max_vertex_distance(&monge.mesh, &half.mesh) < 1e-14);
    for j in 1..5 {
        assert!((half.normals.get(0, j) - DVec3::X).length() < 1e-15);
    }
    // τ = ¾: ψ = ¾ π, P = cos ψ n_in + sin ψ u with n_in = w × ê = ẑ-ish normal of the support plane
    // of strip 0 (the plane y-x through G_{0,0} = (0, 1, 0), w = ŷ): n_in = ŷ × x̂ = −ẑ, u = x̂.
    let tilted =
        construct_coplanar(&CoplanarInputs::new(directrix, generatrix).plane_ratios(0.75)).unwrap();
    let psi = 0.75 * std::f64::consts::PI;
    let expected = DVec3::new(psi.sin(), 0.0, -psi.cos());
    for j in 1..5 {
        assert!(
            (tilted.normals.get(0, j) - expected).length() < 1e-14,
            "{}",
            tilted.normals.get(0, j)
        );
    }
}
