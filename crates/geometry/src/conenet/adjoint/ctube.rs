//! The adjoint of the C-tube construction (`ctube.construct`, [`super::super::construct_ctube`]):
//! the backward sweep of [`super`] with the planes given beforehand. A step's plane is then the
//! step's `b` itself ([`super::PlaneRule::Given`]), so its cotangent is what the sweep collects
//! for `b`: on the bisectors (the directrix) for the Monge planes, else per vertex, pulled back
//! through the normalization and orientation of the user's normals (`P = ±p / |p|`, `P·ê_j > 0`)
//! and summed over the rows when the normals are shared.

use glam::DVec3;

use super::super::correction_adjoint::Piece;
use super::super::inputs::{CtubeInputs, GridValues, NormalsInput};
use super::super::prepare::prepare;
use super::{
    Backward, ConstructAdjoint, GivenPlanes, OutputBars, Wrt, check_sizes, finite, sweep_and_pull,
};
use crate::{GeometryError, QuadGrid};

/// The unit normal the construction uses for the user's normal `p` at an edge `e`
/// (`ctube::orient`): `p / |p|`, flipped so that it points along `e`; and the sign taken.
fn oriented(p: DVec3, e: DVec3) -> (DVec3, f64) {
    let sign = if p.dot(e) < 0.0 { -1.0 } else { 1.0 };
    (p.normalize() * sign, sign)
}

/// The pull-back of `P = s p / |p|` for the cotangent `bar` of P: `s (I − P Pᵀ) bar / |p|`.
fn normal_pullback(p: DVec3, e: DVec3, bar: DVec3) -> DVec3 {
    let (unit, sign) = oriented(p, e);
    (bar - unit * unit.dot(bar)) * (sign / p.length())
}

/// The backward sweep of the C-tube construction for the mesh it built (`mesh`) and the
/// cotangents of its outputs (`bars`: mesh, apex values, apices, plane normals, margins): the
/// generatrix's cotangent, and those `wrt` asks for among the apex input's and the scale's
/// (`apex`), the directrix's and the given normals' (`normals`: in the shape of the input, M−1
/// shared or N·(M−1) row-major; `None` for the Monge planes, which follow the directrix). The
/// ratios' and ε's are empty and `None` (the construction has neither).
pub fn ctube_adjoint_for(
    inputs: &CtubeInputs,
    mesh: &QuadGrid,
    bars: OutputBars<'_>,
    wrt: Wrt,
) -> Result<ConstructAdjoint, GeometryError> {
    let prep = prepare(
        &inputs.directrix,
        &inputs.generatrix,
        &inputs.apex,
        inputs.end_planes,
    )?;
    let (n, m) = (prep.generatrix.len(), prep.dx.columns());
    check_sizes(n, m, mesh, &bars)?;
    let edges = &prep.dx.edges;
    let wrong = || {
        GeometryError::Degenerate(format!(
            "the adjoint needs the normals the construction used ({} per row)",
            m - 1
        ))
    };
    let (planes, per_vertex, monge) = match &inputs.normals {
        NormalsInput::Monge => (prep.dx.bisectors[1..].to_vec(), false, true),
        NormalsInput::PerColumn(list) => {
            if list.len() != m - 1 {
                return Err(wrong());
            }
            let planes = (list.iter().enumerate())
                .map(|(k, &p)| oriented(p, edges[k + 1]).0)
                .collect();
            (planes, false, false)
        }
        NormalsInput::PerVertex(table) => {
            if table.len() != n || table.iter().any(|row| row.len() != m - 1) {
                return Err(wrong());
            }
            let planes = (table.iter())
                .flat_map(|row| (row.iter().enumerate()).map(|(k, &p)| oriented(p, edges[k + 1]).0))
                .collect();
            (planes, true, false)
        }
    };
    // No ratios: the step reads none (a placeholder grid).
    let ratios = GridValues::Uniform(0.5);
    let grid = ratios.resolve("ratios", n, m - 1, (0.0, 1.0, "a value in [0, 1]"))?;
    let piece = Piece {
        apex: prep.apex.clone(),
        ..Piece::default()
    };
    let sweep = Backward {
        prep: &prep,
        grid: &grid,
        mesh,
        mesh_bar: bars.mesh,
        plane_bar: &[],
        piece: &piece,
        epsilon: 0.0,
        given: Some(GivenPlanes {
            planes: &planes,
            per_vertex,
            monge,
            pencil: None,
        }),
    };
    let wrt = Wrt {
        epsilon: false,
        ..wrt
    };
    let mut result = sweep_and_pull(
        sweep,
        &bars,
        wrt,
        &inputs.apex,
        inputs.end_planes,
        inputs.directrix.points.len(),
    )?;
    result.ratios = Vec::new();
    result.epsilon = None;
    result.normals = match (&inputs.normals, result.normals.take()) {
        (NormalsInput::PerColumn(list), Some(per_vertex)) => Some(
            (list.iter().enumerate())
                .map(|(k, &p)| {
                    let bar = (0..n).map(|i| per_vertex[i * (m - 1) + k]).sum();
                    normal_pullback(p, edges[k + 1], bar)
                })
                .collect(),
        ),
        (NormalsInput::PerVertex(table), Some(per_vertex)) => Some(
            (table.iter().flatten().enumerate())
                .map(|(k, &p)| normal_pullback(p, edges[k % (m - 1) + 1], per_vertex[k]))
                .collect(),
        ),
        _ => None,
    };
    finite(result)
}
