//! The optimization panel (View › Optimization): the graph's stored optimization setup
//! (`cnets_engine::optimize::Setup`: variables with bounds, objective, penalties, method, iteration
//! limit), picked from the canvas and edited as document edits (undo, saved in the file's
//! `optimization` section), and runs of the engine's optimizer on a worker thread with a live
//! objective plot.
//!
//! Picking: right-click an unconnected input's label › *Optimize this value* (a number, an item of a
//! list, a coordinate of a point; bounds: a `param.number`'s slider range, `[0, 1]` for graph-mapper
//! handles, ±50 % of the value otherwise), right-click a number output › *Minimize this output* or
//! *Add as penalty*. A setup needs an objective and at least one variable to be stored in the file;
//! until both are picked the panel keeps a draft.
//!
//! A run works on a copy of the graph (cluster instances duplicated, so caches stay separate) and
//! never blocks the UI: *Stop* sets the evaluation context's cancel flag; when it ends, *Accept*
//! writes the optimized values into the document as one undo step, *Revert* discards them.

mod candidates;
mod panel;
mod run;

use cnets_engine::Value;
use cnets_engine::optimize::{Iteration, Method, Penalty, PenaltyKind, Setup, ValuePath, Variable};
use std::sync::Arc;

use crate::document::GraphDocument;

pub use candidates::{
    Candidate, MAX_CANDIDATES, default_bounds, variable_candidates, variable_menu, whole_input,
};
pub use panel::{current_value, value_label};
pub use run::{Finished, fold_warnings, isolated};

fn fmt(x: f64) -> String {
    crate::worker::format_number(x)
}

/// Whether an output may be the objective or a penalty: a single number (`ratios.table` is a table
/// of numbers: offered before issue 32, the run then failed with "list<list<number>>, not a
/// number").
pub fn minimizable(port: &cnets_engine::PortDef) -> bool {
    port.ty == cnets_engine::ValueType::Number && port.access == cnets_engine::Access::Item
}

/// Checks the bounds of the variables as typed: finite, and min ≤ max. A refusal names the
/// variable; the setup is then left as it was (bounds are never rewritten silently).
pub fn check_bounds(variables: &[Variable]) -> Result<(), String> {
    for v in variables {
        if !(v.min.is_finite() && v.max.is_finite()) {
            return Err(format!(
                "the bounds of {} must be numbers, got [{}, {}]",
                v.input, v.min, v.max
            ));
        }
        if v.min > v.max {
            return Err(format!(
                "the bounds of {} were not changed: min {} is above max {}",
                v.input,
                fmt(v.min),
                fmt(v.max)
            ));
        }
    }
    Ok(())
}

/// A setup still missing its objective or its variables (not stored in the file yet).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Draft {
    /// The objective, once picked.
    pub objective: Option<ValuePath>,
    /// Variables picked so far.
    pub variables: Vec<Variable>,
    /// Penalties picked so far.
    pub penalties: Vec<Penalty>,
    /// Constructions whose faces must stay (++)(++), picked so far.
    pub convex: Vec<String>,
}

/// The panel's state.
pub struct OptimizationPanel {
    /// Whether the panel is shown.
    pub open: bool,
    /// The setup being picked while it is incomplete.
    pub draft: Draft,
    /// The iterations reported by the current (or last) run.
    pub iterations: Vec<Iteration>,
    /// The last finished run, until accepted or reverted; or why it could not run.
    pub result: Option<Result<Finished, String>>,
    running: Option<run::Running>,
    /// The live view of the run: the document's graph with the best point so far applied.
    live: Option<run::Live>,
    wake: Arc<dyn Fn() + Send + Sync>,
}

impl OptimizationPanel {
    /// A closed panel; `wake` is called by the run's thread after each iteration.
    pub fn new(wake: Arc<dyn Fn() + Send + Sync>) -> Self {
        Self {
            open: false,
            draft: Draft::default(),
            iterations: Vec::new(),
            result: None,
            running: None,
            live: None,
            wake,
        }
    }

    /// Whether a run is in progress.
    pub fn running(&self) -> bool {
        self.running.is_some()
    }

