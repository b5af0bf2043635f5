//! What every front end of the cnets engine shares — the `cnets` command line, the Python package
//! (`python/`), the Hops server behind it: node types named by id or by graph file
//! (`cluster:<path>`), inputs completed with the ports' defaults, graph files loaded with library
//! folders, read permissions and `node.input=value` overrides. Front ends only decide where values
//! come from (JSON, Python objects) and where results go.

pub mod error;
pub mod inputs;
pub mod library;
pub mod node_type;

pub use error::HostError;
pub use inputs::{apply_set, complete_inputs, decode_input, node_inputs, split_target};
pub use library::{PREFIX, cluster_def, folder_defs, load_graph, options, writes_files};
pub use node_type::{NodeType, resolve};
