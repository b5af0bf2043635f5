//! Supplementary and fabrication tools (paper Sec. 4.4.2, construction notes §7): apex from widths,
//! torsion-free node axes, conical and parallel support layers, support strips and beams, the parallel (Combescure) transform,
//! strips and unrolling, the panel schedule, and polygon-mesh tools (cut by a plane, mirror, join, weld, per-face
//! attributes, triangulation). Every formula is documented in its module and in
//! `docs/fabrication.md`; errors are typed ([`FabricationError`]) and name the offending indices.

// `!(x > tol)` is used on purpose: it is also true for NaN, so non-finite values fail the checks.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod apex_graph;
pub mod axes;
pub mod boundary;
pub mod carry;
pub mod collapsed;
pub mod conical;
pub mod cut;
pub mod error;
pub mod face_attributes;
pub mod folds;
pub mod join;
pub mod layout;
pub mod lines;
pub mod marks;
pub mod mesh_strips;
pub mod mirror;
pub mod nest;
pub mod panels;
pub mod parallel_support;
pub mod parallel_transform;
pub mod polygon;
pub mod schedule;
pub mod split;
pub mod strips;
pub mod support_strips;
pub mod unroll;

pub use apex_graph::{graph_to_apex, graph_to_normalized_apex};
pub use axes::{directrix_for, torsion_free_axes};
pub use carry::{carry, owner_of, rigid_motion};
pub use collapsed::{COLLAPSED_EDGE, CollapsedEdge};
pub use conical::conical_support;
pub use cut::{Cut, cut_by_plane};
pub use error::FabricationError;
pub use face_attributes::{
    FaceClass, face_classes, face_planarity, planarity_colour, polygon_planarity,
};
pub use folds::{Fold, folds};
pub use join::{join, weld};
pub use marks::{Mark, neighbour_marks, station_marks};
pub use mesh_strips::{
    MeshStrip, UnrolledMesh, UnrolledMeshStrip, grid_of, mesh_strips, unroll_mesh_strips,
};
pub use mirror::mirror;
pub use nest::{Nested, nest, nest_until, stack_sheets};
pub use panels::{Panel, PanelSource, StripPanels, grid_panels, mesh_panels};
pub use parallel_support::parallel_support;
pub use parallel_transform::{ParallelTransform, parallel_transform};
pub use polygon::triangulate;
pub use schedule::{ScheduleRow, polygon_area, schedule};
pub use split::{Pieces, split_strips};
pub use strips::{Strip, StripDirection, extract_strips, strips};
pub use support_strips::{beam_strips, directrix_support_strips};
pub use unroll::{UnrollOptions, Unrolled, UnrolledStrip, unroll_strips};
