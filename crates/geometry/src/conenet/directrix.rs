//! The directrix as swept by the construction: points X_0 … X_{M−1} (a closed directrix repeats its
//! first point), unit edges ê_j, lengths l_j, the outgoing edge at every vertex and the default Monge
//! (bisecting) plane normals (notes §1–§2).

use glam::DVec3;

use super::inputs::EndPlanes;
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
    /// `outgoing[j]`: the unit edge leaving X_j: ê_{j+1} for j < M−1; at the last vertex ê_1 (closed
    /// directrix), or for an open one ê_{M−1} (straight continuation, [`EndPlanes::Perpendicular`])
    /// or ê_{M−1} reflected in the mirrored plane ([`EndPlanes::Mirror`]).
    pub outgoing: Vec<DVec3>,
    /// `bisectors[j] = unit(ê_j + outgoing[j])`, the Monge plane normal at X_j; zero where the
    /// directrix reverses (see [`SweptDirectrix::bisector`]).
    pub bisectors: Vec<DVec3>,
}

impl SweptDirectrix {
    /// Validates the directrix (≥ 2 points, finite, no zero-length edge) and prepares it with
    /// perpendicular end planes.
    pub fn new(directrix: &Polyline) -> Result<Self, GeometryError> {
        Self::with_end_planes(directrix, EndPlanes::Perpendicular)
    }

    /// Like [`SweptDirectrix::new`], with the given choice of the plane at an open directrix's last
    /// vertex. [`EndPlanes::Mirror`] reflects the bisecting plane at X_{M−2} in the perpendicular
    /// bisector plane of the last edge (normal `2 (b·ê) ê − b`, oriented along ê) and takes the
    /// outgoing edge that makes it the bisector (`2 (ê·b') b' − ê`).
    pub fn with_end_planes(directrix: &Polyline, end: EndPlanes) -> Result<Self, GeometryError> {
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
        if end == EndPlanes::Mirror && !directrix.closed && m >= 3 {
            let (b, e) = (bisectors[m - 2], edges[m - 1]);
            // A reversal at X_{M−2} (b = 0) stays an error there; the end plane is then unused.
            if b != DVec3::ZERO {
                let mirrored = (2.0 * b.dot(e) * e - b).normalize_or_zero();
                let out = 2.0 * e.dot(mirrored) * mirrored - e;
                outgoing[m - 1] = out.normalize_or_zero();
                bisectors[m - 1] = if (e + outgoing[m - 1]).length() > tolerance::REVERSAL {
                    mirrored
                } else {
                    DVec3::ZERO
                };
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
        // Mirror: the bisector (1, 1)/√2 at X_1 reflected in the plane y = ½ (the perpendicular
        // bisector of the last edge) and oriented along ê_2 = (0, 1) is (−1, 1)/√2; the outgoing
        // edge that makes it the bisector is (−1, 0).
        let open = Polyline::open(vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0)]);
        let m = SweptDirectrix::with_end_planes(&open, EndPlanes::Mirror).unwrap();
        let expected = DVec3::new(-1.0, 1.0, 0.0).normalize();
        assert!((m.bisector(2).unwrap() - expected).length() < 1e-15);
        assert!((m.outgoing[2] - DVec3::new(-1.0, 0.0, 0.0)).length() < 1e-15);
        let reversing = Polyline::open(vec![DVec3::ZERO, DVec3::X, DVec3::ZERO]);
        let d = SweptDirectrix::new(&reversing).unwrap();
        assert_eq!(
            d.bisector(1),
            Err(GeometryError::DirectrixReverses { column: 1 })
        );
    }
}
