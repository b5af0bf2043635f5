//! Every quad of every construction is planar to rounding error: the distance of a vertex from the
//! plane of the other three (the best-conditioned choice) is at most 1e-12 × the mesh size, over
//! random valid designs.

use crate::common;

use cnets_geometry::conenet::{
    ConstructInputs, CoplanarInputs, CtubeInputs, construct, construct_coplanar, construct_ctube,
};
use common::{Design, design, max_plane_distance};
use proptest::prelude::*;

fn check(mesh: &cnets_geometry::QuadGrid) -> Result<(), TestCaseError> {
    let size = mesh.size();
    let dist = max_plane_distance(mesh);
    prop_assert!(
        dist <= 1e-12 * size,
        "plane distance {dist:e} for mesh size {size}"
    );
    Ok(())
}

fn ctube_with_normals(d: &Design) -> CtubeInputs {
    // Monge normals of the directrix perturbed per vertex.
    let x = &d.directrix.points;
    let normals = d
        .normal_noise
        .iter()
        .map(|row| {
            row.iter()
                .enumerate()
                .map(|(k, noise)| {
                    let j = k + 1;
                    let e = (x[j] - x[j - 1]).normalize();
                    let out = if j + 1 < x.len() {
                        (x[j + 1] - x[j]).normalize()
                    } else {
                        e
                    };
                    (e + out).normalize() + *noise
                })
                .collect()
        })
        .collect::<Vec<Vec<_>>>();
    CtubeInputs::new(d.directrix.clone(), d.generatrix.clone())
        .apex(d.apex.clone())
        .normals(normals)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn ctube_with_random_normals_has_planar_quads(d in design(6, 10)) {
        let net = construct_ctube(&ctube_with_normals(&d)).unwrap();
        check(&net.mesh)?;
        prop_assert!(net.quality.max_cone_residual <= 1e-9);
    }

    #[test]
    fn construct_with_random_ratios_has_planar_quads(d in design(6, 10)) {
        let inputs = ConstructInputs::new(d.directrix.clone(), d.generatrix.clone())
            .apex(d.apex.clone())
            .ratios(d.ratios.clone());
        let net = construct(&inputs).unwrap();
        check(&net.mesh)?;
        // With assistance the mesh is still planar (corrections move planes and apex values only).
        let assisted = construct(&inputs.assistance(0.5)).unwrap();
        check(&assisted.mesh)?;
    }

    #[test]
    fn coplanar_has_planar_quads(d in design(6, 10)) {
        let inputs = CoplanarInputs::new(d.directrix.clone(), d.generatrix.clone())
            .apex(d.apex.clone())
            .ruling_ratios(d.rho.clone())
            .plane_ratios(d.tau.clone());
        let net = construct_coplanar(&inputs).unwrap();
        check(&net.mesh)?;
        let assisted = construct_coplanar(&inputs.assistance(0.5)).unwrap();
        check(&assisted.mesh)?;
    }
}
