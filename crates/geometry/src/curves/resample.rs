//! Resampling polylines: evenly by arc length (by count or by a target edge length), or into
//! exactly equal chords.

use glam::DVec3;

use super::{check_count, cumulative_lengths};
use crate::error::check_finite_points;
use crate::{GeometryError, Polyline};

/// The points walked along (a closed polyline returns to its first point) and its total length.
fn walk_points(curve: &Polyline) -> Result<(Vec<DVec3>, f64), GeometryError> {
    let what = "curve";
    if curve.points.len() < 2 {
        return Err(GeometryError::TooFewPoints {
            what,
            needed: 2,
            got: curve.points.len(),
        });
    }
    check_finite_points(what, &curve.points)?;
    let points = curve.swept_points();
    let total: f64 = points.windows(2).map(|w| w[0].distance(w[1])).sum();
    if total.is_nan() || total <= 0.0 {
        return Err(GeometryError::Degenerate(
            "the curve has zero length (all its points coincide)".into(),
        ));
    }
    if !total.is_finite() {
        return Err(GeometryError::Degenerate(
            "the curve's length overflows".into(),
        ));
    }
    Ok((points, total))
}

/// Resamples `curve` at `count` points evenly spaced by arc length along it: an open curve keeps
/// both end points (count ≥ 2); a closed curve keeps its first point and stays closed (count ≥ 3).
/// Consecutive duplicate points in the input are harmless.
pub fn resample_by_count(curve: &Polyline, count: usize) -> Result<Polyline, GeometryError> {
    let min = if curve.closed { 3 } else { 2 };
    check_count("count", count, min)?;
    let (points, total) = walk_points(curve)?;
    let cumulative = cumulative_lengths(&points);
    let intervals = if curve.closed { count } else { count - 1 };
    let mut out = Vec::with_capacity(count);
    let mut seg = 0;
    for k in 0..count {
        if k == 0 {
            out.push(points[0]);
            continue;
        }
        if !curve.closed && k + 1 == count {
            out.push(points[points.len() - 1]);
            continue;
        }
        let s = total * k as f64 / intervals as f64;
        while seg + 2 < points.len() && cumulative[seg + 1] < s {
            seg += 1;
        }
        let (sa, sb) = (cumulative[seg], cumulative[seg + 1]);
        let u = if sb > sa {
            ((s - sa) / (sb - sa)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        out.push(points[seg].lerp(points[seg + 1], u));
    }
    Ok(Polyline {
        points: out,
        closed: curve.closed,
    })
}

/// The number of edges closest to `total / length` (at least 1 for open curves, 3 for closed ones).
pub fn edge_count_for_length(
    total: f64,
    length: f64,
    closed: bool,
) -> Result<usize, GeometryError> {
    if !(length.is_finite() && length > 0.0) {
        return Err(GeometryError::InvalidParameter {
            what: "target edge length",
            value: length,
            expected: "a positive number",
        });
    }
    let edges = (total / length).round();
    if edges > super::MAX_POINTS as f64 {
        return Err(GeometryError::Degenerate(format!(
            "target edge length {length} would need {edges} edges (at most {})",
            super::MAX_POINTS
        )));
    }
    Ok((edges as usize).max(if closed { 3 } else { 1 }))
}

/// Resamples `curve` evenly by arc length into the whole number of edges closest to
/// `length(curve) / length` (at least one edge; at least three for a closed curve).
pub fn resample_by_length(curve: &Polyline, length: f64) -> Result<Polyline, GeometryError> {
    let (_, total) = walk_points(curve)?;
    let edges = edge_count_for_length(total, length, curve.closed)?;
    resample_by_count(curve, if curve.closed { edges } else { edges + 1 })
}

/// The first point after arc position (`seg`, `u`) on `points` at distance `chord` from `from`:
/// the point where the curve leaves the sphere of radius `chord` about `from` (which lies on the
/// curve at that position). `None` when the curve ends inside the sphere.
fn next_chord_point(
    points: &[DVec3],
    from: DVec3,
    seg: usize,
    u: f64,
    chord: f64,
) -> Option<(usize, f64, DVec3)> {
    let r2 = chord * chord;
    for j in seg..points.len() - 1 {
        let (a, b) = (points[j], points[j + 1]);
        let d = b - a;
        let dd = d.length_squared();
        if dd == 0.0 {
            continue;
        }
        let f = a - from;
        let half_b = f.dot(d);
        let c = f.length_squared() - r2;
        let disc = half_b * half_b - dd * c;
        if disc < 0.0 {
            continue;
        }
        let root = (-half_b + disc.sqrt()) / dd;
        let u_min = if j == seg { u } else { 0.0 };
        // A small tolerance keeps an exit exactly at a vertex from slipping between two segments.
        if root >= u_min - 1e-12 && root <= 1.0 + 1e-12 {
            let root = root.clamp(u_min, 1.0);
            return Some((j, root, a + d * root));
        }
    }
    None
}

/// Walks `steps` chords of length `chord` from the start; returns the points (excluding the start)
/// and the arc position (segment, parameter) of the last one, or `None` when the curve runs out.
fn walk_chords(points: &[DVec3], chord: f64, steps: usize) -> Option<(Vec<DVec3>, usize, f64)> {
    let mut out = Vec::with_capacity(steps);
    let (mut seg, mut u, mut at) = (0, 0.0, points[0]);
    for _ in 0..steps {
        let (s, v, p) = next_chord_point(points, at, seg, u, chord)?;
        out.push(p);
        (seg, u, at) = (s, v, p);
    }
    Some((out, seg, u))
}

/// Largest point count of [`divide_equal_chords`] (each bisection step walks the whole curve).
pub const MAX_CHORDS: usize = 1_000_000;

/// Divides `curve` into edges of exactly equal length (chords, as with a pair of dividers): an
/// open curve into `count − 1` chords from its first to its last point (count ≥ 2), a closed curve
/// into `count` chords from its first point around back to it (count ≥ 3). The points lie on the
/// input polyline. Fails when no equal division exists within 1e-9 of the curve length (e.g. a
/// curve whose ends almost meet, divided into very few chords).
pub fn divide_equal_chords(curve: &Polyline, count: usize) -> Result<Polyline, GeometryError> {
    let min = if curve.closed { 3 } else { 2 };
    check_count("count", count, min)?;
    if count > MAX_CHORDS {
        return Err(GeometryError::Degenerate(format!(
            "equal chords: count {count} is too large (at most {MAX_CHORDS})"
        )));
    }
    let (points, total) = walk_points(curve)?;
    let chords = if curve.closed { count } else { count - 1 };
    let end = points[points.len() - 1];
    let cumulative = cumulative_lengths(&points);
    let arc_at = |seg: usize, u: f64| cumulative[seg] + u * (cumulative[seg + 1] - cumulative[seg]);
    // With chord c = total / chords every step advances at least c along the curve, so `chords`
    // steps reach the end or run out: that is an upper bound. Bisect on whether the last chord
    // overshoots the end.
    let (mut lo, mut hi) = (0.0, total / chords as f64);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        let reaches = match walk_chords(&points, mid, chords) {
            None => true,
            Some((_, seg, u)) => arc_at(seg, u) >= total,
        };
        if reaches {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let chord = 0.5 * (lo + hi);
    let Some((mut out, _, _)) = walk_chords(&points, chord, chords - 1) else {
        return Err(GeometryError::Degenerate(format!(
            "cannot divide the curve into {chords} equal chords"
        )));
    };
    let last = out.last().copied().unwrap_or(points[0]);
    let residual = (last.distance(end) - chord).abs();
    if residual > 1e-9 * total.max(1.0) {
        return Err(GeometryError::Degenerate(format!(
            "cannot divide the curve into {chords} equal chords (closest miss {residual:.3e})"
        )));
    }
    out.insert(0, points[0]);
    if !curve.closed {
        out.push(end);
    }
    Ok(Polyline {
        points: out,
        closed: curve.closed,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Plane;
    use crate::curves::primitives::{arc, circle};

    fn ell() -> Polyline {
        Polyline::open(vec![
            DVec3::ZERO,
            DVec3::new(3.0, 0.0, 0.0),
            DVec3::new(3.0, 0.0, 0.0), // duplicate: harmless
            DVec3::new(3.0, 1.0, 0.0),
        ])
    }

    #[test]
    fn by_count_spaces_points_evenly_along_the_curve() {
        let p = resample_by_count(&ell(), 5).unwrap();
        let expected = [
            DVec3::ZERO,
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(3.0, 0.0, 0.0),
            DVec3::new(3.0, 1.0, 0.0),
        ];
        for (a, b) in p.points.iter().zip(expected) {
            assert!((*a - b).length() < 1e-12, "{a} vs {b}");
        }
    }

    #[test]
    fn closed_curves_stay_closed_and_keep_their_start() {
        let square = Polyline::closed(vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::Y,
        ]);
        let p = resample_by_count(&square, 8).unwrap();
        assert!(p.closed);
        assert_eq!(p.points.len(), 8);
        assert_eq!(p.points[0], DVec3::ZERO);
        assert!((p.points[7] - DVec3::new(0.0, 0.5, 0.0)).length() < 1e-12);
        assert!(resample_by_count(&square, 2).is_err());
    }

    #[test]
    fn by_length_rounds_to_the_nearest_edge_count() {
        let p = resample_by_length(&ell(), 0.9).unwrap(); // 4 / 0.9 = 4.4 → 4 edges
        assert_eq!(p.points.len(), 5);
        let p = resample_by_length(&ell(), 100.0).unwrap(); // at least one edge
        assert_eq!(p.points.len(), 2);
        assert!(resample_by_length(&ell(), 0.0).is_err());
        assert!(resample_by_length(&ell(), f64::NAN).is_err());
        assert!(resample_by_length(&ell(), 1e-12).is_err());
    }

    #[test]
    fn equal_chords_are_equal_and_on_the_curve() {
        let a = arc(DVec3::ZERO, 2.0, 0.0, 270.0, &Plane::XY, 50).unwrap();
        let p = divide_equal_chords(&a, 7).unwrap();
        assert_eq!(p.points[0], a.points[0]);
        assert_eq!(p.points[6], a.points[49]);
        let lengths: Vec<f64> = p.edges().map(|(x, y)| x.distance(y)).collect();
        for l in &lengths {
            assert!((l - lengths[0]).abs() < 1e-8, "{lengths:?}");
        }
        let c = circle(DVec3::ZERO, 1.0, &Plane::XY, 40).unwrap();
        let q = divide_equal_chords(&c, 5).unwrap();
        assert!(q.closed);
        let lengths: Vec<f64> = q.edges().map(|(x, y)| x.distance(y)).collect();
        for l in &lengths {
            assert!((l - lengths[0]).abs() < 1e-8, "{lengths:?}");
        }
    }

    #[test]
    fn degenerate_curves_are_errors() {
        let dot = Polyline::open(vec![DVec3::X, DVec3::X]);
        assert!(matches!(
            resample_by_count(&dot, 3),
            Err(GeometryError::Degenerate(_))
        ));
        assert!(resample_by_count(&Polyline::open(vec![DVec3::X]), 3).is_err());
        let bad = Polyline::open(vec![DVec3::ZERO, DVec3::INFINITY]);
        assert!(resample_by_count(&bad, 3).is_err());
        assert!(resample_by_count(&ell(), 1).is_err());
        assert!(divide_equal_chords(&ell(), 1).is_err());
    }
}
