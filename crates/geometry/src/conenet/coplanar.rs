//! The coplanar variant (CNets Construct Coplanar, notes §4): one plane per column, turned about the
//! ruling R_{0,j} of support strip 0.
//!
//! `n_in = unit(R × ê_j)` (flipped so that `n_in · ê_{j+1} ≥ 0`), `u = unit(ê_j − (ê_j·R) R)`, and the
//! candidate normals are `P(ψ) = cos ψ n_in + sin ψ u`. `ψ_out ∈ (0, π]` makes the plane contain the
//! outgoing edge; the rotation ratio τ gives ψ = τ ψ_out.

use std::f64::consts::PI;

use glam::DVec3;

use super::ratios::{SupportFrame, ratio_to_angle};
use super::tolerance;
use crate::GeometryError;

/// The one-parameter family of planes through the ruling R_{0,j} at one column.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanePencil {
    /// The ruling R_{0,j} (unit).
    pub ruling: DVec3,
    /// `n_in`: the normal of the plane through R containing the incoming edge (ψ = 0).
    pub n_in: DVec3,
    /// `u`: the in-pencil direction towards ê_j (ψ = π/2).
    pub u: DVec3,
    /// ψ_out ∈ (0, π]: the plane containing the outgoing edge.
    pub psi_out: f64,
}

impl PlanePencil {
    /// The pencil at column j from the frame of support strip 0, the Monge normal `b` at X_j, the
    /// ruling ratio ρ and the outgoing unit edge. Fails (naming column j) when the ruling runs along
    /// the incoming edge (ρ = 0 or 1): every plane of the pencil would contain that edge.
    pub fn new(
        frame: &SupportFrame,
        b: DVec3,
        rho: f64,
        outgoing: DVec3,
        column: usize,
    ) -> Result<Self, GeometryError> {
        let theta = ratio_to_angle(rho, frame.bisector_angle(b));
        let ruling = frame.ruling(theta);
        let e = frame.e;
        // R × ê = sin θ (w × ê): for θ ∈ (0, π) this is the normal of the support plane.
        let mut n_in = frame.w.cross(e);
        let along = n_in.dot(outgoing);
        // Flip so that n_in · ê_{j+1} ≥ 0. When the outgoing edge lies in the support plane (within
        // tolerance) the flip is ill-defined; keep w × ê and take ψ_out = π (notes silent, see docs).
        let in_plane = along.abs() <= tolerance::COPLANAR_TIE;
        if !in_plane && along < 0.0 {
            n_in = -n_in;
        }
        let u_raw = e - ruling * e.dot(ruling);
        let u_len = u_raw.length();
        if !(u_len > tolerance::EDGE_PLANE) {
            return Err(GeometryError::PlaneContainsEdge { row: None, column });
        }
        let u = u_raw / u_len;
        let mut psi_out = if in_plane {
            PI
        } else {
            n_in.dot(outgoing).atan2(-u.dot(outgoing))
        };
        if psi_out <= 0.0 {
            psi_out = PI;
        }
        Ok(Self {
            ruling,
            n_in,
            u,
            psi_out,
        })
    }

    /// The normal at rotation ψ.
    #[inline]
    pub fn normal(&self, psi: f64) -> DVec3 {
        let (s, c) = psi.sin_cos();
        self.n_in * c + self.u * s
    }

    /// The normal for rotation ratio τ (ψ = τ ψ_out).
    #[inline]
    pub fn normal_for_ratio(&self, tau: f64) -> DVec3 {
        self.normal(tau * self.psi_out)
    }

    /// The interval of ψ in `[ε ψ_out, (1 − ε) ψ_out]` for which every `q` (q_i = X_{j+1} − G_{i,j})
    /// satisfies `q · P(ψ) ≥ ε |q|` (Eq. 2 with margin ε); `None` when empty. Exact: each constraint
    /// `A cos ψ + B sin ψ ≥ m` is an arc shorter than π, so the intersection is one interval.
    pub fn feasible(&self, qs: impl Iterator<Item = DVec3>, epsilon: f64) -> Option<(f64, f64)> {
        let mut lo = epsilon * self.psi_out;
        let mut hi = (1.0 - epsilon) * self.psi_out;
        for q in qs {
            let (a, b) = (q.dot(self.n_in), q.dot(self.u));
            let r = (a * a + b * b).sqrt();
            let m = epsilon * q.length();
            if !(r > m) {
                return None;
            }
            let half = (m / r).acos();
            let center = b.atan2(a);
            // Arc [center − half, center + half]; bring it into position around [0, ψ_out].
            let start = (center - half).rem_euclid(2.0 * PI);
            let end = start + 2.0 * half;
            // The arc is shorter than π and [lo, hi] ⊂ (0, π]: when it wraps past 2π only its
            // shifted copy can meet [lo, hi].
            let (s0, e0) = if end > 2.0 * PI {
                (start - 2.0 * PI, end - 2.0 * PI)
            } else {
                (start, end)
            };
            lo = lo.max(s0);
            hi = hi.min(e0);
            if lo > hi {
                return None;
            }
        }
        Some((lo, hi))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pencil() -> PlanePencil {
        let frame =
            SupportFrame::new(DVec3::ZERO, DVec3::X, DVec3::new(0.2, 1.0, 0.3), 0, 1).unwrap();
        let out = DVec3::new(1.0, 0.2, 0.6).normalize();
        let b = (DVec3::X + out).normalize();
        PlanePencil::new(&frame, b, 0.5, out, 1).unwrap()
    }

    #[test]
    fn half_half_is_the_bisecting_plane_and_corners_contain_edges() {
        let out = DVec3::new(1.0, 0.2, 0.6).normalize();
        let b = (DVec3::X + out).normalize();
        let p = pencil();
        assert!((p.normal_for_ratio(0.5) - b).length() < 1e-14);
        assert!(p.normal_for_ratio(1.0).dot(out).abs() < 1e-14);
        assert!(p.normal_for_ratio(0.0).dot(DVec3::X).abs() < 1e-14);
        for t in [0.0, 0.3, 0.5, 1.0] {
            assert!(p.normal_for_ratio(t).dot(p.ruling).abs() < 1e-14);
        }
    }

    #[test]
    fn feasible_interval_satisfies_every_constraint_and_is_tight() {
        let p = pencil();
        let qs = [
            DVec3::new(1.0, -0.5, 0.2),
            DVec3::new(0.4, 0.1, -0.9),
            DVec3::new(0.8, 0.8, 0.1),
        ];
        let eps = 0.01;
        let (lo, hi) = p.feasible(qs.iter().copied(), eps).expect("feasible");
        for psi in [lo, 0.5 * (lo + hi), hi] {
            for q in qs {
                assert!(q.dot(p.normal(psi)) >= eps * q.length() - 1e-12);
            }
        }
        // Just outside the interval some constraint (or the ψ range) is violated.
        for psi in [lo - 1e-6, hi + 1e-6] {
            let range_ok = psi >= eps * p.psi_out && psi <= (1.0 - eps) * p.psi_out;
            let all = qs.iter().all(|q| q.dot(p.normal(psi)) >= eps * q.length());
            assert!(!(range_ok && all));
        }
        assert!(
            p.feasible(
                [DVec3::new(0.0, 0.0, 1.0), DVec3::new(0.0, 0.0, -1.0)].into_iter(),
                eps
            )
            .is_none()
        );
    }
}
