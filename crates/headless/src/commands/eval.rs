//! `cnets eval <TYPE> --inputs <FILE.json | -> [--timing] [--out DIR]`.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use cnets_engine::Value;
use cnets_engine::eval::evaluate_node;
use cnets_engine::value::json::JsonOut;
use cnets_engine::{MemoryBudget, NodeContext, NodeFlag};

use crate::failure::{CommandResult, Failure};
use crate::inputs::{node_inputs, read_json};
use crate::library;
use std::sync::Arc;

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
    /// The most memory the evaluation's values may take, e.g. `12G`, `512MB` (default: half the
    /// machine's memory); a node that would need more fails with what it needs.
    #[arg(long, value_name = "SIZE", value_parser = cnets_engine::budget::parse_size)]
    max_memory: Option<u64>,
    /// A folder nodes and cluster files may also read from (besides the graph file's folder);
    /// repeat for several.
    #[arg(long = "allow-read", value_name = "DIR")]
    allow_read: Vec<PathBuf>,
    /// Extra folders searched for cluster graph files.
    #[arg(long)]
    library: Vec<PathBuf>,
}

/// Runs the command.
pub fn run(args: Args) -> CommandResult {
    let _peak = PeakOnExit(args.timing);
    let registry = Arc::new(cnets_nodes::registry());
    let cluster;
    let def = if let Some(path) = args.node_type.strip_prefix(library::PREFIX) {
        cluster = library::cluster_def(path, &registry, &args.library, &args.allow_read)?;
        &cluster
    } else if let Some(def) = registry.get(&args.node_type) {
        def.as_ref()
    } else {
        let hints = registry.similar_ids(&args.node_type);
        let hint = if hints.is_empty() {
            String::new()
        } else {
            format!(" (did you mean {}?)", hints.join(", "))
        };
        return Err(Failure::usage(format!(
            "unknown node type '{}'{hint}; `cnets nodes` lists them",
            cnets_engine::files::excerpt(&args.node_type, 60)
        )));
    };
    // The document is consumed by decoding: its packed rows move into the input values.
    let budget = match args.max_memory {
        Some(limit) => {
            let granted = MemoryBudget::requested(limit);
            if let Some(w) = &granted.warning {
                crate::errln!("warning: {w}");
            }
            granted.budget
        }
        None => MemoryBudget::default(),
    };
    let inputs = node_inputs(def, read_json(&args.inputs, budget.limit)?)?;
    let out_dir = def.has_flag(NodeFlag::Export).then(|| args.out.clone());
    if let Some(dir) = &out_dir {
        crate::commands::create_out_dir(dir)?;
    }
    let base = std::env::current_dir().ok();
    let mut ctx = NodeContext::new(out_dir, base);
    ctx.budget = budget;
    ctx.allow_read = args.allow_read.clone();
    ctx.cancel = crate::signals::cancel_flag();
    if let Some(names) = &args.outputs {
        if let Some(bad) = names.iter().find(|n| def.output_index(n).is_none()) {
            return Err(Failure::usage(format!(
                "unknown output '{bad}' for {}; valid outputs: {}",
                def.id,
                def.output_names()
            )));
        }
        ctx.requested = Some(names.clone());
    }
    let start = Instant::now();
    let result = evaluate_node(def, &ctx, &inputs);
    let elapsed = start.elapsed();
    if args.timing {
        crate::errln!("time: {:.3} ms", elapsed.as_secs_f64() * 1e3);
    }
    if ctx.cancelled() {
        cnets_engine::files::temp::remove_own();
        return Err(Failure {
            code: crate::signals::CANCELLED,
            messages: vec!["cancelled".to_string()],
        });
    }
    let outputs = result.map_err(|message| Failure::node(format!("{}: {message}", def.id)))?;
    for w in &outputs.warnings {
        crate::errln!("warning: {}: {w}", def.id);
    }
    let printed: Vec<(&str, &Value)> = def
        .outputs
        .iter()
        .zip(&outputs.values)
        .filter(|(p, _)| ctx.wants(&p.name))
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
