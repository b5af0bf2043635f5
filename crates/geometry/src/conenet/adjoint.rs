//! The adjoint (reverse-mode derivative) of CNets Construct (ratios): a backward sweep.
//!
//! The forward sweep is a recurrence along each row: `G_{i,j} = F(G_{i,j−1}, r_{i,j}, a_j, X_{j−1},
//! X_j, ê_j, b_j)` with the plane Π_{i,j} from the ratio (its support frame depends on G_{i,j−1}) and
//! the step of Eq. 1. For cotangents `λ_{i,j} = ∂L/∂G_{i,j}` of an objective L, the backward sweep
//! runs j = M−1 … 1: `∂L/∂r_{i,j} = J_r(i,j)ᵀ λ_{i,j}`, `λ_{i,j−1} += J_g(i,j)ᵀ λ_{i,j}`, and the
//! column quantities collect `J_a ᵀ λ`, `J_X ᵀ λ`, `J_ê ᵀ λ`, `J_b ᵀ λ` summed over the rows; what
//! reaches column 0 is the generatrix's cotangent. The local Jacobians come from one forward-mode
//! evaluation of the step on dual numbers (`dual`) at the stored vertices, with as many
//! directions as the wanted inputs need ([`Wrt`]: 4, 6 or 18), so the backward sweep costs a small
//! constant times the forward one, rows in parallel. The column cotangents are then pulled back
//! through the directrix's edges and bisectors and the apex normalization to the user's inputs
//! (`directrix_adjoint`).
//!
//! The ratio → angle map has a kink at r = ½; exactly there the mean of its two slopes is used.
//! Besides the mesh, the apex values used, the apices, the plane normals and the convexity margins
//! may carry cotangents ([`OutputBars`], `output_adjoint`): they seed the sweep (the
//! planes' through the step that made them).
//!
//! A run of the assisted correction is differentiated on the piece it took
//! (`correction_adjoint`): planes only (per-row plane fixes, `θ = (1 − ε) φ`: the plane
//! then reads ε instead of the ratio and the bisector), apex only (the fixed a_{j0} and the
//! generatrix scale are smooth functions of one row's values; the rows are coupled only at those
//! columns) or a blend (0 < α < 1: planes only on apex values and a generatrix moved the fraction
//! λ towards apex only's; the cotangents of a_j^Q and t_Q go through apex only's own backward
//! sweep). A run where a plane fix was numerically insufficient and fell back to an apex or
//! generatrix fix (mixed) is declined (an error: the caller differentiates by finite differences
//! and says so).

use std::f64::consts::PI;

use glam::DVec3;
use rayon::prelude::*;

use super::construct::construct_with;
use super::correction_adjoint::{
    ApexFix, Blend, FIX_B0, FIX_B1, FIX_E0, FIX_E1, FIX_EPS, FIX_G, FIX_R0, FIX_R1, FIX_X, FIX_XM,
    FIX_XP, GeneratrixFix, N_FIX, Piece, apex_fix, generatrix_scale, piece,
};
use super::directrix_adjoint::{ColumnBars, pull_back};
use super::dual::{D3, Dual};
use super::inputs::{ConstructInputs, GridValues};
use super::output_adjoint::seed;
use super::prepare::prepare;
use super::result::Reports;
use super::tolerance;
use crate::{GeometryError, QuadGrid};

mod coplanar;
mod ctube;
pub use coplanar::coplanar_adjoint_for;
pub use ctube::ctube_adjoint_for;

/// The directions of a step's local Jacobian: G_{i,j−1} (3), r, a_j, ε, X_{j−1} (3), X_j (3), ê_j
/// (3), b_j (3). A sweep follows the first N of them.
pub(super) mod layout {
    pub const G: usize = 0;
    pub const R: usize = 3;
    pub const A: usize = 4;
    pub const EPS: usize = 5;
    pub const X0: usize = 6;
    pub const X1: usize = 9;
    pub const E: usize = 12;
    pub const B: usize = 15;
}
use layout::{A, B, E, EPS, G, R, X0, X1};
/// Directions for the ratios and the generatrix only.
const N_RATIOS: usize = 4;
/// … and the apex values and ε.
const N_APEX: usize = 6;
/// … and the directrix.
const N_ALL: usize = 18;

/// How the plane of a step is obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum PlaneRule {
    /// From the ratio (notes §3).
    Ratio,
    /// The assisted correction's plane fix: `θ = (1 − ε) φ` (notes §6).
    Fixed,
    /// Given beforehand (the C-tube construction): the step's `b` is the plane normal itself.
    Given,
}

/// The values one step reads, on dual numbers.
pub(super) struct StepInputs<const N: usize> {
    pub g: D3<N>,
    pub r: Dual<N>,
    pub a: Dual<N>,
    pub epsilon: Dual<N>,
    pub x0: D3<N>,
    pub x1: D3<N>,
    pub e: D3<N>,
    pub b: D3<N>,
}

/// One step of the ratio construction on dual numbers: `G_{i,jn}` and the plane normal `P_{i,jn}` from `g = G_{i,jn−1}`, the ratio
/// `r` (or the plane fix's ε), `a = a_jn`, `x0 = X_{jn−1}`, `x1 = X_jn`, `e = ê_jn` and the Monge
/// normal `b = b_jn` (same formulas as the lanes kernel, `ratios::ratio_planes`, the plane fix of
/// `sweep::sources` and `prepare::step`). `e` and `b` are followed as free vectors: only their
/// derivatives along the unit sphere are used by the chain that follows.
#[inline(always)]
fn ratio_step<const N: usize>(
    s: &StepInputs<N>,
    rule: PlaneRule,
    inv_scale: f64,
) -> (D3<N>, D3<N>) {
    let p = step_plane(s, rule, inv_scale);
    (step_vertex(s.g, s.a, s.x0, s.x1, p), p)
}

/// The plane normal Π_{i,jn} of a step (see [`ratio_step`]; `s.a` is not read).
#[inline(always)]
pub(super) fn step_plane<const N: usize>(
    s: &StepInputs<N>,
    rule: PlaneRule,
    inv_scale: f64,
) -> D3<N> {
    let StepInputs {
        g,
        r,
        epsilon,
        x0,
        x1,
        e,
        b,
        ..
    } = *s;
    if rule == PlaneRule::Given {
        return b;
    }
    let d = g.sub(x0);
    let on_directrix =
        d.0.iter().fold(0.0f64, |m, x| m.max(x.v.abs())) * inv_scale <= tolerance::FRAME;
    if on_directrix {
        return b;
    }
    let perp = d.sub(e.scale(d.dot(e)));
    let inv_len = Dual::constant(1.0) / perp.dot(perp).sqrt();
    let w = perp.scale(inv_len);
    let theta = match rule {
        PlaneRule::Fixed => {
            // φ: the angle of G_{i,j−1} − X_j from ê in the support frame.
            let v = g.sub(x1);
            Dual::atan2(w.dot(v), e.dot(v)) * (Dual::constant(1.0) - epsilon)
        }
        PlaneRule::Ratio | PlaneRule::Given => ratio_angle(r, Dual::atan2(e.dot(b), -w.dot(b))),
    };
    e.scale(theta.sin()).sub(w.scale(theta.cos()))
}