    /// Forgets the draft and any result (another document was opened).
    pub fn reset(&mut self) {
        self.running = None;
        self.live = None;
        self.draft = Draft::default();
        self.iterations.clear();
        self.result = None;
    }

    /// Adds a variable (or updates its bounds); returns a status message.
    pub fn add_variable(
        &mut self,
        doc: &mut GraphDocument,
        variable: Variable,
        prepare: Option<Value>,
    ) -> Result<String, String> {
        let path = variable.input.clone();
        let message = format!(
            "optimization variable {path} in [{}, {}]",
            fmt(variable.min),
            fmt(variable.max)
        );
        if doc.meta.optimization.is_some() {
            doc.edit(None, |g, meta| {
                if let Some(v) = prepare {
                    g.set_value(&path.node, &path.port, v)
                        .map_err(|e| e.to_string())?;
                }
                let setup = meta.optimization.as_mut().ok_or("no setup")?;
                match setup.variables.iter_mut().find(|v| v.input == path) {
                    Some(v) => *v = variable,
                    None => setup.variables.push(variable),
                }
                Ok::<_, String>(())
            })?;
            return Ok(message);
        }
        if let Some(v) = prepare {
            doc.edit(None, |g, _| {
                g.set_value(&path.node, &path.port, v)
                    .map(|_| ())
                    .map_err(|e| e.to_string())
            })?;
        }
        match self.draft.variables.iter_mut().find(|v| v.input == path) {
            Some(v) => *v = variable,
            None => self.draft.variables.push(variable),
        }
        self.commit_draft(doc).map(|stored| {
            if stored {
                message
            } else {
                format!("{message}; now pick the objective (right-click a number output)")
            }
        })
    }

    /// Forgets the figures and the result of a run made for another objective than the stored
    /// setup's (they would be read as this objective's).
    pub fn clear_stale(&mut self, doc: &GraphDocument) {
        if self.running.is_some() {
            return;
        }
        let current = doc.meta.optimization.as_ref().map(|s| &s.objective);
        let stale = match &self.result {
            Some(Ok(f)) => current != Some(&f.setup.objective),
            _ => false,
        };
        if stale {
            self.iterations.clear();
            self.result = None;
        }
    }

    /// Makes `path` the objective; returns a status message.
    pub fn set_objective(
        &mut self,
        doc: &mut GraphDocument,
        path: ValuePath,
    ) -> Result<String, String> {
        let message = format!("optimization objective: minimize {path}");
        if self.running.is_none()
            && doc
                .meta
                .optimization
                .as_ref()
                .is_some_and(|s| s.objective != path)
        {
            // The figures shown were for the previous objective.
            self.iterations.clear();
            self.result = None;
        }
        if doc.meta.optimization.is_some() {
            doc.edit(None, |_, meta| {
                if let Some(s) = meta.optimization.as_mut() {
                    s.objective = path;
                }
                Ok::<_, String>(())
            })?;
            return Ok(message);
        }
        self.draft.objective = Some(path);
        self.commit_draft(doc).map(|stored| {
            if stored {
                message
            } else {
                format!("{message}; now pick variables (right-click a number input)")
            }
        })
    }

    /// Adds `path` as a penalty (kind `at_most`, target 0, weight 1: edit them in the panel).
    pub fn add_penalty(
        &mut self,
        doc: &mut GraphDocument,
        path: ValuePath,
    ) -> Result<String, String> {
        let penalty = Penalty {
            output: path.clone(),
            weight: 1.0,
            kind: PenaltyKind::AtMost,
            target: 0.0,
        };
        if doc.meta.optimization.is_some() {
            doc.edit(None, |_, meta| {
                if let Some(s) = meta.optimization.as_mut() {
                    s.penalties.push(penalty);
                }
                Ok::<_, String>(())
            })?;
        } else {
            self.draft.penalties.push(penalty);
        }
        Ok(format!("optimization penalty on {path}"))
    }

