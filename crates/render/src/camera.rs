//! The orbit camera: Z up (as in Rhino), perspective projection with reverse-Z depth.
//!
//! The eye sits at `target + distance · (cos pitch cos yaw, cos pitch sin yaw, sin pitch)`; yaw turns
//! around the Z axis, pitch lifts the eye above the XY plane (±90° looks straight down/up, which is
//! fine: the camera's up vector is derived from yaw and pitch, never from a fixed world axis).
//!
//! The projection is an infinite-far, reverse-Z perspective (`near` maps to depth 1, infinity to 0),
//! which keeps `Depth32Float` precise over any scene size; `near` follows the orbit distance. An
//! orthographic camera ([`Projection::Orthographic`], the named Top, Front and Right views of the
//! editor) shows the same picture height at the target as the perspective one would
//! (`2 · distance · tan(fov / 2)`), with linear reverse-Z depth over [`ORTHO_DEPTH`] orbit
//! distances on either side of the target.

use std::f32::consts::{FRAC_PI_2, FRAC_PI_4};
use std::fmt;
use std::str::FromStr;

use glam::camera::rh;
use glam::{Mat4, Vec3};

use crate::scene::Bounds;

/// A preset viewing direction.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum View {
    /// Isometric, from the south-east and above (+X, −Y, +Z), like Rhino's SE isometric.
    #[default]
    Iso,
    /// From above, looking down −Z: X to the right, Y up on screen.
    Top,
    /// From the front (−Y), looking along +Y: X to the right, Z up.
    Front,
    /// From the right side (+X), looking along −X: Y to the right, Z up.
    Side,
}

impl View {
    /// All presets.
    pub const ALL: [View; 4] = [View::Iso, View::Top, View::Front, View::Side];

    /// `(yaw, pitch)` in radians of the preset.
    pub fn angles(self) -> (f32, f32) {
        match self {
            // True isometric elevation: atan(1/√2) ≈ 35.26°.
            View::Iso => (-FRAC_PI_4, (1.0f32 / 2.0f32.sqrt()).atan()),
            View::Top => (-FRAC_PI_2, FRAC_PI_2),
            View::Front => (-FRAC_PI_2, 0.0),
            View::Side => (0.0, 0.0),
        }
    }

    /// The lower-case name used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            View::Iso => "iso",
            View::Top => "top",
            View::Front => "front",
            View::Side => "side",
        }
    }
}

impl fmt::Display for View {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Error of parsing a [`View`].
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown view {0:?} (expected iso, top, front or side)")]
pub struct ParseViewError(pub String);

impl FromStr for View {
    type Err = ParseViewError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "iso" => Ok(View::Iso),
            "top" => Ok(View::Top),
            "front" => Ok(View::Front),
            "side" | "right" => Ok(View::Side),
            _ => Err(ParseViewError(s.to_string())),
        }
    }
}

/// How the camera projects: perspective, or parallel (orthographic) as Rhino's Top, Front and
/// Right views.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Projection {
    /// Perspective (the default).
    #[default]
    Perspective,
    /// Parallel projection: sizes do not shrink with depth.
    Orthographic,
}

/// An orthographic camera sees this many orbit distances in front of and behind the target.
pub const ORTHO_DEPTH: f32 = 1000.0;

/// A ray from the eye through a point of the image: `origin + t · direction`, `t ≥ 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Where the ray starts (the eye, or on the image plane of an orthographic camera).
    pub origin: Vec3,
    /// Unit direction.
    pub direction: Vec3,
}

/// Margin kept around a fitted box, as a fraction of the half field of view.
const FIT_MARGIN: f32 = 0.92;
/// Smallest orbit distance, relative to nothing (absolute world units); keeps matrices invertible.
const MIN_DISTANCE: f32 = 1e-6;
/// Near plane as a fraction of the orbit distance.
const NEAR_FRACTION: f32 = 1e-3;

/// An orbit camera around `target`. See the module docs for the conventions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// The point orbited around and looked at.
    pub target: Vec3,
    /// Angle around +Z in radians (0: eye on +X).
    pub yaw: f32,
    /// Elevation in radians, within `-π/2..=π/2`.
    pub pitch: f32,
    /// Eye-to-target distance (> 0).
    pub distance: f32,
    /// Vertical field of view in radians.
    pub fov_y: f32,
    /// Perspective or orthographic.
    pub projection: Projection,
}

