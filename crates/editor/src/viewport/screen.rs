//! Between the screen and the world: where a world point is drawn in the view, the ray under a
//! screen point, and the planes rays meet (the construction planes are in [`super::cplane`]).
//! Every viewport tool goes through these, so they agree on what is under the pointer.

use cnets_engine::numbers::snap;
use cnets_geometry::DVec3;
use cnets_render::Camera;
use egui::{Pos2, Rect};
use glam::Vec3;

pub use super::cplane::{CPlane, snap_along};

/// The view's rectangle on screen and its camera: the mapping between screen points and the world.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScreenMap {
    /// Where the view is drawn (screen points).
    pub rect: Rect,
    /// The camera.
    pub camera: Camera,
}

/// A ray in world coordinates (f64): `origin + t · direction`, `t ≥ 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorldRay {
    /// Start.
    pub origin: DVec3,
    /// Unit direction.
    pub direction: DVec3,
}

impl WorldRay {
    /// The point at parameter `t`.
    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + self.direction * t
    }
}

fn to_f64(v: Vec3) -> DVec3 {
    DVec3::new(f64::from(v.x), f64::from(v.y), f64::from(v.z))
}

impl ScreenMap {
    /// Width over height of the view.
    pub fn aspect(&self) -> f32 {
        self.rect.width().max(1.0) / self.rect.height().max(1.0)
    }

    /// Normalized device coordinates (x right, y up, −1..1 over the view) of a screen point.
    pub fn ndc(&self, p: Pos2) -> (f32, f32) {
        let r = self.rect;
        (
            (p.x - r.center().x) / (0.5 * r.width().max(1.0)),
            (r.center().y - p.y) / (0.5 * r.height().max(1.0)),
        )
    }

    /// Where a world point is drawn; `None` when it is behind the eye.
    pub fn to_screen(&self, p: DVec3) -> Option<Pos2> {
        let q = Vec3::new(p.x as f32, p.y as f32, p.z as f32);
        let ndc = self.camera.project(q, self.aspect())?;
        let r = self.rect;
        Some(Pos2::new(
            r.center().x + ndc.x * 0.5 * r.width(),
            r.center().y - ndc.y * 0.5 * r.height(),
        ))
    }

    /// The ray under a screen point.
    pub fn ray(&self, p: Pos2) -> WorldRay {
        let (x, y) = self.ndc(p);
        let r = self.camera.ray(x, y, self.aspect());
        WorldRay {
            origin: to_f64(r.origin),
            direction: to_f64(r.direction).normalize(),
        }
    }

    /// World size of one screen point at the camera's target.
    pub fn world_per_point(&self) -> f64 {
        2.0 * f64::from(self.camera.half_height_at_target())
            / f64::from(self.rect.height().max(1.0))
    }

    /// The unit vector from the target towards the eye (f64).
    pub fn back(&self) -> DVec3 {
        to_f64(self.camera.back())
    }

    /// The camera's target (f64).
    pub fn target(&self) -> DVec3 {
        to_f64(self.camera.target)
    }
}

/// A plane through `origin` with unit `normal` (f64).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorldPlane {
    /// A point of the plane.
    pub origin: DVec3,
    /// Unit normal.
    pub normal: DVec3,
}

impl WorldPlane {
    /// Where `ray` meets the plane; `None` when it runs (nearly) parallel to it or the plane is
    /// behind its start.
    pub fn hit(&self, ray: &WorldRay) -> Option<DVec3> {
        let denom = ray.direction.dot(self.normal);
        if denom.abs() < 1e-9 {
            return None;
        }
        let t = (self.origin - ray.origin).dot(self.normal) / denom;
        (t >= 0.0 && t.is_finite()).then(|| ray.at(t))
    }
}

/// `k` grid steps as the editor stores them (the shortest decimal: `3 × 0.1` is 0.3).
pub fn steps(k: f64, step: f64) -> f64 {
    snap(k * step, 0.0, step)
}

#[cfg(test)]
mod tests {
    use super::*;
    use cnets_render::{Projection, View};

    fn map(view: View, projection: Projection) -> ScreenMap {
        let mut camera = Camera::new(view);
        camera.projection = projection;
        camera.distance = 20.0;
        ScreenMap {
            rect: Rect::from_min_size(Pos2::new(100.0, 50.0), egui::vec2(800.0, 600.0)),
            camera,
        }
    }

    #[test]
    fn a_screen_point_and_the_ray_under_it_agree() {
        for projection in [Projection::Perspective, Projection::Orthographic] {
            for view in View::ALL {
                let m = map(view, projection);
                for p in [DVec3::new(1.0, 2.0, 0.5), DVec3::new(-3.0, 0.0, 2.0)] {
                    let s = m.to_screen(p).expect("in front");
                    let ray = m.ray(s);
                    // The point lies on the ray (to f32 rounding).
                    let t = (p - ray.origin).dot(ray.direction);
                    let miss = (ray.at(t) - p).length();
                    assert!(miss < 1e-3, "{view:?} {projection:?}: {miss}");
                }
            }
        }
    }

    #[test]
    fn construction_planes_snap_in_plane_and_keep_the_normal_coordinate() {
        let p = DVec3::new(1.26, -0.74, 3.33);
        assert_eq!(CPlane::XY.snap(p, 0.5), DVec3::new(1.5, -0.5, 3.33));
        assert_eq!(CPlane::XZ.snap(p, 0.5), DVec3::new(1.5, -0.74, 3.5));
        assert_eq!(CPlane::YZ.snap(p, 0.1), DVec3::new(1.26, -0.7, 3.3));
        let ray = WorldRay {
            origin: DVec3::new(2.0, 3.0, 10.0),
            direction: DVec3::NEG_Z,
        };
        assert_eq!(
            CPlane::XY.world().hit(&ray),
            Some(DVec3::new(2.0, 3.0, 0.0))
        );
        assert_eq!(CPlane::XZ.world().hit(&ray), None, "parallel");
        assert_eq!(steps(3.0, 0.1), 0.3);
    }
}
