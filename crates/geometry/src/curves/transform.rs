//! Rigid and similarity transforms of points and polylines: scale about a point, rotate about an
//! axis, mirror in a plane, move by a vector.

use glam::DVec3;

use super::{check_finite, check_finite_vec};
use crate::error::check_finite_points;
use crate::plane::unit;
use crate::{GeometryError, Plane, Polyline};

/// A transform applied in a fixed order: **scale** about `centre`, then **rotate** by `angle`
/// degrees about the axis through `centre` along `axis` (right-hand rule), then **mirror** in
/// `mirror` (when set), then **move** by `translation`. The default is the identity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Transform {
    /// Vector added last.
    pub translation: DVec3,
    /// Rotation angle in degrees (counter-clockwise looking against `axis`).
    pub angle: f64,
    /// Direction of the rotation axis (any length > 0).
    pub axis: DVec3,
    /// Centre of the scaling and a point on the rotation axis.
    pub centre: DVec3,
    /// Uniform scale factor (non-zero; negative values also reflect through `centre`).
    pub scale: f64,
    /// Plane to mirror in, if any.
    pub mirror: Option<Plane>,
}

impl Default for Transform {
    fn default() -> Self {
        Self {
            translation: DVec3::ZERO,
            angle: 0.0,
            axis: DVec3::Z,
            centre: DVec3::ZERO,
            scale: 1.0,
            mirror: None,
        }
    }
}

/// A validated transform: unit axis and the rotation's sine and cosine.
#[derive(Debug, Clone, Copy)]
struct Prepared {
    t: Transform,
    axis: DVec3,
    sin: f64,
    cos: f64,
}

impl Transform {
    /// A translation.
    pub fn translation(v: DVec3) -> Self {
        Self {
            translation: v,
            ..Self::default()
        }
    }

    /// A rotation by `angle` degrees about the axis through `origin` along `axis`.
    pub fn rotation(origin: DVec3, axis: DVec3, angle: f64) -> Self {
        Self {
            angle,
            axis,
            centre: origin,
            ..Self::default()
        }
    }

    /// A uniform scaling about `centre`.
    pub fn scaling(centre: DVec3, factor: f64) -> Self {
        Self {
            centre,
            scale: factor,
            ..Self::default()
        }
    }

    /// A reflection in `plane`.
    pub fn mirroring(plane: Plane) -> Self {
        Self {
            mirror: Some(plane),
            ..Self::default()
        }
    }

    fn prepare(&self) -> Result<Prepared, GeometryError> {
        check_finite_vec("move vector", self.translation)?;
        check_finite_vec("centre", self.centre)?;
        check_finite("rotation angle", self.angle)?;
        if !(self.scale.is_finite() && self.scale != 0.0) {
            return Err(GeometryError::InvalidParameter {
                what: "scale",
                value: self.scale,
                expected: "a finite non-zero number",
            });
        }
        let axis = if self.angle == 0.0 {
            DVec3::Z
        } else {
            unit(self.axis, "rotation axis")?
        };
        if let Some(m) = &self.mirror {
            if !m.is_finite() {
                return Err(GeometryError::NonFinite {
                    what: "mirror plane",
                    index: 0,
                });
            }
            unit(m.normal, "mirror plane normal")?;
        }
        let (sin, cos) = self.angle.to_radians().sin_cos();
        Ok(Prepared {
            t: *self,
            axis,
            sin,
            cos,
        })
    }

    /// Applies the transform to one point.
    pub fn apply(&self, p: DVec3) -> Result<DVec3, GeometryError> {
        check_finite_vec("point", p)?;
        Ok(self.prepare()?.apply(p))
    }

    /// Applies the transform to every point of `curve` (the closed flag and point order are kept;
    /// a mirror therefore reverses the curve's turning sense).
    pub fn apply_polyline(&self, curve: &Polyline) -> Result<Polyline, GeometryError> {
        check_finite_points("curve", &curve.points)?;
        let prepared = self.prepare()?;
        super::check_output(
            "transform",
            Polyline {
                points: curve.points.iter().map(|&p| prepared.apply(p)).collect(),
                closed: curve.closed,
            },
        )
    }
}

impl Prepared {
    fn apply(&self, p: DVec3) -> DVec3 {
        let c = self.t.centre;
        let mut v = (p - c) * self.t.scale;
        if self.t.angle != 0.0 {
            // Rodrigues' rotation formula.
            let k = self.axis;
            v = v * self.cos + k.cross(v) * self.sin + k * (k.dot(v) * (1.0 - self.cos));
        }
        let mut q = c + v;
        if let Some(m) = &self.t.mirror {
            let n = m.normal.normalize();
            q -= n * (2.0 * (q - m.origin).dot(n));
        }
        q + self.t.translation
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_part_does_what_it_says() {
        let p = DVec3::new(1.0, 0.0, 0.0);
        let r = Transform::rotation(DVec3::ZERO, DVec3::Z, 90.0)
            .apply(p)
            .unwrap();
        assert!((r - DVec3::Y).length() < 1e-15);
        let r = Transform::rotation(DVec3::new(1.0, 1.0, 0.0), DVec3::Z * 5.0, 180.0)
            .apply(p)
            .unwrap();
        assert!((r - DVec3::new(1.0, 2.0, 0.0)).length() < 1e-15);
        let s = Transform::scaling(DVec3::ONE, 2.0).apply(p).unwrap();
        assert_eq!(s, DVec3::new(1.0, -1.0, -1.0));
        let m = Transform::mirroring(Plane::YZ).apply(p).unwrap();
        assert_eq!(m, DVec3::new(-1.0, 0.0, 0.0));
        let t = Transform::translation(DVec3::Z).apply(p).unwrap();
        assert_eq!(t, DVec3::new(1.0, 0.0, 1.0));
    }

    #[test]
    fn parts_apply_in_the_documented_order() {
        // Scale 2 about the origin, rotate 90° about z, mirror in YZ, then move by +z.
        let t = Transform {
            translation: DVec3::Z,
            angle: 90.0,
            axis: DVec3::Z,
            centre: DVec3::ZERO,
            scale: 2.0,
            mirror: Some(Plane::ZX),
        };
        // (1,0,0) → (2,0,0) → (0,2,0) → mirrored in ZX (y → −y) → (0,−2,0) → (0,−2,1).
        let q = t.apply(DVec3::X).unwrap();
        assert!((q - DVec3::new(0.0, -2.0, 1.0)).length() < 1e-15);
    }

    #[test]
    fn bad_parameters_are_errors() {
        let p = DVec3::ONE;
        assert!(Transform::scaling(DVec3::ZERO, 0.0).apply(p).is_err());
        assert!(
            Transform::rotation(DVec3::ZERO, DVec3::ZERO, 10.0)
                .apply(p)
                .is_err()
        );
        // A zero axis is fine when nothing rotates.
        assert!(
            Transform::rotation(DVec3::ZERO, DVec3::ZERO, 0.0)
                .apply(p)
                .is_ok()
        );
        assert!(Transform::translation(DVec3::NAN).apply(p).is_err());
        assert!(Transform::default().apply(DVec3::NAN).is_err());
        let far = Polyline::open(vec![DVec3::ZERO, DVec3::splat(1e300)]);
        assert!(
            Transform::scaling(DVec3::ZERO, 1e10)
                .apply_polyline(&far)
                .is_err()
        );
        let mut bad = Plane::XY;
        bad.normal = DVec3::ZERO;
        assert!(Transform::mirroring(bad).apply(p).is_err());
    }
}
