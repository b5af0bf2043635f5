//! The pure math kernel of cnets.
//!
//! Plain `f64` value types over [`glam::DVec3`]: polylines, planes, line segments, quad-grid meshes and
//! general polygon meshes, plus the cone-net construction kernel ([`conenet`]). Nothing here knows
//! about the node engine, the editor or the GPU: the crate is usable as a library on its own.

pub mod conenet;
pub mod curves;
pub mod error;
pub mod fabrication;
pub mod face_class;
pub mod line;
pub mod measure;
pub mod mesh_parts;
pub mod mesh_query;
pub mod mesh_weld;
pub mod objectives;
pub mod plane;
pub mod polygon_mesh;
pub mod polyline;
pub mod quad_grid;
pub mod seam;
pub mod serial;
pub mod simd;
pub mod surface_fit;

pub use conenet::{
    ConeNet, ConstructInputs, CoplanarInputs, CtubeInputs, construct, construct_coplanar,
    construct_ctube, encode,
};
pub use error::GeometryError;
pub use face_class::FaceClass;
pub use glam::DVec3;
pub use line::Line;
pub use mesh_parts::MeshParts;
pub use plane::Plane;
pub use polygon_mesh::PolygonMesh;
pub use polyline::Polyline;
pub use quad_grid::QuadGrid;
