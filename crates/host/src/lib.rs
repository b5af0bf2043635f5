//! What every front end of the cnets engine shares — the `cnets` command line, the Python package
//! (`python/`), the Hops server behind it: node types named by id or by graph file
//! (`cluster:<path>`), inputs completed with the ports' defaults, graph files loaded with library
//! folders, read permissions and `node.input=value` overrides — and the editor (`crates/editor`):
//! its library's graphs and the clusters it inserts from them. A [`Session`] holds what an
//! evaluation may use (budget, reads, library, output folder, cancellation) and makes its node
//! contexts. Front ends only decide where values come from (JSON, Python objects) and where
//! results go.

pub mod error;
pub mod inputs;
pub mod library;
pub mod node_type;
pub mod session;

pub use error::HostError;
pub use inputs::{apply_set, complete_inputs, decode_input, node_inputs, split_target};
pub use library::{
    LibraryEntry, PREFIX, cluster_def, document_options, folder_defs, graph_files, library_entry,
    library_folders, load_graph, options, source_def, writes_files,
};
pub use node_type::{NodeType, resolve};
pub use session::{LIBRARY_VAR, NodeRun, Session, SessionError, check_outputs, library_from_env};
