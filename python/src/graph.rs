//! `cnets.Graph`: a graph file loaded with the engine (as `cnets run` loads it), edited by
//! `set("node.input", value)` and evaluated incrementally by one evaluator kept with it.

use std::collections::HashSet;
use std::path::{Path, PathBuf};

use cnets_engine::file::{Document, GraphMeta, save_file};
use cnets_engine::{Evaluator, Graph, NodeFlag, NodeResult};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::settings::Settings;
use crate::{args, convert, error, warn};

/// A graph file loaded for evaluation. `Graph.load(path)`, then `set("node.input", value)` and
/// `run()`; after an edit only what depends on it runs again (`last_run_nodes`).
#[pyclass(name = "Graph", module = "cnets")]
pub struct PyGraph {
    graph: Graph,
    meta: GraphMeta,
    evaluator: Evaluator,
    path: PathBuf,
    settings: Settings,
    /// The nodes that ran in the last evaluation (the others were up to date).
    last_run: Vec<String>,
    /// The nodes the last evaluation verified: the requested ones and everything they depend on
    /// (`None`: every node). Failures are reported for these only.
    evaluated: Option<HashSet<usize>>,
    files: Vec<PathBuf>,
    warnings: Vec<String>,
}

impl PyGraph {
    fn from_document(doc: Document, path: PathBuf, settings: Settings) -> Self {
        Self {
            warnings: doc.warnings.iter().map(ToString::to_string).collect(),
            graph: doc.graph,
            meta: doc.meta,
            evaluator: Evaluator::new(),
            path,
            settings,
            last_run: Vec::new(),
            evaluated: None,
            files: Vec::new(),
        }
    }

    /// `"node.input"` split and checked: the node's index and the input's index.
    fn target(&self, target: &str) -> PyResult<(String, usize)> {
        let (id, input) = cnets_host::split_target(target)
            .ok_or_else(|| error(format!("'{target}': expected \"<node>.<input>\"")))?;
        let def = &self
            .graph
            .node(id)
            .ok_or_else(|| error(format!("'{target}': no node '{id}'")))?
            .def;
        let k = def.input_index(input).ok_or_else(|| {
            error(format!(
                "'{target}': {}",
                cnets_host::inputs::unknown_input(def, input)
            ))
        })?;
        Ok((id.to_string(), k))
    }

    /// Evaluates the requested nodes (all when `None`) with the GIL released, then issues the
    /// warnings of the nodes that ran as `cnets.CnetsWarning`s.
    fn evaluate(&mut self, py: Python<'_>, ids: Option<&[String]>) -> PyResult<()> {
        let request: Vec<_> = match ids {
            None => self.graph.nodes().map(|(k, _)| k).collect(),
            Some(ids) => ids
                .iter()
                .map(|id| {
                    self.graph
                        .index(id)
                        .map_err(|_| error(format!("nodes: no node '{id}'")))
                })
                .collect::<PyResult<Vec<_>>>()?,
        };
        let exports = self.graph.nodes().any(|(_, n)| {
            n.enabled
                && (n.def.has_flag(NodeFlag::Export)
                    || cnets_engine::cluster::Cluster::of(&n.def)
                        .is_some_and(|c| cnets_host::writes_files(&c.template)))
        });
        let base = self.path.parent().map(Path::to_path_buf);
        let before: Vec<u64> = self
            .graph
            .nodes()
            .map(|(_, n)| self.evaluator.runs(&self.graph, &n.id))
            .collect();
        let (graph, evaluator, settings) = (&self.graph, &mut self.evaluator, &self.settings);
        let outcome = py.detach(|| {
            let ctx = settings.context(exports, base)?;
            Ok::<_, String>(evaluator.evaluate(graph, &request, &ctx, &mut |_, _| {}))
        });
        outcome.map_err(error)?;
        self.evaluated = ids.map(|_| {
            let mut seen = HashSet::new();
            let mut stack = request.clone();
            while let Some(k) = stack.pop() {
                if seen.insert(k.index()) {
                    stack.extend(self.graph.sources(k));
                }
            }
            seen
        });
        self.last_run = self
            .graph
            .nodes()
            .zip(before)
            .filter(|((_, n), runs)| self.evaluator.runs(&self.graph, &n.id) > *runs)
            .map(|((_, n), _)| n.id.clone())
            .collect();
        self.files = self
            .graph
            .nodes()
            .filter(|(_, n)| self.last_run.contains(&n.id))
            .filter_map(|(k, _)| self.evaluator.result_at(&self.graph, k))
            .filter_map(NodeResult::outputs)
            .flat_map(|o| o.files.iter().cloned())
            .collect();
        for id in &self.last_run {
            let Some(node) = self.graph.node(id) else {
                continue;
            };
            if let Some(outputs) = self
                .evaluator
                .result(&self.graph, id)
                .and_then(NodeResult::outputs)
            {
                for w in &outputs.warnings {
                    warn(py, &format!("node '{id}' ({}): {w}", node.def.id))?;
                }
            }
        }
        Ok(())
    }

