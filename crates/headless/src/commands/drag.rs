//! `cnets drag <GRAPH.ron> --node NODE --vertex I,J --to X,Y,Z [--pin I,J]… [--free NODE.INPUT]…
//! [--out FILE] [--json]`: the editor's Drag net tool, solved once (docs/editor/3d-view.md, Dragging the
//! net; the solver is `cnets_engine::optimize::drag`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use cnets_engine::file::save_file;
use cnets_engine::optimize::drag::{DragError, DragReport, DragRequest, default_free, drag};
use cnets_engine::optimize::{ValuePath, Variable};
use serde_json::json;

use crate::failure::{CommandResult, Failure};
use crate::session::SessionArgs;

/// Arguments of `cnets drag`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The graph file.
    graph: PathBuf,
    /// The node whose quad mesh is dragged (e.g. a `cnets.construct`).
    #[arg(long)]
    node: String,
    /// The grabbed vertex: row I (along the generatrix), column J (along the directrix).
    #[arg(long, value_name = "I,J", value_parser = parse_vertex)]
    vertex: (usize, usize),
    /// Which net when the node's output is a list of them (a construction over several
    /// generatrices, e.g. the facade's non-manifold one), counted from 0.
    #[arg(long, value_name = "K")]
    item: Option<usize>,
    /// Where the vertex should go.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_point, allow_hyphen_values = true)]
    to: [f64; 3],
    /// A vertex that must stay where it is (repeat for several).
    #[arg(long = "pin", value_name = "I,J", value_parser = parse_vertex)]
    pins: Vec<(usize, usize)>,
    /// An input the drag may change, `node.input` (repeat for several; default: every slider,
    /// point list, mapper handle and list of numbers upstream of the node).
    #[arg(long = "free", value_name = "NODE.INPUT")]
    free: Vec<String>,
    /// Write the graph with the new values to this file (atomically).
    #[arg(long)]
    out: Option<PathBuf>,
    #[command(flatten)]
    session: SessionArgs,
    /// Print the report as JSON.
    #[arg(long)]
    json: bool,
}

/// `I,J` → (I, J).
fn parse_vertex(text: &str) -> Result<(usize, usize), String> {
    let bad = || {
        format!(
            "'{}' is not a vertex I,J (two whole numbers ≥ 0)",
            cnets_engine::files::excerpt(text, 40)
        )
    };
    let (i, j) = text.split_once(',').ok_or_else(bad)?;
    Ok((
        i.trim().parse().map_err(|_| bad())?,
        j.trim().parse().map_err(|_| bad())?,
    ))
}

/// `X,Y,Z` → [X, Y, Z], finite.
fn parse_point(text: &str) -> Result<[f64; 3], String> {
    let bad = |why: &str| {
        format!(
            "'{}' is not a point X,Y,Z ({why})",
            cnets_engine::files::excerpt(text, 60)
        )
    };
    let parts: Vec<&str> = text.split(',').collect();
    let [x, y, z] = parts.as_slice() else {
        return Err(bad("three numbers separated by commas"));
    };
    let mut p = [0.0f64; 3];
    for (v, s) in p.iter_mut().zip([x, y, z]) {
        *v = s.trim().parse().map_err(|_| bad("three numbers"))?;
        if !v.is_finite() {
            return Err(bad("a coordinate is not finite"));
        }
    }
    Ok(p)
}

/// Runs the command.
pub fn run(args: Args) -> CommandResult {
    let session = args.session.session();
    let mut doc = session.load_graph(&args.graph, &[])?;
    if let Some(out) = &args.out {
        crate::commands::render::check_target(out)?;
    }
    let free = if args.free.is_empty() {
        None
    } else {
        let all = default_free(&doc.graph, &args.node).map_err(usage)?;
        let mut chosen = Vec::new();
        for f in &args.free {
            let path = ValuePath::parse(f).map_err(|e| Failure::usage(format!("--free: {e}")))?;
            // A default free input keeps its bounds; another literal input is free unbounded.
            chosen.push(
                all.iter()
                    .find(|v| v.input.node == path.node && v.input.port == path.port)
                    .cloned()
                    .unwrap_or(Variable {
                        input: path,
                        min: f64::NEG_INFINITY,
                        max: f64::INFINITY,
                    }),
            );
        }
        Some(chosen)
    };
    let mut request = DragRequest::new(args.node.clone(), args.vertex, args.to.into());
    request.pins = args.pins.clone();
    request.item = args.item;
    request.free = free;
    let ctx = session.context(args.graph.parent().map(Path::to_path_buf));
    let report = drag(&doc.graph, &request, &ctx).map_err(|e| match e {
        DragError::Evaluation(m) => Failure::node(m),
        other => usage(other),
    })?;
    print_report(&args, &report)?;
    if let Some(out) = &args.out {
        doc.graph = report.graph;
        save_file(out, &doc.graph, &doc.meta)
            .map_err(|e| Failure::usage(format!("{}: cannot write: {e}", out.display())))?;
        if !args.json {
            crate::outln!("wrote {}", out.display());
        }
    }
    Ok(ExitCode::SUCCESS)
}

fn usage(e: DragError) -> Failure {
    Failure::usage(e.to_string())
}

fn print_report(args: &Args, r: &DragReport) -> Result<(), Failure> {
    let not_convex: serde_json::Map<String, serde_json::Value> = r
        .not_convex
        .iter()
        .map(|(node, n)| (node.clone(), json!(n)))
        .collect();
    if args.json {
        let changes: Vec<serde_json::Value> = r
            .changes
            .iter()
            .map(|c| json!({"input": c.input.to_string(), "old": c.old, "new": c.new}))
            .collect();
        crate::outln!(
            "{}",
            json!({
                "reached": r.reached.to_array(),
                "distance_left": r.distance_left,
                "pin_drift": r.pin_drift,
                "not_convex": not_convex,
                "changes": changes,
                "iterations": r.iterations,
                "evaluations": r.evaluations,
            })
        );
        return Ok(());
    }
    let p = r.reached;
    crate::outln!(
        "reached ({}, {}, {}); distance left {:.3e} ({} steps, {} evaluations)",
        p.x,
        p.y,
        p.z,
        r.distance_left,
        r.iterations,
        r.evaluations
    );
    if !args.pins.is_empty() {
        crate::outln!("pinned vertices moved at most {:.3e}", r.pin_drift);
    }
    for (node, n) in &r.not_convex {
        match n {
            Some(n) => crate::outln!("faces not (++)(++): {n} ({node})"),
            None => crate::outln!("faces not (++)(++): unknown ({node} failed)"),
        }
    }
    for c in &r.changes {
        crate::outln!("  {}: {} -> {}", c.input, c.old, c.new);
    }
    Ok(())
}
