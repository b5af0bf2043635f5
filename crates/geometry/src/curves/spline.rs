//! Interpolating splines through control points, open or closed.
//!
//! Both kinds use **centripetal** knot spacing (t_{i+1} − t_i = |P_{i+1} − P_i|^½), which avoids
//! cusps and self-intersections within a span:
//! - [`SplineKind::CatmullRom`]: the centripetal Catmull–Rom spline (C¹, local: moving a control
//!   point changes only the two spans on either side). Open ends use the mirrored phantom points
//!   2P₀ − P₁ and 2P_{n−1} − P_{n−2}.
//! - [`SplineKind::Natural`]: the cubic spline (C², global) with zero second derivative at the ends
//!   of an open curve, periodic for a closed one.
//!
//! Both pass exactly through every control point (at the knots).

use glam::DVec3;

use super::check_count;
use crate::error::check_finite_points;
use crate::{GeometryError, Polyline};

/// Samples per span of the arc-length table [`Spline::sample_even`] spaces its samples by.
pub const ARC_TABLE_PER_SPAN: usize = 64;

/// Which interpolating spline.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SplineKind {
    /// Centripetal Catmull–Rom (C¹, local).
    CatmullRom,
    /// Natural (open) or periodic (closed) cubic spline (C², global).
    Natural,
}

impl SplineKind {
    /// Parses `catmull-rom` (also `catmull_rom`, `catmullrom`, `centripetal`) or `natural`
    /// (also `cubic`), case-insensitively.
    pub fn parse(s: &str) -> Result<Self, GeometryError> {
        // A word with any other character (a control, format or combining one) is refused.
        let norm = super::choice_key(s).unwrap_or_else(|| "\u{0}".to_string());
        match norm.as_str() {
            "catmullrom" | "centripetal" | "" => Ok(Self::CatmullRom),
            "natural" | "cubic" => Ok(Self::Natural),
            _ => Err(GeometryError::Degenerate(format!(
                "unknown spline method '{s}': expected 'catmull-rom' or 'natural'"
            ))),
        }
    }
}

/// An interpolating spline through control points, parameterized on `[knots[0], knots[last]]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Spline {
    kind: SplineKind,
    closed: bool,
    /// Control points; for a closed spline the first point is repeated at the end.
    points: Vec<DVec3>,
    /// One knot per entry of `points`, strictly increasing.
    knots: Vec<f64>,
    /// Catmull–Rom: the phantom points before the first and after the last span.
    /// Natural: unused.
    ends: (DVec3, DVec3),
    /// Natural: second derivatives at the knots (unused for Catmull–Rom).
    second: Vec<DVec3>,
}

impl Spline {
    /// Builds a spline of `kind` through `points` (open: ≥ 2 points; closed: ≥ 3 points, the first
    /// point not repeated at the end). Consecutive coincident points are an error.
    pub fn new(kind: SplineKind, points: &[DVec3], closed: bool) -> Result<Self, GeometryError> {
        let what = "spline control points";
        let min = if closed { 3 } else { 2 };
        if points.len() < min {
            return Err(GeometryError::TooFewPoints {
                what,
                needed: min,
                got: points.len(),
            });
        }
        check_finite_points(what, points)?;
        let mut pts = points.to_vec();
        if closed {
            pts.push(points[0]);
        }
        let mut knots = Vec::with_capacity(pts.len());
        knots.push(0.0);
        for (k, w) in pts.windows(2).enumerate() {
            let d = w[0].distance(w[1]);
            if d <= 1e-300 {
                return Err(GeometryError::ZeroLengthEdge {
                    what,
                    index: k,
                    next: (k + 1) % points.len(),
                });
            }
            knots.push(knots[k] + d.sqrt());
        }
        let n = pts.len();
        let ends = if closed {
            (pts[n - 2], pts[1])
        } else {
            (2.0 * pts[0] - pts[1], 2.0 * pts[n - 1] - pts[n - 2])
        };
        let second = match kind {
            SplineKind::CatmullRom => Vec::new(),
            SplineKind::Natural if closed => periodic_second_derivatives(&pts, &knots),
            SplineKind::Natural => natural_second_derivatives(&pts, &knots),
        };
        Ok(Self {
            kind,
            closed,
            points: pts,
            knots,
            ends,
            second,
        })
    }

    /// The kind of spline.
    pub fn kind(&self) -> SplineKind {
        self.kind
    }

