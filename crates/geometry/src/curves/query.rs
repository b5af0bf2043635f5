//! Reading a polyline by arc length: the point and tangent at a parameter, and the closest point.
//!
//! The parameter `t` runs from 0 at the first point to 1 at the end by arc length; a closed curve's
//! end is its first point again, after the closing edge.

use glam::DVec3;

use crate::error::check_finite_points;
use crate::{GeometryError, Polyline};

/// Cumulative arc lengths at the start of each edge, and the total.
fn edge_starts(curve: &Polyline) -> (Vec<f64>, f64) {
    let mut starts = Vec::with_capacity(curve.edge_count());
    let mut total = 0.0;
    for (a, b) in curve.edges() {
        starts.push(total);
        total += a.distance(b);
    }
    (starts, total)
}

fn check_curve(curve: &Polyline) -> Result<f64, GeometryError> {
    check_finite_points("curve", &curve.points)?;
    if curve.edge_count() == 0 {
        return Err(GeometryError::TooFewPoints {
            what: "curve",
            needed: 2,
            got: curve.points.len(),
        });
    }
    let length = curve.length();
    if !(length.is_finite() && length > 0.0) {
        return Err(GeometryError::Degenerate(format!(
            "the curve has no length to evaluate along (length {length})"
        )));
    }
    Ok(length)
}

/// The unit direction of the edge at `k`, or of the nearest edge with a length (zero-length edges
/// have no direction of their own).
fn edge_direction(curve: &Polyline, k: usize) -> DVec3 {
    let n = curve.edge_count();
    (0..n)
        .flat_map(|d| [k + d, k + n - d])
        .map(|j| curve.edge(j % n))
        .map(|(a, b)| b - a)
        .find(|d| d.length_squared() > 0.0)
        .map_or(DVec3::X, DVec3::normalize)
}

/// The point at parameter `t` (0 … 1 by arc length) and the unit tangent there. An open curve clamps
/// `t` to [0, 1]; a closed curve wraps it. At a vertex the tangent is the next edge's.
pub fn evaluate(curve: &Polyline, t: f64) -> Result<(DVec3, DVec3), GeometryError> {
    crate::curves::check_finite("t", t)?;
    check_curve(curve)?;
    let (starts, total) = edge_starts(curve);
    let t = if curve.closed {
        t.rem_euclid(1.0)
    } else {
        t.clamp(0.0, 1.0)
    };
    let s = t * total;
    // The last edge that starts at or before s (and has a length, unless none after it does).
    let mut k = starts
        .partition_point(|&start| start <= s)
        .saturating_sub(1);
    let (a, b) = curve.edge(k);
    let length = a.distance(b);
    let point = if length > 0.0 {
        a + (b - a) * ((s - starts[k]) / length).clamp(0.0, 1.0)
    } else {
        a
    };
    if length == 0.0 {
        k = (k + 1) % curve.edge_count();
    }
    Ok((point, edge_direction(curve, k)))
}

/// The closest point of a segment to `p`, and its fraction along the segment.
fn closest_on_segment(a: DVec3, b: DVec3, p: DVec3) -> (DVec3, f64) {
    let d = b - a;
    let len2 = d.length_squared();
    if len2 == 0.0 {
        return (a, 0.0);
    }
    let f = ((p - a).dot(d) / len2).clamp(0.0, 1.0);
    (a + d * f, f)
}

/// The point of the curve closest to `p`, its parameter (as in [`evaluate`]) and the distance. On
/// ties the first edge wins.
pub fn closest_point(curve: &Polyline, p: DVec3) -> Result<(DVec3, f64, f64), GeometryError> {
    crate::curves::check_finite_vec("point", p)?;
    check_curve(curve)?;
    let (starts, total) = edge_starts(curve);
    let mut best = (curve.points[0], 0.0, f64::INFINITY);
    for (k, (a, b)) in curve.edges().enumerate() {
        let (q, f) = closest_on_segment(a, b, p);
        let d = q.distance_squared(p);
        if d < best.2 {
            best = (q, (starts[k] + f * a.distance(b)) / total, d);
        }
    }
    let (q, t, d2) = best;
    Ok((q, t.clamp(0.0, 1.0), d2.sqrt()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Polyline {
        Polyline::closed(vec![
            DVec3::ZERO,
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(2.0, 2.0, 0.0),
            DVec3::new(0.0, 2.0, 0.0),
        ])
    }

    #[test]
    fn evaluate_walks_by_arc_length_including_the_closing_edge() {
        let c = square();
        let (p, t) = evaluate(&c, 0.0).unwrap();
        assert_eq!((p, t), (DVec3::ZERO, DVec3::X));
        let (p, t) = evaluate(&c, 0.375).unwrap();
        assert_eq!((p, t), (DVec3::new(2.0, 1.0, 0.0), DVec3::Y));
        let (p, t) = evaluate(&c, 0.875).unwrap();
        assert_eq!(
            (p, t),
            (DVec3::new(0.0, 1.0, 0.0), -DVec3::Y),
            "closing edge"
        );
        assert_eq!(
            evaluate(&c, 1.0).unwrap().0,
            DVec3::ZERO,
            "closed: t = 1 is the start"
        );
        let open = Polyline::open(vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::X,
            DVec3::new(1.0, 3.0, 0.0),
        ]);
        let (p, t) = evaluate(&open, 0.25).unwrap();
        assert_eq!(
            (p, t),
            (DVec3::X, DVec3::Y),
            "a zero-length edge is skipped"
        );
        assert_eq!(evaluate(&open, 2.0).unwrap().0, DVec3::new(1.0, 3.0, 0.0));
        assert!(evaluate(&Polyline::open(vec![DVec3::X, DVec3::X]), 0.5).is_err());
        assert!(evaluate(&open, f64::NAN).is_err());
    }

    #[test]
    fn closest_point_projects_onto_the_nearest_edge() {
        let c = square();
        let (q, t, d) = closest_point(&c, DVec3::new(3.0, 1.0, 0.0)).unwrap();
        assert_eq!((q, t, d), (DVec3::new(2.0, 1.0, 0.0), 0.375, 1.0));
        let (q, t, d) = closest_point(&c, DVec3::new(-1.0, 1.0, 2.0)).unwrap();
        assert_eq!(q, DVec3::new(0.0, 1.0, 0.0));
        assert_eq!(t, 0.875);
        assert!((d - 5f64.sqrt()).abs() < 1e-15);
        // The closest point evaluates back to itself.
        let (q, t, _) = closest_point(&c, DVec3::new(0.7, -0.4, 0.0)).unwrap();
        assert!((evaluate(&c, t).unwrap().0 - q).length() < 1e-15);
    }
}