    fn outputs_dict<'py>(&self, py: Python<'py>, id: &str) -> PyResult<Option<Bound<'py, PyDict>>> {
        let node = self
            .graph
            .node(id)
            .ok_or_else(|| error(format!("no node '{id}'")))?;
        let Some(outputs) = self
            .evaluator
            .result(&self.graph, id)
            .and_then(NodeResult::outputs)
        else {
            return Ok(None);
        };
        let d = PyDict::new(py);
        for (k, port) in node.def.outputs.iter().enumerate() {
            if let Some(value) = outputs.computed(k) {
                d.set_item(
                    port.name.as_ref(),
                    convert::to_py_typed(py, value, &port.ty)?,
                )?;
            }
        }
        Ok(Some(d))
    }

    /// Messages of the nodes that failed or were blocked, by node id.
    fn failures(&self) -> Vec<(String, String)> {
        self.graph
            .nodes()
            .filter(|(k, _)| {
                self.evaluated
                    .as_ref()
                    .is_none_or(|e| e.contains(&k.index()))
            })
            .filter_map(|(k, n)| {
                let result = self.evaluator.result_at(&self.graph, k)?;
                match result {
                    NodeResult::Ok(_) | NodeResult::Disabled => None,
                    r => Some((
                        n.id.clone(),
                        format!(
                            "node '{}' ({}): {}",
                            n.id,
                            n.def.id,
                            r.error().as_deref().unwrap_or("")
                        ),
                    )),
                }
            })
            .collect()
    }
}

#[pymethods]
impl PyGraph {
    /// Loads a graph file. `allow_read`: further folders nodes and cluster files may read from
    /// (besides the file's own folder); `max_memory`: the memory budget of an evaluation, bytes or
    /// a size such as `"2G"` (default: half the machine's memory); `library`: folders searched
    /// for cluster graph files; `out`: the folder export nodes write into (default `out` in the
    /// working folder). A file that does not load raises `CnetsError` with every problem as
    /// `file:line:col: message`, one per line.
    #[staticmethod]
    #[pyo3(signature = (path, allow_read=None, max_memory=None, library=None, out=None))]
    fn load(
        path: &Bound<'_, PyAny>,
        allow_read: Option<&Bound<'_, PyAny>>,
        max_memory: Option<&Bound<'_, PyAny>>,
        library: Option<&Bound<'_, PyAny>>,
        out: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let path = args::path(path, "path")?;
        let settings = Settings::new(max_memory, allow_read, library, out, "")?;
        let doc = settings
            .session()
            .load_graph(&path, &[])
            .map_err(|e| error(e.to_string()))?;
        Ok(Self::from_document(doc, path, settings))
    }

