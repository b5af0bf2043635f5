//! Closest points of two lines: the stable solve used wherever two coplanar lines must meet (conical
//! and parallel support layers, the parallel transform).

use glam::DVec3;

/// Two lines count as parallel when the sine of their angle is at most this.
pub const PARALLEL_SINE: f64 = 1e-12;

/// Parameters (t, s) of the closest points `p + t u` and `q + s v` of two lines.
///
/// With `w = p − q`, `a = u·u`, `b = u·v`, `c = v·v`, `d = u·w`, `e = v·w` and
/// `D = |u × v|² = ac − b²` (computed from the cross product, which keeps it accurate for small
/// angles): `t = (b e − c d) / D`, `s = (a e − b d) / D`. For two coplanar lines both points are the
/// intersection. `None` when a direction vanishes, the lines are parallel (`|u × v| ≤ 1e-12 |u||v|`)
/// or the result is not finite.
pub fn closest_parameters(p: DVec3, u: DVec3, q: DVec3, v: DVec3) -> Option<(f64, f64)> {
    let a = u.length_squared();
    let c = v.length_squared();
    let denom = u.cross(v).length_squared();
    if !(denom > PARALLEL_SINE * PARALLEL_SINE * a * c) {
        return None;
    }
    let w = p - q;
    let b = u.dot(v);
    let d = u.dot(w);
    let e = v.dot(w);
    let t = (b * e - c * d) / denom;
    let s = (a * e - b * d) / denom;
    (t.is_finite() && s.is_finite()).then_some((t, s))
}

/// The intersection of two (coplanar) lines `p + t u` and `q + s v`: the midpoint of their closest
/// points; `None` when they are parallel.
pub fn intersect(p: DVec3, u: DVec3, q: DVec3, v: DVec3) -> Option<DVec3> {
    let (t, s) = closest_parameters(p, u, q, v)?;
    let m = (p + u * t + q + v * s) * 0.5;
    m.is_finite().then_some(m)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossing_lines_meet_and_parallel_lines_do_not() {
        // x axis and the line through (2, 1, 0) along −y meet at (2, 0, 0).
        let (t, s) =
            closest_parameters(DVec3::ZERO, DVec3::X, DVec3::new(2.0, 1.0, 0.0), -DVec3::Y)
                .unwrap();
        assert_eq!((t, s), (2.0, 1.0));
        assert_eq!(
            intersect(
                DVec3::ZERO,
                DVec3::X * 3.0,
                DVec3::new(2.0, 1.0, 0.0),
                -DVec3::Y
            ),
            Some(DVec3::new(2.0, 0.0, 0.0))
        );
        assert_eq!(
            intersect(DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::X * 2.0),
            None
        );
        assert_eq!(
            intersect(DVec3::ZERO, DVec3::ZERO, DVec3::Y, DVec3::X),
            None
        );
        // Skew lines: the closest points are (0,0,0) on the x axis and (0,0,1) on the shifted y axis.
        let (t, s) = closest_parameters(DVec3::ZERO, DVec3::X, DVec3::Z, DVec3::Y).unwrap();
        assert_eq!((t, s), (0.0, 0.0));
    }
}
