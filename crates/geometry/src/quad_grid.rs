//! Regular quad-grid meshes stored row-major.

use glam::DVec3;

use crate::{FaceClass, GeometryError, Polyline};

/// A regular `rows × cols` quad mesh. Vertex (i, j) is `vertices[i * cols + j]`; rows run along the
/// generatrix (index i), columns along the directrix (index j).
///
/// `wrap_rows` means the last row connects back to the first (a closed generatrix: quads between rows
/// `rows − 1` and `0` exist); `wrap_cols` likewise for columns.
#[derive(Debug, Clone, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct QuadGrid {
    /// Number of rows (points along the generatrix).
    pub rows: usize,
    /// Number of columns (points along the directrix).
    pub cols: usize,
    /// Quads between the last and the first row exist.
    pub wrap_rows: bool,
    /// Quads between the last and the first column exist.
    pub wrap_cols: bool,
    /// Row-major vertices, `rows * cols` of them.
    pub vertices: Vec<DVec3>,
    /// The configuration class of every quad in quad order (row after row), as the construction
    /// that made the net found them; empty when not known (a grid made otherwise, or moved off its
    /// cones). Carried into the polygon meshes made from the grid.
    pub classes: Vec<FaceClass>,
}

impl QuadGrid {
    /// A grid from row-major vertices; fails when the vertex count is not `rows * cols`.
    pub fn new(rows: usize, cols: usize, vertices: Vec<DVec3>) -> Result<Self, GeometryError> {
        let expected = rows.saturating_mul(cols);
        if vertices.len() != expected {
            return Err(GeometryError::GridSize {
                rows,
                cols,
                expected,
                got: vertices.len(),
            });
        }
        Ok(Self {
            rows,
            cols,
            wrap_rows: false,
            wrap_cols: false,
            vertices,
            classes: Vec::new(),
        })
    }

    /// The faces' classes when they are known and fit the grid (one per quad).
    pub fn face_classes(&self) -> Option<&[FaceClass]> {
        (!self.classes.is_empty() && self.classes.len() == self.quad_count())
            .then_some(self.classes.as_slice())
    }

    /// Sets the wrap flags (builder style).
    pub fn with_wrap(mut self, wrap_rows: bool, wrap_cols: bool) -> Self {
        self.wrap_rows = wrap_rows;
        self.wrap_cols = wrap_cols;
        self
    }

    /// Checks the invariants: vertex count and wrap flags that need at least 3 rows/cols.
    pub fn validate(&self) -> Result<(), GeometryError> {
        let expected = self.rows.saturating_mul(self.cols);
        if self.vertices.len() != expected {
            return Err(GeometryError::GridSize {
                rows: self.rows,
                cols: self.cols,
                expected,
                got: self.vertices.len(),
            });
        }
        Ok(())
    }

    /// Vertex (i, j).
    #[inline]
    pub fn at(&self, i: usize, j: usize) -> DVec3 {
        self.vertices[i * self.cols + j]
    }

    /// Mutable vertex (i, j).
    #[inline]
    pub fn at_mut(&mut self, i: usize, j: usize) -> &mut DVec3 {
        &mut self.vertices[i * self.cols + j]
    }

    /// Number of quad rows (strips between consecutive rows, including the wrapping one).
    pub fn quad_rows(&self) -> usize {
        span_count(self.rows, self.wrap_rows)
    }

    /// Number of quad columns.
    pub fn quad_cols(&self) -> usize {
        span_count(self.cols, self.wrap_cols)
    }

    /// Total number of quads.
    pub fn quad_count(&self) -> usize {
        self.quad_rows() * self.quad_cols()
    }

    /// Vertex indices of quad (i, j) in the order `(i, j), (i, j+1), (i+1, j+1), (i+1, j)`, wrapping.
    #[inline]
    pub fn quad_indices(&self, i: usize, j: usize) -> [usize; 4] {
        let i1 = (i + 1) % self.rows;
        let j1 = (j + 1) % self.cols;
        [
            i * self.cols + j,
            i * self.cols + j1,
            i1 * self.cols + j1,
            i1 * self.cols + j,
        ]
    }

