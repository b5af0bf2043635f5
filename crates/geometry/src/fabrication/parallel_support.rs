//! The parallel support layer (PQ Mesh Construct Support, paper Sec. 4.4.2, notes §7): a second mesh
//! whose vertices lie on the torsion-free node axes X_j G_{i,j} and whose edges are parallel to the
//! edges of the mesh.
//!
//! `H_{0,0} = G_{0,0} + δ (G_{0,0} − X_0) / |G_{0,0} − X_0|` (δ = `distance`, positive away from the
//! directrix). Every further vertex is where its node axis `G_{i,j} + s (G_{i,j} − X_j)` meets the line
//! through an already placed neighbour along the corresponding edge of G: first down column 0
//! (`H_{i+1,0}` from `H_{i,0}` along `G_{i+1,0} − G_{i,0}`), then along every row (`H_{i,j+1}` from
//! `H_{i,j}` along `G_{i,j+1} − G_{i,j}`). Neighbouring axes are coplanar, so each step intersects two
//! coplanar lines (stable closest-point solve, the vertex written on its axis). Around a face the
//! placed vertices are the axes' intersections with the plane through the first one parallel to the
//! face, so the result does not depend on the order of the steps: every edge is parallel to its
//! counterpart and every face is planar. Along column j all axes pass through X_j, so a closed
//! generatrix closes up as well.

use glam::DVec3;

use super::FabricationError;
use super::axes::{axis_directions, check_grid, directrix_for};
use super::conical::CONSISTENCY;
use super::lines::closest_parameters;
use crate::{Polyline, QuadGrid};

/// The parallel support layer at offset `distance` (finite) from G_{0,0} along its node axis.
pub fn parallel_support(
    directrix: &Polyline,
    mesh: &QuadGrid,
    distance: f64,
) -> Result<QuadGrid, FabricationError> {
    check_grid(mesh, 1, 2)?;
    FabricationError::check_finite("distance", distance, "a finite number")?;
    let x = directrix_for(directrix, mesh)?;
    let axes = axis_directions(&x, mesh)?;
    let m = mesh.cols;
    let scale = mesh.size().max(f64::MIN_POSITIVE);
    let mut h = vec![DVec3::ZERO; mesh.vertices.len()];
    h[0] = mesh.at(0, 0) + axes[0].normalize() * distance;
    // One step: the vertex `to` from the placed vertex `from` along the mesh edge from → to.
    let place = |from: (usize, usize), to: (usize, usize), h: &mut Vec<DVec3>| {
        let edge = mesh.at(to.0, to.1) - mesh.at(from.0, from.1);
        if !(edge.length() > 1e-14 * scale) {
            return Err(FabricationError::ZeroEdge {
                what: "parallel support",
                row: from.0,
                column: from.1,
                row2: to.0,
                column2: to.1,
            });
        }
        let start = h[from.0 * m + from.1];
        let g = mesh.at(to.0, to.1);
        let axis = axes[to.0 * m + to.1];
        let (t, s) =
            closest_parameters(start, edge, g, axis).ok_or(FabricationError::NoIntersection {
                what: "parallel support",
                row: to.0,
                column: to.1,
                reason: "the mesh edge is parallel to the node axis",
            })?;
        let on_axis = g + axis * s;
        let residual = (start + edge * t).distance(on_axis) / scale;
        if !(residual <= CONSISTENCY) {
            return Err(FabricationError::Inconsistent {
                what: "parallel support",
                row: to.0,
                column: to.1,
                residual,
            });
        }
        if !on_axis.is_finite() {
            return Err(FabricationError::NoIntersection {
                what: "parallel support",
                row: to.0,
                column: to.1,
                reason: "the vertex overflows",
            });
        }
        h[to.0 * m + to.1] = on_axis;
        Ok(())
    };
    for i in 1..mesh.rows {
        place((i - 1, 0), (i, 0), &mut h)?;
    }
    for i in 0..mesh.rows {
        for j in 1..m {
            place((i, j - 1), (i, j), &mut h)?;
        }
    }
    Ok(QuadGrid {
        classes: Vec::new(),
        rows: mesh.rows,
        cols: m,
        wrap_rows: mesh.wrap_rows,
        wrap_cols: mesh.wrap_cols,
        vertices: h,
    })
}
