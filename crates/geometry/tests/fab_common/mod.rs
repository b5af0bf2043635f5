//! Shared helpers of the fabrication tests: cone-nets built with the kernel and independent checks
//! (distances to lines, angles between edges, polygon overlap).
#![allow(dead_code)]

use cnets_geometry::conenet::{ConeNet, CtubeInputs, construct_ctube};
use cnets_geometry::{DVec3, Polyline, QuadGrid};
use glam::DVec2;
use proptest::prelude::*;

/// A curved open directrix of `m` points.
pub fn directrix(m: usize) -> Polyline {
    Polyline::open(
        (0..m)
            .map(|j| {
                let t = j as f64;
                DVec3::new(t, 0.3 * (0.7 * t).sin(), 0.04 * t * t)
            })
            .collect(),
    )
}

/// A generatrix of `n` points on an arc around X_0 (closed: a full circle of `n` points).
pub fn generatrix(n: usize, closed: bool) -> Polyline {
    let points = (0..n)
        .map(|i| {
            let t = if closed {
                std::f64::consts::TAU * i as f64 / n as f64
            } else {
                0.3 + 2.2 * i as f64 / (n - 1) as f64
            };
            DVec3::new(-0.1 * t.cos(), 1.2 * t.cos(), 0.9 * t.sin() + 0.2)
        })
        .collect();
    Polyline { points, closed }
}

/// Apex values alternating around 1, with one translation (a = 1).
pub fn apex(m: usize) -> Vec<f64> {
    (1..m)
        .map(|j| match j % 3 {
            0 => 1.0,
            1 => 0.93,
            _ => 1.06,
        })
        .collect()
}

/// A C-tube cone-net (Monge planes) of n × m vertices.
pub fn cone_net(n: usize, m: usize, closed: bool) -> ConeNet {
    construct_ctube(&CtubeInputs::new(directrix(m), generatrix(n, closed)).apex(apex(m)))
        .expect("the test cone-net constructs")
}

/// Distance from `p` to the line through `a` and `b`.
pub fn distance_to_line(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let d = b - a;
    (p - a).cross(d).length() / d.length()
}

/// Sine of the angle between two non-zero vectors.
pub fn sine(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length() / (a.length() * b.length())
}

/// The largest quad planarity (libigl measure) of a grid.
pub fn max_planarity(mesh: &QuadGrid) -> f64 {
    mesh.quads()
        .map(|(_, q)| cnets_geometry::conenet::quad_planarity(q))
        .fold(0.0, f64::max)
}

/// Every edge of the grid as ((i, j), (i', j')), including wrapping edges.
pub fn edges(mesh: &QuadGrid) -> Vec<((usize, usize), (usize, usize))> {
    let mut out = Vec::new();
    for i in 0..mesh.rows {
        for j in 0..mesh.cols {
            if j + 1 < mesh.cols || (mesh.wrap_cols && mesh.cols > 2) {
                out.push(((i, j), (i, (j + 1) % mesh.cols)));
            }
            if i + 1 < mesh.rows || (mesh.wrap_rows && mesh.rows > 2) {
                out.push(((i, j), ((i + 1) % mesh.rows, j)));
            }
        }
    }
    out
}

/// The largest sine of the angle between corresponding edges of two grids of the same size.
pub fn max_edge_sine(a: &QuadGrid, b: &QuadGrid) -> f64 {
    edges(a)
        .into_iter()
        .map(|(p, q)| {
            sine(
                a.at(q.0, q.1) - a.at(p.0, p.1),
                b.at(q.0, q.1) - b.at(p.0, p.1),
            )
        })
        .fold(0.0, f64::max)
}

/// Whether two closed polygons (XY) overlap: an edge crossing or a vertex of one strictly inside the
/// other.
pub fn polygons_overlap(a: &[DVec2], b: &[DVec2]) -> bool {
    let seg = |p: &[DVec2], k: usize| (p[k], p[(k + 1) % p.len()]);
    let orient = |a: DVec2, b: DVec2, c: DVec2| (b - a).perp_dot(c - a);
    for i in 0..a.len() {
        let (p1, p2) = seg(a, i);
        for j in 0..b.len() {
            let (q1, q2) = seg(b, j);
            let d1 = orient(q1, q2, p1);
            let d2 = orient(q1, q2, p2);
            let d3 = orient(p1, p2, q1);
            let d4 = orient(p1, p2, q2);
            if d1 * d2 < 0.0 && d3 * d4 < 0.0 {
                return true;
            }
        }
    }
    inside(a[0], b) || inside(b[0], a)
}

/// Point in polygon (even-odd rule).
pub fn inside(p: DVec2, poly: &[DVec2]) -> bool {
    let mut c = false;
    for k in 0..poly.len() {
        let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
        if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x) {
            c = !c;
        }
    }
    c
}

/// A random well-posed C-tube design: (directrix, generatrix, apex values).
pub fn random_design() -> impl Strategy<Value = (Polyline, Polyline, Vec<f64>)> {
    (3usize..8, 2usize..7, any::<bool>()).prop_flat_map(|(m, n, closed)| {
        let n = if closed { n.max(3) } else { n };
        (
            prop::collection::vec((0.6..1.4f64, -0.3..0.3f64, -0.3..0.3f64), m - 1),
            prop::collection::vec((0.6..1.6f64, -0.15..0.15f64), n),
            prop::collection::vec(0.8..1.25f64, m - 1),
            Just(closed),
        )
            .prop_map(|(steps, radii, apex, closed)| {
                let mut p = DVec3::ZERO;
                let mut dir = DVec3::X;
                let mut xs = vec![p];
                for (len, ty, tz) in steps {
                    p += dir * len;
                    xs.push(p);
                    dir = (dir + DVec3::new(0.0, ty, tz)).normalize();
                }
                let n = radii.len();
                let gs = radii
                    .iter()
                    .enumerate()
                    .map(|(i, (r, dx))| {
                        let t = if closed {
                            std::f64::consts::TAU * i as f64 / n as f64
                        } else {
                            0.3 + 2.0 * i as f64 / (n - 1).max(1) as f64
                        };
                        DVec3::new(*dx, r * t.cos(), r * t.sin())
                    })
                    .collect();
                (Polyline::open(xs), Polyline { points: gs, closed }, apex)
            })
    })
}
