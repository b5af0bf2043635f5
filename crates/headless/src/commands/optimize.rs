//! `cnets optimize <GRAPH.ron> [--max-iter N] [--out FILE] [--method M] [--json]`.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use cnets_engine::NodeContext;
use cnets_engine::file::save_file;
use cnets_engine::optimize::{Method, Options, Stop, check_gradient, optimize};
use serde_json::json;

use crate::failure::{CommandResult, Failure};
use crate::progress::Progress;
use crate::session::SessionArgs;

/// Arguments of `cnets optimize`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The graph file; it must contain an `optimization: (…)` setup.
    graph: PathBuf,
    /// Iteration limit (overrides the setup's `max_iter`).
    #[arg(long)]
    max_iter: Option<usize>,
    /// Write the graph with the optimized values to this file (atomically).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Minimizer: auto, lbfgsb or nelder_mead (overrides the setup's `method`).
    #[arg(long)]
    method: Option<String>,
    /// Re-evaluate the whole graph for every objective evaluation (baseline for comparisons).
    #[arg(long)]
    full: bool,
    /// Compare the exact gradient with finite differences at the start point and print
    /// `largest relative difference: <number>` (no optimization).
    #[arg(long)]
    check_gradient: bool,
    /// Gradients by finite differences of the whole graph instead of the exact reverse pass
    /// (the baseline for comparisons).
    #[arg(long)]
    finite_differences: bool,
    /// Stop after this many seconds (wall clock) and keep the best point found so far.
    #[arg(long)]
    time_limit: Option<f64>,
    /// Print the result (and every iteration) as JSON.
    #[arg(long)]
    json: bool,
    /// Print every iteration on stderr.
    #[arg(long, short)]
    verbose: bool,
    #[command(flatten)]
    session: SessionArgs,
}

