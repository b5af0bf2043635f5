//! Points, vectors and planes: construct and deconstruct.
//!
//! All inputs have item access: lists of coordinates give lists of points.

use cnets_engine::prelude::*;

fn finite3(what: &str, v: DVec3) -> Result<DVec3, NodeError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(NodeError::new(format!("{what} {v} is not finite")))
    }
}

node! {
    /// A point from its x, y and z coordinates (lists of coordinates give lists of points).
    #[node(id = "vector.point", category = "Vectors")]
    pub fn point(
        /// x coordinate.
        x: k::Number = 0.0,
        /// y coordinate.
        y: k::Number = 0.0,
        /// z coordinate.
        z: k::Number = 0.0,
    ) -> (
        /// The point.
        point: k::Point,
    ) {
        Ok((finite3("point", DVec3::new(x, y, z))?,))
    }
}

node! {
    /// A vector from its x, y and z components.
    #[node(id = "vector.vector", category = "Vectors")]
    pub fn vector(
        /// x component.
        x: k::Number = 0.0,
        /// y component.
        y: k::Number = 0.0,
        /// z component.
        z: k::Number = 0.0,
    ) -> (
        /// The vector.
        vector: k::Vector,
    ) {
        Ok((finite3("vector", DVec3::new(x, y, z))?,))
    }
}

node! {
    /// The x, y and z coordinates of a point or vector.
    #[node(id = "vector.deconstruct", category = "Vectors")]
    pub fn deconstruct(
        /// A point or vector.
        point: k::Point,
    ) -> (
        /// x coordinate.
        x: k::Number,
        /// y coordinate.
        y: k::Number,
        /// z coordinate.
        z: k::Number,
    ) {
        Ok((point.x, point.y, point.z))
    }
}

node! {
    /// A plane through `origin` with the given `normal`. Its x axis is `x_axis` made perpendicular
    /// to the normal, or, when not given, a fixed choice (world x, or world y when the normal is
    /// close to x); its y axis completes a right-handed frame.
    #[node(id = "vector.plane", category = "Vectors")]
    pub fn plane(
        /// A point on the plane.
        origin: k::Point = DVec3::ZERO,
        /// The plane's normal (non-zero).
        normal: k::Vector = DVec3::Z,
        /// Direction of the plane's x axis (not parallel to the normal).
        x_axis: Option<k::Vector>,
    ) -> (
        /// The plane.
        plane: k::Plane,
    ) {
        let origin = finite3("origin", origin)?;
        let normal = finite3("normal", normal)?;
        let plane = match x_axis {
            None => Plane::from_normal(origin, normal)?,
            Some(x) => {
                let x = finite3("x_axis", x)?;
                if normal.length_squared() <= f64::MIN_POSITIVE {
                    return Err("the plane normal is a zero-length vector".into());
                }
                let n = normal.normalize();
                let along = x - n * x.dot(n);
                if along.length() <= 1e-12 * x.length().max(f64::MIN_POSITIVE) {
                    return Err("x_axis is parallel to the normal (or zero)".into());
                }
                Plane::from_axes(origin, along, n.cross(along))?
            }
        };
        Ok((plane,))
    }
}

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![point(), vector(), deconstruct(), plane()]
}

#[cfg(test)]
mod tests {
    use super::*;
    use cnets_engine::eval::evaluate_node;

    fn run(def: NodeDef, inputs: &[Value]) -> Result<Vec<Value>, String> {
        evaluate_node(&def, &NodeContext::default(), inputs).map(|o| o.values)
    }

    #[test]
    fn construct_and_deconstruct_round_trip() {
        let xs = Value::list(vec![Value::Number(1.0), Value::Number(2.0)]);
        let out = run(point(), &[xs, Value::Number(5.0), Value::Integer(-1)]).unwrap();
        let expected = Value::list(vec![
            Value::Point(DVec3::new(1.0, 5.0, -1.0)),
            Value::Point(DVec3::new(2.0, 5.0, -1.0)),
        ]);
        assert_eq!(out[0], expected);
        let parts = run(deconstruct(), &[expected]).unwrap();
        assert_eq!(
            parts[0],
            Value::list(vec![Value::Number(1.0), Value::Number(2.0)])
        );
        assert_eq!(
            parts[2],
            Value::list(vec![Value::Number(-1.0), Value::Number(-1.0)])
        );
        let v = run(
            vector(),
            &[Value::Number(0.0), Value::Number(0.0), Value::Number(2.0)],
        );
        assert_eq!(v.unwrap()[0], Value::Vector(DVec3::new(0.0, 0.0, 2.0)));
        // Vectors deconstruct too (they convert to points).
        let parts = run(deconstruct(), &[Value::Vector(DVec3::new(4.0, 5.0, 6.0))]).unwrap();
        assert_eq!(parts[1], Value::Number(5.0));
        assert!(
            run(
                point(),
                &[
                    Value::Number(f64::NAN),
                    Value::Number(0.0),
                    Value::Number(0.0)
                ]
            )
            .is_err()
        );
    }

    #[test]
    fn plane_frames_are_orthonormal_and_follow_the_inputs() {
        let o = DVec3::new(1.0, 2.0, 3.0);
        let n = DVec3::new(0.0, 0.0, 2.0);
        let out = run(
            plane(),
            &[
                Value::Point(o),
                Value::Vector(n),
                Value::Vector(DVec3::new(1.0, 1.0, 5.0)),
            ],
        )
        .unwrap();
        let Value::Plane(p) = &out[0] else {
            panic!("plane")
        };
        assert_eq!(p.origin, o);
        assert!((p.normal - DVec3::Z).length() < 1e-15);
        assert!((p.x_axis - DVec3::new(1.0, 1.0, 0.0).normalize()).length() < 1e-15);
        assert!((p.x_axis.cross(p.y_axis) - p.normal).length() < 1e-15);
        let out = run(
            plane(),
            &[Value::Point(o), Value::Vector(DVec3::X), Value::Null],
        )
        .unwrap();
        let Value::Plane(p) = &out[0] else {
            panic!("plane")
        };
        assert!((p.normal - DVec3::X).length() < 1e-15);
        assert!(
            run(
                plane(),
                &[Value::Point(o), Value::Vector(DVec3::ZERO), Value::Null]
            )
            .is_err()
        );
        let e = run(
            plane(),
            &[
                Value::Point(o),
                Value::Vector(DVec3::Z),
                Value::Vector(DVec3::Z),
            ],
        )
        .unwrap_err();
        assert!(e.contains("parallel"), "{e}");
    }
}
