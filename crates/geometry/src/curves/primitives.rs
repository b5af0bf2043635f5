//! Primitive curves sampled as polylines: line, arc, circle, regular polygon, helix.

use std::f64::consts::TAU;

use glam::DVec3;

use super::{check_count, check_finite, check_finite_vec, check_output};
use crate::{GeometryError, Plane, Polyline};

fn check_plane(plane: &Plane) -> Result<(), GeometryError> {
    if plane.is_finite() {
        Ok(())
    } else {
        Err(GeometryError::NonFinite {
            what: "plane",
            index: 0,
        })
    }
}

fn check_radius(radius: f64) -> Result<(), GeometryError> {
    if radius.is_finite() && radius > 0.0 {
        Ok(())
    } else {
        Err(GeometryError::InvalidParameter {
            what: "radius",
            value: radius,
            expected: "a positive number",
        })
    }
}

/// The point at `angle` (radians) on the circle of `radius` about `centre` in `plane`'s frame.
fn on_circle(centre: DVec3, plane: &Plane, radius: f64, angle: f64) -> DVec3 {
    centre + (plane.x_axis * angle.cos() + plane.y_axis * angle.sin()) * radius
}

/// The straight segment from `start` to `end` sampled at `count` evenly spaced points (≥ 2).
pub fn line(start: DVec3, end: DVec3, count: usize) -> Result<Polyline, GeometryError> {
    check_finite_vec("line start", start)?;
    check_finite_vec("line end", end)?;
    check_count("count", count, 2)?;
    if start.distance_squared(end) <= f64::MIN_POSITIVE {
        return Err(GeometryError::Degenerate(
            "line start and end coincide".into(),
        ));
    }
    let last = (count - 1) as f64;
    let points = (0..count)
        .map(|k| {
            if k + 1 == count {
                end
            } else {
                start.lerp(end, k as f64 / last)
            }
        })
        .collect();
    check_output("line", Polyline::open(points))
}

/// A circular arc about `centre` in the orientation of `plane` (its origin is ignored), from angle
/// `start` to `end` in degrees (from the plane's x axis towards its y axis; `end < start` runs
/// clockwise), sampled at `count` evenly spaced points (≥ 2).
pub fn arc(
    centre: DVec3,
    radius: f64,
    start: f64,
    end: f64,
    plane: &Plane,
    count: usize,
) -> Result<Polyline, GeometryError> {
    check_radius(radius)?;
    check_finite_vec("centre", centre)?;
    check_finite("start angle", start)?;
    check_finite("end angle", end)?;
    check_plane(plane)?;
    check_count("count", count, 2)?;
    if start == end {
        return Err(GeometryError::Degenerate(format!(
            "arc start and end angles are equal ({start}°)"
        )));
    }
    let last = (count - 1) as f64;
    let points = (0..count)
        .map(|k| {
            let t = (start + (end - start) * k as f64 / last).to_radians();
            on_circle(centre, plane, radius, t)
        })
        .collect();
    check_output("arc", Polyline::open(points))
}

