//! The cotangents of the construction's other outputs in the adjoint ([`super::adjoint`]): the
//! apex values used and the apices (onto a_j and X_j), the plane normals (onto the steps that
//! made them) and the convexity margins ([`super::margins`]: onto the mesh, the planes, the
//! directrix and, in the first column, the stand-in plane [`generatrix_normal`]).

use glam::DVec3;

use super::adjoint::{Backward, OutputBars};
use super::apex::apex_point;
use super::configuration::generatrix_normal;
use super::directrix_adjoint::ColumnBars;
use super::dual::{D3, Dual};
use super::margins::PER_FACE;
use crate::GeometryError;

/// The cotangents the backward sweep starts from.
pub(super) struct Seeded {
    /// ∂L/∂G (N·M): the mesh output's plus the margins'.
    pub mesh: Vec<DVec3>,
    /// ∂L/∂P_{i,j} (N·(M−1)), or empty.
    pub planes: Vec<DVec3>,
    /// The column quantities' (from the apex, apices and margins outputs).
    pub columns: ColumnBars,
}

/// The starting cotangents of `sweep` (its `mesh_bar` is the mesh output's) from the outputs'.
pub(super) fn seed(sweep: &Backward<'_>, bars: &OutputBars<'_>) -> Result<Seeded, GeometryError> {
    let (dx, mesh) = (&sweep.prep.dx, sweep.mesh);
    let (n, m) = (mesh.rows, mesh.cols);
    let cols = m - 1;
    let size = |len: usize, want: usize, what: &str| {
        if len != 0 && len != want {
            Err(GeometryError::Degenerate(format!(
                "the adjoint needs {want} {what} cotangents, got {len}"
            )))
        } else {
            Ok(())
        }
    };
    size(bars.planes.len(), n * cols, "plane")?;
    size(
        bars.margins.len(),
        mesh.quad_rows() * cols * PER_FACE,
        "margin",
    )?;
    let mut columns = ColumnBars::zeros(m);
    columns
        .a
        .iter_mut()
        .zip(bars.apex)
        .for_each(|(s, x)| *s += x);
    for (j, c_bar) in (1..m).zip(bars.apices) {
        let a = sweep.piece.apex[j - 1];
        // C = X_j + (X_j − X_{j−1}) a / (1 − a) (`apex::apex_point`); none at infinity.
        if apex_point(dx.points[j - 1], dx.points[j], a).is_none() {
            continue;
        }
        let t = 1.0 - a;
        columns.x[j] += *c_bar / t;
        columns.x[j - 1] -= *c_bar * (a / t);
        columns.a[j - 1] += c_bar.dot(dx.points[j] - dx.points[j - 1]) / (t * t);
    }
    let mut mesh_bar = sweep.mesh_bar.to_vec();
    let mut planes = bars.planes.to_vec();
    if !bars.margins.is_empty() {
        if planes.is_empty() {
            planes = vec![DVec3::ZERO; n * cols];
        }
        // Face (i, j): s1, s2 of c_{i,j}, then of c_{i+1,j} (wrapping).
        let mut config = vec![0.0; n * cols * 2];
        for (f, b) in bars.margins.chunks_exact(PER_FACE).enumerate() {
            let (i, j) = (f / cols, f % cols);
            let next = (i + 1) % n;
            config[2 * (i * cols + j)] += b[0];
            config[2 * (i * cols + j) + 1] += b[1];
            config[2 * (next * cols + j)] += b[2];
            config[2 * (next * cols + j) + 1] += b[3];
        }
        let x = &dx.points;
        let g = |i: usize, j: usize| mesh.vertices[i * m + j];
        for i in 0..n {
            for j in 0..cols {
                let (b1, b2) = (config[2 * (i * cols + j)], config[2 * (i * cols + j) + 1]);
                if b1 == 0.0 && b2 == 0.0 {
                    continue;
                }
                let edge = x[j + 1] - x[j];
                let l = edge.length();
                let p_before = if j == 0 {
                    generatrix_normal(x[0], dx.edges[1], g(i, 0))
                } else {
                    sweep.plane(i, j)
                };
                let p_next = sweep.plane(i, j + 1);
                let (d1, d2) = (g(i, j + 1) - x[j], x[j + 1] - g(i, j));
                let (s1, s2) = (d1.dot(p_before), d2.dot(p_next));
                // m = s / l: l's cotangent −(b1 s1 + b2 s2) / l², along the edge.
                let l_bar = -(b1 * s1 + b2 * s2) / (l * l);
                columns.x[j + 1] += edge / l * l_bar;
                columns.x[j] -= edge / l * l_bar;
                let (s1_bar, s2_bar) = (b1 / l, b2 / l);
                mesh_bar[i * m + j + 1] += p_before * s1_bar;
                columns.x[j] -= p_before * s1_bar;
                let p_before_bar = d1 * s1_bar;
                if j == 0 {
                    let (x0, e, g0) = stand_in_pullback(x[0], dx.edges[1], g(i, 0), p_before_bar);
                    columns.x[0] += x0;
                    columns.e[1] += e;
                    mesh_bar[i * m] += g0;
                } else {
                    planes[i * cols + j - 1] += p_before_bar;
                }
                columns.x[j + 1] += p_next * s2_bar;
                mesh_bar[i * m + j] -= p_next * s2_bar;
                planes[i * cols + j] += d2 * s2_bar;
            }
        }
    }
    Ok(Seeded {
        mesh: mesh_bar,
        planes,
        columns,
    })
}

/// The pull-back of [`generatrix_normal`]`(x0, e, g)` for the cotangent `bar` of its value: the
/// cotangents of x0, e and g (its fallbacks, ê when the plane is undefined, follow e alone).
fn stand_in_pullback(x0: DVec3, e: DVec3, g: DVec3, bar: DVec3) -> (DVec3, DVec3, DVec3) {
    let d = g - x0;
    let dd = d.length_squared();
    let regular = dd > 0.0 && dd.is_finite() && (e - d * (e.dot(d) / dd)).length_squared() > 1e-24;
    if !regular {
        return (DVec3::ZERO, bar, DVec3::ZERO);
    }
    let (xd, ed, gd) = (
        D3::<9>::seed(x0, 0),
        D3::<9>::seed(e, 3),
        D3::<9>::seed(g, 6),
    );
    let d = gd.sub(xd);
    let n = ed.sub(d.scale(ed.dot(d) / d.dot(d)));
    let n = n.scale(Dual::constant(1.0) / n.dot(n).sqrt());
    let pull = |k: usize| n.pull3(bar, k);
    (pull(0), pull(3), pull(6))
}
