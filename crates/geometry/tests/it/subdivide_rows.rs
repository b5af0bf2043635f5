//! `cnets.subdivide_rows` (issue 17): the fine rows lie on the coarse faces (≤ 1e-12 relative), the
//! coarse rows are kept bit for bit, the fine net is a planar cone-net with the coarse apices.

use crate::common;

use cnets_geometry::conenet::{ConstructInputs, cone_check, construct, subdivide_rows};
use cnets_geometry::{DVec3, Polyline, QuadGrid};
use common::{design, face_plane, max_plane_distance};
use proptest::prelude::*;

/// The checks of one subdivision; returns the largest relative on-face distance.
fn check(coarse: &QuadGrid, count: usize) -> Result<f64, TestCaseError> {
    let fine = subdivide_rows(coarse, count).unwrap();
    let (n, m) = (coarse.rows, coarse.cols);
    let strips = if coarse.wrap_rows { n } else { n - 1 };
    prop_assert_eq!(fine.rows, strips * count + usize::from(!coarse.wrap_rows));
    prop_assert_eq!(fine.cols, m);
    prop_assert_eq!(fine.wrap_rows, coarse.wrap_rows);
    let size = coarse.size().max(f64::MIN_POSITIVE);
    let mut worst: f64 = 0.0;
    for i in 0..n {
        // Original rows bit for bit.
        for j in 0..m {
            prop_assert_eq!(
                fine.at(i * count, j).to_array().map(f64::to_bits),
                coarse.at(i, j).to_array().map(f64::to_bits)
            );
        }
    }
    for s in 0..strips {
        let (i, i1) = (s, (s + 1) % n);
        for k in 1..count {
            for j in 0..m {
                let v = fine.at(s * count + k, j);
                // On the coarse edge G_ij G_i+1,j (distance from its line)…
                let (a, b) = (coarse.at(i, j), coarse.at(i1, j));
                let e = b - a;
                let off_edge = if e == DVec3::ZERO {
                    v.distance(a)
                } else {
                    (v - a).cross(e).length() / e.length()
                };
                worst = worst.max(off_edge / size);
                // …and on the planes of the coarse faces on either side.
                for jf in [j.checked_sub(1), Some(j)].into_iter().flatten() {
                    if jf + 1 >= m {
                        continue;
                    }
                    let q = [
                        coarse.at(i, jf),
                        coarse.at(i, jf + 1),
                        coarse.at(i1, jf + 1),
                        coarse.at(i1, jf),
                    ];
                    if let Some((point, normal)) = face_plane(q) {
                        worst = worst.max((v - point).dot(normal).abs() / size);
                    }
                }
            }
        }
    }
    prop_assert!(worst <= 1e-12, "on-face distance {:e}", worst);
    // Every fine quad planar, and the fine net a cone-net with the coarse apices.
    let planarity = max_plane_distance(&fine) / size;
    prop_assert!(planarity <= 1e-12, "fine planarity {:e}", planarity);
    let (coarse_cones, fine_cones) = (cone_check(coarse).unwrap(), cone_check(&fine).unwrap());
    prop_assert!(
        fine_cones.max <= 1e-9,
        "fine cone residual {:e}",
        fine_cones.max
    );
    for (a, b) in coarse_cones.apices.iter().zip(&fine_cones.apices) {
        // Far apices (a ≈ 1) are ill-conditioned fits; compare the ones near the design.
        if let (Some(a), Some(b)) = (a, b)
            && a.length() < 100.0 * size
        {
            let scale = a.length().max(size);
            prop_assert!(a.distance(*b) <= 1e-6 * scale, "apex {} vs {}", a, b);
        }
    }
    Ok(worst)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Random cone-nets (varying apex function and ratios), count 1 … 4.
    #[test]
    fn fine_rows_lie_on_the_coarse_faces(d in design(6, 9), count in 1usize..5) {
        let inputs = ConstructInputs::new(d.directrix.clone(), d.generatrix.clone())
            .apex(d.apex.clone())
            .ratios(d.ratios.clone());
        let Ok(net) = construct(&inputs) else { return Ok(()) };
        check(&net.mesh, count)?;
    }
}

#[test]
fn closed_generatrix_keeps_wrapping_and_translations_project_in_parallel() {
    // a ≡ 1 (every apex at infinity): the projection is parallel; a closed generatrix wraps.
    let directrix = Polyline::open(vec![
        DVec3::ZERO,
        DVec3::new(1.0, 0.2, 0.0),
        DVec3::new(2.0, 0.1, 0.3),
        DVec3::new(3.0, -0.2, 0.2),
    ]);
    let generatrix = Polyline::closed(
        (0..5)
            .map(|i| {
                let t = std::f64::consts::TAU * i as f64 / 5.0;
                DVec3::new(0.1 * t.sin(), t.cos(), 0.7 * t.sin())
            })
            .collect(),
    );
    let net = construct(&ConstructInputs::new(directrix.clone(), generatrix.clone())).unwrap();
    let worst = check(&net.mesh, 3).unwrap();
    assert!(worst <= 1e-12);
    let fine = subdivide_rows(&net.mesh, 3).unwrap();
    assert_eq!(fine.rows, 15);
    // With a varying apex function (finite apices) too.
    let net = construct(
        &ConstructInputs::new(directrix, generatrix)
            .apex(vec![0.9, 1.1, 0.95])
            .ratios(vec![0.45, 0.55, 0.5]),
    )
    .unwrap();
    check(&net.mesh, 2).unwrap();
}

#[test]
fn count_one_is_the_identity() {
    let mesh = QuadGrid::new(
        3,
        2,
        vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::Y,
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::Y * 2.0,
            DVec3::new(1.0, 2.0, 0.0),
        ],
    )
    .unwrap();
    assert_eq!(subdivide_rows(&mesh, 1).unwrap(), mesh);
}
