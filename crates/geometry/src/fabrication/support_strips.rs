//! Support strips and beams of a cone-net (paper Sec. 4.4.2, Fig. 3).
//!
//! - **Support strips** (with the directrix): for every directrix-aligned polyline G_{i,:} the strip of
//!   planar quads X_j X_{j+1} G_{i,j+1} G_{i,j} — a 2 × M grid whose first row is the directrix and
//!   whose second is the mesh row. Each quad lies in the support plane through X_j, X_{j+1} and the
//!   cone apex C_j (both of its long edges pass through C_j).
//! - **Beams** (with a second layer, `conical_support` or `parallel_support`): the quads
//!   G G' G' G between the mesh and the layer along the torsion-free node axes, one strip per
//!   polyline of the chosen direction — a 2 × M grid (directrix) or a 2 × N grid (generatrix,
//!   wrapping where the generatrix is closed). Neighbouring node axes are coplanar, so every beam quad
//!   is planar.

use glam::DVec3;

use super::FabricationError;
use super::axes::{check_grid, directrix_for};
use super::strips::StripDirection;
use crate::{Polyline, QuadGrid};

/// The support strips of `mesh` against its `directrix` (one point per mesh column, as swept):
/// strip i has rows X_0 … X_{M−1} and G_{i,0} … G_{i,M−1}.
pub fn directrix_support_strips(
    directrix: &Polyline,
    mesh: &QuadGrid,
) -> Result<Vec<QuadGrid>, FabricationError> {
    check_grid(mesh, 1, 2)?;
    let x = directrix_for(directrix, mesh)?;
    let m = mesh.cols;
    Ok((0..mesh.rows)
        .map(|i| {
            let mut vertices = Vec::with_capacity(2 * m);
            vertices.extend_from_slice(&x);
            vertices.extend_from_slice(&mesh.vertices[i * m..(i + 1) * m]);
            QuadGrid {
                classes: Vec::new(),
                rows: 2,
                cols: m,
                wrap_rows: false,
                wrap_cols: mesh.wrap_cols,
                vertices,
            }
        })
        .collect())
}

/// The beams between `mesh` and its second `layer` (same size) along the node axes: one strip per
/// polyline of `direction`, first row on the mesh, second on the layer.
pub fn beam_strips(
    mesh: &QuadGrid,
    layer: &QuadGrid,
    direction: StripDirection,
) -> Result<Vec<QuadGrid>, FabricationError> {
    check_grid(mesh, 1, 1)?;
    check_grid(layer, 1, 1)?;
    if (layer.rows, layer.cols) != (mesh.rows, mesh.cols) {
        return Err(FabricationError::WrongLength {
            what: "layer",
            expected: format!(
                "{} vertices ({} × {}, the mesh's size)",
                mesh.vertices.len(),
                mesh.rows,
                mesh.cols
            ),
            got: layer.vertices.len(),
        });
    }
    let strip = |points: &dyn Fn(&QuadGrid) -> Vec<DVec3>, wrap: bool| {
        let mut vertices = points(mesh);
        vertices.extend(points(layer));
        QuadGrid {
            classes: Vec::new(),
            rows: 2,
            cols: vertices.len() / 2,
            wrap_rows: false,
            wrap_cols: wrap,
            vertices,
        }
    };
    let (n, m) = (mesh.rows, mesh.cols);
    let strips: Vec<QuadGrid> = match direction {
        StripDirection::Directrix => (0..n)
            .map(|i| {
                strip(
                    &|g: &QuadGrid| g.vertices[i * m..(i + 1) * m].to_vec(),
                    mesh.wrap_cols,
                )
            })
            .collect(),
        StripDirection::Generatrix => (0..m)
            .map(|j| {
                strip(
                    &|g: &QuadGrid| (0..n).map(|i| g.vertices[i * m + j]).collect(),
                    mesh.wrap_rows,
                )
            })
            .collect(),
    };
    if strips.iter().any(|s| s.cols < 2) {
        return Err(FabricationError::TooSmall {
            what: "mesh",
            needed: 2,
            unit: "vertices along the beams",
            got: strips.first().map_or(0, |s| s.cols),
        });
    }
    Ok(strips)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shapes_and_rows() {
        let mesh = QuadGrid::new(
            2,
            3,
            (0..6).map(|k| DVec3::new(k as f64, 1.0, 0.0)).collect(),
        )
        .unwrap();
        let layer = QuadGrid::new(
            2,
            3,
            (0..6).map(|k| DVec3::new(k as f64, 2.0, 0.0)).collect(),
        )
        .unwrap();
        let d = beam_strips(&mesh, &layer, StripDirection::Directrix).unwrap();
        assert_eq!(d.len(), 2);
        assert_eq!(d[1].vertices[0], mesh.at(1, 0));
        assert_eq!(d[1].vertices[3], layer.at(1, 0));
        let g = beam_strips(&mesh, &layer, StripDirection::Generatrix).unwrap();
        assert_eq!(g.len(), 3);
        assert_eq!((g[2].rows, g[2].cols), (2, 2));
        assert_eq!(g[2].vertices[1], mesh.at(1, 2));
        let small = QuadGrid::new(1, 3, mesh.vertices[..3].to_vec()).unwrap();
        assert!(beam_strips(&mesh, &small, StripDirection::Directrix).is_err());
        let one_row = QuadGrid::new(1, 3, mesh.vertices[..3].to_vec()).unwrap();
        assert!(beam_strips(&one_row, &one_row, StripDirection::Generatrix).is_err());
        let x = Polyline::open(vec![DVec3::ZERO, DVec3::X, DVec3::X * 2.0]);
        let s = directrix_support_strips(&x, &mesh).unwrap();
        assert_eq!(s.len(), 2);
        assert_eq!(s[0].vertices[..3], x.points[..]);
        let short = Polyline::open(vec![DVec3::ZERO, DVec3::X]);
        assert!(directrix_support_strips(&short, &mesh).is_err());
    }
}
