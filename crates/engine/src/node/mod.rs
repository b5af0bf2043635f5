//! Node type definitions: ports, documentation, the function that runs, and the context it runs in
//! — the contract every node author reads.
//!
//! A leaf of the engine's modules: it imports values, errors, the memory budget and files, and
//! nothing of the evaluator, the graph or the optimizer (which import it).
//!
//! - [`def`]: [`NodeDef`], [`PortDef`], [`NodeFlag`], [`RunFn`].
//! - [`context`]: [`NodeContext`], what a running node may see and report.
//! - [`derivative`]: the vector–Jacobian product and branch function a node may carry.
//! - [`hint`]: [`PortHint`], [`Widget`], [`Choices`]: how a port is shown and edited.
//! - [`layer`]: [`Layer`], the preview's layers (an output declares one).
//! - [`mask`]: [`OutputMask`], which outputs a node is asked for.
//! - [`stamp`]: [`FileStamp`], what a node saw of a file it read.

pub mod context;
pub mod def;
pub mod derivative;
pub mod hint;
pub mod layer;
pub mod mask;
pub mod stamp;

pub use crate::error::NodeError;
pub use context::{MAX_CLUSTER_DEPTH, NodeContext};
pub use def::{NodeDef, NodeFlag, PortDef, RunFn, doc_text, port_name};
pub use derivative::{Branch, BranchFn, Cotangents, VjpArgs, VjpFn, VjpResult};
pub use hint::{Choices, HintBuilder, PortHint, Role, Widget};
pub use layer::Layer;
pub use mask::OutputMask;
pub use stamp::FileStamp;