    /// Whether the spline is closed.
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// The knots: control point `i` is reached at `knots()[i]` (a closed spline has one more knot,
    /// where it returns to its first point).
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The parameter domain.
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[0], self.knots[self.knots.len() - 1])
    }

    /// The point at parameter `t` (clamped to the domain).
    pub fn eval(&self, t: f64) -> DVec3 {
        let (t0, t1) = self.domain();
        let t = if t.is_nan() { t0 } else { t.clamp(t0, t1) };
        let span = self
            .knots
            .partition_point(|&k| k <= t)
            .saturating_sub(1)
            .min(self.knots.len() - 2);
        self.eval_in(span, t)
    }

    /// The spline at `t` on span `span` (its knots' interval; `t` clamped by the caller), without
    /// looking the span up.
    fn eval_in(&self, span: usize, t: f64) -> DVec3 {
        match self.kind {
            SplineKind::CatmullRom => self.eval_catmull_rom(span, t),
            SplineKind::Natural => self.eval_natural(span, t),
        }
    }

    fn eval_natural(&self, i: usize, t: f64) -> DVec3 {
        let (ta, tb) = (self.knots[i], self.knots[i + 1]);
        let h = tb - ta;
        let (a, b) = (tb - t, t - ta);
        let (ma, mb) = (self.second[i], self.second[i + 1]);
        let (pa, pb) = (self.points[i], self.points[i + 1]);
        ma * (a * a * a / (6.0 * h))
            + mb * (b * b * b / (6.0 * h))
            + (pa / h - ma * (h / 6.0)) * a
            + (pb / h - mb * (h / 6.0)) * b
    }

    /// Control point (with phantoms) and knot at extended index `i` (−1 … n).
    fn extended(&self, i: isize) -> (DVec3, f64) {
        let n = self.points.len() as isize;
        if i < 0 {
            let t = self.knots[0] - (self.knots[1] - self.knots[0]).max(0.0);
            let t = if self.closed {
                self.knots[0] - (self.knots[n as usize - 1] - self.knots[n as usize - 2])
            } else {
                t
            };
            (self.ends.0, t)
        } else if i >= n {
            let last = n as usize - 1;
            let t = if self.closed {
                self.knots[last] + (self.knots[1] - self.knots[0])
            } else {
                self.knots[last] + (self.knots[last] - self.knots[last - 1])
            };
            (self.ends.1, t)
        } else {
            (self.points[i as usize], self.knots[i as usize])
        }
    }

    fn eval_catmull_rom(&self, i: usize, t: f64) -> DVec3 {
        let i = i as isize;
        let (p0, t0) = self.extended(i - 1);
        let (p1, t1) = self.extended(i);
        let (p2, t2) = self.extended(i + 1);
        let (p3, t3) = self.extended(i + 2);
        // Barry–Goldman pyramid.
        let lerp = |a: DVec3, b: DVec3, ta: f64, tb: f64| -> DVec3 {
            if tb - ta <= 0.0 {
                a
            } else {
                a * ((tb - t) / (tb - ta)) + b * ((t - ta) / (tb - ta))
            }
        };
        let a1 = lerp(p0, p1, t0, t1);
        let a2 = lerp(p1, p2, t1, t2);
        let a3 = lerp(p2, p3, t2, t3);
        let b1 = lerp(a1, a2, t0, t2);
        let b2 = lerp(a2, a3, t1, t3);
        lerp(b1, b2, t1, t2)
    }

    /// The second derivatives of a natural spline at its knots (one per knot; empty for
    /// Catmull–Rom).
    pub fn second_derivatives(&self) -> &[DVec3] {
        &self.second
    }

    /// A dense table of (parameter, cumulative arc length) with `per_span` samples per span: the
    /// first entry is (first knot, 0), then span by span the parameters
    /// `t_i + (t_{i+1} − t_i) k / per_span` (k = 1 … per_span, the last exactly the next knot) and
    /// the length of the chords through the spline's points there, from the first control point.
    pub fn arc_table(&self, per_span: usize) -> Vec<(f64, f64)> {
        let mut table = Vec::with_capacity((self.knots.len() - 1) * per_span + 1);
        table.extend(self.arc_walk(per_span));
        table
    }

    /// The entries of [`Spline::arc_table`] one by one, computed as they are needed (the same
    /// numbers, nothing stored: a million-point spline's table would take a gigabyte).
    fn arc_walk(&self, per_span: usize) -> ArcWalk<'_> {
        ArcWalk {
            spline: self,
            per_span,
            span: 0,
            k: 0,
            prev: self.points[0],
            acc: 0.0,
        }
    }

    /// Samples `count` points evenly spaced by arc length along the spline (open: ≥ 2, both ends
    /// included; closed: ≥ 3, starting at the first control point). Every sample lies exactly on
    /// the spline; the spacing is even to within the accuracy of a 64-per-span arc-length table.
    pub fn sample_even(&self, count: usize) -> Result<Polyline, GeometryError> {
        check_count("count", count, if self.closed { 3 } else { 2 })?;
        // Two walks along the arc-length table, nothing stored: the total length, then the
        // samples (the same numbers as a stored table).
        let entries = (self.knots.len() - 1) * ARC_TABLE_PER_SPAN + 1;
        let total = self
            .arc_walk(ARC_TABLE_PER_SPAN)
            .last()
            .map_or(0.0, |e| e.1);
        let mut walk = self.arc_walk(ARC_TABLE_PER_SPAN);
        let mut a = walk.next().unwrap_or((self.knots[0], 0.0));
        let mut b = walk.next().unwrap_or(a);
        let intervals = if self.closed { count } else { count - 1 };
        let mut points = Vec::with_capacity(count);
        let mut cursor = 0;
        for k in 0..count {
            if !self.closed && k + 1 == count {
                points.push(self.points[self.points.len() - 1]);
                break;
            }
            if k == 0 {
                points.push(self.points[0]);
                continue;
            }
            let s = total * k as f64 / intervals as f64;
            while cursor + 1 < entries - 1 && b.1 < s {
                a = b;
                b = walk.next().unwrap_or(a);
                cursor += 1;
            }
            let ((ta, sa), (tb, sb)) = (a, b);
            let t = if sb > sa {
                ta + (tb - ta) * ((s - sa) / (sb - sa))
            } else {
                ta
            };
            points.push(self.eval(t));
        }
        super::check_output(
            "spline",
            Polyline {
                points,
                closed: self.closed,
            },
        )
    }

    /// Samples `count` points evenly spaced in the spline parameter (open: both ends included;
    /// closed: starting at the first control point).
    pub fn sample_parameter(&self, count: usize) -> Result<Polyline, GeometryError> {
        check_count("count", count, if self.closed { 3 } else { 2 })?;
        let (t0, t1) = self.domain();
        let intervals = if self.closed { count } else { count - 1 };
        let points = (0..count)
            .map(|k| self.eval(t0 + (t1 - t0) * k as f64 / intervals as f64))
            .collect();
        super::check_output(
            "spline",
            Polyline {
                points,
                closed: self.closed,
            },
        )
    }
}

