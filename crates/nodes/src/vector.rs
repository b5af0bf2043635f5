//! Points, vectors and planes: construct and deconstruct; vector arithmetic and measures (length,
//! unit, dot, cross, distance, add, scale, angle).
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
    #[node(id = "vector.deconstruct", category = "Vectors", name = "Deconstruct vector")]
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

/// The vector, checked finite and non-zero, and rescaled when its length would under- or
/// overflow in a dot product (only then: ordinary vectors keep their exact bits).
fn non_zero(what: &str, v: DVec3) -> Result<DVec3, NodeError> {
    let v = finite3(what, v)?;
    let largest = v.abs().max_element();
    if largest == 0.0 {
        return Err(format!("{what} is a zero-length vector: it has no direction").into());
    }
    Ok(if (1e-150..1e150).contains(&largest) {
        v
    } else {
        v / largest
    })
}

node! {
    /// The length of a vector.
    #[node(id = "vector.length", category = "Vectors")]
    pub fn length(
        /// The vector.
        vector: k::Vector,
    ) -> (
        /// Its length.
        length: k::Number,
    ) {
        Ok((finite3("vector", vector)?.length(),))
    }
}

node! {
    /// The vector scaled to length 1 (a zero vector is an error).
    #[node(id = "vector.unit", category = "Vectors")]
    pub fn unit(
        /// The vector.
        vector: k::Vector,
    ) -> (
        /// The unit vector of the same direction.
        vector: k::Vector,
    ) {
        // Divide by the length (glam's normalize multiplies by its reciprocal: one rounding more).
        let v = non_zero("vector", vector)?;
        Ok((v / v.length(),))
    }
}

node! {
    /// The dot product a · b.
    #[node(id = "vector.dot", category = "Vectors")]
    pub fn dot(
        /// First vector.
        a: k::Vector,
        /// Second vector.
        b: k::Vector,
    ) -> (
        /// a · b.
        value: k::Number,
    ) {
        Ok((finite3("a", a)?.dot(finite3("b", b)?),))
    }
}

node! {
    /// The cross product a × b (right-handed).
    #[node(id = "vector.cross", category = "Vectors")]
    pub fn cross(
        /// First vector.
        a: k::Vector,
        /// Second vector.
        b: k::Vector,
    ) -> (
        /// a × b.
        vector: k::Vector,
    ) {
        Ok((finite3("a", a)?.cross(finite3("b", b)?),))
    }
}

node! {
    /// The distance between two points.
    #[node(id = "vector.distance", category = "Vectors")]
    pub fn distance(
        /// First point.
        a: k::Point,
        /// Second point.
        b: k::Point,
    ) -> (
        /// |a − b|.
        distance: k::Number,
    ) {
        Ok((finite3("a", a)?.distance(finite3("b", b)?),))
    }
}

node! {
    /// The sum a + b of two vectors (a point plus a vector is the moved point's position).
    #[node(id = "vector.add", category = "Vectors")]
    pub fn add(
        /// First vector.
        a: k::Vector,
        /// Second vector.
        b: k::Vector,
    ) -> (
        /// a + b.
        vector: k::Vector,
    ) {
        Ok((finite3("a", a)? + finite3("b", b)?,))
    }
}

node! {
    /// The vector multiplied by a factor (negative factors reverse it).
    #[node(id = "vector.scale", category = "Vectors")]
    pub fn scale(
        /// The vector.
        vector: k::Vector,
        /// The factor.
        factor: k::Number = 1.0,
    ) -> (
        /// factor · vector.
        vector: k::Vector,
    ) {
        if !factor.is_finite() {
            return Err(format!("factor is {factor}, expected a finite number").into());
        }
        Ok((finite3("vector", vector)? * factor,))
    }
}

