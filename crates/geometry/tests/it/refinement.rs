//! Refinement stability (paper Fig. 6, notes §5): the same normalized apex profile ā(t) and ratio
//! profile r(t) on a directrix sampled with 10, 20 and 40 edges give surfaces whose differences
//! shrink with refinement; the same values used without normalization do not.

use cnets_geometry::conenet::{ConeNet, ConstructInputs, construct};
use cnets_geometry::{DVec3, Polyline};

fn curve(t: f64) -> DVec3 {
    DVec3::new(
        4.0 * (1.5 * t).sin(),
        4.0 * (1.0 - (1.5 * t).cos()),
        1.5 * t,
    )
}

fn apex_profile(t: f64) -> f64 {
    1.0 + 0.3 * (std::f64::consts::PI * t).sin()
}

fn ratio_profile(t: f64) -> f64 {
    0.5 + 0.12 * (std::f64::consts::TAU * t).cos()
}

fn build(edges: usize, normalized: bool) -> ConeNet {
    let directrix = Polyline::open(
        (0..=edges)
            .map(|j| curve(j as f64 / edges as f64))
            .collect(),
    );
    // A generatrix in the plane through X_0 perpendicular to the start tangent, on the inner side.
    let generatrix = Polyline::open(
        (0..6)
            .map(|i| DVec3::new(0.0, 0.4 + 0.25 * i as f64, -0.6 + 0.3 * i as f64))
            .collect(),
    );
    let apex: Vec<f64> = (1..=edges)
        .map(|j| apex_profile((j as f64 - 0.5) / edges as f64))
        .collect();
    let ratios: Vec<f64> = (1..=edges)
        .map(|j| ratio_profile(j as f64 / edges as f64))
        .collect();
    construct(
        &ConstructInputs::new(directrix, generatrix)
            .apex(apex)
            .ratios(ratios)
            .normalized(normalized, None),
    )
    .unwrap()
}

/// Largest distance between the two surfaces over the directrix parameters t = k / 10 (columns both
/// resolutions share), all rows.
fn difference(coarse: &ConeNet, fine: &ConeNet) -> f64 {
    let column = |net: &ConeNet, k: usize| k * (net.mesh.cols - 1) / 10;
    (1..=10)
        .flat_map(|k| {
            (0..coarse.mesh.rows).map(move |i| {
                coarse
                    .mesh
                    .at(i, column(coarse, k))
                    .distance(fine.mesh.at(i, column(fine, k)))
            })
        })
        .fold(0.0, f64::max)
}

#[test]
fn normalized_apex_converges_under_refinement() {
    let nets: Vec<ConeNet> = [10, 20, 40].iter().map(|&k| build(k, true)).collect();
    let d1 = difference(&nets[0], &nets[1]);
    let d2 = difference(&nets[1], &nets[2]);
    assert!(
        d2 < 0.75 * d1,
        "differences {d1:.4} then {d2:.4} do not shrink"
    );
    // The surface stays comparable in size across refinements.
    let sizes: Vec<f64> = nets.iter().map(|n| n.mesh.size()).collect();
    assert!(
        sizes[2] / sizes[0] < 1.2 && sizes[0] / sizes[2] < 1.2,
        "{sizes:?}"
    );
}

#[test]
fn unnormalized_apex_does_not_converge() {
    let nets: Vec<ConeNet> = [10, 20, 40].iter().map(|&k| build(k, false)).collect();
    let d1 = difference(&nets[0], &nets[1]);
    let d2 = difference(&nets[1], &nets[2]);
    assert!(
        d2 >= d1,
        "unnormalized differences {d1:.4} then {d2:.4} shrink"
    );
    // The apex values compound: the mesh blows up with the number of edges.
    assert!(nets[2].mesh.size() > 3.0 * nets[0].mesh.size());
}
