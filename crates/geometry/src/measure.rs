//! Distances used by optimization objectives: point sets, closure gaps, point-to-surface distances.

use glam::DVec3;

use crate::{GeometryError, PolygonMesh, QuadGrid};

/// Sum of squared distances between corresponding points, and the largest distance.
pub fn point_distance(a: &[DVec3], b: &[DVec3]) -> Result<(f64, f64), GeometryError> {
    if a.len() != b.len() {
        return Err(GeometryError::WrongLength {
            what: "second point list",
            expected: a.len().to_string(),
            got: b.len(),
        });
    }
    crate::error::check_finite_points("first point list", a)?;
    crate::error::check_finite_points("second point list", b)?;
    Ok(a.iter().zip(b).fold((0.0, 0.0), |(sum, max), (p, q)| {
        let d2 = p.distance_squared(*q);
        (sum + d2, f64::max(max, d2.sqrt()))
    }))
}

/// The gap between the first and the last column of a quad grid (a tube's first and last
/// generatrix-aligned polylines): sum of squared distances of corresponding vertices, and the largest.
pub fn closure_gap(mesh: &QuadGrid) -> Result<(f64, f64), GeometryError> {
    mesh.validate()?;
    if mesh.cols < 2 || mesh.rows == 0 {
        return Err(GeometryError::Degenerate(format!(
            "a closure gap needs at least 2 columns and 1 row, the mesh is {} × {}",
            mesh.rows, mesh.cols
        )));
    }
    let first: Vec<DVec3> = (0..mesh.rows).map(|i| mesh.at(i, 0)).collect();
    let last: Vec<DVec3> = (0..mesh.rows).map(|i| mesh.at(i, mesh.cols - 1)).collect();
    point_distance(&first, &last)
}

/// The point of triangle (a, b, c) closest to p (Ericson, Real-Time Collision Detection 5.1.5).
pub fn closest_point_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = va + vb + vc;
    if denom.abs() <= f64::MIN_POSITIVE {
        // A degenerate (zero-area) triangle: the closest of its edges' points.
        return [(a, b), (b, c), (c, a)]
            .into_iter()
            .map(|(s, e)| closest_on_segment(p, s, e))
            .min_by(|x, y| x.distance_squared(p).total_cmp(&y.distance_squared(p)))
            .unwrap_or(a);
    }
    a + ab * (vb / denom) + ac * (vc / denom)
}

fn closest_on_segment(p: DVec3, s: DVec3, e: DVec3) -> DVec3 {
    let d = e - s;
    let len2 = d.length_squared();
    if len2 <= f64::MIN_POSITIVE {
        return s;
    }
    s + d * ((p - s).dot(d) / len2).clamp(0.0, 1.0)
}

/// Distances from `points` to the surface of `reference` (polygons fanned into triangles): mean of
/// the squared distances and the largest distance. The closest points come from a BVH
/// ([`crate::mesh_query::MeshQuery`]); the sum runs in point order, so the result does not depend on
/// the thread count.
pub fn surface_distance(
    points: &[DVec3],
    reference: &PolygonMesh,
) -> Result<(f64, f64), GeometryError> {
    let query = crate::mesh_query::MeshQuery::new(reference)
        .map_err(|e| GeometryError::Degenerate(format!("the reference mesh: {e}")))?;
    crate::error::check_finite_points("points", points)?;
    if points.is_empty() {
        return Ok((0.0, 0.0));
    }
    let hits = query.closest_all(points)?;
    let mut sum = 0.0;
    let mut max = 0.0f64;
    for hit in &hits {
        sum += hit.distance * hit.distance;
        max = max.max(hit.distance);
    }
    Ok((sum / points.len() as f64, max))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closest_points_in_each_region() {
        let (a, b, c) = (DVec3::ZERO, DVec3::X, DVec3::Y);
        let inside = closest_point_on_triangle(DVec3::new(0.2, 0.2, 5.0), a, b, c);
        assert!(
            (inside - DVec3::new(0.2, 0.2, 0.0)).length() < 1e-15,
            "{inside}"
        );
        assert_eq!(
            closest_point_on_triangle(DVec3::new(-1.0, -1.0, 0.0), a, b, c),
            a
        );
        assert_eq!(
            closest_point_on_triangle(DVec3::new(3.0, -1.0, 0.0), a, b, c),
            b
        );
        assert_eq!(
            closest_point_on_triangle(DVec3::new(0.5, -2.0, 1.0), a, b, c),
            DVec3::new(0.5, 0.0, 0.0)
        );
        let on_hyp = closest_point_on_triangle(DVec3::new(1.0, 1.0, 0.0), a, b, c);
        assert!((on_hyp - DVec3::new(0.5, 0.5, 0.0)).length() < 1e-15);
        let degenerate =
            closest_point_on_triangle(DVec3::new(0.5, 1.0, 0.0), a, b, DVec3::new(2.0, 0.0, 0.0));
        assert!((degenerate - DVec3::new(0.5, 0.0, 0.0)).length() < 1e-15);
    }

    #[test]
    fn distances() {
        let (sum, max) =
            point_distance(&[DVec3::ZERO, DVec3::X], &[DVec3::Y, DVec3::X * 3.0]).unwrap();
        assert_eq!((sum, max), (5.0, 2.0));
        assert!(point_distance(&[DVec3::ZERO], &[]).is_err());
        let square = PolygonMesh::from_faces(
            vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
            &[vec![0, 1, 2, 3]],
        )
        .unwrap();
        let (mean, max) = surface_distance(
            &[DVec3::new(0.5, 0.5, 2.0), DVec3::new(0.5, 0.5, 0.0)],
            &square,
        )
        .unwrap();
        assert_eq!((mean, max), (2.0, 2.0));
    }
}