/// The circular arc from `first` through `through` to `last`, sampled at `count` points (≥ 3) with
/// the three given points among them, exactly: the samples split the two sub-arcs in proportion to
/// their angles. Fails when the points are collinear, coincide or are not finite.
pub fn arc_through(
    first: DVec3,
    through: DVec3,
    last: DVec3,
    count: usize,
) -> Result<Polyline, GeometryError> {
    check_finite_vec("first point", first)?;
    check_finite_vec("through point", through)?;
    check_finite_vec("last point", last)?;
    check_count("count", count, 3)?;
    let (a, b) = (through - first, last - first);
    let normal = a.cross(b);
    let scale = a.length().max(b.length());
    let area = normal.length();
    if area.is_nan() || area <= 1e-12 * scale * scale {
        return Err(GeometryError::Degenerate(
            "the three points of the arc are collinear or coincide: no circle passes through them"
                .into(),
        ));
    }
    // The circumcentre of the triangle (first, through, last).
    let centre = first
        + (b.cross(normal) * a.length_squared() + normal.cross(a) * b.length_squared())
            / (2.0 * normal.length_squared());
    let u = first - centre;
    let radius = u.length();
    let (x, n) = (u / radius, normal.normalize());
    let y = n.cross(x);
    let angle_of = |p: DVec3| {
        let d = p - centre;
        let t = d.dot(y).atan2(d.dot(x));
        if t <= 0.0 {
            t + std::f64::consts::TAU
        } else {
            t
        }
    };
    let (t1, t2) = (angle_of(through), angle_of(last));
    // Samples before the through point: in proportion to its angle, at least one each side.
    let steps = count - 1;
    let k1 = ((steps as f64 * t1 / t2).round() as usize).clamp(1, steps - 1);
    let mut points = Vec::with_capacity(count);
    for k in 0..=steps {
        let p = if k == 0 {
            first
        } else if k == k1 {
            through
        } else if k == steps {
            last
        } else {
            let t = if k < k1 {
                t1 * k as f64 / k1 as f64
            } else {
                t1 + (t2 - t1) * (k - k1) as f64 / (steps - k1) as f64
            };
            centre + (x * t.cos() + y * t.sin()) * radius
        };
        points.push(p);
    }
    check_output("arc", Polyline::open(points))
}

/// An arc over a chord of length `span` (centred at `centre`, along the plane's x axis) rising
/// `rise` at its middle (along the plane's y axis): the arc through the chord's ends and the top.
pub fn arc_span_rise(
    centre: DVec3,
    span: f64,
    rise: f64,
    plane: &Plane,
    count: usize,
) -> Result<Polyline, GeometryError> {
    check_finite_vec("centre", centre)?;
    check_plane(plane)?;
    if span.is_nan() || span <= 0.0 || span.is_infinite() {
        return Err(GeometryError::Degenerate(format!(
            "an arc's span must be a positive length, got {span}"
        )));
    }
    if rise == 0.0 || !rise.is_finite() {
        return Err(GeometryError::Degenerate(format!(
            "an arc's rise must be a non-zero length, got {rise}"
        )));
    }
    let half = plane.x_axis * (span / 2.0);
    arc_through(
        centre - half,
        centre + plane.y_axis * rise,
        centre + half,
        count,
    )
}

/// A closed circle about `centre` in the orientation of `plane`, sampled at `count` points (≥ 3);
/// the first point lies on the plane's x axis direction.
pub fn circle(
    centre: DVec3,
    radius: f64,
    plane: &Plane,
    count: usize,
) -> Result<Polyline, GeometryError> {
    polygon(centre, radius, count, plane, 0.0)
}

/// A closed regular polygon with `sides` vertices (≥ 3) on the circle of `radius` (circumradius)
/// about `centre`; the first vertex is at `rotation` degrees from the plane's x axis.
pub fn polygon(
    centre: DVec3,
    radius: f64,
    sides: usize,
    plane: &Plane,
    rotation: f64,
) -> Result<Polyline, GeometryError> {
    check_radius(radius)?;
    check_finite_vec("centre", centre)?;
    check_finite("rotation", rotation)?;
    check_plane(plane)?;
    check_count("sides", sides, 3)?;
    let r0 = rotation.to_radians();
    let points = (0..sides)
        .map(|k| on_circle(centre, plane, radius, r0 + TAU * k as f64 / sides as f64))
        .collect();
    check_output("polygon", Polyline::closed(points))
}

