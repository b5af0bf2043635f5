//! The gradient of `mapper.graph` (`cnets_geometry::curves::mapper`) in its handles (u and v),
//! its domains (`x_start`, `x_end`, `y_start`, `y_end`) and the `values` it maps, for every curve
//! kind.
//!
//! Each mapped value is y = y₀ + f(u; H)·(y₁ − y₀) with u = (x − x₀)/(x₁ − x₀) (or u = k/(n − 1)
//! when sampling). f and its partials in u and the handles come from one forward-mode evaluation
//! of the kind's formula on dual numbers (lane 0: u; lanes 1 + 2i, 2 + 2i: handle i's u and v):
//!
//! - closed forms (linear, parabola, power, sine, gaussian, square root): the formula itself,
//!   the power's exponent ln r / ln s through its shape handle, the gaussian's σ through its flank;
//! - bezier and conic: the curve parameter t of x(t) = u is found by bisection as the run does, its
//!   derivative by the implicit function theorem, dt = −(∂x/∂H dH − du)/x′(t);
//! - piecewise and spline: the interval the value falls in (handles sorted by u); the spline's
//!   Fritsch–Carlson slopes on the piece the run is on — which limiter branch every knot took
//!   (harmonic mean or zero at an extremum; at the ends the three-point formula, zero or clamped
//!   to 3δ) — the node's branch, so the optimizer reports a step that crosses one;
//! - the held ends (values beyond the end handles of bezier, power, sqrt, conic, piecewise,
//!   spline) depend on the end handle's v only.
//!
//! `kind` and `count` are not differentiable. Mappers with more than 23 handles decline (finite
//! differences of the node's run).

use cnets_engine::PortKind;
use cnets_engine::optimize::branch::{Branch, key_of};
use cnets_engine::optimize::vjp::{VjpArgs, VjpResult};
use cnets_engine::prelude::*;
use cnets_geometry::curves::MapperKind;
use glam::DVec2;

use super::dual::Dual;
use crate::choices::MapperCurve;

/// Dual lanes: u and 23 handles (u, v).
const N: usize = 48;
type D = Dual<N>;

fn c(x: f64) -> D {
    D::constant(x)
}

fn exp(a: D) -> D {
    let e = a.v.exp();
    D {
        v: e,
        d: a.d.map(|x| x * e),
    }
}

fn ln(a: D) -> D {
    D {
        v: a.v.ln(),
        d: a.d.map(|x| x / a.v),
    }
}

fn cos(a: D) -> D {
    let (s, co) = a.v.sin_cos();
    D {
        v: co,
        d: a.d.map(|x| -x * s),
    }
}

/// A handle of dual numbers.
#[derive(Clone, Copy)]
struct P {
    x: D,
    y: D,
}

fn sub(a: P, b: P) -> P {
    P {
        x: a.x - b.x,
        y: a.y - b.y,
    }
}

fn cross(a: P, b: P) -> D {
    a.x * b.y - a.y * b.x
}

/// What the run read.
struct Run {
    kind: MapperKind,
    /// The handles given (None: the kind's defaults).
    given: Option<Vec<DVec3>>,
    handles: Vec<DVec2>,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    /// The mapped values (None: sampling).
    values: Option<Vec<f64>>,
    /// u of every output value.
    us: Vec<f64>,
}

fn input<K: PortKind>(inputs: &[Value], k: usize, name: &str) -> Result<K::In, NodeError> {
    K::extract(inputs.get(k).unwrap_or(&Value::Null), name)
}

fn number(inputs: &[Value], k: usize, default: f64) -> f64 {
    inputs.get(k).and_then(Value::as_f64).unwrap_or(default)
}

fn read(inputs: &[Value]) -> Result<Run, NodeError> {
    let kind = input::<k::Choice<MapperCurve>>(inputs, 0, "kind")?;
    let given = match inputs.get(1) {
        None | Some(Value::Null) => None,
        Some(_) => Some(input::<k::List<k::Point>>(inputs, 1, "handles")?),
    };
    let handles = match &given {
        Some(h) if !h.is_empty() => h.iter().map(|p| p.truncate()).collect(),
        _ => kind.default_handles(),
    };
    let (x0, x1) = (number(inputs, 2, 0.0), number(inputs, 3, 1.0));
    let (y0, y1) = (number(inputs, 4, 0.0), number(inputs, 5, 1.0));
    let values = match inputs.get(7) {
        None | Some(Value::Null) => None,
        Some(_) => Some(input::<k::List<k::Number>>(inputs, 7, "values")?),
    };
    let us = match &values {
        Some(xs) => xs.iter().map(|x| (x - x0) / (x1 - x0)).collect(),
        None => {
            let n = input::<k::Integer>(inputs, 6, "count")?.max(0) as usize;
            (0..n)
                .map(|k| {
                    if n == 1 {
                        0.0
                    } else {
                        k as f64 / (n - 1) as f64
                    }
                })
                .collect()
        }
    };
    Ok(Run {
        kind,
        given,
        handles,
        x0,
        x1,
        y0,
        y1,
        values,
        us,
    })
}

