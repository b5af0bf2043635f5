//! Flattening of the curved segments of vector drawings into points: quadratic and cubic Bézier
//! curves and elliptical arcs given SVG-style by their end points (SVG 1.1 appendix F.6). Used by the
//! SVG reader; the maths is here, the path syntax there.
//!
//! Each flattening returns the points after the start point, evenly spaced in the curve parameter,
//! the last one exactly the end point: `segments` points (none for `segments` = 0). Inputs are
//! finite (the callers check); the functions never panic.

use std::f64::consts::TAU;

use glam::DVec2;

/// The cubic Bézier curve with control points `p0 … p3` at parameter `t` (Bernstein form).
#[inline]
pub fn cubic_bezier(p0: DVec2, p1: DVec2, p2: DVec2, p3: DVec2, t: f64) -> DVec2 {
    let s = 1.0 - t;
    p0 * (s * s * s) + p1 * (3.0 * s * s * t) + p2 * (3.0 * s * t * t) + p3 * (t * t * t)
}

/// The quadratic Bézier curve with control points `p0 … p2` at parameter `t`.
#[inline]
pub fn quadratic_bezier(p0: DVec2, p1: DVec2, p2: DVec2, t: f64) -> DVec2 {
    let s = 1.0 - t;
    p0 * (s * s) + p1 * (2.0 * s * t) + p2 * (t * t)
}

/// `segments` points of the cubic Bézier curve `p0 … p3` after `p0`, at t = k / segments; the last is
/// `p3` exactly.
pub fn flatten_cubic(p0: DVec2, p1: DVec2, p2: DVec2, p3: DVec2, segments: usize) -> Vec<DVec2> {
    (1..=segments)
        .map(|k| {
            if k == segments {
                p3
            } else {
                cubic_bezier(p0, p1, p2, p3, k as f64 / segments as f64)
            }
        })
        .collect()
}

/// `segments` points of the quadratic Bézier curve `p0 … p2` after `p0`; the last is `p2` exactly.
pub fn flatten_quadratic(p0: DVec2, p1: DVec2, p2: DVec2, segments: usize) -> Vec<DVec2> {
    (1..=segments)
        .map(|k| {
            if k == segments {
                p2
            } else {
                quadratic_bezier(p0, p1, p2, k as f64 / segments as f64)
            }
        })
        .collect()
}

