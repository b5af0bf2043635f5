//! Non-uniform rational B-splines (NURBS), evaluated by de Boor's algorithm — the curves CAD files
//! store (DXF `SPLINE`).

use glam::DVec3;

use crate::GeometryError;

/// A NURBS curve: degree, knot vector (`control.len() + degree + 1` non-decreasing knots) and
/// control points with weights (all 1 when empty).
#[derive(Debug, Clone, PartialEq)]
pub struct Nurbs {
    /// Polynomial degree (≥ 1).
    pub degree: usize,
    /// The knot vector.
    pub knots: Vec<f64>,
    /// Control points.
    pub control: Vec<DVec3>,
    /// Weights, one per control point (empty: non-rational).
    pub weights: Vec<f64>,
}

impl Nurbs {
    /// Checks the sizes, finiteness and order of the data.
    pub fn validate(&self) -> Result<(), GeometryError> {
        let n = self.control.len();
        let bad = |m: String| Err(GeometryError::Degenerate(m));
        if self.degree == 0 || self.degree > 32 {
            return bad(format!("spline degree {} is not 1 to 32", self.degree));
        }
        if n <= self.degree {
            return bad(format!(
                "a degree-{} spline needs at least {} control points, got {n}",
                self.degree,
                self.degree + 1
            ));
        }
        if self.knots.len() != n + self.degree + 1 {
            return bad(format!(
                "the spline has {} knots; {n} control points of degree {} need {}",
                self.knots.len(),
                self.degree,
                n + self.degree + 1
            ));
        }
        if self.knots.iter().any(|k| !k.is_finite()) || self.knots.windows(2).any(|w| w[0] > w[1]) {
            return bad("the spline's knots are not finite and non-decreasing".into());
        }
        if !self.weights.is_empty()
            && (self.weights.len() != n
                || self.weights.iter().any(|w| !(w.is_finite() && *w > 0.0)))
        {
            return bad("the spline's weights must be positive, one per control point".into());
        }
        crate::error::check_finite_points("spline control points", &self.control)?;
        if self.domain().1 <= self.domain().0 {
            return bad("the spline's knot span is empty".into());
        }
        Ok(())
    }

    /// The parameter range: knots `degree` … `len − degree − 1`.
    pub fn domain(&self) -> (f64, f64) {
        (
            self.knots[self.degree],
            self.knots[self.knots.len() - self.degree - 1],
        )
    }

    fn weight(&self, k: usize) -> f64 {
        self.weights.get(k).copied().unwrap_or(1.0)
    }

    /// The point at parameter `t` (clamped to the domain).
    pub fn point(&self, t: f64) -> DVec3 {
        let p = self.degree;
        let (lo, hi) = self.domain();
        let t = t.clamp(lo, hi);
        // The knot span: the last k with knots[k] <= t < knots[k + 1], within the domain.
        let n = self.control.len();
        let mut span = p;
        while span + 1 < n && self.knots[span + 1] <= t {
            span += 1;
        }
        // de Boor on homogeneous points (x·w, y·w, z·w, w).
        let mut d: Vec<(DVec3, f64)> = (0..=p)
            .map(|j| {
                let k = span - p + j;
                let w = self.weight(k);
                (self.control[k] * w, w)
            })
            .collect();
        for r in 1..=p {
            for j in (r..=p).rev() {
                let i = span - p + j;
                let denominator = self.knots[i + p + 1 - r] - self.knots[i];
                let alpha = if denominator > 0.0 {
                    (t - self.knots[i]) / denominator
                } else {
                    0.0
                };
                d[j] = (
                    d[j - 1].0 * (1.0 - alpha) + d[j].0 * alpha,
                    d[j - 1].1 * (1.0 - alpha) + d[j].1 * alpha,
                );
            }
        }
        d[p].0 / d[p].1
    }

    /// Points along the curve: `per_span` steps across every non-empty knot span, both ends
    /// included.
    pub fn sample(&self, per_span: usize) -> Result<Vec<DVec3>, GeometryError> {
        self.validate()?;
        let per_span = per_span.max(1);
        let (lo, hi) = self.domain();
        let mut breaks: Vec<f64> = self.knots[self.degree..self.knots.len() - self.degree].to_vec();
        breaks.dedup();
        let spans = breaks.len().saturating_sub(1);
        crate::curves::check_count("spline samples", spans * per_span + 1, 2)?;
        let mut points = Vec::with_capacity(spans * per_span + 1);
        for w in breaks.windows(2) {
            for s in 0..per_span {
                points.push(self.point(w[0] + (w[1] - w[0]) * s as f64 / per_span as f64));
            }
        }
        points.push(self.point(hi));
        debug_assert!(lo < hi);
        Ok(points)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_quadratic_bezier_and_a_rational_quarter_circle() {
        // Bézier: knots 0 0 0 1 1 1; at t = ½ the point is (P0 + 2P1 + P2) / 4.
        let b = Nurbs {
            degree: 2,
            knots: vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            control: vec![
                DVec3::ZERO,
                DVec3::new(1.0, 2.0, 0.0),
                DVec3::new(2.0, 0.0, 0.0),
            ],
            weights: vec![],
        };
        assert_eq!(b.point(0.5), DVec3::new(1.0, 1.0, 0.0));
        assert_eq!(b.point(0.0), DVec3::ZERO);
        assert_eq!(b.point(1.0), DVec3::new(2.0, 0.0, 0.0));
        // The exact quarter circle: weights 1, √½, 1.
        let q = Nurbs {
            weights: vec![1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0],
            control: vec![DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
            ..b
        };
        for p in q.sample(16).unwrap() {
            assert!((p.length() - 1.0).abs() < 1e-15, "{p}");
        }
        assert_eq!(q.sample(16).unwrap().len(), 17);
    }

    #[test]
    fn bad_data_is_an_error() {
        let mut s = Nurbs {
            degree: 3,
            knots: vec![0.0; 4],
            control: vec![DVec3::ZERO; 4],
            weights: vec![],
        };
        assert!(s.validate().is_err());
        s.knots = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
        assert!(s.validate().is_ok());
        s.knots[5] = 0.5;
        assert!(s.validate().is_err(), "decreasing knots");
        s.knots[5] = 1.0;
        s.weights = vec![1.0, -1.0, 1.0, 1.0];
        assert!(s.validate().is_err());
    }
}