impl Default for Camera {
    fn default() -> Self {
        let (yaw, pitch) = View::Iso.angles();
        Self {
            target: Vec3::ZERO,
            yaw,
            pitch,
            distance: 10.0,
            fov_y: 40f32.to_radians(),
            projection: Projection::Perspective,
        }
    }
}

impl Camera {
    /// The default camera turned to a preset view.
    pub fn new(view: View) -> Self {
        let mut c = Self::default();
        c.set_view(view);
        c
    }

    /// A camera looking from `view` that frames `bounds` at the given aspect ratio (width / height).
    pub fn framing(view: View, bounds: Option<Bounds>, aspect: f32) -> Self {
        let mut c = Self::new(view);
        c.fit(bounds, aspect);
        c
    }

    /// A camera looking from `view` that frames everything in `scene` tightly.
    pub fn framing_scene(view: View, scene: &crate::Scene, aspect: f32) -> Self {
        let mut c = Self::new(view);
        c.fit_scene(scene, aspect);
        c
    }

    /// Turns to a preset view, keeping target and distance.
    pub fn set_view(&mut self, view: View) {
        (self.yaw, self.pitch) = view.angles();
    }

    /// Unit vector from the target towards the eye.
    pub fn back(&self) -> Vec3 {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        Vec3::new(cp * cy, cp * sy, sp)
    }

    /// Unit view direction (from the eye towards the target).
    pub fn forward(&self) -> Vec3 {
        -self.back()
    }

    /// Unit up vector of the image (orthogonal to the view direction; +Z-ish unless looking along Z).
    pub fn up(&self) -> Vec3 {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        Vec3::new(-sp * cy, -sp * sy, cp)
    }

    /// Unit right vector of the image.
    pub fn right(&self) -> Vec3 {
        self.forward().cross(self.up())
    }

    /// Eye position (for an orthographic camera: far back along the view axis, where the depth
    /// range starts).
    pub fn eye(&self) -> Vec3 {
        self.target + self.back() * self.eye_distance()
    }

    /// Whether the projection is orthographic.
    pub fn is_orthographic(&self) -> bool {
        self.projection == Projection::Orthographic
    }

    /// Distance from the eye to the target along the view axis.
    fn eye_distance(&self) -> f32 {
        match self.projection {
            Projection::Perspective => self.distance(),
            Projection::Orthographic => self.distance() * ORTHO_DEPTH,
        }
    }

    /// Half the height of the picture at the target, in world units.
    pub fn half_height_at_target(&self) -> f32 {
        self.distance() * (self.fov() * 0.5).tan()
    }

    /// The ray through a point of the image given in normalized device coordinates (x right,
    /// y up, both in `-1..=1` over the view).
    pub fn ray(&self, ndc_x: f32, ndc_y: f32, aspect: f32) -> Ray {
        let aspect = safe_aspect(aspect);
        let (right, up, forward) = (self.right(), self.up(), self.forward());
        let half_h = (self.fov() * 0.5).tan();
        match self.projection {
            Projection::Perspective => Ray {
                origin: self.eye(),
                direction: (forward + right * (ndc_x * half_h * aspect) + up * (ndc_y * half_h))
                    .normalize(),
            },
            Projection::Orthographic => {
                let h = self.half_height_at_target();
                Ray {
                    origin: self.eye() + right * (ndc_x * h * aspect) + up * (ndc_y * h),
                    direction: forward,
                }
            }
        }
    }

    /// Depth bias scale for the renderer: 0 for perspective (biases are relative to the depth),
    /// else the orbit distance in normalized depth units (biases are added, relative to it).
    pub fn ortho_bias_scale(&self) -> f32 {
        match self.projection {
            Projection::Perspective => 0.0,
            Projection::Orthographic => 1.0 / (2.0 * ORTHO_DEPTH),
        }
    }

    /// The orbit distance, made safe (finite and positive).
    fn distance(&self) -> f32 {
        if self.distance.is_finite() {
            self.distance.max(MIN_DISTANCE)
        } else {
            10.0
        }
    }

    /// The vertical field of view, made safe (1°..=170°).
    fn fov(&self) -> f32 {
        if self.fov_y.is_finite() {
            self.fov_y.clamp(1f32.to_radians(), 170f32.to_radians())
        } else {
            0.7
        }
    }

