//! The lines G_{i,j}G_{i,j+1} of each strip j meet at the apex C_j (on the line X_jX_{j+1}), or are
//! parallel to the directrix edge when the apex is at infinity; the quality's cone check agrees
//! (≤ 1e-9 relative).

use crate::common;

use cnets_geometry::conenet::ConeNet;
use cnets_geometry::conenet::{ConstructInputs, CoplanarInputs, construct, construct_coplanar};
use common::{design, sin_angle};
use proptest::prelude::*;

fn check(net: &ConeNet) -> Result<(), TestCaseError> {
    let m = &net.mesh;
    let x = &net.directrix;
    prop_assert_eq!(net.apices.len(), m.cols - 1);
    let size = m.size().max(f64::MIN_POSITIVE);
    for j in 0..m.cols - 1 {
        let edge = x[j + 1] - x[j];
        match net.apices[j] {
            Some(c) => {
                // C_j lies on the line X_j X_{j+1} …
                prop_assert!(sin_angle(c - x[j], edge) <= 1e-9 || (c - x[j]).length() <= 1e-12);
                // … and on every line G_{i,j} G_{i,j+1}.
                for i in 0..m.rows {
                    let (a, b) = (m.at(i, j), m.at(i, j + 1));
                    let s = sin_angle(a - c, b - c);
                    prop_assert!(s <= 1e-9, "strip {j}, row {i}: sin {s:e}");
                }
            }
            None => {
                prop_assert!((net.apex[j] - 1.0).abs() <= 1e-12);
                for i in 0..m.rows {
                    let rung = m.at(i, j + 1) - m.at(i, j);
                    let s = sin_angle(rung, edge);
                    // A rung that has nearly collapsed (a strip pinched to a point) has no
                    // direction to speak of: its end's distance from the parallel through its
                    // start is then held to rounding of the design's size instead (CI seed
                    // 13387616969905358863: a 1.6e-7 rung, sin 1.1e-9, off the parallel by 2e-16).
                    let off = rung.cross(edge).length() / edge.length();
                    prop_assert!(
                        s <= 1e-9 || off <= 1e-12 * size,
                        "strip {j}, row {i}: not parallel (sin {s:e}, off by {off:e})"
                    );
                }
            }
        }
    }
    prop_assert!(
        net.quality.max_cone_residual <= 1e-9,
        "cone residual {:e}",
        net.quality.max_cone_residual
    );
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn strips_meet_at_their_apex(d in design(6, 10)) {
        let net = construct(
            &ConstructInputs::new(d.directrix.clone(), d.generatrix.clone()).apex(d.apex.clone()).ratios(d.ratios.clone()),
        )
        .unwrap();
        check(&net)?;
        let net = construct_coplanar(
            &CoplanarInputs::new(d.directrix.clone(), d.generatrix.clone())
                .apex(d.apex.clone())
                .ruling_ratios(d.rho.clone())
                .plane_ratios(d.tau.clone()),
        )
        .unwrap();
        check(&net)?;
    }
}

#[test]
fn cone_check_flags_a_non_cone_net() {
    use cnets_geometry::conenet::cone_check;
    use cnets_geometry::{DVec3, QuadGrid};
    // A twisted grid: rows are straight lines that do not meet.
    let v = (0..3)
        .flat_map(|i| {
            (0..3).map(move |j| {
                DVec3::new(
                    j as f64,
                    i as f64,
                    (i * j) as f64 * 0.3 + (i * i) as f64 * 0.2 * j as f64,
                )
            })
        })
        .collect();
    let c = cone_check(&QuadGrid::new(3, 3, v).unwrap()).unwrap();
    assert!(c.max > 1e-3, "{c:?}");
}
