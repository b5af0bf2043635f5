//! Graph mappers: functions y = f(x) drawn in a unit square by a curve type and a few handles, then
//! stretched onto an x domain and a y range (Grasshopper's Graph Mapper).
//!
//! Handles are points (u, v) in the **unit square** of the graph: u runs along the x domain
//! (u = 0 at `x_start`, 1 at `x_end`), v along the y range (v = 0 at `y_start`, 1 at `y_end`). A
//! mapped value is `y = y_start + f(u) · (y_end − y_start)` with
//! `u = (x − x_start) / (x_end − x_start)`. Handles may lie outside the unit square.
//!
//! Each kind passes exactly through its *on-curve* handles (bezier and conic also have control
//! handles that shape the curve without lying on it). Outside the span of its handles a kind either
//! **extends** its formula (linear, parabola, sine, gaussian) or **holds** the value of the nearest
//! end handle (bezier, power, square root, conic, piecewise, spline). See `docs/inputs.md`.

use glam::DVec2;

use crate::GeometryError;

/// The curve type of a graph mapper.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MapperKind {
    /// Straight line through handles A, B (A.u ≠ B.u); extends beyond them.
    Linear,
    /// Cubic Bézier P0, P1, P2, P3: P0 and P3 are on the curve, P1 and P2 are its two tangent
    /// handles (P0.u < P3.u and P1.u, P2.u within [P0.u, P3.u], so it is a function of u). Holds.
    Bezier,
    /// Parabola with vertex V and another point P (P.u ≠ V.u); extends.
    Parabola,
    /// v = A.v + (B.v − A.v)·s^p, s = (u − A.u)/(B.u − A.u), from A to B through C, which fixes
    /// the exponent p (C strictly inside the box spanned by A and B). Holds.
    Power,
    /// Cosine wave whose consecutive extrema are A and B (A.u ≠ B.u; half period B.u − A.u);
    /// extends periodically.
    Sine,
    /// Bell curve v = P.v·exp(−(u − P.u)²/(2σ²)) over the baseline v = 0, with peak P and a flank
    /// point W (W.v/P.v in (0, 1), W.u ≠ P.u) that fixes σ; extends.
    Gaussian,
    /// v = A.v + (B.v − A.v)·√s, s = (u − A.u)/(B.u − A.u), from A (vertical tangent) to B. Holds.
    SquareRoot,
    /// Rational quadratic Bézier (a conic arc) from P0 to P2 with control point P1, through the
    /// shoulder point S (strictly inside the triangle P0 P1 P2), which fixes the weight
    /// (w < 1 ellipse, = 1 parabola, > 1 hyperbola). Needs P0.u < P2.u and P1.u within them. Holds.
    Conic,
    /// Straight segments through two or more points (sorted by u, distinct u). Holds.
    Piecewise,
    /// Smooth monotone-preserving cubic (Fritsch–Carlson PCHIP) through two or more points (sorted
    /// by u, distinct u): monotone wherever the points are, never overshoots them. Holds.
    Spline,
}

impl MapperKind {
    /// Every kind, in documentation order.
    pub const ALL: [MapperKind; 10] = [
        Self::Linear,
        Self::Bezier,
        Self::Parabola,
        Self::Power,
        Self::Sine,
        Self::Gaussian,
        Self::SquareRoot,
        Self::Conic,
        Self::Piecewise,
        Self::Spline,
    ];