    /// Sets the literal value of an input, `target` = `"node.input"`. The value is converted to
    /// the port's type; a wrong node, input or type raises `CnetsError`, and so does an input
    /// fed by a wire (its value comes from the wire: set the source instead). A value the node
    /// then changes (a slider clamping to its range) is reported by a `CnetsWarning` when it
    /// runs.
    fn set(&mut self, target: &Bound<'_, PyAny>, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let target = args::text(target, "target")?;
        let (id, k) = self.target(&target)?;
        let index = self.graph.index(&id).map_err(|e| error(e.to_string()))?;
        let node = self.graph.node_at(index).expect("indexed node");
        if let Some((from, wire)) = self
            .graph
            .wires_into(index)
            .into_iter()
            .find(|(_, w)| w.to_input == k)
        {
            let source = self.graph.node_at(from).expect("wired node");
            return Err(error(format!(
                "'{target}' is wired from '{}.{}': its value comes from the wire, so setting it \
                 would change nothing; set an input of '{}' instead",
                source.id, source.def.outputs[wire.from_output].name, source.id
            )));
        }
        let def = node.def.clone();
        let port = &def.inputs[k];
        let budget = self.settings.budget();
        let v = convert::to_value(value, &port.ty, &budget)
            .map_err(|e| error(format!("'{target}' ({}): {e}", port.type_name())))?;
        self.graph
            .set_value(&id, &port.name, v)
            .map_err(|e| error(format!("'{target}': {e}")))?;
        Ok(())
    }

    /// Removes the literal value of an input (`"node.input"`): it falls back to the port's default.
    fn unset(&mut self, target: &Bound<'_, PyAny>) -> PyResult<()> {
        let target = args::text(target, "target")?;
        let (id, k) = self.target(&target)?;
        let input = self.graph.node(&id).expect("checked node").def.inputs[k]
            .name
            .clone();
        self.graph
            .clear_value(&id, &input)
            .map_err(|e| error(format!("'{target}': {e}")))?;
        Ok(())
    }

