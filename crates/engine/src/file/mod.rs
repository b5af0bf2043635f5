//! Graph files: versioned, hand-editable RON.
//!
//! ```ron
//! (
//!     version: 1,
//!     name: "torus",
//!     nodes: {
//!         "arc": (
//!             type: "curve.arc",
//!             position: (40.0, 80.0),
//!             inputs: {
//!                 "radius": 5.0,
//!             },
//!         ),
//!     },
//!     edges: [
//!         "arc.curve -> sweep.directrix",
//!     ],
//! )
//! ```
//!
//! Nodes are keyed by id and keep file order; `preview` and `enabled` are written only when false,
//! a node's preview `color: "#rrggbb"` only when one was picked (files without it load unchanged).
//! The editor's named construction planes are an optional `cplanes: [..]` list (`cplanes`).
//! Loading reports every problem with file, line and column; saving is atomic.

//!
//! One concept per module: [`Diagnostic`]s and [`LoadError`] (`diagnostics`), reading and
//! validating a file into a [`Document`] (`load`), the cluster nodes' subgraphs from files or
//! inline graphs (`clusters`), canonical text and atomic saves (`save`).

mod clusters;
pub mod cplanes;
mod diagnostics;
pub mod literal;
mod load;
pub mod ron;
mod save;

pub use clusters::load_cluster_source;
pub use cplanes::NamedPlane;
pub use diagnostics::{Diagnostic, LoadError};
pub use load::{
    Document, GraphMeta, LoadOptions, format_color, load_file, load_file_with, load_str,
    load_str_with, parse_color, parse_edge,
};
pub use save::{save_file, to_ron};

/// The graph file format version this build writes and reads.
pub const FORMAT_VERSION: i64 = 1;
