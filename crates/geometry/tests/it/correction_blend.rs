//! The assisted correction blends monotonically (issue 17; `docs/geometry.md`, "The blend"): for
//! α = 0, 0.125, …, 1 the total apex change Σ_j |Δa_j| never exceeds the apex-only (α = 1) change,
//! the total plane turn (Σ over the vertices of the angle between the corrected P_{i,j} and the plane
//! its ratio gives at the same place) never exceeds the planes-only (α = 0) turn, the generatrix never
//! moves more than at α = 1, Eq. 2 holds and every quad is planar. Both totals are measured here from
//! the output geometry, independently of the kernel's own accounting.

use crate::common;

use cnets_geometry::conenet::ratios::SupportFrame;
use cnets_geometry::conenet::{ConeNet, ConstructInputs, SweptDirectrix, construct};
use cnets_geometry::curves::mapper::{Domains, GraphMapper, MapperKind};
use cnets_geometry::curves::primitives::arc;
use cnets_geometry::{DVec3, Plane, Polyline};
use common::{design, max_plane_distance};
use glam::DVec2;
use proptest::prelude::*;

/// α = 0, 0.125, …, 1.
fn alphas() -> impl Iterator<Item = f64> {
    (0..=8).map(|k| k as f64 / 8.0)
}

/// The design of `graphs/correction.ron` (its first copy: the others are translations of it): an arc
/// directrix of 17 points, an arc generatrix of 9 points, a ≡ 1, ε = 0.01 and the Gaussian ratio
/// profile from ½ up to `lean` = 0.93 at the middle column.
fn correction_graph() -> (ConstructInputs, Vec<Vec<f64>>) {
    let directrix = arc(
        DVec3::new(0.0, -20.0, 0.0),
        20.0,
        70.0,
        110.0,
        &Plane::XY,
        17,
    )
    .unwrap();
    let generatrix = arc(DVec3::new(13.68, 0.0, 0.0), 3.0, 20.0, 160.0, &Plane::YZ, 9).unwrap();
    let kind = MapperKind::parse("gaussian").unwrap();
    let mapper = GraphMapper::new(kind, &[DVec2::new(0.5, 1.0), DVec2::new(0.45, 0.3)]).unwrap();
    let domains = Domains {
        y_start: 0.5,
        y_end: 0.93,
        ..Domains::default()
    };
    let (_, ratios) = mapper.sample(16, domains).unwrap();
    let table = vec![ratios; 9];
    let inputs = ConstructInputs::new(directrix, generatrix)
        .apex(1.0)
        .epsilon(0.01)
        .ratios(table.clone());
    (inputs, table)
}

/// What a correction changed, measured from the output.
#[derive(Debug, Clone, Copy)]
struct Change {
    /// Σ_j |a_j − a_j^input|.
    apex: f64,
    /// Σ_{i,j} ∠(P_{i,j}, ratio plane of r_{i,j} in the support frame of the output).
    turn: f64,
    /// The largest distance a generatrix point moved, over the input design's size.
    generatrix: f64,
}

fn change(
    inputs: &ConstructInputs,
    ratios: &[Vec<f64>],
    input_apex: &[f64],
    net: &ConeNet,
) -> Change {
    let dx = SweptDirectrix::with_end_planes(&inputs.directrix, inputs.end_planes).unwrap();
    let apex = net
        .apex
        .iter()
        .zip(input_apex)
        .map(|(a, b)| (a - b).abs())
        .sum();
    let mut turn = 0.0;
    for (i, row) in ratios.iter().enumerate() {
        for j in 1..net.mesh.cols {
            let frame =
                SupportFrame::new(dx.points[j - 1], dx.edges[j], net.mesh.at(i, j - 1), i, j)
                    .unwrap();
            let p = frame.ratio_normal(dx.bisectors[j], row[j - 1]);
            let q = net.normals.get(i, j);
            turn += p.cross(q).length().atan2(p.dot(q));
        }
    }
    let size = size(&[&inputs.directrix.points[..], &inputs.generatrix.points[..]].concat());
    let generatrix = inputs
        .generatrix
        .points
        .iter()
        .enumerate()
        .map(|(i, g)| g.distance(net.mesh.at(i, 0)) / size)
        .fold(0.0, f64::max);
    Change {
        apex,
        turn,
        generatrix,
    }
}

fn size(points: &[DVec3]) -> f64 {
    let (lo, hi) = points
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(*p), hi.max(*p))
        });
    (hi - lo).max_element()
}

/// Eq. 2 at every vertex: no (−−) and no (+−) configuration (planes only may leave (−+), which the
/// correction does not target, see `docs/geometry.md`).
fn eq2_holds(net: &ConeNet) -> bool {
    let c = net.quality.configurations;
    c.minus_minus == 0 && c.plus_minus == 0
}

