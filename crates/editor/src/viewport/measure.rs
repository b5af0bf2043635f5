//! The measure tool (Rhino's Distance): click two points — snapped to the nearest drawn vertex or
//! handle within a few points, else to the grid on the construction plane — and the view shows
//! the segment between them with its length and its Δx, Δy, Δz. A third click starts over; Esc
//! leaves the tool.

use cnets_geometry::DVec3;
use egui::{Color32, Painter, Stroke, vec2};

use super::screen::ScreenMap;
use crate::worker::format_number;

/// The measure tool's state.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeasureTool {
    /// The first point clicked.
    pub from: Option<DVec3>,
    /// The second point clicked.
    pub to: Option<DVec3>,
}

impl MeasureTool {
    /// A click on `p`: the first point, the second, or (after both) a new first point.
    pub fn click(&mut self, p: DVec3) {
        match (self.from, self.to) {
            (Some(_), None) => self.to = Some(p),
            _ => {
                self.from = Some(p);
                self.to = None;
            }
        }
    }

    /// The measured distance, once both points are clicked.
    pub fn distance(&self) -> Option<f64> {
        Some((self.to? - self.from?).length())
    }

    /// The measurement as the status bar and the view write it.
    pub fn text(&self) -> Option<String> {
        let (a, b) = (self.from?, self.to?);
        let d = b - a;
        Some(format!(
            "distance {} m  (Δx {}, Δy {}, Δz {})",
            format_number(d.length()),
            format_number(d.x),
            format_number(d.y),
            format_number(d.z)
        ))
    }

    /// Paints the measured segment (or the one following the pointer) and its length.
    pub fn paint(&self, painter: &Painter, map: &ScreenMap, hover: Option<DVec3>) {
        let ink = Color32::from_rgb(0x7a, 0x2f, 0xb5);
        let Some(a) = self.from else {
            if let Some(h) = hover.and_then(|h| map.to_screen(h)) {
                painter.circle_stroke(h, 4.0, Stroke::new(1.5, ink));
            }
            return;
        };
        let Some(b) = self.to.or(hover) else {
            return;
        };
        let (Some(sa), Some(sb)) = (map.to_screen(a), map.to_screen(b)) else {
            return;
        };
        painter.line_segment([sa, sb], Stroke::new(2.0, ink));
        for s in [sa, sb] {
            painter.circle(s, 4.0, Color32::WHITE, Stroke::new(1.5, ink));
        }
        let label = format!("{} m", format_number((b - a).length()));
        let mid = sa + (sb - sa) * 0.5 + vec2(6.0, -6.0);
        let galley = painter.layout_no_wrap(label, egui::FontId::proportional(13.0), ink);
        let r =
            egui::Rect::from_min_size(mid - vec2(0.0, galley.size().y), galley.size()).expand(3.0);
        painter.rect_filled(r, 3.0, Color32::from_rgba_unmultiplied(255, 255, 255, 230));
        painter.galley(r.min + vec2(3.0, 3.0), galley, ink);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_clicks_measure_and_a_third_starts_over() {
        let mut m = MeasureTool::default();
        m.click(DVec3::new(0.0, 0.0, 0.0));
        assert_eq!(m.distance(), None);
        m.click(DVec3::new(3.0, 4.0, 0.0));
        assert_eq!(m.distance(), Some(5.0));
        assert_eq!(m.text().unwrap(), "distance 5 m  (Δx 3, Δy 4, Δz 0)");
        m.click(DVec3::new(1.0, 1.0, 1.0));
        assert_eq!((m.from, m.to), (Some(DVec3::ONE), None));
    }
}