/// Points of the elliptical arc from `p1` to `p2` (excluding `p1`) with `radii`, the ellipse's x axis
/// turned by `rotation` degrees, and the SVG flags `large` (the arc spans more than 180°) and `sweep`
/// (positive angle direction), by the endpoint-to-centre conversion of the SVG specification
/// (appendix F.6.5/F.6.6; radii too small for the end points are scaled up, F.6.6). Equal end points
/// give no points; a zero radius a straight segment (the end point alone).
pub fn elliptical_arc(
    p1: DVec2,
    radii: DVec2,
    rotation: f64,
    large: bool,
    sweep: bool,
    p2: DVec2,
    segments: usize,
) -> Vec<DVec2> {
    if p1 == p2 {
        return Vec::new();
    }
    let (mut rx, mut ry) = (radii.x.abs(), radii.y.abs());
    if rx == 0.0 || ry == 0.0 {
        return vec![p2];
    }
    let (s, c) = rotation.to_radians().sin_cos();
    let d = (p1 - p2) * 0.5;
    let x1 = c * d.x + s * d.y;
    let y1 = -s * d.x + c * d.y;
    let lambda = (x1 * x1) / (rx * rx) + (y1 * y1) / (ry * ry);
    if lambda > 1.0 {
        rx *= lambda.sqrt();
        ry *= lambda.sqrt();
    }
    let num = rx * rx * ry * ry - rx * rx * y1 * y1 - ry * ry * x1 * x1;
    let den = rx * rx * y1 * y1 + ry * ry * x1 * x1;
    let mut coef = (num / den).max(0.0).sqrt();
    if large == sweep {
        coef = -coef;
    }
    let cxp = coef * rx * y1 / ry;
    let cyp = -coef * ry * x1 / rx;
    let mid = (p1 + p2) * 0.5;
    let centre = DVec2::new(c * cxp - s * cyp + mid.x, s * cxp + c * cyp + mid.y);
    let angle = |u: DVec2, v: DVec2| (u.x * v.y - u.y * v.x).atan2(u.dot(v));
    let u = DVec2::new((x1 - cxp) / rx, (y1 - cyp) / ry);
    let v = DVec2::new((-x1 - cxp) / rx, (-y1 - cyp) / ry);
    let theta1 = angle(DVec2::X, u);
    let mut dtheta = angle(u, v);
    if !sweep && dtheta > 0.0 {
        dtheta -= TAU;
    } else if sweep && dtheta < 0.0 {
        dtheta += TAU;
    }
    (1..=segments)
        .map(|k| {
            if k == segments {
                return p2;
            }
            let t = theta1 + dtheta * k as f64 / segments as f64;
            let (st, ct) = t.sin_cos();
            centre + DVec2::new(rx * ct * c - ry * st * s, rx * ct * s + ry * st * c)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn near(a: DVec2, b: DVec2) -> bool {
        a.distance(b) < 1e-12
    }

    #[test]
    fn beziers_hit_their_closed_forms_and_end_exactly() {
        // Quadratic (0,0) (1,2) (2,0) at t = ½: (1, 1).
        let q = flatten_quadratic(DVec2::ZERO, DVec2::new(1.0, 2.0), DVec2::new(2.0, 0.0), 4);
        assert_eq!(q.len(), 4);
        assert!(near(q[1], DVec2::new(1.0, 1.0)));
        assert_eq!(q[3], DVec2::new(2.0, 0.0));
        // Cubic (0,0) (0,1) (1,1) (1,0) at t = ½: (½, ¾).
        let (p0, p1, p2, p3) = (DVec2::ZERO, DVec2::Y, DVec2::ONE, DVec2::X);
        let c = flatten_cubic(p0, p1, p2, p3, 2);
        assert!(near(c[0], DVec2::new(0.5, 0.75)));
        assert_eq!(c[1], p3);
        assert!(flatten_cubic(p0, p1, p2, p3, 0).is_empty());
        // The curve ends are the end control points.
        assert_eq!(cubic_bezier(p0, p1, p2, p3, 0.0), p0);
        assert_eq!(quadratic_bezier(p0, p1, p2, 1.0), p2);
    }

    #[test]
    fn arcs_lie_on_their_ellipse_and_follow_the_flags() {
        let (a, b) = (DVec2::ZERO, DVec2::new(2.0, 0.0));
        // Half circle of radius 1 about (1, 0) from angle π to 2π (sweep: increasing angle), so
        // through (1, −1) at 3π/2; without sweep the other half, through (1, 1).
        let pts = elliptical_arc(a, DVec2::ONE, 0.0, false, true, b, 8);
        assert_eq!(pts.len(), 8);
        for p in &pts {
            assert!(((*p - DVec2::X).length() - 1.0).abs() < 1e-12);
        }
        assert!(near(pts[3], DVec2::new(1.0, -1.0)));
        assert_eq!(pts[7], b);
        let other = elliptical_arc(a, DVec2::ONE, 0.0, false, false, b, 8);
        assert!(near(other[3], DVec2::new(1.0, 1.0)));
        // Radii too small are scaled up to the half circle.
        let scaled = elliptical_arc(a, DVec2::splat(0.1), 0.0, false, true, b, 8);
        assert!(near(scaled[3], DVec2::new(1.0, -1.0)));
        // A rotated ellipse (radii 2, 1, turned 90°) through (0,0) and (0,4): its centre (0, 2).
        let e = elliptical_arc(
            a,
            DVec2::new(2.0, 1.0),
            90.0,
            false,
            true,
            DVec2::new(0.0, 4.0),
            16,
        );
        for p in &e {
            let q = *p - DVec2::new(0.0, 2.0);
            assert!(
                ((q.y / 2.0).powi(2) + q.x.powi(2) - 1.0).abs() < 1e-12,
                "{p}"
            );
        }
        // Degenerate arcs.
        assert!(elliptical_arc(a, DVec2::ONE, 0.0, false, true, a, 8).is_empty());
        assert_eq!(
            elliptical_arc(a, DVec2::new(0.0, 1.0), 0.0, false, true, b, 8),
            vec![b]
        );
    }
}
