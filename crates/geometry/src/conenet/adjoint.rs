//! The adjoint (reverse-mode derivative) of CNets Construct (ratios): a backward sweep.
//!
//! The forward sweep is a recurrence along each row: `G_{i,j+1} = F(G_{i,j}, r_{i,j+1})` with the
//! plane Π_{i,j+1} from the ratio (its support frame depends on G_{i,j}) and the step of Eq. 1. For
//! cotangents `λ_{i,j} = ∂L/∂G_{i,j}` of an objective L, the backward sweep runs j = M−1 … 1:
//! `∂L/∂r_{i,j} = J_r(i,j)ᵀ λ_{i,j}` and `λ_{i,j−1} += J_g(i,j)ᵀ λ_{i,j}`; what reaches column 0 is
//! the generatrix's cotangent. The local Jacobians (3 × 4: g and r) come from one forward-mode
//! evaluation of the step on dual numbers ([`Dual`]) at the stored vertices, so the backward sweep
//! costs a small constant times the forward one, rows in parallel. This is the branch the forward
//! sweep took without assistance; a run in which the correction changed planes is declined by the
//! caller (the optimizer then differentiates the node by finite differences and says so). The ratio
//! → angle map has a kink at r = ½; exactly there the mean of its two slopes is used.

use std::f64::consts::PI;
use std::ops::{Add, Div, Mul, Neg, Sub};

use glam::DVec3;
use rayon::prelude::*;

use super::inputs::{ConstructInputs, GridValues};
use super::prepare::prepare;
use super::tolerance;
use crate::{GeometryError, QuadGrid};

/// Derivative directions: g.x, g.y, g.z, r.
const N: usize = 4;

/// A number with its derivatives along [`N`] directions (forward mode).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dual {
    /// The value.
    pub v: f64,
    /// ∂value/∂direction.
    pub d: [f64; N],
}

impl Dual {
    fn constant(v: f64) -> Self {
        Self { v, d: [0.0; N] }
    }
    fn variable(v: f64, k: usize) -> Self {
        let mut d = [0.0; N];
        d[k] = 1.0;
        Self { v, d }
    }
    fn map(self, v: f64, dv: f64) -> Self {
        Self {
            v,
            d: self.d.map(|x| x * dv),
        }
    }
    fn sqrt(self) -> Self {
        let s = self.v.sqrt();
        self.map(s, 0.5 / s)
    }
    fn sin(self) -> Self {
        self.map(self.v.sin(), self.v.cos())
    }
    fn cos(self) -> Self {
        self.map(self.v.cos(), -self.v.sin())
    }
    /// atan2(y, x).
    fn atan2(y: Self, x: Self) -> Self {
        let r2 = x.v * x.v + y.v * y.v;
        let mut d = [0.0; N];
        for (k, dk) in d.iter_mut().enumerate() {
            *dk = (x.v * y.d[k] - y.v * x.d[k]) / r2;
        }
        Self {
            v: y.v.atan2(x.v),
            d,
        }
    }
}

impl Add for Dual {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        let mut d = self.d;
        d.iter_mut().zip(o.d).for_each(|(a, b)| *a += b);
        Self { v: self.v + o.v, d }
    }
}

impl Sub for Dual {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        self + (-o)
    }
}

impl Neg for Dual {
    type Output = Self;
    fn neg(self) -> Self {
        Self {
            v: -self.v,
            d: self.d.map(|x| -x),
        }
    }
}

impl Mul for Dual {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        let mut d = [0.0; N];
        for (k, dk) in d.iter_mut().enumerate() {
            *dk = self.d[k] * o.v + self.v * o.d[k];
        }
        Self { v: self.v * o.v, d }
    }
}

impl Mul<f64> for Dual {
    type Output = Self;
    fn mul(self, o: f64) -> Self {
        self.map(self.v * o, o)
    }
}

impl Div for Dual {
    type Output = Self;
    fn div(self, o: Self) -> Self {
        let inv = 1.0 / o.v;
        let mut d = [0.0; N];
        for (k, dk) in d.iter_mut().enumerate() {
            *dk = (self.d[k] - self.v * inv * o.d[k]) * inv;
        }
        Self { v: self.v * inv, d }
    }
}

