//! Sampling curves: interpolating splines, resampling, subdivision.

use cnets_engine::prelude::*;
use cnets_geometry::curves::{self, Spline};

use super::count_input;

/// Bytes a spline holds per control point: the point (24), its knot (8), its second derivative (24)
/// and the working copies of the natural spline's solve (3 × 8).
const SPLINE_BYTES_PER_POINT: usize = 80;

node! {
    /// A smooth curve through the control points (it passes exactly through each of them), open or
    /// closed, sampled at `count` points evenly spaced by arc length along the smooth curve (an open
    /// curve starts and ends at its first and last control points; a closed one starts at its first
    /// control point). `method` is `catmull-rom` (centripetal Catmull–Rom: C¹, local, never loops
    /// within a span) or `natural` (cubic spline: C², global; natural ends when open, periodic when
    /// closed). Needs at least 2 control points (3 when closed), no two consecutive ones equal.
    #[node(id = "curve.spline", category = "Curves")]
    pub fn spline[ctx](
        /// The control points, in order.
        points: k::List<k::Point>,
        /// Whether the curve closes back to its first point.
        closed: k::Boolean = false,
        /// Number of sampled points (≥ 2; ≥ 3 when closed).
        count: k::Integer = 32,
        /// `catmull-rom` or `natural`.
        method: k::Choice<crate::choices::SplineMethod> = "catmull-rom",
    ) -> (
        /// The sampled curve.
        curve: k::Polyline,
    ) {
        let kind = method;
        let n = count_input("count", count)?;
        // What the spline holds (its points, knots and second derivatives) and the samples, before
        // anything is built; the arc-length table is walked, not stored.
        ctx.reserve(
            cnets_engine::budget::bytes_of(points.len() as u128, SPLINE_BYTES_PER_POINT)
                .saturating_add(cnets_engine::budget::bytes_of(n as u128, 24)),
            &format!("a spline through {} points sampled at {n}", points.len()),
        )?;
        let spline = Spline::new(kind, &points, closed)?;
        Ok((spline.sample_even(n)?,))
    }
}

node! {
    /// Resamples a curve at points evenly spaced by arc length: `count` points (an open curve keeps
    /// both ends; a closed one keeps its first point and stays closed), or, when `length` is given,
    /// the whole number of edges closest to curve length / `length`. With `chords` on, the edges are
    /// instead exactly equal straight chords (points on the input curve, as walked with dividers);
    /// this fails when no such division exists.
    #[node(id = "curve.resample", category = "Curves")]
    pub fn resample(
        /// The curve.
        curve: k::Polyline,
        /// Number of points (≥ 2; ≥ 3 when closed); ignored when `length` is given.
        count: k::Integer = 16,
        /// Target edge length (> 0); overrides `count`.
        length: Option<k::Number>,
        /// Make all edges exactly equal chords instead of equal arcs.
        chords: k::Boolean = false,
    ) -> (
        /// The resampled curve.
        curve: k::Polyline,
    ) {
        let n = match length {
            Some(target) => {
                let edges = curves::resample::edge_count_for_length(curve.length(), target, curve.closed)?;
                if curve.closed { edges } else { edges + 1 }
            }
            None => count_input("count", count)?,
        };
        let out = if chords {
            curves::divide_equal_chords(&curve, n)?
        } else {
            curves::resample_by_count(&curve, n)?
        };
        Ok((out,))
    }
}

