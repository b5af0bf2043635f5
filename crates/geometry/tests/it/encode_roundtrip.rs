//! Encoder round trip (paper Proposition 1, notes §8): a random cone-net → encode → C-tube
//! construction reproduces it (≤ 1e-9 relative), with a_j > 0 and N × (M−1) normals; meshes that are
//! not cone-nets are rejected naming the strip.

use crate::common;

use cnets_geometry::conenet::{
    ConstructInputs, CoplanarInputs, construct, construct_coplanar, construct_ctube, encode,
};
use cnets_geometry::{DVec3, GeometryError, QuadGrid};
use common::{design, max_vertex_distance};
use proptest::prelude::*;

/// Bounding-box diagonal of the design's directrix and generatrix.
fn design_size(d: &common::Design) -> f64 {
    let points: Vec<DVec3> = d
        .directrix
        .points
        .iter()
        .chain(&d.generatrix.points)
        .copied()
        .collect();
    let lo = points.iter().fold(DVec3::INFINITY, |a, p| a.min(*p));
    let hi = points.iter().fold(DVec3::NEG_INFINITY, |a, p| a.max(*p));
    lo.distance(hi)
}

fn round_trip(mesh: &QuadGrid) -> Result<(), TestCaseError> {
    let enc = encode(mesh).map_err(|e| TestCaseError::fail(format!("encode failed: {e}")))?;
    prop_assert_eq!(enc.apex.len(), mesh.cols - 1);
    prop_assert!(enc.apex.iter().all(|&a| a > 0.0), "apex {:?}", enc.apex);
    prop_assert_eq!(enc.normals.len(), mesh.rows);
    prop_assert!(enc.normals.iter().all(|r| r.len() == mesh.cols - 1));
    prop_assert_eq!(enc.directrix.points.len(), mesh.cols);
    prop_assert_eq!(enc.generatrix.closed, mesh.wrap_rows);
    let rebuilt = construct_ctube(&enc.to_ctube_inputs()).unwrap();
    let dev = max_vertex_distance(&rebuilt.mesh, mesh);
    prop_assert!(
        dev <= 1e-9 * mesh.size(),
        "deviation {dev:e} (size {})",
        mesh.size()
    );
    prop_assert_eq!(rebuilt.mesh.wrap_rows, mesh.wrap_rows);
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

        /// Random designs can throw a vertex far beyond the design (a ray meeting its plane almost
    /// tangentially); such meshes amplify every rounding error by that conditioning, so the 1e-9
    /// relative bound is checked on well-conditioned meshes (within 100 design sizes).
    #[test]
    fn random_cone_nets_round_trip(d in design(6, 10)) {
        let net = construct(
            &ConstructInputs::new(d.directrix.clone(), d.generatrix.clone())
                .apex(d.apex.clone())
                .ratios(d.ratios.clone()),
        )
        .unwrap();
        prop_assume!(net.mesh.size() < 100.0 * design_size(&d));
        round_trip(&net.mesh)?;
        let net = construct_coplanar(
            &CoplanarInputs::new(d.directrix.clone(), d.generatrix.clone())
                .apex(d.apex.clone())
                .ruling_ratios(d.rho.clone())
                .plane_ratios(d.tau.clone()),
        )
                .unwrap();
        prop_assume!(net.mesh.size() < 100.0 * design_size(&d));
        round_trip(&net.mesh)?;
    }

    /// Negative apex values (the apex between X_{j−1} and X_j) still encode with a_j > 0.
    #[test]
    fn negative_apex_values_encode_positively(d in design(5, 6), neg in 0usize..5) {
        let mut apex = d.apex.clone();
        let k = neg % apex.len();
        apex[k] = -0.6;
        let net = construct(&ConstructInputs::new(d.directrix.clone(), d.generatrix.clone()).apex(apex)).unwrap();
        // A negative apex can throw vertices far beyond the design (near-parallel intersections);
        // keep to well-conditioned meshes so that the 1e-9 bound stays meaningful.
                prop_assume!(net.mesh.size() < 100.0 * design_size(&d));
        round_trip(&net.mesh)?;
    }
}

#[test]
fn closed_generatrix_round_trips() {
    let directrix = cnets_geometry::Polyline::open(
        (0..6)
            .map(|j| DVec3::new(j as f64, 0.3 * (j as f64).sin(), 0.1 * j as f64))
            .collect(),
    );
    let ring = cnets_geometry::Polyline::closed(
        (0..7)
            .map(|k| {
                let t = k as f64 * std::f64::consts::TAU / 7.0;
                DVec3::new(0.1 * t.sin(), 1.5 * t.cos(), 1.5 * t.sin())
            })
            .collect(),
    );
    let net = construct(
        &ConstructInputs::new(directrix, ring)
            .apex(vec![1.1, 0.9, 1.0, 1.2, 0.8])
            .ratios(0.45),
    )
    .unwrap();
    let enc = encode(&net.mesh).unwrap();
    assert!(enc.generatrix.closed);
    let rebuilt = construct_ctube(&enc.to_ctube_inputs()).unwrap();
    assert!(max_vertex_distance(&rebuilt.mesh, &net.mesh) <= 1e-9 * net.mesh.size());
}

#[test]
fn non_cone_nets_and_bad_meshes_are_rejected() {
    // Rows are straight lines in parallel planes with different slopes: the lines of a strip do not
    // meet (not even at infinity).
    let v = (0..3)
        .flat_map(|i| {
            (0..4).map(move |j| {
                DVec3::new(
                    j as f64,
                    i as f64,
                    0.4 * (i * j) as f64 + 0.3 * (i * i * j) as f64,
                )
            })
        })
        .collect();
    let mesh = QuadGrid::new(3, 4, v).unwrap();
    match encode(&mesh) {
        Err(GeometryError::NotAConeNet { column, residual }) => {
            assert!(column < 3 && residual > 1e-6);
        }
        other => panic!("expected NotAConeNet, got {other:?}"),
    }
    let wrapped = QuadGrid::new(2, 2, vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE])
        .unwrap()
        .with_wrap(false, true);
    assert!(matches!(
        encode(&wrapped),
        Err(GeometryError::Unsupported(_))
    ));
    let thin = QuadGrid::new(1, 3, vec![DVec3::ZERO, DVec3::X, DVec3::Y]).unwrap();
    assert!(matches!(
        encode(&thin),
        Err(GeometryError::TooFewPoints { .. })
    ));
    let nan = QuadGrid::new(
        2,
        2,
        vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::splat(f64::NAN)],
    )
    .unwrap();
    assert!(matches!(
        encode(&nan),
        Err(GeometryError::NonFinite { index: 3, .. })
    ));
    let coincident =
        QuadGrid::new(2, 2, vec![DVec3::ZERO, DVec3::ZERO, DVec3::Y, DVec3::ONE]).unwrap();
    assert!(matches!(
        encode(&coincident),
        Err(GeometryError::ZeroLengthEdge {
            index: 0,
            next: 1,
            ..
        })
    ));
}