    /// The name used in graph files.
    pub fn name(self) -> &'static str {
        match self {
            Self::Linear => "linear",
            Self::Bezier => "bezier",
            Self::Parabola => "parabola",
            Self::Power => "power",
            Self::Sine => "sine",
            Self::Gaussian => "gaussian",
            Self::SquareRoot => "sqrt",
            Self::Conic => "conic",
            Self::Piecewise => "piecewise",
            Self::Spline => "spline",
        }
    }

    /// Parses a name (case-insensitive; `square-root`, `bell`, `polyline` and `smooth` are accepted
    /// as aliases of `sqrt`, `gaussian`, `piecewise` and `spline`).
    pub fn parse(s: &str) -> Result<Self, GeometryError> {
        // A word with any other character (a control, format or combining one) is refused.
        let norm = super::choice_key(s).unwrap_or_else(|| "\u{0}".to_string());
        let kind = match norm.as_str() {
            "linear" | "line" => Self::Linear,
            "bezier" => Self::Bezier,
            "parabola" => Self::Parabola,
            "power" => Self::Power,
            "sine" | "sin" => Self::Sine,
            "gaussian" | "bell" | "gauss" => Self::Gaussian,
            "sqrt" | "squareroot" => Self::SquareRoot,
            "conic" => Self::Conic,
            "piecewise" | "polyline" | "piecewiselinear" => Self::Piecewise,
            "spline" | "smooth" => Self::Spline,
            _ => {
                return Err(GeometryError::Degenerate(format!(
                    "unknown graph type '{s}': expected one of {}",
                    Self::ALL.map(Self::name).join(", ")
                )));
            }
        };
        Ok(kind)
    }

    /// The handles used when none are given.
    pub fn default_handles(self) -> Vec<DVec2> {
        let p = DVec2::new;
        let h = std::f64::consts::FRAC_1_SQRT_2;
        match self {
            Self::Linear | Self::SquareRoot => vec![p(0.0, 0.0), p(1.0, 1.0)],
            Self::Bezier => vec![p(0.0, 0.0), p(0.5, 0.0), p(0.5, 1.0), p(1.0, 1.0)],
            Self::Parabola => vec![p(0.5, 1.0), p(0.0, 0.0)],
            Self::Power => vec![p(0.0, 0.0), p(1.0, 1.0), p(0.5, 0.25)],
            Self::Sine => vec![p(0.0, 0.0), p(0.5, 1.0)],
            Self::Gaussian => vec![p(0.5, 1.0), p(0.3, 0.5)],
            // A quarter circle from (0, 0) to (1, 1) about (1, 0).
            Self::Conic => vec![p(0.0, 0.0), p(0.0, 1.0), p(1.0, 1.0), p(1.0 - h, h)],
            Self::Piecewise => vec![p(0.0, 0.0), p(0.5, 1.0), p(1.0, 0.5)],
            Self::Spline => vec![p(0.0, 0.0), p(0.3, 0.6), p(0.7, 0.4), p(1.0, 1.0)],
        }
    }

    /// How many handles the kind takes: (minimum, maximum); `None` = no maximum.
    pub fn handle_count(self) -> (usize, Option<usize>) {
        match self {
            Self::Linear | Self::Parabola | Self::Sine | Self::Gaussian | Self::SquareRoot => {
                (2, Some(2))
            }
            Self::Power => (3, Some(3)),
            Self::Bezier | Self::Conic => (4, Some(4)),
            Self::Piecewise | Self::Spline => (2, None),
        }
    }

    /// True when the kind extends its formula beyond its handles; false when it holds the value of
    /// the nearest end handle.
    pub fn extends(self) -> bool {
        matches!(
            self,
            Self::Linear | Self::Parabola | Self::Sine | Self::Gaussian
        )
    }
}

/// The evaluated shape of a mapper (precomputed coefficients).
#[derive(Debug, Clone, PartialEq)]
enum Shape {
    Linear {
        a: DVec2,
        slope: f64,
    },
    Bezier([DVec2; 4]),
    Parabola {
        vertex: DVec2,
        a: f64,
    },
    Power {
        a: DVec2,
        b: DVec2,
        exponent: f64,
    },
    Sine {
        a: DVec2,
        b: DVec2,
    },
    Gaussian {
        peak: DVec2,
        two_sigma2: f64,
    },
    Conic {
        p: [DVec2; 3],
        w: f64,
    },
    Piecewise(Vec<DVec2>),
    Spline {
        points: Vec<DVec2>,
        slopes: Vec<f64>,
    },
}

/// A graph mapper: a kind and its validated handles.
#[derive(Debug, Clone, PartialEq)]
pub struct GraphMapper {
    kind: MapperKind,
    handles: Vec<DVec2>,
    shape: Shape,
}

fn bad(kind: MapperKind, msg: impl std::fmt::Display) -> GeometryError {
    GeometryError::Degenerate(format!("{} graph: {msg}", kind.name()))
}