    /// Stores the draft in the document once it is complete (one undo step); returns whether it
    /// was stored.
    fn commit_draft(&mut self, doc: &mut GraphDocument) -> Result<bool, String> {
        let Some(objective) = self.draft.objective.clone() else {
            return Ok(false);
        };
        if self.draft.variables.is_empty() {
            return Ok(false);
        }
        let setup = Setup {
            objective,
            variables: self.draft.variables.clone(),
            penalties: self.draft.penalties.clone(),
            convex: self.draft.convex.clone(),
            method: Method::Auto,
            max_iter: 100,
        };
        doc.edit(None, |_, meta| {
            meta.optimization = Some(setup);
            Ok::<_, String>(())
        })?;
        self.draft = Draft::default();
        Ok(true)
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use cnets_engine::Graph;

    /// A number `n` in [0.1, 2], a graph mapper `m` and an arc of radius 4.
    pub(crate) fn graph() -> Graph {
        let registry = Arc::new(cnets_nodes::registry());
        let mut g = Graph::new(registry);
        g.add_node("n", "param.number").unwrap();
        g.set_value("n", "value", Value::Number(0.3)).unwrap();
        g.set_value("n", "min", Value::Number(0.1)).unwrap();
        g.set_value("n", "max", Value::Number(2.0)).unwrap();
        g.add_node("m", "mapper.graph").unwrap();
        g.add_node("arc", "curve.arc").unwrap();
        g.set_value("arc", "radius", Value::Number(4.0)).unwrap();
        g
    }

    #[test]
    fn a_draft_becomes_the_stored_setup_once_complete() {
        let mut doc = GraphDocument::from_parts(graph(), Default::default(), None);
        let mut panel = OptimizationPanel::new(Arc::new(|| {}));
        let var = Variable {
            input: ValuePath::parse("n.value").unwrap(),
            min: 0.1,
            max: 2.0,
        };
        let m = panel.add_variable(&mut doc, var, None).unwrap();
        assert!(m.contains("objective"), "{m}");
        assert!(doc.meta.optimization.is_none(), "incomplete: a draft");
        assert!(!doc.history.can_undo());
        panel
            .set_objective(&mut doc, ValuePath::parse("n.value").unwrap())
            .unwrap();
        let setup = doc.meta.optimization.clone().expect("stored");
        assert_eq!(setup.variables.len(), 1);
        assert_eq!(doc.history.undo_len(), 1);
        assert!(doc.to_ron().contains("optimization: ("));
        assert!(doc.undo());
        assert!(doc.meta.optimization.is_none());
    }

    /// A document of [`graph`] and a panel minimizing `n.value` over `n.value` in [0.1, 2].
    fn panel_minimizing_n() -> (GraphDocument, OptimizationPanel) {
        let mut doc = GraphDocument::from_parts(graph(), Default::default(), None);
        let mut panel = OptimizationPanel::new(Arc::new(|| {}));
        let var = Variable {
            input: ValuePath::parse("n.value").unwrap(),
            min: 0.1,
            max: 2.0,
        };
        panel.add_variable(&mut doc, var, None).unwrap();
        panel
            .set_objective(&mut doc, ValuePath::parse("n.value").unwrap())
            .unwrap();
        (doc, panel)
    }

    #[test]
    fn the_live_view_gives_the_best_point_once_per_point_and_ends_with_revert() {
        let (doc, mut panel) = panel_minimizing_n();
        assert!(!panel.shows_live_view());
        panel.start(&doc, None, Some(20)).unwrap();
        assert!(panel.wait(std::time::Duration::from_secs(60)));
        assert!(
            panel.shows_live_view(),
            "the result is shown until Accept or Revert"
        );
        let options = crate::preview::PreviewOptions::default();
        let g = panel.live_graph(options).expect("the result's picture");
        let best = match &panel.result {
            Some(Ok(f)) => f.outcome.x[0],
            _ => panic!("a finished run"),
        };
        assert_eq!(
            g.node("n").unwrap().value_of("value"),
            Some(&Value::Number(best))
        );
        assert!(
            (best - 0.1).abs() < 1e-6,
            "minimized to the lower bound: {best}"
        );
        assert_eq!(
            doc.graph.node("n").unwrap().value_of("value"),
            Some(&Value::Number(0.3)),
            "the document keeps its value"
        );
        assert!(
            panel.live_graph(options).is_none(),
            "the same point is not sent twice"
        );
        let mut other = options;
        other.color_mode = crate::preview::ColorMode::Planarity;
        assert!(
            panel.live_graph(other).is_some(),
            "new display options: sent again"
        );
        panel.revert();
        assert!(!panel.shows_live_view() && panel.live_graph(options).is_none());
    }

    #[test]
    fn bounds_are_refused_when_min_is_above_max_never_rewritten() {
        let var = |min: f64, max: f64| Variable {
            input: ValuePath::parse("n.value").unwrap(),
            min,
            max,
        };
        assert!(check_bounds(&[var(0.1, 2.0), var(0.5, 0.5)]).is_ok());
        let e = check_bounds(&[var(0.1, 2.0), var(1.2, 0.95)]).unwrap_err();
        assert!(e.contains("min 1.2 is above max 0.95"), "{e}");
        assert!(e.contains("n.value"), "{e}");
        assert!(check_bounds(&[var(f64::NAN, 1.0)]).is_err());
        assert!(check_bounds(&[var(0.0, f64::INFINITY)]).is_err());
    }

    #[test]
    fn only_single_number_outputs_can_be_minimized() {
        let registry = cnets_nodes::registry();
        let port = |id: &str, name: &str| {
            let def = registry.get(id).unwrap();
            let k = def.output_index(name).unwrap();
            minimizable(&def.outputs[k])
        };
        assert!(port("measure.surface_distance", "symmetric"));
        assert!(port("param.number", "value"));
        assert!(!port("list.table", "table"), "a table of numbers");
        assert!(!port("param.series", "values"), "a list of numbers");
        assert!(!port("cnets.construct", "mesh"));
    }

    #[test]
    fn faces_left_not_plus_plus_are_a_warning() {
        // The correction gallery graph: the same folding inputs uncorrected and repaired.
        let registry = Arc::new(cnets_nodes::registry());
        let path =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../graphs/correction.ron");
        let doc = cnets_engine::file::load_file(&path, &registry).unwrap();
        let warnings = fold_warnings(&doc.graph, &cnets_engine::NodeContext::default());
        assert_eq!(warnings.len(), 1, "{warnings:?}");
        assert!(warnings[0].starts_with("'nets': "), "{warnings:?}");
        assert!(
            warnings[0].contains("faces are not (++)(++)"),
            "{warnings:?}"
        );
        // The editor's default net (every face (++)(++)): no warning.
        let mut g = graph();
        g.add_node("net", "cnets.construct").unwrap();
        g.add_node("d", "curve.arc").unwrap();
        g.add_node("gen", "curve.arc").unwrap();
        for (node, input, value) in [
            ("d", "radius", Value::Number(6.0)),
            ("d", "end", Value::Number(150.0)),
            ("d", "count", Value::Integer(19)),
            (
                "gen",
                "centre",
                Value::Point(glam::DVec3::new(8.0, 0.0, 0.0)),
            ),
            ("gen", "radius", Value::Number(2.0)),
            ("gen", "start", Value::Number(100.0)),
            ("gen", "end", Value::Number(260.0)),
            ("gen", "count", Value::Integer(11)),
            (
                "gen",
                "plane",
                Value::Plane(Arc::new(cnets_geometry::Plane::ZX)),
            ),
        ] {
            g.set_value(node, input, value).unwrap();
        }
        g.connect("d", "curve", "net", "directrix").unwrap();
        g.connect("gen", "curve", "net", "generatrix").unwrap();
        assert!(fold_warnings(&g, &cnets_engine::NodeContext::default()).is_empty());
    }

    #[test]
    fn a_new_objective_clears_the_previous_runs_figures() {
        let (mut doc, mut panel) = panel_minimizing_n();
        let figure = Iteration {
            iteration: 3,
            objective: 0.25,
            gradient: 1.0,
            evaluations: 7,
            node_runs: 9,
            method: Method::Lbfgsb,
            best: vec![0.5],
        };
        panel.iterations.push(figure.clone());
        // The same objective again keeps them; another one clears them.
        panel
            .set_objective(&mut doc, ValuePath::parse("n.value").unwrap())
            .unwrap();
        assert_eq!(panel.iterations, vec![figure]);
        panel
            .set_objective(&mut doc, ValuePath::parse("m.y").unwrap())
            .unwrap();
        assert!(panel.iterations.is_empty());
        assert!(panel.result.is_none());
    }
}
