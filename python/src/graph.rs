//! `cnets.Graph`: a graph file loaded with the engine (as `cnets run` loads it), edited by
//! `set("node.input", value)` and evaluated incrementally by one evaluator kept with it.

use std::path::{Path, PathBuf};

use cnets_engine::file::{Document, GraphMeta, save_file};
use cnets_engine::{Evaluator, Graph, NodeFlag, NodeResult};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::settings::Settings;
use crate::{convert, error};

/// A graph file loaded for evaluation. `Graph.load(path)`, then `set("node.input", value)` and
/// `run()`; after an edit only what depends on it runs again (`last_run_nodes`).
#[pyclass(name = "Graph", module = "cnets")]
pub struct PyGraph {
    graph: Graph,
    meta: GraphMeta,
    evaluator: Evaluator,
    path: PathBuf,
    settings: Settings,
    /// Run counts of every node before the last run (to tell which ran).
    last_run: Vec<String>,
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
            files: Vec::new(),
        }
    }

    /// Evaluates the requested nodes (all when empty) with the GIL released.
    fn evaluate(&mut self, py: Python<'_>, ids: &[String]) -> PyResult<()> {
        let request = if ids.is_empty() {
            self.graph.nodes().map(|(k, _)| k).collect()
        } else {
            ids.iter()
                .map(|id| self.graph.index(id).map_err(|e| error(e.to_string())))
                .collect::<PyResult<Vec<_>>>()?
        };
        let exports = self
            .graph
            .nodes()
            .any(|(_, n)| n.def.has_flag(NodeFlag::Export) && n.enabled);
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
        for (port, value) in node.def.outputs.iter().zip(&outputs.values) {
            d.set_item(port.name.as_ref(), convert::to_py(py, value)?)?;
        }
        Ok(Some(d))
    }

    /// Messages of the nodes that failed or were blocked, by node id.
    fn failures(&self) -> Vec<(String, String)> {
        self.graph
            .nodes()
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
                            r.error().unwrap_or("")
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
        path: PathBuf,
        allow_read: Option<Vec<PathBuf>>,
        max_memory: Option<&Bound<'_, PyAny>>,
        library: Option<Vec<PathBuf>>,
        out: Option<PathBuf>,
    ) -> PyResult<Self> {
        let settings = Settings::new(max_memory, allow_read, library, out)?;
        let doc = cnets_host::load_graph(&path, &settings.library, &[], &settings.allow_read)
            .map_err(|e| error(e.to_string()))?;
        Ok(Self::from_document(doc, path, settings))
    }

    /// Sets the literal value of an input, `target` = `"node.input"`. The value is converted to
    /// the port's type; a wrong node, input or type raises `CnetsError`.
    fn set(&mut self, target: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let (id, input) = cnets_host::split_target(target)
            .ok_or_else(|| error(format!("'{target}': expected \"<node>.<input>\"")))?;
        let node = self
            .graph
            .node(id)
            .ok_or_else(|| error(format!("'{target}': no node '{id}'")))?;
        let def = node.def.clone();
        let k = def.input_index(input).ok_or_else(|| {
            error(format!(
                "'{target}': {}",
                cnets_host::inputs::unknown_input(&def, input)
            ))
        })?;
        let port = &def.inputs[k];
        let v = convert::to_value(value, &port.ty)
            .map_err(|e| error(format!("'{target}' ({}): {e}", port.type_name())))?;
        self.graph
            .set_value(id, input, v)
            .map_err(|e| error(format!("'{target}': {e}")))?;
        Ok(())
    }

    /// Removes the literal value of an input (`"node.input"`): it falls back to the port's default.
    fn unset(&mut self, target: &str) -> PyResult<()> {
        let (id, input) = cnets_host::split_target(target)
            .ok_or_else(|| error(format!("'{target}': expected \"<node>.<input>\"")))?;
        self.graph
            .clear_value(id, input)
            .map_err(|e| error(format!("'{target}': {e}")))?;
        Ok(())
    }

    /// The literal value of an input (`"node.input"`), or `None` when it has none.
    fn get<'py>(&self, py: Python<'py>, target: &str) -> PyResult<Bound<'py, PyAny>> {
        let (id, input) = cnets_host::split_target(target)
            .ok_or_else(|| error(format!("'{target}': expected \"<node>.<input>\"")))?;
        let node = self
            .graph
            .node(id)
            .ok_or_else(|| error(format!("'{target}': no node '{id}'")))?;
        if node.def.input_index(input).is_none() {
            return Err(error(format!(
                "'{target}': {}",
                cnets_host::inputs::unknown_input(&node.def, input)
            )));
        }
        match node.value_of(input) {
            Some(v) => convert::to_py(py, v),
            None => Ok(py.None().into_bound(py)),
        }
    }

    /// Evaluates the graph (only what changed since the last run) and returns the outputs of
    /// every node that ran successfully: `{node_id: {output: value}}`. With `check` (the default)
    /// a failed node raises `CnetsError` naming every failure; otherwise see `errors`. `nodes`
    /// limits the evaluation to those nodes and what they depend on.
    #[pyo3(signature = (nodes=None, check=true))]
    fn run<'py>(
        &mut self,
        py: Python<'py>,
        nodes: Option<Vec<String>>,
        check: bool,
    ) -> PyResult<Bound<'py, PyDict>> {
        let ids = nodes.unwrap_or_default();
        self.evaluate(py, &ids)?;
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
        let ids: Vec<String> = self.graph.nodes().map(|(_, n)| n.id.clone()).collect();
        for id in ids {
            if let Some(d) = self.outputs_dict(py, &id)? {
                result.set_item(id, d)?;
            }
        }
        Ok(result)
    }

    /// The outputs of one node (`{output: value}`), evaluating it first when needed; a node that
    /// failed or is blocked raises `CnetsError` with its message.
    fn outputs<'py>(&mut self, py: Python<'py>, node_id: &str) -> PyResult<Bound<'py, PyDict>> {
        if self.graph.node(node_id).is_none() {
            return Err(error(format!("no node '{node_id}'")));
        }
        self.evaluate(py, &[node_id.to_string()])?;
        match self.outputs_dict(py, node_id)? {
            Some(d) => Ok(d),
            None => {
                let message = self
                    .evaluator
                    .result(&self.graph, node_id)
                    .and_then(NodeResult::error)
                    .unwrap_or("not evaluated")
                    .to_string();
                Err(error(format!("node '{node_id}': {message}")))
            }
        }
    }

    /// Saves the graph (with the values set) as a graph file, atomically.
    fn save(&self, path: PathBuf) -> PyResult<()> {
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
    fn node_type(&self, node_id: &str) -> PyResult<String> {
        self.graph
            .node(node_id)
            .map(|n| n.def.id.to_string())
            .ok_or_else(|| error(format!("no node '{node_id}'")))
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
    fn set_out(&mut self, out: Option<PathBuf>) {
        self.settings.out = out;
    }

    /// Milliseconds a node took on its last run.
    fn time_ms(&self, node_id: &str) -> Option<f64> {
        self.evaluator
            .time(&self.graph, node_id)
            .map(|t| t.as_secs_f64() * 1e3)
    }

    fn __repr__(&self) -> String {
        format!(
            "Graph({:?}, {} nodes)",
            self.path.display().to_string(),
            self.graph.node_count()
        )
    }
}