impl GraphMapper {
    /// A mapper of `kind` with its default handles.
    pub fn with_defaults(kind: MapperKind) -> Self {
        match Self::new(kind, &kind.default_handles()) {
            Ok(m) => m,
            // Default handles are valid by construction (tested); fall back to a straight line.
            Err(_) => Self {
                kind: MapperKind::Linear,
                handles: vec![DVec2::ZERO, DVec2::ONE],
                shape: Shape::Linear {
                    a: DVec2::ZERO,
                    slope: 1.0,
                },
            },
        }
    }

    /// A mapper of `kind` through `handles` (unit-square coordinates), validated as documented on
    /// [`MapperKind`]. Piecewise and spline handles are sorted by u.
    pub fn new(kind: MapperKind, handles: &[DVec2]) -> Result<Self, GeometryError> {
        let (min, max) = kind.handle_count();
        if handles.len() < min || max.is_some_and(|m| handles.len() > m) {
            return Err(GeometryError::WrongLength {
                what: "graph mapper handles",
                expected: match max {
                    Some(m) if m == min => format!("{min} for a {} graph", kind.name()),
                    _ => format!("at least {min} for a {} graph", kind.name()),
                },
                got: handles.len(),
            });
        }
        if let Some(index) = handles.iter().position(|h| !h.is_finite()) {
            return Err(GeometryError::NonFinite {
                what: "graph mapper handle",
                index,
            });
        }
        let h = handles;
        let shape = match kind {
            MapperKind::Linear => {
                let (a, b) = (h[0], h[1]);
                if a.x == b.x {
                    return Err(bad(kind, "the two handles have the same u"));
                }
                Shape::Linear {
                    a,
                    slope: (b.y - a.y) / (b.x - a.x),
                }
            }
            MapperKind::Bezier => {
                let [p0, p1, p2, p3] = [h[0], h[1], h[2], h[3]];
                if p0.x >= p3.x {
                    return Err(bad(
                        kind,
                        "the start handle must lie left of the end handle",
                    ));
                }
                for (k, c) in [(1, p1), (2, p2)] {
                    if c.x < p0.x || c.x > p3.x {
                        return Err(bad(
                            kind,
                            format!("tangent handle {k} must lie between the end handles in u"),
                        ));
                    }
                }
                Shape::Bezier([p0, p1, p2, p3])
            }
            MapperKind::Parabola => {
                let (v, p) = (h[0], h[1]);
                if v.x == p.x {
                    return Err(bad(kind, "the point has the same u as the vertex"));
                }
                Shape::Parabola {
                    vertex: v,
                    a: (p.y - v.y) / ((p.x - v.x) * (p.x - v.x)),
                }
            }
            MapperKind::Power => {
                let (a, b, c) = (h[0], h[1], h[2]);
                if a.x >= b.x || a.y == b.y {
                    return Err(bad(
                        kind,
                        "the end handle must lie right of the start handle, at another v",
                    ));
                }
                let s = (c.x - a.x) / (b.x - a.x);
                let r = (c.y - a.y) / (b.y - a.y);
                if !(s > 0.0 && s < 1.0 && r > 0.0 && r < 1.0) {
                    return Err(bad(
                        kind,
                        "the shape handle must lie strictly inside the box of the end handles",
                    ));
                }
                let exponent = r.ln() / s.ln();
                if !exponent.is_finite() || exponent <= 0.0 {
                    return Err(bad(kind, "the shape handle gives no usable exponent"));
                }
                Shape::Power { a, b, exponent }
            }
            MapperKind::Sine => {
                let (a, b) = (h[0], h[1]);
                if a.x == b.x {
                    return Err(bad(kind, "the two extrema have the same u"));
                }
                Shape::Sine { a, b }
            }
            MapperKind::Gaussian => {
                let (p, w) = (h[0], h[1]);
                let ratio = w.y / p.y;
                if p.y == 0.0 || !(ratio > 0.0 && ratio < 1.0) {
                    return Err(bad(
                        kind,
                        "the flank handle must lie between the baseline v = 0 and the peak",
                    ));
                }
                if w.x == p.x {
                    return Err(bad(kind, "the flank handle has the same u as the peak"));
                }
                let d = w.x - p.x;
                Shape::Gaussian {
                    peak: p,
                    two_sigma2: d * d / (1.0 / ratio).ln(),
                }
            }
            MapperKind::SquareRoot => {
                let (a, b) = (h[0], h[1]);
                if a.x >= b.x {
                    return Err(bad(
                        kind,
                        "the end handle must lie right of the start handle",
                    ));
                }
                Shape::Power {
                    a,
                    b,
                    exponent: 0.5,
                }
            }
            MapperKind::Conic => {
                let [p0, p1, p2, s] = [h[0], h[1], h[2], h[3]];
                if p0.x >= p2.x {
                    return Err(bad(
                        kind,
                        "the start handle must lie left of the end handle",
                    ));
                }
                if p1.x < p0.x || p1.x > p2.x {
                    return Err(bad(
                        kind,
                        "the control handle must lie between the end handles in u",
                    ));
                }
                let area = cross(p1 - p0, p2 - p0);
                if area.abs() <= 1e-12 * (p2 - p0).length_squared() {
                    return Err(bad(kind, "the end and control handles are collinear"));
                }
                let b0 = cross(p1 - s, p2 - s) / area;
                let b1 = cross(p2 - s, p0 - s) / area;
                let b2 = cross(p0 - s, p1 - s) / area;
                if !(b0 > 0.0 && b1 > 0.0 && b2 > 0.0) {
                    return Err(bad(
                        kind,
                        "the shoulder handle must lie strictly inside the triangle of the other three",
                    ));
                }
                Shape::Conic {
                    p: [p0, p1, p2],
                    w: b1 / (2.0 * (b0 * b2).sqrt()),
                }
            }
            MapperKind::Piecewise | MapperKind::Spline => {
                let mut points = h.to_vec();
                points.sort_by(|a, b| a.x.total_cmp(&b.x));
                if let Some(k) = points.windows(2).position(|w| w[0].x == w[1].x) {
                    return Err(bad(kind, format!("two handles share u = {}", points[k].x)));
                }
                if kind == MapperKind::Piecewise {
                    Shape::Piecewise(points)
                } else {
                    let slopes = pchip_slopes(&points);
                    Shape::Spline { points, slopes }
                }
            }
        };
        Ok(Self {
            kind,
            handles: handles.to_vec(),
            shape,
        })
    }

