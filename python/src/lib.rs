//! `cnets._cnets`: the extension module of the `cnets` Python package. It evaluates node types
//! through the node registry (as `cnets eval` does) and graph files through the engine's evaluator
//! (as `cnets run` does); the shared front-end logic is in `cnets-host`. The pure-Python package
//! (`python/cnets/`) builds the public API on it.
//!
//! Errors are `cnets.CnetsError` (a `ValueError`) with the engine's message; the evaluation runs
//! with the GIL released; panics in nodes are caught by the engine, and pyo3 turns any other panic
//! into a Python exception.

mod args;
mod convert;
mod graph;
mod settings;

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

use cnets_engine::{Registry, Value};
use numpy::PyArray1;
use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::settings::Settings;

create_exception!(
    cnets,
    CnetsWarning,
    pyo3::exceptions::PyUserWarning,
    "A warning of a node that ran but reported something (a value clamped to a slider's range, a \
     wrap dropped…)."
);

create_exception!(
    cnets,
    CnetsError,
    PyValueError,
    "An error of cnets: a node that failed, a graph file that does not load (file:line:col), an \
     unknown node type, input or value."
);

create_exception!(
    cnets,
    NoInterfaceError,
    CnetsError,
    "A graph file named as a node (`cluster:…`) has no graph.input or graph.output node: a \
     graph, not a component."
);

/// The module's allocator, as the `cnets` binary's: mimalloc keeps freed memory for reuse, where
/// glibc's malloc hands the large buffers of a construction and of the arrays handed to numpy back
/// to the kernel and faults them in again on the next call (at 100 × 100 that was a third of the
/// call's time). Arrays handed to numpy own their Rust buffer, so they are freed by it too.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// The node library's registry, built once per process.
fn registry() -> &'static Arc<Registry> {
    static REGISTRY: std::sync::OnceLock<Arc<Registry>> = std::sync::OnceLock::new();
    REGISTRY.get_or_init(|| Arc::new(cnets_nodes::registry()))
}

/// Nanoseconds the last node evaluation of [`eval`] took (the node alone: no conversion).
static LAST_EVAL_NANOS: AtomicU64 = AtomicU64::new(0);

/// A `CnetsError` with this message; long quoted inputs (a 1 MB input name, a path of a million
/// characters) are cut to excerpts, as on the command line (`files::short_quotes`).
pub(crate) fn error(message: impl Into<String>) -> PyErr {
    CnetsError::new_err(cnets_engine::files::short_quotes(&message.into(), 200))
}

/// A `CnetsError` for a session's failure. A node's failure carries its parts as attributes:
/// `node_type`, `reason` (its error without the node type in front) and `kind`
/// (`NodeError::kind`: `message`, `geometry`, `io`, `convert`, `json`, `memory`, `file`, `panic`),
/// so a caller (the Hops server) never takes the message's text apart.
fn session_error(py: Python<'_>, e: cnets_host::SessionError) -> PyErr {
    let err = error(e.to_string());
    if let cnets_host::SessionError::Node {
        node_type,
        error: node_error,
    } = &e
    {
        let value = err.value(py);
        let reason = cnets_engine::files::short_quotes(&node_error.to_string(), 200);
        let set = value
            .setattr("node_type", node_type.as_str())
            .and_then(|()| value.setattr("reason", reason))
            .and_then(|()| value.setattr("kind", node_error.kind()));
        if let Err(failed) = set {
            return failed;
        }
    }
    err
}

