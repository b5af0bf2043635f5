//! `cnets run <GRAPH.ron> [--set <node>.<input>=<value>]… [--out <DIR>] [--json]`.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use cnets_engine::Value;
use cnets_engine::eval::OutputMask;
use cnets_engine::value::json::JsonOut;
use cnets_engine::{Evaluator, NodeFlag, NodeResult};

use crate::commands::render::{Look, render_png};
use crate::failure::{CommandResult, Failure};
use crate::progress::Progress;
use crate::session::SessionArgs;

/// Arguments of `cnets run`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The graph file.
    graph: PathBuf,
    #[command(flatten)]
    session: SessionArgs,
    /// Override an input before running: `node.input=value` (value in JSON; plain text for text inputs).
    #[arg(long = "set", value_name = "NODE.INPUT=VALUE")]
    sets: Vec<String>,
    /// Output directory for export nodes (never written outside of).
    #[arg(long, default_value = "out")]
    out: PathBuf,
    /// Print `{ "nodes": { "<id>": { "outputs", "errors", "time_ms" } } }` instead of a summary.
    #[arg(long)]
    json: bool,
    /// Also render the previewed geometry to this PNG (as `cnets render` with its defaults).
    #[arg(long)]
    png: Option<PathBuf>,
}

fn errors_of(result: Option<&NodeResult>) -> Vec<String> {
    match result {
        Some(NodeResult::Ok(_)) | None => Vec::new(),
        Some(NodeResult::Disabled) => Vec::new(),
        Some(r) => r.error().map(|m| m.into_owned()).into_iter().collect(),
    }
}

fn status(result: Option<&NodeResult>) -> &'static str {
    match result {
        Some(NodeResult::Ok(_)) => "ok",
        Some(NodeResult::Failed(_) | NodeResult::Invalid(_)) => "failed",
        Some(NodeResult::Blocked(_)) => "blocked",
        Some(NodeResult::Disabled) => "disabled",
        None => "not evaluated",
    }
}

impl Args {
    /// Whether this run renders a picture (`--png`).
    pub fn renders(&self) -> bool {
        self.png.is_some()
    }
}

