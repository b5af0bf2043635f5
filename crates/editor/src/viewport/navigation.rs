//! Moving around the 3D view: the named views (Top, Front and Right orthographic, Perspective) and
//! their construction planes, orbit, pan and the wheel zooming towards the pointer.

use cnets_render::{Camera, Projection, View};
use egui::{Key, Modifiers};

use super::screen::{CPlane, ScreenMap};

/// A named view, as Rhino's four viewports.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum NamedView {
    /// From above, orthographic; draws on world XY.
    Top,
    /// From the front (−Y), orthographic; draws on world XZ.
    Front,
    /// From the right (+X), orthographic; draws on world YZ.
    Right,
    /// Perspective; draws on the chosen construction plane (world XY unless set).
    #[default]
    Perspective,
}

impl NamedView {
    /// All views, in menu order.
    pub const ALL: [NamedView; 4] = [
        NamedView::Top,
        NamedView::Front,
        NamedView::Right,
        NamedView::Perspective,
    ];

    /// Menu and button label.
    pub fn label(self) -> &'static str {
        match self {
            NamedView::Top => "Top",
            NamedView::Front => "Front",
            NamedView::Right => "Right",
            NamedView::Perspective => "Perspective",
        }
    }

    /// The one-key shortcut (1–4) and the Rhino one (Ctrl+F1–F4).
    pub fn keys(self) -> (Key, Key) {
        match self {
            NamedView::Top => (Key::Num1, Key::F1),
            NamedView::Front => (Key::Num2, Key::F2),
            NamedView::Right => (Key::Num3, Key::F3),
            NamedView::Perspective => (Key::Num4, Key::F4),
        }
    }

    /// The shortcut as menus write it.
    pub fn shortcut(self) -> &'static str {
        match self {
            NamedView::Top => "1 · Ctrl+F1",
            NamedView::Front => "2 · Ctrl+F2",
            NamedView::Right => "3 · Ctrl+F3",
            NamedView::Perspective => "4 · Ctrl+F4",
        }
    }

    /// The camera direction.
    pub fn direction(self) -> View {
        match self {
            NamedView::Top => View::Top,
            NamedView::Front => View::Front,
            NamedView::Right => View::Side,
            NamedView::Perspective => View::Iso,
        }
    }

    /// The projection.
    pub fn projection(self) -> Projection {
        match self {
            NamedView::Perspective => Projection::Perspective,
            _ => Projection::Orthographic,
        }
    }

    /// Whether the view is orthographic.
    pub fn is_orthographic(self) -> bool {
        self.projection() == Projection::Orthographic
    }

    /// The construction plane: the view's own plane, or `perspective` for the Perspective view.
    pub fn cplane(self, perspective: CPlane) -> CPlane {
        match self {
            NamedView::Top => CPlane::XY,
            NamedView::Front => CPlane::XZ,
            NamedView::Right => CPlane::YZ,
            NamedView::Perspective => perspective,
        }
    }

    /// The view whose shortcut was pressed this frame (consumed), if any.
    pub fn pressed(ctx: &egui::Context) -> Option<NamedView> {
        ctx.input_mut(|i| {
            NamedView::ALL.into_iter().find(|v| {
                let (digit, function) = v.keys();
                i.consume_key(Modifiers::NONE, digit) || i.consume_key(Modifiers::COMMAND, function)
            })
        })
    }
}

/// Turns the camera to a named view (its direction and projection; target and distance kept).
pub fn turn_to(camera: &mut Camera, view: NamedView) {
    camera.set_view(view.direction());
    camera.projection = view.projection();
}

/// Orbits by a drag of `delta` screen points.
pub fn orbit(camera: &mut Camera, delta: egui::Vec2) {
    camera.orbit(-delta.x * 0.008, delta.y * 0.008);
}

/// Zooms with a wheel of `scroll` points towards the screen point `at`.
pub fn wheel(map: &mut ScreenMap, scroll: f32, at: egui::Pos2) {
    let (x, y) = map.ndc(at);
    let aspect = map.aspect();
    map.camera.zoom_at((-scroll * 0.002).exp(), x, y, aspect);
}

#[cfg(test)]
mod tests {
    use super::*;
    use cnets_geometry::DVec3;
    use egui::{Pos2, Rect};

    #[test]
    fn the_wheel_zooms_towards_the_pointer() {
        for view in NamedView::ALL {
            let mut camera = Camera::new(View::Iso);
            turn_to(&mut camera, view);
            camera.distance = 10.0;
            let mut map = ScreenMap {
                rect: Rect::from_min_size(Pos2::new(50.0, 20.0), egui::vec2(600.0, 400.0)),
                camera,
            };
            let at = Pos2::new(500.0, 100.0);
            // The point of the target's plane under the pointer stays under it.
            let plane = super::super::screen::WorldPlane {
                origin: map.target(),
                normal: map.back(),
            };
            let before = plane.hit(&map.ray(at)).unwrap();
            wheel(&mut map, 240.0, at);
            assert!(map.camera.distance < 10.0, "wheel up zooms in");
            let after = map.to_screen(before).unwrap();
            assert!(after.distance(at) < 0.05, "{view:?}: {after:?} vs {at:?}");
            let _ = DVec3::ZERO;
        }
    }
}
