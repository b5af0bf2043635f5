//! Per-face attributes for analysis overlays and export colours: planarity and configuration class,
//! and the colour maps that turn them into RGB (components in [0, 1], linear).

use glam::DVec3;

use super::FabricationError;
use super::polygon::{check_mesh, newell};
use crate::conenet::quad_planarity;
pub use crate::face_class::FaceClass;
use crate::{PolygonMesh, QuadGrid};

/// Planarity of one polygon: triangles 0; quads the libigl measure (distance between the diagonal
/// lines over the mean diagonal length, as `conenet::quad_planarity`); polygons with more corners the
/// largest distance of a corner from the plane through their centroid with the Newell normal, over the
/// mean edge length. A polygon without area counts as planar (0).
pub fn polygon_planarity(points: &[DVec3]) -> f64 {
    match points.len() {
        0..=3 => 0.0,
        4 => quad_planarity([points[0], points[1], points[2], points[3]]),
        n => {
            let Some(normal) = newell(points) else {
                return 0.0;
            };
            let c = points.iter().copied().sum::<DVec3>() / n as f64;
            let off = points
                .iter()
                .map(|p| (*p - c).dot(normal).abs())
                .fold(0.0, f64::max);
            let mean_edge = (0..n)
                .map(|k| points[k].distance(points[(k + 1) % n]))
                .sum::<f64>()
                / n as f64;
            if mean_edge > 0.0 {
                off / mean_edge
            } else {
                0.0
            }
        }
    }
}

/// Planarity of every face of a polygon mesh, in face order.
pub fn face_planarity(mesh: &PolygonMesh) -> Result<Vec<f64>, FabricationError> {
    check_mesh(mesh, "mesh")?;
    let mut corners = Vec::new();
    Ok(mesh
        .faces()
        .map(|f| {
            corners.clear();
            corners.extend(f.iter().map(|&v| mesh.vertices[v as usize]));
            polygon_planarity(&corners)
        })
        .collect())
}

/// Parses a configuration label: `++`, `--`, `+-`, `-+` (the minus may also be `−`). Returns
/// (s1 > 0, s2 > 0).
fn parse_label(label: &str) -> Option<(bool, bool)> {
    let signs: Vec<char> = label.trim().chars().collect();
    let sign = |c: char| match c {
        '+' => Some(true),
        '-' | '−' => Some(false),
        _ => None,
    };
    match signs.as_slice() {
        [a, b] => Some((sign(*a)?, sign(*b)?)),
        _ => None,
    }
}

/// The class of every face of `mesh` (row-major over quad rows × quad columns) from the construction's
/// configurations: N rows of M−1 labels, row i entry j being c_{i,j} (j = 0 … M−2, one per face
/// column). Tables of M−2 labels (c_{i,1} … c_{i,M−2}, without the first column) are read too; their
/// faces of column 0 are [`FaceClass::Unclassified`].
pub fn face_classes(
    mesh: &QuadGrid,
    labels: &[Vec<String>],
) -> Result<Vec<FaceClass>, FabricationError> {
    mesh.validate()?;
    let full = mesh.cols.saturating_sub(1);
    let cols = match labels.first() {
        Some(row) if row.len() + 1 == full => full - 1,
        _ => full,
    };
    // Face column j reads label j − shift.
    let shift = full - cols;
    if labels.len() != mesh.rows {
        return Err(FabricationError::WrongLength {
            what: "configurations",
            expected: format!("{} rows (one per mesh row, N)", mesh.rows),
            got: labels.len(),
        });
    }
    let mut parsed = Vec::with_capacity(mesh.rows * cols);
    for (i, row) in labels.iter().enumerate() {
        if row.len() != cols {
            return Err(FabricationError::WrongLength {
                what: "configurations row",
                expected: format!("{cols} labels in row {i} (M − 1, as row 0)"),
                got: row.len(),
            });
        }
        for (k, l) in row.iter().enumerate() {
            parsed.push(parse_label(l).ok_or_else(|| FabricationError::BadLabel {
                row: i,
                column: k + shift,
                label: l.clone(),
            })?);
        }
    }
    let mut out = Vec::with_capacity(mesh.quad_count());
    for i in 0..mesh.quad_rows() {
        let i1 = (i + 1) % mesh.rows;
        for j in 0..mesh.quad_cols() {
            if j < shift {
                out.push(FaceClass::Unclassified);
                continue;
            }
            let k = j - shift;
            let (a, b) = (parsed[i * cols + k], parsed[i1 * cols + k]);
            out.push(FaceClass::of_signs(a, b));
        }
    }
    Ok(out)
}

/// The planarity colour map: `t = clamp(value / limit, 0, 1)` from green (t = 0) through yellow
/// (t = ½) to red (t = 1); non-finite values are magenta. `limit` > 0.
pub fn planarity_colour(value: f64, limit: f64) -> DVec3 {
    if !value.is_finite() {
        return DVec3::new(1.0, 0.0, 1.0);
    }
    let t = (value / limit).clamp(0.0, 1.0);
    let green = DVec3::new(0.15, 0.60, 0.25);
    let yellow = DVec3::new(0.95, 0.80, 0.10);
    let red = DVec3::new(0.85, 0.10, 0.10);
    if t <= 0.5 {
        green.lerp(yellow, 2.0 * t)
    } else {
        yellow.lerp(red, 2.0 * t - 1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classes_follow_the_two_configurations() {
        let mesh = QuadGrid::new(3, 4, vec![DVec3::ZERO; 12]).unwrap();
        let l = |s: &[&str]| s.iter().map(|x| x.to_string()).collect::<Vec<_>>();
        let labels = vec![l(&["++", "--"]), l(&["++", "--"]), l(&["--", "+-"])];
        let c = face_classes(&mesh, &labels).unwrap();
        use FaceClass::*;
        assert_eq!(
            c,
            vec![
                Unclassified,
                Convex,
                MinusMinus,
                Unclassified,
                NonConvex,
                NegativeApex
            ]
        );
        assert!(matches!(
            face_classes(
                &mesh,
                &[l(&["++", "x+"]), l(&["++", "++"]), l(&["++", "++"])]
            ),
            Err(FabricationError::BadLabel {
                row: 0,
                column: 2,
                ..
            })
        ));
        // The full table (M − 1 labels) classifies column 0 too.
        let full = vec![
            l(&["--", "++", "--"]),
            l(&["++", "++", "--"]),
            l(&["++", "--", "+-"]),
        ];
        assert_eq!(
            face_classes(&mesh, &full).unwrap(),
            vec![
                NonConvex,
                Convex,
                MinusMinus,
                Convex,
                NonConvex,
                NegativeApex
            ]
        );
        assert!(matches!(
            face_classes(&mesh, &[l(&["++"; 3]), l(&["++"; 2]), l(&["++"; 3])]),
            Err(FabricationError::WrongLength { .. })
        ));
    }

    #[test]
    fn colour_map_ends() {
        assert_eq!(planarity_colour(0.0, 1.0), DVec3::new(0.15, 0.60, 0.25));
        assert_eq!(planarity_colour(5.0, 1.0), DVec3::new(0.85, 0.10, 0.10));
    }
}