/// The ratio → angle map (`ratios::ratio_to_angle`) on dual numbers. At r = ½ the map has a kink
/// (slopes 2θ_b and 2(π − θ_b)): the mean slope π is used there, the derivative central
/// differences see (an element of the subdifferential). Both pieces have slope 1 in θ_b there.
#[inline(always)]
pub(super) fn ratio_angle<const N: usize>(r: Dual<N>, theta_b: Dual<N>) -> Dual<N> {
    if r.v == 0.5 {
        theta_b + (r - Dual::constant(0.5)) * PI
    } else if r.v < 0.5 {
        r * theta_b * 2.0
    } else {
        theta_b + (r * 2.0 - Dual::constant(1.0)) * (Dual::constant(PI) - theta_b)
    }
}

/// The step of Eq. 1 on dual numbers: `G_{i,j}` from `g = G_{i,j−1}`, `a = a_j`, `x0 = X_{j−1}`,
/// `x1 = X_j` and the plane normal `p`.
#[inline(always)]
pub(super) fn step_vertex<const N: usize>(
    g: D3<N>,
    a: Dual<N>,
    x0: D3<N>,
    x1: D3<N>,
    p: D3<N>,
) -> D3<N> {
    let v = g.sub(x0).scale(a).add(x1).sub(g);
    let t = x1.sub(g).dot(p) / v.dot(p);
    g.add(v.scale(t))
}

/// Which cotangents [`construct_adjoint_for`] computes besides the ratios' and the generatrix's.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Wrt {
    /// The apex input's and the normalization scale's.
    pub apex: bool,
    /// The directrix points'.
    pub directrix: bool,
    /// The correction margin ε's.
    pub epsilon: bool,
    /// The given plane normals' (the C-tube construction, [`ctube_adjoint_for`]).
    pub normals: bool,
}

impl Wrt {
    /// Every input.
    pub const ALL: Wrt = Wrt {
        apex: true,
        directrix: true,
        epsilon: true,
        normals: true,
    };
}

/// The cotangents of the construction's outputs that the adjoint takes.
#[derive(Debug, Clone, Copy)]
pub struct OutputBars<'a> {
    /// ∂L/∂G per mesh vertex (row-major, N·M).
    pub mesh: &'a [DVec3],
    /// ∂L/∂a_j of the `apex` output (the values used, M−1), or empty.
    pub apex: &'a [f64],
    /// ∂L/∂C_{j−1} of the `apices` output (M−1; an apex at infinity has none and is ignored), or
    /// empty.
    pub apices: &'a [DVec3],
    /// ∂L/∂P_{i,j} of the plane normals used (N·(M−1), row-major), or empty.
    pub planes: &'a [DVec3],
    /// ∂L/∂ the convexity margins ([`super::margins::face_margins`]: 4 per face), or empty.
    pub margins: &'a [f64],
}

/// What the backward sweep returns.
#[derive(Debug, Clone, PartialEq)]
pub struct ConstructAdjoint {
    /// ∂L/∂ratios in the shape of the input: 1 number (uniform), M−1 (per column) or N·(M−1)
    /// (per vertex, row-major).
    pub ratios: Vec<f64>,
    /// ∂L/∂generatrix points (N).
    pub generatrix: Vec<DVec3>,
    /// ∂L/∂apex values in the shape of the input (1 or M−1; ā_j when normalized); `None` when not
    /// asked for.
    pub apex: Option<Vec<f64>>,
    /// ∂L/∂ the normalization scale L; `None` when not asked for or not given (0 when the apex
    /// function is not normalized).
    pub scale: Option<f64>,
    /// ∂L/∂directrix points (as stored: a closed directrix without its repeated first point);
    /// `None` when not asked for.
    pub directrix: Option<Vec<DVec3>>,
    /// ∂L/∂ε (nonzero only when the correction turned planes); `None` when not asked for.
    pub epsilon: Option<f64>,
    /// ∂L/∂ the shared apex ([`super::inputs::ApexInput::seam`]); `None` when not given or when
    /// neither the apex nor the directrix was asked for.
    pub seam: Option<DVec3>,
    /// ∂L/∂ the given plane normals of the C-tube construction, in the shape of the input (M−1
    /// shared, or N·(M−1) per vertex, row-major; the Monge planes have none); `None` when not
    /// asked for or not given.
    pub normals: Option<Vec<DVec3>>,
    /// ∂L/∂ρ of the coplanar construction ([`coplanar_adjoint_for`]) in the shape of the input
    /// (1 or M−1); empty for the others.
    pub ruling_ratios: Vec<f64>,
    /// ∂L/∂τ of the coplanar construction in the shape of the input (1 or M−1); empty for the
    /// others.
    pub plane_ratios: Vec<f64>,
}

/// The backward sweep of [`super::construct`] for the mesh it built (`mesh`) and the cotangents of
/// its vertices (`mesh_bar`, row-major): every input's cotangent (see [`construct_adjoint_for`]).
pub fn construct_adjoint(
    inputs: &ConstructInputs,
    mesh: &QuadGrid,
    mesh_bar: &[DVec3],
) -> Result<ConstructAdjoint, GeometryError> {
    let bars = OutputBars {
        mesh: mesh_bar,
        apex: &[],
        apices: &[],
        planes: &[],
        margins: &[],
    };
    construct_adjoint_for(inputs, mesh, bars, Wrt::ALL)
}

/// The backward sweep of [`super::construct`] for the mesh it built (`mesh`) and the cotangents of
/// its outputs (`bars`): the ratios' and the generatrix's cotangents, and those `wrt` asks for.
///
/// With the assisted correction on, the construction is run again to learn which piece it took
/// (see `correction_adjoint`; a blend also runs and differentiates its apex-only sweep); a run
/// mixing plane fixes with apex or generatrix fixes is declined (an error).
pub fn construct_adjoint_for(
    inputs: &ConstructInputs,
    mesh: &QuadGrid,
    bars: OutputBars<'_>,
    wrt: Wrt,
) -> Result<ConstructAdjoint, GeometryError> {
    adjoint_on_piece(inputs, mesh, bars, wrt, 0.0)
}

/// [`construct_adjoint_for`] with `scale_bar`, a cotangent of the generatrix fix's total scale
/// from outside (a blend's, sent to its apex-only sweep; ignored without that fix).
fn adjoint_on_piece(
    inputs: &ConstructInputs,
    mesh: &QuadGrid,
    bars: OutputBars<'_>,
    wrt: Wrt,
    scale_bar: f64,
) -> Result<ConstructAdjoint, GeometryError> {
    let prep = prepare(
        &inputs.directrix,
        &inputs.generatrix,
        &inputs.apex,
        inputs.end_planes,
    )?;
    let (n, m) = (prep.generatrix.len(), prep.dx.columns());
    check_sizes(n, m, mesh, &bars)?;
    let grid = inputs
        .ratios
        .resolve("ratios", n, m - 1, (0.0, 1.0, "a value in [0, 1]"))?;
    let mut piece = piece(inputs, &prep, &grid, mesh)?;
    if let Some(fix) = &mut piece.generatrix_fix {
        fix.bar = scale_bar;
    }
    let sweep = Backward {
        prep: &prep,
        grid: &grid,
        mesh,
        mesh_bar: bars.mesh,
        plane_bar: &[],
        piece: &piece,
        epsilon: inputs.assistance.epsilon,
        given: None,
    };
    let wrt = Wrt {
        normals: false,
        ..wrt
    };
    let (mut result, blend) = sweep_and_pull_blend(
        sweep,
        &bars,
        wrt,
        &inputs.apex,
        inputs.end_planes,
        inputs.directrix.points.len(),
    )?;
    let swept = std::mem::take(&mut result.ratios);
    result.ratios = match &inputs.ratios {
        GridValues::Uniform(_) => vec![swept.iter().sum()],
        GridValues::PerColumn(_) => (0..m - 1)
            .map(|j| swept.iter().skip(j).step_by(m - 1).sum())
            .collect(),
        GridValues::PerVertex(_) => swept,
    };
    if let Some(blend) = blend {
        // The apex-only sweep the blend took its apex values a^Q and scale t_Q from, with their
        // cotangents as outputs: a smooth function of the inputs on its own piece.
        let mut apex_only = inputs.clone();
        apex_only.assistance.alpha = 1.0;
        let q = construct_with(
            &apex_only,
            Reports {
                apices: false,
                quality: false,
            },
        )?;
        let zero = vec![DVec3::ZERO; q.mesh.vertices.len()];
        let q_bars = OutputBars {
            mesh: &zero,
            apex: &blend.apex,
            apices: &[],
            planes: &[],
            margins: &[],
        };
        let q = adjoint_on_piece(&apex_only, &q.mesh, q_bars, wrt, blend.scale)?;
        result = result.add(q);
    }
    finite(result)
}

