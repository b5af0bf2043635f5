//! The built-in optimizer: drives a graph's number inputs to minimize a number output.
//!
//! A graph file may store an optimization [`Setup`] (variables with bounds, an objective, soft
//! constraints as penalties). [`optimize`] runs it with bounded L-BFGS on finite-difference gradients
//! (central differences, one-sided at a bound) and falls back to Nelder–Mead when the objective is not
//! smooth (a failed line search, a non-finite value). Every objective evaluation re-runs only the part
//! of the graph that depends on the changed variable — the incremental engine at work — and the
//! evaluations and node runs are counted. Runs are deterministic (bit for bit), cancellable through
//! the context's cancel flag, and report every iteration.

pub mod branch;
pub mod convexity;
pub mod drag;
pub mod gradient;
mod lbfgsb;
mod nelder_mead;
pub mod path;
mod problem;
pub mod setup;
pub mod vjp;

/// The number leaves of values (moved down to `value`: the node contract reads them too).
pub use crate::value::leaves;
pub use gradient::Gradient;
pub use path::ValuePath;
pub use problem::{Problem, SetupMismatch};
pub use setup::{Method, Penalty, PenaltyKind, Setup, Variable};

use crate::graph::Graph;
use crate::node::NodeContext;
use lbfgsb::{Memory, project, projected_gradient};
use nelder_mead::{Simplex, initial_points};

/// Settings of one run.
#[derive(Debug, Clone)]
pub struct Options {
    /// Overrides the setup's iteration limit.
    pub max_iter: Option<usize>,
    /// Overrides the setup's method.
    pub method: Option<Method>,
    /// Re-evaluate incrementally (true) or from scratch every time (the baseline for comparisons).
    pub incremental: bool,
    /// Stop when the projected gradient's largest component is at most this times the starting one.
    pub gradient_tolerance: f64,
    /// Exact gradients by the reverse pass (true) or central differences of the whole graph
    /// (false: the baseline for comparisons).
    pub exact_gradients: bool,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            max_iter: None,
            method: None,
            incremental: true,
            gradient_tolerance: 1e-12,
            exact_gradients: true,
        }
    }
}

/// What one iteration reached.
#[derive(Debug, Clone, PartialEq)]
pub struct Iteration {
    /// Iteration number (0 = the start).
    pub iteration: usize,
    /// Objective (with penalties) at the current point.
    pub objective: f64,
    /// Largest projected-gradient component (NaN for Nelder–Mead).
    pub gradient: f64,
    /// Objective evaluations so far.
    pub evaluations: u64,
    /// Node runs so far.
    pub node_runs: u64,
    /// The method that made the step.
    pub method: Method,
    /// The best point so far (the variables' values, in setup order): what a live view shows.
    pub best: Vec<f64>,
}

/// Why the run stopped.
#[derive(Debug, Clone, PartialEq)]
pub enum Stop {
    /// A convergence test passed (which one).
    Converged(String),
    /// The iteration limit was reached.
    MaxIterations,
    /// Cancellation was requested.
    Cancelled,
}

/// The result of a run.
#[derive(Debug)]
pub struct Outcome {
    /// Best variable values found.
    pub x: Vec<f64>,
    /// The variables of `x` (whole-input variables expanded into one per number).
    pub variables: Vec<Variable>,
    /// Objective at the start.
    pub start: f64,
    /// Objective at `x`.
    pub objective: f64,
    /// Iterations made.
    pub iterations: usize,
    /// Objective evaluations.
    pub evaluations: u64,
    /// Node runs over all evaluations.
    pub node_runs: u64,
    /// Gradients computed.
    pub gradients: u64,
    /// Gradients that were exact: the reverse pass with no node on the path differentiated by
    /// finite differences (the others used finite differences of a node or of the whole graph).
    pub exact_gradients: u64,
    /// Nodes whose part of some gradient was taken by finite differences of their own run.
    pub finite_difference_nodes: Vec<String>,
    /// Per construction on the path (and each `convex` names): its faces that are not (++)(++)
    /// at the result (`None`: it failed there).
    pub not_convex: Vec<(String, Option<usize>)>,
    /// Nodes whose part of the gradient used finite differences of their own run, with the reason
    /// (first occurrence of each), and why whole gradients fell back to finite differences.
    pub notes: Vec<String>,
    /// Steps on which a piecewise-smooth node on the path changed its piece (a kink crossed;
    /// the first ones are described in `notes`).
    pub branch_crossings: u64,
    /// Whether the run switched to Nelder–Mead.
    pub fell_back: bool,
    /// Why it stopped.
    pub stop: Stop,
    /// The graph with `x` applied.
    pub graph: Graph,
}

