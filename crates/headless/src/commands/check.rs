//! `cnets check <GRAPH.ron>`.

use std::path::PathBuf;
use std::process::ExitCode;

use crate::failure::CommandResult;
use crate::session::SessionArgs;

/// Arguments of `cnets check`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The graph file.
    graph: PathBuf,
    /// The session's flags (`--max-memory` is accepted as everywhere; nothing is evaluated).
    #[command(flatten)]
    session: SessionArgs,
}

/// Runs the command.
pub fn run(args: Args) -> CommandResult {
    let doc = args.session.session().load_graph(&args.graph, &[])?;
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