/// Evaluates one node type on inputs (a dict by input name) and returns its outputs by name.
/// `label_tables`: lists of label rows (configurations) come back as `(codes, labels)`.
/// `option_prefix` is how the caller spells the options in messages (`cnets.eval` takes them as
/// `_outputs`, `_max_memory`, …).
#[pyfunction]
#[pyo3(signature = (node_type, inputs, outputs=None, max_memory=None, allow_read=None, library=None, out=None, label_tables=false, option_prefix=""))]
#[allow(clippy::too_many_arguments)]
fn eval<'py>(
    py: Python<'py>,
    node_type: &Bound<'py, PyAny>,
    inputs: &Bound<'py, PyAny>,
    outputs: Option<&Bound<'py, PyAny>>,
    max_memory: Option<&Bound<'py, PyAny>>,
    allow_read: Option<&Bound<'py, PyAny>>,
    library: Option<&Bound<'py, PyAny>>,
    out: Option<&Bound<'py, PyAny>>,
    label_tables: bool,
    option_prefix: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let node_type = node_type_arg(node_type)?;
    let inputs = inputs.cast::<PyDict>().map_err(|_| {
        error(format!(
            "inputs: expected a dict, got {}",
            args::describe(inputs)
        ))
    })?;
    let outputs = args::texts(outputs, &format!("{option_prefix}outputs"))?;
    let settings = Settings::new(max_memory, allow_read, library, out, option_prefix)?;
    let session = settings.session();
    let node = session
        .resolve(&node_type, registry())
        .map_err(|e| error(e.to_string()))?;
    let def = node.def().clone();
    let budget = session.budget();
    let mut given: Vec<Option<Value>> = vec![None; def.inputs.len()];
    for (name, value) in inputs.iter() {
        let name: String = name
            .extract()
            .map_err(|_| error("input names must be strings"))?;
        let Some(k) = def.input_index(&name) else {
            return Err(error(
                cnets_host::inputs::unknown_input(&def, &name).to_string(),
            ));
        };
        let port = &def.inputs[k];
        let v = convert::to_value(&value, &port.ty, &budget).map_err(|e| {
            error(format!(
                "{}: input '{name}' ({}): {e}",
                def.id,
                port.type_name()
            ))
        })?;
        given[k] = Some(v);
    }
    let values = cnets_host::complete_inputs(&def, given).map_err(|e| error(e.to_string()))?;
    let base = std::env::current_dir().ok();
    let run = py
        .detach(|| session.eval_node(&def, &values, outputs.as_deref(), base))
        .map_err(|e| error(e.to_string()))?;
    LAST_EVAL_NANOS.store(run.elapsed.as_nanos() as u64, Ordering::Relaxed);
    let outputs_of = run.into_outputs().map_err(|e| session_error(py, e))?;
    for w in &outputs_of.warnings {
        warn(py, &format!("{}: {w}", def.id))?;
    }
    let dict = PyDict::new(py);
    for (port, value) in def.outputs.iter().zip(&outputs_of.values) {
        if outputs
            .as_ref()
            .is_none_or(|o| o.iter().any(|n| n == &port.name))
        {
            let table = if label_tables {
                convert::label_table(py, value)?
            } else {
                None
            };
            match table {
                Some(t) => dict.set_item(port.name.as_ref(), t)?,
                None => dict.set_item(
                    port.name.as_ref(),
                    convert::to_py_typed(py, value, &port.ty)?,
                )?,
            }
        }
    }
    if !outputs_of.files.is_empty() {
        let files: Vec<String> = outputs_of
            .files
            .iter()
            .map(|f| f.display().to_string())
            .collect();
        dict.set_item("__files__", files)?;
    }
    Ok(dict)
}

/// A node type argument: a registry id or `cluster:<path>`.
fn node_type_arg(obj: &Bound<'_, PyAny>) -> PyResult<String> {
    if obj.is_instance_of::<pyo3::types::PyString>() {
        return obj.extract();
    }
    Err(error(format!(
        "node_type: expected a node type id such as \"cnets.construct\" (see cnets.node_types()) \
         or \"cluster:<graph.ron>\", got {}",
        args::describe(obj)
    )))
}

/// Issues a `cnets.CnetsWarning` (a node's warning: a clamped value, a dropped wrap…).
pub(crate) fn warn(py: Python<'_>, message: &str) -> PyResult<()> {
    let category = py.get_type::<CnetsWarning>();
    PyErr::warn(
        py,
        &category,
        &std::ffi::CString::new(message.replace('\0', " "))?,
        1,
    )
}

/// Seconds the node itself took in the last `eval` call (inputs already converted, outputs not
/// yet), for comparing the Python overhead with the node's own time.
#[pyfunction]
fn last_eval_seconds() -> f64 {
    LAST_EVAL_NANOS.load(Ordering::Relaxed) as f64 * 1e-9
}

/// The quad indices (F, 4) of a rows × cols grid, row-major vertex indices `i * cols + j`, with
/// the wrapping quads when the rows or columns wrap (the engine's `QuadGrid::quad_indices`).
#[pyfunction]
fn quad_faces<'py>(
    py: Python<'py>,
    rows: &Bound<'py, PyAny>,
    cols: &Bound<'py, PyAny>,
    wrap_rows: &Bound<'py, PyAny>,
    wrap_cols: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let (rows, cols) = (args::count(rows, "rows")?, args::count(cols, "cols")?);
    let grid = cnets_geometry::QuadGrid {
        classes: Vec::new(),
        rows,
        cols,
        wrap_rows: args::flag(wrap_rows, "wrap_rows")?,
        wrap_cols: args::flag(wrap_cols, "wrap_cols")?,
        vertices: Vec::new(),
    };
    let (qr, qc) = (grid.quad_rows(), grid.quad_cols());
    let count = qr
        .checked_mul(qc)
        .and_then(|n| n.checked_mul(4))
        .filter(|&n| n.saturating_mul(8) as u64 <= cnets_engine::MemoryBudget::default().limit)
        .ok_or_else(|| error(format!("a grid of {rows} × {cols} vertices is too large")))?;
    let mut data = Vec::with_capacity(count);
    for i in 0..qr {
        for j in 0..qc {
            data.extend(grid.quad_indices(i, j).map(|k| k as i64));
        }
    }
    PyArray1::from_vec(py, data)
        .reshape([qr * qc, 4])
        .map(|a| a.into_any())
}

