//! Gradients of the curve nodes on the path from a drawn curve to a net: `curve.polyline`,
//! `curve.transform`, `curve.resample` and `curve.spline`, in their input points (and the
//! transform in its parameters).
//!
//! - `curve.polyline` passes its points on (a closed curve's repeated last point is dropped: its
//!   cotangent is zero; whether it was is the node's piece).
//! - `curve.transform` is p ↦ s R (p − c) + c, mirrored, moved: exact in the curve, the
//!   translation, the angle, the axis, the centre and the scale (a plane carries no derivative).
//! - `curve.resample` by arc length: each sample is `a + (b − a) u` on the segment it falls on, u
//!   from the arc position `total · k / intervals` and the segment's cumulative lengths; with
//!   `chords`, each point is where the curve leaves the sphere of the common chord length about
//!   the previous one, the chord fixed by the last chord ending on the curve's end (implicit
//!   differentiation). The piece: the segment of every point and the point count.
//! - `curve.spline`, both methods, open and closed: the centripetal knots (square roots of the
//!   control point distances), the phantom end points, the natural spline's second derivatives
//!   (a tridiagonal or cyclic solve, differentiated by its adjoint solve), the arc-length table
//!   the samples are spaced by and the parameter of every sample interpolated in it. The piece:
//!   the table interval of every sample.
//!
//! Counts, the closed flag and the method are not differentiable (their cotangents are zero).

use cnets_engine::PortKind;
use cnets_engine::broadcast::{self, Level};
use cnets_engine::node::PortDef;
use cnets_engine::optimize::branch::{Branch, key_of};
use cnets_engine::optimize::vjp::{VjpArgs, VjpResult};
use cnets_engine::prelude::*;
use cnets_geometry::curves::spline::ARC_TABLE_PER_SPAN;
use cnets_geometry::curves::{self, Spline, SplineKind};

use super::dual::Dual;
use super::{flat, points};
use crate::choices::SplineMethod;