node! {
    /// The angle between two vectors in degrees, 0 to 180 (zero vectors are an error).
    #[node(id = "vector.angle", category = "Vectors")]
    pub fn angle(
        /// First vector.
        a: k::Vector,
        /// Second vector.
        b: k::Vector,
    ) -> (
        /// The angle in degrees.
        degrees: k::Number,
    ) {
        let (a, b) = (non_zero("a", a)?, non_zero("b", b)?);
        // atan2 of |a × b| and a · b is accurate for small and nearly straight angles alike.
        Ok((a.cross(b).length().atan2(a.dot(b)).to_degrees(),))
    }
}

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![
        point(),
        vector(),
        deconstruct(),
        plane(),
        length(),
        unit(),
        dot(),
        cross(),
        distance(),
        add(),
        scale(),
        angle(),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use cnets_engine::eval::evaluate_node;

    fn run(def: NodeDef, inputs: &[Value]) -> Result<Vec<Value>, String> {
        evaluate_node(&def, &NodeContext::default(), inputs)
            .map(|o| o.values)
            .map_err(|e| e.to_string())
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
    fn vector_arithmetic_matches_hand_values() {
        use crate::testing::run_named;
        let v = |x: f64, y: f64, z: f64| Value::Vector(DVec3::new(x, y, z));
        let one = |def: NodeDef, named: &[(&str, Value)]| run_named(&def, named).unwrap().remove(0);
        assert_eq!(
            one(length(), &[("vector", v(3.0, 4.0, 12.0))]),
            Value::Number(13.0)
        );
        assert_eq!(
            one(unit(), &[("vector", v(0.0, 0.0, -1e-300))]),
            v(0.0, 0.0, -1.0)
        );
        assert_eq!(
            one(unit(), &[("vector", v(3.0, 0.0, 4.0))]),
            v(0.6, 0.0, 0.8)
        );
        assert!(
            run_named(&unit(), &[("vector", v(0.0, 0.0, 0.0))])
                .unwrap_err()
                .contains("zero-length")
        );
        assert_eq!(
            one(dot(), &[("a", v(1.0, 2.0, 3.0)), ("b", v(4.0, -5.0, 6.0))]),
            Value::Number(12.0)
        );
        assert_eq!(
            one(cross(), &[("a", v(1.0, 0.0, 0.0)), ("b", v(0.0, 1.0, 0.0))]),
            v(0.0, 0.0, 1.0)
        );
        let p = |x: f64, y: f64, z: f64| Value::Point(DVec3::new(x, y, z));
        assert_eq!(
            one(
                distance(),
                &[("a", p(1.0, 1.0, 1.0)), ("b", p(4.0, 5.0, 1.0))]
            ),
            Value::Number(5.0)
        );
        assert_eq!(
            one(add(), &[("a", v(1.0, 2.0, 3.0)), ("b", v(1.0, 1.0, 1.0))]),
            v(2.0, 3.0, 4.0)
        );
        assert_eq!(
            one(
                scale(),
                &[
                    ("vector", v(1.0, -2.0, 0.5)),
                    ("factor", Value::Number(-2.0))
                ]
            ),
            v(-2.0, 4.0, -1.0)
        );
        let deg = |a: Value, b: Value| one(angle(), &[("a", a), ("b", b)]).as_f64().unwrap();
        assert_eq!(deg(v(1.0, 0.0, 0.0), v(0.0, 2.0, 0.0)), 90.0);
        assert_eq!(deg(v(1.0, 0.0, 0.0), v(-3.0, 0.0, 0.0)), 180.0);
        assert!((deg(v(1.0, 0.0, 0.0), v(1.0, 1.0, 0.0)) - 45.0).abs() < 1e-13);
        assert!(
            deg(v(1.0, 0.0, 0.0), v(1.0, 1e-12, 0.0)) > 0.0,
            "tiny angles are not rounded to 0"
        );
        assert!(
            run_named(
                &angle(),
                &[("a", v(0.0, 0.0, 0.0)), ("b", v(1.0, 0.0, 0.0))]
            )
            .is_err()
        );
        // Points convert to vectors and lists map item by item.
        let lens = one(
            length(),
            &[(
                "vector",
                Value::list(vec![p(0.0, 3.0, 4.0), v(1.0, 0.0, 0.0)]),
            )],
        );
        assert_eq!(
            lens,
            Value::list(vec![Value::Number(5.0), Value::Number(1.0)])
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
