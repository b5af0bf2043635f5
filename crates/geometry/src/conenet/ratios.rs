//! Ratios → rulings → construction planes (CNets Construct, paper Sec. 4.4.1, notes §3).
//!
//! In the support plane S_{i,j} through X_{j−1}, X_j and G_{i,j−1} the frame is `ê = ê_j` and
//! `w = unit(D − (D·ê) ê)` with `D = G_{i,j−1} − X_{j−1}`. A ruling at angle θ ∈ (0, π) from ê is
//! `R(θ) = cos θ ê + sin θ w`, its plane normal `P(θ) = sin θ ê − cos θ w`. The ratio r maps to θ
//! piecewise linearly in angle, with r = ½ at the bisector angle θ_b (the ruling in the Monge plane).

use std::f64::consts::PI;

use glam::DVec3;

use super::{tolerance, trig};
use crate::GeometryError;

/// The orthonormal frame (ê, w) of a support plane S_{i,j}.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SupportFrame {
    /// ê_j, the unit directrix edge into X_j.
    pub e: DVec3,
    /// Unit vector in S_{i,j}, perpendicular to ê, pointing towards the strip (towards G_{i,j−1}).
    pub w: DVec3,
}

impl SupportFrame {
    /// The frame of S_{i,j} from `x_prev = X_{j−1}`, the unit edge `e = ê_j` and `g = G_{i,j−1}`.
    /// Fails when g lies on the line of the edge (the support plane is undefined).
    #[inline]
    pub fn new(
        x_prev: DVec3,
        e: DVec3,
        g: DVec3,
        row: usize,
        column: usize,
    ) -> Result<Self, GeometryError> {
        let d = g - x_prev;
        let perp = d - e * d.dot(e);
        let n2 = perp.length_squared();
        if !(n2 > tolerance::FRAME * tolerance::FRAME * d.length_squared()) || !n2.is_finite() {
            return Err(GeometryError::DegenerateSupport { row, column });
        }
        Ok(Self {
            e,
            w: perp * (1.0 / n2.sqrt()),
        })
    }

    /// The ruling direction at angle θ from ê.
    #[inline]
    pub fn ruling(&self, theta: f64) -> DVec3 {
        let (s, c) = trig::sin_cos(theta);
        self.e * c + self.w * s
    }

    /// The construction-plane normal at angle θ: contains the ruling, is perpendicular to the support
    /// plane and satisfies P·ê = sin θ > 0.
    #[inline]
    pub fn normal(&self, theta: f64) -> DVec3 {
        let (s, c) = trig::sin_cos(theta);
        self.e * s - self.w * c
    }

    /// (cos θ_b, sin θ_b) · h for the bisector angle of the Monge normal `b`, with h > 0.
    #[inline]
    fn bisector_pair(&self, b: DVec3) -> (f64, f64) {
        (-self.w.dot(b), self.e.dot(b))
    }

    /// The bisector angle θ_b = atan2(ê·b, −w·b) ∈ (0, π): the ruling in the Monge plane b.
    #[inline]
    pub fn bisector_angle(&self, b: DVec3) -> f64 {
        let (x, y) = self.bisector_pair(b);
        trig::atan2(y, x)
    }

    /// The plane normal for ratio r, given the Monge normal `b` at X_j. r = ½ is computed without
    /// trigonometry and gives exactly the plane through the bisecting ruling.
    #[inline]
    pub fn ratio_normal(&self, b: DVec3, r: f64) -> DVec3 {
        let (x, y) = self.bisector_pair(b);
        if r == 0.5 {
            let inv = 1.0 / (x * x + y * y).sqrt();
            self.e * (y * inv) - self.w * (x * inv)
        } else {
            self.normal(ratio_to_angle(r, trig::atan2(y, x)))
        }
    }

    /// The angle φ ∈ (0, π), measured in this frame from ê, of `q − x`, where `x` is X_j (the vertex
    /// the frame's rulings start from). Eq. 2 of the paper holds exactly when θ < φ for
    /// `q = G_{i,j−1}` (notes §6, plane fix).
    #[inline]
    pub fn angle_of(&self, q: DVec3, x: DVec3) -> f64 {
        let v = q - x;
        trig::atan2(self.w.dot(v), self.e.dot(v))
    }
}

