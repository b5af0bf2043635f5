//! Ratios → rulings → construction planes (CNets Construct, paper Sec. 4.4.1, notes §3).
//!
//! In the support plane S_{i,j} through X_{j−1}, X_j and G_{i,j−1} the frame is `ê = ê_j` and
//! `w = unit(D − (D·ê) ê)` with `D = G_{i,j−1} − X_{j−1}`. A ruling at angle θ ∈ (0, π) from ê is
//! `R(θ) = cos θ ê + sin θ w`, its plane normal `P(θ) = sin θ ê − cos θ w`. The ratio r maps to θ
//! piecewise linearly in angle, with r = ½ at the bisector angle θ_b (the ruling in the Monge plane).

use std::f64::consts::PI;

use glam::DVec3;

use super::directrix::SweptDirectrix;
use super::lanes::{F, M, V3};
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

/// The per-column constants of the ratio hot path at X_j: `X_{j−1}`, `ê_j`, the Monge normal `b`
/// and `ê_j · b` (sin θ_b times a positive factor, the same for every row).
#[derive(Debug, Clone, Copy)]
pub(crate) struct RatioColumn {
    x_prev: DVec3,
    e: DVec3,
    b: DVec3,
    eb: f64,
}

impl RatioColumn {
    /// The constants of column j (1 … M−1).
    #[inline(always)]
    pub(crate) fn new(dx: &SweptDirectrix, j: usize) -> Self {
        let (e, b) = (dx.edges[j], dx.bisectors[j]);
        Self {
            x_prev: dx.points[j - 1],
            e,
            b,
            eb: e.dot(b),
        }
    }
}

/// The construction planes of [`LANES`](super::lanes::LANES) rows at one column (see
/// [`ratio_planes`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct RatioPlanes {
    /// Unit normals.
    pub p: V3,
    /// The support plane is undefined (G_{i,j−1} on the line of the edge, elsewhere than X_{j−1}).
    pub degenerate: M,
    /// The plane can be used: the support plane is defined and the plane does not (nearly) contain
    /// the edge (`P·ê > EDGE_PLANE`).
    pub usable: M,
}

impl RatioPlanes {
    /// Lane `l`'s normal, or its typed error (row i, column j).
    pub(crate) fn get(&self, l: usize, row: usize, column: usize) -> Result<DVec3, GeometryError> {
        if self.degenerate.get(l) {
            Err(GeometryError::DegenerateSupport { row, column })
        } else if !self.usable.get(l) {
            Err(GeometryError::PlaneContainsEdge {
                row: Some(row),
                column,
            })
        } else {
            Ok(self.p.lane(l))
        }
    }
}

/// Hot path of the ratio construction: the unit normals of Π_{i,j} for
/// [`LANES`](super::lanes::LANES) rows at once, from `g = G_{i,j−1}` and the ratios `r` (equal to
/// `SupportFrame::new(..).ratio_normal(b, r)` up to rounding), branch-free per row. `inv_scale`
/// (1 / design size) keeps the magnitudes near 1 at any scale. The frame's `w` is `perp / |perp|`
/// with `perp` the part of `G_{i,j−1} − X_{j−1}` perpendicular to ê, and
/// `(cos θ_b, sin θ_b) ∝ (−w·b, ê·b)`. r = ½ uses the bisecting ruling without trigonometry (the
/// trigonometry is skipped when no row needs it).
///
/// When `G_{i,j−1} = X_{j−1}` (a generatrix vertex on the directrix, e.g. a wall standing on it)
/// the support plane is undefined but the vertex is not: the step runs along the directrix edge and
/// meets any plane through X_j at X_j, so the Monge plane is used.
#[inline(always)]
pub(crate) fn ratio_planes(col: &RatioColumn, g: &V3, r: F, inv_scale: f64) -> RatioPlanes {
    let (e, b) = (V3::splat(col.e), V3::splat(col.b));
    let d = (*g - V3::splat(col.x_prev)) * inv_scale;
    let d_max = d.abs().max_element();
    let perp = d - e * d.dot(e);
    let n2 = perp.dot(perp);
    let inv_len = F::splat(1.0) / n2.sqrt();
    // −w·b and ê·b.
    let wb = -(perp.dot(b) * inv_len);
    let eb = F::splat(col.eb);
    let on_directrix = d_max.le(F::splat(tolerance::FRAME));
    // (An infinite |perp|² gives inv_len = 0, a NaN one a NaN: both fail `inv_len > 0`.)
    let degenerate = !on_directrix
        & (!perp.abs().max_element().gt(d_max * tolerance::FRAME) | !inv_len.gt(F::splat(0.0)));
    let half = r.eq(F::splat(0.5));
    let (s, c) = if half.all() {
        bisector_sin_cos(eb, wb)
    } else if !half.any() {
        ratio_sin_cos(r, eb, wb)
    } else {
        let ((s0, c0), (s1, c1)) = (bisector_sin_cos(eb, wb), ratio_sin_cos(r, eb, wb));
        (F::select(half, s0, s1), F::select(half, c0, c1))
    };
    // P = sin θ ê − cos θ w; the Monge plane for a vertex on the directrix (rare: tested first).
    let mut p = e * s - perp * (c * inv_len);
    if on_directrix.any() {
        p = V3::select(on_directrix, b, p);
    }
    RatioPlanes {
        p,
        degenerate,
        usable: !degenerate & p.dot(e).gt(F::splat(tolerance::EDGE_PLANE)),
    }
}

