//! The adjoint (reverse-mode derivative) of CNets Construct (ratios): a backward sweep.
//!
//! The forward sweep is a recurrence along each row: `G_{i,j} = F(G_{i,j−1}, r_{i,j}, a_j, X_{j−1},
//! X_j, ê_j, b_j)` with the plane Π_{i,j} from the ratio (its support frame depends on G_{i,j−1}) and
//! the step of Eq. 1. For cotangents `λ_{i,j} = ∂L/∂G_{i,j}` of an objective L, the backward sweep
//! runs j = M−1 … 1: `∂L/∂r_{i,j} = J_r(i,j)ᵀ λ_{i,j}`, `λ_{i,j−1} += J_g(i,j)ᵀ λ_{i,j}`, and the
//! column quantities collect `J_a ᵀ λ`, `J_X ᵀ λ`, `J_ê ᵀ λ`, `J_b ᵀ λ` summed over the rows; what
//! reaches column 0 is the generatrix's cotangent. The local Jacobians come from one forward-mode
//! evaluation of the step on dual numbers ([`super::dual`]) at the stored vertices, with as many
//! directions as the wanted inputs need ([`Wrt`]: 4, 6 or 18), so the backward sweep costs a small
//! constant times the forward one, rows in parallel. The column cotangents are then pulled back
//! through the directrix's edges and bisectors and the apex normalization to the user's inputs
//! ([`super::directrix_adjoint`]).
//!
//! The ratio → angle map has a kink at r = ½; exactly there the mean of its two slopes is used.
//! A run of the assisted correction is differentiated on the piece it took when it only turned
//! planes (per-row plane fixes, `θ = (1 − ε) φ`: then the plane no longer depends on the ratio nor
//! the bisector, but on ε); a run that changed apex values or scaled the generatrix is declined (an
//! error: the caller differentiates by finite differences and says so).

use std::f64::consts::PI;

use glam::DVec3;
use rayon::prelude::*;

use super::construct::construct_with;
use super::correction::CorrectionKind;
use super::directrix_adjoint::{ColumnBars, pull_back};
use super::dual::{D3, Dual};
use super::inputs::{ConstructInputs, GridValues};
use super::prepare::prepare;
use super::result::Reports;
use super::tolerance;
use crate::{GeometryError, QuadGrid};

// The directions of a step's local Jacobian: G_{i,j−1} (3), r, a_j, ε, X_{j−1} (3), X_j (3), ê_j
// (3), b_j (3). A sweep follows the first N of them.
const G: usize = 0;
const R: usize = 3;
const A: usize = 4;
const EPS: usize = 5;
const X0: usize = 6;
const X1: usize = 9;
const E: usize = 12;
const B: usize = 15;
/// Directions for the ratios and the generatrix only.
const N_RATIOS: usize = 4;
/// … and the apex values and ε.
const N_APEX: usize = 6;
/// … and the directrix.
const N_ALL: usize = 18;

/// How the plane of a step is obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum PlaneRule {
    /// From the ratio (notes §3).
    Ratio,
    /// The assisted correction's plane fix: `θ = (1 − ε) φ` (notes §6).
    Fixed,
}

/// The values one step reads, on dual numbers.
struct StepInputs<const N: usize> {
    g: D3<N>,
    r: Dual<N>,
    a: Dual<N>,
    epsilon: Dual<N>,
    x0: D3<N>,
    x1: D3<N>,
    e: D3<N>,
    b: D3<N>,
}