/// Checks the blend over α = 0 … 1; returns the changes per α.
fn check_blend(
    inputs: &ConstructInputs,
    ratios: &[Vec<f64>],
) -> Result<Vec<Change>, TestCaseError> {
    let raw = construct(inputs).unwrap();
    let mut out = Vec::new();
    for alpha in alphas() {
        let net = construct(&inputs.clone().assistance(alpha)).unwrap();
        out.push(change(inputs, ratios, &raw.apex, &net));
        prop_assert!(
            eq2_holds(&net),
            "α = {}: {:?}",
            alpha,
            net.configurations.to_strings()
        );
        let size = size(&net.mesh.vertices);
        prop_assert!(
            max_plane_distance(&net.mesh) <= 1e-11 * size,
            "α = {}: planarity {} (size {})",
            alpha,
            max_plane_distance(&net.mesh),
            size
        );
    }
    let (planes_only, apex_only) = (out[0], out[8]);
    // Apex only keeps every plane at its ratio (the ratios, not the angles, survive an apex fix
    // that moves the support frames: CI's seed 558defc… found the angles kept).
    prop_assert!(
        apex_only.turn <= 1e-9 * (1.0 + planes_only.turn),
        "apex only turned the planes by {}",
        apex_only.turn
    );
    for (k, c) in out.iter().enumerate() {
        let alpha = k as f64 / 8.0;
        prop_assert!(
            c.apex <= apex_only.apex * (1.0 + 1e-12) + 1e-13,
            "α = {}: apex change {} > apex-only {}",
            alpha,
            c.apex,
            apex_only.apex
        );
        prop_assert!(
            c.turn <= planes_only.turn * (1.0 + 1e-9) + 1e-12,
            "α = {}: plane turn {} > planes-only {}",
            alpha,
            c.turn,
            planes_only.turn
        );
        prop_assert!(
            // Rounding of coordinates far from the origin, over the design's size.
            c.generatrix <= apex_only.generatrix * (1.0 + 1e-9) + 1e-13,
            "α = {}: generatrix moved {} > apex-only {}",
            alpha,
            c.generatrix,
            apex_only.generatrix
        );
    }
    Ok(out)
}

/// graphs/correction.ron: the apex change grows and the plane turn shrinks with α, from planes only
/// (no apex change) to apex only (no plane turn).
#[test]
fn correction_graph_blends_monotonically() {
    let (inputs, ratios) = correction_graph();
    let raw = construct(&inputs).unwrap();
    assert!(
        raw.quality.configurations.minus_minus > 0,
        "the inputs fold over"
    );
    let out = check_blend(&inputs, &ratios).unwrap();
    for (k, c) in out.iter().enumerate() {
        println!(
            "α = {:.3}: Σ|Δa| = {:.4}, Σ turn = {:.4} rad",
            k as f64 / 8.0,
            c.apex,
            c.turn
        );
    }
    assert_eq!(out[0].apex, 0.0, "planes only");
    assert!(out[8].turn < 1e-12, "apex only: {}", out[8].turn);
    assert!(out[8].apex > 0.5 && out[0].turn > 1.0, "{out:?}");
    for w in out.windows(2) {
        assert!(w[1].apex >= w[0].apex, "apex change grows with α: {out:?}");
        assert!(w[1].turn <= w[0].turn, "plane turn shrinks with α: {out:?}");
    }
    // Linear apex change: λ = α on this design.
    for (k, c) in out.iter().enumerate() {
        let alpha = k as f64 / 8.0;
        assert!(
            (c.apex - alpha * out[8].apex).abs() < 1e-12,
            "α = {alpha}: {out:?}"
        );
    }
}

/// A random design made to fold: ratios spread over 0.06 … 0.94, apex values over 0.25 … 1.9, and
/// the first generatrix point pushed along the first edge by `push` (first-column fold-overs).
fn folding(d: &common::Design, push: f64) -> (ConstructInputs, Vec<Vec<f64>>) {
    let ratios: Vec<Vec<f64>> = d
        .ratios
        .iter()
        .map(|r| r.iter().map(|v| (v - 0.5) * 2.2 + 0.5).collect())
        .collect();
    let apex: Vec<f64> = d.apex.iter().map(|a| (a - 1.0) * 3.0 + 1.0).collect();
    let mut g = d.generatrix.clone();
    let e = (d.directrix.points[1] - d.directrix.points[0]).normalize();
    g.points[0] += e * push;
    let inputs = ConstructInputs::new(d.directrix.clone(), g)
        .apex(apex)
        .ratios(ratios.clone());
    (inputs, ratios)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn random_folding_designs_blend_within_the_pure_bounds(
        d in design(6, 12),
        push in prop_oneof![Just(0.0), 0.0..1.6f64],
    ) {
        let (inputs, ratios) = folding(&d, push);
        let Ok(raw) = construct(&inputs) else { return Ok(()) };
        prop_assume!(raw.quality.configurations.bad() > 0);
        // Designs whose apex-only fix is impossible (a' ≤ 0) or whose frames degenerate are errors for
        // every α > 0; they are not blends.
        if construct(&inputs.clone().assistance(1.0)).is_err()
            || construct(&inputs.clone().assistance(0.0)).is_err()
        {
            return Ok(());
        }
        check_blend(&inputs, &ratios)?;
    }
}

/// The blend does not depend on how the rows are split over threads, and an unassisted fold is the
/// same for every α when nothing needs fixing.
#[test]
fn blend_without_folds_is_the_plain_construction() {
    let d = Polyline::open(
        (0..6)
            .map(|j| DVec3::new(j as f64, 0.1 * (j * j) as f64, 0.0))
            .collect(),
    );
    let g = Polyline::open(vec![DVec3::new(0.0, 1.0, 0.0), DVec3::new(0.0, 1.5, 0.5)]);
    let inputs = ConstructInputs::new(d, g).ratios(0.5);
    let plain = construct(&inputs).unwrap();
    for alpha in alphas() {
        let net = construct(&inputs.clone().assistance(alpha)).unwrap();
        assert!(net.corrections.is_empty());
        assert_eq!(net.mesh, plain.mesh, "α = {alpha}");
    }
}
