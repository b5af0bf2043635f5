//! The conical support layer (CNet Construct Conical Support, paper Sec. 4.4.2, notes §7): a second
//! cone-net that shares the cone apices of the first and has every vertex on its node axis.
//!
//! The construction is rerun with the same apex values a_j from the scaled first column
//! `G'_{i,0} = X_0 + λ (G_{i,0} − X_0)`. The construction planes Π_{i,j} are not an input: every
//! plane Π_{i,j} contains X_j and G_{i,j}, hence the node axis, and the step direction
//! `V' = a_j (G'_{i,j−1} − X_{j−1}) + X_j − G'_{i,j−1}` lies in the support plane through X_{j−1},
//! X_j and G_{i,j−1} (it points at the apex C_{j−1} on the line X_{j−1}X_j). The plane meets that
//! support plane exactly in the node axis, so the step `G'_{i,j} = Π_{i,j} ∩ (G'_{i,j−1} + t V')` is
//! the intersection of two coplanar lines: the line through G'_{i,j−1} along V' and the axis
//! X_j + s (G_{i,j} − X_j). It is solved by the stable closest-point solve and the vertex is written
//! as `X_j + s (G_{i,j} − X_j)`, exactly on its axis.

use glam::DVec3;

use super::FabricationError;
use super::axes::{axis_directions, check_grid, directrix_for};
use super::lines::closest_parameters;
use crate::{Polyline, QuadGrid};

/// Relative distance between the two lines above which the inputs are rejected as inconsistent.
pub const CONSISTENCY: f64 = 1e-6;

/// The conical support layer of a constructed cone-net.
///
/// `directrix` and `apex` (M−1 values a_1 … a_{M−1}, the construction's `apex` output) must be those
/// the mesh was built from; `factor` is λ (finite, ≠ 0; λ = 1 reproduces the mesh). The result has the
/// same size and wrap flags as `mesh`.
pub fn conical_support(
    directrix: &Polyline,
    mesh: &QuadGrid,
    apex: &[f64],
    factor: f64,
) -> Result<QuadGrid, FabricationError> {
    check_grid(mesh, 1, 2)?;
    let x = directrix_for(directrix, mesh)?;
    let m = mesh.cols;
    if apex.len() != m - 1 {
        return Err(FabricationError::WrongLength {
            what: "apex",
            expected: format!("{} (one per directrix edge, M − 1)", m - 1),
            got: apex.len(),
        });
    }
    if let Some(index) = apex.iter().position(|a| !a.is_finite()) {
        return Err(FabricationError::BadEntry {
            what: "apex",
            index,
            value: apex[index],
            expected: "a finite number",
        });
    }
    if !(factor.is_finite() && factor != 0.0) {
        return Err(FabricationError::BadParameter {
            what: "factor",
            value: factor,
            expected: "a finite number ≠ 0",
        });
    }
    let axes = axis_directions(&x, mesh)?;
    let scale = mesh.size().max(f64::MIN_POSITIVE);
    let mut out = Vec::with_capacity(mesh.vertices.len());
    for i in 0..mesh.rows {
        let mut g = x[0] + (mesh.at(i, 0) - x[0]) * factor;
        out.push(g);
        for j in 1..m {
            let a = apex[j - 1];
            let v = (g - x[j - 1]) * a + x[j] - g;
            let axis = axes[i * m + j];
            let (t, s) = closest_parameters(g, v, x[j], axis).ok_or(
                FabricationError::NoIntersection {
                    what: "conical support",
                    row: i,
                    column: j,
                    reason: "the line towards the cone apex is parallel to the node axis, or the previous vertex is the apex",
                },
            )?;
            let on_axis = x[j] + axis * s;
            let residual = (g + v * t).distance(on_axis) / scale;
            if !(residual <= CONSISTENCY) {
                return Err(FabricationError::Inconsistent {
                    what: "conical support",
                    row: i,
                    column: j,
                    residual,
                });
            }
            g = on_axis;
            out.push(g);
        }
    }
    if let Some(k) = out.iter().position(|p: &DVec3| !p.is_finite()) {
        return Err(FabricationError::NoIntersection {
            what: "conical support",
            row: k / m,
            column: k % m,
            reason: "the vertex overflows",
        });
    }
    Ok(QuadGrid {
        classes: Vec::new(),
        rows: mesh.rows,
        cols: m,
        wrap_rows: mesh.wrap_rows,
        wrap_cols: mesh.wrap_cols,
        vertices: out,
    })
}