/// A helix about the axis through `centre` along `plane`'s normal, starting on the plane's x axis
/// direction: `turns` full turns (negative turns wind clockwise about the normal), rising `pitch`
/// per turn along the normal, with the radius varying linearly from `radius` to `end_radius`
/// (a conical helix when they differ), sampled at `count` points (≥ 2) evenly spaced in angle.
pub fn helix(
    centre: DVec3,
    plane: &Plane,
    radius: f64,
    end_radius: f64,
    pitch: f64,
    turns: f64,
    count: usize,
) -> Result<Polyline, GeometryError> {
    check_finite_vec("centre", centre)?;
    check_plane(plane)?;
    for (what, r) in [("radius", radius), ("end radius", end_radius)] {
        if !(r.is_finite() && r >= 0.0) {
            return Err(GeometryError::InvalidParameter {
                what,
                value: r,
                expected: "a finite number ≥ 0",
            });
        }
    }
    check_finite("pitch", pitch)?;
    check_finite("turns", turns)?;
    check_count("count", count, 2)?;
    if turns == 0.0 {
        return Err(GeometryError::InvalidParameter {
            what: "turns",
            value: turns,
            expected: "a non-zero number of turns",
        });
    }
    if radius == 0.0 && end_radius == 0.0 && pitch == 0.0 {
        return Err(GeometryError::Degenerate(
            "helix with zero radius and zero pitch is a single point".into(),
        ));
    }
    let last = (count - 1) as f64;
    let points = (0..count)
        .map(|k| {
            let s = k as f64 / last;
            let r = radius + (end_radius - radius) * s;
            let angle = TAU * turns * s;
            on_circle(centre, plane, r, angle) + plane.normal * (pitch * turns.abs() * s)
        })
        .collect();
    check_output("helix", Polyline::open(points))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The distance from `p` to the polyline's nearest vertex.
    fn nearest_vertex(line: &Polyline, p: DVec3) -> f64 {
        line.points
            .iter()
            .map(|q| q.distance(p))
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn an_arc_by_span_and_rise_passes_through_its_three_points() {
        let plane = Plane::XY;
        let centre = DVec3::new(1.0, 2.0, 3.0);
        for count in [3, 8, 17, 50] {
            let arc = arc_span_rise(centre, 6.0, 3.0, &plane, count).unwrap();
            assert_eq!(arc.points.len(), count);
            for p in [
                centre - DVec3::X * 3.0,
                centre + DVec3::Y * 3.0,
                centre + DVec3::X * 3.0,
            ] {
                assert!(nearest_vertex(&arc, p) <= 1e-12, "{count}: {p}");
            }
            // Span 6, rise 3: a half circle of radius 3 about the chord's middle.
            for q in &arc.points {
                assert!((q.distance(centre) - 3.0).abs() <= 1e-12, "{q}");
            }
        }
        // A flat arc: every sample on the circle through the three points.
        let arc = arc_span_rise(DVec3::ZERO, 10.0, 1.0, &plane, 21).unwrap();
        let r = (25.0 + 1.0) / 2.0; // r = (s²/4 + h²) / 2h
        let c = DVec3::new(0.0, 1.0 - r, 0.0);
        for q in &arc.points {
            assert!((q.distance(c) - r).abs() <= 1e-12);
        }
        assert!((arc.points[10] - DVec3::new(0.0, 1.0, 0.0)).length() <= 1e-15);
        assert!(arc_span_rise(DVec3::ZERO, 6.0, 0.0, &plane, 9).is_err());
        assert!(arc_span_rise(DVec3::ZERO, -1.0, 1.0, &plane, 9).is_err());
    }

    #[test]
    fn an_arc_through_three_points_keeps_them_and_refuses_a_line() {
        let (a, b, c) = (
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 2.0, 0.5),
            DVec3::new(3.0, 1.0, -1.0),
        );
        let arc = arc_through(a, b, c, 12).unwrap();
        assert_eq!(arc.points[0], a);
        assert_eq!(*arc.points.last().unwrap(), c);
        assert!(arc.points.contains(&b));
        assert!(arc_through(a, DVec3::X, DVec3::X * 2.0, 5).is_err());
    }

    #[test]
    fn line_is_evenly_spaced_and_exact_at_the_ends() {
        let end = DVec3::new(3.0, 0.3, -1.0);
        let p = line(DVec3::ONE, end, 7).unwrap();
        assert_eq!(p.points.len(), 7);
        assert_eq!(p.points[0], DVec3::ONE);
        assert_eq!(p.points[6], end);
        let step = DVec3::ONE.distance(end) / 6.0;
        for (a, b) in p.edges() {
            assert!((a.distance(b) - step).abs() < 1e-12);
        }
        assert!(line(DVec3::ZERO, DVec3::ZERO, 3).is_err());
        assert!(line(DVec3::ZERO, DVec3::X, 1).is_err());
        assert!(line(DVec3::NAN, DVec3::X, 2).is_err());
    }

    #[test]
    fn arc_points_lie_on_the_circle_in_the_plane() {
        let plane = Plane::from_normal(DVec3::ZERO, DVec3::new(1.0, 1.0, 1.0)).unwrap();
        let c = DVec3::new(1.0, 2.0, 3.0);
        let p = arc(c, 2.0, -30.0, 200.0, &plane, 20).unwrap();
        for q in &p.points {
            assert!(((*q - c).length() - 2.0).abs() < 1e-12);
            assert!((*q - c).dot(plane.normal).abs() < 1e-12);
        }
        let first = (p.points[0] - c).normalize();
        let expected =
            plane.x_axis * (-30f64).to_radians().cos() + plane.y_axis * (-30f64).to_radians().sin();
        assert!((first - expected).length() < 1e-12);
        assert!(arc(c, 0.0, 0.0, 90.0, &plane, 4).is_err());
        assert!(arc(c, 1.0, 10.0, 10.0, &plane, 4).is_err());
    }

    #[test]
    fn circle_and_polygon_are_closed_and_regular() {
        let c = circle(DVec3::ZERO, 1.5, &Plane::XY, 12).unwrap();
        assert!(c.closed);
        assert_eq!(c.points.len(), 12);
        let side = 2.0 * 1.5 * (std::f64::consts::PI / 12.0).sin();
        for (a, b) in c.edges() {
            assert!((a.distance(b) - side).abs() < 1e-12);
        }
        let sq = polygon(DVec3::ZERO, 2f64.sqrt(), 4, &Plane::XY, 45.0).unwrap();
        assert!((sq.points[0] - DVec3::new(1.0, 1.0, 0.0)).length() < 1e-12);
        assert!((sq.length() - 8.0).abs() < 1e-12);
        assert!(polygon(DVec3::ZERO, 1.0, 2, &Plane::XY, 0.0).is_err());
    }

    #[test]
    fn helix_rises_pitch_per_turn_and_tapers() {
        let h = helix(DVec3::ZERO, &Plane::XY, 1.0, 1.0, 2.0, 3.0, 61).unwrap();
        assert!((h.points[60].z - 6.0).abs() < 1e-12);
        // One full turn later (20 samples per turn) the point is straight above.
        assert!((h.points[20] - (h.points[0] + DVec3::Z * 2.0)).length() < 1e-12);
        for q in &h.points {
            assert!(((q.x * q.x + q.y * q.y).sqrt() - 1.0).abs() < 1e-12);
        }
        let cone = helix(DVec3::ZERO, &Plane::XY, 2.0, 0.0, 1.0, 1.0, 5).unwrap();
        assert!(cone.points[4].truncate().length() < 1e-12);
        assert!(helix(DVec3::ZERO, &Plane::XY, 1.0, 1.0, 1.0, 0.0, 5).is_err());
        assert!(helix(DVec3::ZERO, &Plane::XY, 0.0, 0.0, 0.0, 1.0, 5).is_err());
        assert!(helix(DVec3::ZERO, &Plane::XY, -1.0, 1.0, 1.0, 1.0, 5).is_err());
        let huge = helix(DVec3::ZERO, &Plane::XY, 1.0, 1.0, 1e308, 1e10, 5);
        assert!(huge.unwrap_err().to_string().contains("overflows"));
    }
}
