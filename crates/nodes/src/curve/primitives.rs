//! Curves made from numbers and points: polyline, line, arc, circle, polygon, helix.

use cnets_engine::prelude::*;
use cnets_geometry::curves;

use super::count_input;

node! {
    /// A polyline through the given points, open or closed. A closed polyline stores each point
    /// once (its closing edge is implicit); when the last point repeats the first, the repeat is
    /// dropped. Needs at least 2 points (3 when closed), all finite, with no two consecutive points
    /// equal. A list of point lists gives one polyline per list.
    #[node(id = "curve.polyline", category = "Curves")]
    pub fn polyline(
        /// The points, in order.
        points: k::List<k::Point>,
        /// Whether the last point connects back to the first.
        closed: k::Boolean = false,
    ) -> (
        /// The polyline.
        curve: k::Polyline,
    ) {
        let mut points = points;
        if closed && points.len() > 3 && points.first() == points.last() {
            points.pop();
        }
        let curve = Polyline { points, closed };
        curve.validate("polyline", if closed { 3 } else { 2 })?;
        Ok((curve,))
    }
}

node! {
    /// The straight segment from `start` to `end`, sampled at `count` evenly spaced points (≥ 2).
    #[node(id = "curve.line", category = "Curves")]
    pub fn line(
        /// First point.
        start: k::Point = DVec3::ZERO,
        /// Last point (≠ start).
        end: k::Point = DVec3::X,
        /// Number of points (≥ 2).
        count: k::Integer = 2,
    ) -> (
        /// The sampled segment.
        curve: k::Polyline,
    ) {
        Ok((curves::line(start, end, count_input("count", count)?)?,))
    }
}

node! {
    /// A circular arc in a plane, from `start` to `end` (degrees, measured from the plane's x axis
    /// towards its y axis; `end` < `start` runs the other way), sampled at `count` evenly spaced
    /// points. Through three points: `curve.arc_three_points`; by span and rise:
    /// `curve.arc_span_rise`.
    #[node(id = "curve.arc", category = "Curves")]
    pub fn arc(
        /// Centre of the arc (in world coordinates).
        centre: k::Point = DVec3::ZERO,
        /// Radius (> 0).
        radius: k::Number = 1.0,
        /// Start angle in degrees.
        start: k::Number = 0.0,
        /// End angle in degrees (≠ start).
        end: k::Number = 90.0,
        /// Plane of the arc (its origin is ignored: the arc is centred at `centre`).
        plane: k::Plane = Plane::XY,
        /// Number of points (≥ 2).
        count: k::Integer = 16,
    ) -> (
        /// The sampled arc.
        curve: k::Polyline,
    ) {
        let n = count_input("count", count)?;
        Ok((curves::arc(centre, radius, start, end, &plane, n)?,))
    }
}

node! {
    /// The circular arc from `first` through `through` to `last`, sampled at `count` points with
    /// the three points among them, exactly.
    #[node(id = "curve.arc_three_points", category = "Curves", name = "Arc through three points")]
    pub fn arc_three_points(
        /// Where the arc starts.
        first: k::Point = DVec3::new(-1.0, 0.0, 0.0),
        /// A point the arc passes through.
        through: k::Point = DVec3::new(0.0, 1.0, 0.0),
        /// Where the arc ends.
        last: k::Point = DVec3::new(1.0, 0.0, 0.0),
        /// Number of points (≥ 3).
        count: k::Integer = 16,
    ) -> (
        /// The sampled arc.
        curve: k::Polyline,
    ) {
        let n = count_input("count", count)?;
        Ok((curves::arc_through(first, through, last, n)?,))
    }
}

node! {
    /// An arc over a chord of length `span` centred at `centre` along the plane's x axis, rising
    /// `rise` at its middle along the plane's y axis (a vault's profile: one `rise` slider drives
    /// it), sampled at `count` points with its ends and its top among them, exactly.
    #[node(id = "curve.arc_span_rise", category = "Curves", name = "Arc by span and rise")]
    pub fn arc_span_rise(
        /// The chord's middle.
        centre: k::Point = DVec3::ZERO,
        /// The chord's length (> 0).
        span: k::Number = 6.0,
        /// The height of the arc's middle above the chord (≠ 0; negative: below).
        rise: k::Number = 1.0,
        /// Plane of the arc: the chord along its x axis, the rise along its y axis.
        plane: k::Plane = Plane::XY,
        /// Number of points (≥ 3).
        count: k::Integer = 17,
    ) -> (
        /// The sampled arc.
        curve: k::Polyline,
    ) {
        let n = count_input("count", count)?;
        Ok((curves::arc_span_rise(centre, span, rise, &plane, n)?,))
    }
}

