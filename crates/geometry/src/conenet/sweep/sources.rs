//! Plane sources: where a row gets its construction planes from — given planes (shared or per
//! row), ratio planes computed as the row advances (with the inline plane fix), or the coplanar
//! shared plane built from support strip 0.

use glam::DVec3;

use super::super::coplanar::PlanePencil;
use super::super::correction::{Correction, CorrectionKind};
use super::super::directrix::SweptDirectrix;
use super::super::lanes::{F, LANES, M, V3};
use super::super::ratios::{
    RatioColumn, SupportFrame, angle_to_ratio, ratio_planes, ratio_to_angle,
};
use super::super::tolerance;
use super::batch::Slot;
use crate::GeometryError;

/// Where a row gets its planes from.
pub(super) trait PlaneSource {
    /// The plane for building column `jn` from `g = G_{i,jn−1}`.
    fn plane(&mut self, jn: usize, g: DVec3) -> Result<DVec3, GeometryError>;
    /// The stored (final) plane of column `j`.
    fn stored(&self, j: usize) -> DVec3;
    /// Stores the final plane of column `j`.
    fn store(&mut self, j: usize, p: DVec3);
    /// Eq. 2 fails at step j (vertex G_{i,j} = `g` against the plane `p` of column j + 1): a
    /// row-local fix (new plane) or `None` when the fix couples the rows.
    fn fix_inline(&mut self, j: usize, g: DVec3, p: DVec3) -> Result<Option<DVec3>, GeometryError>;
    /// The planes for building column `jn` of a batch of rows (lane l is row `slots[l]`) from the
    /// lanes `g` = G_{·,jn−1}, with the mask of the lanes whose plane can be used; for the others
    /// [`PlaneSource::plane`] gives the error. Lanes of ended rows and lanes beyond the batch may
    /// hold anything.
    #[inline(always)]
    fn planes(slots: &mut [Slot<'_, Self>], jn: usize, g: &V3) -> (V3, M)
    where
        Self: Sized,
    {
        let mut p = *g;
        let mut ok = M::splat(false);
        for (l, s) in slots.iter_mut().enumerate() {
            if s.end.is_none()
                && let Ok(q) = s.src.plane(jn, g.lane(l))
            {
                p.set_lane(l, q);
                ok.set(l, true);
            }
        }
        (p, ok)
    }
}

/// Planes given beforehand, read only: the planes shared by every row, or one row's planes (given
/// per-vertex normals).
pub(super) struct ReadOnly<'p>(pub(super) &'p [DVec3]);

impl PlaneSource for ReadOnly<'_> {
    #[inline]
    fn plane(&mut self, jn: usize, _: DVec3) -> Result<DVec3, GeometryError> {
        Ok(self.0[jn - 1])
    }
    #[inline]
    fn stored(&self, j: usize) -> DVec3 {
        self.0[j - 1]
    }
    #[inline]
    fn store(&mut self, _: usize, _: DVec3) {}
    fn fix_inline(&mut self, _: usize, _: DVec3, _: DVec3) -> Result<Option<DVec3>, GeometryError> {
        Ok(None)
    }
}

/// Ratio planes of one row, computed and stored as the row advances.
pub(super) struct RatioRow<'p> {
    pub(super) i: usize,
    pub(super) dx: &'p SweptDirectrix,
    /// The row's ratios (entry j − 1 is column j).
    pub(super) ratios: &'p [f64],
    pub(super) planes: &'p mut [DVec3],
    pub(super) inv_scale: f64,
    /// α: 0 (planes only) or 1 (apex-like fixes only); negative: off.
    pub(super) alpha: f64,
    pub(super) epsilon: f64,
    /// Inline plane fixes: (step, record, turn |Δθ| of the plane).
    pub(super) fixes: Vec<(usize, Correction, f64)>,
}

