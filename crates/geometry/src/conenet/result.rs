//! The result of a construction: everything a construction node outputs.

use std::ops::Range;

use glam::DVec3;
use rayon::prelude::*;

use super::configuration::Configurations;
use super::correction::Correction;
use super::quality::Quality;
use crate::QuadGrid;

/// Construction-plane normals P_{i,j} for i = 0 … N−1, j = 1 … M−1: either one normal per column
/// shared by all rows (Monge planes, shared user normals, the coplanar construction) or one per
/// vertex. Normals are unit vectors oriented so that `P_{i,j} · ê_j > 0`.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PlaneNormals {
    rows: usize,
    /// M − 1.
    cols: usize,
    shared: bool,
    data: Vec<DVec3>,
}

impl PlaneNormals {
    /// Normals shared by all `rows` rows: `data[j − 1]` is the normal of column j.
    pub fn shared(rows: usize, data: Vec<DVec3>) -> Self {
        Self {
            rows,
            cols: data.len(),
            shared: true,
            data,
        }
    }

    /// Per-vertex normals, row-major: `data[i * cols + j − 1]`.
    pub fn per_vertex(rows: usize, cols: usize, data: Vec<DVec3>) -> Self {
        debug_assert_eq!(data.len(), rows * cols);
        Self {
            rows,
            cols,
            shared: false,
            data,
        }
    }

    /// Number of rows N.
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Number of plane columns, M − 1.
    pub fn cols(&self) -> usize {
        self.cols
    }

    /// Whether one normal per column is shared by all rows.
    pub fn is_shared(&self) -> bool {
        self.shared
    }

    /// The normal P_{i,j} (j = 1 … M−1).
    #[inline]
    pub fn get(&self, i: usize, j: usize) -> DVec3 {
        assert!(
            i < self.rows && j >= 1 && j <= self.cols,
            "plane ({i}, {j}) out of range"
        );
        if self.shared {
            self.data[j - 1]
        } else {
            self.data[i * self.cols + j - 1]
        }
    }

    /// The normals P_{i,1} … P_{i,M−1} of row i.
    pub fn row(&self, i: usize) -> &[DVec3] {
        &self.data[self.row_range(i)]
    }

    /// Where row i's normals are in the table [`PlaneNormals::into_data`] returns (all rows
    /// share one range when the normals are shared).
    pub fn row_range(&self, i: usize) -> Range<usize> {
        assert!(i < self.rows, "plane row {i} out of range");
        if self.shared {
            0..self.cols
        } else {
            i * self.cols..(i + 1) * self.cols
        }
    }

    /// The table of normals, moved out; [`PlaneNormals::row_range`] locates each row in it.
    pub fn into_data(self) -> Vec<DVec3> {
        self.data
    }

    /// N lists of M−1 normals, as the nodes output them.
    pub fn to_rows(&self) -> Vec<Vec<DVec3>> {
        (0..self.rows).map(|i| self.row(i).to_vec()).collect()
    }
}

/// Which reports a construction computes besides the mesh, the apex values, the plane normals
/// and the configurations (lazy outputs: a node whose `apices` or `quality` nobody reads skips
/// them). A report not computed is left empty (no apices, [`Quality::default`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Reports {
    /// The cone apices C_j.
    pub apices: bool,
    /// The quality measures (planarity, cone residuals, configuration counts).
    pub quality: bool,
}

impl Reports {
    /// Every report.
    pub const ALL: Reports = Reports {
        apices: true,
        quality: true,
    };
}

/// A constructed cone-net and everything the construction nodes report about it.
#[derive(Debug, Clone, PartialEq)]
pub struct ConeNet {
    /// The mesh: N rows (generatrix points) × M columns (swept directrix points); `wrap_rows` for a
    /// closed generatrix.
    pub mesh: QuadGrid,
    /// The swept directrix X_0 … X_{M−1} (a closed directrix repeats its first point).
    pub directrix: Vec<DVec3>,
    /// The apex values a_j actually used (j = 1 … M−1 at index j − 1), after normalization and
    /// correction.
    pub apex: Vec<f64>,
    /// The cone apices C_0 … C_{M−2} (`apices[j − 1] = C_{j−1}`); `None` at infinity (a_j = 1).
    pub apices: Vec<Option<DVec3>>,
    /// The construction-plane normals actually used.
    pub normals: PlaneNormals,
    /// Configurations c_{i,j}, j = 1 … M−2.
    pub configurations: Configurations,
    /// Every correction made by the assisted construction, by column.
    pub corrections: Vec<Correction>,
    /// Quality measures of the mesh.
    pub quality: Quality,
}

impl ConeNet {
    /// The corrections as text, one line each (the nodes' `corrections` output); formatted in
    /// parallel (a folding design makes tens of thousands of plane fixes).
    pub fn correction_lines(&self) -> Vec<String> {
        self.corrections
            .par_iter()
            .map(ToString::to_string)
            .collect()
    }
}