/// Bytes of a size text (`"64MB"`, `"2G"`, `"1.5GiB"`, a plain number of bytes), as the command
/// line's `--max-memory` reads it.
#[pyfunction]
fn parse_size(text: &Bound<'_, PyAny>) -> PyResult<u64> {
    let text = args::text(text, "size")?;
    cnets_engine::budget::parse_size(&text).map_err(error)
}

/// Bytes for messages, in decimal units (`64 MB`, `1.5 GB`).
#[pyfunction]
fn format_bytes(bytes: u64) -> String {
    cnets_engine::budget::format_bytes(bytes)
}

/// Checks that copying `count` numbers (8 bytes each) for `what` fits the memory budget
/// (`max_memory`, else half the machine's memory), before the copy is made; raises `CnetsError`
/// with what it would need otherwise.
#[pyfunction]
#[pyo3(signature = (count, what, max_memory=None))]
fn check_memory(count: u128, what: &str, max_memory: Option<&Bound<'_, PyAny>>) -> PyResult<()> {
    let settings = Settings::new(max_memory, None, None, None, "")?;
    settings
        .budget()
        .check(cnets_engine::budget::bytes_of(count, 8), 0, what)
        .map_err(|e| error(e.to_string()))
}

/// A node type as a dict: `id`, `category`, `doc`, `inputs` and `outputs` (each a dict with
/// `name`, `type`, `doc`, and for inputs `default` and `optional`).
fn def_dict<'py>(py: Python<'py>, def: &cnets_engine::NodeDef) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("id", def.id.as_ref())?;
    d.set_item("category", def.category.as_ref())?;
    d.set_item("doc", def.doc.as_ref())?;
    let ports =
        |ports: &[cnets_engine::PortDef], inputs: bool| -> PyResult<Vec<Bound<'py, PyDict>>> {
            ports
                .iter()
                .map(|p| {
                    let pd = PyDict::new(py);
                    pd.set_item("name", p.name.as_ref())?;
                    pd.set_item("type", p.type_name())?;
                    pd.set_item("doc", p.doc.as_ref())?;
                    if inputs {
                        let default = match &p.default {
                            Some(v) => convert::to_py(py, v)?,
                            None => py.None().into_bound(py),
                        };
                        pd.set_item("default", default)?;
                        pd.set_item("optional", p.optional)?;
                    }
                    Ok(pd)
                })
                .collect()
        };
    d.set_item("inputs", ports(&def.inputs, true)?)?;
    d.set_item("outputs", ports(&def.outputs, false)?)?;
    Ok(d)
}

/// Every node type of the library (see [`def_dict`]).
#[pyfunction]
fn node_types<'py>(py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
    registry().iter().map(|def| def_dict(py, def)).collect()
}

/// One node type by id, or a graph file's interface (`cluster:<path>`), as a dict (see
/// [`def_dict`]).
#[pyfunction]
#[pyo3(signature = (node_type, library=None, allow_read=None))]
fn node_interface<'py>(
    py: Python<'py>,
    node_type: &Bound<'py, PyAny>,
    library: Option<&Bound<'py, PyAny>>,
    allow_read: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let session = cnets_host::Session::new()
        .with_library(settings::library_with_env(args::paths(library, "library")?))
        .with_allow_read(args::paths(allow_read, "allow_read")?);
    let node = session
        .resolve(&node_type_arg(node_type)?, registry())
        .map_err(|e| match e {
            cnets_host::HostError::NoInterface { .. } => NoInterfaceError::new_err(e.to_string()),
            e => error(e.to_string()),
        })?;
    def_dict(py, node.def())
}

use numpy::PyArrayMethods;

/// The module.
#[pymodule]
fn _cnets(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("CnetsError", m.py().get_type::<CnetsError>())?;
    m.add("CnetsWarning", m.py().get_type::<CnetsWarning>())?;
    m.add("NoInterfaceError", m.py().get_type::<NoInterfaceError>())?;
    m.add_function(wrap_pyfunction!(eval, m)?)?;
    m.add_function(wrap_pyfunction!(last_eval_seconds, m)?)?;
    m.add_function(wrap_pyfunction!(quad_faces, m)?)?;
    m.add_function(wrap_pyfunction!(node_types, m)?)?;
    m.add_function(wrap_pyfunction!(node_interface, m)?)?;
    m.add_function(wrap_pyfunction!(parse_size, m)?)?;
    m.add_function(wrap_pyfunction!(format_bytes, m)?)?;
    m.add_function(wrap_pyfunction!(check_memory, m)?)?;
    m.add_class::<graph::PyGraph>()?;
    Ok(())
}
