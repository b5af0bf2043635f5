//! The parallel (Combescure) transform of a PQ quad grid (PQ Mesh Parallel Transform, paper
//! Sec. 4.4.2, notes §7): a mesh with every edge parallel to the corresponding edge of G, fixed by
//! scale factors of the edges of the two boundary polylines G_{:,0} (μ) and G_{0,:} (ν).
//!
//! `H_{0,0} = G_{0,0}`, `H_{i+1,0} = H_{i,0} + μ_i (G_{i+1,0} − G_{i,0})`,
//! `H_{0,j+1} = H_{0,j} + ν_j (G_{0,j+1} − G_{0,j})`, and `H_{i+1,j+1}` is the intersection of the line
//! through `H_{i+1,j}` along `G_{i+1,j+1} − G_{i+1,j}` with the line through `H_{i,j+1}` along
//! `G_{i+1,j+1} − G_{i,j+1}`. The two lines are coplanar when the face of G is planar; they are met
//! by the stable closest-point solve and the midpoint of the two closest points is taken.
//!
//! A wrapped direction (closed generatrix or directrix) is swept as open: the factors are given for
//! the N−1 (M−1) open edges. A Combescure transform of a closed strip closes only for special
//! factors; the result keeps the wrap when the closing edges come out parallel to those of G (sine
//! of the angle ≤ 1e-9) and drops the closing quads otherwise ([`ParallelTransform::dropped_wrap`]).

use glam::DVec3;

use super::FabricationError;
use super::axes::check_grid;
use super::lines::intersect;
use crate::QuadGrid;

/// Sine of the angle below which two edges count as parallel when checking closure.
pub const CLOSURE_SINE: f64 = 1e-9;

/// The result of a parallel transform.
#[derive(Debug, Clone, PartialEq)]
pub struct ParallelTransform {
    /// The transformed mesh (same rows and columns as the input).
    pub mesh: QuadGrid,
    /// Directions whose wrap was dropped because the transform does not close: `(rows, cols)`.
    pub dropped_wrap: (bool, bool),
}

/// Expands the factors of `count` edges: a single value is broadcast; each must be finite and ≠ 0.
fn factors(what: &'static str, values: &[f64], count: usize) -> Result<Vec<f64>, FabricationError> {
    let out = match values.len() {
        1 => vec![values[0]; count],
        n if n == count => values.to_vec(),
        n => {
            return Err(FabricationError::WrongLength {
                what,
                expected: format!("{count} (one per boundary edge) or 1"),
                got: n,
            });
        }
    };
    match out.iter().position(|f| !(f.is_finite() && *f != 0.0)) {
        Some(index) => Err(FabricationError::BadEntry {
            what,
            index,
            value: out[index],
            expected: "a finite number ≠ 0",
        }),
        None => Ok(out),
    }
}

/// Sine of the angle between two vectors (0 when both vanish, 1 when only one does).
fn sine(a: DVec3, b: DVec3) -> f64 {
    let (la, lb) = (a.length(), b.length());
    match (la > 0.0, lb > 0.0) {
        (true, true) => a.cross(b).length() / (la * lb),
        (false, false) => 0.0,
        _ => 1.0,
    }
}

/// The Combescure transform of `mesh` with factors μ (N−1 values, or 1 broadcast) for the edges of
/// column 0 and ν (M−1 values, or 1) for the edges of row 0.
pub fn parallel_transform(
    mesh: &QuadGrid,
    mu: &[f64],
    nu: &[f64],
) -> Result<ParallelTransform, FabricationError> {
    check_grid(mesh, 2, 2)?;
    let (n, m) = (mesh.rows, mesh.cols);
    let mu = factors("mu", mu, n - 1)?;
    let nu = factors("nu", nu, m - 1)?;
    let scale = mesh.size().max(f64::MIN_POSITIVE);
    let edge = |a: (usize, usize), b: (usize, usize)| -> Result<DVec3, FabricationError> {
        let e = mesh.at(b.0, b.1) - mesh.at(a.0, a.1);
        if e.length() > 1e-14 * scale {
            Ok(e)
        } else {
            Err(FabricationError::ZeroEdge {
                what: "parallel transform",
                row: a.0,
                column: a.1,
                row2: b.0,
                column2: b.1,
            })
        }
    };
    let mut h = vec![DVec3::ZERO; n * m];
    h[0] = mesh.at(0, 0);
    for i in 0..n - 1 {
        h[(i + 1) * m] = h[i * m] + edge((i, 0), (i + 1, 0))? * mu[i];
    }
    for j in 0..m - 1 {
        h[j + 1] = h[j] + edge((0, j), (0, j + 1))? * nu[j];
    }
    for i in 0..n - 1 {
        for j in 0..m - 1 {
            let along_row = edge((i + 1, j), (i + 1, j + 1))?;
            let along_col = edge((i, j + 1), (i + 1, j + 1))?;
            let p = intersect(h[(i + 1) * m + j], along_row, h[i * m + j + 1], along_col).ok_or(
                FabricationError::NoIntersection {
                    what: "parallel transform",
                    row: i + 1,
                    column: j + 1,
                    reason: "the two edges of the face that meet there are parallel",
                },
            )?;
            h[(i + 1) * m + j + 1] = p;
        }
    }
    let mut out = QuadGrid {
        classes: Vec::new(),
        rows: n,
        cols: m,
        wrap_rows: mesh.wrap_rows,
        wrap_cols: mesh.wrap_cols,
        vertices: h,
    };
    let closes = |a: (usize, usize), b: (usize, usize)| {
        sine(
            out.at(b.0, b.1) - out.at(a.0, a.1),
            mesh.at(b.0, b.1) - mesh.at(a.0, a.1),
        ) <= CLOSURE_SINE
    };
    let rows_close = !mesh.wrap_rows || n < 3 || (0..m).all(|j| closes((n - 1, j), (0, j)));
    let cols_close = !mesh.wrap_cols || m < 3 || (0..n).all(|i| closes((i, m - 1), (i, 0)));
    out.wrap_rows &= rows_close;
    out.wrap_cols &= cols_close;
    Ok(ParallelTransform {
        mesh: out,
        dropped_wrap: (!rows_close, !cols_close),
    })
}
