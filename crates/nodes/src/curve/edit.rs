//! Editing curves: transform, reverse, join, offset.

use cnets_engine::prelude::*;
use cnets_geometry::curves::{self, Transform};

node! {
    /// Moves, rotates, scales and mirrors a curve, in this order: **scale** by `scale` about
    /// `centre`, **rotate** by `angle` degrees about the axis through `centre` along `axis`
    /// (right-hand rule), **mirror** in the plane `mirror` (when given), then **move** by
    /// `translation`. The defaults do nothing, so set only what you need. Point order and the
    /// closed flag are kept.
    #[node(id = "curve.transform", category = "Curves")]
    pub fn transform(
        /// The curve.
        curve: k::Polyline,
        /// Vector to move by (applied last).
        translation: k::Vector = DVec3::ZERO,
        /// Rotation angle in degrees about `axis` through `centre`.
        angle: k::Number = 0.0,
        /// Direction of the rotation axis (non-zero when `angle` ≠ 0).
        axis: k::Vector = DVec3::Z,
        /// Centre of scaling and a point on the rotation axis.
        centre: k::Point = DVec3::ZERO,
        /// Uniform scale factor (≠ 0; negative also reflects through `centre`).
        scale: k::Number = 1.0,
        /// Plane to mirror in (none: no mirroring).
        mirror: Option<k::Plane>,
    ) -> (
        /// The transformed curve.
        curve: k::Polyline,
    ) {
        let t = Transform {
            translation,
            angle,
            axis,
            centre,
            scale,
            mirror,
        };
        Ok((t.apply_polyline(&curve)?,))
    }
}

node! {
    /// The curve run backwards. A closed curve keeps its first point (p₀, p_{n−1}, …, p₁), so its
    /// seam stays where it was.
    #[node(id = "curve.reverse", category = "Curves")]
    pub fn reverse(
        /// The curve.
        curve: k::Polyline,
    ) -> (
        /// The reversed curve.
        curve: k::Polyline,
    ) {
        Ok((curves::reverse(&curve),))
    }
}

node! {
    /// Joins open curves that meet end to end (ends closer than `tolerance`) into longer ones,
    /// flipping pieces as needed; a chain whose ends meet becomes closed. Chains grow from the first
    /// unused curve in input order, at its end first, then at its start. Closed curves pass through
    /// unchanged.
    #[node(id = "curve.join", category = "Curves")]
    pub fn join(
        /// The curves to join.
        curves: k::List<k::Polyline>,
        /// Largest gap between two ends that still join (≥ 0).
        tolerance: k::Number = 1e-6,
    ) -> (
        /// The joined curves.
        curves: k::List<k::Polyline>,
    ) {
        let input: Vec<Polyline> = curves.iter().map(|c| (**c).clone()).collect();
        Ok((curves::join(&input, tolerance)?,))
    }
}

node! {
    /// The curve offset in a plane by `distance`: positive to the left of the direction of travel
    /// as seen from the plane's normal (a counter-clockwise closed curve in world XY shrinks),
    /// corners mitred (consecutive offset edges meet at their intersection). The offset is taken
    /// in the curve's projection onto the plane; points keep their height above it. A curve that
    /// turns back on itself has no mitre there and is an error.
    #[node(id = "curve.offset", category = "Curves")]
    pub fn offset(
        /// The curve.
        curve: k::Polyline,
        /// Offset distance (negative: to the right).
        distance: k::Number = 1.0,
        /// The plane to offset in (world XY by default).
        plane: k::Plane = Plane::XY,
    ) -> (
        /// The offset curve.
        curve: k::Polyline,
    ) {
        Ok((curves::offset(&curve, distance, &plane)?,))
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_util::{pl, poly, run};
    use super::*;

    #[test]
    fn offset_moves_left_with_mitres() {
        let l = [
            DVec3::ZERO,
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(2.0, 2.0, 0.0),
        ];
        let out = run(
            &offset(),
            &[("curve", pl(&l, false)), ("distance", Value::Number(0.5))],
        );
        let c = poly(&out.unwrap()[0]);
        assert_eq!(
            c.points,
            vec![
                DVec3::new(0.0, 0.5, 0.0),
                DVec3::new(1.5, 0.5, 0.0),
                DVec3::new(1.5, 2.0, 0.0)
            ]
        );
        // Seen from below (plane normal −z) left and right swap.
        let below = Value::from(Plane::from_normal(DVec3::ZERO, -DVec3::Z).unwrap());
        let out = run(
            &offset(),
            &[
                ("curve", pl(&l, false)),
                ("distance", Value::Number(0.5)),
                ("plane", below),
            ],
        );
        assert!((poly(&out.unwrap()[0]).points[0] - DVec3::new(0.0, -0.5, 0.0)).length() < 1e-15);
    }

    #[test]
    fn transform_applies_scale_rotate_mirror_move_in_order() {
        let c = pl(&[DVec3::X, DVec3::new(2.0, 0.0, 0.0)], false);
        let out = run(
            &transform(),
            &[
                ("curve", c.clone()),
                ("scale", Value::Number(2.0)),
                ("angle", Value::Number(90.0)),
                ("translation", Value::Vector(DVec3::Z)),
            ],
        )
        .unwrap();
        let p = poly(&out[0]);
        assert!((p.points[0] - DVec3::new(0.0, 2.0, 1.0)).length() < 1e-15);
        assert!((p.points[1] - DVec3::new(0.0, 4.0, 1.0)).length() < 1e-15);
        let m = run(
            &transform(),
            &[("curve", c.clone()), ("mirror", Value::from(Plane::YZ))],
        )
        .unwrap();
        assert_eq!(poly(&m[0]).points[1], DVec3::new(-2.0, 0.0, 0.0));
        let identity = run(&transform(), &[("curve", c.clone())]).unwrap();
        assert_eq!(identity[0], c);
        assert!(
            run(
                &transform(),
                &[("curve", c.clone()), ("scale", Value::Number(0.0))]
            )
            .is_err()
        );
        let e = run(
            &transform(),
            &[
                ("curve", c),
                ("angle", Value::Number(10.0)),
                ("axis", Value::Vector(DVec3::ZERO)),
            ],
        )
        .unwrap_err();
        assert!(e.contains("rotation axis"), "{e}");
    }

    #[test]
    fn reverse_and_join() {
        let c = pl(&[DVec3::ZERO, DVec3::X, DVec3::Y], true);
        let out = run(&reverse(), &[("curve", c)]).unwrap();
        assert_eq!(poly(&out[0]).points, vec![DVec3::ZERO, DVec3::Y, DVec3::X]);

        let a = pl(&[DVec3::ZERO, DVec3::X], false);
        let b = pl(&[DVec3::new(2.0, 0.0, 0.0), DVec3::X], false);
        let far = pl(
            &[DVec3::new(5.0, 0.0, 0.0), DVec3::new(6.0, 0.0, 0.0)],
            false,
        );
        let out = run(&join(), &[("curves", Value::list(vec![a, b, far]))]).unwrap();
        let joined = out[0].as_list().unwrap();
        assert_eq!(joined.len(), 2);
        assert_eq!(poly(&joined[0]).points.len(), 3);
        assert!(
            run(
                &join(),
                &[
                    ("curves", Value::list(vec![])),
                    ("tolerance", Value::Number(-1.0))
                ]
            )
            .is_err()
        );
    }
}
