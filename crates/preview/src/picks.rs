//! What the preview drew, by where it came from: every previewed mesh with the node and output
//! that made it, its face classes and planarity, and every previewed curve — so the editor's 3D
//! view can name what the pointer is over (node, row and column, class, planarity), snap to
//! vertices, and find the folded faces. The geometry is shared with the evaluation's results, not
//! copied.

use std::sync::Arc;

use cnets_geometry::fabrication::FaceClass;
use cnets_geometry::{DVec3, PolygonMesh, Polyline, QuadGrid};

/// A previewed mesh's geometry.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub enum PickGeometry {
    /// A regular quad grid: faces and vertices have a row and a column.
    Grid(#[serde(deserialize_with = "cnets_geometry::serial::checked")] Arc<QuadGrid>),
    /// A general polygon mesh: faces and vertices have an index.
    Mesh(#[serde(deserialize_with = "cnets_geometry::serial::checked")] Arc<PolygonMesh>),
}

impl PickGeometry {
    /// The vertices.
    pub fn vertices(&self) -> &[DVec3] {
        match self {
            PickGeometry::Grid(g) => &g.vertices,
            PickGeometry::Mesh(m) => &m.vertices,
        }
    }

    /// Number of faces.
    pub fn face_count(&self) -> usize {
        match self {
            PickGeometry::Grid(g) => g.quad_count(),
            PickGeometry::Mesh(m) => m.face_count(),
        }
    }

    /// The corners of face `f` (quads in [`QuadGrid::quads`] order; polygons in face order).
    pub fn face_corners(&self, f: usize) -> Vec<DVec3> {
        if f >= self.face_count() {
            return Vec::new();
        }
        match self {
            PickGeometry::Grid(g) => {
                let qc = g.quad_cols();
                g.quad(f / qc, f % qc).to_vec()
            }
            PickGeometry::Mesh(m) => m
                .face(f)
                .iter()
                .filter_map(|&k| m.vertices.get(k as usize).copied())
                .collect(),
        }
    }

    /// The row and column of face `f` of a grid (`None` for a polygon mesh).
    pub fn face_row_col(&self, f: usize) -> Option<(usize, usize)> {
        match self {
            PickGeometry::Grid(g) if f < g.quad_count() => {
                let qc = g.quad_cols();
                Some((f / qc, f % qc))
            }
            _ => None,
        }
    }

    /// The row and column of vertex `v` of a grid (`None` for a polygon mesh).
    pub fn vertex_row_col(&self, v: usize) -> Option<(usize, usize)> {
        match self {
            PickGeometry::Grid(g) if g.cols > 0 && v < g.vertices.len() => {
                Some((v / g.cols, v % g.cols))
            }
            _ => None,
        }
    }
}

/// A previewed mesh and where it came from.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct PickMesh {
    /// The node that made it.
    pub node: String,
    /// Its output.
    pub output: String,
    /// The item of a list output (`None` for a single value).
    pub item: Option<usize>,
    /// The geometry (shared with the evaluation's result).
    pub geometry: PickGeometry,
    /// The class of each face (when the node gives configurations).
    pub classes: Option<Vec<FaceClass>>,
    /// The relative planarity of each quad (quad grids; empty for polygon meshes).
    pub planarity: Vec<f64>,
}

/// A previewed curve and where it came from.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct PickCurve {
    /// The node that made it.
    pub node: String,
    /// Its output.
    pub output: String,
    /// The curve (shared with the evaluation's result).
    pub polyline: Arc<Polyline>,
}

/// Everything the preview drew that the pointer can point at.
#[derive(Clone, Debug, Default, serde::Serialize, serde::Deserialize)]
pub struct Picks {
    /// Previewed meshes (the surfaces layer and support layers, as drawn).
    pub meshes: Vec<PickMesh>,
    /// Previewed curves (as drawn).
    pub curves: Vec<PickCurve>,
}

impl Picks {
    /// The faces that are not (++)(++) (folds and other configurations): (mesh, face) pairs.
    pub fn folded_faces(&self) -> Vec<(usize, usize)> {
        self.meshes
            .iter()
            .enumerate()
            .flat_map(|(m, mesh)| {
                mesh.classes
                    .iter()
                    .flat_map(|c| c.iter().enumerate())
                    .filter(|(_, c)| !matches!(c, FaceClass::Convex))
                    .map(move |(f, _)| (m, f))
            })
            .collect()
    }

    /// Every vertex drawn (mesh vertices and curve points), for snapping.
    pub fn vertices(&self) -> impl Iterator<Item = DVec3> + '_ {
        self.meshes
            .iter()
            .flat_map(|m| m.geometry.vertices().iter().copied())
            .chain(
                self.curves
                    .iter()
                    .flat_map(|c| c.polyline.points.iter().copied()),
            )
    }
}
