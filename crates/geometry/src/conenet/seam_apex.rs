//! A net continuing another across a shared row (the seam): its first strip's apex set to the
//! previous net's last apex, so the directrix-direction edges run straight across the seam.
//!
//! The first strip's apex is C_0 = (X_1 − a_1 X_0) / (1 − a_1), on the line of the first directrix
//! edge; C_0 = C exactly when C − X_1 = a_1 (C − X_0). When the directrix turns at the seam, C is
//! off that line and no a_1 reaches it: a_1 is the least-squares value
//! a_1 = (C − X_1)·(C − X_0) / |C − X_0|², and [`SeamApex::offset`] says how far C is from the line.

use glam::DVec3;

use crate::GeometryError;

/// The apex value a_1 for a shared apex, and how far from possible it is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeamApex {
    /// a_1 (the least-squares value when the apex is off the first edge's line).
    pub value: f64,
    /// The distance from the shared apex to the line of the first directrix edge (0: the rows
    /// continue straight across the seam).
    pub offset: f64,
}

/// The a_1 that puts the first strip's apex at `apex`, for the first directrix edge `x0 → x1`.
pub fn seam_apex(x0: DVec3, x1: DVec3, apex: DVec3) -> Result<SeamApex, GeometryError> {
    let (u, v) = (apex - x1, apex - x0);
    let vv = v.length_squared();
    if !(vv > 0.0) || !apex.is_finite() {
        return Err(GeometryError::Degenerate(format!(
            "the shared apex {apex} lies on the directrix's first vertex: no apex value reaches it"
        )));
    }
    let value = u.dot(v) / vv;
    let edge = (x1 - x0).normalize_or_zero();
    let offset = (v - edge * v.dot(edge)).length();
    Ok(SeamApex { value, offset })
}

