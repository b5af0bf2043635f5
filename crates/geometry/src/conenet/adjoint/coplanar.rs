//! The adjoint of CNets Construct Coplanar ([`super::super::construct_coplanar`]): the backward
//! sweep of [`super`] with the shared planes given ([`super::PlaneRule::Given`]), each pulled back
//! through the pencil that made it once every row has passed its column.
//!
//! The plane of column j is `P_j = cos ψ n_in + sin ψ u` with `ψ = τ_j ψ_out` (`coplanar`,
//! `sweep::sources::CoplanarRow0`): it reads row 0's vertex G_{0,j−1} (through the frame of
//! support strip 0), ρ_j, τ_j, X_{j−1}, ê_j, the Monge normal b_j and the outgoing edge at X_j
//! (ê_{j+1}; at an open directrix's last vertex ê_{M−1}, or for mirrored end planes
//! `unit(2 (ê·b) b − ê)`; at a closed one's, ê_1). The rows are coupled at every column: the
//! sweep goes one column at a time, and the plane's cotangent (summed over the rows) reaches row
//! 0's vertex before that row's next step. A run the assisted correction changed is declined (an
//! error: the caller differentiates by finite differences).

use glam::DVec3;

use super::super::correction_adjoint::Piece;
use super::super::dual::{D3, Dual};
use super::super::inputs::{ColumnValues, CoplanarInputs, EndPlanes, GridValues};
use super::super::prepare::{Prepared, prepare};
use super::super::result::Reports;
use super::super::tolerance;
use super::super::{construct_coplanar_with, directrix_adjoint::ColumnBars};
use super::{
    Backward, ConstructAdjoint, GivenPlanes, OutputBars, Wrt, check_sizes, finite, ratio_angle,
    sweep_and_pull,
};
use crate::{GeometryError, QuadGrid};

/// The coplanar construction's ratios: ρ_j and τ_j at index j − 1.
#[derive(Clone, Copy)]
pub(in crate::conenet) struct PencilRatios<'a> {
    /// The ruling ratios ρ.
    pub rho: &'a [f64],
    /// The plane-rotation ratios τ.
    pub tau: &'a [f64],
    /// The plane at an open directrix's last vertex (its outgoing edge).
    pub end: EndPlanes,
}

// The directions of the plane of a column: G_{0,j−1} (3), ρ_j, τ_j, X_{j−1} (3), ê_j (3), b_j
// (3), the outgoing edge at X_j (3).
const G: usize = 0;
const RHO: usize = 3;
const TAU: usize = 4;
const X0: usize = 5;
const E: usize = 8;
const B: usize = 11;
const OUT: usize = 14;
const N_PLANE: usize = 17;

/// `a × b` on dual numbers.
fn cross<const N: usize>(a: D3<N>, b: D3<N>) -> D3<N> {
    let ([ax, ay, az], [bx, by, bz]) = (a.0, b.0);
    D3([ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx])
}

/// `v / |v|` on dual numbers.
fn unit<const N: usize>(v: D3<N>) -> D3<N> {
    v.scale(Dual::constant(1.0) / v.dot(v).sqrt())
}

/// The shared plane of a column on dual numbers (`coplanar::PlanePencil::new` and `normal`, the
/// frame of `ratios::SupportFrame::new`), from `g` = G_{0,j−1}, ρ, τ, `x0` = X_{j−1}, ê_j, b_j and
/// the outgoing edge.
#[allow(clippy::too_many_arguments)]
fn pencil_plane<const N: usize>(
    g: D3<N>,
    rho: Dual<N>,
    tau: Dual<N>,
    x0: D3<N>,
    e: D3<N>,
    b: D3<N>,
    out: D3<N>,
) -> D3<N> {
    let d = g.sub(x0);
    let w = unit(d.sub(e.scale(d.dot(e))));
    let theta = ratio_angle(rho, Dual::atan2(e.dot(b), -w.dot(b)));
    let ruling = e.scale(theta.cos()).add(w.scale(theta.sin()));
    let mut n_in = cross(w, e);
    let along = n_in.dot(out);
    let in_plane = along.v.abs() <= tolerance::COPLANAR_TIE;
    if !in_plane && along.v < 0.0 {
        n_in = n_in.scale(Dual::constant(-1.0));
    }
    let u = unit(e.sub(ruling.scale(e.dot(ruling))));
    let pi = Dual::constant(std::f64::consts::PI);
    let psi_out = if in_plane {
        pi
    } else {
        let psi = Dual::atan2(n_in.dot(out), -u.dot(out));
        if psi.v <= 0.0 { pi } else { psi }
    };
    let psi = tau * psi_out;
    n_in.scale(psi.cos()).add(u.scale(psi.sin()))
}

