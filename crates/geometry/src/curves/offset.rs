//! Planar offset of a polyline with mitred corners.

use glam::{DVec2, DVec3};

use crate::error::check_finite_points;
use crate::{GeometryError, Plane, Polyline};

/// Corners sharper than this (the cosine of the turn between consecutive edges, −1 = a U-turn)
/// have no usable mitre: their mitre point would run off to infinity.
const MIN_MITRE_COSINE: f64 = -0.999_999;

/// The curve offset by `distance` in `plane`: each edge moves sideways, positive to the left of the
/// direction of travel as seen from the plane's normal, and consecutive offset edges meet at their
/// intersection (a mitred corner). The offset is taken in the curve's projection onto the plane;
/// every point keeps its height above the plane. Open ends move perpendicular to their edge.
/// Repeated consecutive points are merged first.
pub fn offset(curve: &Polyline, distance: f64, plane: &Plane) -> Result<Polyline, GeometryError> {
    crate::curves::check_finite("distance", distance)?;
    check_finite_points("curve", &curve.points)?;
    let to_2d = |p: DVec3| {
        let d = p - plane.origin;
        (
            DVec2::new(d.dot(plane.x_axis), d.dot(plane.y_axis)),
            d.dot(plane.normal),
        )
    };
    let mut flat: Vec<(DVec2, f64)> = Vec::with_capacity(curve.points.len());
    for &p in &curve.points {
        let q = to_2d(p);
        if flat.last().is_none_or(|last| last.0 != q.0) {
            flat.push(q);
        }
    }
    if curve.closed && flat.len() > 1 && flat[0].0 == flat[flat.len() - 1].0 {
        flat.pop();
    }
    let n = flat.len();
    if n < 2 {
        return Err(GeometryError::Degenerate(
            "the curve has fewer than two distinct points in the offset plane".into(),
        ));
    }
    let edge_count = if curve.closed { n } else { n - 1 };
    // Unit left normal of each edge: the direction turned +90° about the plane normal.
    let normals: Vec<DVec2> = (0..edge_count)
        .map(|k| {
            let d = (flat[(k + 1) % n].0 - flat[k].0).normalize();
            DVec2::new(-d.y, d.x)
        })
        .collect();
    let mut points = Vec::with_capacity(n);
    for (k, &(p, height)) in flat.iter().enumerate() {
        let before = if k > 0 {
            Some(normals[k - 1])
        } else if curve.closed {
            Some(normals[edge_count - 1])
        } else {
            None
        };
        let after = (k < edge_count).then(|| normals[k]);
        let shift = match (before, after) {
            (Some(a), Some(b)) => {
                let cosine = a.dot(b);
                if cosine < MIN_MITRE_COSINE {
                    return Err(GeometryError::Degenerate(format!(
                        "the curve turns back on itself at point {k}: the corner has no mitre"
                    )));
                }
                (a + b) / (1.0 + cosine)
            }
            (Some(a), None) | (None, Some(a)) => a,
            (None, None) => DVec2::ZERO,
        };
        let q = p + shift * distance;
        points.push(plane.origin + plane.x_axis * q.x + plane.y_axis * q.y + plane.normal * height);
    }
    crate::curves::check_output(
        "offset curve",
        Polyline {
            points,
            closed: curve.closed,
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn xy() -> Plane {
        Plane::from_normal(DVec3::ZERO, DVec3::Z).unwrap()
    }

    #[test]
    fn a_counter_clockwise_square_grows_inwards_to_the_left() {
        let square = Polyline::closed(vec![
            DVec3::ZERO,
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(2.0, 2.0, 0.0),
            DVec3::new(0.0, 2.0, 0.0),
        ]);
        let inner = offset(&square, 0.5, &xy()).unwrap();
        let expected = [[0.5, 0.5], [1.5, 0.5], [1.5, 1.5], [0.5, 1.5]];
        for (p, e) in inner.points.iter().zip(expected) {
            assert!((*p - DVec3::new(e[0], e[1], 0.0)).length() < 1e-15, "{p}");
        }
        let outer = offset(&square, -1.0, &xy()).unwrap();
        assert!((outer.points[0] - DVec3::new(-1.0, -1.0, 0.0)).length() < 1e-15);
        assert!(outer.closed);
    }

    #[test]
    fn open_ends_move_square_and_heights_are_kept() {
        let l = Polyline::open(vec![
            DVec3::new(0.0, 0.0, 3.0),
            DVec3::new(4.0, 0.0, 3.0),
            DVec3::new(4.0, 4.0, 1.0),
        ]);
        let o = offset(&l, 1.0, &xy()).unwrap();
        assert!((o.points[0] - DVec3::new(0.0, 1.0, 3.0)).length() < 1e-15);
        assert!(
            (o.points[1] - DVec3::new(3.0, 1.0, 3.0)).length() < 1e-15,
            "{}",
            o.points[1]
        );
        assert!((o.points[2] - DVec3::new(3.0, 4.0, 1.0)).length() < 1e-15);
        // Every offset edge is parallel to its original, at the distance.
        let back = Polyline::open(vec![DVec3::ZERO, DVec3::X, DVec3::ZERO]);
        assert!(offset(&back, 1.0, &xy()).is_err(), "a U-turn has no mitre");
        assert!(offset(&Polyline::open(vec![DVec3::X, DVec3::X]), 1.0, &xy()).is_err());
    }
}
