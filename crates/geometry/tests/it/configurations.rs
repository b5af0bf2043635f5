//! Configuration classification (paper Sec. 4.2.1): the four sign cases from
//! `s1 = (G_{i,j+1} − X_j)·P_{i,j}` and `s2 = (X_{j+1} − G_{i,j})·P_{i,j+1}`, recomputed here
//! independently from the mesh and planes the construction reports, for every support-strip quad
//! j = 0 … M−2 (at j = 0 the plane through X_0 and G_{i,0} perpendicular to the support plane stands in
//! for the missing Π_{i,0}: the test against the generatrix).

use crate::common;

use cnets_geometry::conenet::{
    ConeNet, Configuration, ConstructInputs, CtubeInputs, construct, construct_ctube,
};
use cnets_geometry::{DVec3, Polyline};
use common::design;
use proptest::prelude::*;

fn recompute(net: &ConeNet) -> Vec<Vec<Configuration>> {
    let (m, x) = (&net.mesh, &net.directrix);
    (0..m.rows)
        .map(|i| {
            (0..m.cols - 1)
                .map(|j| {
                    let p_prev = if j == 0 {
                        let e = (x[1] - x[0]).normalize();
                        let w = (m.at(i, 0) - x[0]).normalize();
                        e - w * e.dot(w)
                    } else {
                        net.normals.get(i, j)
                    };
                    let s1 = (m.at(i, j + 1) - x[j]).dot(p_prev);
                    let s2 = (x[j + 1] - m.at(i, j)).dot(net.normals.get(i, j + 1));
                    Configuration::from_signs(s1, s2)
                })
                .collect()
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn reported_configurations_match_the_definition(d in design(6, 10), alpha in prop::sample::select(vec![-1.0, 0.0, 0.5, 1.0])) {
        // Wide ratios so that every sign case occurs across the cases.
        let ratios: Vec<Vec<f64>> = d.ratios.iter().map(|r| r.iter().map(|v| (v - 0.5) * 2.2 + 0.5).collect()).collect();
        let apex: Vec<f64> = d.apex.iter().map(|a| (a - 1.0) * 3.0 + 1.0).collect();
        let Ok(net) = construct(&ConstructInputs::new(d.directrix.clone(), d.generatrix.clone()).apex(apex).ratios(ratios).assistance(alpha)) else {
            return Ok(());
        };
        let expected = recompute(&net);
        for (i, row) in expected.iter().enumerate() {
            prop_assert_eq!(net.configurations.row(i), &row[..]);
        }
        let counts = net.configurations.counts();
        prop_assert_eq!(counts.total(), net.mesh.rows * (net.mesh.cols - 1));
        prop_assert_eq!(net.quality.configurations, counts);
        let first = (0..net.mesh.cols - 1).find_map(|j| (0..net.mesh.rows).find(|&i| expected[i][j] != Configuration::PlusPlus).map(|i| (i, j)));
        prop_assert_eq!(net.quality.first_bad, first);
    }
}

/// Hand-made cases with a negative apex value (the apex between X_1 and X_2).
#[test]
fn negative_apex_gives_mixed_signs() {
    let directrix = Polyline::open((0..4).map(|j| DVec3::new(j as f64, 0.0, 0.0)).collect());
    let generatrix = Polyline::open(vec![DVec3::new(0.0, 1.0, 0.0), DVec3::new(0.0, 2.0, 0.0)]);
    // a_2 = −1: the strip between columns 1 and 2 flips through its apex at x = 1.5.
    let net = construct_ctube(&CtubeInputs::new(directrix, generatrix).apex(vec![1.0, -1.0, 1.0]))
        .unwrap();
    let labels = net.configurations.to_strings();
    // Column 0: s1 = (G_{i,1} − X_0)·x̂ = 1 > 0 (the plane of the generatrix, x = 0); s2 = 1 > 0.
    // Column 1: s1 = (G_{i,2} − X_1)·x̂ = 1 > 0 (Monge planes x = j); s2 = (X_2 − G_{i,1})·x̂ = 1 > 0.
    assert_eq!(labels, vec![vec!["++", "++", "++"], vec!["++", "++", "++"]]);
    // G_{i,2} is G_{i,1} reflected through the apex: y changes sign.
    assert!(net.mesh.at(0, 2).y < 0.0 && net.mesh.at(0, 1).y > 0.0);
    // Tilting Π_1 to the normal (1, −2, 0): with a_1 = 1, G_{0,1} = (3, 1, 0) lies beyond Π_2 (x = 2),
    // s2 = −1; the line from C_1 = (1.5, 0, 0) through it meets x = 2 at G_{0,2} = (2, ⅓, 0), ahead of
    // Π_1: s1 = (1 − ⅔)/√5 > 0. Hence (+−).
    let tilted = construct_ctube(
        &CtubeInputs::new(
            Polyline::open((0..4).map(|j| DVec3::new(j as f64, 0.0, 0.0)).collect()),
            Polyline::open(vec![DVec3::new(0.0, 1.0, 0.0), DVec3::new(0.0, 2.0, 0.0)]),
        )
        .apex(vec![1.0, -1.0, 1.0])
        .normals(vec![DVec3::new(1.0, -2.0, 0.0), DVec3::X, DVec3::X]),
    )
    .unwrap();
    assert_eq!(
        tilted.configurations.get(0, 1),
        Configuration::PlusMinus,
        "{:?}",
        tilted.configurations.to_strings()
    );
    assert!((tilted.mesh.at(0, 1) - DVec3::new(3.0, 1.0, 0.0)).length() < 1e-14);
    assert!((tilted.mesh.at(0, 2) - DVec3::new(2.0, 1.0 / 3.0, 0.0)).length() < 1e-14);
    assert_eq!(tilted.quality.first_bad, Some((0, 1)));
}