impl ConstructAdjoint {
    /// The sum of two adjoints of the same inputs (a blend's two sweeps).
    fn add(mut self, o: ConstructAdjoint) -> ConstructAdjoint {
        fn sum<T: Copy + std::ops::AddAssign>(a: &mut [T], b: &[T]) {
            a.iter_mut().zip(b).for_each(|(x, y)| *x += *y);
        }
        sum(&mut self.ratios, &o.ratios);
        sum(&mut self.generatrix, &o.generatrix);
        if let (Some(a), Some(b)) = (&mut self.apex, &o.apex) {
            sum(a, b);
        }
        if let (Some(a), Some(b)) = (&mut self.scale, o.scale) {
            *a += b;
        }
        if let (Some(a), Some(b)) = (&mut self.directrix, &o.directrix) {
            sum(a, b);
        }
        if let (Some(a), Some(b)) = (&mut self.epsilon, o.epsilon) {
            *a += b;
        }
        if let (Some(a), Some(b)) = (&mut self.seam, o.seam) {
            *a += b;
        }
        self
    }
}

/// Checks the mesh has the construction's size and the outputs' cotangents fit it.
pub(super) fn check_sizes(
    n: usize,
    m: usize,
    mesh: &QuadGrid,
    bars: &OutputBars<'_>,
) -> Result<(), GeometryError> {
    if mesh.rows != n || mesh.cols != m || bars.mesh.len() != n * m {
        return Err(GeometryError::Degenerate(format!(
            "the adjoint needs the {n} × {m} mesh the construction built and one cotangent per vertex"
        )));
    }
    let extra = |len: usize, what: &str| {
        if len != 0 && len != m - 1 {
            Err(GeometryError::Degenerate(format!(
                "the adjoint needs one {what} cotangent per directrix edge ({}), got {len}",
                m - 1
            )))
        } else {
            Ok(())
        }
    };
    extra(bars.apex.len(), "apex")?;
    extra(bars.apices.len(), "apices")
}

/// Seeds `sweep` from the outputs' cotangents, runs it with as many directions as `wrt` needs and
/// pulls the column cotangents back to the directrix and the apex input (`stored` directrix
/// points): every cotangent, the ratios' and the given normals' per vertex (N·(M−1), row-major;
/// the normals' `None` unless asked for and given, not the Monge planes).
pub(super) fn sweep_and_pull(
    sweep: Backward<'_>,
    bars: &OutputBars<'_>,
    wrt: Wrt,
    apex: &super::inputs::ApexInput,
    end_planes: super::inputs::EndPlanes,
    stored: usize,
) -> Result<ConstructAdjoint, GeometryError> {
    sweep_and_pull_blend(sweep, bars, wrt, apex, end_planes, stored).map(|(a, _)| a)
}

/// [`sweep_and_pull`], also returning a blend's cotangents of apex only's values.
fn sweep_and_pull_blend(
    sweep: Backward<'_>,
    bars: &OutputBars<'_>,
    wrt: Wrt,
    apex: &super::inputs::ApexInput,
    end_planes: super::inputs::EndPlanes,
    stored: usize,
) -> Result<(ConstructAdjoint, Option<BlendBars>), GeometryError> {
    let seeded = seed(&sweep, bars)?;
    let sweep = Backward {
        mesh_bar: &seeded.mesh,
        plane_bar: &seeded.planes,
        ..sweep
    };
    let outputs = seeded.columns;
    let coupled = !sweep.piece.apex_fixes.is_empty()
        || sweep.piece.generatrix_fix.is_some()
        || sweep.piece.blend.is_some();
    let normals = wrt.normals && sweep.given.is_some_and(|g| !g.monge && g.pencil.is_none());
    let pencil = sweep.given.is_some_and(|g| g.pencil.is_some());
    let swept = if wrt.directrix || coupled || normals || pencil {
        sweep.run::<N_ALL>(outputs)
    } else if wrt.apex || wrt.epsilon {
        sweep.run::<N_APEX>(outputs)
    } else {
        sweep.run::<N_RATIOS>(outputs)
    };
    let dx = &sweep.prep.dx;
    let Swept {
        ratios,
        generatrix,
        columns,
        epsilon,
        normals: normals_bar,
        pencil: (rho, tau),
        blend,
    } = swept;
    let mut pulled =
        (wrt.apex || wrt.directrix).then(|| pull_back(columns, dx, end_planes, apex, stored));
    Ok((
        ConstructAdjoint {
            ratios,
            generatrix,
            apex: pulled
                .as_mut()
                .filter(|_| wrt.apex)
                .map(|p| std::mem::take(&mut p.apex)),
            scale: pulled.as_ref().filter(|_| wrt.apex).and_then(|p| p.scale),
            directrix: pulled
                .as_mut()
                .filter(|_| wrt.directrix)
                .map(|p| std::mem::take(&mut p.directrix)),
            epsilon: wrt.epsilon.then_some(epsilon),
            seam: pulled.as_ref().and_then(|p| p.seam),
            normals: normals.then_some(normals_bar),
            ruling_ratios: rho,
            plane_ratios: tau,
        },
        blend,
    ))
}

/// `result`, or an error when one of its numbers is not finite.
pub(super) fn finite(result: ConstructAdjoint) -> Result<ConstructAdjoint, GeometryError> {
    let finite = |x: &f64| x.is_finite();
    let all_finite = result.ratios.iter().all(finite)
        && result.generatrix.iter().all(|g| g.is_finite())
        && result.apex.iter().flatten().all(finite)
        && result.scale.iter().all(finite)
        && result.directrix.iter().flatten().all(|g| g.is_finite())
        && result.epsilon.iter().all(finite)
        && result.seam.iter().all(|c| c.is_finite())
        && result.normals.iter().flatten().all(|g| g.is_finite())
        && result.ruling_ratios.iter().all(finite)
        && result.plane_ratios.iter().all(finite);
    if !all_finite {
        return Err(GeometryError::Degenerate(
            "the construction's derivative is not finite (a degenerate step)".into(),
        ));
    }
    Ok(result)
}

/// Plane normals given beforehand (the C-tube construction): those the sweep used.
#[derive(Clone, Copy)]
pub(super) struct GivenPlanes<'a> {
    /// Unit normals with `P·ê_j > 0`: M−1 shared by every row, or N·(M−1) (row-major).
    pub planes: &'a [DVec3],
    /// Whether `planes` has one normal per vertex.
    pub per_vertex: bool,
    /// Whether they are the Monge planes (the bisectors: their cotangents go to the directrix).
    pub monge: bool,
    /// The coplanar construction's ratios: the shared planes are then functions of row 0's
    /// vertices (`coplanar`), pulled back column by column.
    pub pencil: Option<coplanar::PencilRatios<'a>>,
}

