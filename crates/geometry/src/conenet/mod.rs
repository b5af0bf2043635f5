//! The cone-net geometry kernel: C-tube construction, CNets Construct (ratios), CNets Construct
//! Coplanar, the normalized apex function, configuration classification, assisted correction, the
//! encoder of any cone-net, quality measures and apex points.
//!
//! Conventions (construction notes §1): directrix X_0 … X_{M−1}, generatrix G_{0,0} … G_{N−1,0}; the
//! mesh G[i][j] is row-major (`i * M + j`), i along the generatrix (N rows), j along the directrix
//! (M columns). Apex values a_j and planes Π_{i,j} are indexed j = 1 … M−1 (stored at `j − 1`).
//!
//! Entry points: [`construct_ctube`], [`construct`], [`construct_coplanar`] (all returning a
//! [`ConeNet`]), [`encode`], [`planarity`], [`cone_check`], [`apex_points`].

// The kernel writes its tolerance tests as `!(x > tol)` on purpose: the test then also fails for NaN,
// which `x <= tol` would let through.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod adjoint;
pub mod apex;
mod blend;
pub mod configuration;
pub mod construct;
pub mod coplanar;
pub mod correction;
mod correction_adjoint;
pub mod ctube;
pub mod directrix;
mod directrix_adjoint;
mod dual;
mod eigen;
pub mod encode;
pub mod inputs;
mod lanes;
pub mod margins;
pub mod normalize;
mod ordered;
mod output_adjoint;
mod prepare;
pub mod quality;
pub mod ratios;
pub mod result;
pub mod seam_apex;
pub mod subdivide;
mod sweep;
mod trig;

pub use apex::apex_points;
pub use configuration::{Configuration, ConfigurationCounts, Configurations};
pub use construct::{construct, construct_coplanar, construct_coplanar_with, construct_with};
pub use correction::{Correction, CorrectionKind};
pub use ctube::{construct_ctube, construct_ctube_with, ctube_mesh};
pub use directrix::SweptDirectrix;
pub use encode::{Encoding, encode};
pub use inputs::{
    ApexInput, Assistance, ColumnValues, ConstructInputs, CoplanarInputs, CtubeInputs, EndPlanes,
    GridValues, NormalsInput,
};
pub use quality::{ConeCheck, Planarity, Quality, cone_check, planarity, quad_planarity};
pub use result::{ConeNet, PlaneNormals, Reports};
pub use subdivide::subdivide_rows;

/// Tolerances of the kernel (all relative, see `docs/geometry.md`).
pub mod tolerance {
    /// A step is degenerate when `|V·P| ≤ PARALLEL · |V| |P|`.
    pub const PARALLEL: f64 = 1e-12;
    /// A plane contains its incoming edge when `|P·ê_j| ≤ EDGE_PLANE` (P unit).
    pub const EDGE_PLANE: f64 = 1e-12;
    /// A support plane is undefined when the part of `D = G_{i,j−1} − X_{j−1}` perpendicular to ê_j is
    /// at most `FRAME · |D|`.
    pub const FRAME: f64 = 1e-12;
    /// The bisecting plane is undefined when `|ê_j + ê_{j+1}| ≤ REVERSAL`.
    pub const REVERSAL: f64 = 1e-12;
    /// Coplanar mode: the outgoing edge counts as lying in the support plane of strip 0 when
    /// `|n_in · ê_{j+1}| ≤ COPLANAR_TIE`; then ψ_out = π.
    pub const COPLANAR_TIE: f64 = 1e-12;
    /// The apex C_{j−1} is at infinity (reported as `None`) when `|1 − a_j| ≤ APEX_AT_INFINITY`.
    pub const APEX_AT_INFINITY: f64 = 1e-12;
    /// The encoder rejects meshes whose relative cone residual exceeds this.
    pub const CONE_NET: f64 = 1e-6;
    /// Maximum number of fix rounds at one column before the correction gives up.
    pub const MAX_CORRECTION_ROUNDS: usize = 8;
}