    /// The kind.
    pub fn kind(&self) -> MapperKind {
        self.kind
    }

    /// The handles as given.
    pub fn handles(&self) -> &[DVec2] {
        &self.handles
    }

    /// The handles the curve passes through exactly (bezier: P0, P3; conic: P0, P2, S; others: all).
    pub fn on_curve_handles(&self) -> Vec<DVec2> {
        let h = &self.handles;
        match self.kind {
            MapperKind::Bezier => vec![h[0], h[3]],
            MapperKind::Conic => vec![h[0], h[2], h[3]],
            _ => h.clone(),
        }
    }

    /// f(u) in unit-square coordinates. `u` should be finite (NaN gives NaN).
    pub fn eval(&self, u: f64) -> f64 {
        match &self.shape {
            Shape::Linear { a, slope } => a.y + (u - a.x) * slope,
            Shape::Parabola { vertex, a } => vertex.y + a * (u - vertex.x) * (u - vertex.x),
            Shape::Sine { a, b } => {
                let mid = 0.5 * (a.y + b.y);
                let amp = 0.5 * (a.y - b.y);
                if u == a.x {
                    a.y
                } else if u == b.x {
                    b.y
                } else {
                    mid + amp * (std::f64::consts::PI * (u - a.x) / (b.x - a.x)).cos()
                }
            }
            Shape::Gaussian { peak, two_sigma2 } => {
                let d = u - peak.x;
                peak.y * (-(d * d) / two_sigma2).exp()
            }
            Shape::Power { a, b, exponent } => {
                if u <= a.x {
                    a.y
                } else if u >= b.x {
                    b.y
                } else {
                    let s = (u - a.x) / (b.x - a.x);
                    a.y + (b.y - a.y) * s.powf(*exponent)
                }
            }
            Shape::Bezier(p) => {
                if u <= p[0].x {
                    p[0].y
                } else if u >= p[3].x {
                    p[3].y
                } else {
                    let t = solve_monotone(|t| bezier(p, t).x, u);
                    bezier(p, t).y
                }
            }
            Shape::Conic { p, w } => {
                if u <= p[0].x {
                    p[0].y
                } else if u >= p[2].x {
                    p[2].y
                } else {
                    let t = solve_monotone(|t| conic(p, *w, t).x, u);
                    conic(p, *w, t).y
                }
            }
            Shape::Piecewise(points) => piecewise(points, u, |k, t, _h| {
                points[k].y + (points[k + 1].y - points[k].y) * t
            }),
            Shape::Spline { points, slopes } => piecewise(points, u, |k, t, h| {
                let (t2, t3) = (t * t, t * t * t);
                let h00 = 2.0 * t3 - 3.0 * t2 + 1.0;
                let h10 = t3 - 2.0 * t2 + t;
                let h01 = -2.0 * t3 + 3.0 * t2;
                let h11 = t3 - t2;
                h00 * points[k].y
                    + h10 * h * slopes[k]
                    + h01 * points[k + 1].y
                    + h11 * h * slopes[k + 1]
            }),
        }
    }

