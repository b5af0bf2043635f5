//! The Draw curve tool (Rhino's InterpCrv / Polyline): click points on the view's construction
//! plane, snapped to the grid, with a rubber band showing the curve so far. Clicking the first
//! point again closes the curve; Enter or a double-click finishes; Backspace removes the last
//! point; Esc cancels. A finished curve becomes a `param.points` node holding the points wired
//! into a `curve.spline` (or `curve.polyline`, the tool's option).

use cnets_geometry::DVec3;
use cnets_geometry::curves::{Spline, SplineKind};
use egui::{Color32, Painter, Pos2, Stroke};

use super::screen::ScreenMap;

/// Screen distance (points) within which a click on the first point closes the curve.
pub const CLOSE_RADIUS: f32 = 9.0;

/// A curve drawn in the view, ready to become nodes.
#[derive(Clone, Debug, PartialEq)]
pub struct DrawnCurve {
    /// The clicked points.
    pub points: Vec<DVec3>,
    /// Closed by clicking the first point.
    pub closed: bool,
    /// A spline through the points (else a polyline).
    pub spline: bool,
}

/// The Draw curve tool's state.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DrawTool {
    /// Points clicked so far.
    pub points: Vec<DVec3>,
    /// Draw a polyline instead of a spline.
    pub polyline: bool,
}

/// What a click did.
#[derive(Clone, Debug, PartialEq)]
pub enum Click {
    /// A point was added.
    Added,
    /// The curve was closed and finished.
    Finished(DrawnCurve),
}

impl DrawTool {
    /// A click at screen point `at`, on the plane at `world` (snapped by the caller).
    pub fn click(&mut self, map: &ScreenMap, at: Pos2, world: DVec3) -> Click {
        let near_first = self
            .points
            .first()
            .and_then(|&p| map.to_screen(p))
            .is_some_and(|s| s.distance(at) <= CLOSE_RADIUS);
        if near_first && self.points.len() >= 3 {
            return Click::Finished(self.take(true));
        }
        // The second click of a double-click lands on the point just added: not a new point.
        if self.points.last() != Some(&world) {
            self.points.push(world);
        }
        Click::Added
    }

    /// Finishes an open curve (Enter, double-click); `None` with fewer than two points.
    pub fn finish(&mut self) -> Option<DrawnCurve> {
        (self.points.len() >= 2).then(|| self.take(false))
    }

    fn take(&mut self, closed: bool) -> DrawnCurve {
        DrawnCurve {
            points: std::mem::take(&mut self.points),
            closed,
            spline: !self.polyline,
        }
    }

    /// Removes the last point (Backspace).
    pub fn undo_point(&mut self) {
        self.points.pop();
    }

    /// The curve so far with the pointer's point `hover` appended, as the rubber band draws it.
    pub fn rubber_band(&self, hover: Option<DVec3>) -> Vec<DVec3> {
        let mut points = self.points.clone();
        if let Some(h) = hover
            && points.last() != Some(&h)
        {
            points.push(h);
        }
        if self.polyline || points.len() < 3 {
            return points;
        }
        // The curve.spline node's default: centripetal Catmull–Rom.
        Spline::new(SplineKind::CatmullRom, &points, false)
            .and_then(|s| s.sample_even(16 * points.len()))
            .map_or(points, |p| p.points)
    }

    /// Paints the rubber band and the clicked points.
    pub fn paint(&self, painter: &Painter, map: &ScreenMap, hover: Option<DVec3>) {
        let ink = Color32::from_rgb(0xe0, 0x6c, 0x00);
        let line: Vec<Pos2> = self
            .rubber_band(hover)
            .into_iter()
            .filter_map(|p| map.to_screen(p))
            .collect();
        if line.len() >= 2 {
            painter.add(egui::Shape::line(line, Stroke::new(2.0, ink)));
        }
        for (k, p) in self.points.iter().enumerate() {
            if let Some(s) = map.to_screen(*p) {
                let r = if k == 0 { 5.0 } else { 3.5 };
                painter.circle(s, r, Color32::WHITE, Stroke::new(1.5, ink));
            }
        }
        if let Some(h) = hover.and_then(|h| map.to_screen(h)) {
            painter.circle_stroke(h, 4.0, Stroke::new(1.0, ink));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use cnets_render::{Camera, Projection, View};
    use egui::Rect;

    #[test]
    fn clicks_add_points_the_first_closes_and_enter_finishes() {
        let mut camera = Camera::new(View::Top);
        camera.projection = Projection::Orthographic;
        let map = ScreenMap {
            rect: Rect::from_min_size(Pos2::ZERO, egui::vec2(400.0, 300.0)),
            camera,
        };
        let mut tool = DrawTool::default();
        let pts = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
        ];
        for p in pts {
            let s = map.to_screen(p).unwrap();
            assert_eq!(tool.click(&map, s, p), Click::Added);
        }
        // A double-click's second click does not add the same point twice.
        let s = map.to_screen(pts[2]).unwrap();
        assert_eq!(tool.click(&map, s, pts[2]), Click::Added);
        assert_eq!(tool.points.len(), 3);
        let first = map.to_screen(pts[0]).unwrap();
        let Click::Finished(curve) = tool.click(&map, first + egui::vec2(2.0, 0.0), pts[0]) else {
            panic!("closed")
        };
        assert!(curve.closed && curve.spline);
        assert_eq!(curve.points, pts);
        assert!(tool.points.is_empty());
        tool.polyline = true;
        tool.click(&map, s, pts[2]);
        assert_eq!(tool.finish(), None, "one point is no curve");
        tool.click(&map, first, pts[0]);
        let open = tool.finish().unwrap();
        assert!(!open.closed && !open.spline);
    }
}