    /// Corner positions of quad (i, j), in the order of [`QuadGrid::quad_indices`].
    #[inline]
    pub fn quad(&self, i: usize, j: usize) -> [DVec3; 4] {
        self.quad_indices(i, j).map(|k| self.vertices[k])
    }

    /// Iterator over all quads as `((i, j), corners)`, row by row.
    pub fn quads(&self) -> impl Iterator<Item = ((usize, usize), [DVec3; 4])> + '_ {
        let qc = self.quad_cols();
        (0..self.quad_rows()).flat_map(move |i| (0..qc).map(move |j| ((i, j), self.quad(i, j))))
    }

    /// Row `i` as a polyline (directrix-aligned), closed when columns wrap.
    pub fn row(&self, i: usize) -> Polyline {
        let start = i * self.cols;
        Polyline {
            points: self.vertices[start..start + self.cols].to_vec(),
            closed: self.wrap_cols,
        }
    }

    /// Column `j` as a polyline (generatrix-aligned), closed when rows wrap.
    pub fn column(&self, j: usize) -> Polyline {
        Polyline {
            points: (0..self.rows).map(|i| self.at(i, j)).collect(),
            closed: self.wrap_rows,
        }
    }

    /// Axis-aligned bounding box; `None` when empty.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        bounds_of(&self.vertices)
    }

    /// Length of the bounding-box diagonal (0 for an empty grid): the scale for relative tolerances.
    pub fn size(&self) -> f64 {
        self.bounds().map_or(0.0, |(lo, hi)| lo.distance(hi))
    }
}

/// Number of spans between `n` consecutive items, counting the wrapping span when `wrap` and n > 2.
fn span_count(n: usize, wrap: bool) -> usize {
    match n {
        0 | 1 => 0,
        2 => 1,
        n if wrap => n,
        n => n - 1,
    }
}

/// Axis-aligned bounding box of a point set; `None` when empty.
pub fn bounds_of(points: &[DVec3]) -> Option<(DVec3, DVec3)> {
    let first = *points.first()?;
    Some(
        points
            .iter()
            .fold((first, first), |(lo, hi), p| (lo.min(*p), hi.max(*p))),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(rows: usize, cols: usize) -> QuadGrid {
        let v = (0..rows)
            .flat_map(|i| (0..cols).map(move |j| DVec3::new(j as f64, i as f64, 0.0)))
            .collect();
        QuadGrid::new(rows, cols, v).unwrap()
    }

    #[test]
    fn counts_and_indices_with_and_without_wrap() {
        let g = grid(3, 4);
        assert_eq!(g.quad_count(), 2 * 3);
        assert_eq!(g.quad_indices(1, 2), [6, 7, 11, 10]);
        let w = g.clone().with_wrap(true, false);
        assert_eq!(w.quad_count(), 3 * 3);
        assert_eq!(w.quad_indices(2, 0), [8, 9, 1, 0]);
        assert_eq!(g.at(2, 3), DVec3::new(3.0, 2.0, 0.0));
        assert_eq!(g.row(1).points.len(), 4);
        assert_eq!(
            g.column(1).points,
            vec![
                DVec3::X,
                DVec3::new(1.0, 1.0, 0.0),
                DVec3::new(1.0, 2.0, 0.0)
            ]
        );
    }

    #[test]
    fn new_rejects_wrong_vertex_count() {
        assert!(matches!(
            QuadGrid::new(2, 2, vec![DVec3::ZERO; 3]),
            Err(GeometryError::GridSize {
                expected: 4,
                got: 3,
                ..
            })
        ));
        assert_eq!(QuadGrid::new(0, 5, vec![]).unwrap().quad_count(), 0);
    }
}
