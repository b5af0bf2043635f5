//! Subdivision of polylines: each level doubles the number of edges.

use glam::DVec3;

use super::MAX_POINTS;
use crate::error::check_finite_points;
use crate::{GeometryError, Polyline};

/// How new points are placed at each subdivision level.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SubdivisionScheme {
    /// Edge midpoints are inserted; the shape does not change.
    Linear,
    /// The interpolating four-point scheme (Dyn–Levin–Gregory, w = 1/16): old points stay, new
    /// points are −1/16, 9/16, 9/16, −1/16 of their four neighbours (open ends use the mirrored
    /// phantom points 2P₀ − P₁ and 2P_{n−1} − P_{n−2}). The limit curve is C¹.
    FourPoint,
    /// Chaikin's corner cutting: each edge is replaced by its ¼ and ¾ points (open curves keep
    /// their two end points). Approximating: old points move; the limit is a quadratic B-spline.
    Chaikin,
}

impl SubdivisionScheme {
    /// Parses `linear`, `four-point` (also `fourpoint`, `4-point`) or `chaikin`, case-insensitively.
    pub fn parse(s: &str) -> Result<Self, GeometryError> {
        // A word with any other character (a control, format or combining one) is refused.
        let norm = super::choice_key(s).unwrap_or_else(|| "\u{0}".to_string());
        match norm.as_str() {
            "linear" | "" => Ok(Self::Linear),
            "fourpoint" | "4point" => Ok(Self::FourPoint),
            "chaikin" => Ok(Self::Chaikin),
            _ => Err(GeometryError::Degenerate(format!(
                "unknown subdivision scheme '{s}': expected 'linear', 'four-point' or 'chaikin'"
            ))),
        }
    }
}

/// Subdivides `curve` `levels` times with `scheme` (0 levels returns the curve unchanged). An open
/// curve of n points becomes one of 2n − 1 points per level (Chaikin: 2n − 2); a closed curve of n
/// points one of 2n points.
pub fn subdivide(
    curve: &Polyline,
    levels: usize,
    scheme: SubdivisionScheme,
) -> Result<Polyline, GeometryError> {
    let what = "curve";
    let min = if curve.closed { 3 } else { 2 };
    if curve.points.len() < min {
        return Err(GeometryError::TooFewPoints {
            what,
            needed: min,
            got: curve.points.len(),
        });
    }
    check_finite_points(what, &curve.points)?;
    let mut size = curve.points.len() as f64;
    for _ in 0..levels {
        size *= 2.0;
        if size > MAX_POINTS as f64 {
            return Err(GeometryError::Degenerate(format!(
                "{levels} subdivision levels of {} points exceed {MAX_POINTS} points",
                curve.points.len()
            )));
        }
    }
    let mut points = curve.points.clone();
    for _ in 0..levels {
        points = match scheme {
            SubdivisionScheme::Linear => linear(&points, curve.closed),
            SubdivisionScheme::FourPoint => four_point(&points, curve.closed),
            SubdivisionScheme::Chaikin => chaikin(&points, curve.closed),
        };
    }
    super::check_output(
        "subdivision",
        Polyline {
            points,
            closed: curve.closed,
        },
    )
}

fn edges(points: &[DVec3], closed: bool) -> usize {
    if closed {
        points.len()
    } else {
        points.len() - 1
    }
}

fn linear(p: &[DVec3], closed: bool) -> Vec<DVec3> {
    let n = p.len();
    let mut out = Vec::with_capacity(2 * n);
    for k in 0..edges(p, closed) {
        out.push(p[k]);
        out.push(p[k].midpoint(p[(k + 1) % n]));
    }
    if !closed {
        out.push(p[n - 1]);
    }
    out
}

