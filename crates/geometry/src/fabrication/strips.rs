//! PQ strips of a quad grid (PQ Mesh Extract Strips, paper Sec. 4.4.2, notes §7).
//!
//! The directrix-aligned strip i is the row of quads between mesh rows i and i+1; the
//! generatrix-aligned strip j is the column of quads between mesh columns j and j+1 (wrapping where
//! the mesh wraps). A strip is a chain of *rungs*: the mesh edges it shares between consecutive quads
//! (for strip i of the directrix direction, rung k joins G_{i,k} and G_{i+1,k}).

use std::fmt;
use std::str::FromStr;

use glam::DVec3;

use super::FabricationError;
use crate::QuadGrid;

/// Which family of strips.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum StripDirection {
    /// Strips along the directrix: strip i = quads between rows i and i+1.
    Directrix,
    /// Strips along the generatrix: strip j = quads between columns j and j+1.
    Generatrix,
}

impl StripDirection {
    /// The name used by the nodes: `"directrix"` or `"generatrix"`.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Directrix => "directrix",
            Self::Generatrix => "generatrix",
        }
    }

    /// The label prefix of its strips: `D` or `G`.
    pub fn prefix(self) -> char {
        match self {
            Self::Directrix => 'D',
            Self::Generatrix => 'G',
        }
    }
}

impl fmt::Display for StripDirection {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl FromStr for StripDirection {
    type Err = FabricationError;

    /// Parses `directrix` or `generatrix` (case and surrounding spaces ignored).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "directrix" => Ok(Self::Directrix),
            "generatrix" => Ok(Self::Generatrix),
            _ => Err(FabricationError::UnknownOption {
                what: "direction",
                value: s.to_string(),
                expected: "\"directrix\" or \"generatrix\"",
            }),
        }
    }
}

/// One strip as a chain of rungs.
#[derive(Debug, Clone, PartialEq)]
pub struct Strip {
    /// Strip index (i for directrix strips, j for generatrix strips).
    pub index: usize,
    /// The family.
    pub direction: StripDirection,
    /// Rung vertex indices into the mesh: `(a, b)` with a on mesh row i (column j), b on row i+1
    /// (column j+1). A closed strip does not repeat its first rung.
    pub rungs: Vec<(usize, usize)>,
    /// Whether the last rung connects back to the first (a wrapped strip).
    pub closed: bool,
}

impl Strip {
    /// Number of quads: rungs − 1, or rungs for a closed strip.
    pub fn quad_count(&self) -> usize {
        if self.closed {
            self.rungs.len()
        } else {
            self.rungs.len().saturating_sub(1)
        }
    }

    /// The mesh quad (row, column) of quad k of the strip.
    pub fn mesh_quad(&self, k: usize) -> (usize, usize) {
        match self.direction {
            StripDirection::Directrix => (self.index, k),
            StripDirection::Generatrix => (k, self.index),
        }
    }

    /// Rungs k and k+1 (wrapping) of quad k.
    pub fn quad_rungs(&self, k: usize) -> ((usize, usize), (usize, usize)) {
        (self.rungs[k], self.rungs[(k + 1) % self.rungs.len()])
    }

    /// Corner indices of quad k in the mesh's own order `(i,j), (i,j+1), (i+1,j+1), (i+1,j)`.
    pub fn quad_indices(&self, k: usize) -> [usize; 4] {
        let (r0, r1) = self.quad_rungs(k);
        match self.direction {
            StripDirection::Directrix => [r0.0, r1.0, r1.1, r0.1],
            StripDirection::Generatrix => [r0.0, r0.1, r1.1, r1.0],
        }
    }

    /// The label `D<i>` or `G<j>`.
    pub fn label(&self) -> String {
        format!("{}{}", self.direction.prefix(), self.index)
    }
}

/// The strips of `mesh` in the given direction (at least 2 × 2 vertices, all finite).
pub fn strips(mesh: &QuadGrid, direction: StripDirection) -> Result<Vec<Strip>, FabricationError> {
    super::axes::check_grid(mesh, 2, 2)?;
    let cols = mesh.cols;
    Ok(match direction {
        StripDirection::Directrix => (0..mesh.quad_rows())
            .map(|i| {
                let i1 = (i + 1) % mesh.rows;
                Strip {
                    index: i,
                    direction,
                    rungs: (0..cols).map(|k| (i * cols + k, i1 * cols + k)).collect(),
                    closed: mesh.quad_cols() == cols,
                }
            })
            .collect(),
        StripDirection::Generatrix => (0..mesh.quad_cols())
            .map(|j| {
                let j1 = (j + 1) % cols;
                Strip {
                    index: j,
                    direction,
                    rungs: (0..mesh.rows)
                        .map(|k| (k * cols + j, k * cols + j1))
                        .collect(),
                    closed: mesh.quad_rows() == mesh.rows,
                }
            })
            .collect(),
    })
}

/// The strips as meshes in the mesh's own orientation: a directrix strip i is a 2 × M grid (rows i
/// and i+1, wrapping columns when the mesh does), a generatrix strip j an N × 2 grid (columns j and
/// j+1, wrapping rows when the mesh does).
pub fn extract_strips(
    mesh: &QuadGrid,
    direction: StripDirection,
) -> Result<Vec<QuadGrid>, FabricationError> {
    let list = strips(mesh, direction)?;
    Ok(list
        .iter()
        .map(|s| {
            let a = s.rungs.iter().map(|r| mesh.vertices[r.0]);
            let b = s.rungs.iter().map(|r| mesh.vertices[r.1]);
            match direction {
                StripDirection::Directrix => QuadGrid {
                    rows: 2,
                    cols: s.rungs.len(),
                    wrap_rows: false,
                    wrap_cols: s.closed,
                    vertices: a.chain(b).collect(),
                    classes: Vec::new(),
                },
                StripDirection::Generatrix => QuadGrid {
                    rows: s.rungs.len(),
                    cols: 2,
                    wrap_rows: s.closed,
                    wrap_cols: false,
                    vertices: a.zip(b).flat_map(|(p, q)| [p, q]).collect::<Vec<DVec3>>(),
                    classes: Vec::new(),
                },
            }
        })
        .collect())
}