/// Runs the command.
pub fn run(args: Args) -> CommandResult {
    if let Some(png) = &args.png {
        crate::commands::render::check_target(png)?;
    }
    let session = args.session.session().with_out_dir(Some(args.out.clone()));
    let doc = session.load_graph(&args.graph, &args.sets)?;
    let graph = doc.graph;
    let exports = graph
        .nodes()
        .any(|(_, n)| n.def.has_flag(NodeFlag::Export) && n.enabled);
    let base = args.graph.parent().map(Path::to_path_buf);
    let ctx = session.export_context(base, exports)?;
    let mut evaluator = Evaluator::new();
    // Every node runs (its errors are reported). Outputs are lazy: `--json` prints them all, so
    // it asks for all; otherwise a previewed node (as in the editor) and an export are asked for
    // all, any other node only for its outputs wired into others.
    let all: Vec<_> = graph
        .nodes()
        .map(|(k, n)| {
            let mask = if args.json || n.preview || n.def.has_flag(NodeFlag::Export) {
                OutputMask::ALL
            } else {
                OutputMask::NONE
            };
            (k, mask)
        })
        .collect();
    let progress = Progress::new("evaluating");
    let start = Instant::now();
    let summary = evaluator.evaluate_outputs(&graph, &all, &ctx, &mut |done, total| {
        progress.update(done, total)
    });
    let elapsed = start.elapsed();
    progress.finish();
    // A cancel seen by a node (an export stopped mid-file) counts as much as one between nodes.
    if summary.cancelled || ctx.cancelled() {
        cnets_engine::files::temp::remove_own();
        return Err(Failure {
            code: crate::signals::CANCELLED,
            messages: vec!["cancelled".to_string()],
        });
    }

    let mut failed = Vec::new();
    let mut nodes: Vec<NodeOut<'_>> = Vec::new();
    let mut files = Vec::new();
    for (index, node) in graph.nodes() {
        let result = evaluator.result_at(&graph, index);
        if result.is_some_and(NodeResult::is_failure) {
            failed.push(format!(
                "node '{}' ({}): {}",
                node.id,
                node.def.id,
                result.and_then(NodeResult::error).as_deref().unwrap_or("")
            ));
        }
        let outputs = result.and_then(NodeResult::outputs);
        if let Some(o) = outputs {
            files.extend(o.files.iter().cloned());
        }
        if args.json {
            let values = outputs
                .map(|o| {
                    node.def
                        .outputs
                        .iter()
                        .zip(&o.values)
                        .map(|(p, v)| (p.name.as_ref(), v))
                        .collect()
                })
                .unwrap_or_default();
            let time_ms = evaluator
                .time(&graph, &node.id)
                .map_or(0.0, |t| t.as_secs_f64() * 1e3);
            nodes.push(NodeOut {
                id: &node.id,
                ty: &node.def.id,
                status: status(result),
                outputs: values,
                errors: errors_of(result),
                warnings: outputs.map(|o| o.warnings.as_slice()).unwrap_or_default(),
                time_ms,
            });
        }
    }
    if args.json {
        crate::output::json_line(&RunOut(&nodes))?;
    } else {
        crate::outln!(
            "{}: {} nodes evaluated in {:.1} ms, {} failed",
            args.graph.display(),
            summary.ran,
            elapsed.as_secs_f64() * 1e3,
            failed.len()
        );
        for (_, node) in graph.nodes() {
            if let Some(o) = evaluator
                .result(&graph, &node.id)
                .and_then(NodeResult::outputs)
            {
                for w in &o.warnings {
                    crate::errln!("warning: node '{}': {w}", node.id);
                }
            }
        }
        for f in &files {
            crate::outln!("wrote {}", f.display());
        }
    }
    if let Some(png) = &args.png {
        let look = Look::parse("1280x720", "iso", "config", &[])?;
        let line = render_png(&graph, &evaluator, &look, png)?;
        if args.json {
            crate::errln!("{line}");
        } else {
            crate::outln!("{line}");
        }
    }
    if failed.is_empty() {
        Ok(ExitCode::SUCCESS)
    } else {
        Err(Failure {
            code: 1,
            messages: failed,
        })
    }
}

/// One node of `run --json`: `{ "type", "status", "outputs", "errors", "warnings", "time_ms" }`.
struct NodeOut<'a> {
    id: &'a str,
    ty: &'a str,
    status: &'static str,
    outputs: Vec<(&'a str, &'a Value)>,
    errors: Vec<String>,
    warnings: &'a [String],
    time_ms: f64,
}

/// `{ "nodes": { "<id>": … } }`, streamed: the values are written as they are read, with no JSON
/// tree of them (a 10⁷-point curve's tree took gigabytes).
struct RunOut<'a>(&'a [NodeOut<'a>]);

impl serde::Serialize for RunOut<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        struct Nodes<'a>(&'a [NodeOut<'a>]);
        impl serde::Serialize for Nodes<'_> {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.collect_map(self.0.iter().map(|n| (n.id, n)))
            }
        }
        let mut m = s.serialize_map(Some(1))?;
        m.serialize_entry("nodes", &Nodes(self.0))?;
        m.end()
    }
}

impl serde::Serialize for NodeOut<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        struct Outputs<'a>(&'a [(&'a str, &'a Value)]);
        impl serde::Serialize for Outputs<'_> {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.collect_map(self.0.iter().map(|(name, v)| (*name, JsonOut(v))))
            }
        }
        let mut m = s.serialize_map(Some(6))?;
        m.serialize_entry("type", self.ty)?;
        m.serialize_entry("status", self.status)?;
        m.serialize_entry("outputs", &Outputs(&self.outputs))?;
        m.serialize_entry("errors", &self.errors)?;
        m.serialize_entry("warnings", self.warnings)?;
        m.serialize_entry("time_ms", &self.time_ms)?;
        m.end()
    }
}
