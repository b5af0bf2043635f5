//! Reading curves: length, points, the point at a parameter and the closest point.

use cnets_engine::prelude::*;
use cnets_geometry::curves;

node! {
    /// The total length of a polyline (including the closing edge of a closed one).
    #[node(id = "curve.length", category = "Curves")]
    pub fn length(
        /// The curve.
        curve: k::Polyline,
    ) -> (
        /// Its length.
        length: k::Number,
    ) {
        Ok((curve.length(),))
    }
}

node! {
    /// The points of a polyline (each point once: a closed polyline does not repeat its first
    /// point), whether it is closed, and how many points it has.
    #[node(id = "curve.points", category = "Curves", name = "Curve points")]
    pub fn points(
        /// The curve.
        curve: k::Polyline,
    ) -> (
        /// Its points, in order.
        points: k::List<k::Point>,
        /// Whether it is closed.
        closed: k::Boolean,
        /// Number of points.
        count: k::Integer,
    ) {
        Ok((curve.points.clone(), curve.closed, curve.points.len()))
    }
}

node! {
    /// The point and unit tangent at parameter `t` of a curve, by arc length: 0 is the first point,
    /// 1 the end (a closed curve's end is its start again, after the closing edge). An open curve
    /// clamps t to 0 … 1, a closed one wraps it. At a vertex the tangent is the next edge's.
    #[node(id = "curve.evaluate", category = "Curves")]
    pub fn evaluate(
        /// The curve.
        curve: k::Polyline,
        /// Where, 0 … 1 by arc length.
        t: k::Number = 0.5,
    ) -> (
        /// The point at t.
        point: k::Point,
        /// The unit tangent at t.
        tangent: k::Vector,
    ) {
        Ok(curves::evaluate(&curve, t)?)
    }
}

node! {
    /// The point of a curve closest to a given point, its parameter t (0 … 1 by arc length, as in
    /// `curve.evaluate`) and the distance.
    #[node(id = "curve.closest_point", category = "Curves")]
    pub fn closest_point(
        /// The curve.
        curve: k::Polyline,
        /// The point to project.
        point: k::Point,
    ) -> (
        /// The closest point on the curve.
        point: k::Point,
        /// Its parameter, 0 … 1 by arc length.
        t: k::Number,
        /// The distance from the given point.
        distance: k::Number,
    ) {
        Ok(curves::closest_point(&curve, point)?)
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_util::{pl, run};
    use super::*;

    #[test]
    fn length_and_points() {
        let sq = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
        let out = run(&length(), &[("curve", pl(&sq, true))]).unwrap();
        assert_eq!(out[0], Value::Number(4.0));
        let out = run(&length(), &[("curve", pl(&sq, false))]).unwrap();
        assert_eq!(out[0], Value::Number(3.0));
        let out = run(&points(), &[("curve", pl(&sq, true))]).unwrap();
        assert_eq!(out[0].as_list().unwrap().len(), 4);
        assert_eq!(out[0].as_list().unwrap()[2], Value::Point(sq[2]));
        assert_eq!(out[1], Value::Boolean(true));
        assert_eq!(out[2], Value::Integer(4));
    }

    #[test]
    fn evaluate_and_closest_point_by_arc_length() {
        let sq = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
        let out = run(
            &evaluate(),
            &[("curve", pl(&sq, true)), ("t", Value::Number(0.625))],
        );
        let out = out.unwrap();
        assert_eq!(out[0].as_vec3(), Some(DVec3::new(0.5, 1.0, 0.0)));
        assert_eq!(out[1].as_vec3(), Some(-DVec3::X));
        let probe = Value::Point(DVec3::new(0.25, -2.0, 0.0));
        let out = run(
            &closest_point(),
            &[("curve", pl(&sq, false)), ("point", probe)],
        )
        .unwrap();
        assert_eq!(
            out,
            vec![
                Value::Point(DVec3::new(0.25, 0.0, 0.0)),
                Value::Number(0.25 / 3.0),
                Value::Number(2.0)
            ]
        );
    }
}