node! {
    /// A closed circle in a plane, sampled at `count` points (≥ 3); the first point lies in the
    /// direction of the plane's x axis, the points run towards its y axis.
    #[node(id = "curve.circle", category = "Curves")]
    pub fn circle(
        /// Centre (in world coordinates).
        centre: k::Point = DVec3::ZERO,
        /// Radius (> 0).
        radius: k::Number = 1.0,
        /// Plane of the circle (its origin is ignored: the circle is centred at `centre`).
        plane: k::Plane = Plane::XY,
        /// Number of points (≥ 3).
        count: k::Integer = 32,
    ) -> (
        /// The sampled circle (closed).
        curve: k::Polyline,
    ) {
        let n = count_input("count", count)?;
        Ok((curves::circle(centre, radius, &plane, n)?,))
    }
}

node! {
    /// A closed regular polygon with `sides` corners on a circle of `radius` (the circumradius);
    /// the first corner is at `rotation` degrees from the plane's x axis.
    #[node(id = "curve.polygon", category = "Curves")]
    pub fn polygon(
        /// Centre (in world coordinates).
        centre: k::Point = DVec3::ZERO,
        /// Distance from the centre to each corner (> 0).
        radius: k::Number = 1.0,
        /// Number of corners (≥ 3).
        sides: k::Integer = 6,
        /// Plane of the polygon (its origin is ignored).
        plane: k::Plane = Plane::XY,
        /// Angle of the first corner in degrees.
        rotation: k::Number = 0.0,
    ) -> (
        /// The polygon (closed).
        curve: k::Polyline,
    ) {
        let n = count_input("sides", sides)?;
        Ok((curves::polygon(centre, radius, n, &plane, rotation)?,))
    }
}