/// The arc-length table of a spline walked entry by entry ([`Spline::arc_table`]).
struct ArcWalk<'a> {
    spline: &'a Spline,
    per_span: usize,
    /// The span being walked (`knots.len() − 1` when done).
    span: usize,
    /// The step inside it (0: the first entry, not yet given).
    k: usize,
    prev: DVec3,
    acc: f64,
}

impl Iterator for ArcWalk<'_> {
    type Item = (f64, f64);

    fn next(&mut self) -> Option<(f64, f64)> {
        let knots = &self.spline.knots;
        if self.span == 0 && self.k == 0 {
            self.k = 1;
            return Some((knots[0], 0.0));
        }
        if self.span + 1 >= knots.len() {
            return None;
        }
        let (t0, t1) = (knots[self.span], knots[self.span + 1]);
        let k = self.k;
        let t = if k == self.per_span {
            t1
        } else {
            t0 + (t1 - t0) * k as f64 / self.per_span as f64
        };
        // The span is known (no lookup: a walk over a million spans made 128 million of them);
        // a span's end is its successor's start, as `eval` takes it.
        let p = if k == self.per_span && self.span + 2 < knots.len() {
            self.spline.eval_in(self.span + 1, t)
        } else if t < t1 || self.span + 2 >= knots.len() {
            self.spline.eval_in(self.span, t)
        } else {
            self.spline.eval(t)
        };
        self.acc += p.distance(self.prev);
        self.prev = p;
        if k == self.per_span {
            self.span += 1;
            self.k = 1;
        } else {
            self.k += 1;
        }
        Some((t, self.acc))
    }
}