/// One step of the ratio construction on dual numbers: `G_{i,jn}` from `g = G_{i,jn−1}`, the ratio
/// `r` (or the plane fix's ε), `a = a_jn`, `x0 = X_{jn−1}`, `x1 = X_jn`, `e = ê_jn` and the Monge
/// normal `b = b_jn` (same formulas as the lanes kernel, `ratios::ratio_planes`, the plane fix of
/// `sweep::sources` and `prepare::step`). `e` and `b` are followed as free vectors: only their
/// derivatives along the unit sphere are used by the chain that follows.
#[inline(always)]
fn ratio_step<const N: usize>(s: &StepInputs<N>, rule: PlaneRule, inv_scale: f64) -> D3<N> {
    let StepInputs {
        g,
        r,
        a,
        epsilon,
        x0,
        x1,
        e,
        b,
    } = *s;
    let d = g.sub(x0);
    let on_directrix =
        d.0.iter().fold(0.0f64, |m, x| m.max(x.v.abs())) * inv_scale <= tolerance::FRAME;
    let p = if on_directrix {
        b
    } else {
        let perp = d.sub(e.scale(d.dot(e)));
        let inv_len = Dual::constant(1.0) / perp.dot(perp).sqrt();
        let w = perp.scale(inv_len);
        let theta = match rule {
            PlaneRule::Fixed => {
                // φ: the angle of G_{i,j−1} − X_j from ê in the support frame.
                let v = g.sub(x1);
                Dual::atan2(w.dot(v), e.dot(v)) * (Dual::constant(1.0) - epsilon)
            }
            PlaneRule::Ratio => {
                let theta_b = Dual::atan2(e.dot(b), -w.dot(b));
                // At r = ½ the map has a kink (slopes 2θ_b and 2(π − θ_b)): the mean slope π is
                // used there, the derivative central differences see (an element of the
                // subdifferential). Both pieces have slope 1 in θ_b there.
                if r.v == 0.5 {
                    theta_b + (r - Dual::constant(0.5)) * PI
                } else if r.v < 0.5 {
                    r * theta_b * 2.0
                } else {
                    theta_b + (r * 2.0 - Dual::constant(1.0)) * (Dual::constant(PI) - theta_b)
                }
            }
        };
        e.scale(theta.sin()).sub(w.scale(theta.cos()))
    };
    let v = d.scale(a).add(x1).sub(g);
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
}

impl Wrt {
    /// Every input.
    pub const ALL: Wrt = Wrt {
        apex: true,
        directrix: true,
        epsilon: true,
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
    };
    construct_adjoint_for(inputs, mesh, bars, Wrt::ALL)
}