    /// The literal value of an input (`"node.input"`), or `None` when it has none.
    fn get<'py>(&self, py: Python<'py>, target: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        let target = args::text(target, "target")?;
        let (id, k) = self.target(&target)?;
        let node = self.graph.node(&id).expect("checked node");
        match node.value(k) {
            Some(v) => convert::to_py_typed(py, v, &node.def.inputs[k].ty),
            None => Ok(py.None().into_bound(py)),
        }
    }

    /// Evaluates the graph (only what changed since the last run) and returns the outputs of
    /// the nodes evaluated now that succeeded: `{node_id: {output: value}}`. `nodes` (a node id
    /// or a list of them) limits the evaluation to those nodes and what they depend on, and the
    /// result to those nodes; without it every node is evaluated and returned. With `check` (the
    /// default) a failed node among them raises `CnetsError` naming every failure; otherwise see
    /// `errors`. Warnings of the nodes that ran are issued as `cnets.CnetsWarning`.
    #[pyo3(signature = (nodes=None, check=None))]
    fn run<'py>(
        &mut self,
        py: Python<'py>,
        nodes: Option<&Bound<'py, PyAny>>,
        check: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let ids = args::texts(nodes, "nodes")?;
        let check = match check.filter(|c| !c.is_none()) {
            Some(c) => args::flag(c, "check")?,
            None => true,
        };
        self.evaluate(py, ids.as_deref())?;
        if check {
            let failures = self.failures();
            let failed: Vec<&str> = failures
                .iter()
                .filter(|(id, _)| {
                    self.evaluator
                        .result(&self.graph, id)
                        .is_some_and(NodeResult::is_failure)
                })
                .map(|(_, m)| m.as_str())
                .collect();
            if !failed.is_empty() {
                return Err(error(failed.join("\n")));
            }
        }
        let result = PyDict::new(py);
        let returned: Vec<String> = match ids {
            Some(ids) => ids,
            None => self.graph.nodes().map(|(_, n)| n.id.clone()).collect(),
        };
        for id in returned {
            if let Some(d) = self.outputs_dict(py, &id)? {
                result.set_item(id, d)?;
            }
        }
        Ok(result)
    }

    /// The outputs of one node (`{output: value}`), evaluating it first when needed; a node that
    /// failed or is blocked raises `CnetsError` with its message.
    fn outputs<'py>(
        &mut self,
        py: Python<'py>,
        node_id: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let node_id = args::text(node_id, "node_id")?;
        if self.graph.node(&node_id).is_none() {
            return Err(error(format!("node_id: no node '{node_id}'")));
        }
        self.evaluate(py, Some(std::slice::from_ref(&node_id)))?;
        match self.outputs_dict(py, &node_id)? {
            Some(d) => Ok(d),
            None => {
                let message = self
                    .evaluator
                    .result(&self.graph, &node_id)
                    .and_then(NodeResult::error)
                    .map_or_else(|| "not evaluated".to_string(), |m| m.into_owned());
                Err(error(format!("node '{node_id}': {message}")))
            }
        }
    }

    /// Runs the graph file's optimization setup (as `cnets optimize`) and keeps the result's
    /// values in this graph. `max_iter`: the iteration limit (default: the setup's); `method`:
    /// `"auto"`, `"lbfgsb"` or `"nelder_mead"`; `convex`: a construction's node id or a list of
    /// them whose faces must stay (++)(++) for the whole run (added to the setup's `convex`).
    /// Returns a dict: `start`, `objective`, `iterations`, `evaluations`, `gradients`,
    /// `exact_gradients`, `finite_difference_nodes`, `not_convex` (`{node: faces}` for every
    /// construction on the path), `notes`, `stop` and `variables` (`{"node.input[i]": value}`).
    #[pyo3(signature = (max_iter=None, method=None, convex=None))]
    fn optimize<'py>(
        &mut self,
        py: Python<'py>,
        max_iter: Option<&Bound<'py, PyAny>>,
        method: Option<&Bound<'py, PyAny>>,
        convex: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        use cnets_engine::optimize::{self, Method, Options, Stop};
        let mut setup = self.meta.optimization.clone().ok_or_else(|| {
            error("this graph file has no optimization setup (an `optimization: (…)` section)")
        })?;
        for id in args::texts(convex, "convex")?.unwrap_or_default() {
            if !setup.convex.contains(&id) {
                setup.convex.push(id);
            }
        }
        let mut options = Options::default();
        if let Some(m) = max_iter.filter(|m| !m.is_none()) {
            let n = args::count(m, "max_iter")?;
            if n == 0 {
                return Err(error("max_iter: expected a positive integer, got 0"));
            }
            options.max_iter = Some(n);
        }
        if let Some(m) = method.filter(|m| !m.is_none()) {
            let name = args::text(m, "method")?;
            options.method = Some(Method::parse(&name).ok_or_else(|| {
                error(format!(
                    "method: expected \"auto\", \"lbfgsb\" or \"nelder_mead\", got '{name}'"
                ))
            })?);
        }
        let base = self.path.parent().map(Path::to_path_buf);
        let (graph, settings) = (&self.graph, &self.settings);
        let outcome = py
            .detach(|| {
                let ctx = settings.context(false, base)?;
                optimize::optimize(graph, &setup, &options, &ctx, &mut |_| {})
                    .map_err(|e| e.to_string())
            })
            .map_err(error)?;
        let d = PyDict::new(py);
        d.set_item("start", outcome.start)?;
        d.set_item("objective", outcome.objective)?;
        d.set_item("iterations", outcome.iterations)?;
        d.set_item("evaluations", outcome.evaluations)?;
        d.set_item("gradients", outcome.gradients)?;
        d.set_item("exact_gradients", outcome.exact_gradients)?;
        d.set_item(
            "finite_difference_nodes",
            outcome.finite_difference_nodes.clone(),
        )?;
        let folded = PyDict::new(py);
        for (node, n) in &outcome.not_convex {
            folded.set_item(node, *n)?;
        }
        d.set_item("not_convex", folded)?;
        d.set_item("notes", outcome.notes.clone())?;
        d.set_item(
            "stop",
            match &outcome.stop {
                Stop::Converged(why) => format!("converged ({why})"),
                Stop::MaxIterations => "iteration limit reached".to_string(),
                Stop::Cancelled => "cancelled".to_string(),
            },
        )?;
        let variables = PyDict::new(py);
        for (v, x) in outcome.variables.iter().zip(&outcome.x) {
            variables.set_item(v.input.to_string(), *x)?;
        }
        d.set_item("variables", variables)?;
        // The result's values are this graph's from now on (evaluated afresh).
        self.graph = outcome.graph;
        self.evaluator = Evaluator::new();
        Ok(d)
    }

    /// Drags vertex `vertex` = (i, j) (row along the generatrix, column along the directrix) of
    /// node `node`'s quad mesh to the point `to`, as the editor's Drag net tool and `cnets drag`
    /// do: the free inputs (`free`: `"node.input"` names; default every slider, point list,
    /// mapper handle and list of numbers upstream) are solved so the vertex reaches the point,
    /// the `pins` ((i, j) pairs) stay where they are and the faces stay (++)(++). The new values
    /// are kept in this graph. Returns a dict: `reached` (x, y, z), `distance_left`, `pin_drift`,
    /// `not_convex` (`{node: faces}`), `changes` (`[{"input", "old", "new"}]`), `iterations` and
    /// `evaluations`. `item`: which net when the node's output is a list of them.
    #[pyo3(signature = (node, vertex, to, pins=None, free=None, item=None))]
    #[allow(clippy::too_many_arguments)] // Python's keyword arguments, one parameter each
    fn drag<'py>(
        &mut self,
        py: Python<'py>,
        node: &Bound<'py, PyAny>,
        vertex: &Bound<'py, PyAny>,
        to: &Bound<'py, PyAny>,
        pins: Option<&Bound<'py, PyAny>>,
        free: Option<&Bound<'py, PyAny>>,
        item: Option<usize>,
    ) -> PyResult<Bound<'py, PyDict>> {
        use cnets_engine::optimize::drag::{DragRequest, default_free, drag};
        use cnets_engine::optimize::{ValuePath, Variable};
        let node = args::text(node, "node")?;
        let pair = |v: &Bound<'py, PyAny>, name: &str| -> PyResult<(usize, usize)> {
            let items: Vec<Bound<'py, PyAny>> = v
                .try_iter()
                .and_then(|it| it.collect::<PyResult<Vec<_>>>())
                .map_err(|_| {
                    error(format!(
                        "{name}: expected (i, j), got {}",
                        args::describe(v)
                    ))
                })?;
            match items.as_slice() {
                [i, j] => Ok((args::count(i, name)?, args::count(j, name)?)),
                _ => Err(error(format!(
                    "{name}: expected (i, j), got {}",
                    args::describe(v)
                ))),
            }
        };
        let vertex = pair(vertex, "vertex")?;
        let to: Vec<f64> = to
            .try_iter()
            .and_then(|it| {
                it.map(|x| x?.extract::<f64>())
                    .collect::<PyResult<Vec<_>>>()
            })
            .map_err(|_| {
                error(format!(
                    "to: expected (x, y, z), got {}",
                    args::describe(to)
                ))
            })?;
        let [x, y, z] = to.as_slice() else {
            return Err(error("to: expected three numbers (x, y, z)"));
        };
        let mut request = DragRequest::new(node.clone(), vertex, [*x, *y, *z].into());
        request.item = item;
        if let Some(pins) = pins.filter(|p| !p.is_none()) {
            for p in pins
                .try_iter()
                .map_err(|_| error("pins: expected a list of (i, j)"))?
            {
                request.pins.push(pair(&p?, "pins")?);
            }
        }
        if let Some(names) = args::texts(free, "free")? {
            let all = default_free(&self.graph, &node).map_err(|e| error(e.to_string()))?;
            let mut chosen = Vec::new();
            for f in names {
                let path = ValuePath::parse(&f).map_err(|e| error(format!("free: {e}")))?;
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
            request.free = Some(chosen);
        }
        let base = self.path.parent().map(Path::to_path_buf);
        let (graph, settings) = (&self.graph, &self.settings);
        let report = py
            .detach(|| {
                let ctx = settings.context(false, base)?;
                drag(graph, &request, &ctx).map_err(|e| e.to_string())
            })
            .map_err(error)?;
        let d = PyDict::new(py);
        d.set_item("reached", report.reached.to_array().to_vec())?;
        d.set_item("distance_left", report.distance_left)?;
        d.set_item("pin_drift", report.pin_drift)?;
        let folded = PyDict::new(py);
        for (n, count) in &report.not_convex {
            folded.set_item(n, *count)?;
        }
        d.set_item("not_convex", folded)?;
        let changes = pyo3::types::PyList::empty(py);
        for c in &report.changes {
            let item = PyDict::new(py);
            item.set_item("input", c.input.to_string())?;
            item.set_item("old", c.old)?;
            item.set_item("new", c.new)?;
            changes.append(item)?;
        }
        d.set_item("changes", changes)?;
        d.set_item("iterations", report.iterations)?;
        d.set_item("evaluations", report.evaluations)?;
        self.graph = report.graph;
        self.evaluator = Evaluator::new();
        Ok(d)
    }

    /// Saves the graph (with the values set) as a graph file, atomically.
    fn save(&self, path: &Bound<'_, PyAny>) -> PyResult<()> {
        let path = args::path(path, "path")?;
        save_file(&path, &self.graph, &self.meta)
            .map_err(|e| error(format!("{}: cannot save: {e}", path.display())))
    }

    /// The ids of the nodes that ran in the last `run` / `outputs` (unchanged ones did not).
    #[getter]
    fn last_run_nodes(&self) -> Vec<String> {
        self.last_run.clone()
    }

    /// Node ids in file order.
    #[getter]
    fn nodes(&self) -> Vec<String> {
        self.graph.nodes().map(|(_, n)| n.id.clone()).collect()
    }

    /// The node type id of a node.
    fn node_type(&self, node_id: &Bound<'_, PyAny>) -> PyResult<String> {
        let node_id = args::text(node_id, "node_id")?;
        self.graph
            .node(&node_id)
            .map(|n| n.def.id.to_string())
            .ok_or_else(|| error(format!("node_id: no node '{node_id}'")))
    }

    /// Messages of the nodes that failed or were blocked in the last evaluation, by node id.
    #[getter]
    fn errors(&self) -> Vec<(String, String)> {
        self.failures()
    }

    /// Files the export nodes wrote in the last run.
    #[getter]
    fn files(&self) -> Vec<PathBuf> {
        self.files.clone()
    }

    /// Problems found while loading that did not stop it (e.g. a required input not set).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.warnings.clone()
    }

    /// The graph file's path.
    #[getter]
    fn path(&self) -> PathBuf {
        self.path.clone()
    }

    /// The folder export nodes write into (`None`: `out` in the working folder).
    #[getter]
    fn get_out(&self) -> Option<PathBuf> {
        self.settings.out.clone()
    }

    /// Sets the folder export nodes write into.
    #[setter]
    fn set_out(&mut self, out: Option<&Bound<'_, PyAny>>) -> PyResult<()> {
        self.settings.out = args::opt_path(out, "out")?;
        Ok(())
    }

    /// Milliseconds a node took on its last run.
    fn time_ms(&self, node_id: &Bound<'_, PyAny>) -> PyResult<Option<f64>> {
        let node_id = args::text(node_id, "node_id")?;
        if self.graph.node(&node_id).is_none() {
            return Err(error(format!("node_id: no node '{node_id}'")));
        }
        Ok(self
            .evaluator
            .time(&self.graph, &node_id)
            .map(|t| t.as_secs_f64() * 1e3))
    }

    fn __repr__(&self) -> String {
        format!(
            "Graph({:?}, {} nodes)",
            self.path.display().to_string(),
            self.graph.node_count()
        )
    }
}