/// Second derivatives of the natural cubic spline (zero at both ends) by the Thomas algorithm.
fn natural_second_derivatives(p: &[DVec3], t: &[f64]) -> Vec<DVec3> {
    let n = p.len();
    let mut m = vec![DVec3::ZERO; n];
    if n < 3 {
        return m;
    }
    // Unknowns m[1..n-1]; row i: h[i-1] m[i-1] + 2(h[i-1]+h[i]) m[i] + h[i] m[i+1] = r[i].
    let h: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
    let inner = n - 2;
    let mut diag = vec![0.0; inner];
    let mut upper = vec![0.0; inner];
    let mut rhs = vec![DVec3::ZERO; inner];
    for k in 0..inner {
        let i = k + 1;
        diag[k] = 2.0 * (h[i - 1] + h[i]);
        upper[k] = h[i];
        rhs[k] = 6.0 * ((p[i + 1] - p[i]) / h[i] - (p[i] - p[i - 1]) / h[i - 1]);
    }
    // Forward sweep (lower[k] = h[k] for row k ≥ 1).
    for k in 1..inner {
        let w = h[k] / diag[k - 1];
        diag[k] -= w * upper[k - 1];
        rhs[k] = rhs[k] - rhs[k - 1] * w;
    }
    let mut x = vec![DVec3::ZERO; inner];
    x[inner - 1] = rhs[inner - 1] / diag[inner - 1];
    for k in (0..inner - 1).rev() {
        x[k] = (rhs[k] - x[k + 1] * upper[k]) / diag[k];
    }
    m[1..n - 1].copy_from_slice(&x);
    m
}

/// Second derivatives of the periodic cubic spline through `p` (first point repeated at the end),
/// solving the cyclic tridiagonal system with the Sherman–Morrison correction.
fn periodic_second_derivatives(p: &[DVec3], t: &[f64]) -> Vec<DVec3> {
    let n = p.len() - 1; // distinct points
    let h: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect(); // n spans
    let prev = |i: usize| (i + n - 1) % n;
    // Row i (0..n): h[i-1] m[i-1] + 2(h[i-1] + h[i]) m[i] + h[i] m[i+1] = r[i] (indices cyclic).
    let mut a = vec![0.0; n]; // sub-diagonal (a[0] is the corner)
    let mut b = vec![0.0; n];
    let mut c = vec![0.0; n]; // super-diagonal (c[n-1] is the corner)
    let mut r = vec![DVec3::ZERO; n];
    for i in 0..n {
        let hp = h[prev(i)];
        let hi = h[i];
        a[i] = hp;
        b[i] = 2.0 * (hp + hi);
        c[i] = hi;
        let next = p[i + 1];
        let before = if i == 0 { p[n - 1] } else { p[i - 1] };
        r[i] = 6.0 * ((next - p[i]) / hi - (p[i] - before) / hp);
    }
    let alpha = c[n - 1]; // bottom-left corner (row n-1, column 0)
    let beta = a[0]; // top-right corner (row 0, column n-1)
    let gamma = -b[0];
    let mut bb = b.clone();
    bb[0] -= gamma;
    bb[n - 1] -= alpha * beta / gamma;
    let x = thomas(&a, &bb, &c, &r);
    let mut u = vec![DVec3::ZERO; n];
    u[0] = DVec3::splat(gamma);
    u[n - 1] = DVec3::splat(alpha);
    let z = thomas(&a, &bb, &c, &u);
    let fact_num = x[0] + x[n - 1] * (beta / gamma);
    let fact_den = DVec3::ONE + z[0] + z[n - 1] * (beta / gamma);
    let fact = fact_num / fact_den;
    let mut m: Vec<DVec3> = x.iter().zip(&z).map(|(xi, zi)| *xi - fact * *zi).collect();
    m.push(m[0]);
    m
}

