//! a ≡ 1 on a straight directrix gives a translational surface: with Monge planes (or ratios ½) every
//! column after the first is the previous one translated by the directrix edge; when the generatrix
//! lies in the plane through X_0 perpendicular to the directrix, every column is a translate of it.

use cnets_geometry::conenet::{ConstructInputs, CtubeInputs, construct, construct_ctube};
use cnets_geometry::{DVec3, Polyline};
use proptest::prelude::*;

fn straight(dir: DVec3, lengths: &[f64]) -> Polyline {
    let d = dir.normalize();
    let mut p = DVec3::new(0.3, -0.2, 0.1);
    let mut points = vec![p];
    for l in lengths {
        p += d * *l;
        points.push(p);
    }
    Polyline::open(points)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn translational_surface(
        dir in (-1.0..1.0f64, -1.0..1.0f64, 0.3..1.0f64),
        lengths in prop::collection::vec(0.2..2.0f64, 1..8),
        offsets in prop::collection::vec((-2.0..2.0f64, -2.0..2.0f64, -0.5..0.5f64), 2..6),
    ) {
        let dir = DVec3::new(dir.0, dir.1, dir.2);
        let directrix = straight(dir, &lengths);
        let e = dir.normalize();
        let u = e.any_orthonormal_vector();
        let v = e.cross(u);
        let x0 = directrix.points[0];
        // A generatrix that leaves the perpendicular plane (along-e offsets), away from the axis.
        let generatrix = Polyline::open(
            offsets.iter().enumerate().map(|(i, (a, b, s))| x0 + u * (a + 3.0 + i as f64) + v * *b + e * *s).collect(),
        );
        for net in [
            construct_ctube(&CtubeInputs::new(directrix.clone(), generatrix.clone())).unwrap(),
            construct(&ConstructInputs::new(directrix.clone(), generatrix.clone())).unwrap(),
        ] {
            let m = &net.mesh;
            let tol = 1e-12 * m.size();
            for i in 0..m.rows {
                for j in 1..m.cols - 1 {
                    let step = m.at(i, j + 1) - m.at(i, j);
                    let edge = directrix.points[j + 1] - directrix.points[j];
                    prop_assert!((step - edge).length() <= tol, "({i},{j}): {step} vs {edge}");
                }
                // Column 1 lies in the perpendicular plane through X_1, reached along e.
                let g1 = m.at(i, 1);
                prop_assert!((g1 - directrix.points[1]).dot(e).abs() <= tol);
                prop_assert!((g1 - m.at(i, 0)).cross(e).length() <= tol);
            }
            prop_assert_eq!(&net.apices, &vec![None; lengths.len()]);
        }
        // Generatrix in the perpendicular plane: every column is a translate of the generatrix.
        let flat = Polyline::open(
            offsets.iter().enumerate().map(|(i, (a, b, _))| x0 + u * (a + 3.0 + i as f64) + v * *b).collect(),
        );
        let net = construct_ctube(&CtubeInputs::new(directrix.clone(), flat.clone())).unwrap();
        let tol = 1e-12 * net.mesh.size();
        for i in 0..net.mesh.rows {
            for j in 0..net.mesh.cols {
                let expected = flat.points[i] + (directrix.points[j] - x0);
                prop_assert!((net.mesh.at(i, j) - expected).length() <= tol);
            }
        }
    }
}