/// The backward sweep of [`super::construct`] for the mesh it built (`mesh`) and the cotangents of
/// its outputs (`bars`): the ratios' and the generatrix's cotangents, and those `wrt` asks for.
///
/// With the assisted correction on, the construction is run again to learn which planes it fixed;
/// a run that changed apex values or scaled the generatrix is declined (an error).
pub fn construct_adjoint_for(
    inputs: &ConstructInputs,
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
    extra(bars.apices.len(), "apices")?;
    let grid = inputs
        .ratios
        .resolve("ratios", n, m - 1, (0.0, 1.0, "a value in [0, 1]"))?;
    let fixed = fixed_planes(inputs, n, m)?;
    let sweep = Backward {
        prep: &prep,
        grid: &grid,
        mesh,
        mesh_bar: bars.mesh,
        fixed: &fixed,
        epsilon: inputs.assistance.epsilon,
    };
    let (ratio_bar, generatrix, mut columns, epsilon) = if wrt.directrix {
        sweep.run::<N_ALL>()
    } else if wrt.apex || wrt.epsilon {
        sweep.run::<N_APEX>()
    } else {
        sweep.run::<N_RATIOS>()
    };
    // The apex and apices outputs.
    let dx = &prep.dx;
    columns
        .a
        .iter_mut()
        .zip(bars.apex)
        .for_each(|(s, x)| *s += x);
    for (j, c_bar) in (1..m).zip(bars.apices) {
        let a = prep.apex[j - 1];
        let t = 1.0 - a;
        let edge = dx.points[j] - dx.points[j - 1];
        // C = X_j + (X_j − X_{j−1}) a / (1 − a) (`apex::apex_point`); none at infinity.
        if super::apex::apex_point(dx.points[j - 1], dx.points[j], a).is_none() {
            continue;
        }
        columns.x[j] += *c_bar / t;
        columns.x[j - 1] -= *c_bar * (a / t);
        columns.a[j - 1] += c_bar.dot(edge) / (t * t);
    }
    let ratios = match &inputs.ratios {
        GridValues::Uniform(_) => vec![ratio_bar.iter().sum()],
        GridValues::PerColumn(_) => (0..m - 1)
            .map(|j| ratio_bar.iter().skip(j).step_by(m - 1).sum())
            .collect(),
        GridValues::PerVertex(_) => ratio_bar,
    };
    let stored = inputs.directrix.points.len();
    let pulled = (wrt.apex || wrt.directrix)
        .then(|| pull_back(columns, dx, inputs.end_planes, &inputs.apex, stored));
    let finite = |x: &f64| x.is_finite();
    let result = ConstructAdjoint {
        ratios,
        generatrix,
        apex: pulled.as_ref().filter(|_| wrt.apex).map(|p| p.apex.clone()),
        scale: pulled.as_ref().filter(|_| wrt.apex).and_then(|p| p.scale),
        directrix: pulled
            .as_ref()
            .filter(|_| wrt.directrix)
            .map(|p| p.directrix.clone()),
        epsilon: wrt.epsilon.then_some(epsilon),
    };
    let all_finite = result.ratios.iter().all(finite)
        && result.generatrix.iter().all(|g| g.is_finite())
        && result.apex.iter().flatten().all(finite)
        && result.scale.iter().all(finite)
        && result.directrix.iter().flatten().all(|g| g.is_finite())
        && result.epsilon.iter().all(finite);
    if !all_finite {
        return Err(GeometryError::Degenerate(
            "the construction's derivative is not finite (a degenerate step)".into(),
        ));
    }
    Ok(result)
}

/// Which planes the assisted correction fixed (N·(M−1), row-major; empty without assistance), or
/// the error that declines a run whose corrections this adjoint does not follow.
fn fixed_planes(inputs: &ConstructInputs, n: usize, m: usize) -> Result<Vec<bool>, GeometryError> {
    if !inputs.assistance.enabled() {
        return Ok(Vec::new());
    }
    let net = construct_with(
        inputs,
        Reports {
            apices: false,
            quality: false,
        },
    )?;
    let mut fixed = vec![false; n * (m - 1)];
    for c in &net.corrections {
        match (c.kind, c.row) {
            (CorrectionKind::Ratio, Some(i)) if i < n && (1..m).contains(&c.column) => {
                fixed[i * (m - 1) + c.column - 1] = true;
            }
            _ => {
                return Err(GeometryError::Degenerate(format!(
                    "the derivative of a correction that changes the apex function or the \
                     generatrix is not implemented ({c})"
                )));
            }
        }
    }
    Ok(fixed)
}

/// The backward sweep's data.
struct Backward<'a> {
    prep: &'a super::prepare::Prepared,
    grid: &'a super::inputs::Grid<'a>,
    mesh: &'a QuadGrid,
    mesh_bar: &'a [DVec3],
    /// Plane-fixed steps (N·(M−1)), or empty.
    fixed: &'a [bool],
    epsilon: f64,
}

/// What the column quantities collect over the rows: their cotangents and ε's.
struct Collected {
    columns: ColumnBars,
    epsilon: f64,
}