/// The handles as dual numbers (handle i: lanes 1 + 2i and 2 + 2i).
fn dual_handles(handles: &[DVec2]) -> Result<Vec<P>, NodeError> {
    if 1 + 2 * handles.len() > N {
        return Err(NodeError::new(format!(
            "the graph mapper's derivative takes at most {} handles",
            (N - 1) / 2
        )));
    }
    Ok(handles
        .iter()
        .enumerate()
        .map(|(i, h)| P {
            x: D::variable(h.x, 1 + 2 * i),
            y: D::variable(h.y, 2 + 2 * i),
        })
        .collect())
}

/// Handles sorted by u (stable, as the run sorts them).
fn sorted(h: &[P]) -> Vec<P> {
    let mut s = h.to_vec();
    s.sort_by(|a, b| a.x.v.total_cmp(&b.x.v));
    s
}

/// Per knot, which limiter branch the Fritsch–Carlson slopes took (interior: 0 harmonic mean,
/// 1 zero at an extremum; ends: 0 three-point formula, 1 zero, 2 clamped to 3δ), and the slopes.
fn pchip(p: &[P]) -> (Vec<D>, Vec<u64>) {
    let n = p.len();
    let h: Vec<D> = p.windows(2).map(|w| w[1].x - w[0].x).collect();
    let delta: Vec<D> = p
        .windows(2)
        .zip(&h)
        .map(|(w, h)| (w[1].y - w[0].y) / *h)
        .collect();
    if n == 2 {
        return (vec![delta[0], delta[0]], vec![0, 0]);
    }
    let mut d = vec![c(0.0); n];
    let mut codes = vec![0u64; n];
    for k in 1..n - 1 {
        let (a, b) = (delta[k - 1], delta[k]);
        if a.v * b.v <= 0.0 {
            codes[k] = 1;
        } else {
            let w1 = h[k] * 2.0 + h[k - 1];
            let w2 = h[k] + h[k - 1] * 2.0;
            d[k] = (w1 + w2) / (w1 / a + w2 / b);
        }
    }
    let end = |h0: D, h1: D, d0: D, d1: D| -> (D, u64) {
        let s = ((h0 * 2.0 + h1) * d0 - h0 * d1) / (h0 + h1);
        if s.v.signum() != d0.v.signum() || d0.v == 0.0 {
            (c(0.0), 1)
        } else if d0.v.signum() != d1.v.signum() && s.v.abs() > 3.0 * d0.v.abs() {
            (d0 * 3.0, 2)
        } else {
            (s, 0)
        }
    };
    (d[0], codes[0]) = end(h[0], h[1], delta[0], delta[1]);
    (d[n - 1], codes[n - 1]) = end(h[n - 2], h[n - 3], delta[n - 2], delta[n - 3]);
    (d, codes)
}

/// Whether the monotone spline through sorted handles `p` sits on a branch boundary of its
/// limiter: a step of zero next to a knot, or an end slope at a switch to rounding (handles
/// 0.46, 0.55, 0.52 at u = 0, ½, 1 give an end slope of 3δ up to the last bit).
fn on_limiter_kink(p: &[P]) -> bool {
    let n = p.len();
    if n < 3 {
        return false;
    }
    let delta: Vec<f64> = p
        .windows(2)
        .map(|w| (w[1].y.v - w[0].y.v) / (w[1].x.v - w[0].x.v))
        .collect();
    if delta.contains(&0.0) {
        return true;
    }
    let end = |h0: f64, h1: f64, d0: f64, d1: f64| {
        let s = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
        let near = |a: f64, b: f64| (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1e-300);
        s == 0.0 || near(s.abs(), 3.0 * d0.abs())
    };
    let h = |k: usize| p[k + 1].x.v - p[k].x.v;
    end(h(0), h(1), delta[0], delta[1]) || end(h(n - 2), h(n - 3), delta[n - 2], delta[n - 3])
}