    /// Half the horizontal and vertical field of view (radians) for an aspect ratio.
    fn half_fovs(&self, aspect: f32) -> (f32, f32) {
        let ty = (self.fov() * 0.5).tan();
        let tx = ty * safe_aspect(aspect);
        (tx.atan(), ty.atan())
    }

    /// World-to-view matrix (right-handed, looking along −Z in view space).
    pub fn view_matrix(&self) -> Mat4 {
        rh::view::look_at_mat4(self.eye(), self.target, self.up())
    }

    /// Projection matrix: infinite reverse-Z perspective (depth 1 at the near plane, 0 at
    /// infinity), or orthographic with linear reverse-Z depth (1 at the eye, 0 at
    /// `2 · ORTHO_DEPTH` orbit distances from it).
    pub fn projection_matrix(&self, aspect: f32) -> Mat4 {
        match self.projection {
            // wgpu's NDC is DirectX-like: z in 0..1, y up.
            Projection::Perspective => rh::proj::directx::perspective_infinite_reverse(
                self.fov(),
                safe_aspect(aspect),
                self.near(),
            ),
            Projection::Orthographic => {
                let h = self.half_height_at_target();
                let w = h * safe_aspect(aspect);
                let far = 2.0 * self.eye_distance();
                // View space looks along −z: depth d = −z; ndc z = (far − d) / far.
                Mat4::from_cols(
                    glam::Vec4::new(1.0 / w, 0.0, 0.0, 0.0),
                    glam::Vec4::new(0.0, 1.0 / h, 0.0, 0.0),
                    glam::Vec4::new(0.0, 0.0, 1.0 / far, 0.0),
                    glam::Vec4::new(0.0, 0.0, 1.0, 1.0),
                )
            }
        }
    }

    /// Near plane distance.
    pub fn near(&self) -> f32 {
        self.distance() * NEAR_FRACTION
    }

    /// `projection × view`.
    pub fn view_projection(&self, aspect: f32) -> Mat4 {
        self.projection_matrix(aspect) * self.view_matrix()
    }

    /// Sets target and distance so the whole box is visible from the current direction with a
    /// small margin, its image centred (the target stays in the box's middle plane, near its
    /// centre). Empty bounds (`None`) frame the unit cube around the origin; a box of (almost)
    /// zero size, e.g. a single point, is padded to a small cube around it and its centre becomes
    /// the target.
    pub fn fit(&mut self, bounds: Option<Bounds>, aspect: f32) {
        let b = padded(bounds);
        let degenerate = bounds != Some(b);
        self.fit_points_inner(&b.corners(), b, aspect, !degenerate);
    }

    /// Like [`Camera::fit`] but frames the given points tightly and centres their image (a box's
    /// corners usually project wider than the geometry inside it). Non-finite points are ignored; no finite point frames
    /// the unit cube around the origin.
    pub fn fit_points(&mut self, points: &[Vec3], aspect: f32) {
        let bounds = Bounds::from_points(points.iter().copied());
        let b = padded(bounds);
        match bounds {
            Some(raw) if raw.size().max_element() >= b.size().max_element() * 0.999 => {
                self.fit_points_inner(points, b, aspect, true)
            }
            // Degenerate: frame the padded box instead.
            _ => self.fit_points_inner(&b.corners(), b, aspect, false),
        }
    }

    /// Frames everything drawn in `scene` tightly ([`Camera::fit_points`] over all its vertices).
    pub fn fit_scene(&mut self, scene: &crate::Scene, aspect: f32) {
        let points: Vec<Vec3> = scene.positions().collect();
        self.fit_points(&points, aspect);
    }

    /// Frames the surfaces of `scene` (apices and other markers can lie far away, even near infinity,
    /// and would shrink the mesh to a dot), or everything when it has no surfaces.
    pub fn fit_surfaces(&mut self, scene: &crate::Scene, aspect: f32) {
        let surfaces: Vec<Vec3> = scene
            .face_vertices()
            .iter()
            .map(|v| Vec3::from(v.position))
            .collect();
        if surfaces.is_empty() {
            self.fit_scene(scene, aspect);
        } else {
            self.fit_points(&surfaces, aspect);
        }
    }