/// The plane of column `jn` on dual numbers following the first `N` directions (the layout
/// above), at the vertices of `mesh`.
fn column_plane<const N: usize>(
    prep: &Prepared,
    ratios: PencilRatios<'_>,
    mesh: &QuadGrid,
    jn: usize,
) -> D3<N> {
    let dx = &prep.dx;
    pencil_plane(
        D3::seed(mesh.vertices[jn - 1], G),
        Dual::seed(ratios.rho[jn - 1], RHO),
        Dual::seed(ratios.tau[jn - 1], TAU),
        D3::seed(dx.points[jn - 1], X0),
        D3::seed(dx.edges[jn], E),
        D3::seed(dx.bisectors[jn], B),
        D3::seed(dx.outgoing[jn], OUT),
    )
}

/// Pulls the cotangent `bar` of the shared plane P_jn back: adds the directrix quantities' to
/// `columns` (the outgoing edge's onto the edge and Monge normal it is made of) and returns the
/// cotangents of G_{0,jn−1}, ρ_jn and τ_jn.
pub(super) fn pull_plane(
    prep: &Prepared,
    ratios: PencilRatios<'_>,
    mesh: &QuadGrid,
    jn: usize,
    bar: DVec3,
    columns: &mut ColumnBars,
) -> (DVec3, f64, f64) {
    let dx = &prep.dx;
    let m = dx.columns();
    let p = column_plane::<N_PLANE>(prep, ratios, mesh, jn);
    columns.x[jn - 1] += p.pull3(bar, X0);
    columns.e[jn] += p.pull3(bar, E);
    columns.b[jn] += p.pull3(bar, B);
    let out_bar = p.pull3(bar, OUT);
    if jn + 1 < m {
        columns.e[jn + 1] += out_bar;
    } else if dx.closed {
        columns.e[1] += out_bar;
    } else if ratios.end == EndPlanes::Mirror && m >= 3 && dx.bisectors[m - 2] != DVec3::ZERO {
        // outgoing = unit(2 (ê·b) b − ê) with the mirrored b = b_{M−1}.
        let (e, b) = (
            D3::<6>::seed(dx.edges[jn], 0),
            D3::<6>::seed(dx.bisectors[jn], 3),
        );
        let out = unit(b.scale(e.dot(b) * 2.0).sub(e));
        columns.e[jn] += out.pull3(out_bar, 0);
        columns.b[jn] += out.pull3(out_bar, 3);
    } else {
        columns.e[jn] += out_bar;
    }
    (p.pull3(bar, G), p.pull(bar, RHO), p.pull(bar, TAU))
}

/// The backward sweep of CNets Construct Coplanar for the mesh it built (`mesh`) and the
/// cotangents of its outputs (`bars`: mesh, apex values, apices, plane normals, margins): the
/// generatrix's, the ruling ratios' and the plane ratios' cotangents (`ruling_ratios`,
/// `plane_ratios`, in the shape of the inputs), and those `wrt` asks for among the apex input's
/// and the scale's and the directrix's. The ratios', ε's and normals' are empty and `None`.
/// A run the assisted correction changed is declined (an error).
pub fn coplanar_adjoint_for(
    inputs: &CoplanarInputs,
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
    if inputs.assistance.enabled() {
        let reports = Reports {
            apices: false,
            quality: false,
        };
        let net = construct_coplanar_with(inputs, reports)?;
        if let Some(c) = net.corrections.first() {
            return Err(GeometryError::Degenerate(format!(
                "the assisted correction changed the coplanar construction ({c}): its \
                 derivative is not implemented"
            )));
        }
    }
    let rho = inputs.ruling_ratios.resolve("ruling_ratios", m - 1)?;
    let tau = inputs.plane_ratios.resolve("plane_ratios", m - 1)?;
    let ratios = PencilRatios {
        rho: &rho,
        tau: &tau,
        end: inputs.end_planes,
    };
    let planes: Vec<DVec3> = (1..m)
        .map(|jn| column_plane::<0>(&prep, ratios, mesh, jn).value())
        .collect();
    // No per-vertex ratios: the step reads none (a placeholder grid).
    let placeholder = GridValues::Uniform(0.5);
    let grid = placeholder.resolve("ratios", n, m - 1, (0.0, 1.0, "a value in [0, 1]"))?;
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
        epsilon: inputs.assistance.epsilon,
        given: Some(GivenPlanes {
            planes: &planes,
            per_vertex: false,
            monge: false,
            pencil: Some(ratios),
        }),
    };
    let wrt = Wrt {
        epsilon: false,
        normals: false,
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
    let shape = |values: &ColumnValues, bars: Vec<f64>| match values {
        ColumnValues::Uniform(_) => vec![bars.iter().sum()],
        ColumnValues::List(_) => bars,
    };
    result.ratios = Vec::new();
    result.epsilon = None;
    result.ruling_ratios = shape(
        &inputs.ruling_ratios,
        std::mem::take(&mut result.ruling_ratios),
    );
    result.plane_ratios = shape(
        &inputs.plane_ratios,
        std::mem::take(&mut result.plane_ratios),
    );
    finite(result)
}