    /// Maps one value x: u = (x − x_start)/(x_end − x_start), y = y_start + f(u)·(y_end − y_start).
    pub fn map(&self, x: f64, domain: Domains) -> Result<f64, GeometryError> {
        domain.check()?;
        self.map_checked(x, &domain, 0)
    }

    fn map_checked(&self, x: f64, d: &Domains, index: usize) -> Result<f64, GeometryError> {
        if !x.is_finite() {
            return Err(GeometryError::NonFinite {
                what: "graph mapper input value",
                index,
            });
        }
        let u = (x - d.x_start) / (d.x_end - d.x_start);
        self.finish(self.eval(u), d, index)
    }

    fn finish(&self, v: f64, d: &Domains, index: usize) -> Result<f64, GeometryError> {
        let y = d.y_start + v * (d.y_end - d.y_start);
        if y.is_finite() {
            Ok(y)
        } else {
            Err(GeometryError::Degenerate(format!(
                "{} graph: value {index} overflows (the curve grows too fast outside its handles)",
                self.kind.name()
            )))
        }
    }

    /// Maps every value (see [`GraphMapper::map`]).
    pub fn map_values(&self, values: &[f64], domain: Domains) -> Result<Vec<f64>, GeometryError> {
        domain.check()?;
        values
            .iter()
            .enumerate()
            .map(|(k, &x)| self.map_checked(x, &domain, k))
            .collect()
    }

    /// Samples f at `count` evenly spaced x from `x_start` to `x_end` (both included); count 1
    /// samples `x_start` only, count 0 gives empty lists. Returns (x, y).
    pub fn sample(
        &self,
        count: usize,
        domain: Domains,
    ) -> Result<(Vec<f64>, Vec<f64>), GeometryError> {
        domain.check()?;
        if count > super::MAX_POINTS {
            return Err(GeometryError::Degenerate(format!(
                "count {count} is too large (at most {})",
                super::MAX_POINTS
            )));
        }
        let mut xs = Vec::with_capacity(count);
        let mut ys = Vec::with_capacity(count);
        for k in 0..count {
            let u = if count == 1 {
                0.0
            } else {
                k as f64 / (count - 1) as f64
            };
            let x = if k + 1 == count && count > 1 {
                domain.x_end
            } else {
                domain.x_start + u * (domain.x_end - domain.x_start)
            };
            xs.push(x);
            ys.push(self.finish(self.eval(u), &domain, k)?);
        }
        Ok((xs, ys))
    }
}

/// The x domain and y range a mapper is stretched onto.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Domains {
    /// x mapped to u = 0.
    pub x_start: f64,
    /// x mapped to u = 1 (≠ `x_start`; may be smaller, which mirrors the graph).
    pub x_end: f64,
    /// y at v = 0.
    pub y_start: f64,
    /// y at v = 1 (may equal or be smaller than `y_start`).
    pub y_end: f64,
}

