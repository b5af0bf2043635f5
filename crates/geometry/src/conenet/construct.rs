//! CNets Construct (ratios, notes §3) and CNets Construct Coplanar (notes §4), with the assisted
//! correction (notes §6).

use glam::DVec3;

use super::blend::{Taken, assisted, assisted_traced};
use super::ctube::Raw;
use super::inputs::{ConstructInputs, CoplanarInputs, check_unit_interval};
use super::prepare::prepare;
use super::result::{ConeNet, Reports};
use super::sweep::{Rule, Sweep, zeroed_points};
use crate::GeometryError;

/// CNets Construct (`cnets.construct`): ratios r_{i,j} pick the rulings of the support strips, the
/// planes follow (notes §3); the assisted correction runs when `assistance.alpha ≥ 0`.
pub fn construct(inputs: &ConstructInputs) -> Result<ConeNet, GeometryError> {
    construct_with(inputs, Reports::ALL)
}

/// [`construct`] computing only the chosen reports (the others are left empty).
pub fn construct_with(
    inputs: &ConstructInputs,
    reports: Reports,
) -> Result<ConeNet, GeometryError> {
    construct_traced(inputs, reports).map(|(net, _)| net)
}

/// [`construct_with`], also saying which form of the assisted correction the run took.
pub(super) fn construct_traced(
    inputs: &ConstructInputs,
    reports: Reports,
) -> Result<(ConeNet, Taken), GeometryError> {
    let prep = prepare(
        &inputs.directrix,
        &inputs.generatrix,
        &inputs.apex,
        inputs.end_planes,
    )?;
    let (n, m) = (prep.generatrix.len(), prep.dx.columns());
    let grid = inputs
        .ratios
        .resolve("ratios", n, m - 1, (0.0, 1.0, "a value in [0, 1]"))?;
    inputs.assistance.validate()?;
    prep.dx.check_bisectors()?;
    let (raw, taken) =
        assisted_traced(&prep, inputs.assistance, |prep, assistance, turn_limit| {
            let mut sweep = Sweep::new(
                prep,
                zeroed_points(n * (m - 1)),
                true,
                Rule::Ratios(&grid),
                assistance,
            );
            sweep.turn_limit = turn_limit;
            sweep.run()?;
            Ok(Raw::from_sweep(sweep, prep.wrap_rows))
        })?;
    Ok((raw.finish_with(reports)?, taken))
}

/// CNets Construct Coplanar (`cnets.construct_coplanar`): one plane per column through the ruling
/// R_{0,j} of support strip 0 (ratio ρ_j), turned by the rotation ratio τ_j (notes §4). Every
/// generatrix-aligned polyline G_{:,j} (j ≥ 1) lies in the plane Π_j.
pub fn construct_coplanar(inputs: &CoplanarInputs) -> Result<ConeNet, GeometryError> {
    construct_coplanar_with(inputs, Reports::ALL)
}

/// [`construct_coplanar`] computing only the chosen reports (the others are left empty).
pub fn construct_coplanar_with(
    inputs: &CoplanarInputs,
    reports: Reports,
) -> Result<ConeNet, GeometryError> {
    let prep = prepare(
        &inputs.directrix,
        &inputs.generatrix,
        &inputs.apex,
        inputs.end_planes,
    )?;
    let m = prep.dx.columns();
    let rho = inputs.ruling_ratios.resolve("ruling_ratios", m - 1)?;
    check_unit_interval("ruling_ratios", &rho)?;
    let tau = inputs.plane_ratios.resolve("plane_ratios", m - 1)?;
    check_unit_interval("plane_ratios", &tau)?;
    inputs.assistance.validate()?;
    prep.dx.check_bisectors()?;
    assisted(&prep, inputs.assistance, |prep, assistance, turn_limit| {
        let mut sweep = Sweep::new(
            prep,
            vec![DVec3::ZERO; m - 1],
            false,
            Rule::Coplanar {
                rho: &rho,
                tau: &tau,
            },
            assistance,
        );
        sweep.turn_limit = turn_limit;
        sweep.run()?;
        Ok(Raw::from_sweep(sweep, prep.wrap_rows))
    })?
    .finish_with(reports)
}
