//! The last part of the construction's adjoint ([`super::adjoint`]): the cotangents of the
//! per-column quantities the sweep reads — the apex values a_j, the swept directrix points X_j, the
//! unit edges ê_j and the Monge normals b_j — pulled back to the user's inputs: the apex function
//! (ā_j when normalized), the normalization scale L and the directrix's stored points.
//!
//! The forward maps ([`super::directrix`], [`super::normalize`]):
//! `ê_j = (X_j − X_{j−1}) / l_j`, `l_j = |X_j − X_{j−1}|`; `b_j = unit(ê_j + o_j)` with the outgoing
//! edge `o_j` = ê_{j+1} inside, ê_1 at the end of a closed directrix, ê_{M−1} at the end of an open
//! one ("perpendicular"), or for "mirror" `b_{M−1} = unit(2 (b_{M−2}·ê_{M−1}) ê_{M−1} − b_{M−2})`;
//! `a_j = 1 − (1 − ā_j) l_j / L` when normalized (ā_j = 1 gives exactly 1, where the formula's
//! derivative — l_j / L in ā_j, 0 in l_j and L — is used), `L = Σ l_j / 5` unless given. A closed
//! directrix's last swept point is its first stored point.

use glam::DVec3;

use super::directrix::SweptDirectrix;
use super::inputs::{ApexInput, ColumnValues, EndPlanes};
use super::seam_apex::seam_apex_pullback;

/// Cotangents of the per-column quantities (index j; entry 0 of `a`, `e`, `b` unused).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ColumnBars {
    /// ∂L/∂a_j at index j − 1 (M − 1).
    pub a: Vec<f64>,
    /// ∂L/∂X_j for the swept points (M).
    pub x: Vec<DVec3>,
    /// ∂L/∂ê_j (M).
    pub e: Vec<DVec3>,
    /// ∂L/∂b_j (M).
    pub b: Vec<DVec3>,
}

impl ColumnBars {
    /// Zeros for M columns.
    pub fn zeros(m: usize) -> Self {
        Self {
            a: vec![0.0; m.saturating_sub(1)],
            x: vec![DVec3::ZERO; m],
            e: vec![DVec3::ZERO; m],
            b: vec![DVec3::ZERO; m],
        }
    }

    /// Adds `o` (sums over rows).
    pub fn add(mut self, o: &Self) -> Self {
        self.a.iter_mut().zip(&o.a).for_each(|(s, x)| *s += x);
        for (s, x) in [
            (&mut self.x, &o.x),
            (&mut self.e, &o.e),
            (&mut self.b, &o.b),
        ] {
            s.iter_mut().zip(x).for_each(|(s, x)| *s += *x);
        }
        self
    }
}

/// The cotangents of the user's inputs.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct InputBars {
    /// The apex input's, in its shape: 1 number (uniform) or M − 1.
    pub apex: Vec<f64>,
    /// The given normalization scale's (0 when the apex is not normalized); `None` when the scale
    /// is not given (the directrix length / 5: its cotangent went to the directrix).
    pub scale: Option<f64>,
    /// The directrix's stored points' (a closed directrix: without the repeated first point).
    pub directrix: Vec<DVec3>,
    /// The shared apex's (a net continuing another, [`ApexInput::seam`]); `None` when not given.
    pub seam: Option<DVec3>,
}

/// `(I − u uᵀ) v / len`: the pull-back of `u = s / |s|` (len = |s|).
#[inline]
fn unit_pullback(u: DVec3, len: f64, v: DVec3) -> DVec3 {
    (v - u * u.dot(v)) / len
}

