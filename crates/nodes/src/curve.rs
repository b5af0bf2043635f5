//! Curves: every curve is a polyline; every sampling count is an input.

use cnets_engine::prelude::*;

node! {
    /// A circular arc in a plane, from `start` to `end` (degrees, measured from the plane's x axis
    /// towards its y axis), sampled at `count` evenly spaced points.
    #[node(id = "curve.arc", category = "Curves")]
    pub fn arc(
        /// Centre of the arc (in world coordinates).
        centre: k::Point = DVec3::ZERO,
        /// Radius (> 0).
        radius: k::Number = 1.0,
        /// Start angle in degrees.
        start: k::Number = 0.0,
        /// End angle in degrees.
        end: k::Number = 90.0,
        /// Plane of the arc (its origin is ignored: the arc is centred at `centre`).
        plane: k::Plane = Plane::XY,
        /// Number of points (≥ 2).
        count: k::Integer = 16,
    ) -> (
        /// The sampled arc.
        curve: k::Polyline,
    ) {
        if !(radius.is_finite() && radius > 0.0) {
            return Err(format!("radius must be a positive number, got {radius}").into());
        }
        if !(start.is_finite() && end.is_finite() && centre.is_finite() && plane.is_finite()) {
            return Err("centre, angles and plane must be finite".into());
        }
        if count < 2 {
            return Err(format!("count must be at least 2, got {count}").into());
        }
        let n = count as usize;
        let points = (0..n)
            .map(|k| {
                let t = (start + (end - start) * k as f64 / (n - 1) as f64).to_radians();
                centre + (plane.x_axis * t.cos() + plane.y_axis * t.sin()) * radius
            })
            .collect();
        Ok((Polyline::open(points),))
    }
}

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

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![arc(), length()]
}

#[cfg(test)]
mod tests {
    use super::*;
    use cnets_engine::eval::run_mapped;

    #[test]
    fn quarter_arc_has_the_right_points_and_length() {
        let def = arc();
        let inputs: Vec<Value> = def
            .inputs
            .iter()
            .map(|p| p.default.clone().unwrap())
            .collect();
        let out = run_mapped(&def, &NodeContext::default(), &inputs).unwrap();
        let Value::Polyline(p) = &out[0] else {
            panic!("polyline")
        };
        assert_eq!(p.points.len(), 16);
        assert!((p.points[15] - DVec3::Y).length() < 1e-15);
        let chord_sum = p.length();
        assert!((chord_sum - std::f64::consts::FRAC_PI_2).abs() < 0.01);
    }
}
