//! Torsion-free node axes of a constructed cone-net (paper Sec. 4.4.2, notes §7): the line through
//! the directrix point X_j and the mesh vertex G_{i,j}, for every vertex. Axes of neighbouring
//! vertices are coplanar: along a column they all pass through X_j; along a row both lie in the
//! support plane through X_j, X_{j+1} and the cone apex C_j.

use glam::DVec3;

use super::FabricationError;
use crate::error::check_finite_points;
use crate::{Line, Polyline, QuadGrid};

/// The directrix points X_0 … X_{M−1} matching the columns of `mesh`: the swept points (a closed
/// directrix repeats its first point), or the stored points when those already match (a swept
/// directrix given as an open polyline). Fails when neither count equals the mesh's columns.
pub fn directrix_for(
    directrix: &Polyline,
    mesh: &QuadGrid,
) -> Result<Vec<DVec3>, FabricationError> {
    let swept = directrix.swept_points();
    let points = if swept.len() == mesh.cols {
        swept
    } else if directrix.points.len() == mesh.cols {
        directrix.points.clone()
    } else {
        return Err(FabricationError::DirectrixMismatch {
            points: directrix.points.len(),
            swept: swept.len(),
            columns: mesh.cols,
        });
    };
    check_finite_points("directrix", &points)?;
    Ok(points)
}

/// Checks a construction mesh: vertex count, finite vertices, at least `rows × cols` vertices.
pub fn check_grid(
    mesh: &QuadGrid,
    min_rows: usize,
    min_cols: usize,
) -> Result<(), FabricationError> {
    mesh.validate()?;
    if mesh.vertices.is_empty() {
        return Err(FabricationError::Empty("mesh"));
    }
    if mesh.rows < min_rows {
        return Err(FabricationError::TooSmall {
            what: "mesh",
            needed: min_rows,
            unit: "rows",
            got: mesh.rows,
        });
    }
    if mesh.cols < min_cols {
        return Err(FabricationError::TooSmall {
            what: "mesh",
            needed: min_cols,
            unit: "columns",
            got: mesh.cols,
        });
    }
    check_finite_points("mesh", &mesh.vertices)?;
    Ok(())
}

/// The node axes as segments from X_j to G_{i,j}, row-major (`i * M + j`), and an error naming the
/// first vertex that coincides with its directrix point (its axis has no direction).
pub fn torsion_free_axes(
    directrix: &Polyline,
    mesh: &QuadGrid,
) -> Result<Vec<Line>, FabricationError> {
    check_grid(mesh, 1, 2)?;
    let x = directrix_for(directrix, mesh)?;
    let axes = axis_directions(&x, mesh)?;
    Ok(axes
        .iter()
        .enumerate()
        .map(|(k, d)| {
            let j = k % mesh.cols;
            Line::new(x[j], x[j] + *d)
        })
        .collect())
}

/// `G_{i,j} − X_j` for every vertex, row-major; an error names the first zero (or near-zero, relative
/// to the mesh size) direction.
pub(crate) fn axis_directions(
    x: &[DVec3],
    mesh: &QuadGrid,
) -> Result<Vec<DVec3>, FabricationError> {
    let scale = mesh.size().max(f64::MIN_POSITIVE);
    let mut out = Vec::with_capacity(mesh.vertices.len());
    for i in 0..mesh.rows {
        for (j, xj) in x.iter().enumerate() {
            let d = mesh.at(i, j) - *xj;
            if !(d.length() > 1e-14 * scale) {
                return Err(FabricationError::DegenerateAxis { row: i, column: j });
            }
            out.push(d);
        }
    }
    Ok(out)
}