/// The interval of sorted points `u` falls in: None before the first or after the last (held).
fn interval(p: &[P], u: f64) -> Option<usize> {
    let n = p.len();
    if u <= p[0].x.v || u >= p[n - 1].x.v {
        return None;
    }
    Some(p.partition_point(|q| q.x.v <= u) - 1)
}

fn bezier(p: &[P], t: D) -> P {
    let s = c(1.0) - t;
    let (b0, b1, b2, b3) = (s * s * s, s * s * t * 3.0, s * t * t * 3.0, t * t * t);
    P {
        x: p[0].x * b0 + p[1].x * b1 + p[2].x * b2 + p[3].x * b3,
        y: p[0].y * b0 + p[1].y * b1 + p[2].y * b2 + p[3].y * b3,
    }
}

fn conic(p: &[P], w: D, t: D) -> P {
    let s = c(1.0) - t;
    let (b0, b1, b2) = (s * s, w * s * t * 2.0, t * t);
    let sum = b0 + b1 + b2;
    P {
        x: (p[0].x * b0 + p[1].x * b1 + p[2].x * b2) / sum,
        y: (p[0].y * b0 + p[1].y * b1 + p[2].y * b2) / sum,
    }
}

/// The run's bisection for x(t) = u.
fn solve_monotone(x: impl Fn(f64) -> f64, u: f64) -> f64 {
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if x(mid) < u {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The parameter t of x(t) = u on a curve `x` with the derivative of t: −(∂x/∂H − ∂u)/x′(t).
fn implicit_t(x: impl Fn(D) -> D, u: D) -> Result<D, NodeError> {
    let t = solve_monotone(|t| x(c(t)).v, u.v);
    // x′(t) from a dual in t alone (the handles held): lane 0 carries t here.
    let mut probe = x(D::variable(t, 0));
    let fixed = x(c(t));
    let slope = probe.d[0] - fixed.d[0];
    if slope.is_nan() || slope.abs() <= 1e-12 {
        return Err(NodeError::new(
            "the graph mapper's curve is vertical there (no derivative)",
        ));
    }
    probe.v = t;
    for (k, d) in probe.d.iter_mut().enumerate() {
        *d = -(fixed.d[k] - u.d[k]) / slope;
    }
    Ok(probe)
}

/// A region code of a value: 0 before the handles (held), 1 + k in interval k, and the like.
const BEFORE: u64 = 0;
const AFTER: u64 = 1;

/// f(u) on dual numbers, and the region of the value (held before/after, or interval 2 + k).
fn eval(kind: MapperKind, h: &[P], u: D) -> Result<(D, u64), NodeError> {
    let held = |lo: P, hi: P| {
        if u.v <= lo.x.v {
            Some((lo.y, BEFORE))
        } else if u.v >= hi.x.v {
            Some((hi.y, AFTER))
        } else {
            None
        }
    };
    Ok(match kind {
        MapperKind::Linear => {
            let (a, b) = (h[0], h[1]);
            (a.y + (u - a.x) * ((b.y - a.y) / (b.x - a.x)), 2)
        }
        MapperKind::Parabola => {
            let (v, p) = (h[0], h[1]);
            let a = (p.y - v.y) / ((p.x - v.x) * (p.x - v.x));
            (v.y + a * (u - v.x) * (u - v.x), 2)
        }
        MapperKind::Sine => {
            let (a, b) = (h[0], h[1]);
            let mid = (a.y + b.y) * 0.5;
            let amp = (a.y - b.y) * 0.5;
            (
                mid + amp * cos((u - a.x) * std::f64::consts::PI / (b.x - a.x)),
                2,
            )
        }
        MapperKind::Gaussian => {
            let (p, w) = (h[0], h[1]);
            let ratio = w.y / p.y;
            let dw = w.x - p.x;
            let two_sigma2 = dw * dw / -ln(ratio);
            let d = u - p.x;
            (p.y * exp(-(d * d) / two_sigma2), 2)
        }
        MapperKind::Power | MapperKind::SquareRoot => {
            let (a, b) = (h[0], h[1]);
            if let Some(r) = held(a, b) {
                return Ok(r);
            }
            let exponent = if kind == MapperKind::Power {
                let cc = h[2];
                let s = (cc.x - a.x) / (b.x - a.x);
                let r = (cc.y - a.y) / (b.y - a.y);
                ln(r) / ln(s)
            } else {
                c(0.5)
            };
            let s = (u - a.x) / (b.x - a.x);
            (a.y + (b.y - a.y) * exp(exponent * ln(s)), 2)
        }
        MapperKind::Bezier => {
            if let Some(r) = held(h[0], h[3]) {
                return Ok(r);
            }
            let t = implicit_t(|t| bezier(h, t).x, u)?;
            (bezier(h, t).y, 2)
        }
        MapperKind::Conic => {
            let (p0, p1, p2, s) = (h[0], h[1], h[2], h[3]);
            if let Some(r) = held(p0, p2) {
                return Ok(r);
            }
            let area = cross(sub(p1, p0), sub(p2, p0));
            let b0 = cross(sub(p1, s), sub(p2, s)) / area;
            let b1 = cross(sub(p2, s), sub(p0, s)) / area;
            let b2 = cross(sub(p0, s), sub(p1, s)) / area;
            let w = b1 / ((b0 * b2).sqrt() * 2.0);
            let t = implicit_t(|t| conic(h, w, t).x, u)?;
            (conic(h, w, t).y, 2)
        }
        MapperKind::Piecewise | MapperKind::Spline => {
            let p = sorted(h);
            let n = p.len();
            if let Some(r) = held(p[0], p[n - 1]) {
                return Ok(r);
            }
            let Some(k) = interval(&p, u.v) else {
                return Err(NodeError::new("internal: the mapper's interval"));
            };
            let hk = p[k + 1].x - p[k].x;
            let t = (u - p[k].x) / hk;
            let y = if kind == MapperKind::Piecewise {
                p[k].y + (p[k + 1].y - p[k].y) * t
            } else {
                let (slopes, _) = pchip(&p);
                let (t2, t3) = (t * t, t * t * t);
                let h00 = t3 * 2.0 - t2 * 3.0 + c(1.0);
                let h10 = t3 - t2 * 2.0 + t;
                let h01 = t2 * 3.0 - t3 * 2.0;
                let h11 = t3 - t2;
                h00 * p[k].y + h10 * hk * slopes[k] + h01 * p[k + 1].y + h11 * hk * slopes[k + 1]
            };
            (y, 2 + k as u64)
        }
    })
}

/// `mapper.graph`: y_k = y₀ + f(u_k)(y₁ − y₀); the x output is the values (mapping) or
/// x₀ + u_k (x₁ − x₀) (sampling).
fn graph(args: &VjpArgs<'_>) -> VjpResult {
    let run = read(args.inputs)?;
    let h = dual_handles(&run.handles)?;
    if run.kind == MapperKind::Spline && on_limiter_kink(&sorted(&h)) {
        // Exactly on a kink (level neighbouring handles: a step of 0) one side's slope is not what
        // a designer's change sees; the node's own central differences (microseconds) are.
        return Err(NodeError::new(
            "the spline mapper sits on a kink of its slope limiter (level handles)",
        ));
    }
    let cy = args.cotangent(0);
    let cx = args.cotangent(1);
    let ys: Vec<f64> = args
        .outputs
        .first()
        .and_then(Value::as_list)
        .map(|l| l.iter().filter_map(Value::as_f64).collect())
        .unwrap_or_default();
    let n = run.us.len();
    if cy.len() != n || cx.len() != n || ys.len() != n {
        return Err(NodeError::new(
            "internal: the mapper's cotangents do not match its values",
        ));
    }
    let (dy, len) = (run.y1 - run.y0, run.x1 - run.x0);
    let mut gh = vec![0.0; 2 * h.len()];
    let (mut gx0, mut gx1, mut gy0, mut gy1) = (0.0, 0.0, 0.0, 0.0);
    let mut gv = vec![0.0; n];
    for (k, &u) in run.us.iter().enumerate() {
        let (f, _) = eval(run.kind, &h, D::variable(u, 0))?;
        let y = run.y0 + f.v * dy;
        if (y - ys[k]).abs() > 1e-9 * (1.0 + ys[k].abs()) {
            return Err(NodeError::new(format!(
                "internal: the mapper's derivative evaluates {y} where the run gave {}",
                ys[k]
            )));
        }
        let cyk = cy[k];
        gy0 += cyk * (1.0 - f.v);
        gy1 += cyk * f.v;
        for (g, d) in gh.iter_mut().zip(&f.d[1..]) {
            *g += cyk * dy * d;
        }
        let fu = cyk * dy * f.d[0];
        if run.values.is_some() {
            gv[k] = fu / len + cx[k];
            gx0 += fu * (u - 1.0) / len;
            gx1 -= fu * u / len;
        } else {
            gx0 += cx[k] * (1.0 - u);
            gx1 += cx[k] * u;
        }
    }
    let w = |k: usize| args.wanted.get(k).copied().unwrap_or(false);
    let handles = match &run.given {
        Some(given) if w(1) => Some(if given.is_empty() {
            Vec::new()
        } else {
            gh.chunks_exact(2).flat_map(|g| [g[0], g[1], 0.0]).collect()
        }),
        _ => None,
    };
    Ok(vec![
        None,
        handles,
        w(2).then_some(vec![gx0]),
        w(3).then_some(vec![gx1]),
        w(4).then_some(vec![gy0]),
        w(5).then_some(vec![gy1]),
        None,
        (w(7) && run.values.is_some()).then_some(gv),
    ])
}

/// `mapper.graph`'s piece: the region of every value (held before or after the end handles, or
/// the interval between two handles of a piecewise or spline graph) and, for a spline, the
/// limiter branch of every knot's slope. Smooth kinds that extend have one piece.
fn graph_branch(inputs: &[Value], _outputs: &[Value]) -> Option<Branch> {
    let run = read(inputs).ok()?;
    if run.kind.extends() {
        return None;
    }
    let h = dual_handles(&run.handles).ok()?;
    let mut codes = Vec::new();
    let mut regions = Vec::with_capacity(run.us.len());
    for &u in &run.us {
        regions.push(eval(run.kind, &h, c(u)).ok()?.1);
    }
    let (before, after) = (
        regions.iter().filter(|&&r| r == BEFORE).count(),
        regions.iter().filter(|&&r| r == AFTER).count(),
    );
    let mut summary = format!(
        "{} graph: {before} values held before the handles, {after} after, {} between",
        run.kind.name(),
        regions.len() - before - after
    );
    if run.kind == MapperKind::Spline {
        let (_, limits) = pchip(&sorted(&h));
        let zero = limits.iter().filter(|&&l| l == 1).count();
        let clamped = limits.iter().filter(|&&l| l == 2).count();
        summary.push_str(&format!(
            "; spline slopes: {} by the formula, {zero} zero (extrema or end sign), {clamped} \
             clamped to 3δ",
            limits.len() - zero - clamped
        ));
        codes.extend(limits.iter().map(|l| l + 100));
    }
    codes.extend(regions);
    Some(Branch {
        key: key_of(codes),
        summary,
    })
}

/// `list.table`: sum r + c − m, product r·c, mean (r + c)/2 over N rows × M columns.
fn table(args: &VjpArgs<'_>) -> VjpResult {
    let rows = input::<k::List<k::Number>>(args.inputs, 0, "rows")?;
    let columns = input::<k::List<k::Number>>(args.inputs, 1, "columns")?;
    let rule = input::<k::Choice<crate::choices::TableRule>>(args.inputs, 2, "rule")?;
    let (n, m) = (rows.len(), columns.len());
    let g = args.cotangent(0);
    if g.len() != n * m {
        return Err(NodeError::new(
            "internal: the table's cotangent does not match its cells",
        ));
    }
    let mut gr = vec![0.0; n];
    let mut gc = vec![0.0; m];
    let mut gm = 0.0;
    for i in 0..n {
        for j in 0..m {
            let gij = g[i * m + j];
            match rule {
                "sum" => {
                    gr[i] += gij;
                    gc[j] += gij;
                    gm -= gij;
                }
                "product" => {
                    gr[i] += gij * columns[j];
                    gc[j] += gij * rows[i];
                }
                _ => {
                    gr[i] += 0.5 * gij;
                    gc[j] += 0.5 * gij;
                }
            }
        }
    }
    let w = |k: usize| args.wanted.get(k).copied().unwrap_or(false);
    Ok(vec![
        w(0).then_some(gr),
        w(1).then_some(gc),
        None,
        w(3).then_some(vec![gm]),
    ])
}

type Product = fn(&VjpArgs<'_>) -> VjpResult;
type BranchFn = fn(&[Value], &[Value]) -> Option<Branch>;

/// The product of the mapper or the table, by id.
pub fn product(id: &str) -> Option<Product> {
    Some(match id {
        "mapper.graph" => graph,
        "list.table" => table,
        _ => return None,
    })
}

/// The mapper's branch function, by id.
pub fn branch(id: &str) -> Option<BranchFn> {
    (id == "mapper.graph").then_some(graph_branch as BranchFn)
}
