//! `cnets check <GRAPH.ron>`.

use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;

use cnets_engine::file::load_file;

use crate::failure::CommandResult;

/// Arguments of `cnets check`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The graph file.
    graph: PathBuf,
}

/// Runs the command.
pub fn run(args: Args) -> CommandResult {
    let registry = Arc::new(cnets_nodes::registry());
    let doc = load_file(&args.graph, &registry)?;
    for w in &doc.warnings {
        eprintln!("warning: {w}");
    }
    println!(
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
