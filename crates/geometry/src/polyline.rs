//! Polylines: points stored once plus a `closed` flag.

use glam::DVec3;

use crate::error::{GeometryError, check_finite_points};

/// A polyline. Each point is stored once; a closed polyline has an implicit edge from the last point
/// back to the first.
#[derive(Debug, Clone, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct Polyline {
    /// The vertices, in order.
    pub points: Vec<DVec3>,
    /// Whether the last point connects back to the first.
    pub closed: bool,
}

impl Polyline {
    /// An open polyline through `points`.
    pub fn open(points: Vec<DVec3>) -> Self {
        Self {
            points,
            closed: false,
        }
    }

    /// A closed polyline through `points` (the first point is not repeated at the end).
    pub fn closed(points: Vec<DVec3>) -> Self {
        Self {
            points,
            closed: true,
        }
    }

    /// Number of stored points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// True when there are no points.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Number of edges: `len - 1` when open, `len` when closed (0 for fewer than 2 points).
    pub fn edge_count(&self) -> usize {
        match self.points.len() {
            0 | 1 => 0,
            n if self.closed => n,
            n => n - 1,
        }
    }

    /// The edge `k` as (start, end); wraps for the closing edge of a closed polyline.
    pub fn edge(&self, k: usize) -> (DVec3, DVec3) {
        let n = self.points.len();
        (self.points[k], self.points[(k + 1) % n])
    }

    /// Iterator over the edges as (start, end) pairs.
    pub fn edges(&self) -> impl Iterator<Item = (DVec3, DVec3)> + '_ {
        (0..self.edge_count()).map(|k| self.edge(k))
    }

    /// Total length of all edges.
    pub fn length(&self) -> f64 {
        self.edges().map(|(a, b)| a.distance(b)).sum()
    }

    /// The points as swept by a construction: a closed polyline yields its first point again at the end.
    pub fn swept_points(&self) -> Vec<DVec3> {
        let mut points = self.points.clone();
        if self.closed && !points.is_empty() {
            points.push(points[0]);
        }
        points
    }

    /// Checks that the polyline has at least `min_points` points, all finite, and no zero-length edge
    /// (including the closing edge of a closed polyline).
    pub fn validate(&self, what: &'static str, min_points: usize) -> Result<(), GeometryError> {
        if self.points.len() < min_points {
            return Err(GeometryError::TooFewPoints {
                what,
                needed: min_points,
                got: self.points.len(),
            });
        }
        check_finite_points(what, &self.points)?;
        let n = self.points.len();
        for k in 0..self.edge_count() {
            let (a, b) = self.edge(k);
            if a.distance_squared(b) <= f64::MIN_POSITIVE {
                return Err(GeometryError::ZeroLengthEdge {
                    what,
                    index: k,
                    next: (k + 1) % n,
                });
            }
        }
        Ok(())
    }

    /// Axis-aligned bounding box as (min, max); `None` when empty.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        crate::quad_grid::bounds_of(&self.points)
    }

    /// The same polyline with its points in reverse order.
    pub fn reversed(&self) -> Self {
        let mut points = self.points.clone();
        points.reverse();
        Self {
            points,
            closed: self.closed,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closed_square_has_four_edges_and_perimeter_four() {
        let p = Polyline::closed(vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::Y,
        ]);
        assert_eq!(p.edge_count(), 4);
        assert!((p.length() - 4.0).abs() < 1e-15);
        assert_eq!(p.swept_points().len(), 5);
        assert_eq!(p.swept_points()[4], DVec3::ZERO);
    }

    #[test]
    fn validate_reports_zero_length_edge_with_indices() {
        let p = Polyline::open(vec![DVec3::ZERO, DVec3::X, DVec3::X]);
        assert_eq!(
            p.validate("directrix", 2),
            Err(GeometryError::ZeroLengthEdge {
                what: "directrix",
                index: 1,
                next: 2
            })
        );
        let closed = Polyline::closed(vec![DVec3::ZERO, DVec3::X, DVec3::ZERO]);
        assert!(matches!(
            closed.validate("g", 2),
            Err(GeometryError::ZeroLengthEdge {
                index: 2,
                next: 0,
                ..
            })
        ));
    }

    #[test]
    fn validate_reports_non_finite_and_too_few() {
        let p = Polyline::open(vec![DVec3::ZERO, DVec3::new(f64::NAN, 0.0, 0.0)]);
        assert_eq!(
            p.validate("g", 2),
            Err(GeometryError::NonFinite {
                what: "g",
                index: 1
            })
        );
        let q = Polyline::open(vec![DVec3::ZERO]);
        assert!(matches!(
            q.validate("g", 2),
            Err(GeometryError::TooFewPoints { got: 1, .. })
        ));
    }
}