/// Why an optimization could not run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum OptimizeError {
    /// The setup refers to something the graph does not have.
    #[error(transparent)]
    Setup(#[from] SetupMismatch),
    /// The objective cannot be evaluated at the start.
    #[error("the objective cannot be evaluated at the start: {0}")]
    Start(String),
}

struct Run<'a> {
    problem: Problem,
    start: f64,
    ctx: &'a NodeContext,
    lo: Vec<f64>,
    hi: Vec<f64>,
    best: (Vec<f64>, f64),
    gradients: u64,
    exact: bool,
    exact_gradients: u64,
    finite_difference_nodes: Vec<String>,
    notes: Vec<String>,
    branches: branch::BranchWatch,
}

impl<'a> Run<'a> {
    /// A run of `problem` and its start point (projected into the bounds); `exact`: exact
    /// gradients (else finite differences of the whole graph).
    fn at_start(problem: Problem, ctx: &'a NodeContext, exact: bool) -> (Self, Vec<f64>) {
        let (lo, hi) = problem.bounds();
        let mut x = problem.start();
        project(&mut x, &lo, &hi);
        let run = Run {
            problem,
            start: 0.0,
            ctx,
            lo,
            hi,
            best: (x.clone(), f64::INFINITY),
            gradients: 0,
            exact,
            exact_gradients: 0,
            finite_difference_nodes: Vec::new(),
            notes: Vec::new(),
            branches: branch::BranchWatch::default(),
        };
        (run, x)
    }

    /// The objective, `+∞` where the graph fails; remembers the best point.
    fn f(&mut self, x: &[f64]) -> f64 {
        let v = self.problem.value(x, self.ctx).unwrap_or(f64::INFINITY);
        if v < self.best.1 {
            self.best = (x.to_vec(), v);
        }
        v
    }

    fn note(&mut self, note: String) {
        if !self.notes.contains(&note) {
            self.notes.push(note);
        }
    }

    /// The exact gradient (the reverse pass), else central differences.
    fn gradient(&mut self, x: &[f64], fx: f64) -> Vec<f64> {
        if self.exact {
            match self.problem.gradient(x, self.ctx) {
                Ok(g) => {
                    self.gradients += 1;
                    if g.finite_differences.is_empty() {
                        self.exact_gradients += 1;
                    }
                    for (node, reason) in g.finite_differences {
                        if !self.finite_difference_nodes.contains(&node) {
                            self.finite_difference_nodes.push(node.clone());
                        }
                        self.note(format!(
                            "node '{node}': finite differences for its part ({reason})"
                        ));
                    }
                    for report in self.branches.observe(self.gradients, g.branches) {
                        self.note(report);
                    }
                    return g.gradient;
                }
                Err(e) => self.note(format!(
                    "finite differences of the whole graph for a gradient: {e}"
                )),
            }
        }
        self.difference_gradient(x, fx)
    }

    /// Central differences (one-sided at a bound).
    fn difference_gradient(&mut self, x: &[f64], fx: f64) -> Vec<f64> {
        self.gradients += 1;
        let mut g = vec![0.0; x.len()];
        let mut probe = x.to_vec();
        for i in 0..x.len() {
            let h = 1e-6 * x[i].abs().max(1.0);
            let (up, down) = (x[i] + h <= self.hi[i], x[i] - h >= self.lo[i]);
            probe[i] = x[i] + h;
            let fp = if up { self.f(&probe) } else { fx };
            probe[i] = x[i] - h;
            let fm = if down { self.f(&probe) } else { fx };
            probe[i] = x[i];
            let span = h * (f64::from(u8::from(up)) + f64::from(u8::from(down)));
            g[i] = if span > 0.0 { (fp - fm) / span } else { 0.0 };
        }
        g
    }

    fn cancelled(&self) -> bool {
        self.ctx.cancelled()
    }