/// Runs the command.
pub fn run(args: Args) -> CommandResult {
    // Its own cancel flag: `--time-limit` sets it (Ctrl+C ends the process).
    let session = args
        .session
        .session()
        .with_cancel(std::sync::Arc::default());
    let mut doc = session.load_graph(&args.graph, &[])?;
    let setup = doc.meta.optimization.clone().ok_or_else(|| {
        Failure::usage(format!(
            "{}: the graph has no optimization setup (an `optimization: (…)` section)",
            args.graph.display()
        ))
    })?;
    let method = match &args.method {
        Some(m) => Some(Method::parse(m).ok_or_else(|| {
            Failure::usage(format!(
                "unknown method '{m}'; use auto, lbfgsb or nelder_mead"
            ))
        })?),
        None => None,
    };
    let options = Options {
        max_iter: args.max_iter,
        method,
        incremental: !args.full,
        exact_gradients: !args.finite_differences,
        ..Options::default()
    };
    if let Some(out) = &args.out {
        crate::commands::render::check_target(out)?;
    }
    let ctx = session.context(args.graph.parent().map(Path::to_path_buf));
    if args.check_gradient {
        return check(&args, &doc.graph, &setup, &ctx);
    }
    if let Some(seconds) = args.time_limit {
        if !(seconds.is_finite() && seconds >= 0.0) {
            return Err(Failure::usage(format!(
                "--time-limit must be a number of seconds ≥ 0, got {seconds}"
            )));
        }
        let cancel = std::sync::Arc::clone(&ctx.cancel);
        std::thread::spawn(move || {
            std::thread::sleep(std::time::Duration::from_secs_f64(seconds.min(1e9)));
            cancel.store(true, std::sync::atomic::Ordering::Relaxed);
        });
    }
    let started = std::time::Instant::now();
    let progress = Progress::new("optimizing");
    let mut history = Vec::new();
    let limit = args.max_iter.unwrap_or(setup.max_iter);
    let outcome = optimize(&doc.graph, &setup, &options, &ctx, &mut |it| {
        progress.message(&format!("iteration {} objective {:.6e}", it.iteration, it.objective));
        progress.update(it.iteration, limit);
        if args.verbose {
            crate::errln!(
                "iteration {:>4}  objective {:.9e}  gradient {:.3e}  evaluations {}  node runs {}  ({})",
                it.iteration,
                it.objective,
                it.gradient,
                it.evaluations,
                it.node_runs,
                it.method.name()
            );
        }
        history.push(json!({"iteration": it.iteration, "objective": it.objective, "evaluations": it.evaluations, "node_runs": it.node_runs}));
    })
    .map_err(|e| match e {
        cnets_engine::optimize::OptimizeError::Setup(m) => Failure::usage(format!("{}: {m}", args.graph.display())),
        other => Failure::node(format!("{}: {other}", args.graph.display())),
    })?;
    progress.finish();
    let seconds = started.elapsed().as_secs_f64();
    let stop = match &outcome.stop {
        Stop::Converged(why) => format!("converged ({why})"),
        Stop::MaxIterations => "iteration limit reached".to_string(),
        Stop::Cancelled if args.time_limit.is_some() => "stopped at the time limit".to_string(),
        Stop::Cancelled => "cancelled".to_string(),
    };
    if let Some(out) = &args.out {
        doc.graph = outcome.graph;
        save_file(out, &doc.graph, &doc.meta)
            .map_err(|e| Failure::usage(format!("{}: cannot write: {e}", out.display())))?;
    }
    let not_convex: serde_json::Map<String, serde_json::Value> = outcome
        .not_convex
        .iter()
        .map(|(node, n)| (node.clone(), json!(n)))
        .collect();
    let variables: serde_json::Map<String, serde_json::Value> = outcome
        .variables
        .iter()
        .zip(&outcome.x)
        .map(|(v, x)| (v.input.to_string(), json!(x)))
        .collect();
    for (node, n) in &outcome.not_convex {
        if let Some(n) = n.filter(|&n| n > 0) {
            crate::errln!(
                "warning: {n} faces of '{node}' are not (++)(++) (folded); keep them convex with \
                 `convex: [\"{node}\"]` in the optimization setup (docs/optimizer.md)"
            );
        }
    }
    if args.json {
        crate::outln!(
            "{}",
            json!({
                "start": outcome.start,
                "objective": outcome.objective,
                "iterations": outcome.iterations,
                "evaluations": outcome.evaluations,
                "gradients": outcome.gradients,
                "exact_gradients": outcome.exact_gradients,
                "finite_difference_nodes": outcome.finite_difference_nodes,
                "not_convex": not_convex,
                "notes": outcome.notes,
                "branch_crossings": outcome.branch_crossings,
                "node_runs": outcome.node_runs,
                "fell_back": outcome.fell_back,
                "seconds": seconds,
                "stop": stop,
                "variables": variables,
                "history": history,
            })
        );
    } else {
        crate::outln!(
            "objective {:.6e} -> {:.6e} in {} iterations ({} evaluations, {} gradients ({} exact), {} node runs, {seconds:.3} s); {stop}",
            outcome.start,
            outcome.objective,
            outcome.iterations,
            outcome.evaluations,
            outcome.gradients,
            outcome.exact_gradients,
            outcome.node_runs
        );
        for note in &outcome.notes {
            crate::outln!("note: {note}");
        }
        for (node, n) in &outcome.not_convex {
            match n {
                Some(n) => crate::outln!("faces not (++)(++): {n} ({node})"),
                None => crate::outln!("faces not (++)(++): unknown ({node} failed at the result)"),
            }
        }
        if outcome.branch_crossings > 0 {
            crate::outln!(
                "branch crossings: {} (steps on which a node on the path changed its smooth piece)",
                outcome.branch_crossings
            );
        }
        const SHOWN: usize = 60;
        for (name, x) in variables.iter().take(SHOWN) {
            crate::outln!("  {name} = {x}");
        }
        if variables.len() > SHOWN {
            crate::outln!("  … and {} more variables", variables.len() - SHOWN);
        }
        if let Some(out) = &args.out {
            crate::outln!("wrote {}", out.display());
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// `--check-gradient`: the exact gradient against finite differences at the start point.
fn check(
    args: &Args,
    graph: &cnets_engine::Graph,
    setup: &cnets_engine::optimize::Setup,
    ctx: &NodeContext,
) -> CommandResult {
    let checked = check_gradient(graph, setup, ctx).map_err(|e| match e {
        cnets_engine::optimize::OptimizeError::Setup(m) => {
            Failure::usage(format!("{}: {m}", args.graph.display()))
        }
        other => Failure::node(format!("{}: {other}", args.graph.display())),
    })?;
    let notes: Vec<String> = checked
        .node_notes
        .iter()
        .map(|(node, why)| format!("node '{node}': finite differences for its part ({why})"))
        .collect();
    if args.json {
        crate::outln!(
            "{}",
            json!({
                "objective": checked.value,
                "variables": checked.x.len(),
                "exact": checked.exact,
                "finite_differences": checked.finite_differences,
                "largest_relative_difference": checked.largest_relative_difference,
                "notes": notes,
            })
        );
    } else {
        crate::outln!(
            "objective {:.9e}, {} variables",
            checked.value,
            checked.x.len()
        );
        for note in &notes {
            crate::outln!("note: {note}");
        }
        crate::outln!(
            "largest relative difference: {:.3e}",
            checked.largest_relative_difference
        );
    }
    Ok(ExitCode::SUCCESS)
}