/// Hot path of the ratio construction: a positive multiple of the normal of Π_{i,j} for ratio r,
/// from `x_prev = X_{j−1}`, `e = ê_j`, `g = G_{i,j−1}` and the Monge normal `b` at X_j. Equal to
/// `SupportFrame::new(..).ratio_normal(b, r)` up to a positive factor, without normalizing (the
/// construction step does not depend on the length of P), so only the trigonometric path needs a
/// square root. `inv_scale` (1 / design size) keeps the magnitudes near 1 at any scale.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn ratio_normal_unnormalized(
    x_prev: DVec3,
    e: DVec3,
    g: DVec3,
    b: DVec3,
    r: f64,
    inv_scale: f64,
    row: usize,
    column: usize,
) -> Result<DVec3, GeometryError> {
    let d = (g - x_prev) * inv_scale;
    if d.abs().max_element() <= tolerance::FRAME {
        // G_{i,j−1} = X_{j−1}: a generatrix vertex on the directrix (a wall standing on it). The
        // support plane is undefined, but the vertex is not: the step runs along the directrix edge
        // and meets any plane through X_j at X_j. Use the Monge plane.
        return Ok(b);
    }
    let perp = d - e * d.dot(e);
    let n2 = perp.length_squared();
    if !(perp.abs().max_element() > tolerance::FRAME * d.abs().max_element()) || !n2.is_finite() {
        return Err(GeometryError::DegenerateSupport { row, column });
    }
    // With w = perp / |perp|: ê·b = y > 0 and −w·b = x = −(perp·b) / |perp|.
    let y = e.dot(b);
    let pb = perp.dot(b);
    if r == 0.5 {
        // (y ê − x w) · |perp|² = y |perp|² ê + (perp·b) perp.
        Ok(e * (y * n2) + perp * pb)
    } else {
        let n = n2.sqrt();
        let (s, c) = trig::sin_cos(ratio_to_angle(r, trig::atan2(y * n, -pb)));
        // (sin θ ê − cos θ w) · |perp|.
        Ok(e * (s * n) - perp * c)
    }
}

/// The ratio → angle map: `θ = 2 r θ_b` for r ≤ ½, `θ = θ_b + (2r − 1)(π − θ_b)` for r ≥ ½.
#[inline]
pub fn ratio_to_angle(r: f64, theta_b: f64) -> f64 {
    if r <= 0.5 {
        2.0 * r * theta_b
    } else {
        theta_b + (2.0 * r - 1.0) * (PI - theta_b)
    }
}

/// The inverse of [`ratio_to_angle`].
#[inline]
pub fn angle_to_ratio(theta: f64, theta_b: f64) -> f64 {
    if theta <= theta_b {
        theta / (2.0 * theta_b)
    } else {
        0.5 + (theta - theta_b) / (2.0 * (PI - theta_b))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ratio_map_hits_corners_and_bisector() {
        let tb = 1.1;
        assert_eq!(ratio_to_angle(0.0, tb), 0.0);
        assert_eq!(ratio_to_angle(0.5, tb), tb);
        assert!((ratio_to_angle(1.0, tb) - PI).abs() < 1e-15);
        assert!((ratio_to_angle(0.25, tb) - tb / 2.0).abs() < 1e-15);
        for r in [0.0, 0.1, 0.5, 0.7, 1.0] {
            assert!((angle_to_ratio(ratio_to_angle(r, tb), tb) - r).abs() < 1e-15);
        }
    }

    #[test]
    fn half_ratio_plane_contains_the_bisecting_ruling() {
        // Directrix edge along x into X_j = (1,0,0), next edge along y: b = unit(1,1,0).
        let frame =
            SupportFrame::new(DVec3::ZERO, DVec3::X, DVec3::new(0.3, 0.5, 0.7), 0, 1).unwrap();
        let b = DVec3::new(1.0, 1.0, 0.0).normalize();
        let tb = frame.bisector_angle(b);
        let ruling = frame.ruling(tb);
        assert!(
            ruling.dot(b).abs() < 1e-15,
            "the r = ½ ruling lies in the bisecting plane"
        );
        let p = frame.ratio_normal(b, 0.5);
        assert!((p - frame.normal(tb)).length() < 1e-15);
        assert!(p.dot(ruling).abs() < 1e-15 && p.dot(DVec3::X) > 0.0);
        // The plane is perpendicular to the support plane (normal ê × w).
        assert!(p.dot(frame.e.cross(frame.w)).abs() < 1e-15);
    }

    #[test]
    fn frame_rejects_point_on_edge_line() {
        assert_eq!(
            SupportFrame::new(DVec3::ZERO, DVec3::X, DVec3::new(3.0, 0.0, 0.0), 4, 2),
            Err(GeometryError::DegenerateSupport { row: 4, column: 2 })
        );
    }
}