    fn iteration(
        &self,
        iteration: usize,
        objective: f64,
        gradient: f64,
        method: Method,
    ) -> Iteration {
        Iteration {
            iteration,
            objective,
            gradient,
            evaluations: self.problem.evaluations,
            node_runs: self.problem.node_runs,
            method,
            best: self.best.0.clone(),
        }
    }
}

/// Runs the optimization of `setup` on a copy of `graph`.
pub fn optimize(
    graph: &Graph,
    setup: &Setup,
    options: &Options,
    ctx: &NodeContext,
    report: &mut dyn FnMut(&Iteration),
) -> Result<Outcome, OptimizeError> {
    let problem = Problem::new(graph.clone(), setup.clone(), options.incremental)?;
    let (mut run, x) = Run::at_start(problem, ctx, options.exact_gradients);
    let max_iter = options.max_iter.unwrap_or(setup.max_iter);
    let mut start = run.problem.value(&x, ctx).map_err(OptimizeError::Start)?;
    let mut x = x;
    if run.problem.keeps_convex() {
        (x, start) = convex_start(&mut run, x, start, max_iter, options, report)?;
    }
    run.start = start;
    run.best = (x.clone(), start);
    let method = options.method.unwrap_or(setup.method);
    let mut iterations = 0;
    let mut fell_back = false;
    let mut stop = Stop::MaxIterations;
    if method != Method::NelderMead {
        let (s, done, smooth) = lbfgs(&mut run, x.clone(), start, max_iter, options, report);
        iterations = done;
        stop = s;
        if !smooth && method == Method::Auto && iterations < max_iter {
            fell_back = true;
            run.notes.push(format!(
                "L-BFGS stopped after {iterations} iterations ({}) far from a minimum: the \
                 objective is not smooth there; continued with Nelder–Mead (derivative-free)",
                match &stop {
                    Stop::Converged(why) => why.as_str(),
                    _ => "stopped",
                }
            ));
        }
    }
    if method == Method::NelderMead || fell_back {
        let from = run.best.0.clone();
        let (s, done) = nelder_mead(&mut run, from, max_iter - iterations, iterations, report);
        iterations += done;
        stop = s;
    }
    let (x, objective) = run.best.clone();
    // Evaluated at the result, so the faces counted are the result's.
    if run.problem.value(&x, ctx).is_err() {
        run.problem.apply(&x).map_err(OptimizeError::Start)?;
    }
    let not_convex = run.problem.not_convex();
    Ok(Outcome {
        x,
        variables: run.problem.setup().variables.clone(),
        start,
        objective,
        iterations,
        evaluations: run.problem.evaluations,
        node_runs: run.problem.node_runs,
        gradients: run.gradients,
        exact_gradients: run.exact_gradients,
        finite_difference_nodes: run.finite_difference_nodes,
        not_convex,
        notes: run.notes,
        branch_crossings: run.branches.crossings,
        fell_back,
        stop,
        graph: run.problem.into_graph(),
    })
}

/// Prepares a run that keeps faces convex: a folded start is first made convex (the feasibility
/// phase, [`convexity`]); then the barrier's weight is set from the objective there. Returns the
/// start point and its objective with the barrier.
fn convex_start(
    run: &mut Run<'_>,
    x: Vec<f64>,
    fit: f64,
    max_iter: usize,
    options: &Options,
    report: &mut dyn FnMut(&Iteration),
) -> Result<(Vec<f64>, f64), OptimizeError> {
    let ctx = run.ctx;
    let mut x = x;
    let mut fit = fit;
    if run.problem.kept_folded() {
        let folded = folded_count(&run.problem);
        run.problem.phase = convexity::Phase::Feasibility;
        let f0 = run.problem.value(&x, ctx).map_err(OptimizeError::Start)?;
        run.start = f0;
        run.best = (x.clone(), f0);
        let _ = lbfgs(run, x.clone(), f0, max_iter, options, report);
        x = run.best.0.clone();
        run.problem.phase = convexity::Phase::Off;
        fit = run.problem.value(&x, ctx).map_err(OptimizeError::Start)?;
        if run.problem.kept_folded() {
            run.note(format!(
                "the start had {folded} faces not (++)(++) and {} remain after the feasibility \
                 phase: the run continues without keeping faces convex",
                folded_count(&run.problem)
            ));
            return Ok((x, fit));
        }
        run.note(format!(
            "the start had {folded} faces not (++)(++): a feasibility phase made them convex \
             before the fit"
        ));
    }
    let weight = convexity::WEIGHT * fit.abs().max(1e-12);
    run.problem.phase = convexity::Phase::Barrier(weight);
    let start = run.problem.value(&x, ctx).map_err(OptimizeError::Start)?;
    Ok((x, start))
}

