//! The validated inputs common to every construction ([`prepare`], [`Prepared`]), the design size
//! ([`extent`]) and the construction step itself ([`step`], paper Sec. 3.2, notes §2):
//! `V = a_j (G_{i,j−1} − X_{j−1}) + X_j − G_{i,j−1}`,
//! `d = ((X_j − G_{i,j−1}) · P_{i,j}) / (V · P_{i,j})`, `G_{i,j} = G_{i,j−1} + d V`.

use glam::DVec3;

use super::directrix::SweptDirectrix;
use super::inputs::{ApexInput, EndPlanes};
use super::normalize::resolve_apex;
use super::tolerance;
use crate::{GeometryError, Polyline};

/// One construction step: G_{i,j} from `g = G_{i,j−1}`, `x0 = X_{j−1}`, `x1 = X_j`, `a = a_j` and a
/// normal `p` of Π_{i,j} (any length). `None` when `|V·P| ≤ 3·10⁻¹² |V|_∞ |P|_∞` (between 1e-12 and
/// 3e-12 times |V||P|: V parallel to the plane, or V = 0 because g is the cone apex): the caller
/// reports the offending (i, j). The bound uses max-norms so it neither overflows nor underflows.
#[inline(always)]
pub fn step(g: DVec3, x0: DVec3, x1: DVec3, a: f64, p: DVec3) -> Option<DVec3> {
    let v = (g - x0) * a + x1 - g;
    let vp = v.dot(p);
    let bound = 3.0 * tolerance::PARALLEL * v.abs().max_element() * p.abs().max_element();
    if !(vp.abs() > bound) {
        return None;
    }
    Some(g + v * ((x1 - g).dot(p) / vp))
}

/// Validated inputs common to every construction.
#[derive(Clone)]
pub(crate) struct Prepared {
    pub dx: SweptDirectrix,
    pub generatrix: Vec<DVec3>,
    pub wrap_rows: bool,
    pub apex: Vec<f64>,
    /// The design's size (largest coordinate extent of directrix and generatrix), > 0.
    pub scale: f64,
}

/// Validates directrix, generatrix and apex (in this order) and resolves the apex values; `end`
/// chooses the bisecting plane at an open directrix's last vertex.
pub(crate) fn prepare(
    directrix: &Polyline,
    generatrix: &Polyline,
    apex: &ApexInput,
    end: EndPlanes,
) -> Result<Prepared, GeometryError> {
    let dx = SweptDirectrix::with_end_planes(directrix, end)?;
    generatrix.validate("generatrix", 2)?;
    let apex = resolve_apex(apex, &dx)?;
    let scale = extent(dx.points.iter().chain(&generatrix.points).copied());
    Ok(Prepared {
        dx,
        generatrix: generatrix.points.clone(),
        wrap_rows: generatrix.closed,
        apex,
        scale,
    })
}

/// The largest coordinate extent of a point set (∞-norm of the bounding box), computed without
/// overflow; 1 for an empty or degenerate set.
pub(crate) fn extent(points: impl Iterator<Item = DVec3>) -> f64 {
    let (lo, hi) = points.fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
        (lo.min(p), hi.max(p))
    });
    let half = (hi * 0.5 - lo * 0.5).max_element();
    if half > 0.0 && half.is_finite() {
        (2.0 * half).min(f64::MAX)
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn step_hits_the_plane_along_the_scaling_direction() {
        let (x0, x1) = (DVec3::ZERO, DVec3::X);
        let g = DVec3::new(0.0, 1.0, 0.0);
        // a = 0.5: apex C = (2, 0, 0); plane x = 1 ⇒ G = (1, 0.5, 0).
        assert_eq!(
            step(g, x0, x1, 0.5, DVec3::X),
            Some(DVec3::new(1.0, 0.5, 0.0))
        );
        // V parallel to the plane.
        assert_eq!(step(g, x0, x1, 1.0, DVec3::Y), None);
        // g is the apex: V = 0.
        assert_eq!(step(DVec3::new(2.0, 0.0, 0.0), x0, x1, 0.5, DVec3::X), None);
    }
}