impl Default for Domains {
    fn default() -> Self {
        Self {
            x_start: 0.0,
            x_end: 1.0,
            y_start: 0.0,
            y_end: 1.0,
        }
    }
}

impl Domains {
    /// Checks that all bounds are finite and the x domain is not empty.
    pub fn check(&self) -> Result<(), GeometryError> {
        for (what, v) in [
            ("x_start", self.x_start),
            ("x_end", self.x_end),
            ("y_start", self.y_start),
            ("y_end", self.y_end),
        ] {
            super::check_finite(what, v)?;
        }
        if self.x_start == self.x_end {
            return Err(GeometryError::Degenerate(format!(
                "the x domain is empty (x_start = x_end = {})",
                self.x_start
            )));
        }
        if !(self.x_end - self.x_start).is_finite() || !(self.y_end - self.y_start).is_finite() {
            return Err(GeometryError::Degenerate(
                "the x domain or y range is too wide (overflows)".into(),
            ));
        }
        Ok(())
    }
}

fn cross(a: DVec2, b: DVec2) -> f64 {
    a.x * b.y - a.y * b.x
}

fn bezier(p: &[DVec2; 4], t: f64) -> DVec2 {
    let s = 1.0 - t;
    p[0] * (s * s * s) + p[1] * (3.0 * s * s * t) + p[2] * (3.0 * s * t * t) + p[3] * (t * t * t)
}

fn conic(p: &[DVec2; 3], w: f64, t: f64) -> DVec2 {
    let s = 1.0 - t;
    let (b0, b1, b2) = (s * s, 2.0 * w * s * t, t * t);
    (p[0] * b0 + p[1] * b1 + p[2] * b2) / (b0 + b1 + b2)
}

/// Solves x(t) = u for t in [0, 1] by bisection, x non-decreasing with x(0) < u < x(1).
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

/// Evaluates a per-interval formula `f(k, t, h)` on sorted points, holding the end values outside.
fn piecewise(points: &[DVec2], u: f64, f: impl Fn(usize, f64, f64) -> f64) -> f64 {
    let n = points.len();
    if u.is_nan() {
        return f64::NAN;
    }
    if u <= points[0].x {
        return points[0].y;
    }
    if u >= points[n - 1].x {
        return points[n - 1].y;
    }
    let k = points.partition_point(|p| p.x <= u) - 1;
    let h = points[k + 1].x - points[k].x;
    f(k, (u - points[k].x) / h, h)
}