/// Folded faces of the constructions `convex` names, at the last evaluation.
fn folded_count(problem: &Problem) -> usize {
    let kept: Vec<&str> = problem
        .watched
        .iter()
        .filter(|w| w.kept)
        .map(|w| w.node.as_str())
        .collect();
    problem
        .not_convex()
        .iter()
        .filter(|(node, _)| kept.contains(&node.as_str()))
        .map(|(_, n)| n.unwrap_or(0))
        .sum()
}

/// The exact gradient at the start point against central differences of the whole graph.
#[derive(Debug, Clone)]
pub struct GradientCheck {
    /// The start point (projected into the bounds).
    pub x: Vec<f64>,
    /// The objective there.
    pub value: f64,
    /// The reverse pass's gradient.
    pub exact: Vec<f64>,
    /// Central differences (one-sided at a bound).
    pub finite_differences: Vec<f64>,
    /// max_i |exact_i − fd_i| / max_i |fd_i| (0 when both vanish).
    pub largest_relative_difference: f64,
    /// Nodes differentiated by finite differences of their own run, with the reason.
    pub node_notes: Vec<(String, String)>,
}

/// Compares the exact gradient with finite differences at the start point of `setup`.
pub fn check_gradient(
    graph: &Graph,
    setup: &Setup,
    ctx: &NodeContext,
) -> Result<GradientCheck, OptimizeError> {
    let problem = Problem::new(graph.clone(), setup.clone(), true)?;
    let (mut run, x) = Run::at_start(problem, ctx, true);
    let exact = run
        .problem
        .gradient(&x, ctx)
        .map_err(OptimizeError::Start)?;
    let fd = run.difference_gradient(&x, exact.value);
    let scale = max_abs(&fd).max(max_abs(&exact.gradient));
    let diff = exact
        .gradient
        .iter()
        .zip(&fd)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    Ok(GradientCheck {
        x,
        value: exact.value,
        largest_relative_difference: if scale > 0.0 { diff / scale } else { 0.0 },
        exact: exact.gradient,
        finite_differences: fd,
        node_notes: exact.finite_differences,
    })
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// Bounded L-BFGS. Returns the stop reason, the iterations made and whether the objective behaved
/// smoothly (false: fall back to Nelder–Mead).
fn lbfgs(
    run: &mut Run<'_>,
    mut x: Vec<f64>,
    mut f: f64,
    max_iter: usize,
    options: &Options,
    report: &mut dyn FnMut(&Iteration),
) -> (Stop, usize, bool) {
    let mut g = run.gradient(&x, f);
    let g0 = max_abs(&projected_gradient(&x, &g, &run.lo, &run.hi)).max(f64::MIN_POSITIVE);
    report(&run.iteration(0, f, g0, Method::Lbfgsb));
    let mut memory = Memory::default();
    let mut stalls = 0;
    for it in 1..=max_iter {
        if run.cancelled() {
            return (Stop::Cancelled, it - 1, true);
        }
        if g.iter().any(|v| !v.is_finite()) {
            return (Stop::Converged("non-finite gradient".into()), it - 1, false);
        }
        let pg = projected_gradient(&x, &g, &run.lo, &run.hi);
        let gnorm = max_abs(&pg);
        if gnorm <= options.gradient_tolerance * g0 || f == 0.0 {
            return (
                Stop::Converged(format!("projected gradient {gnorm:.3e}")),
                it - 1,
                true,
            );
        }
        let free: Vec<bool> = pg.iter().map(|v| *v != 0.0).collect();
        let mut d = memory.direction(&g, &free);
        if dot(&d, &pg) >= 0.0 || d.iter().any(|v| !v.is_finite()) {
            memory.clear();
            d = pg.iter().map(|v| -v).collect();
        }
        let mut t = if memory.is_empty() {
            (1.0 / max_abs(&d)).min(1.0)
        } else {
            1.0
        };
        let mut accepted = None;
        for _ in 0..50 {
            let mut xn: Vec<f64> = x.iter().zip(&d).map(|(xi, di)| xi + t * di).collect();
            project(&mut xn, &run.lo, &run.hi);
            if xn == x {
                break;
            }
            let step: Vec<f64> = xn.iter().zip(&x).map(|(a, b)| a - b).collect();
            let fn_ = run.f(&xn);
            if fn_.is_finite() && fn_ <= f + 1e-4 * dot(&g, &step) {
                accepted = Some((xn, fn_, step));
                break;
            }
            t *= 0.5;
        }
        let Some((xn, fn_, step)) = accepted else {
            if !memory.is_empty() {
                memory.clear();
                continue;
            }
            // Near a minimum the finite-difference gradient is dominated by rounding and no descent
            // step exists: that is convergence. Far from it (gradient still large, objective barely
            // reduced), the objective is not smooth: let Nelder–Mead take over.
            let reduced = f <= 1e-8 * run.start.abs();
            // At a minimum already (a rerun at an optimum: the gradient is small in absolute
            // terms, not relative to the start's), the first-order decrease the gradient promises
            // over the whole box (or a unit step per unbounded variable) is below what the
            // objective can resolve: that is convergence too, not a reason to leave L-BFGS.
            let promised: f64 = pg
                .iter()
                .zip(x.iter().zip(run.lo.iter().zip(&run.hi)))
                .map(|(g, (xi, (lo, hi)))| {
                    let width = hi - lo;
                    g.abs()
                        * if width.is_finite() {
                            width
                        } else {
                            xi.abs().max(1.0)
                        }
                })
                .sum();
            if f.is_finite() && promised <= 1e-6 * f.abs() {
                return (
                    Stop::Converged(format!(
                        "at a minimum: no descent step, the gradient promises {promised:.1e}, \
                         below 1e-6 of the objective"
                    )),
                    it - 1,
                    true,
                );
            }
            let smooth = f.is_finite() && (gnorm < 1e-6 * g0 || reduced);
            return (
                Stop::Converged("no descent step found".into()),
                it - 1,
                smooth,
            );
        };
        let gn = run.gradient(&xn, fn_);
        let dg: Vec<f64> = gn.iter().zip(&g).map(|(a, b)| a - b).collect();
        memory.push(step, dg);
        stalls = if f - fn_ <= 1e-6 * f.abs() {
            stalls + 1
        } else {
            0
        };
        x = xn;
        f = fn_;
        g = gn;
        report(&run.iteration(
            it,
            f,
            max_abs(&projected_gradient(&x, &g, &run.lo, &run.hi)),
            Method::Lbfgsb,
        ));
        if stalls >= 5 {
            return (Stop::Converged("no further decrease".into()), it, true);
        }
    }
    (Stop::MaxIterations, max_iter, true)
}

fn nelder_mead(
    run: &mut Run<'_>,
    x0: Vec<f64>,
    max_iter: usize,
    offset: usize,
    report: &mut dyn FnMut(&Iteration),
) -> (Stop, usize) {
    let points = initial_points(&x0, &run.lo, &run.hi);
    let mut simplex = Simplex {
        points: points.into_iter().map(|p| (p.clone(), run.f(&p))).collect(),
    };
    simplex.sort();
    let patience = 10 * x0.len().max(2);
    let (mut best, mut since) = (simplex.points[0].1, 0);
    for it in 1..=max_iter {
        if run.cancelled() {
            return (Stop::Cancelled, it - 1);
        }
        let (lo, hi) = (run.lo.clone(), run.hi.clone());
        simplex.step(&lo, &hi, &mut |p| run.f(p));
        report(&run.iteration(
            offset + it,
            simplex.points[0].1,
            f64::NAN,
            Method::NelderMead,
        ));
        let (spread, size) = simplex.spread();
        if spread <= 1e-15 * simplex.points[0].1.abs() && size <= 1e-12 {
            return (Stop::Converged("simplex collapsed".into()), it);
        }
        if simplex.points[0].1 < best * (1.0 - 1e-9) {
            (best, since) = (simplex.points[0].1, 0);
        } else {
            since += 1;
            if since >= patience {
                return (Stop::Converged("no further decrease".into()), it);
            }
        }
    }
    (Stop::MaxIterations, max_iter)
}