/// Pulls `bars` back to the apex input (values `apex`), the scale and the directrix `dx` (built
/// with `end`), for a directrix of `stored` points.
pub(crate) fn pull_back(
    bars: ColumnBars,
    dx: &SweptDirectrix,
    end: EndPlanes,
    apex: &ApexInput,
    stored: usize,
) -> InputBars {
    let m = dx.columns();
    let ColumnBars {
        a: mut a_bar,
        mut x,
        mut e,
        mut b,
    } = bars;
    // A shared apex sets a_1 from X_0, X_1 and the apex: its cotangent goes to them, not to the
    // value given.
    let seam = apex.seam.map(|c| {
        let g = std::mem::take(&mut a_bar[0]);
        let [x0, x1, c_bar] = seam_apex_pullback(dx.points[0], dx.points[1], c, g);
        x[0] += x0;
        x[1] += x1;
        c_bar
    });
    let mut l_bar = vec![0.0; m];
    // The normalization.
    let (values_bar, scale) = if apex.normalized {
        let values = apex
            .values
            .resolve("apex", m - 1)
            .unwrap_or_else(|_| vec![0.0; m - 1]);
        let big_l = apex
            .scale
            .unwrap_or_else(|| super::normalize::default_scale(dx.length()));
        let mut big_l_bar = 0.0;
        let mut values_bar = vec![0.0; m - 1];
        for j in 1..m {
            let (abar, l, g) = (values[j - 1], dx.lengths[j], a_bar[j - 1]);
            values_bar[j - 1] = g * l / big_l;
            l_bar[j] -= g * (1.0 - abar) / big_l;
            big_l_bar += g * (1.0 - abar) * l / (big_l * big_l);
        }
        let scale = match apex.scale {
            Some(_) => Some(big_l_bar),
            None => {
                l_bar.iter_mut().skip(1).for_each(|l| *l += big_l_bar / 5.0);
                None
            }
        };
        (values_bar, scale)
    } else {
        (a_bar, apex.scale.map(|_| 0.0))
    };
    let apex_bar = match apex.values {
        ColumnValues::Uniform(_) => vec![values_bar.iter().sum()],
        ColumnValues::List(_) => values_bar,
    };
    // The mirrored end plane first: it feeds b_{M−2} and ê_{M−1}.
    let mut last = m - 1;
    let mirrored = end == EndPlanes::Mirror
        && !dx.closed
        && m >= 3
        && dx.bisectors[m - 2] != DVec3::ZERO
        && dx.bisectors[m - 1] != DVec3::ZERO;
    if mirrored {
        let (bp, en) = (dx.bisectors[m - 2], dx.edges[m - 1]);
        let v = 2.0 * bp.dot(en) * en - bp;
        let len = v.length();
        let v_bar = unit_pullback(v / len, len, b[m - 1]);
        b[m - 2] += 2.0 * en.dot(v_bar) * en - v_bar;
        e[m - 1] += 2.0 * v_bar.dot(en) * bp + 2.0 * bp.dot(en) * v_bar;
        last = m - 2;
    }
    for j in 1..=last {
        if dx.bisectors[j] == DVec3::ZERO {
            continue;
        }
        let next = if j + 1 < m {
            j + 1
        } else if dx.closed {
            1
        } else {
            j
        };
        let s = dx.edges[j] + dx.edges[next];
        let s_bar = unit_pullback(dx.bisectors[j], s.length(), b[j]);
        e[j] += s_bar;
        e[next] += s_bar;
    }
    // The edges and their lengths.
    for j in 1..m {
        let u_bar = unit_pullback(dx.edges[j], dx.lengths[j], e[j]) + dx.edges[j] * l_bar[j];
        x[j] += u_bar;
        x[j - 1] -= u_bar;
    }
    let mut directrix = x;
    if dx.closed {
        let wrap = directrix[m - 1];
        directrix[0] += wrap;
    }
    directrix.truncate(stored);
    InputBars {
        apex: apex_bar,
        scale,
        directrix,
        seam,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Polyline;
    use crate::conenet::normalize::resolve_apex;

    /// A fixed linear function of everything the sweep reads (a_j, X_j, ê_j, b_j) with the weights
    /// `w`, as a function of the user's inputs.
    fn loss(
        points: &[DVec3],
        closed: bool,
        end: EndPlanes,
        apex: &ApexInput,
        w: &ColumnBars,
    ) -> f64 {
        let poly = if closed {
            Polyline::closed(points.to_vec())
        } else {
            Polyline::open(points.to_vec())
        };
        let dx = SweptDirectrix::with_end_planes(&poly, end).unwrap();
        let a = resolve_apex(apex, &dx).unwrap();
        let mut s: f64 = a.iter().zip(&w.a).map(|(a, w)| a * w).sum();
        for j in 0..dx.columns() {
            s += dx.points[j].dot(w.x[j]) + dx.edges[j].dot(w.e[j]) + dx.bisectors[j].dot(w.b[j]);
        }
        s
    }

    fn check(closed: bool, end: EndPlanes, normalized: bool, scale: Option<f64>, list: bool) {
        let points: Vec<DVec3> = (0..5)
            .map(|k| {
                let t = k as f64 * 0.9;
                DVec3::new(2.0 * t.cos() + 0.1 * t, 1.5 * t.sin(), 0.3 * t * t)
            })
            .collect();
        let stored = points.len();
        let m = stored + usize::from(closed);
        let values = if list {
            ColumnValues::List((1..m).map(|j| 0.7 + 0.13 * j as f64).collect())
        } else {
            ColumnValues::Uniform(0.8)
        };
        let mut apex = ApexInput {
            values,
            normalized,
            scale,
            seam: None,
        };
        let mut w = ColumnBars::zeros(m);
        for j in 0..m {
            let f = j as f64;
            if j > 0 {
                w.a[j - 1] = (1.3 * f).sin();
                w.e[j] = DVec3::new((0.4 * f).cos(), 0.5, -(0.9 * f).sin());
                w.b[j] = DVec3::new(0.3, (1.1 * f).sin(), (0.2 * f).cos());
            }
            w.x[j] = DVec3::new((0.7 * f).sin(), -0.2, (0.3 * f).cos());
        }
        let poly = if closed {
            Polyline::closed(points.clone())
        } else {
            Polyline::open(points.clone())
        };
        let dx = SweptDirectrix::with_end_planes(&poly, end).unwrap();
        let got = pull_back(w.clone(), &dx, end, &apex, stored);
        let h = 1e-6;
        let (mut worst, mut size) = (0.0f64, 0.0f64);
        let mut compare = |fd: f64, exact: f64| {
            worst = worst.max((fd - exact).abs());
            size = size.max(fd.abs());
        };
        for k in 0..stored {
            for c in 0..3 {
                let mut p = points.clone();
                p[k][c] += h;
                let up = loss(&p, closed, end, &apex, &w);
                p[k][c] -= 2.0 * h;
                let down = loss(&p, closed, end, &apex, &w);
                compare((up - down) / (2.0 * h), got.directrix[k][c]);
            }
        }
        let base = apex.clone();
        let n_values = match &base.values {
            ColumnValues::Uniform(_) => 1,
            ColumnValues::List(v) => v.len(),
        };
        for k in 0..n_values {
            let at = |dv: f64| {
                let mut a = base.clone();
                match &mut a.values {
                    ColumnValues::Uniform(v) => *v += dv,
                    ColumnValues::List(v) => v[k] += dv,
                }
                a
            };
            let fd = (loss(&points, closed, end, &at(h), &w)
                - loss(&points, closed, end, &at(-h), &w))
                / (2.0 * h);
            compare(fd, got.apex[k]);
        }
        if let Some(l) = scale {
            apex.scale = Some(l + h);
            let up = loss(&points, closed, end, &apex, &w);
            apex.scale = Some(l - h);
            let down = loss(&points, closed, end, &apex, &w);
            compare((up - down) / (2.0 * h), got.scale.unwrap());
        } else {
            assert_eq!(got.scale, None);
        }
        let rel = worst / size;
        assert!(
            rel < 1e-7,
            "closed {closed}, {end:?}, normalized {normalized}: relative difference {rel}"
        );
    }

    #[test]
    fn pull_back_matches_differences_of_the_directrix_and_apex_maps() {
        for closed in [false, true] {
            for end in [EndPlanes::Perpendicular, EndPlanes::Mirror] {
                for (normalized, scale) in [(false, None), (true, None), (true, Some(1.7))] {
                    for list in [false, true] {
                        check(closed, end, normalized, scale, list);
                    }
                }
            }
        }
    }
}
