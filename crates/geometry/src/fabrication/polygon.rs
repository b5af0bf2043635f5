//! Small polygon helpers shared by the mesh tools: Newell normals, validation of polygon meshes and
//! ear-clipping triangulation (for exporters that need triangles).

use glam::{DVec2, DVec3};

use super::FabricationError;
use crate::PolygonMesh;
use crate::error::check_finite_points;

/// The Newell normal of a polygon (twice its vector area); zero for a degenerate polygon.
pub fn newell_vector(points: &[DVec3]) -> DVec3 {
    let mut n = DVec3::ZERO;
    for (k, p) in points.iter().enumerate() {
        let q = points[(k + 1) % points.len()];
        n += DVec3::new(
            (p.y - q.y) * (p.z + q.z),
            (p.z - q.z) * (p.x + q.x),
            (p.x - q.x) * (p.y + q.y),
        );
    }
    n
}

/// The unit Newell normal of a polygon; `None` when it has no area.
pub fn newell(points: &[DVec3]) -> Option<DVec3> {
    let n = newell_vector(points);
    let len = n.length();
    (len > 0.0 && len.is_finite()).then(|| n / len)
}

/// Checks a polygon mesh: valid faces, finite vertices, at least one face.
pub fn check_mesh(mesh: &PolygonMesh, what: &'static str) -> Result<(), FabricationError> {
    mesh.validate()?;
    if mesh.face_count() == 0 {
        return Err(FabricationError::Empty(what));
    }
    check_finite_points(what, &mesh.vertices)?;
    Ok(())
}

/// Length of the bounding-box diagonal of a point set (0 when empty).
pub fn size_of(points: &[DVec3]) -> f64 {
    crate::quad_grid::bounds_of(points).map_or(0.0, |(lo, hi)| lo.distance(hi))
}

/// Triangulates one polygon by ear clipping in the plane of its Newell normal. Triangles index into
/// `points` and keep the polygon's orientation. A polygon without area, or one ear clipping cannot
/// finish (self-intersecting), falls back to a fan from its first corner.
pub fn triangulate(points: &[DVec3]) -> Vec<[usize; 3]> {
    let n = points.len();
    if n < 3 {
        return Vec::new();
    }
    let fan = |idx: &[usize]| -> Vec<[usize; 3]> {
        (1..idx.len() - 1)
            .map(|k| [idx[0], idx[k], idx[k + 1]])
            .collect()
    };
    if n == 3 {
        return vec![[0, 1, 2]];
    }
    let Some(normal) = newell(points) else {
        return fan(&(0..n).collect::<Vec<_>>());
    };
    let helper = if normal.x.abs() < 0.9 {
        DVec3::X
    } else {
        DVec3::Y
    };
    let u = (helper - normal * helper.dot(normal)).normalize();
    let v = normal.cross(u);
    let p: Vec<DVec2> = points
        .iter()
        .map(|q| DVec2::new(q.dot(u), q.dot(v)))
        .collect();
    let scale = size_of(points).max(f64::MIN_POSITIVE);
    let eps = 1e-14 * scale * scale;
    let mut idx: Vec<usize> = (0..n).collect();
    let mut out = Vec::with_capacity(n - 2);
    while idx.len() > 3 {
        let m = idx.len();
        let ear = (0..m).find(|&k| {
            let (a, b, c) = (idx[(k + m - 1) % m], idx[k], idx[(k + 1) % m]);
            let (pa, pb, pc) = (p[a], p[b], p[c]);
            if (pb - pa).perp_dot(pc - pa) <= eps {
                return false;
            }
            !idx.iter().any(|&o| {
                o != a && o != b && o != c && {
                    let q = p[o];
                    (pb - pa).perp_dot(q - pa) >= -eps
                        && (pc - pb).perp_dot(q - pb) >= -eps
                        && (pa - pc).perp_dot(q - pc) >= -eps
                }
            })
        });
        match ear {
            Some(k) => {
                out.push([idx[(k + m - 1) % m], idx[k], idx[(k + 1) % m]]);
                idx.remove(k);
            }
            None => {
                out.extend(fan(&idx));
                return out;
            }
        }
    }
    out.push([idx[0], idx[1], idx[2]]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn non_convex_polygon_is_triangulated_inside() {
        // An arrow (non-convex at corner 3): a fan from corner 0 would leave the polygon.
        let pts = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(2.0, 2.0, 0.0),
            DVec3::new(1.0, 0.5, 0.0),
            DVec3::new(0.0, 2.0, 0.0),
        ];
        let tris = triangulate(&pts);
        assert_eq!(tris.len(), 3);
        let area: f64 = tris
            .iter()
            .map(|t| 0.5 * (pts[t[1]] - pts[t[0]]).cross(pts[t[2]] - pts[t[0]]).z)
            .sum();
        // Polygon area by the shoelace formula: 4 − 1.5 = 2.5, every triangle positive.
        assert!((area - 2.5).abs() < 1e-12, "{area}");
        for t in &tris {
            assert!((pts[t[1]] - pts[t[0]]).cross(pts[t[2]] - pts[t[0]]).z > 0.0);
        }
    }
}
