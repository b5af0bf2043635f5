//! `cnets check <GRAPH.ron>`.

use std::path::PathBuf;
use std::process::ExitCode;

use crate::failure::CommandResult;
use crate::library;

/// Arguments of `cnets check`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The graph file.
    graph: PathBuf,
    /// A folder nodes and cluster files may also read from (besides the graph file's folder);
    /// repeat for several.
    #[arg(long = "allow-read", value_name = "DIR")]
    allow_read: Vec<PathBuf>,
    /// Extra folders searched for cluster graph files (besides the graph's own folder and
    /// `CNETS_LIBRARY`).
    #[arg(long)]
    library: Vec<PathBuf>,
}

/// Runs the command.
pub fn run(args: Args) -> CommandResult {
    let doc = library::load_graph_allowing(&args.graph, &args.library, &[], &args.allow_read)?;
    for w in &doc.warnings {
        crate::errln!("warning: {w}");
    }
    crate::outln!(
        "ok: {}: {} nodes, {} edges{}",
        args.graph.display(),
        doc.graph.node_count(),
        doc.graph.wire_count(),
        if doc.warnings.is_empty() {
            String::new()
        } else {
            format!(", {} warnings", doc.warnings.len())
        }
    );
    Ok(ExitCode::SUCCESS)
}