/// A point of dual numbers.
#[derive(Debug, Clone, Copy)]
struct D3([Dual; 3]);

impl D3 {
    fn constant(p: DVec3) -> Self {
        Self(p.to_array().map(Dual::constant))
    }
    fn dot(self, o: Self) -> Dual {
        self.0[0] * o.0[0] + self.0[1] * o.0[1] + self.0[2] * o.0[2]
    }
    fn zip(self, o: Self, f: impl Fn(Dual, Dual) -> Dual) -> Self {
        Self([
            f(self.0[0], o.0[0]),
            f(self.0[1], o.0[1]),
            f(self.0[2], o.0[2]),
        ])
    }
    fn scale(self, s: Dual) -> Self {
        Self(self.0.map(|x| x * s))
    }
    fn add(self, o: Self) -> Self {
        self.zip(o, |a, b| a + b)
    }
    fn sub(self, o: Self) -> Self {
        self.zip(o, |a, b| a - b)
    }
}

/// One step of the ratio construction on dual numbers: `G_{i,jn}` from `g = G_{i,jn−1}` and the
/// ratio `r` at column jn (same formulas as the lanes kernel, `ratios::ratio_planes`, and
/// `ctube::step`).
#[allow(clippy::too_many_arguments)]
fn ratio_step(
    g: D3,
    r: Dual,
    x0: DVec3,
    x1: DVec3,
    e: DVec3,
    b: DVec3,
    a: f64,
    inv_scale: f64,
) -> D3 {
    let (ed, bd) = (D3::constant(e), D3::constant(b));
    let d = g.sub(D3::constant(x0));
    let on_directrix =
        d.0.iter().fold(0.0f64, |m, x| m.max(x.v.abs())) * inv_scale <= tolerance::FRAME;
    let p = if on_directrix {
        bd
    } else {
        let perp = d.sub(ed.scale(d.dot(ed)));
        let inv_len = Dual::constant(1.0) / perp.dot(perp).sqrt();
        let w = perp.scale(inv_len);
        let wb = -w.dot(bd);
        let eb = Dual::constant(e.dot(b));
        let theta_b = Dual::atan2(eb, wb);
        // At r = ½ the map has a kink (slopes 2θ_b and 2(π − θ_b)): the mean slope π is used there,
        // the derivative central differences see (an element of the subdifferential).
        let theta = if r.v == 0.5 {
            theta_b + (r - Dual::constant(0.5)) * PI
        } else if r.v < 0.5 {
            r * theta_b * 2.0
        } else {
            theta_b + (r * 2.0 - Dual::constant(1.0)) * (Dual::constant(PI) - theta_b)
        };
        ed.scale(theta.sin()).sub(w.scale(theta.cos()))
    };
    let v = d.scale(Dual::constant(a)).add(D3::constant(x1)).sub(g);
    let t = D3::constant(x1).sub(g).dot(p) / v.dot(p);
    g.add(v.scale(t))
}

/// What the backward sweep returns.
#[derive(Debug, Clone, PartialEq)]
pub struct ConstructAdjoint {
    /// ∂L/∂ratios in the shape of the input: 1 number (uniform), M−1 (per column) or N·(M−1)
    /// (per vertex, row-major).
    pub ratios: Vec<f64>,
    /// ∂L/∂generatrix points (N).
    pub generatrix: Vec<DVec3>,
}