    fn fit_points_inner(&mut self, points: &[Vec3], b: Bounds, aspect: f32, recenter: bool) {
        if self.is_orthographic() {
            self.fit_orthographic(points, b, aspect);
            return;
        }
        let (hx, hy) = self.half_fovs(aspect);
        let (tx, ty) = (hx.tan() * FIT_MARGIN, hy.tan() * FIT_MARGIN);
        let (right, up, back) = (self.right(), self.up(), self.back());
        let radius = b.radius();
        let center = b.center();
        // The points in the camera's frame around the box centre: (x, y) across the image, z
        // towards the eye. The eye sits at (ex, ey, d); a point is in view when
        // |x - ex| <= tx (d - z) and |y - ey| <= ty (d - z).
        let frame: Vec<Vec3> = points
            .iter()
            .filter(|p| p.is_finite())
            .map(|p| {
                let c = *p - center;
                Vec3::new(c.dot(right), c.dot(up), c.dot(back))
            })
            .collect();
        if frame.is_empty() {
            self.target = center;
            self.distance = (radius * 3.0).max(MIN_DISTANCE);
            return;
        }
        // Each axis alone: the eye where the two outermost rays touch the points (its image
        // spans the view exactly), at the depth `(hi - lo) / (2 t)` and across at `(hi + lo) / 2`.
        let wedge = |across: &dyn Fn(&Vec3) -> f32, t: f32| {
            let hi = frame
                .iter()
                .map(|p| across(p) + t * p.z)
                .fold(f32::NEG_INFINITY, f32::max);
            let lo = frame
                .iter()
                .map(|p| across(p) - t * p.z)
                .fold(f32::INFINITY, f32::min);
            (hi - lo) / (2.0 * t)
        };
        let z_max = frame.iter().map(|p| p.z).fold(f32::NEG_INFINITY, f32::max);
        // The axis that needs the farther eye decides; the near plane (a thousandth of d) is
        // kept well clear of the geometry.
        let d = wedge(&|p| p.x, tx)
            .max(wedge(&|p| p.y, ty))
            .max(z_max + 0.05 * radius)
            .max(radius * 0.05)
            .max(MIN_DISTANCE);
        let (ex, ey) = if recenter {
            (
                centred_across(&frame, d, |p| p.x),
                centred_across(&frame, d, |p| p.y),
            )
        } else {
            (0.0, 0.0)
        };
        // The target straight ahead of the eye, at the depth of the box's centre.
        self.target = center + right * ex + up * ey;
        self.distance = d;
    }

    /// Orthographic framing: the image of the points centred, the larger of their half width
    /// (over the aspect) and half height filling the view up to the margin.
    fn fit_orthographic(&mut self, points: &[Vec3], b: Bounds, aspect: f32) {
        let (right, up) = (self.right(), self.up());
        let (mut lo, mut hi) = (
            glam::Vec2::splat(f32::INFINITY),
            glam::Vec2::splat(f32::NEG_INFINITY),
        );
        let center = b.center();
        for p in points.iter().filter(|p| p.is_finite()) {
            let c = *p - center;
            let q = glam::Vec2::new(c.dot(right), c.dot(up));
            lo = lo.min(q);
            hi = hi.max(q);
        }
        if !(lo.is_finite() && hi.is_finite()) {
            (lo, hi) = (glam::Vec2::splat(-0.5), glam::Vec2::splat(0.5));
        }
        let mid = (lo + hi) * 0.5;
        let half = (hi - lo) * 0.5;
        let half_h = (half.y.max(half.x / safe_aspect(aspect)) / FIT_MARGIN)
            .max(b.radius() * 1e-3)
            .max(MIN_DISTANCE);
        self.target = center + right * mid.x + up * mid.y;
        self.distance = half_h / (self.fov() * 0.5).tan();
    }

    /// Zooms by `factor` (< 1 zooms in) keeping the point of the target's plane under the image
    /// point `(ndc_x, ndc_y)` where it is on screen (the mouse wheel zooms towards the pointer).
    pub fn zoom_at(&mut self, factor: f32, ndc_x: f32, ndc_y: f32, aspect: f32) {
        if !(factor.is_finite() && factor > 0.0 && ndc_x.is_finite() && ndc_y.is_finite()) {
            return;
        }
        let h = self.half_height_at_target();
        let under = self.target
            + self.right() * (ndc_x * h * safe_aspect(aspect))
            + self.up() * (ndc_y * h);
        let before = self.distance();
        self.zoom(factor);
        let actual = self.distance() / before;
        self.target = under + (self.target - under) * actual;
    }

