//! The directrix as swept by the construction: points X_0 … X_{M−1} (a closed directrix repeats its
//! first point), unit edges ê_j, lengths l_j, the outgoing edge at every vertex and the default Monge
//! (bisecting) plane normals (notes §1–§2).

use glam::DVec3;

use super::tolerance;
use crate::{GeometryError, Polyline};

/// The directrix prepared for the sweep. Column-indexed arrays use index j directly (entry 0 unused).
#[derive(Debug, Clone, PartialEq)]
pub struct SweptDirectrix {
    /// X_0 … X_{M−1}; for a closed directrix the stored points followed by the first point again.
    pub points: Vec<DVec3>,
    /// Whether the input directrix was closed.
    pub closed: bool,
    /// `edges[j] = ê_j = (X_j − X_{j−1}) / l_j` for j = 1 … M−1 (`edges[0]` = 0).
    pub edges: Vec<DVec3>,
    /// `lengths[j] = l_j` for j = 1 … M−1 (`lengths[0]` = 0).
    pub lengths: Vec<f64>,
    /// `outgoing[j]`: the unit edge leaving X_j: ê_{j+1} for j < M−1; at the last vertex ê_{M−1}
    /// (open directrix: straight continuation) or ê_1 (closed directrix).
    pub outgoing: Vec<DVec3>,
    /// `bisectors[j] = unit(ê_j + outgoing[j])`, the Monge plane normal at X_j; zero where the
    /// directrix reverses (see [`SweptDirectrix::bisector`]).
    pub bisectors: Vec<DVec3>,
}

impl SweptDirectrix {
    /// Validates the directrix (≥ 2 points, finite, no zero-length edge) and prepares it.
    pub fn new(directrix: &Polyline) -> Result<Self, GeometryError> {
        directrix.validate("directrix", 2)?;
        let points = directrix.swept_points();
        let m = points.len();
        let mut edges = vec![DVec3::ZERO; m];
        let mut lengths = vec![0.0; m];
        for j in 1..m {
            let e = points[j] - points[j - 1];
            let l = e.length();
            if !l.is_finite() {
                return Err(GeometryError::NonFiniteOutput {
                    what: "directrix edge length",
                    row: 0,
                    column: j,
                });
            }
            if l <= f64::MIN_POSITIVE {
                return Err(GeometryError::ZeroLengthEdge {
                    what: "directrix",
                    index: j - 1,
                    next: j % directrix.points.len(),
                });
            }
            edges[j] = e / l;
            lengths[j] = l;
        }
        let mut outgoing = vec![DVec3::ZERO; m];
        let mut bisectors = vec![DVec3::ZERO; m];
        for j in 1..m {
            outgoing[j] = if j + 1 < m {
                edges[j + 1]
            } else if directrix.closed {
                edges[1]
            } else {
                edges[j]
            };
            let s = edges[j] + outgoing[j];
            let len = s.length();
            if len > tolerance::REVERSAL {
                bisectors[j] = s / len;
            }
        }
        Ok(Self {
            points,
            closed: directrix.closed,
            edges,
            lengths,
            outgoing,
            bisectors,
        })
    }

    /// Number of columns M.
    pub fn columns(&self) -> usize {
        self.points.len()
    }

    /// Total length of the swept directrix (sum of l_j).
    pub fn length(&self) -> f64 {
        self.lengths.iter().sum()
    }

    /// The Monge (bisecting) normal at X_j, or an error naming j when the directrix reverses there.
    pub fn bisector(&self, j: usize) -> Result<DVec3, GeometryError> {
        let b = self.bisectors[j];
        if b == DVec3::ZERO {
            Err(GeometryError::DirectrixReverses { column: j })
        } else {
            Ok(b)
        }
    }

    /// Checks that every bisecting plane j = 1 … M−1 is defined.
    pub fn check_bisectors(&self) -> Result<(), GeometryError> {
        (1..self.columns()).try_for_each(|j| self.bisector(j).map(|_| ()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closed_directrix_repeats_first_point_and_uses_first_edge_at_the_end() {
        let square = Polyline::closed(vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::Y,
        ]);
        let d = SweptDirectrix::new(&square).unwrap();
        assert_eq!(d.columns(), 5);
        assert_eq!(d.points[4], DVec3::ZERO);
        assert_eq!(d.outgoing[4], DVec3::X);
        let expected = (DVec3::new(0.0, -1.0, 0.0) + DVec3::X).normalize();
        assert!((d.bisector(4).unwrap() - expected).length() < 1e-15);
        assert!((d.length() - 4.0).abs() < 1e-15);
    }

    #[test]
    fn open_directrix_ends_with_the_last_edge_as_normal() {
        let d = SweptDirectrix::new(&Polyline::open(vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::new(1.0, 1.0, 0.0),
        ]))
        .unwrap();
        assert_eq!(d.bisector(2).unwrap(), DVec3::Y);
        let reversing = Polyline::open(vec![DVec3::ZERO, DVec3::X, DVec3::ZERO]);
        let d = SweptDirectrix::new(&reversing).unwrap();
        assert_eq!(
            d.bisector(1),
            Err(GeometryError::DirectrixReverses { column: 1 })
        );
    }
}
