//! Reading curves: length and points.

use cnets_engine::prelude::*;

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
    #[node(id = "curve.points", category = "Curves")]
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
}
