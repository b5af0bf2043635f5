//! The cnets dataflow engine.
//!
//! - [`value`]: the typed value model ([`Value`], [`ValueType`]) and its JSON encoding.
//! - [`kinds`], [`node`], [`node!`]: declaring node types; [`Registry`]: looking them up.
//! - [`graph`]: the graph document (petgraph), edited through validated operations.
//! - [`file`]: versioned RON graph files with located diagnostics and atomic saves.
//! - [`eval`]: incremental, pull-based evaluation with early cutoff.

pub mod atomic;
pub mod broadcast;
pub mod budget;
pub mod cluster;
pub mod convert;
pub mod error;
pub mod eval;
pub mod file;
pub mod files;
pub mod graph;
pub mod kinds;
pub mod node;
mod node_macro;
pub mod numbers;
pub mod optimize;
pub mod registry;
pub mod value;

pub use budget::MemoryBudget;
pub use error::NodeError;
pub use eval::{Blocked, EvalSummary, Evaluator, InvalidInput, NodeOutputs, NodeResult};
pub use graph::{Continued, Graph, GraphError, NodeInstance, Revision, WireRef};
pub use kinds::{ChoiceEnum, IntoPort, PortKind};
pub use node::{
    Choices, Layer, MAX_CLUSTER_DEPTH, NodeContext, NodeDef, NodeFlag, PortDef, PortHint, Role,
    Widget,
};
pub use registry::Registry;
pub use value::{Access, Items, Record, Value, ValueType};

/// What node modules usually import.
pub mod prelude {
    pub use crate::kinds as k;
    pub use crate::node;
    pub use crate::{ChoiceEnum, Items, NodeContext, NodeDef, NodeError, Record, Value};
    pub use cnets_geometry::{DVec3, Line, Plane, PolygonMesh, Polyline, QuadGrid};
}