/// The cotangents of a_1's inputs for a cotangent `g` of a_1: (∂/∂X_0, ∂/∂X_1, ∂/∂C).
pub(crate) fn seam_apex_pullback(x0: DVec3, x1: DVec3, apex: DVec3, g: f64) -> [DVec3; 3] {
    let (u, v) = (apex - x1, apex - x0);
    let vv = v.length_squared();
    let a = u.dot(v) / vv;
    let du = v / vv;
    let dv = (u - 2.0 * a * v) / vv;
    [-dv * g, -du * g, (du + dv) * g]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::conenet::{ColumnValues, ConstructInputs, Reports, construct_with};
    use crate::{Polyline, QuadGrid};

    /// The largest angle between the last directrix-direction edge of `a` and the first of `b` in
    /// each row (`b` continuing `a` across its last column).
    fn crease(a: &QuadGrid, b: &QuadGrid) -> f64 {
        (0..a.rows)
            .map(|i| {
                let before = a.at(i, a.cols - 1) - a.at(i, a.cols - 2);
                let after = b.at(i, 1) - b.at(i, 0);
                // atan2 of |a × b| and a · b: acos near 1 resolves only about 1.5e-8 rad.
                before.cross(after).length().atan2(before.dot(after))
            })
            .fold(0.0, f64::max)
    }

    /// A first net along an arc with a varying apex function, and a directrix continuing its last
    /// edge (tangent, then bending the other way).
    fn first_net() -> (crate::ConeNet, Polyline) {
        let arc: Vec<DVec3> = (0..8)
            .map(|k| {
                let t = 0.12 * k as f64;
                DVec3::new(6.0 * t.sin(), 6.0 - 6.0 * t.cos(), 0.1 * k as f64)
            })
            .collect();
        let generatrix = Polyline::open(
            (0..5)
                .map(|i| DVec3::new(0.2 * i as f64, -0.5 - 0.1 * i as f64, 0.8 * i as f64))
                .collect(),
        );
        let mut inputs = ConstructInputs::new(Polyline::open(arc.clone()), generatrix);
        inputs.apex.values = ColumnValues::List(vec![0.97, 0.98, 1.02, 1.03, 0.99, 0.96, 1.01]);
        let a = construct_with(
            &inputs,
            Reports {
                apices: true,
                quality: true,
            },
        )
        .unwrap();
        let (p, q) = (arc[6], arc[7]);
        let e = q - p;
        let side = DVec3::new(-e.y, e.x, 0.0).normalize() * e.length();
        let next = vec![q, q + e, q + 2.0 * e - 0.2 * side, q + 3.0 * e - 0.6 * side];
        (a, Polyline::open(next))
    }

    #[test]
    fn a_continued_net_sharing_the_last_apex_runs_straight_across_the_seam() {
        let (a, directrix) = first_net();
        let generatrix = a.mesh.column(a.mesh.cols - 1);
        let apex = a
            .apices
            .last()
            .copied()
            .flatten()
            .expect("a finite last apex");
        let mut inputs = ConstructInputs::new(directrix.clone(), generatrix.clone());
        inputs.apex.seam = Some(apex);
        let b = construct_with(
            &inputs,
            Reports {
                apices: true,
                quality: true,
            },
        )
        .unwrap();
        let turn = crease(&a.mesh, &b.mesh);
        assert!(turn < 1e-9, "the rows turn by {turn} rad at the seam");
        let shared = b.apices[0].unwrap();
        assert!(shared.distance(apex) < 1e-9 * apex.length().max(1.0));
        assert!(b.quality.max_planarity < 1e-12);
        // The same net without the shared apex creases visibly.
        let plain = construct_with(
            &ConstructInputs::new(directrix, generatrix),
            Reports {
                apices: true,
                quality: true,
            },
        )
        .unwrap();
        let creased = crease(&a.mesh, &plain.mesh);
        assert!(creased > 1e-3, "without it: {creased} rad");
    }

    #[test]
    fn a_turning_directrix_reports_how_far_the_apex_is_from_reach() {
        let (a, directrix) = first_net();
        let apex = a.apices.last().copied().flatten().unwrap();
        let mut turned = directrix.points.clone();
        turned[1] += DVec3::new(0.0, 0.0, 0.3);
        let s = seam_apex(turned[0], turned[1], apex).unwrap();
        assert!(s.offset > 1e-3, "{s:?}");
        let straight = seam_apex(directrix.points[0], directrix.points[1], apex).unwrap();
        assert!(straight.offset < 1e-9 * apex.length(), "{straight:?}");
    }

    #[test]
    fn the_value_puts_the_apex_back_where_it_was() {
        let (x0, x1) = (DVec3::new(0.0, 0.0, 0.0), DVec3::new(2.0, 0.0, 0.0));
        for a in [0.5, 0.9, 1.3, 2.0, -0.5] {
            let c = (x1 - a * x0) / (1.0 - a);
            let s = seam_apex(x0, x1, c).unwrap();
            assert!((s.value - a).abs() < 1e-12, "{a}: {s:?}");
            assert!(s.offset < 1e-12);
        }
        let off = seam_apex(x0, x1, DVec3::new(4.0, 0.5, 0.0)).unwrap();
        assert!((off.offset - 0.5).abs() < 1e-12);
        assert!(seam_apex(x0, x1, x0).is_err());
    }

    #[test]
    fn the_pullback_matches_central_differences() {
        let (x0, x1, c) = (
            DVec3::new(0.1, -0.2, 0.3),
            DVec3::new(1.7, 0.4, -0.1),
            DVec3::new(5.0, 1.9, 0.7),
        );
        let f = |x0: DVec3, x1: DVec3, c: DVec3| seam_apex(x0, x1, c).unwrap().value;
        let bars = seam_apex_pullback(x0, x1, c, 1.0);
        let h = 1e-6;
        for (k, bar) in bars.iter().enumerate() {
            for axis in 0..3 {
                let mut d = DVec3::ZERO;
                d[axis] = h;
                let shift = |s: DVec3| match k {
                    0 => f(x0 + s, x1, c),
                    1 => f(x0, x1 + s, c),
                    _ => f(x0, x1, c + s),
                };
                let fd = (shift(d) - shift(-d)) / (2.0 * h);
                assert!(
                    (fd - bar[axis]).abs() < 1e-8,
                    "{k} {axis}: {fd} vs {}",
                    bar[axis]
                );
            }
        }
    }
}
