//! Where the view looks from: the camera, the named view and its construction plane, and the
//! rectangle the view was drawn in last frame (the view's own state, owned here).

use cnets_render::{Camera, View};
use egui::Rect;

use super::LABEL_BAND;
use super::cplane::CPlane;
use super::navigation::{self, NamedView};
use super::screen::ScreenMap;

/// The camera and the named view shown, with what framing them needs.
pub struct Framing {
    /// The camera.
    pub camera: Camera,
    /// The named view shown.
    pub view: NamedView,
    /// The Perspective view's construction plane.
    pub perspective_plane: CPlane,
    /// Its name (`World XY`, `CPlane 1`: the grid's corner says it).
    pub perspective_name: String,
    /// Where the view was drawn in the last frame (screen points).
    pub rect: Rect,
    /// Width over height of [`Framing::rect`].
    pub aspect: f32,
    /// Resolution factor of the last frame (1 or [`super::INTERACTIVE_SCALE`]).
    pub render_scale: f32,
    /// Frame the geometry on the next frame.
    pub(super) fit_pending: bool,
    /// The geometry has been framed once since the document opened.
    pub(super) fitted_once: bool,
    /// egui time of the last change of scene or camera.
    pub(super) last_change: f64,
}

impl Default for Framing {
    fn default() -> Self {
        Self {
            camera: Camera::new(View::Iso),
            view: NamedView::Perspective,
            perspective_plane: CPlane::XY,
            perspective_name: CPlane::XY.label().to_string(),
            rect: Rect::NOTHING,
            aspect: 1.0,
            render_scale: 1.0,
            fit_pending: false,
            fitted_once: false,
            last_change: f64::NEG_INFINITY,
        }
    }
}

impl Framing {
    /// The screen mapping of the last frame.
    pub fn screen_map(&self) -> ScreenMap {
        ScreenMap {
            rect: self.rect,
            camera: self.camera,
        }
    }

    /// The construction plane of the view shown.
    pub fn cplane(&self) -> CPlane {
        self.view.cplane(self.perspective_plane)
    }

    /// The name of the construction plane of the view shown.
    pub fn cplane_name(&self) -> String {
        match self.view {
            NamedView::Perspective => self.perspective_name.clone(),
            v => v.cplane(self.perspective_plane).label().to_string(),
        }
    }

    /// Makes `plane`, called `name`, the Perspective view's construction plane.
    pub fn set_perspective_plane(&mut self, plane: CPlane, name: &str) {
        self.perspective_plane = plane;
        self.perspective_name = name.to_string();
    }

    /// Shows a named view (framed on the next frame).
    pub fn set_view(&mut self, view: NamedView) {
        self.view = view;
        navigation::turn_to(&mut self.camera, view);
        self.fit_pending = true;
    }

    /// Keeps the rectangle the view is drawn in this frame.
    pub(super) fn place(&mut self, rect: Rect) {
        self.rect = rect;
        self.aspect = rect.width().max(1.0) / rect.height().max(1.0);
    }

    /// Points the camera at `points`, clear of the label bands.
    pub(super) fn frame_points(&mut self, points: &[glam::Vec3]) {
        self.camera.fit_points(points, self.aspect);
        self.clear_labels();
    }

    /// Zooms out after a fit so the geometry clears the labels along the view's top (the
    /// statistics) and bottom (grid, axes, W × D × H): [`LABEL_BAND`] points each.
    fn clear_labels(&mut self) {
        let height = self.rect.height();
        let bands = 2.0 * LABEL_BAND;
        if height.is_finite() && height > 3.0 * bands {
            self.camera.zoom(height / (height - bands));
        }
    }

    /// A two-finger gesture: zooms by `zoom` (> 1: the fingers spread, in) about `centre` and
    /// pans by the fingers' common move `moved` (screen points).
    pub fn pinch(&mut self, zoom: f32, moved: egui::Vec2, centre: egui::Pos2) {
        if zoom.is_finite() && zoom > 0.0 && (zoom - 1.0).abs() > 1e-6 {
            let r = self.rect;
            let ndc_x = 2.0 * (centre.x - r.left()) / r.width().max(1.0) - 1.0;
            let ndc_y = 1.0 - 2.0 * (centre.y - r.top()) / r.height().max(1.0);
            self.camera.zoom_at(1.0 / zoom, ndc_x, ndc_y, self.aspect);
        }
        if moved != egui::Vec2::ZERO {
            self.camera.pan(moved.x, moved.y, self.rect.height());
        }
    }
}
