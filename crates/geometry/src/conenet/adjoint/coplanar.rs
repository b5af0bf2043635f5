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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Polyline;
    use crate::conenet::construct_coplanar;
    use crate::conenet::inputs::ApexInput;
    use proptest::prelude::*;

    /// L = Σ w_k · G_k with fixed weights.
    fn loss(c: &CoplanarInputs, w: &[DVec3]) -> f64 {
        let net = construct_coplanar(c).unwrap();
        net.mesh
            .vertices
            .iter()
            .zip(w)
            .map(|(g, w)| g.dot(*w))
            .sum()
    }

    /// The largest difference between `exact` and central differences (Richardson) of `loss`
    /// over the scalars `set(c, k, ·)` moves, relative to the largest difference quotient.
    fn compare(
        c: &CoplanarInputs,
        w: &[DVec3],
        exact: &[f64],
        set: impl Fn(&mut CoplanarInputs, usize, f64),
    ) -> f64 {
        let central = |k: usize, h: f64| {
            let (mut p, mut q) = (c.clone(), c.clone());
            set(&mut p, k, h);
            set(&mut q, k, -h);
            (loss(&p, w) - loss(&q, w)) / (2.0 * h)
        };
        let (mut worst, mut size) = (0.0f64, 0.0f64);
        for (k, &x) in exact.iter().enumerate() {
            let fd = (4.0 * central(k, 5e-7) - central(k, 1e-6)) / 3.0;
            worst = worst.max((fd - x).abs());
            size = size.max(fd.abs());
        }
        assert!(size > 0.0, "the gradient is zero");
        worst / size
    }

    fn list(c: &mut ColumnValues, k: usize, h: f64) {
        match c {
            ColumnValues::Uniform(v) => *v += h,
            ColumnValues::List(v) => v[k] += h,
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]
        #[test]
        fn coplanar_gradients_match_differences(
            closed in any::<bool>(),
            mirror in any::<bool>(),
            uniform in any::<bool>(),
            jitter in proptest::collection::vec(-0.15f64..0.15, 18),
            apex in proptest::collection::vec(0.85f64..1.15, 6),
            // Ruling ratios near the kink at ½, on either side (not at it), or farther away.
            rho in proptest::collection::vec(
                prop_oneof![1e-4f64..1e-2, -1e-2f64..-1e-4, -0.15f64..0.15],
                6,
            ),
            tau in proptest::collection::vec(0.3f64..0.7, 6),
        ) {
            let step = if closed { std::f64::consts::PI / 3.0 } else { 0.4 };
            let points: Vec<DVec3> = (0..6)
                .map(|k| {
                    let t = k as f64 * step;
                    let j = DVec3::new(jitter[3 * k], jitter[3 * k + 1], jitter[3 * k + 2]);
                    DVec3::new(3.0 * t.cos(), 3.0 * t.sin(), 0.4 * (2.0 * t).sin()) + j
                })
                .collect();
            let directrix = if closed { Polyline::closed(points) } else { Polyline::open(points) };
            let generatrix = Polyline::open(
                (0..4)
                    .map(|k| DVec3::new(3.4 + 0.4 * k as f64, 0.1, 0.3 * k as f64 - 0.4))
                    .collect(),
            );
            let cols = if closed { 6 } else { 5 };
            let values = |v: Vec<f64>| {
                if uniform { ColumnValues::Uniform(v[0]) } else { ColumnValues::List(v) }
            };
            let mut c = CoplanarInputs::new(directrix, generatrix);
            c.apex = ApexInput {
                values: ColumnValues::List(apex[..cols].to_vec()),
                ..ApexInput::default()
            };
            c.ruling_ratios = values(
                rho[..cols].iter().map(|d| if *d == 0.0 { 0.51 } else { 0.5 + d }).collect(),
            );
            c.plane_ratios = values(tau[..cols].to_vec());
            c.end_planes = if mirror { EndPlanes::Mirror } else { EndPlanes::Perpendicular };
            prop_assume!(construct_coplanar(&c).is_ok());
            let net = construct_coplanar(&c).unwrap();
            let w: Vec<DVec3> = (0..net.mesh.vertices.len())
                .map(|k| DVec3::new((k as f64 * 0.7).sin(), (k as f64 * 1.3).cos(), 0.5))
                .collect();
            let bars = OutputBars { mesh: &w, apex: &[], apices: &[], planes: &[], margins: &[] };
            let adj = coplanar_adjoint_for(&c, &net.mesh, bars, Wrt::ALL).unwrap();
            let flat = |p: &[DVec3]| p.iter().flat_map(|p| p.to_array()).collect::<Vec<f64>>();
            let directrix = compare(&c, &w, &flat(&adj.directrix.unwrap()), |c, k, h| {
                c.directrix.points[k / 3][k % 3] += h;
            });
            let generatrix = compare(&c, &w, &flat(&adj.generatrix), |c, k, h| {
                c.generatrix.points[k / 3][k % 3] += h;
            });
            let apex = compare(&c, &w, &adj.apex.unwrap(), |c, k, h| list(&mut c.apex.values, k, h));
            let ruling = compare(&c, &w, &adj.ruling_ratios, |c, k, h| {
                list(&mut c.ruling_ratios, k, h)
            });
            let plane = compare(&c, &w, &adj.plane_ratios, |c, k, h| {
                list(&mut c.plane_ratios, k, h)
            });
            let rel = [directrix, generatrix, apex, ruling, plane];
            prop_assert!(
                rel.iter().all(|r| *r < 1e-6),
                "directrix, generatrix, apex, ruling ratios, plane ratios: {:?}", rel
            );
        }
    }

    #[test]
    fn a_corrected_run_is_declined() {
        // A straight directrix (slightly bent) with a ruling leaning back at column 2
        // (`adjoint::tests::tilted`): planes only turns a plane.
        let directrix = Polyline::open(
            (0..6)
                .map(|j| DVec3::new(j as f64, 0.05 * (j as f64).sin(), 0.03 * (j * j) as f64))
                .collect(),
        );
        let generatrix = Polyline::open(vec![
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(0.0, 1.5, 0.5),
            DVec3::new(0.0, 2.0, 0.2),
        ]);
        let c = CoplanarInputs::new(directrix, generatrix)
            .ruling_ratios(vec![0.5, 0.95, 0.45, 0.55, 0.5])
            .plane_ratios(vec![0.5, 0.9, 0.5, 0.5, 0.5])
            .assistance(0.0);
        let net = construct_coplanar(&c).unwrap();
        assert!(
            !net.corrections.is_empty(),
            "the correction changed the run"
        );
        let w = vec![DVec3::X; net.mesh.vertices.len()];
        let bars = OutputBars {
            mesh: &w,
            apex: &[],
            apices: &[],
            planes: &[],
            margins: &[],
        };
        let err = coplanar_adjoint_for(&c, &net.mesh, bars, Wrt::ALL).unwrap_err();
        assert!(err.to_string().contains("assisted correction"), "{err}");
    }
}
