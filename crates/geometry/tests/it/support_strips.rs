//! Support strips and beams (issue 17): every quad planar to 1e-12 (relative), every strip unrolled
//! with a length error ≤ 1e-9, on random constructed cone-nets and their conical and parallel layers.

use crate::common;

use cnets_geometry::QuadGrid;
use cnets_geometry::conenet::{ConstructInputs, construct};
use cnets_geometry::fabrication::{
    StripDirection, UnrollOptions, beam_strips, conical_support, directrix_support_strips,
    parallel_support, unroll_strips,
};
use common::{design, max_plane_distance};
use proptest::prelude::*;

/// Largest relative planarity over the strips and largest unroll length error.
fn measure(strips: &[QuadGrid], size: f64) -> (f64, f64) {
    let mut planarity: f64 = 0.0;
    let mut length: f64 = 0.0;
    for s in strips {
        planarity = planarity.max(max_plane_distance(s) / size);
        let u = unroll_strips(s, StripDirection::Directrix, UnrollOptions::default()).unwrap();
        assert_eq!(u.strips.len(), 1);
        length = length.max(u.max_length_error);
    }
    (planarity, length)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn support_strips_and_beams_are_planar_and_unroll_exactly(
        d in design(5, 8),
        factor in 0.8..0.95f64,
        distance in 0.05..0.2f64,
    ) {
        let inputs = ConstructInputs::new(d.directrix.clone(), d.generatrix.clone())
            .apex(d.apex.clone())
            .ratios(d.ratios.clone());
        let Ok(net) = construct(&inputs) else { return Ok(()) };
        let mesh = &net.mesh;
        let size = mesh.size().max(d.directrix.points.iter().map(|p| p.length()).fold(0.0, f64::max));
        let support = directrix_support_strips(&d.directrix, mesh).unwrap();
        prop_assert_eq!(support.len(), mesh.rows);
        let (p, l) = measure(&support, size);
        prop_assert!(p <= 1e-12, "support strip planarity {:e}", p);
        prop_assert!(l <= 1e-9, "support strip unroll error {:e}", l);
        let layers = [
            conical_support(&d.directrix, mesh, &net.apex, factor),
            parallel_support(&d.directrix, mesh, distance),
        ];
        for layer in layers {
            // A layer may be undefined for a random design (an axis parallel to a step); skip those.
            let Ok(layer) = layer else { continue };
            for direction in [StripDirection::Directrix, StripDirection::Generatrix] {
                let beams = beam_strips(mesh, &layer, direction).unwrap();
                let (p, l) = measure(&beams, size);
                prop_assert!(p <= 1e-12, "{} beam planarity {:e}", direction, p);
                prop_assert!(l <= 1e-9, "{} beam unroll error {:e}", direction, l);
            }
        }
    }
}