impl GivenPlanes<'_> {
    /// The plane of row i at column jn.
    #[inline(always)]
    fn plane(&self, i: usize, jn: usize, m: usize) -> DVec3 {
        if self.per_vertex {
            self.planes[i * (m - 1) + jn - 1]
        } else {
            self.planes[jn - 1]
        }
    }
}

/// The backward sweep's data.
#[derive(Clone, Copy)]
pub(super) struct Backward<'a> {
    pub prep: &'a super::prepare::Prepared,
    pub grid: &'a super::inputs::Grid<'a>,
    pub mesh: &'a QuadGrid,
    /// ∂L/∂G (N·M, row-major).
    pub mesh_bar: &'a [DVec3],
    /// ∂L/∂P_{i,j} (N·(M−1), row-major), or empty.
    pub plane_bar: &'a [DVec3],
    /// The piece the run took (plane fixes, the apex values used, coupled fixes).
    pub piece: &'a Piece,
    pub epsilon: f64,
    /// The planes given beforehand (the C-tube construction), or `None`: planes from ratios.
    pub given: Option<GivenPlanes<'a>>,
}

/// What a backward sweep returns: the cotangents of the ratios (N·(M−1), row-major), the
/// generatrix, the column quantities (a_j here: the user's values; a fixed a_j has none), ε and
/// the given plane normals (N·(M−1), row-major, when given and not the Monge planes; else empty).
struct Swept {
    ratios: Vec<f64>,
    generatrix: Vec<DVec3>,
    columns: ColumnBars,
    epsilon: f64,
    normals: Vec<DVec3>,
    /// The coplanar construction's ∂L/∂ρ_j and ∂L/∂τ_j (M−1 each), or empty.
    pencil: (Vec<f64>, Vec<f64>),
    /// A blend's cotangents of apex only's values.
    blend: Option<BlendBars>,
}

/// A blend's cotangents of what it took from apex only: a_j^Q (M−1) and t_Q.
struct BlendBars {
    apex: Vec<f64>,
    scale: f64,
}

/// What the column quantities collect over the rows: their cotangents and ε's.
struct Collected {
    columns: ColumnBars,
    epsilon: f64,
}

impl Collected {
    fn zeros<const N: usize>(m: usize) -> Self {
        Self {
            columns: ColumnBars::zeros(if N > N_RATIOS { m } else { 0 }),
            epsilon: 0.0,
        }
    }
    fn add(self, o: Self) -> Self {
        Self {
            columns: self.columns.add(&o.columns),
            epsilon: self.epsilon + o.epsilon,
        }
    }
}