impl Backward<'_> {
    /// The sweep following the first `N` directions: the ratios' cotangents (N·(M−1), row-major),
    /// the generatrix's, the column quantities' and ε's.
    fn run<const N: usize>(&self) -> (Vec<f64>, Vec<DVec3>, ColumnBars, f64) {
        let (n, m) = (self.prep.generatrix.len(), self.prep.dx.columns());
        let mut ratio_bar = vec![0.0; n * (m - 1)];
        let mut generatrix = vec![DVec3::ZERO; n];
        let columns = |m| Collected {
            columns: ColumnBars::zeros(if N > N_RATIOS { m } else { 0 }),
            epsilon: 0.0,
        };
        let collected = ratio_bar
            .par_chunks_mut(m - 1)
            .zip(generatrix.par_iter_mut())
            .enumerate()
            .fold(
                || columns(m),
                |mut acc, (i, (r_bar, g_bar))| {
                    *g_bar = self.row::<N>(i, r_bar, &mut acc);
                    acc
                },
            )
            .reduce(
                || columns(m),
                |a, b| Collected {
                    columns: a.columns.add(&b.columns),
                    epsilon: a.epsilon + b.epsilon,
                },
            );
        let mut bars = collected.columns;
        if N <= N_RATIOS {
            bars = ColumnBars::zeros(m);
        }
        (ratio_bar, generatrix, bars, collected.epsilon)
    }

    /// Row i's backward sweep: writes ∂L/∂r_{i,·} to `r_bar`, adds the column quantities' and ε's
    /// cotangents to `acc`, returns ∂L/∂G_{i,0}.
    #[inline(always)]
    fn row<const N: usize>(&self, i: usize, r_bar: &mut [f64], acc: &mut Collected) -> DVec3 {
        let (dx, m) = (&self.prep.dx, self.prep.dx.columns());
        let ratios = self.grid.row(i);
        let inv_scale = 1.0 / self.prep.scale;
        let mut lambda = self.mesh_bar[i * m + m - 1];
        for jn in (1..m).rev() {
            let rule = match self.fixed.get(i * (m - 1) + jn - 1) {
                Some(true) => PlaneRule::Fixed,
                _ => PlaneRule::Ratio,
            };
            let s = StepInputs::<N> {
                g: D3::seed(self.mesh.vertices[i * m + jn - 1], G),
                r: Dual::seed(ratios[jn - 1], R),
                a: Dual::seed(self.prep.apex[jn - 1], A),
                epsilon: Dual::seed(self.epsilon, EPS),
                x0: D3::seed(dx.points[jn - 1], X0),
                x1: D3::seed(dx.points[jn], X1),
                e: D3::seed(dx.edges[jn], E),
                b: D3::seed(dx.bisectors[jn], B),
            };
            let out = ratio_step(&s, rule, inv_scale);
            r_bar[jn - 1] = out.pull(lambda, R);
            if N > EPS {
                acc.columns.a[jn - 1] += out.pull(lambda, A);
                acc.epsilon += out.pull(lambda, EPS);
            }
            if N > B {
                let c = &mut acc.columns;
                c.x[jn - 1] += out.pull3(lambda, X0);
                c.x[jn] += out.pull3(lambda, X1);
                c.e[jn] += out.pull3(lambda, E);
                c.b[jn] += out.pull3(lambda, B);
            }
            lambda = out.pull3(lambda, G) + self.mesh_bar[i * m + jn - 1];
        }
        lambda
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Polyline;
    use crate::conenet::construct;
    use crate::conenet::inputs::{ApexInput, Assistance, ColumnValues, EndPlanes};
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
        for (k, &x) in exact.iter().enumerate() {
            let h = 1e-6;
            let mut p = c.clone();
            set(&mut p, k, h);
            let up = loss(&p, weights);
            let mut p = c.clone();
            set(&mut p, k, -h);
            let down = loss(&p, weights);
            let fd = (up - down) / (2.0 * h);
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

    #[test]
    fn plane_fixes_of_the_correction_are_differentiated() {
        // A straight directrix (slightly bent) with a ruling leaning back at column 2: planes only
        // (α = 0) turns the planes of column 2 (tests/correction.rs, `tilted`).
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
        c.apex.values = ColumnValues::List(vec![1.0, 0.97, 1.02, 0.99, 1.0]);
        c.assistance = Assistance::new(0.0);
        let net = construct(&c).unwrap();
        assert!(
            !net.corrections.is_empty()
                && net
                    .corrections
                    .iter()
                    .all(|k| k.kind == CorrectionKind::Ratio),
            "{:?}",
            net.corrections
        );
        let w = weights(net.mesh.vertices.len());
        let adj = construct_adjoint(&c, &net.mesh, &w).unwrap();
        let [directrix, apex, _] = check_inputs(&c);
        assert!(directrix < 1e-6 && apex < 1e-6, "{directrix}, {apex}");
        let ratios = compare(&c, &w, 5, &adj.ratios, |c, k, h| {
            if let GridValues::PerColumn(r) = &mut c.ratios {
                r[k] += h;
            }
        });
        assert!(ratios < 1e-6, "ratios: {ratios}");
        let epsilon = compare(&c, &w, 1, &[adj.epsilon.unwrap()], |c, _, h| {
            c.assistance.epsilon += h;
        });
        assert!(epsilon < 1e-6, "ε: {epsilon}");
        let flat: Vec<f64> = adj.generatrix.iter().flat_map(|p| p.to_array()).collect();
        let generatrix = compare(&c, &w, flat.len(), &flat, |c, k, h| {
            c.generatrix.points[k / 3][k % 3] += h;
        });
        assert!(generatrix < 1e-6, "generatrix: {generatrix}");
        // Apex only changes the apex function: declined.
        c.assistance = Assistance::new(1.0);
        let net = construct(&c).unwrap();
        assert!(construct_adjoint(&c, &net.mesh, &w).is_err());
    }

    #[test]
    fn apex_and_apices_outputs_are_differentiated() {
        let c = design(
            false,
            &[0.0; 18],
            vec![vec![0.45; 5]; 4],
            ColumnValues::List(vec![0.9, 0.95, 1.1, 0.8, 1.05]),
            true,
            None,
            EndPlanes::Perpendicular,
        );
        let net = construct(&c).unwrap();
        let zero = vec![DVec3::ZERO; net.mesh.vertices.len()];
        let apex_w = [0.3, -0.7, 0.2, 0.5, -0.1];
        let apices_w: Vec<DVec3> = (0..5)
            .map(|j| DVec3::new(0.1 * j as f64, -0.2, 0.05))
            .collect();
        let bars = OutputBars {
            mesh: &zero,
            apex: &apex_w,
            apices: &apices_w,
        };
        let adj = construct_adjoint_for(&c, &net.mesh, bars, Wrt::ALL).unwrap();
        let out = |c: &ConstructInputs| {
            let net = construct(c).unwrap();
            let a: f64 = net.apex.iter().zip(apex_w).map(|(a, w)| a * w).sum();
            let p: f64 = net
                .apices
                .iter()
                .zip(&apices_w)
                .filter_map(|(p, w)| p.map(|p| p.dot(*w)))
                .sum();
            a + p
        };
        let flat: Vec<f64> = adj
            .directrix
            .unwrap()
            .iter()
            .flat_map(|p| p.to_array())
            .collect();
        let h = 1e-6;
        let (mut worst, mut size) = (0.0f64, 0.0f64);
        for (k, x) in flat.iter().enumerate() {
            let mut p = c.clone();
            p.directrix.points[k / 3][k % 3] += h;
            let mut q = c.clone();
            q.directrix.points[k / 3][k % 3] -= h;
            let fd = (out(&p) - out(&q)) / (2.0 * h);
            worst = worst.max((fd - x).abs());
            size = size.max(fd.abs());
        }
        for (k, x) in adj.apex.unwrap().iter().enumerate() {
            let mut p = c.clone();
            let mut q = c.clone();
            if let (ColumnValues::List(u), ColumnValues::List(d)) =
                (&mut p.apex.values, &mut q.apex.values)
            {
                u[k] += h;
                d[k] -= h;
            }
            let fd = (out(&p) - out(&q)) / (2.0 * h);
            worst = worst.max((fd - x).abs());
            size = size.max(fd.abs());
        }
        assert!(worst / size < 1e-6, "relative difference {} ({worst} of {size})", worst / size);
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
