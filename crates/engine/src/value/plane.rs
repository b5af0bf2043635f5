//! One rule for a plane given by its fields, shared by every door (a graph file's literal, JSON
//! input, Python): a right-handed orthonormal frame given whole is kept bit for bit, so a plane
//! written out and read back is the same plane everywhere.

use cnets_geometry::{GeometryError, Plane};
use glam::DVec3;

/// How far a given frame may be from orthonormal and still be kept as it is.
const FRAME_TOLERANCE: f64 = 1e-9;

/// True when `x`, `y`, `normal` are unit, orthogonal and right-handed (to 1e-9).
pub fn is_orthonormal_frame(x: DVec3, y: DVec3, normal: DVec3) -> bool {
    [x, y, normal]
        .iter()
        .all(|v| (v.length() - 1.0).abs() < FRAME_TOLERANCE)
        && x.dot(y).abs() < FRAME_TOLERANCE
        && (x.cross(y) - normal).length() < FRAME_TOLERANCE
}

/// The plane through `origin` given by the fields present: `x_axis`, `y_axis` and `normal` that form
/// a right-handed orthonormal frame are kept exactly; otherwise the x axis and the normal (y = normal
/// × x), the normal alone, or the x axis and the y axis define it.
pub fn plane_from_fields(
    origin: DVec3,
    normal: Option<DVec3>,
    x_axis: Option<DVec3>,
    y_axis: Option<DVec3>,
) -> Result<Plane, GeometryError> {
    if let (Some(x), Some(y)) = (x_axis, y_axis) {
        let normal = normal.unwrap_or_else(|| x.cross(y));
        if is_orthonormal_frame(x, y, normal) {
            return Ok(Plane {
                origin,
                x_axis: x,
                y_axis: y,
                normal,
            });
        }
    }
    match (normal, x_axis, y_axis) {
        (Some(n), Some(x), _) => Plane::from_axes(origin, x, n.cross(x)),
        (Some(n), None, _) => Plane::from_normal(origin, n),
        (None, Some(x), Some(y)) => Plane::from_axes(origin, x, y),
        _ => Plane::from_normal(origin, DVec3::ZERO),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_given_orthonormal_frame_is_kept_bit_for_bit() {
        let p = Plane::from_normal(DVec3::new(1.0, 2.0, 0.25), DVec3::new(0.3, 0.7, 1.1)).unwrap();
        let q =
            plane_from_fields(p.origin, Some(p.normal), Some(p.x_axis), Some(p.y_axis)).unwrap();
        assert_eq!(
            (q.x_axis, q.y_axis, q.normal),
            (p.x_axis, p.y_axis, p.normal)
        );
        // Without the normal, x × y is the normal.
        let r = plane_from_fields(p.origin, None, Some(p.x_axis), Some(p.y_axis)).unwrap();
        assert_eq!((r.x_axis, r.y_axis), (p.x_axis, p.y_axis));
    }

    #[test]
    fn other_fields_define_the_plane_as_far_as_they_go() {
        let tilted = plane_from_fields(
            DVec3::ZERO,
            Some(DVec3::Z),
            Some(DVec3::new(1.0, 0.0, 1.0)),
            None,
        )
        .unwrap();
        // The x axis is kept; the y axis is the normal × x.
        assert!((tilted.x_axis - DVec3::new(1.0, 0.0, 1.0).normalize()).length() < 1e-12);
        assert!((tilted.y_axis - DVec3::Y).length() < 1e-12);
        let skew = plane_from_fields(
            DVec3::ZERO,
            None,
            Some(DVec3::X),
            Some(DVec3::new(1.0, 1.0, 0.0)),
        )
        .unwrap();
        assert!((skew.y_axis - DVec3::Y).length() < 1e-12);
        assert!(plane_from_fields(DVec3::ZERO, None, None, None).is_err());
        assert!(plane_from_fields(DVec3::ZERO, Some(DVec3::ZERO), None, None).is_err());
    }
}