node! {
    /// A helix about the axis through `centre` along the plane's normal, starting in the direction
    /// of the plane's x axis: `turns` turns (negative: clockwise about the normal), rising `pitch`
    /// per turn, with the radius going linearly from `radius` to `end_radius` (a conical helix when
    /// they differ; equal when `end_radius` is not given), sampled at `count` points evenly spaced
    /// in angle.
    #[node(id = "curve.helix", category = "Curves")]
    pub fn helix(
        /// Centre of the base circle (in world coordinates).
        centre: k::Point = DVec3::ZERO,
        /// Orientation: the axis is the plane's normal (its origin is ignored).
        plane: k::Plane = Plane::XY,
        /// Radius at the start (≥ 0).
        radius: k::Number = 1.0,
        /// Radius at the end (≥ 0; default: `radius`).
        end_radius: Option<k::Number>,
        /// Rise along the axis per turn.
        pitch: k::Number = 1.0,
        /// Number of turns (≠ 0, may be fractional).
        turns: k::Number = 2.0,
        /// Number of points (≥ 2).
        count: k::Integer = 64,
    ) -> (
        /// The sampled helix.
        curve: k::Polyline,
    ) {
        let n = count_input("count", count)?;
        let end = end_radius.unwrap_or(radius);
        Ok((curves::helix(centre, &plane, radius, end, pitch, turns, n)?,))
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_util::{poly, pts, run};
    use super::*;

    #[test]
    fn an_arc_by_span_and_rise_through_the_node_passes_through_its_three_points() {
        let def = arc_span_rise();
        let out = run(
            &def,
            &[
                ("centre", Value::Point(DVec3::new(0.0, 0.0, 2.0))),
                ("plane", Value::from(Plane::ZX)),
                ("span", Value::Number(6.0)),
                ("rise", Value::Number(3.0)),
                ("count", Value::Integer(9)),
            ],
        )
        .unwrap();
        let curve = poly(&out[0]);
        let xz = Plane::ZX;
        for p in [
            DVec3::new(0.0, 0.0, 2.0) - xz.x_axis * 3.0,
            DVec3::new(0.0, 0.0, 2.0) + xz.y_axis * 3.0,
            DVec3::new(0.0, 0.0, 2.0) + xz.x_axis * 3.0,
        ] {
            let d = curve
                .points
                .iter()
                .map(|q| q.distance(p))
                .fold(f64::INFINITY, f64::min);
            assert!(d <= 1e-12, "{p}: {d}");
        }
        // Through three points given directly: they are among the samples.
        let (a, b, c) = (
            DVec3::ZERO,
            DVec3::new(1.0, 2.0, 0.5),
            DVec3::new(3.0, 1.0, -1.0),
        );
        let out = run(
            &arc_three_points(),
            &[
                ("first", Value::Point(a)),
                ("through", Value::Point(b)),
                ("last", Value::Point(c)),
                ("count", Value::Integer(10)),
            ],
        )
        .unwrap();
        let points = poly(&out[0]).points;
        assert!(points.contains(&a) && points.contains(&b) && points.contains(&c));
        // The arc by centre, radius and angles is unchanged.
        let out = run(
            &arc(),
            &[("radius", Value::Number(2.0)), ("count", Value::Integer(3))],
        )
        .unwrap();
        assert!((poly(&out[0]).points[2] - DVec3::new(0.0, 2.0, 0.0)).length() < 1e-15);
    }

    #[test]
    fn polyline_validates_and_drops_a_repeated_closing_point() {
        let sq = [
            DVec3::ZERO,
            DVec3::X,
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::Y,
            DVec3::ZERO,
        ];
        let out = run(
            &polyline(),
            &[("points", pts(&sq)), ("closed", Value::Boolean(true))],
        )
        .unwrap();
        let p = poly(&out[0]);
        assert!(p.closed);
        assert_eq!(p.points.len(), 4);
        let open = run(&polyline(), &[("points", pts(&sq))]).unwrap();
        assert_eq!(poly(&open[0]).points.len(), 5);
        let e = run(&polyline(), &[("points", pts(&[DVec3::ZERO, DVec3::ZERO]))]).unwrap_err();
        assert!(e.contains("zero-length edge"), "{e}");
        assert!(run(&polyline(), &[("points", pts(&[DVec3::ZERO]))]).is_err());
        // A list of point lists gives one polyline per list.
        let two = Value::list(vec![pts(&sq[..2]), pts(&sq[1..3])]);
        let out = run(&polyline(), &[("points", two)]).unwrap();
        assert_eq!(out[0].as_list().unwrap().len(), 2);
    }

    #[test]
    fn line_and_arc() {
        let out = run(&line(), &[("count", Value::Integer(5))]).unwrap();
        let p = poly(&out[0]);
        assert_eq!(p.points[2], DVec3::new(0.5, 0.0, 0.0));
        assert!(run(&line(), &[("count", Value::Integer(1))]).is_err());
        assert!(
            run(&line(), &[("count", Value::Integer(-3))])
                .unwrap_err()
                .contains("count")
        );

        let out = run(&arc(), &[]).unwrap();
        let p = poly(&out[0]);
        assert_eq!(p.points.len(), 16);
        assert!((p.points[15] - DVec3::Y).length() < 1e-15);
        assert!((p.length() - std::f64::consts::FRAC_PI_2).abs() < 0.01);
        let e = run(&arc(), &[("radius", Value::Number(-1.0))]).unwrap_err();
        assert!(e.contains("radius"), "{e}");
    }

    #[test]
    fn circle_polygon_helix() {
        let out = run(
            &circle(),
            &[("radius", Value::Number(2.0)), ("count", Value::Integer(8))],
        )
        .unwrap();
        let c = poly(&out[0]);
        assert!(c.closed);
        assert_eq!(c.points.len(), 8);
        assert!(c.points.iter().all(|p| (p.length() - 2.0).abs() < 1e-12));
        assert!(run(&circle(), &[("count", Value::Integer(2))]).is_err());

        let out = run(
            &polygon(),
            &[
                ("sides", Value::Integer(4)),
                ("rotation", Value::Number(90.0)),
            ],
        )
        .unwrap();
        let sq = poly(&out[0]);
        assert!((sq.points[0] - DVec3::Y).length() < 1e-15);
        assert!((sq.length() - 4.0 * 2f64.sqrt()).abs() < 1e-12);

        let out = run(
            &helix(),
            &[
                ("end_radius", Value::Number(0.0)),
                ("turns", Value::Number(1.0)),
                ("count", Value::Integer(9)),
            ],
        )
        .unwrap();
        let h = poly(&out[0]);
        assert_eq!(h.points[0], DVec3::X);
        assert!((h.points[8] - DVec3::Z).length() < 1e-12);
        assert!(run(&helix(), &[("turns", Value::Number(0.0))]).is_err());
    }
}
