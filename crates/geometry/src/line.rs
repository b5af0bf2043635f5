//! Line segments.

use glam::DVec3;

/// A line segment from `start` to `end`.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct Line {
    /// First end point.
    pub start: DVec3,
    /// Second end point.
    pub end: DVec3,
}

impl Line {
    /// A segment between two points.
    pub fn new(start: DVec3, end: DVec3) -> Self {
        Self { start, end }
    }

    /// Vector from start to end.
    pub fn direction(&self) -> DVec3 {
        self.end - self.start
    }

    /// Length of the segment.
    pub fn length(&self) -> f64 {
        self.start.distance(self.end)
    }

    /// Point at parameter `t` (0 = start, 1 = end).
    pub fn at(&self, t: f64) -> DVec3 {
        self.start.lerp(self.end, t)
    }

    /// Distance from `p` to the infinite line through the segment; `None` for a zero-length segment.
    pub fn distance_to_line(&self, p: DVec3) -> Option<f64> {
        let d = self.direction();
        let len = d.length();
        if len <= f64::MIN_POSITIVE {
            return None;
        }
        Some((p - self.start).cross(d).length() / len)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distance_to_line_is_perpendicular_distance() {
        let l = Line::new(DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0));
        assert_eq!(l.distance_to_line(DVec3::new(5.0, 3.0, 4.0)), Some(5.0));
        assert_eq!(
            Line::new(DVec3::X, DVec3::X).distance_to_line(DVec3::ZERO),
            None
        );
        assert_eq!(l.at(0.5), DVec3::X);
    }
}