impl PlaneSource for RatioRow<'_> {
    fn plane(&mut self, jn: usize, g: DVec3) -> Result<DVec3, GeometryError> {
        let col = RatioColumn::new(self.dx, jn);
        let r = F::splat(self.ratios[jn - 1]);
        ratio_planes(&col, &V3::splat(g), r, self.inv_scale).get(0, self.i, jn)
    }
    #[inline]
    fn stored(&self, j: usize) -> DVec3 {
        self.planes[j - 1]
    }
    #[inline(always)]
    fn store(&mut self, j: usize, p: DVec3) {
        self.planes[j - 1] = p;
    }
    fn fix_inline(&mut self, j: usize, g: DVec3, _: DVec3) -> Result<Option<DVec3>, GeometryError> {
        let jn = j + 1;
        if self.alpha >= 1.0 {
            // Apex-like fixes only: they couple the rows (a stop).
            return Ok(None);
        }
        // Plane fix: θ goes to (1 − ε) φ. It is row-local; only when the row is still bad (rounding)
        // does the coupled fix (a stop) follow, and the coupled step then redoes this column.
        let dx = self.dx;
        let frame = SupportFrame::new(dx.points[j], dx.edges[jn], g, self.i, jn)?;
        let theta_b = frame.bisector_angle(dx.bisectors[jn]);
        let r_old = self.ratios[jn - 1];
        let theta = (1.0 - self.epsilon) * frame.angle_of(g, dx.points[jn]);
        let p = frame.normal(theta);
        if !(p.dot(frame.e) > tolerance::EDGE_PLANE) {
            return Err(GeometryError::PlaneContainsEdge {
                row: Some(self.i),
                column: jn,
            });
        }
        if !((dx.points[jn] - g).dot(p) > 0.0) {
            return Ok(None);
        }
        self.fixes.push((
            j,
            Correction {
                kind: CorrectionKind::Ratio,
                column: jn,
                row: Some(self.i),
                old: r_old,
                new: angle_to_ratio(theta, theta_b),
            },
            (theta - ratio_to_angle(r_old, theta_b)).abs(),
        ));
        Ok(Some(p))
    }

    #[inline(always)]
    fn planes(slots: &mut [Slot<'_, Self>], jn: usize, g: &V3) -> (V3, M) {
        let last = slots.len() - 1;
        let mut r = F::splat(0.5);
        for l in 0..LANES {
            r.0[l] = slots[l.min(last)].src.ratios[jn - 1];
        }
        let src = &slots[0].src;
        let planes = ratio_planes(&RatioColumn::new(src.dx, jn), g, r, src.inv_scale);
        (planes.p, planes.usable)
    }
}

/// Coplanar mode, row 0: computes the shared plane of every column from support strip 0.
pub(super) struct CoplanarRow0<'p> {
    pub(super) dx: &'p SweptDirectrix,
    pub(super) rho: &'p [f64],
    pub(super) tau: &'p [f64],
    pub(super) planes: &'p mut [DVec3],
    pub(super) psi: &'p mut [f64],
}

impl PlaneSource for CoplanarRow0<'_> {
    fn plane(&mut self, jn: usize, g: DVec3) -> Result<DVec3, GeometryError> {
        let dx = self.dx;
        let frame = SupportFrame::new(dx.points[jn - 1], dx.edges[jn], g, 0, jn)?;
        let pencil = PlanePencil::new(
            &frame,
            dx.bisectors[jn],
            self.rho[jn - 1],
            dx.outgoing[jn],
            jn,
        )?;
        let psi = self.tau[jn - 1] * pencil.psi_out;
        let p = pencil.normal(psi);
        if !(p.dot(frame.e) > tolerance::EDGE_PLANE) {
            return Err(GeometryError::PlaneContainsEdge {
                row: None,
                column: jn,
            });
        }
        self.psi[jn] = psi;
        Ok(p)
    }
    #[inline]
    fn stored(&self, j: usize) -> DVec3 {
        self.planes[j - 1]
    }
    #[inline]
    fn store(&mut self, j: usize, p: DVec3) {
        self.planes[j - 1] = p;
    }
    fn fix_inline(&mut self, _: usize, _: DVec3, _: DVec3) -> Result<Option<DVec3>, GeometryError> {
        Ok(None)
    }
}
