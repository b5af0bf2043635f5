//! `cnets`: the command-line runner. List node types, evaluate one node on JSON inputs, run and
//! check graph files.

mod commands;
mod failure;
mod inputs;
mod library;
mod output;
mod peak;
mod progress;
mod runtime_dir;
mod session;
mod signals;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

use crate::failure::Failure;

/// The process allocator: mimalloc keeps freed memory for reuse, where glibc's malloc hands large
/// freed blocks (a 1000 × 1000 construction's 49 MB) back to the kernel and page-faults them in again
/// on the next evaluation (docs/geometry.md, Performance).
///
/// It is counted (the `cap` crate's wrapper, never limiting: the limit is `usize::MAX`) so the
/// memory budget sees everything the process allocates — readers, writers, input conversion — not
/// only the values held (`cnets_engine::budget::allocated`).
#[global_allocator]
static ALLOCATOR: cap::Cap<mimalloc::MiMalloc> = cap::Cap::new(mimalloc::MiMalloc, usize::MAX);

/// The process's allocated bytes, for the memory budget.
fn allocated() -> u64 {
    ALLOCATOR.allocated() as u64
}

/// cnets: design cone-nets (planar-quad meshes on discrete cones) from node graphs.
#[derive(Debug, Parser)]
#[command(name = "cnets", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// List every node type: id, category, doc, inputs (name, type, default) and outputs.
    Nodes(commands::nodes::Args),
    /// Evaluate one node type on JSON inputs and print its outputs as JSON.
    Eval(commands::eval::Args),
    /// Evaluate a graph file; export nodes write into --out.
    Run(commands::run::Args),
    /// Load and type-check a graph file without evaluating it.
    Check(commands::check::Args),
    /// Run the optimization stored in a graph file and write the optimized graph.
    Optimize(commands::optimize::Args),
    /// Render the previewed geometry of a graph off-screen to a PNG.
    Render(commands::render::Args),
    /// Drag a vertex of a net to a point: solve the design's free inputs (the Drag net tool).
    Drag(commands::drag::Args),
}

/// The exit of a command line clap did not run: help and version on stdout (a failed write is
/// reported, as for every output), usage errors on stderr.
fn clap_exit(e: clap::Error) -> ExitCode {
    let code = u8::try_from(e.exit_code()).unwrap_or(2);
    if e.use_stderr() {
        crate::errln!("{}", e.render().to_string().trim_end());
        return ExitCode::from(code);
    }
    let written = output::text(format_args!("{}", e.render())).and_then(|()| output::flush());
    match written {
        Ok(()) => ExitCode::from(code),
        Err(Failure { code, messages }) => {
            for m in messages {
                crate::errln!("error: {m}");
            }
            ExitCode::from(code)
        }
    }
}

fn main() -> ExitCode {
    cnets_engine::budget::set_allocated_probe(allocated);
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return clap_exit(e),
    };
    let renders = match &cli.command {
        Command::Render(_) => true,
        Command::Run(args) => args.renders(),
        _ => false,
    };
    if renders && let Some(code) = runtime_dir::rerun_with_runtime_dir() {
        return code;
    }
    signals::install();
    // Start the worker threads now: they come up while the inputs are read and parsed, so an
    // evaluation finds them ready (as in the editor and behind a server, where they are long-lived).
    rayon::spawn(|| ());
    let result = match cli.command {
        Command::Nodes(args) => commands::nodes::run(args),
        Command::Eval(args) => commands::eval::run(args),
        Command::Run(args) => commands::run::run(args),
        Command::Check(args) => commands::check::run(args),
        Command::Optimize(args) => commands::optimize::run(args),
        Command::Render(args) => commands::render::run(args),
        Command::Drag(args) => commands::drag::run(args),
    };
    let result = result.and_then(|code| output::flush().map(|()| code));
    match result {
        Ok(code) => code,
        Err(Failure { code, messages }) => {
            for m in messages {
                crate::errln!("error: {m}");
            }
            ExitCode::from(code)
        }
    }
}