type Product = fn(&VjpArgs<'_>) -> VjpResult;
type BranchFn = fn(&[Value]) -> Option<Branch>;

/// Input `k` as its port kind `K` reads it.
fn input<K: PortKind>(inputs: &[Value], k: usize, name: &str) -> Result<K::In, NodeError> {
    K::extract(inputs.get(k).unwrap_or(&Value::Null), name)
}

fn internal(what: &str) -> NodeError {
    NodeError::new(format!("internal: {what}"))
}

/// A short list of indices for a branch summary.
fn listed(codes: &[usize]) -> String {
    let shown: Vec<String> = codes.iter().take(12).map(usize::to_string).collect();
    let more = if codes.len() > 12 { ", …" } else { "" };
    format!("[{}{more}]", shown.join(", "))
}

// ---------------------------------------------------------------------------------------------
// curve.polyline

/// The points of `curve.polyline` and whether the run dropped the last one (a closed curve's
/// repeat of the first).
fn polyline_run(inputs: &[Value]) -> Result<(Vec<DVec3>, bool, bool), NodeError> {
    let points = input::<k::List<k::Point>>(inputs, 0, "points")?;
    let closed = input::<k::Boolean>(inputs, 1, "closed")?;
    let dropped = closed && points.len() > 3 && points.first() == points.last();
    Ok((points, closed, dropped))
}

/// `curve.polyline`: the identity on the points kept.
fn polyline(args: &VjpArgs<'_>) -> VjpResult {
    let (points, _, dropped) = polyline_run(args.inputs)?;
    let mut g = args.cotangent(0);
    if dropped {
        g.extend([0.0; 3]);
    }
    if g.len() != 3 * points.len() {
        return Err(internal(
            "the polyline's cotangent does not match its points",
        ));
    }
    Ok(vec![args.wanted[0].then_some(g), None])
}

/// `curve.polyline`'s piece (closed curves only): whether the repeated last point was dropped.
fn polyline_branch(inputs: &[Value]) -> Option<Branch> {
    let (_, closed, dropped) = polyline_run(inputs).ok()?;
    closed.then(|| Branch {
        key: u64::from(dropped),
        summary: if dropped {
            "the last point repeats the first and is dropped".into()
        } else {
            "every point kept".into()
        },
    })
}

// ---------------------------------------------------------------------------------------------
// curve.transform

/// `curve.transform`: q = s R (p − c) + c, then the mirror M q = q − 2 n̂ (n̂ · (q − o)), then
/// the translation t. With ḡ = Mᵀ g per point: p̄ = s Rᵀ ḡ, t̄ = Σ g, c̄ = Σ (ḡ − s Rᵀ ḡ),
/// s̄ = Σ (Rᵀ ḡ) · (p − c), θ̄ = Σ ḡ · ∂R/∂θ s (p − c) (Rodrigues' formula; per degree), and the
/// unit axis k̂ gets sin θ (v × ḡ) + (1 − cos θ) ((k̂ · v) ḡ + (ḡ · k̂) v) with v = s (p − c),
/// projected off k̂ and divided by the axis length.
fn transform(args: &VjpArgs<'_>) -> VjpResult {
    let Some(Value::Polyline(curve)) = args.inputs.first() else {
        return Err(internal("the transform needs a curve"));
    };
    let vector = |k: usize, default: DVec3| match args.inputs.get(k) {
        Some(Value::Vector(v) | Value::Point(v)) => *v,
        _ => default,
    };
    let number = |k: usize, default: f64| {
        args.inputs
            .get(k)
            .and_then(Value::as_f64)
            .unwrap_or(default)
    };
    let angle = number(2, 0.0);
    let axis = vector(3, DVec3::Z);
    let centre = vector(4, DVec3::ZERO);
    let scale = number(5, 1.0);
    let mirror = match args.inputs.get(6) {
        Some(Value::Plane(p)) => Some(p.normal.normalize()),
        _ => None,
    };
    let rotates = angle != 0.0;
    let k = if rotates || args.wanted[2] {
        cnets_geometry::plane::unit(axis, "rotation axis").map_err(|_| {
            NodeError::new("the rotation's derivative needs a non-zero rotation axis")
        })?
    } else {
        DVec3::Z
    };
    let (sin, cos) = angle.to_radians().sin_cos();
    let c = points(&args.cotangent(0));
    if c.len() != curve.points.len() {
        return Err(internal(
            "the transform's cotangent does not match its points",
        ));
    }
    let (mut gt, mut gc, mut gk) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
    let (mut gs, mut ga) = (0.0, 0.0);
    let mut gp = Vec::with_capacity(c.len());
    for (p, g) in curve.points.iter().zip(c) {
        gt += g;
        let q = match mirror {
            Some(n) => g - n * (2.0 * n.dot(g)),
            None => g,
        };
        gc += q;
        let v0 = *p - centre;
        let v = v0 * scale;
        let vbar = if rotates {
            ga += q.dot(-v * sin + k.cross(v) * cos + k * (k.dot(v) * sin));
            gk += v.cross(q) * sin + (q * k.dot(v) + v * q.dot(k)) * (1.0 - cos);
            q * cos + q.cross(k) * sin + k * (k.dot(q) * (1.0 - cos))
        } else {
            ga += q.dot(k.cross(v));
            q
        };
        gs += vbar.dot(v0);
        gp.push(vbar * scale);
        gc -= vbar * scale;
    }
    let gaxis = if rotates {
        (gk - k * k.dot(gk)) / axis.length()
    } else {
        DVec3::ZERO
    };
    let w = args.wanted;
    Ok(vec![
        w[0].then(|| flat(&gp)),
        w[1].then(|| gt.to_array().to_vec()),
        w[2].then(|| vec![ga.to_radians()]),
        w[3].then(|| gaxis.to_array().to_vec()),
        w[4].then(|| gc.to_array().to_vec()),
        w[5].then(|| vec![gs]),
        None,
    ])
}

// ---------------------------------------------------------------------------------------------
// curve.resample

/// One point of an arc-length resampling.
#[derive(Debug, Clone, Copy)]
enum ArcSample {
    /// The curve's first point.
    First,
    /// The curve's last point (open curves).
    Last,
    /// `lerp(points[seg], points[seg + 1], u)` at arc position `total · fraction`; `inside` when
    /// u was not clamped (it then moves with the arc position).
    On {
        seg: usize,
        fraction: f64,
        u: f64,
        inside: bool,
    },
}

/// The cumulative lengths of `points` from the first.
fn cumulative(points: &[DVec3]) -> Vec<f64> {
    let mut acc = 0.0;
    let mut out = vec![0.0];
    for w in points.windows(2) {
        acc += w[0].distance(w[1]);
        out.push(acc);
    }
    out
}

/// The samples of `curves::resample_by_count` on the swept `points`, as it places them.
fn arc_samples(points: &[DVec3], closed: bool, count: usize) -> Vec<ArcSample> {
    let cum = cumulative(points);
    let total = cum[cum.len() - 1];
    let intervals = if closed { count } else { count - 1 };
    let mut seg = 0;
    let mut out = Vec::with_capacity(count);
    for k in 0..count {
        if k == 0 {
            out.push(ArcSample::First);
            continue;
        }
        if !closed && k + 1 == count {
            out.push(ArcSample::Last);
            continue;
        }
        let s = total * k as f64 / intervals as f64;
        while seg + 2 < points.len() && cum[seg + 1] < s {
            seg += 1;
        }
        let (sa, sb) = (cum[seg], cum[seg + 1]);
        let (u, inside) = if sb > sa {
            let raw = (s - sa) / (sb - sa);
            (raw.clamp(0.0, 1.0), (0.0..=1.0).contains(&raw))
        } else {
            (0.0, false)
        };
        out.push(ArcSample::On {
            seg,
            fraction: k as f64 / intervals as f64,
            u,
            inside,
        });
    }
    out
}

/// `curve.resample`'s inputs as its run reads them: the curve, the point count and whether the
/// points are equal chords.
fn resample_run(inputs: &[Value]) -> Result<(std::sync::Arc<Polyline>, usize, bool), NodeError> {
    let curve = input::<k::Polyline>(inputs, 0, "curve")?;
    let count = input::<k::Integer>(inputs, 1, "count")?;
    let length = input::<Option<k::Number>>(inputs, 2, "length")?;
    let chords = input::<k::Boolean>(inputs, 3, "chords")?;
    let n = match length {
        Some(target) => {
            let edges =
                curves::resample::edge_count_for_length(curve.length(), target, curve.closed)?;
            if curve.closed { edges } else { edges + 1 }
        }
        None => usize::try_from(count)
            .map_err(|_| NodeError::new(format!("count must be 0 or more, got {count}")))?,
    };
    Ok((curve, n, chords))
}

/// Adds the cotangents of the cumulative lengths `cum_bar` of the swept `points` to `g`.
fn pull_lengths(points: &[DVec3], cum_bar: &[f64], g: &mut [DVec3]) {
    let mut carry = 0.0;
    for i in (1..points.len()).rev() {
        carry += cum_bar[i];
        let e = points[i] - points[i - 1];
        let l = e.length();
        if l > 0.0 {
            let u = e / l;
            g[i] += u * carry;
            g[i - 1] -= u * carry;
        }
    }
}

/// Folds the cotangent of a closed curve's swept repeat of its first point into the first point.
fn fold(mut g: Vec<DVec3>, closed: bool) -> Vec<DVec3> {
    if closed && let Some(last) = g.pop() {
        g[0] += last;
    }
    g
}

/// Resampling by arc length: a sample `a + (b − a) u` with u = (s − s_a) / (s_b − s_a),
/// s = total · k / intervals, passes (1 − u) ḡ and u ḡ to a and b and ū = ḡ · (b − a) to the
/// cumulative lengths s_a, s_b and the total, which pass it to the points through the unit edges.
fn resample_arc(points: &[DVec3], closed: bool, count: usize, c: &[DVec3]) -> Vec<DVec3> {
    let cum = cumulative(points);
    let mut g = vec![DVec3::ZERO; points.len()];
    let mut cum_bar = vec![0.0; points.len()];
    let mut total_bar = 0.0;
    let total = cum[cum.len() - 1];
    for (sample, &gk) in arc_samples(points, closed, count).iter().zip(c) {
        match *sample {
            ArcSample::First => g[0] += gk,
            ArcSample::Last => g[points.len() - 1] += gk,
            ArcSample::On {
                seg,
                fraction,
                u,
                inside,
            } => {
                let (a, b) = (points[seg], points[seg + 1]);
                g[seg] += gk * (1.0 - u);
                g[seg + 1] += gk * u;
                if inside {
                    let ubar = gk.dot(b - a);
                    let (sa, sb) = (cum[seg], cum[seg + 1]);
                    let h = sb - sa;
                    let s = total * fraction;
                    let r = (s - sa) / h;
                    total_bar += ubar / h * fraction;
                    cum_bar[seg] += ubar * (r - 1.0) / h;
                    cum_bar[seg + 1] -= ubar * r / h;
                }
            }
        }
    }
    let last = cum_bar.len() - 1;
    cum_bar[last] += total_bar;
    pull_lengths(points, &cum_bar, &mut g);
    g
}

/// The segment and parameter of each point `q[1..]` of an equal-chord division on the swept
/// `points`, found as the walk found them: the first segment at or after the previous point's
/// position that holds the point.
fn chord_positions(points: &[DVec3], q: &[DVec3]) -> Result<Vec<(usize, f64)>, NodeError> {
    let size = points
        .iter()
        .fold(0.0f64, |m, p| m.max(p.abs().max_element()))
        .max(1e-300);
    let (mut seg, mut u_min) = (0usize, 0.0f64);
    let mut out = Vec::with_capacity(q.len());
    for (k, p) in q.iter().enumerate() {
        let found = (seg..points.len() - 1).find_map(|j| {
            let (a, b) = (points[j], points[j + 1]);
            let d = b - a;
            let dd = d.length_squared();
            if dd == 0.0 {
                return None;
            }
            let u = (*p - a).dot(d) / dd;
            let from = if j == seg { u_min } else { 0.0 };
            let on = (a + d * u).distance(*p) <= 1e-9 * size;
            (on && u >= from - 1e-9 && u <= 1.0 + 1e-9).then_some((j, u.clamp(from, 1.0)))
        });
        let Some((j, u)) = found else {
            return Err(internal(&format!(
                "the chord point {} is not on the curve",
                k + 1
            )));
        };
        out.push((j, u));
        (seg, u_min) = (j, u);
    }
    Ok(out)
}

/// Equal chords: q_k = a + (b − a) u_k with |q_k − q_{k−1}| = c, and |end − q_{N−1}| = c. With
/// w_k = q_k − q_{k−1} and d the segment, dq_k = (I − P_k) dL_k + P_k dq_{k−1} + A-terms in dc,
/// P_k = d w_kᵀ / (w_k · d), dL_k = da + u (db − da); the sensitivity to the chord is
/// A_k = d (w_k · A_{k−1} + c) / (w_k · d), and the last chord's condition fixes
/// dc = w_N · (d end − B_{N−1}) / (c + w_N · A_{N−1}). The reverse pass: κ = Σ g_k · A_k /
/// (c + w_N · A_{N−1}) goes to the end as κ w_N and off the last walked point, then the
/// recursion is run backwards.
fn resample_chords(points: &[DVec3], closed: bool, out: &[DVec3], c: &[DVec3]) -> VjpResult {
    let n = points.len();
    let end = points[n - 1];
    // The walked points are out[1..chords]; out[0] is the first point (and out[chords] the end of
    // an open curve).
    let chords = if closed { out.len() } else { out.len() - 1 };
    let q = &out[..chords];
    let positions = chord_positions(points, &q[1..])?;
    let chord = if chords >= 2 {
        q[1].distance(q[0])
    } else {
        end.distance(q[0])
    };
    let mut sens = vec![DVec3::ZERO; chords];
    for k in 1..chords {
        let (j, _) = positions[k - 1];
        let d = points[j + 1] - points[j];
        let w = q[k] - q[k - 1];
        let wd = w.dot(d);
        if wd == 0.0 {
            return Err(NodeError::new(format!(
                "chord {k} is tangent to the sphere about its start (no derivative)"
            )));
        }
        sens[k] = d * ((w.dot(sens[k - 1]) + chord) / wd);
    }
    let wn = end - q[chords - 1];
    let den = chord + wn.dot(sens[chords - 1]);
    if den == 0.0 {
        return Err(NodeError::new(
            "the last chord is tangent to the curve's end (no derivative)",
        ));
    }
    let mut gq: Vec<DVec3> = c[..chords].to_vec();
    let kappa = gq.iter().zip(&sens).map(|(g, a)| g.dot(*a)).sum::<f64>() / den;
    let mut g = vec![DVec3::ZERO; n];
    g[n - 1] += wn * kappa;
    if !closed {
        g[n - 1] += c[chords];
    }
    gq[chords - 1] -= wn * kappa;
    let mut beta = gq[chords - 1];
    for k in (1..chords).rev() {
        let (j, u) = positions[k - 1];
        let d = points[j + 1] - points[j];
        let w = q[k] - q[k - 1];
        let along = w * (d.dot(beta) / w.dot(d));
        let lbar = beta - along;
        g[j] += lbar * (1.0 - u);
        g[j + 1] += lbar * u;
        beta = gq[k - 1] + along;
    }
    g[0] += beta;
    Ok(vec![Some(flat(&fold(g, closed)))])
}

/// `curve.resample`: by arc length or in equal chords, on the piece of the run (see the module
/// docs). Count and target length have zero cotangents (the count is a whole number).
fn resample(args: &VjpArgs<'_>) -> VjpResult {
    let (curve, count, chords) = resample_run(args.inputs)?;
    let Some(Value::Polyline(out)) = args.outputs.first() else {
        return Err(internal("the resampling's output is a curve"));
    };
    let c = points(&args.cotangent(0));
    if c.len() != out.points.len() || out.points.len() != count {
        return Err(internal(
            "the resampling's cotangent does not match its points",
        ));
    }
    let points = curve.swept_points();
    let g = if chords {
        resample_chords(&points, curve.closed, &out.points, &c)?
            .pop()
            .flatten()
            .unwrap_or_default()
    } else {
        flat(&fold(
            resample_arc(&points, curve.closed, count, &c),
            curve.closed,
        ))
    };
    Ok(vec![args.wanted[0].then_some(g), None, None, None])
}

/// `curve.resample`'s piece: the point count and the segment every point lies on.
fn resample_branch(inputs: &[Value]) -> Option<Branch> {
    let (curve, count, chords) = resample_run(inputs).ok()?;
    let points = curve.swept_points();
    let segments: Vec<usize> = if chords {
        let out = curves::divide_equal_chords(&curve, count).ok()?;
        let walked = if curve.closed { count } else { count - 1 };
        chord_positions(&points, &out.points[1..walked])
            .ok()?
            .into_iter()
            .map(|(j, _)| j)
            .collect()
    } else {
        if count < if curve.closed { 3 } else { 2 } {
            return None;
        }
        arc_samples(&points, curve.closed, count)
            .into_iter()
            .filter_map(|s| match s {
                ArcSample::On { seg, .. } => Some(seg),
                _ => None,
            })
            .collect()
    };
    Some(Branch {
        key: key_of(
            [count as u64, u64::from(chords)]
                .into_iter()
                .chain(segments.iter().map(|&j| j as u64)),
        ),
        summary: format!(
            "{count} points{}, inner points on segments {}",
            if chords { " (equal chords)" } else { "" },
            listed(&segments)
        ),
    })
}

// ---------------------------------------------------------------------------------------------
// curve.spline

/// `curve.spline`'s inputs as its run reads them.
fn spline_run(inputs: &[Value]) -> Result<(Spline, Vec<DVec3>, usize), NodeError> {
    let points = input::<k::List<k::Point>>(inputs, 0, "points")?;
    let closed = input::<k::Boolean>(inputs, 1, "closed")?;
    let count = input::<k::Integer>(inputs, 2, "count")?;
    let kind = input::<k::Choice<SplineMethod>>(inputs, 3, "method")?;
    let count = usize::try_from(count)
        .map_err(|_| NodeError::new(format!("count must be 0 or more, got {count}")))?;
    let spline = Spline::new(kind, &points, closed)?;
    Ok((spline, points, count))
}

/// One sample of `Spline::sample_even`.
#[derive(Debug, Clone, Copy)]
enum SplineSample {
    /// The first control point.
    First,
    /// The last control point (open splines).
    Last,
    /// The spline at `t`, interpolated in table interval `cursor` at ratio `r` of the arc
    /// positions (`interpolated` false: the interval has no length and t is its start), arc
    /// position `total · fraction`.
    At {
        cursor: usize,
        t: f64,
        r: f64,
        fraction: f64,
        interpolated: bool,
    },
}

/// The samples of `Spline::sample_even` placed in `table`, as it places them.
fn spline_samples(table: &[(f64, f64)], closed: bool, count: usize) -> Vec<SplineSample> {
    let total = table[table.len() - 1].1;
    let intervals = if closed { count } else { count - 1 };
    let mut out = Vec::with_capacity(count);
    let mut cursor = 0;
    for k in 0..count {
        if !closed && k + 1 == count {
            out.push(SplineSample::Last);
            break;
        }
        if k == 0 {
            out.push(SplineSample::First);
            continue;
        }
        let s = total * k as f64 / intervals as f64;
        while cursor + 1 < table.len() - 1 && table[cursor + 1].1 < s {
            cursor += 1;
        }
        let (ta, sa) = table[cursor];
        let (tb, sb) = table[cursor + 1];
        let fraction = k as f64 / intervals as f64;
        out.push(if sb > sa {
            let r = (s - sa) / (sb - sa);
            SplineSample::At {
                cursor,
                t: ta + (tb - ta) * r,
                r,
                fraction,
                interpolated: true,
            }
        } else {
            SplineSample::At {
                cursor,
                t: ta,
                r: 0.0,
                fraction,
                interpolated: false,
            }
        });
    }
    out
}

/// Where a point of a Catmull–Rom span comes from.
#[derive(Debug, Clone, Copy)]
enum Source {
    Point(usize),
    Before,
    After,
}

/// A spline's data and the cotangents gathered on it.
struct SplineAdjoint {
    kind: SplineKind,
    closed: bool,
    /// Control points (a closed spline's first repeated at the end).
    pts: Vec<DVec3>,
    knots: Vec<f64>,
    /// The phantom points before the first and after the last span.
    ends: [DVec3; 2],
    /// Natural: the second derivatives at the knots.
    second: Vec<DVec3>,
    pts_bar: Vec<DVec3>,
    ends_bar: [DVec3; 2],
    knots_bar: Vec<f64>,
    second_bar: Vec<DVec3>,
}

impl SplineAdjoint {
    fn new(spline: &Spline, controls: &[DVec3]) -> Self {
        let closed = spline.is_closed();
        let mut pts = controls.to_vec();
        if closed {
            pts.push(controls[0]);
        }
        let n = pts.len();
        let ends = if closed {
            [pts[n - 2], pts[1]]
        } else {
            [2.0 * pts[0] - pts[1], 2.0 * pts[n - 1] - pts[n - 2]]
        };
        Self {
            kind: spline.kind(),
            closed,
            knots: spline.knots().to_vec(),
            second: spline.second_derivatives().to_vec(),
            ends,
            pts_bar: vec![DVec3::ZERO; n],
            ends_bar: [DVec3::ZERO; 2],
            knots_bar: vec![0.0; n],
            second_bar: vec![DVec3::ZERO; n],
            pts,
        }
    }

    /// The span `Spline::eval` evaluates `t` on.
    fn span(&self, t: f64) -> usize {
        let (t0, t1) = (self.knots[0], self.knots[self.knots.len() - 1]);
        let t = if t.is_nan() { t0 } else { t.clamp(t0, t1) };
        self.knots
            .partition_point(|&k| k <= t)
            .saturating_sub(1)
            .min(self.knots.len() - 2)
    }

    /// The extended point `i` (−1 … n) of a Catmull–Rom spline and its knot as a combination
    /// of knots.
    fn extended(&self, i: isize) -> (Source, DVec3, [(usize, f64); 3]) {
        let n = self.pts.len();
        if i < 0 {
            let knot = if self.closed {
                [(0, 1.0), (n - 1, -1.0), (n - 2, 1.0)]
            } else {
                [(0, 2.0), (1, -1.0), (0, 0.0)]
            };
            (Source::Before, self.ends[0], knot)
        } else if i as usize >= n {
            let knot = if self.closed {
                [(n - 1, 1.0), (1, 1.0), (0, -1.0)]
            } else {
                [(n - 1, 2.0), (n - 2, -1.0), (0, 0.0)]
            };
            (Source::After, self.ends[1], knot)
        } else {
            let i = i as usize;
            (
                Source::Point(i),
                self.pts[i],
                [(i, 1.0), (0, 0.0), (0, 0.0)],
            )
        }
    }

    fn knot_value(&self, knot: &[(usize, f64); 3]) -> f64 {
        knot.iter().map(|&(i, w)| self.knots[i] * w).sum()
    }

    /// Passes the cotangent `g` of the spline's point at `t` to the spline's data; returns the
    /// cotangent of `t`.
    fn eval_reverse(&mut self, t: f64, g: DVec3) -> f64 {
        if g == DVec3::ZERO {
            return 0.0;
        }
        let i = self.span(t);
        match self.kind {
            SplineKind::CatmullRom => {
                let ext: Vec<_> = (0..4).map(|k| self.extended(i as isize - 1 + k)).collect();
                type D = Dual<5>;
                let tk: Vec<D> = ext
                    .iter()
                    .enumerate()
                    .map(|(k, e)| D::variable(self.knot_value(&e.2), k))
                    .collect();
                let tt = D::variable(t, 4);
                let unit = |k: usize| {
                    let mut e = [D::constant(0.0); 4];
                    e[k] = D::constant(1.0);
                    e
                };
                let lerp = |a: [D; 4], b: [D; 4], ta: D, tb: D| {
                    let den = tb - ta;
                    let (wa, wb) = ((tb - tt) / den, (tt - ta) / den);
                    [0, 1, 2, 3].map(|k| a[k] * wa + b[k] * wb)
                };
                let a1 = lerp(unit(0), unit(1), tk[0], tk[1]);
                let a2 = lerp(unit(1), unit(2), tk[1], tk[2]);
                let a3 = lerp(unit(2), unit(3), tk[2], tk[3]);
                let b1 = lerp(a1, a2, tk[0], tk[2]);
                let b2 = lerp(a2, a3, tk[1], tk[3]);
                let w = lerp(b1, b2, tk[1], tk[2]);
                let mut tbar = 0.0;
                let mut knot_bar = [0.0; 4];
                for (k, (source, p, _)) in ext.iter().enumerate() {
                    let gp = g * w[k].v;
                    match *source {
                        Source::Point(j) => self.pts_bar[j] += gp,
                        Source::Before => self.ends_bar[0] += gp,
                        Source::After => self.ends_bar[1] += gp,
                    }
                    let s = g.dot(*p);
                    tbar += s * w[k].d[4];
                    for (kb, d) in knot_bar.iter_mut().zip(&w[k].d) {
                        *kb += s * d;
                    }
                }
                for ((_, _, knot), kb) in ext.iter().zip(knot_bar) {
                    for &(j, c) in knot {
                        self.knots_bar[j] += c * kb;
                    }
                }
                tbar
            }
            SplineKind::Natural => {
                type D = Dual<3>;
                let (ta, tb, tt) = (
                    D::variable(self.knots[i], 0),
                    D::variable(self.knots[i + 1], 1),
                    D::variable(t, 2),
                );
                let h = tb - ta;
                let (a, b) = (tb - tt, tt - ta);
                let sixth = D::constant(1.0 / 6.0);
                let c_ma = a * a * a / (h * 6.0) - h * sixth * a;
                let c_mb = b * b * b / (h * 6.0) - h * sixth * b;
                let (c_pa, c_pb) = (a / h, b / h);
                self.pts_bar[i] += g * c_pa.v;
                self.pts_bar[i + 1] += g * c_pb.v;
                self.second_bar[i] += g * c_ma.v;
                self.second_bar[i + 1] += g * c_mb.v;
                let terms = [
                    (c_pa, g.dot(self.pts[i])),
                    (c_pb, g.dot(self.pts[i + 1])),
                    (c_ma, g.dot(self.second[i])),
                    (c_mb, g.dot(self.second[i + 1])),
                ];
                let mut tbar = 0.0;
                for (c, s) in terms {
                    self.knots_bar[i] += s * c.d[0];
                    self.knots_bar[i + 1] += s * c.d[1];
                    tbar += s * c.d[2];
                }
                tbar
            }
        }
    }

    /// The natural spline's second derivatives m solve A(h) m = r(p, h): λ = A⁻¹ m̄ (A is
    /// symmetric), then p̄ −= (∂F/∂p)ᵀ λ and h̄ −= (∂F/∂h)ᵀ λ for F = A m − r.
    fn second_reverse(&mut self) {
        if self.kind != SplineKind::Natural {
            return;
        }
        let n = self.pts.len();
        let h: Vec<f64> = self.knots.windows(2).map(|w| w[1] - w[0]).collect();
        // Rows (i, the index before it, the index after it) and their multipliers.
        let (rows, lambda): (Vec<[usize; 3]>, Vec<DVec3>) = if self.closed {
            // The n − 1 distinct points, cyclic; m and p hold the first again at index n − 1.
            let count = n - 1;
            let prev = |i: usize| (i + count - 1) % count;
            let a: Vec<f64> = (0..count).map(|i| h[prev(i)]).collect();
            let b: Vec<f64> = (0..count).map(|i| 2.0 * (h[prev(i)] + h[i])).collect();
            let mut rhs = self.second_bar[..count].to_vec();
            rhs[0] += self.second_bar[count];
            let lambda = solve_cyclic(&a, &b, &h[..count], &rhs);
            ((0..count).map(|i| [i, prev(i), i + 1]).collect(), lambda)
        } else {
            if n < 3 {
                return;
            }
            let inner = n - 2;
            let a: Vec<f64> = (0..inner).map(|k| h[k]).collect();
            let b: Vec<f64> = (0..inner).map(|k| 2.0 * (h[k] + h[k + 1])).collect();
            let lambda = thomas(&a, &b, &h[1..], &self.second_bar[1..n - 1]);
            ((1..n - 1).map(|i| [i, i - 1, i + 1]).collect(), lambda)
        };
        let mut h_bar = vec![0.0; h.len()];
        let (m, p) = (&self.second, &self.pts);
        for (&[i, prev, next], &l) in rows.iter().zip(&lambda) {
            // F_i = h_prev m_prev + 2 (h_prev + h_i) m_i + h_i m_next
            //       − 6 ((p_next − p_i) / h_i − (p_i − p_prev) / h_prev).
            let (hp, hi) = (h[prev], h[i]);
            let d_hp = m[prev] + 2.0 * m[i] - (p[i] - p[prev]) * (6.0 / (hp * hp));
            let d_hi = 2.0 * m[i] + m[next] + (p[next] - p[i]) * (6.0 / (hi * hi));
            h_bar[prev] -= l.dot(d_hp);
            h_bar[i] -= l.dot(d_hi);
            self.pts_bar[next] += l * (6.0 / hi);
            self.pts_bar[i] -= l * (6.0 / hi + 6.0 / hp);
            self.pts_bar[prev] += l * (6.0 / hp);
        }
        for (k, hb) in h_bar.into_iter().enumerate() {
            self.knots_bar[k + 1] += hb;
            self.knots_bar[k] -= hb;
        }
    }

    /// Passes the phantom points' and the knots' cotangents to the control points; returns the
    /// control points' cotangents.
    fn finish(mut self) -> Vec<DVec3> {
        self.second_reverse();
        let n = self.pts.len();
        let [e0, e1] = self.ends_bar;
        if self.closed {
            self.pts_bar[n - 2] += e0;
            self.pts_bar[1] += e1;
        } else {
            self.pts_bar[0] += 2.0 * e0;
            self.pts_bar[1] -= e0;
            self.pts_bar[n - 1] += 2.0 * e1;
            self.pts_bar[n - 2] -= e1;
        }
        // t_{j+1} = t_j + |p_{j+1} − p_j|^½.
        let mut acc = 0.0;
        for j in (0..n - 1).rev() {
            acc += self.knots_bar[j + 1];
            let e = self.pts[j + 1] - self.pts[j];
            let d = e.length();
            let dbar = acc * 0.5 / d.sqrt();
            let u = e / d;
            self.pts_bar[j + 1] += u * dbar;
            self.pts_bar[j] -= u * dbar;
        }
        fold(self.pts_bar, self.closed)
    }
}

/// Solves a tridiagonal system (a: sub-diagonal, a[0] unused; c: super-diagonal, c[n−1] unused).
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

/// Solves a cyclic tridiagonal system (a[0] the top-right corner, c[n−1] the bottom-left one) by
/// the Sherman–Morrison correction of a tridiagonal solve.
fn solve_cyclic(a: &[f64], b: &[f64], c: &[f64], r: &[DVec3]) -> Vec<DVec3> {
    let n = b.len();
    let (alpha, beta) = (c[n - 1], a[0]);
    let gamma = -b[0];
    let mut bb = b.to_vec();
    bb[0] -= gamma;
    bb[n - 1] -= alpha * beta / gamma;
    let x = thomas(a, &bb, c, r);
    let mut u = vec![DVec3::ZERO; n];
    u[0] = DVec3::splat(gamma);
    u[n - 1] = DVec3::splat(alpha);
    let z = thomas(a, &bb, c, &u);
    let fact = (x[0] + x[n - 1] * (beta / gamma)) / (DVec3::ONE + z[0] + z[n - 1] * (beta / gamma));
    x.iter().zip(&z).map(|(xi, zi)| *xi - fact * *zi).collect()
}

/// `curve.spline`: the reverse pass through the samples, the arc-length table, the spans, the
/// natural spline's solve, the phantom points and the centripetal knots (see the module docs).
fn spline(args: &VjpArgs<'_>) -> VjpResult {
    let (spline, controls, count) = spline_run(args.inputs)?;
    let c = points(&args.cotangent(0));
    if c.len() != count {
        return Err(internal("the spline's cotangent does not match its points"));
    }
    let table = spline.arc_table(ARC_TABLE_PER_SPAN);
    let mut adj = SplineAdjoint::new(&spline, &controls);
    let n = adj.pts.len();
    let mut t_bar = vec![0.0; table.len()];
    let mut s_bar = vec![0.0; table.len()];
    let mut total_bar = 0.0;
    for (sample, &g) in spline_samples(&table, adj.closed, count).iter().zip(&c) {
        match *sample {
            SplineSample::First => adj.pts_bar[0] += g,
            SplineSample::Last => adj.pts_bar[n - 1] += g,
            SplineSample::At {
                cursor,
                t,
                r,
                fraction,
                interpolated,
            } => {
                let tb = adj.eval_reverse(t, g);
                if interpolated {
                    let ((ta, sa), (tb_, sb)) = (table[cursor], table[cursor + 1]);
                    let h = sb - sa;
                    let dt = tb_ - ta;
                    t_bar[cursor] += tb * (1.0 - r);
                    t_bar[cursor + 1] += tb * r;
                    total_bar += tb * dt / h * fraction;
                    s_bar[cursor] += tb * dt * (r - 1.0) / h;
                    s_bar[cursor + 1] -= tb * dt * r / h;
                } else {
                    t_bar[cursor] += tb;
                }
            }
        }
    }
    let last = table.len() - 1;
    s_bar[last] += total_bar;
    // The table's chords: e_0 is the first control point, e_i the spline at the table's t_i.
    let e: Vec<DVec3> = table
        .iter()
        .enumerate()
        .map(|(i, &(t, _))| if i == 0 { adj.pts[0] } else { spline.eval(t) })
        .collect();
    let mut e_bar = vec![DVec3::ZERO; table.len()];
    pull_lengths(&e, &s_bar, &mut e_bar);
    adj.pts_bar[0] += e_bar[0];
    for i in 1..table.len() {
        t_bar[i] += adj.eval_reverse(table[i].0, e_bar[i]);
    }
    // t_i = k_s + (k_{s+1} − k_s) k / per_span for entry i = 1 + s per_span + (k − 1).
    adj.knots_bar[0] += t_bar[0];
    for (i, tb) in t_bar.iter().enumerate().skip(1) {
        let (span, k) = (
            (i - 1) / ARC_TABLE_PER_SPAN,
            (i - 1) % ARC_TABLE_PER_SPAN + 1,
        );
        let f = k as f64 / ARC_TABLE_PER_SPAN as f64;
        adj.knots_bar[span] += tb * (1.0 - f);
        adj.knots_bar[span + 1] += tb * f;
    }
    let g = adj.finish();
    Ok(vec![args.wanted[0].then(|| flat(&g)), None, None, None])
}

/// `curve.spline`'s piece: the arc-length table interval every sample falls in.
fn spline_branch(inputs: &[Value]) -> Option<Branch> {
    let (spline, _, count) = spline_run(inputs).ok()?;
    if count < if spline.is_closed() { 3 } else { 2 } {
        return None;
    }
    let table = spline.arc_table(ARC_TABLE_PER_SPAN);
    let cursors: Vec<usize> = spline_samples(&table, spline.is_closed(), count)
        .into_iter()
        .filter_map(|s| match s {
            SplineSample::At { cursor, .. } => Some(cursor),
            _ => None,
        })
        .collect();
    Some(Branch {
        key: key_of(cursors.iter().map(|&c| c as u64)),
        summary: format!(
            "{count} samples, inner ones in arc-table intervals {} ({ARC_TABLE_PER_SPAN} per span)",
            listed(&cursors)
        ),
    })
}

// ---------------------------------------------------------------------------------------------
// Lookup

/// The product of a curve node, by id.
pub fn product(id: &str) -> Option<Product> {
    Some(match id {
        "curve.polyline" => polyline,
        "curve.transform" => transform,
        "curve.resample" => resample,
        "curve.spline" => spline,
        _ => return None,
    })
}

/// The branch function of a piecewise curve node, by id, mapped over lists as the node is (the
/// pieces of every run in one key).
pub fn branch(
    id: &str,
    ports: Vec<PortDef>,
) -> Option<impl Fn(&[Value], &[Value]) -> Option<Branch> + Send + Sync + 'static> {
    let f: BranchFn = match id {
        "curve.polyline" => polyline_branch,
        "curve.resample" => resample_branch,
        "curve.spline" => spline_branch,
        _ => return None,
    };
    Some(move |inputs: &[Value], _outputs: &[Value]| mapped_branch(&ports, inputs, f))
}

/// `f` on every run of a node mapped over lists (the broadcast rule of the evaluator); one piece
/// for all of them.
pub(super) fn mapped_branch(ports: &[PortDef], inputs: &[Value], f: BranchFn) -> Option<Branch> {
    fn collect(ports: &[PortDef], inputs: &[Value], f: BranchFn, out: &mut Vec<Branch>) {
        match broadcast::level(ports, inputs) {
            Level::Run => out.extend(f(inputs)),
            Level::Split(split) => {
                if split.empty {
                    return;
                }
                let mut slots = inputs.to_vec();
                for k in 0..split.count {
                    split.fill(&mut slots, k);
                    collect(ports, &slots, f, out);
                }
            }
        }
    }
    let mut pieces = Vec::new();
    collect(ports, inputs, f, &mut pieces);
    match pieces.len() {
        0 => None,
        1 => pieces.pop(),
        runs => Some(Branch {
            key: key_of(pieces.iter().map(|p| p.key)),
            summary: format!("{runs} runs; the first: {}", pieces[0].summary),
        }),
    }
}