    /// Turns the eye around the target by `d_yaw` and `d_pitch` radians (pitch clamped to ±90°).
    /// The target and the distance stay.
    pub fn orbit(&mut self, d_yaw: f32, d_pitch: f32) {
        if d_yaw.is_finite() {
            self.yaw = (self.yaw + d_yaw).rem_euclid(std::f32::consts::TAU);
        }
        if d_pitch.is_finite() {
            self.pitch = (self.pitch + d_pitch).clamp(-FRAC_PI_2, FRAC_PI_2);
        }
    }

    /// Moves the target (and the eye with it) in the image plane by a mouse drag of `dx, dy`
    /// pixels in a viewport `viewport_height` pixels tall: the point under the cursor at the
    /// target's depth follows the cursor. Positive `dy` is downwards, as in screen coordinates.
    pub fn pan(&mut self, dx: f32, dy: f32, viewport_height: f32) {
        if !(dx.is_finite() && dy.is_finite() && viewport_height > 0.0) {
            return;
        }
        let world_per_px = 2.0 * self.distance() * (self.fov() * 0.5).tan() / viewport_height;
        self.target += (-dx * self.right() + dy * self.up()) * world_per_px;
    }

    /// Multiplies the distance by `factor` (< 1 zooms in); the target stays.
    pub fn zoom(&mut self, factor: f32) {
        if factor.is_finite() && factor > 0.0 {
            self.distance = (self.distance() * factor).max(MIN_DISTANCE);
        }
    }

    /// Projects a world point to normalized device coordinates `(x, y, depth)`; `None` when it is
    /// behind the eye. Inside the view means x, y in `-1..=1` and depth in `0..=1`.
    pub fn project(&self, p: Vec3, aspect: f32) -> Option<Vec3> {
        let clip = self.view_projection(aspect) * p.extend(1.0);
        (clip.w > 0.0).then(|| clip.truncate() / clip.w)
    }
}

/// The box to frame: the unit cube for none, padded to a small cube when (almost) degenerate.
fn padded(bounds: Option<Bounds>) -> Bounds {
    let b = match bounds {
        Some(b) if b.min.is_finite() && b.max.is_finite() => b,
        _ => return Bounds::new(Vec3::splat(-0.5), Vec3::splat(0.5)),
    };
    let extent = b.size().max_element();
    let scale = b.min.abs().max(b.max.abs()).max_element();
    // Below this size f32 cannot resolve the geometry anyway; pad to a visible cube.
    let min_extent = (scale * 1e-4).max(1e-3);
    if extent >= min_extent {
        return b;
    }
    let half = 0.5
        * if extent > 0.0 {
            min_extent
        } else {
            min_extent.max(1.0)
        };
    Bounds::new(
        b.center() - Vec3::splat(half),
        b.center() + Vec3::splat(half),
    )
}

fn safe_aspect(aspect: f32) -> f32 {
    if aspect.is_finite() && aspect > 0.0 {
        aspect.clamp(1e-3, 1e3)
    } else {
        1.0
    }
}

/// Where across the image (along one axis of the camera's frame) the eye at depth `d` sees the
/// points centred: the offset where the largest image coordinate of a point equals minus the
/// smallest. Each point's image coordinate `(across - e) / (d - z)` falls as `e` grows, so the
/// balance does too; bisection between the points' extremes (where it is ≥ 0 and ≤ 0) finds it
/// whatever the depths — a long object seen end-on is centred as exactly as a flat one.
fn centred_across(frame: &[Vec3], d: f32, across: impl Fn(&Vec3) -> f32) -> f32 {
    let balance = |e: f32| {
        let (lo, hi) = frame
            .iter()
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), p| {
                let u = (across(p) - e) / (d - p.z).max(f32::MIN_POSITIVE);
                (lo.min(u), hi.max(u))
            });
        hi + lo
    };
    let (mut lo, mut hi) = frame
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(across(p)), hi.max(across(p)))
        });
    if !(lo.is_finite() && hi.is_finite()) {
        return 0.0;
    }
    for _ in 0..64 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if balance(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}