/// (sin θ_b, cos θ_b) from `(eb, wb) ∝ (sin θ_b, cos θ_b)` without trigonometry (r = ½).
#[inline(always)]
fn bisector_sin_cos(eb: F, wb: F) -> (F, F) {
    let h = F::splat(1.0) / (eb * eb + wb * wb).sqrt();
    (eb * h, wb * h)
}

/// (sin θ, cos θ) for ratios r, with θ_b = atan2(eb, wb).
#[inline(always)]
fn ratio_sin_cos(r: F, eb: F, wb: F) -> (F, F) {
    trig::sin_cos_upper(ratio_to_angle_lanes(r, trig::atan2_upper(eb, wb)))
}

/// [`ratio_to_angle`] per lane.
#[inline(always)]
fn ratio_to_angle_lanes(r: F, theta_b: F) -> F {
    let low = r * 2.0 * theta_b;
    let high = theta_b + (r * 2.0 - 1.0) * (F::splat(PI) - theta_b);
    F::select(r.le(F::splat(0.5)), low, high)
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
    fn lane_planes_match_the_support_frame() {
        use super::super::lanes::LANES;
        let dx = SweptDirectrix::new(&crate::Polyline::open(vec![
            DVec3::ZERO,
            DVec3::new(1.0, 0.2, 0.1),
            DVec3::new(1.8, 1.0, 0.3),
        ]))
        .unwrap();
        let col = RatioColumn::new(&dx, 1);
        let mut state = 3u64;
        let mut rnd = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for trial in 0..500 {
            let (mut g, mut r) = (V3::ZERO, F::splat(0.5));
            for l in 0..LANES {
                let q = DVec3::new(rnd() - 0.5, rnd() + 0.1, rnd() - 0.5) * 3.0;
                g.set_lane(l, q);
                // Mixed lanes, all-½ and no-½ groups.
                r.0[l] = match trial % 3 {
                    0 if l % 3 == 0 => 0.5,
                    1 => 0.5,
                    _ => 0.02 + 0.96 * rnd(),
                };
            }
            let planes = ratio_planes(&col, &g, r, 0.7);
            for l in 0..LANES {
                let frame = SupportFrame::new(dx.points[0], dx.edges[1], g.lane(l), 0, 1).unwrap();
                let expected = frame.ratio_normal(dx.bisectors[1], r.0[l]);
                let p = planes.p.lane(l);
                assert!((p - expected).length() < 1e-14, "{p} vs {expected}");
                assert!(planes.usable.get(l) && !planes.degenerate.get(l));
            }
        }
        // Lane 0 on the directrix point X_0 (Monge plane), lane 1 on the line of the edge
        // (undefined support plane), lane 2 with r = 0 (the plane contains the edge).
        let mut g = V3::splat(DVec3::new(0.2, 1.0, 0.3));
        g.set_lane(0, DVec3::ZERO);
        g.set_lane(1, dx.edges[1] * -2.0);
        let mut r = F::splat(0.3);
        r.0[2] = 0.0;
        let planes = ratio_planes(&col, &g, r, 1.0);
        assert_eq!(planes.get(0, 0, 1), Ok(dx.bisectors[1]));
        assert_eq!(
            planes.get(1, 4, 1),
            Err(GeometryError::DegenerateSupport { row: 4, column: 1 })
        );
        assert_eq!(
            planes.get(2, 5, 1),
            Err(GeometryError::PlaneContainsEdge {
                row: Some(5),
                column: 1
            })
        );
        assert!(planes.get(3, 0, 1).is_ok());
    }

    #[test]
    fn frame_rejects_point_on_edge_line() {
        assert_eq!(
            SupportFrame::new(DVec3::ZERO, DVec3::X, DVec3::new(3.0, 0.0, 0.0), 4, 2),
            Err(GeometryError::DegenerateSupport { row: 4, column: 2 })
        );
    }
}