/// The backward sweep of [`super::construct`] for the mesh it built (`mesh`) and the cotangents of
/// its vertices (`mesh_bar`, row-major): the ratios' and the generatrix's cotangents. The apex
/// function and the directrix are held fixed.
pub fn construct_adjoint(
    inputs: &ConstructInputs,
    mesh: &QuadGrid,
    mesh_bar: &[DVec3],
) -> Result<ConstructAdjoint, GeometryError> {
    let prep = prepare(
        &inputs.directrix,
        &inputs.generatrix,
        &inputs.apex,
        inputs.end_planes,
    )?;
    let (n, m) = (prep.generatrix.len(), prep.dx.columns());
    if mesh.rows != n || mesh.cols != m || mesh_bar.len() != n * m {
        return Err(GeometryError::Degenerate(format!(
            "the adjoint needs the {n} × {m} mesh the construction built and one cotangent per vertex"
        )));
    }
    let grid = inputs
        .ratios
        .resolve("ratios", n, m - 1, (0.0, 1.0, "a value in [0, 1]"))?;
    let dx = &prep.dx;
    let inv_scale = 1.0 / prep.scale;
    let apex = &prep.apex;
    // Per row: (∂L/∂r_{i,1…M−1}, ∂L/∂G_{i,0}).
    let rows: Vec<(Vec<f64>, DVec3)> = (0..n)
        .into_par_iter()
        .map(|i| {
            let ratios = grid.row(i);
            let mut lambda = mesh_bar[i * m + m - 1];
            let mut r_bar = vec![0.0; m - 1];
            for jn in (1..m).rev() {
                let g = mesh.vertices[i * m + jn - 1];
                let gd = D3([
                    Dual::variable(g.x, 0),
                    Dual::variable(g.y, 1),
                    Dual::variable(g.z, 2),
                ]);
                let r = Dual::variable(ratios[jn - 1], 3);
                let out = ratio_step(
                    gd,
                    r,
                    dx.points[jn - 1],
                    dx.points[jn],
                    dx.edges[jn],
                    dx.bisectors[jn],
                    apex[jn - 1],
                    inv_scale,
                );
                // Jᵀ λ: column k of J is (out.x.d[k], out.y.d[k], out.z.d[k]).
                let jt = |k: usize| {
                    out.0[0].d[k] * lambda.x + out.0[1].d[k] * lambda.y + out.0[2].d[k] * lambda.z
                };
                r_bar[jn - 1] = jt(3);
                lambda = DVec3::new(jt(0), jt(1), jt(2)) + mesh_bar[i * m + jn - 1];
            }
            (r_bar, lambda)
        })
        .collect();
    let generatrix = rows.iter().map(|r| r.1).collect();
    let ratios = match &inputs.ratios {
        GridValues::Uniform(_) => vec![rows.iter().flat_map(|r| &r.0).sum()],
        GridValues::PerColumn(_) => (0..m - 1)
            .map(|j| rows.iter().map(|r| r.0[j]).sum())
            .collect(),
        GridValues::PerVertex(_) => rows.iter().flat_map(|r| r.0.iter().copied()).collect(),
    };
    if ratios.iter().any(|x: &f64| !x.is_finite()) {
        return Err(GeometryError::Degenerate(
            "the construction's derivative is not finite (a degenerate step)".into(),
        ));
    }
    Ok(ConstructAdjoint { ratios, generatrix })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Polyline;
    use crate::conenet::construct;
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

    /// L = Σ w_k · G_k with fixed weights: its gradient through the adjoint against central
    /// differences of the construction.
    fn check(ratios: Vec<Vec<f64>>, twist: f64) -> f64 {
        let c = inputs(ratios.clone(), twist);
        let net = construct(&c).unwrap();
        let weights: Vec<DVec3> = (0..net.mesh.vertices.len())
            .map(|k| DVec3::new((k as f64 * 0.7).sin(), (k as f64 * 1.3).cos(), 0.5))
            .collect();
        let loss = |r: &[Vec<f64>]| {
            let net = construct(&inputs(r.to_vec(), twist)).unwrap();
            net.mesh
                .vertices
                .iter()
                .zip(&weights)
                .map(|(g, w)| g.dot(*w))
                .sum::<f64>()
        };
        let adj = construct_adjoint(&c, &net.mesh, &weights).unwrap();
        let mut worst = 0.0f64;
        let mut scale = 0.0f64;
        let cols = ratios[0].len();
        for i in 0..ratios.len() {
            for j in 0..cols {
                let h = 1e-6;
                let mut p = ratios.clone();
                p[i][j] += h;
                let up = loss(&p);
                p[i][j] -= 2.0 * h;
                let down = loss(&p);
                let fd = (up - down) / (2.0 * h);
                let exact = adj.ratios[i * cols + j];
                worst = worst.max((fd - exact).abs());
                scale = scale.max(fd.abs());
            }
        }
        worst / scale.max(1e-300)
    }

    #[test]
    fn monge_ratios_gradient_matches_differences() {
        let rel = check(vec![vec![0.5; 5]; 4], 0.5);
        assert!(rel < 1e-6, "relative difference {rel}");
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
    }
}