impl Backward<'_> {
    /// What step `jn` of row i reads, on dual numbers following the first `N` directions, and
    /// how its plane is obtained.
    #[inline(always)]
    pub(super) fn step_inputs<const N: usize>(
        &self,
        i: usize,
        jn: usize,
    ) -> (StepInputs<N>, PlaneRule) {
        let (dx, m) = (&self.prep.dx, self.prep.dx.columns());
        let rule = match (self.given, self.piece.fixed.get(i * (m - 1) + jn - 1)) {
            (Some(_), _) => PlaneRule::Given,
            (None, Some(true)) => PlaneRule::Fixed,
            _ => PlaneRule::Ratio,
        };
        let b = self
            .given
            .map_or(dx.bisectors[jn], |given| given.plane(i, jn, m));
        let s = StepInputs::<N> {
            g: D3::seed(self.mesh.vertices[i * m + jn - 1], G),
            r: Dual::seed(self.grid.row(i)[jn - 1], R),
            a: Dual::seed(self.piece.apex[jn - 1], A),
            epsilon: Dual::seed(self.epsilon, EPS),
            x0: D3::seed(dx.points[jn - 1], X0),
            x1: D3::seed(dx.points[jn], X1),
            e: D3::seed(dx.edges[jn], E),
            b: D3::seed(b, B),
        };
        (s, rule)
    }

    /// The plane normal P_{i,jn} the run used.
    pub(super) fn plane(&self, i: usize, jn: usize) -> DVec3 {
        let (s, rule) = self.step_inputs::<0>(i, jn);
        step_plane(&s, rule, 1.0 / self.prep.scale).value()
    }

    /// The sweep following the first `N` directions, the column cotangents starting at `outputs`
    /// (the outputs' own). The rows are swept in parallel between the columns of coupled fixes;
    /// at such a column the fixed a_{j0}'s total cotangent goes to the row the fix came from.
    fn run<const N: usize>(&self, outputs: ColumnBars) -> Swept {
        let (n, m) = (self.prep.generatrix.len(), self.prep.dx.columns());
        let mut ratios = vec![0.0; n * (m - 1)];
        // The given normals' cotangents: one per vertex, else a dummy per row.
        let normal_bars = self.given_normals();
        let width = if normal_bars { m - 1 } else { 1 };
        let mut normals = vec![DVec3::ZERO; n * width];
        let mut lambda: Vec<DVec3> = (0..n).map(|i| self.mesh_bar[i * m + m - 1]).collect();
        let mut total = Collected {
            columns: outputs,
            epsilon: 0.0,
        };
        let mut hi = m - 1;
        let mut fixes = self.piece.apex_fixes.iter().peekable();
        let pencil = self.given.and_then(|g| g.pencil);
        let mut pencil_bars = match pencil {
            Some(_) => (vec![0.0; m - 1], vec![0.0; m - 1]),
            None => Default::default(),
        };
        while hi >= 1 {
            let fix = fixes.next_if(|f| f.column <= hi && f.column >= 1);
            // The coplanar planes couple the rows at every column (row 0's vertex).
            let lo = match (fix, pencil) {
                (_, Some(_)) => hi,
                (Some(f), None) => f.column,
                (None, None) => 1,
            };
            let part = ratios
                .par_chunks_mut(m - 1)
                .zip(normals.par_chunks_mut(width))
                .zip(lambda.par_iter_mut())
                .enumerate()
                .fold(
                    || Collected::zeros::<N>(m),
                    |mut acc, (i, ((r_bar, p_bar), l))| {
                        *l = self.row::<N>(i, hi, lo, *l, (r_bar, p_bar), &mut acc);
                        acc
                    },
                )
                .reduce(|| Collected::zeros::<N>(m), Collected::add);
            if N > N_RATIOS {
                total = total.add(part);
            }
            if let Some(fix) = fix {
                self.pull_apex_fix(fix, &mut total, &mut ratios, &mut lambda);
            }
            if let Some(pencil) = pencil {
                let bar = (0..n).map(|i| normals[i * width + hi - 1]).sum();
                let (g, rho, tau) =
                    coplanar::pull_plane(self.prep, pencil, self.mesh, hi, bar, &mut total.columns);
                lambda[0] += g;
                pencil_bars.0[hi - 1] = rho;
                pencil_bars.1[hi - 1] = tau;
            }
            hi = lo - 1;
        }
        if let Some(fix) = self.piece.generatrix_fix {
            self.pull_generatrix_fix(fix, &mut total, &mut ratios, &mut lambda);
        }
        let blend = self
            .piece
            .blend
            .map(|b| self.pull_blend(b, &mut total, &mut lambda));
        if !normal_bars {
            normals.clear();
        }
        Swept {
            ratios,
            generatrix: lambda,
            columns: total.columns,
            epsilon: total.epsilon,
            normals,
            pencil: pencil_bars,
            blend,
        }
    }

    /// Whether the planes are given by the user (not the Monge planes): their cotangents are
    /// kept per vertex (the Monge planes' go to the bisectors).
    fn given_normals(&self) -> bool {
        self.given.is_some_and(|g| !g.monge)
    }

    /// Row i's backward sweep over the steps `hi` down to `lo` from λ_{i,hi}: writes ∂L/∂r_{i,·}
    /// to `r_bar` and the given normals' ∂L/∂P_{i,·} to `p_bar` (when [`Self::given_normals`]),
    /// adds the column quantities' and ε's cotangents to `acc`, returns λ_{i,lo−1}.
    #[inline(always)]
    fn row<const N: usize>(
        &self,
        i: usize,
        hi: usize,
        lo: usize,
        mut lambda: DVec3,
        (r_bar, p_bar): (&mut [f64], &mut [DVec3]),
        acc: &mut Collected,
    ) -> DVec3 {
        let m = self.prep.dx.columns();
        let normal_bars = self.given_normals();
        let inv_scale = 1.0 / self.prep.scale;
        for jn in (lo..=hi).rev() {
            let (s, rule) = self.step_inputs::<N>(i, jn);
            let (out, p) = ratio_step(&s, rule, inv_scale);
            let mu = self
                .plane_bar
                .get(i * (m - 1) + jn - 1)
                .copied()
                .unwrap_or(DVec3::ZERO);
            let pull = |k: usize| out.pull(lambda, k) + p.pull(mu, k);
            let pull3 = |k: usize| out.pull3(lambda, k) + p.pull3(mu, k);
            r_bar[jn - 1] = pull(R);
            if N > EPS {
                acc.columns.a[jn - 1] += pull(A);
                acc.epsilon += pull(EPS);
            }
            if N > B {
                let c = &mut acc.columns;
                c.x[jn - 1] += pull3(X0);
                c.x[jn] += pull3(X1);
                c.e[jn] += pull3(E);
                if normal_bars {
                    p_bar[jn - 1] = pull3(B);
                } else {
                    c.b[jn] += pull3(B);
                }
            }
            lambda = pull3(G) + self.mesh_bar[i * m + jn - 1];
        }
        lambda
    }

    /// The apex fix at column j0: a_{j0}'s whole cotangent (its steps' and the outputs') goes to
    /// what the fixed value reads; the user's a_{j0} keeps none.
    fn pull_apex_fix(
        &self,
        fix: &ApexFix,
        total: &mut Collected,
        ratios: &mut [f64],
        lambda: &mut [DVec3],
    ) {
        let (j0, i, m) = (fix.column, fix.row, self.prep.dx.columns());
        let bar = std::mem::take(&mut total.columns.a[j0 - 1]);
        let a = apex_fix::<N_FIX>(
            self.prep,
            self.grid,
            self.mesh,
            &self.piece.apex,
            j0,
            i,
            self.epsilon,
            fix.pole,
        );
        let one = |k: usize| bar * a.d[k];
        let three = |k: usize| DVec3::new(one(k), one(k + 1), one(k + 2));
        lambda[i] += three(FIX_G);
        ratios[i * (m - 1) + j0 - 1] += one(FIX_R0);
        ratios[i * (m - 1) + j0] += one(FIX_R1);
        total.epsilon += one(FIX_EPS);
        let c = &mut total.columns;
        c.x[j0 - 1] += three(FIX_XM);
        c.x[j0] += three(FIX_X);
        c.x[j0 + 1] += three(FIX_XP);
        c.e[j0] += three(FIX_E0);
        c.b[j0] += three(FIX_B0);
        c.e[j0 + 1] += three(FIX_E1);
        c.b[j0 + 1] += three(FIX_B1);
    }

    /// A blend: the sweep read a_j(λ) = (1 − λ) a_j + λ a_j^Q and the generatrix scaled about X_0
    /// by t(λ) = (1 − λ) + λ t_Q. The user's a_j and generatrix keep their parts (`total`,
    /// `lambda`: the mesh's column 0 cotangents on entry, the input generatrix's on return);
    /// apex only's a_j^Q and t_Q get the rest.
    fn pull_blend(&self, blend: Blend, total: &mut Collected, lambda: &mut [DVec3]) -> BlendBars {
        let (x0, t, l) = (self.prep.dx.points[0], blend.scale, blend.lambda);
        let mut t_bar = 0.0;
        for (g_bar, g) in lambda.iter_mut().zip(&self.prep.generatrix) {
            t_bar += g_bar.dot(*g - x0);
            total.columns.x[0] += *g_bar * (1.0 - t);
            *g_bar *= t;
        }
        let apex = total
            .columns
            .a
            .iter_mut()
            .map(|a| {
                let q = l * *a;
                *a *= 1.0 - l;
                q
            })
            .collect();
        BlendBars {
            apex,
            scale: l * t_bar,
        }
    }

    /// The generatrix fix: column 0 of the mesh is `X_0 + (G_{i,0} − X_0) T`; `lambda` holds its
    /// cotangents on entry and the input generatrix's on return.
    fn pull_generatrix_fix(
        &self,
        fix: GeneratrixFix,
        total: &mut Collected,
        ratios: &mut [f64],
        lambda: &mut [DVec3],
    ) {
        let (x0, m) = (self.prep.dx.points[0], self.prep.dx.columns());
        let t = fix.scale;
        let mut t_bar = fix.bar;
        for (l, g) in lambda.iter_mut().zip(&self.prep.generatrix) {
            t_bar += l.dot(*g - x0);
            total.columns.x[0] += *l * (1.0 - t);
            *l *= t;
        }
        let s = generatrix_scale::<N_ALL>(self.prep, self.grid, fix.row, self.epsilon);
        let one = |k: usize| t_bar * s.d[k];
        let three = |k: usize| DVec3::new(one(k), one(k + 1), one(k + 2));
        lambda[fix.row] += three(G);
        ratios[fix.row * (m - 1)] += one(R);
        total.epsilon += one(EPS);
        let c = &mut total.columns;
        c.x[0] += three(X0);
        c.x[1] += three(X1);
        c.e[1] += three(E);
        c.b[1] += three(B);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Polyline;
    use crate::conenet::blend::Taken;
    use crate::conenet::construct;
    use crate::conenet::construct::construct_traced;
    use crate::conenet::correction::CorrectionKind;
    use crate::conenet::inputs::{ApexInput, Assistance, ColumnValues, EndPlanes};
    use crate::conenet::margins::face_margins;
    use proptest::prelude::*;

    fn inputs(ratios: Vec<Vec<f64>>, twist: f64) -> ConstructInputs {
        let directrix = Polyline::open(
            (0..6)
                .map(|k| {
                    let t = k as f64 * 0.4;
                    DVec3::new(3.0 * t.cos(), 3.0 * t.sin(), twist * t)
                })
                .collect(),
        );
        let generatrix = Polyline::open(
            (0..4)
                .map(|k| DVec3::new(3.2 + 0.4 * k as f64, 0.0, 0.3 * k as f64))
                .collect(),
        );
        let mut c = ConstructInputs::new(directrix, generatrix);
        c.ratios = GridValues::PerVertex(ratios);
        c
    }

    /// Fixed weights w_k of the objective L = Σ w_k · G_k.
    fn weights(count: usize) -> Vec<DVec3> {
        (0..count)
            .map(|k| DVec3::new((k as f64 * 0.7).sin(), (k as f64 * 1.3).cos(), 0.5))
            .collect()
    }

    fn loss(c: &ConstructInputs, weights: &[DVec3]) -> f64 {
        let net = construct(c).unwrap();
        net.mesh
            .vertices
            .iter()
            .zip(weights)
            .map(|(g, w)| g.dot(*w))
            .sum()
    }

    /// The largest difference between `exact` and central differences of `loss` over the scalars
    /// `set(c, k, ·)` moves (k < count), relative to the largest difference quotient.
    fn compare(
        c: &ConstructInputs,
        weights: &[DVec3],
        count: usize,
        exact: &[f64],
        set: impl Fn(&mut ConstructInputs, usize, f64),
    ) -> f64 {
        assert_eq!(exact.len(), count);
        let (mut worst, mut size) = (0.0f64, 0.0f64);
        // Central differences at h and h/2, extrapolated (Richardson): error O(h⁴), so a design
        // near a degenerate one (the loss's slope 4.6e6 in the apex: h² alone left 1e-5) is
        // still checked to 1e-6.
        let central = |k: usize, h: f64| {
            let mut p = c.clone();
            set(&mut p, k, h);
            let up = loss(&p, weights);
            let mut p = c.clone();
            set(&mut p, k, -h);
            let down = loss(&p, weights);
            (up - down) / (2.0 * h)
        };
        for (k, &x) in exact.iter().enumerate() {
            let h = 1e-6;
            let fd = (4.0 * central(k, h / 2.0) - central(k, h)) / 3.0;
            worst = worst.max((fd - x).abs());
            size = size.max(fd.abs());
        }
        assert!(size > 0.0, "the gradient is zero");
        worst / size
    }

    /// L = Σ w_k · G_k with fixed weights: its gradient in the ratios through the adjoint against
    /// central differences of the construction.
    fn check(ratios: Vec<Vec<f64>>, twist: f64) -> f64 {
        let c = inputs(ratios.clone(), twist);
        let net = construct(&c).unwrap();
        let w = weights(net.mesh.vertices.len());
        let adj = construct_adjoint(&c, &net.mesh, &w).unwrap();
        let cols = ratios[0].len();
        compare(&c, &w, ratios.len() * cols, &adj.ratios, |c, k, h| {
            if let GridValues::PerVertex(r) = &mut c.ratios {
                r[k / cols][k % cols] += h;
            }
        })
    }

    /// The relative differences of the directrix's, the apex input's and the scale's exact
    /// cotangents against central differences (the scale's is 0 when it is not given).
    fn check_inputs(c: &ConstructInputs) -> [f64; 3] {
        let net = construct(c).unwrap();
        let w = weights(net.mesh.vertices.len());
        let adj = construct_adjoint(c, &net.mesh, &w).unwrap();
        let flat: Vec<f64> = adj
            .directrix
            .unwrap()
            .iter()
            .flat_map(|p| p.to_array())
            .collect();
        let directrix = compare(c, &w, flat.len(), &flat, |c, k, h| {
            c.directrix.points[k / 3][k % 3] += h;
        });
        let apex = adj.apex.unwrap();
        let apex = compare(c, &w, apex.len(), &apex, |c, k, h| {
            match &mut c.apex.values {
                ColumnValues::Uniform(v) => *v += h,
                ColumnValues::List(v) => v[k] += h,
            }
        });
        let scale = match (c.apex.scale, adj.scale) {
            (Some(_), Some(s)) if c.apex.normalized => compare(c, &w, 1, &[s], |c, _, h| {
                c.apex.scale = c.apex.scale.map(|l| l + h);
            }),
            (Some(_), Some(s)) => s.abs(),
            (None, None) => 0.0,
            (given, got) => panic!("scale given {given:?}, its cotangent {got:?}"),
        };
        [directrix, apex, scale]
    }

    /// A design: `closed` directrix of 6 points near a circle of radius 3 (else an arc) moved by
    /// `jitter`, 4 generatrix points outside it, per-vertex `ratios` (4 × M−1), apex `values`.
    fn design(
        closed: bool,
        jitter: &[f64],
        ratios: Vec<Vec<f64>>,
        values: ColumnValues,
        normalized: bool,
        scale: Option<f64>,
        end: EndPlanes,
    ) -> ConstructInputs {
        let step = if closed { PI / 3.0 } else { 0.4 };
        let points = (0..6)
            .map(|k| {
                let t = k as f64 * step;
                let j = DVec3::new(jitter[3 * k], jitter[3 * k + 1], jitter[3 * k + 2]);
                DVec3::new(3.0 * t.cos(), 3.0 * t.sin(), 0.4 * (2.0 * t).sin()) + j
            })
            .collect();
        let directrix = if closed {
            Polyline::closed(points)
        } else {
            Polyline::open(points)
        };
        let generatrix = Polyline::open(
            (0..4)
                .map(|k| DVec3::new(3.4 + 0.4 * k as f64, 0.1, 0.3 * k as f64 - 0.4))
                .collect(),
        );
        let mut c = ConstructInputs::new(directrix, generatrix);
        c.ratios = GridValues::PerVertex(ratios);
        c.apex = ApexInput {
            values,
            normalized,
            scale,
            seam: None,
        };
        c.end_planes = end;
        c
    }

    #[test]
    fn monge_ratios_gradient_matches_differences() {
        let rel = check(vec![vec![0.5; 5]; 4], 0.5);
        assert!(rel < 1e-6, "relative difference {rel}");
    }

    #[test]
    fn input_gradients_match_differences_at_half_ratios() {
        // Exactly ½ (the Monge planes): the directrix and apex derivatives have no kink there.
        let jitter = [0.0; 18];
        for closed in [false, true] {
            let m = if closed { 7 } else { 6 };
            for (values, normalized, scale) in [
                (ColumnValues::Uniform(0.95), false, None),
                (
                    ColumnValues::List((1..m).map(|j| 0.9 + 0.03 * j as f64).collect()),
                    false,
                    Some(2.0),
                ),
                (ColumnValues::Uniform(0.8), true, None),
                (
                    ColumnValues::List((1..m).map(|j| if j == 2 { 1.0 } else { 0.7 }).collect()),
                    true,
                    Some(1.5),
                ),
            ] {
                for end in [EndPlanes::Perpendicular, EndPlanes::Mirror] {
                    let c = design(
                        closed,
                        &jitter,
                        vec![vec![0.5; m - 1]; 4],
                        values.clone(),
                        normalized,
                        scale,
                        end,
                    );
                    let rel = check_inputs(&c);
                    assert!(
                        rel.iter().all(|r| *r < 1e-6),
                        "closed {closed}, {values:?}, normalized {normalized}, scale {scale:?}, \
                         {end:?}: directrix, apex, scale {rel:?}"
                    );
                }
            }
        }
    }

    /// The relative differences of every exact cotangent (directrix, apex, ratios, ε, generatrix)
    /// against central differences.
    fn check_all(c: &ConstructInputs) -> [f64; 5] {
        let net = construct(c).unwrap();
        let w = weights(net.mesh.vertices.len());
        let adj = construct_adjoint(c, &net.mesh, &w).unwrap();
        let [directrix, apex, _] = check_inputs(c);
        let ratios = compare(
            c,
            &w,
            adj.ratios.len(),
            &adj.ratios,
            |c, k, h| match &mut c.ratios {
                GridValues::Uniform(r) => *r += h,
                GridValues::PerColumn(r) => r[k] += h,
                GridValues::PerVertex(r) => {
                    let cols = r[0].len();
                    r[k / cols][k % cols] += h;
                }
            },
        );
        // ε: zero without fixes (then the differences must vanish too).
        let at = |h: f64| {
            let mut p = c.clone();
            p.assistance.epsilon += h;
            loss(&p, &w)
        };
        let fd = (at(1e-6) - at(-1e-6)) / 2e-6;
        let exact = adj.epsilon.unwrap();
        let epsilon = (fd - exact).abs() / fd.abs().max(1e-9);
        let flat: Vec<f64> = adj.generatrix.iter().flat_map(|p| p.to_array()).collect();
        let generatrix = compare(c, &w, flat.len(), &flat, |c, k, h| {
            c.generatrix.points[k / 3][k % 3] += h;
        });
        [directrix, apex, ratios, epsilon, generatrix]
    }

    /// A straight directrix (slightly bent) with a ruling leaning back at column 2: the vertices
    /// of column 1 lie beyond Π_{·,2} (tests/correction.rs, `tilted`).
    fn tilted(alpha: f64) -> ConstructInputs {
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
        let mut c = ConstructInputs::new(directrix, generatrix);
        c.ratios = GridValues::PerColumn(vec![0.5, 0.9, 0.45, 0.55, 0.5]);
        c.apex.values = ColumnValues::List(vec![1.01, 0.97, 1.02, 0.99, 1.03]);
        c.assistance = Assistance::new(alpha);
        c
    }

    fn kinds(c: &ConstructInputs) -> Vec<CorrectionKind> {
        construct(c)
            .unwrap()
            .corrections
            .iter()
            .map(|c| c.kind)
            .collect()
    }

    #[test]
    fn plane_fixes_of_the_correction_are_differentiated() {
        // Planes only (α = 0) turns the planes of column 2.
        let c = tilted(0.0);
        let k = kinds(&c);
        assert!(
            !k.is_empty() && k.iter().all(|k| *k == CorrectionKind::Ratio),
            "{k:?}"
        );
        let rel = check_all(&c);
        assert!(
            rel.iter().all(|r| *r < 1e-6),
            "directrix, apex, ratios, ε, generatrix: {rel:?}"
        );
    }

    /// Which piece a run took: its form (a blend's λ) and which values the correction changed.
    type PieceKey = (Taken, Vec<(CorrectionKind, usize, Option<usize>)>);

    fn piece_key(c: &ConstructInputs) -> PieceKey {
        let (net, taken) = construct_traced(c, Reports::ALL).unwrap();
        let changed = net
            .corrections
            .iter()
            .map(|c| (c.kind, c.column, c.row))
            .collect();
        (taken, changed)
    }

    /// Asserts every input moved by ±1e-6 (the difference steps) keeps the piece of `c`.
    fn assert_one_piece(c: &ConstructInputs) {
        let key = piece_key(c);
        let mut moved: Vec<ConstructInputs> = Vec::new();
        for h in [1e-6, -1e-6, 5e-7, -5e-7] {
            for k in 0..c.directrix.points.len() * 3 {
                let mut p = c.clone();
                p.directrix.points[k / 3][k % 3] += h;
                moved.push(p);
            }
            for k in 0..c.generatrix.points.len() * 3 {
                let mut p = c.clone();
                p.generatrix.points[k / 3][k % 3] += h;
                moved.push(p);
            }
            let mut p = c.clone();
            p.assistance.epsilon += h;
            moved.push(p);
            let count = match &c.apex.values {
                ColumnValues::Uniform(_) => 1,
                ColumnValues::List(v) => v.len(),
            };
            for k in 0..count {
                let mut p = c.clone();
                match &mut p.apex.values {
                    ColumnValues::Uniform(v) => *v += h,
                    ColumnValues::List(v) => v[k] += h,
                }
                moved.push(p);
            }
            let count = match &c.ratios {
                GridValues::Uniform(_) => 1,
                GridValues::PerColumn(r) => r.len(),
                GridValues::PerVertex(r) => r.len() * r[0].len(),
            };
            for k in 0..count {
                let mut p = c.clone();
                match &mut p.ratios {
                    GridValues::Uniform(r) => *r += h,
                    GridValues::PerColumn(r) => r[k] += h,
                    GridValues::PerVertex(r) => {
                        let cols = r[0].len();
                        r[k / cols][k % cols] += h;
                    }
                }
                moved.push(p);
            }
        }
        for p in &moved {
            assert_eq!(piece_key(p), key, "a difference step leaves the piece");
        }
    }

    #[test]
    fn a_blended_run_of_the_correction_is_differentiated() {
        // A blend (α = 0.5): the apex values and the generatrix scale move half way to apex
        // only's (another sweep, differentiated on its own piece), planes only on top.
        for (what, mut c, ratios) in [
            ("per column", tilted(0.5), None),
            (
                "per vertex",
                tilted(0.5),
                Some(GridValues::PerVertex(vec![
                    vec![0.5, 0.9, 0.45, 0.55, 0.5],
                    vec![0.52, 0.88, 0.5, 0.5, 0.47],
                    vec![0.49, 0.91, 0.53, 0.5, 0.5],
                ])),
            ),
            ("generatrix scaled", first_column_fold(0.5), None),
        ] {
            if let Some(r) = ratios {
                c.ratios = r;
            }
            let (taken, changed) = piece_key(&c);
            assert!(
                matches!(taken, Taken::Blend { lambda, mixed: false } if lambda == 0.5),
                "{what}: {taken:?}"
            );
            assert!(
                changed.iter().any(|k| k.0 != CorrectionKind::Ratio),
                "{what}: {changed:?}"
            );
            assert_one_piece(&c);
            let rel = check_all(&c);
            assert!(
                rel.iter().all(|r| *r < 1e-6),
                "{what}: directrix, apex, ratios, ε, generatrix: {rel:?}"
            );
            let rel = check_outputs(&c);
            assert!(rel < 1e-6, "{what}: the other outputs: {rel}");
        }
    }

    #[test]
    fn apex_fixes_of_the_correction_are_differentiated() {
        // Apex only (α = 1) lowers a_1, per column, and with ratios per vertex.
        let mut c = tilted(1.0);
        for per_vertex in [false, true] {
            if per_vertex {
                c.ratios = GridValues::PerVertex(vec![
                    vec![0.5, 0.9, 0.45, 0.55, 0.5],
                    vec![0.52, 0.88, 0.5, 0.5, 0.47],
                    vec![0.49, 0.91, 0.53, 0.5, 0.5],
                ]);
            }
            let k = kinds(&c);
            assert!(
                !k.is_empty() && k.iter().all(|k| *k == CorrectionKind::Apex),
                "{k:?}"
            );
            let rel = check_all(&c);
            assert!(
                rel.iter().all(|r| *r < 1e-6),
                "per vertex {per_vertex}: directrix, apex, ratios, ε, generatrix: {rel:?}"
            );
        }
    }

    /// G_{1,0} beyond the first plane (tests/correction.rs, `first_column_fold`), the directrix
    /// slightly bent.
    fn first_column_fold(alpha: f64) -> ConstructInputs {
        let directrix = Polyline::open(
            (0..4)
                .map(|j| DVec3::new(j as f64, 0.04 * (j * j) as f64, -0.03 * j as f64))
                .collect(),
        );
        let generatrix = Polyline::open(vec![
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(1.4, 1.0, 1.0),
            DVec3::new(0.0, 1.0, 2.0),
        ]);
        let mut c = ConstructInputs::new(directrix, generatrix);
        c.ratios = GridValues::PerColumn(vec![0.48, 0.53, 0.5]);
        c.apex.values = ColumnValues::List(vec![0.98, 1.02, 0.97]);
        c.assistance = Assistance::new(alpha);
        c
    }

    #[test]
    fn the_generatrix_fix_of_the_correction_is_differentiated() {
        // Apex only scales the generatrix about X_0.
        let c = first_column_fold(1.0);
        let k = kinds(&c);
        assert!(k.contains(&CorrectionKind::Generatrix), "{k:?}");
        let rel = check_all(&c);
        assert!(
            rel.iter().all(|r| *r < 1e-6),
            "directrix, apex, ratios, ε, generatrix: {rel:?}"
        );
    }

    /// L = Σ weights · (apex values, apices, plane normals, convexity margins): the relative
    /// differences of the exact directrix, apex, ratio and generatrix cotangents against central
    /// differences.
    fn check_outputs(c: &ConstructInputs) -> f64 {
        let net = construct(c).unwrap();
        let cols = net.apex.len();
        let zero = vec![DVec3::ZERO; net.mesh.vertices.len()];
        let apex_w: Vec<f64> = (0..cols).map(|j| (0.9 * j as f64).sin() + 0.2).collect();
        let apices_w: Vec<DVec3> = (0..cols)
            .map(|j| DVec3::new(0.1 * j as f64, -0.2, 0.05))
            .collect();
        let planes_w: Vec<DVec3> = (0..net.mesh.rows * cols)
            .map(|k| DVec3::new((0.3 * k as f64).cos(), 0.4, -(0.7 * k as f64).sin()))
            .collect();
        let margins_w: Vec<f64> = (0..face_margins(&net).len())
            .map(|k| (1.7 * k as f64).sin())
            .collect();
        let bars = OutputBars {
            mesh: &zero,
            apex: &apex_w,
            apices: &apices_w,
            planes: &planes_w,
            margins: &margins_w,
        };
        let adj = construct_adjoint_for(c, &net.mesh, bars, Wrt::ALL).unwrap();
        let out = |c: &ConstructInputs| {
            let net = construct(c).unwrap();
            let a: f64 = net.apex.iter().zip(&apex_w).map(|(a, w)| a * w).sum();
            let p: f64 = net
                .apices
                .iter()
                .zip(&apices_w)
                .filter_map(|(p, w)| p.map(|p| p.dot(*w)))
                .sum();
            let rows = net.mesh.rows;
            let planes: f64 = (0..rows * cols)
                .map(|k| net.normals.get(k / cols, k % cols + 1).dot(planes_w[k]))
                .sum();
            let margins: f64 = face_margins(&net)
                .iter()
                .zip(&margins_w)
                .map(|(m, w)| m * w)
                .sum();
            a + p + planes + margins
        };
        let central = |set: &dyn Fn(&mut ConstructInputs, f64)| {
            let h = 1e-6;
            let (mut p, mut q) = (c.clone(), c.clone());
            set(&mut p, h);
            set(&mut q, -h);
            (out(&p) - out(&q)) / (2.0 * h)
        };
        let (mut worst, mut size) = (0.0f64, 0.0f64);
        let mut compare = |fd: f64, x: f64| {
            worst = worst.max((fd - x).abs());
            size = size.max(fd.abs());
        };
        for (k, p) in adj.directrix.unwrap().iter().enumerate() {
            for d in 0..3 {
                compare(central(&|c, h| c.directrix.points[k][d] += h), p[d]);
            }
        }
        for (k, p) in adj.generatrix.iter().enumerate() {
            for d in 0..3 {
                compare(central(&|c, h| c.generatrix.points[k][d] += h), p[d]);
            }
        }
        for (k, x) in adj.apex.unwrap().iter().enumerate() {
            compare(
                central(&|c, h| match &mut c.apex.values {
                    ColumnValues::Uniform(v) => *v += h,
                    ColumnValues::List(v) => v[k] += h,
                }),
                *x,
            );
        }
        for (k, x) in adj.ratios.iter().enumerate() {
            compare(
                central(&|c, h| match &mut c.ratios {
                    GridValues::Uniform(r) => *r += h,
                    GridValues::PerColumn(r) => r[k] += h,
                    GridValues::PerVertex(r) => {
                        let cols = r[0].len();
                        r[k / cols][k % cols] += h;
                    }
                }),
                *x,
            );
        }
        worst / size
    }

    #[test]
    fn the_other_outputs_are_differentiated() {
        let c = design(
            false,
            &[0.0; 18],
            vec![vec![0.45; 5]; 4],
            ColumnValues::List(vec![0.9, 0.95, 1.1, 0.8, 1.05]),
            true,
            None,
            EndPlanes::Perpendicular,
        );
        let mut closed = design(
            true,
            &[0.05; 18],
            vec![vec![0.52; 6]; 4],
            ColumnValues::Uniform(0.96),
            false,
            None,
            EndPlanes::Perpendicular,
        );
        // A closed generatrix too: the margins of the faces between the last row and the first.
        closed.generatrix.closed = true;
        for (what, c) in [
            ("open, normalized", c),
            ("closed directrix and generatrix", closed),
            ("planes only", tilted(0.0)),
            ("apex only", tilted(1.0)),
        ] {
            let rel = check_outputs(&c);
            assert!(rel < 1e-6, "{what}: relative difference {rel}");
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]
        #[test]
        fn ratio_gradient_matches_differences(
            table in proptest::collection::vec(proptest::collection::vec(0.3f64..0.7, 5), 4),
            twist in 0.0f64..1.0,
        ) {
            // Keep off the kink of the ratio → angle map at ½ (the derivative jumps there).
            let table: Vec<Vec<f64>> = table
                .into_iter()
                .map(|r| r.into_iter().map(|x| if (x - 0.5).abs() < 1e-3 { x + 2e-3 } else { x }).collect())
                .collect();
            let rel = check(table, twist);
            prop_assert!(rel < 1e-6, "relative difference {}", rel);
        }

        #[test]
        fn input_gradients_match_differences(
            closed in any::<bool>(),
            mirror in any::<bool>(),
            normalized in any::<bool>(),
            given_scale in proptest::option::of(1.0f64..2.5),
            uniform in any::<bool>(),
            jitter in proptest::collection::vec(-0.15f64..0.15, 18),
            values in proptest::collection::vec(0.85f64..1.15, 6),
            // Ratios near the kink at ½, on either side (not at it), or farther away.
            offsets in proptest::collection::vec(
                prop_oneof![1e-4f64..1e-2, -1e-2f64..-1e-4, -0.15f64..0.15],
                24,
            ),
        ) {
            let m = if closed { 7 } else { 6 };
            let ratios: Vec<Vec<f64>> = offsets
                .chunks(6)
                .map(|r| r[..m - 1].iter().map(|d| if *d == 0.0 { 0.51 } else { 0.5 + d }).collect())
                .collect();
            let values = if uniform {
                ColumnValues::Uniform(values[0])
            } else {
                ColumnValues::List(values[..m - 1].to_vec())
            };
            let end = if mirror { EndPlanes::Mirror } else { EndPlanes::Perpendicular };
            let c = design(closed, &jitter, ratios, values, normalized, given_scale, end);
            prop_assume!(construct(&c).is_ok());
            let rel = check_inputs(&c);
            prop_assert!(
                rel.iter().all(|r| *r < 1e-6),
                "directrix, apex, scale: {:?}", rel
            );
        }
    }
}
