//! `cnets eval <TYPE> --inputs <FILE.json | -> [--timing] [--out DIR]`.

use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;

use cnets_engine::Value;
use cnets_engine::value::json::JsonOut;

use crate::failure::CommandResult;
use crate::inputs::{node_inputs, read_json};
use crate::session::SessionArgs;

/// Arguments of `cnets eval`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The node type id, e.g. `curve.arc`.
    node_type: String,
    /// JSON object of inputs: a file, or `-` for stdin.
    #[arg(long)]
    inputs: String,
    /// Print `time: <ms> ms` on stderr (evaluation only) and, after the outputs, `peak memory:
    /// <MB> MB` (the whole process: reading, evaluation, writing; Linux).
    #[arg(long)]
    timing: bool,
    /// Compute and print only these outputs (comma-separated names); a node may skip the work of
    /// the others.
    #[arg(long, value_delimiter = ',', value_name = "NAMES")]
    outputs: Option<Vec<String>>,
    /// Output directory for export nodes.
    #[arg(long, default_value = "out")]
    out: PathBuf,
    #[command(flatten)]
    session: SessionArgs,
}

/// Runs the command.
pub fn run(args: Args) -> CommandResult {
    let _peak = PeakOnExit(args.timing);
    let registry = Arc::new(cnets_nodes::registry());
    let session = args.session.session().with_out_dir(Some(args.out.clone()));
    let node = session.resolve(&args.node_type, &registry)?;
    let def = node.def();
    // The document is consumed by decoding: its packed rows move into the input values.
    let inputs = node_inputs(def, read_json(&args.inputs, session.budget().limit)?)?;
    let run = session.eval_node(
        def,
        &inputs,
        args.outputs.as_deref(),
        std::env::current_dir().ok(),
    )?;
    if args.timing {
        crate::errln!("time: {:.3} ms", run.elapsed.as_secs_f64() * 1e3);
    }
    let outputs = run.into_outputs()?;
    for w in &outputs.warnings {
        crate::errln!("warning: {}: {w}", def.id);
    }
    let printed: Vec<(&str, &Value)> = def
        .outputs
        .iter()
        .zip(&outputs.values)
        .filter(|(p, _)| {
            args.outputs
                .as_ref()
                .is_none_or(|names| names.iter().any(|n| n == &p.name))
        })
        .map(|(p, v)| (p.name.as_ref(), v))
        .collect();
    crate::output::json_line(&Outputs(&printed))?;
    Ok(ExitCode::SUCCESS)
}

/// With `--timing`, prints the peak memory when the command ends, also when it fails (a refused
/// input or a node over the budget are measured too).
struct PeakOnExit(bool);

impl Drop for PeakOnExit {
    fn drop(&mut self) {
        if let Some(peak) = crate::peak::peak_memory().filter(|_| self.0) {
            crate::errln!("peak memory: {:.1} MB", peak as f64 / 1e6);
        }
    }
}

/// `{ "<output>": <value>, … }`, streamed.
struct Outputs<'a>(&'a [(&'a str, &'a Value)]);

impl serde::Serialize for Outputs<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_map(self.0.iter().map(|(name, v)| (*name, JsonOut(v))))
    }
}
