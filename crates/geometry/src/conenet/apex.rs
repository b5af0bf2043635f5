//! Cone apex points from the apex-locating function (paper Eq. 1, notes §1).

use glam::DVec3;

use super::tolerance;

/// The apex of the strip between columns j−1 and j: `C_{j−1} = (X_j − a_j X_{j−1}) / (1 − a_j)`;
/// `None` at infinity (`|1 − a_j| ≤ 1e-12`, a translation) or when the point overflows.
#[inline]
pub fn apex_point(x_prev: DVec3, x: DVec3, a: f64) -> Option<DVec3> {
    let t = 1.0 - a;
    if !(t.abs() > tolerance::APEX_AT_INFINITY) {
        return None;
    }
    // X_j + a (X_j − X_{j−1}) / (1 − a): the same point, written to stay accurate near a = 0.
    let c = x + (x - x_prev) * (a / t);
    c.is_finite().then_some(c)
}

/// All apices C_0 … C_{M−2} for the swept directrix `points` (M) and apex values `apex` (M−1).
pub fn apex_points(points: &[DVec3], apex: &[f64]) -> Vec<Option<DVec3>> {
    points
        .windows(2)
        .zip(apex)
        .map(|(w, &a)| apex_point(w[0], w[1], a))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn apex_is_the_scaling_center() {
        // X_0 = 0, X_1 = (1,0,0), a = 0.5 ⇒ C = (X_1 − 0.5 X_0) / 0.5 = (2, 0, 0).
        assert_eq!(
            apex_point(DVec3::ZERO, DVec3::X, 0.5),
            Some(DVec3::new(2.0, 0.0, 0.0))
        );
        assert_eq!(apex_point(DVec3::ZERO, DVec3::X, 1.0), None);
        // a = 2 ⇒ C = (X_1 − 2 X_0)/(−1) = (−1, 0, 0).
        assert_eq!(
            apex_point(DVec3::ZERO, DVec3::X, 2.0),
            Some(DVec3::new(-1.0, 0.0, 0.0))
        );
        let c = apex_point(DVec3::new(1.0, 2.0, 3.0), DVec3::new(2.0, 2.0, 3.5), 0.3).unwrap();
        // σ(X_0) = X_1: C is fixed by σ: a (C − X_0) + X_1 = C.
        assert!(
            (0.3 * (c - DVec3::new(1.0, 2.0, 3.0)) + DVec3::new(2.0, 2.0, 3.5) - c).length()
                < 1e-14
        );
    }
}