fn four_point(p: &[DVec3], closed: bool) -> Vec<DVec3> {
    let n = p.len();
    let at = |i: isize| -> DVec3 {
        if closed {
            p[i.rem_euclid(n as isize) as usize]
        } else if i < 0 {
            2.0 * p[0] - p[1]
        } else if i as usize >= n {
            2.0 * p[n - 1] - p[n - 2]
        } else {
            p[i as usize]
        }
    };
    let mut out = Vec::with_capacity(2 * n);
    for (k, &pk) in p.iter().enumerate().take(edges(p, closed)) {
        let i = k as isize;
        out.push(pk);
        let new = (at(i) + at(i + 1)) * (9.0 / 16.0) - (at(i - 1) + at(i + 2)) * (1.0 / 16.0);
        out.push(new);
    }
    if !closed {
        out.push(p[n - 1]);
    }
    out
}

fn chaikin(p: &[DVec3], closed: bool) -> Vec<DVec3> {
    let n = p.len();
    let mut out = Vec::with_capacity(2 * n);
    if !closed {
        out.push(p[0]);
    }
    for k in 0..edges(p, closed) {
        let (a, b) = (p[k], p[(k + 1) % n]);
        if closed || k > 0 {
            out.push(a.lerp(b, 0.25));
        }
        if closed || k + 2 < n {
            out.push(a.lerp(b, 0.75));
        }
    }
    if !closed {
        out.push(p[n - 1]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(closed: bool) -> Polyline {
        Polyline {
            points: vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
            closed,
        }
    }

    #[test]
    fn point_counts_per_level() {
        for (scheme, open_count) in [
            (SubdivisionScheme::Linear, 7),
            (SubdivisionScheme::FourPoint, 7),
            (SubdivisionScheme::Chaikin, 6),
        ] {
            assert_eq!(
                subdivide(&square(false), 1, scheme).unwrap().len(),
                open_count
            );
            assert_eq!(subdivide(&square(true), 2, scheme).unwrap().len(), 16);
            assert_eq!(subdivide(&square(true), 0, scheme).unwrap(), square(true));
        }
    }

    #[test]
    fn linear_keeps_the_shape_and_four_point_interpolates() {
        let sq = square(true);
        let lin = subdivide(&sq, 3, SubdivisionScheme::Linear).unwrap();
        assert!((lin.length() - sq.length()).abs() < 1e-12);
        let fp = subdivide(&sq, 2, SubdivisionScheme::FourPoint).unwrap();
        for (k, p) in sq.points.iter().enumerate() {
            assert_eq!(fp.points[4 * k], *p);
        }
        // The closed four-point curve of a square bulges outwards at edge midpoints.
        assert!(fp.points[2].y < 0.0);
        let open = subdivide(&square(false), 2, SubdivisionScheme::Chaikin).unwrap();
        assert_eq!(open.points[0], DVec3::ZERO);
        assert_eq!(*open.points.last().unwrap(), DVec3::Y);
    }

    #[test]
    fn straight_lines_stay_straight_under_every_scheme() {
        let line = Polyline::open(vec![DVec3::ZERO, DVec3::X, DVec3::new(2.0, 0.0, 0.0)]);
        for scheme in [
            SubdivisionScheme::Linear,
            SubdivisionScheme::FourPoint,
            SubdivisionScheme::Chaikin,
        ] {
            let s = subdivide(&line, 3, scheme).unwrap();
            assert!(s.points.iter().all(|p| p.y == 0.0 && p.z == 0.0));
            assert!(s.points.windows(2).all(|w| w[1].x > w[0].x));
        }
    }

    #[test]
    fn bad_inputs() {
        let s = SubdivisionScheme::Linear;
        assert!(subdivide(&Polyline::open(vec![DVec3::ZERO]), 1, s).is_err());
        assert!(subdivide(&square(true), 40, s).is_err());
        let nan = Polyline::open(vec![DVec3::ZERO, DVec3::NAN]);
        assert!(subdivide(&nan, 1, s).is_err());
        assert_eq!(
            SubdivisionScheme::parse("Four-Point").unwrap(),
            SubdivisionScheme::FourPoint
        );
        assert!(SubdivisionScheme::parse("loop").is_err());
    }
}