/// Fritsch–Carlson (Fritsch–Butland weighted harmonic mean) slopes of a monotone-preserving cubic
/// Hermite interpolant, with the shape-preserving three-point end conditions.
fn pchip_slopes(p: &[DVec2]) -> Vec<f64> {
    let n = p.len();
    let h: Vec<f64> = p.windows(2).map(|w| w[1].x - w[0].x).collect();
    let delta: Vec<f64> = p
        .windows(2)
        .zip(&h)
        .map(|(w, h)| (w[1].y - w[0].y) / h)
        .collect();
    if n == 2 {
        return vec![delta[0], delta[0]];
    }
    let mut d = vec![0.0; n];
    for k in 1..n - 1 {
        let (a, b) = (delta[k - 1], delta[k]);
        if a * b <= 0.0 {
            d[k] = 0.0;
        } else {
            let w1 = 2.0 * h[k] + h[k - 1];
            let w2 = h[k] + 2.0 * h[k - 1];
            d[k] = (w1 + w2) / (w1 / a + w2 / b);
        }
    }
    let end = |h0: f64, h1: f64, d0: f64, d1: f64| -> f64 {
        let mut s = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
        if s.signum() != d0.signum() || d0 == 0.0 {
            s = 0.0;
        } else if d0.signum() != d1.signum() && s.abs() > 3.0 * d0.abs() {
            s = 3.0 * d0;
        }
        s
    };
    d[0] = end(h[0], h[1], delta[0], delta[1]);
    d[n - 1] = end(h[n - 2], h[n - 3], delta[n - 2], delta[n - 3]);
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: f64, y: f64) -> DVec2 {
        DVec2::new(x, y)
    }

    #[test]
    fn every_kind_hits_its_default_on_curve_handles() {
        for kind in MapperKind::ALL {
            let m = GraphMapper::new(kind, &kind.default_handles())
                .unwrap_or_else(|e| panic!("{kind:?}: {e}"));
            for h in m.on_curve_handles() {
                let v = m.eval(h.x);
                assert!((v - h.y).abs() < 1e-12, "{kind:?} at {h}: {v}");
            }
            assert_eq!(MapperKind::parse(kind.name()).unwrap(), kind);
        }
    }

    #[test]
    fn closed_forms() {
        let m = GraphMapper::with_defaults(MapperKind::Power);
        assert!((m.eval(0.3) - 0.09).abs() < 1e-12); // exponent 2
        let m = GraphMapper::with_defaults(MapperKind::SquareRoot);
        assert!((m.eval(0.25) - 0.5).abs() < 1e-15);
        let m = GraphMapper::with_defaults(MapperKind::Parabola);
        assert!((m.eval(0.25) - 0.75).abs() < 1e-15);
        let m = GraphMapper::with_defaults(MapperKind::Sine);
        assert!((m.eval(1.0) - 0.0).abs() < 1e-15);
        assert!((m.eval(0.25) - 0.5).abs() < 1e-15);
        // The default conic is the quarter circle about (1, 0).
        let m = GraphMapper::with_defaults(MapperKind::Conic);
        for u in [0.1, 0.4, 0.77] {
            let v: f64 = m.eval(u);
            assert!(
                ((u - 1.0f64).powi(2) + v * v - 1.0).abs() < 1e-12,
                "{u} {v}"
            );
        }
    }

    #[test]
    fn holding_and_extending_outside_the_handles() {
        for kind in MapperKind::ALL {
            let m = GraphMapper::with_defaults(kind);
            let hs = m.on_curve_handles();
            let first = hs.iter().min_by(|a, b| a.x.total_cmp(&b.x)).unwrap();
            if !kind.extends() {
                assert_eq!(m.eval(first.x - 5.0), first.y, "{kind:?}");
            }
        }
        let lin = GraphMapper::with_defaults(MapperKind::Linear);
        assert_eq!(lin.eval(2.0), 2.0);
    }

    #[test]
    fn domains_stretch_the_unit_square() {
        let m = GraphMapper::with_defaults(MapperKind::Linear);
        let d = Domains {
            x_start: 10.0,
            x_end: 20.0,
            y_start: 1.0,
            y_end: -1.0,
        };
        assert!((m.map(15.0, d).unwrap() - 0.0).abs() < 1e-15);
        let (xs, ys) = m.sample(3, d).unwrap();
        assert_eq!(xs, vec![10.0, 15.0, 20.0]);
        assert_eq!(ys, vec![1.0, 0.0, -1.0]);
        assert_eq!(m.sample(0, d).unwrap().0.len(), 0);
        assert_eq!(m.sample(1, d).unwrap(), (vec![10.0], vec![1.0]));
        let empty = Domains { x_end: 10.0, ..d };
        assert!(
            m.sample(3, empty)
                .unwrap_err()
                .to_string()
                .contains("x domain is empty")
        );
        assert!(m.map_values(&[1.0, f64::NAN], d).is_err());
    }

    #[test]
    fn invalid_handles_are_explained() {
        use MapperKind::*;
        let cases: Vec<(MapperKind, Vec<DVec2>)> = vec![
            (Linear, vec![p(0.5, 0.0), p(0.5, 1.0)]),
            (Linear, vec![p(0.0, 0.0)]),
            (
                Bezier,
                vec![p(0.0, 0.0), p(1.5, 0.0), p(0.5, 1.0), p(1.0, 1.0)],
            ),
            (Parabola, vec![p(0.5, 1.0), p(0.5, 0.0)]),
            (Power, vec![p(0.0, 0.0), p(1.0, 1.0), p(0.5, 1.5)]),
            (Gaussian, vec![p(0.5, 1.0), p(0.2, 1.2)]),
            (Gaussian, vec![p(0.5, 0.0), p(0.2, 0.0)]),
            (SquareRoot, vec![p(1.0, 0.0), p(0.0, 1.0)]),
            (
                Conic,
                vec![p(0.0, 0.0), p(0.0, 1.0), p(1.0, 1.0), p(0.9, 0.1)],
            ),
            (
                Conic,
                vec![p(0.0, 0.0), p(0.5, 0.5), p(1.0, 1.0), p(0.5, 0.5)],
            ),
            (Piecewise, vec![p(0.2, 0.0), p(0.2, 1.0)]),
            (Spline, vec![p(0.0, 0.0), p(f64::NAN, 1.0)]),
        ];
        for (kind, handles) in cases {
            assert!(
                GraphMapper::new(kind, &handles).is_err(),
                "{kind:?} {handles:?}"
            );
        }
        assert!(
            MapperKind::parse("wobble")
                .unwrap_err()
                .to_string()
                .contains("linear")
        );
    }

    /// Checks that `f` is monotone (non-decreasing when `up`) on [a, b].
    fn monotone(f: impl Fn(f64) -> f64, a: f64, b: f64, up: bool) -> bool {
        let n = 400;
        (0..n).all(|k| {
            let (u0, u1) = (
                a + (b - a) * k as f64 / n as f64,
                a + (b - a) * (k + 1) as f64 / n as f64,
            );
            let d = f(u1) - f(u0);
            if up { d >= -1e-15 } else { d <= 1e-15 }
        })
    }

    #[test]
    fn analytic_kinds_are_monotone_where_documented() {
        let lin = GraphMapper::new(MapperKind::Linear, &[p(0.2, 0.9), p(0.8, 0.1)]).unwrap();
        assert!(monotone(|u| lin.eval(u), -1.0, 2.0, false));
        let sine = GraphMapper::new(MapperKind::Sine, &[p(0.2, 0.9), p(0.6, 0.1)]).unwrap();
        assert!(monotone(|u| sine.eval(u), 0.2, 0.6, false));
        assert!(monotone(|u| sine.eval(u), 0.6, 1.0, true));
        let gauss = GraphMapper::new(MapperKind::Gaussian, &[p(0.4, 0.8), p(0.3, 0.2)]).unwrap();
        assert!(monotone(|u| gauss.eval(u), -1.0, 0.4, true));
        assert!(monotone(|u| gauss.eval(u), 0.4, 2.0, false));
        let par = GraphMapper::new(MapperKind::Parabola, &[p(0.3, 0.1), p(0.9, 0.8)]).unwrap();
        assert!(monotone(|u| par.eval(u), -1.0, 0.3, false));
        assert!(monotone(|u| par.eval(u), 0.3, 2.0, true));
        let sqrt = GraphMapper::new(MapperKind::SquareRoot, &[p(0.1, 0.9), p(0.7, 0.2)]).unwrap();
        assert!(monotone(|u| sqrt.eval(u), -1.0, 2.0, false));
        assert!((sqrt.eval(0.1 + 0.6 * 0.25) - (0.9 - 0.7 * 0.5)).abs() < 1e-15);
    }

    #[test]
    fn spline_is_monotone_on_monotone_handles_and_does_not_overshoot() {
        let hs = [
            p(0.0, 0.0),
            p(0.1, 0.8),
            p(0.2, 0.85),
            p(0.9, 0.9),
            p(1.0, 1.0),
        ];
        let m = GraphMapper::new(MapperKind::Spline, &hs).unwrap();
        let mut prev = f64::NEG_INFINITY;
        for k in 0..=1000 {
            let v = m.eval(k as f64 / 1000.0);
            assert!(v >= prev - 1e-15, "not monotone at {k}");
            prev = v;
        }
        for h in hs {
            assert!((m.eval(h.x) - h.y).abs() < 1e-15);
        }
        // A peak handle is a local maximum: no overshoot above it.
        let bump = [p(0.0, 0.0), p(0.5, 1.0), p(1.0, 0.0)];
        let m = GraphMapper::new(MapperKind::Spline, &bump).unwrap();
        assert!((0..=100).all(|k| m.eval(k as f64 / 100.0) <= 1.0));
    }
}
