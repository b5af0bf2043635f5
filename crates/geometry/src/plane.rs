//! Oriented planes with an in-plane frame.

use glam::DVec3;

use crate::GeometryError;

/// A plane with an origin and a right-handed orthonormal frame (`x_axis`, `y_axis`, `normal`).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Plane {
    /// A point on the plane.
    pub origin: DVec3,
    /// First in-plane unit axis.
    pub x_axis: DVec3,
    /// Second in-plane unit axis (`normal × x_axis`).
    pub y_axis: DVec3,
    /// Unit normal.
    pub normal: DVec3,
}

impl Default for Plane {
    fn default() -> Self {
        Self::XY
    }
}

impl Plane {
    /// The world XY plane through the origin.
    pub const XY: Plane = Plane {
        origin: DVec3::ZERO,
        x_axis: DVec3::X,
        y_axis: DVec3::Y,
        normal: DVec3::Z,
    };
    /// The world YZ plane through the origin.
    pub const YZ: Plane = Plane {
        origin: DVec3::ZERO,
        x_axis: DVec3::Y,
        y_axis: DVec3::Z,
        normal: DVec3::X,
    };
    /// The world ZX plane through the origin (x axis along Z, normal along Y).
    pub const ZX: Plane = Plane {
        origin: DVec3::ZERO,
        x_axis: DVec3::Z,
        y_axis: DVec3::X,
        normal: DVec3::Y,
    };

    /// A plane through `origin` with the given normal; the x axis is chosen deterministically.
    pub fn from_normal(origin: DVec3, normal: DVec3) -> Result<Self, GeometryError> {
        let n = unit(normal, "plane normal")?;
        let helper = if n.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
        let x = (helper - n * helper.dot(n)).normalize();
        Ok(Self {
            origin,
            x_axis: x,
            y_axis: n.cross(x),
            normal: n,
        })
    }

    /// A plane through `origin` spanned by `x_dir` and (the part of) `y_hint` orthogonal to it.
    pub fn from_axes(origin: DVec3, x_dir: DVec3, y_hint: DVec3) -> Result<Self, GeometryError> {
        let x = unit(x_dir, "plane x axis")?;
        let y = unit(
            y_hint - x * y_hint.dot(x),
            "plane y axis (parallel to x axis)",
        )?;
        Ok(Self {
            origin,
            x_axis: x,
            y_axis: y,
            normal: x.cross(y),
        })
    }

    /// Signed distance of `p` from the plane (positive on the normal side).
    pub fn signed_distance(&self, p: DVec3) -> f64 {
        (p - self.origin).dot(self.normal)
    }

    /// Orthogonal projection of `p` onto the plane.
    pub fn project(&self, p: DVec3) -> DVec3 {
        p - self.normal * self.signed_distance(p)
    }

    /// Reflection of `p` in the plane.
    pub fn reflect(&self, p: DVec3) -> DVec3 {
        p - self.normal * (2.0 * self.signed_distance(p))
    }

    /// True when all fields are finite.
    pub fn is_finite(&self) -> bool {
        self.origin.is_finite()
            && self.x_axis.is_finite()
            && self.y_axis.is_finite()
            && self.normal.is_finite()
    }
}

/// Normalizes `v`, failing with a typed error when it is (almost) zero or not finite.
pub fn unit(v: DVec3, what: &'static str) -> Result<DVec3, GeometryError> {
    let len = v.length();
    if !len.is_finite() {
        return Err(GeometryError::NonFinite { what, index: 0 });
    }
    if len <= 1e-300 {
        return Err(GeometryError::ZeroVector { what });
    }
    Ok(v / len)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn from_normal_builds_orthonormal_right_handed_frame() {
        for n in [DVec3::Z, DVec3::X, DVec3::new(1.0, 2.0, -3.0)] {
            let p = Plane::from_normal(DVec3::ONE, n).unwrap();
            assert!((p.x_axis.length() - 1.0).abs() < 1e-15);
            assert!(p.x_axis.dot(p.normal).abs() < 1e-15);
            assert!((p.x_axis.cross(p.y_axis) - p.normal).length() < 1e-15);
            assert!((p.normal - n.normalize()).length() < 1e-15);
        }
        assert_eq!(
            Plane::from_normal(DVec3::ZERO, DVec3::ZERO),
            Err(GeometryError::ZeroVector {
                what: "plane normal"
            })
        );
    }

    #[test]
    fn reflect_and_project() {
        let p = Plane::XY;
        assert_eq!(
            p.reflect(DVec3::new(1.0, 2.0, 3.0)),
            DVec3::new(1.0, 2.0, -3.0)
        );
        assert_eq!(
            p.project(DVec3::new(1.0, 2.0, 3.0)),
            DVec3::new(1.0, 2.0, 0.0)
        );
        assert!(Plane::from_axes(DVec3::ZERO, DVec3::X, DVec3::X).is_err());
    }
}