node! {
    /// Subdivides a curve `levels` times; each level doubles its edges. `scheme`: `linear` (edge
    /// midpoints, the shape is unchanged), `four-point` (interpolating: old points stay, the curve
    /// is smoothed through them) or `chaikin` (corner cutting: a smooth curve inside the polygon;
    /// open curves keep their end points).
    #[node(id = "curve.subdivide", category = "Curves")]
    pub fn subdivide(
        /// The curve.
        curve: k::Polyline,
        /// Number of subdivision levels (≥ 0).
        levels: k::Integer = 1,
        /// `linear`, `four-point` or `chaikin`.
        scheme: k::Choice<crate::choices::Subdivision> = "linear",
    ) -> (
        /// The subdivided curve.
        curve: k::Polyline,
    ) {
        let levels = count_input("levels", levels)?;
        Ok((curves::subdivide(&curve, levels, scheme)?,))
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_util::{pl, poly, pts, run};
    use super::*;

    fn wave() -> Vec<DVec3> {
        (0..5)
            .map(|k| DVec3::new(k as f64, (k % 2) as f64, 0.0))
            .collect()
    }

    #[test]
    fn spline_passes_through_the_ends_and_samples_evenly() {
        for method in ["catmull-rom", "natural"] {
            let out = run(
                &spline(),
                &[
                    ("points", pts(&wave())),
                    ("count", Value::Integer(50)),
                    ("method", Value::text(method)),
                ],
            )
            .unwrap();
            let p = poly(&out[0]);
            assert_eq!(p.points.len(), 50);
            assert_eq!(p.points[0], DVec3::ZERO);
            assert_eq!(p.points[49], DVec3::new(4.0, 0.0, 0.0));
            let l: Vec<f64> = p.edges().map(|(a, b)| a.distance(b)).collect();
            let mean = l.iter().sum::<f64>() / l.len() as f64;
            assert!(
                l.iter().all(|x| (x / mean - 1.0).abs() < 0.05),
                "{method}: {l:?}"
            );
        }
        let closed = run(
            &spline(),
            &[("points", pts(&wave())), ("closed", Value::Boolean(true))],
        )
        .unwrap();
        assert!(poly(&closed[0]).closed);
        let e = run(
            &spline(),
            &[("points", pts(&wave())), ("method", Value::text("bspline"))],
        )
        .unwrap_err();
        assert!(e.contains("catmull-rom"), "{e}");
        assert!(run(&spline(), &[("points", pts(&wave()[..1]))]).is_err());
    }

    #[test]
    fn resample_by_count_length_and_chords() {
        let l = pl(
            &[
                DVec3::ZERO,
                DVec3::new(4.0, 0.0, 0.0),
                DVec3::new(4.0, 2.0, 0.0),
            ],
            false,
        );
        let out = run(
            &resample(),
            &[("curve", l.clone()), ("count", Value::Integer(4))],
        )
        .unwrap();
        assert_eq!(poly(&out[0]).points[1], DVec3::new(2.0, 0.0, 0.0));
        let out = run(
            &resample(),
            &[("curve", l.clone()), ("length", Value::Number(0.5))],
        )
        .unwrap();
        assert_eq!(poly(&out[0]).points.len(), 13);
        let out = run(
            &resample(),
            &[
                ("curve", l.clone()),
                ("count", Value::Integer(3)),
                ("chords", Value::Boolean(true)),
            ],
        )
        .unwrap();
        let p = poly(&out[0]);
        let (a, b) = (
            p.points[0].distance(p.points[1]),
            p.points[1].distance(p.points[2]),
        );
        assert!((a - b).abs() < 1e-9);
        assert!(
            run(
                &resample(),
                &[("curve", l.clone()), ("count", Value::Integer(1))]
            )
            .is_err()
        );
        assert!(
            run(
                &resample(),
                &[("curve", l), ("length", Value::Number(-1.0))]
            )
            .is_err()
        );
    }

    #[test]
    fn subdivide_levels_and_schemes() {
        let sq = pl(
            &[DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
            true,
        );
        for scheme in ["linear", "four-point", "chaikin"] {
            let out = run(
                &subdivide(),
                &[
                    ("curve", sq.clone()),
                    ("levels", Value::Integer(2)),
                    ("scheme", Value::text(scheme)),
                ],
            )
            .unwrap();
            assert_eq!(poly(&out[0]).points.len(), 16, "{scheme}");
        }
        assert!(
            run(
                &subdivide(),
                &[("curve", sq.clone()), ("levels", Value::Integer(-1))]
            )
            .is_err()
        );
        assert!(
            run(
                &subdivide(),
                &[("curve", sq), ("scheme", Value::text("loop"))]
            )
            .is_err()
        );
    }
}