/// Solves a tridiagonal system (a: sub-diagonal, a[0] unused; c: super-diagonal, c[n-1] unused).
fn thomas(a: &[f64], b: &[f64], c: &[f64], r: &[DVec3]) -> Vec<DVec3> {
    let n = b.len();
    let mut cp = vec![0.0; n];
    let mut rp = vec![DVec3::ZERO; n];
    cp[0] = c[0] / b[0];
    rp[0] = r[0] / b[0];
    for i in 1..n {
        let den = b[i] - a[i] * cp[i - 1];
        cp[i] = c[i] / den;
        rp[i] = (r[i] - rp[i - 1] * a[i]) / den;
    }
    let mut x = vec![DVec3::ZERO; n];
    x[n - 1] = rp[n - 1];
    for i in (0..n - 1).rev() {
        x[i] = rp[i] - x[i + 1] * cp[i];
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The stored-table sampling the walk replaced, written out independently.
    fn sample_even_stored(sp: &Spline, count: usize) -> Vec<DVec3> {
        let mut table = vec![(sp.knots[0], 0.0)];
        let (mut prev, mut acc) = (sp.points[0], 0.0);
        for w in sp.knots.windows(2) {
            for k in 1..=ARC_TABLE_PER_SPAN {
                let t = if k == ARC_TABLE_PER_SPAN {
                    w[1]
                } else {
                    w[0] + (w[1] - w[0]) * k as f64 / ARC_TABLE_PER_SPAN as f64
                };
                let p = sp.eval(t);
                acc += p.distance(prev);
                prev = p;
                table.push((t, acc));
            }
        }
        let total = table[table.len() - 1].1;
        let intervals = if sp.closed { count } else { count - 1 };
        let mut cursor = 0;
        (0..count)
            .map(|k| {
                if !sp.closed && k + 1 == count {
                    return sp.points[sp.points.len() - 1];
                }
                if k == 0 {
                    return sp.points[0];
                }
                let s = total * k as f64 / intervals as f64;
                while cursor + 1 < table.len() - 1 && table[cursor + 1].1 < s {
                    cursor += 1;
                }
                let ((ta, sa), (tb, sb)) = (table[cursor], table[cursor + 1]);
                let t = if sb > sa {
                    ta + (tb - ta) * ((s - sa) / (sb - sa))
                } else {
                    ta
                };
                sp.eval(t)
            })
            .collect()
    }

    #[test]
    fn sampling_walks_the_arc_table_without_storing_it_and_gives_the_same_points() {
        let pts: Vec<DVec3> = (0..9)
            .map(|k| {
                let t = k as f64 * 0.7;
                DVec3::new(t.cos() * (2.0 + t), t.sin(), 0.3 * t * t)
            })
            .collect();
        for kind in [SplineKind::CatmullRom, SplineKind::Natural] {
            for closed in [false, true] {
                let sp = Spline::new(kind, &pts, closed).unwrap();
                for count in [3, 17, 200] {
                    let walked = sp.sample_even(count).unwrap();
                    assert_eq!(
                        walked.points,
                        sample_even_stored(&sp, count),
                        "{kind:?} {closed} {count}"
                    );
                }
                assert_eq!(
                    sp.arc_table(ARC_TABLE_PER_SPAN).len(),
                    (sp.knots.len() - 1) * ARC_TABLE_PER_SPAN + 1
                );
            }
        }
    }

    fn zigzag() -> Vec<DVec3> {
        vec![
            DVec3::ZERO,
            DVec3::new(1.0, 2.0, 0.0),
            DVec3::new(3.0, -1.0, 0.5),
            DVec3::new(4.0, 0.5, 1.0),
            DVec3::new(7.0, 0.0, 0.0),
        ]
    }

    #[test]
    fn both_kinds_interpolate_their_control_points() {
        for kind in [SplineKind::CatmullRom, SplineKind::Natural] {
            for closed in [false, true] {
                let pts = zigzag();
                let s = Spline::new(kind, &pts, closed).unwrap();
                for (i, p) in pts.iter().enumerate() {
                    let q = s.eval(s.knots()[i]);
                    assert!(
                        (q - *p).length() < 1e-12,
                        "{kind:?} {closed} {i}: {q} vs {p}"
                    );
                }
                if closed {
                    let (_, t1) = s.domain();
                    assert!((s.eval(t1) - pts[0]).length() < 1e-12);
                }
            }
        }
    }

    #[test]
    fn two_points_give_a_straight_segment() {
        for kind in [SplineKind::CatmullRom, SplineKind::Natural] {
            let s = Spline::new(kind, &[DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0)], false).unwrap();
            let p = s.sample_even(5).unwrap();
            for (k, q) in p.points.iter().enumerate() {
                assert!((*q - DVec3::new(0.5 * k as f64, 0.0, 0.0)).length() < 1e-9);
            }
        }
    }

    #[test]
    fn natural_spline_is_c2_at_interior_knots() {
        let pts = zigzag();
        for closed in [false, true] {
            let s = Spline::new(SplineKind::Natural, &pts, closed).unwrap();
            let e = 1e-4;
            let range = if closed {
                0..pts.len()
            } else {
                1..pts.len() - 1
            };
            for i in range {
                let t = s.knots()[i];
                let (lo, hi) = if closed && i == 0 {
                    (s.domain().1, s.domain().0)
                } else {
                    (t, t)
                };
                // Second differences on either side converge to the same second derivative.
                let left = (s.eval(lo) - 2.0 * s.eval(lo - e) + s.eval(lo - 2.0 * e)) / (e * e);
                let right = (s.eval(hi + 2.0 * e) - 2.0 * s.eval(hi + e) + s.eval(hi)) / (e * e);
                assert!(
                    (left - right).length() < 1e-2 * (1.0 + left.length()),
                    "closed {closed} knot {i}: {left} vs {right}"
                );
            }
        }
    }

    #[test]
    fn catmull_rom_is_c1_at_interior_knots() {
        let pts = zigzag();
        let s = Spline::new(SplineKind::CatmullRom, &pts, true).unwrap();
        let e = 1e-6;
        for i in 1..pts.len() {
            let t = s.knots()[i];
            let left = (s.eval(t) - s.eval(t - e)) / e;
            let right = (s.eval(t + e) - s.eval(t)) / e;
            assert!((left - right).length() < 1e-3 * (1.0 + left.length()));
        }
    }

    #[test]
    fn even_sampling_is_even_and_keeps_the_ends() {
        // Gentle control polygons, so that chords of the samples are close to their arcs.
        let wave: Vec<DVec3> = (0..7)
            .map(|k| DVec3::new(k as f64, (k as f64).sin() * 0.8, 0.1 * k as f64))
            .collect();
        let ring: Vec<DVec3> = (0..6)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 6.0;
                DVec3::new(3.0 * a.cos(), (2.0 + 0.3 * k as f64) * a.sin(), 0.0)
            })
            .collect();
        for kind in [SplineKind::CatmullRom, SplineKind::Natural] {
            for closed in [false, true] {
                let pts = if closed { &ring } else { &wave };
                let s = Spline::new(kind, pts, closed).unwrap();
                let p = s.sample_even(100).unwrap();
                assert_eq!(p.points.len(), 100);
                assert_eq!(p.closed, closed);
                assert_eq!(p.points[0], pts[0]);
                if !closed {
                    assert_eq!(p.points[99], pts[6]);
                }
                let lengths: Vec<f64> = p.edges().map(|(a, b)| a.distance(b)).collect();
                let mean = lengths.iter().sum::<f64>() / lengths.len() as f64;
                for l in &lengths {
                    assert!(
                        (l / mean - 1.0).abs() < 0.005,
                        "{kind:?} {closed}: {l} vs {mean}"
                    );
                }
                // Samples lie on the spline: the parameter-sampled curve passes close to them.
                let dense = s.sample_parameter(5000).unwrap();
                for q in &p.points {
                    let d = dense
                        .points
                        .iter()
                        .map(|r| r.distance(*q))
                        .fold(f64::INFINITY, f64::min);
                    assert!(d < 0.01, "{q} is {d} from the spline");
                }
            }
        }
    }

    #[test]
    fn bad_inputs_are_typed_errors() {
        let k = SplineKind::CatmullRom;
        assert!(matches!(
            Spline::new(k, &[DVec3::ZERO], false),
            Err(GeometryError::TooFewPoints { .. })
        ));
        assert!(matches!(
            Spline::new(k, &[DVec3::ZERO, DVec3::X], true),
            Err(GeometryError::TooFewPoints { .. })
        ));
        assert!(matches!(
            Spline::new(k, &[DVec3::ZERO, DVec3::ZERO, DVec3::X], false),
            Err(GeometryError::ZeroLengthEdge { index: 0, .. })
        ));
        assert!(matches!(
            Spline::new(k, &[DVec3::ZERO, DVec3::X, DVec3::ZERO], true),
            Err(GeometryError::ZeroLengthEdge {
                index: 2,
                next: 0,
                ..
            })
        ));
        assert!(Spline::new(k, &[DVec3::ZERO, DVec3::NAN], false).is_err());
        let s = Spline::new(k, &zigzag(), false).unwrap();
        assert!(s.sample_even(1).is_err());
        assert!(s.eval(f64::NAN).is_finite());
        let huge = [
            DVec3::ZERO,
            DVec3::splat(1e308),
            DVec3::new(-1e308, 1e308, 0.0),
        ];
        let e = Spline::new(SplineKind::Natural, &huge, false).and_then(|s| s.sample_even(9));
        assert!(e.is_err());
        assert_eq!(SplineKind::parse(" Natural ").unwrap(), SplineKind::Natural);
        assert_eq!(
            SplineKind::parse("catmull_rom").unwrap(),
            SplineKind::CatmullRom
        );
        assert!(SplineKind::parse("bspline").is_err());
    }
}
