//! What an evaluation may use: the memory budget, the folders it may read, the library folders of
//! cluster files, and where exports go (docs/engine.md, Bounded resources and File access); each
//! evaluation's [`Session`] is made from them.

use std::path::PathBuf;

use cnets_engine::{MemoryBudget, NodeContext};
use cnets_host::Session;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyInt, PyString};

use crate::{args, error};

/// Resource settings of an evaluation, from Python keyword arguments.
#[derive(Debug, Clone, Default)]
pub struct Settings {
    /// The memory budget in bytes (`None`: half the machine's memory).
    pub max_memory: Option<u64>,
    /// Folders nodes and cluster files may also read from.
    pub allow_read: Vec<PathBuf>,
    /// Folders searched for cluster graph files: `CNETS_LIBRARY`'s, then those given.
    pub library: Vec<PathBuf>,
    /// Where export nodes write (`None`: `out` in the working folder, as `cnets run`).
    pub out: Option<PathBuf>,
}

impl Settings {
    /// Settings from keyword arguments, named in messages as `names` gives them (`max_memory`,
    /// `allow_read`, `library`, `out`, each with `prefix` before it: `cnets.eval` takes them as
    /// `_max_memory` …). `max_memory` is a number of bytes or a size text such as `"512MB"`;
    /// `allow_read` and `library` a folder or a list of folders (the library after
    /// `CNETS_LIBRARY`'s folders); `out` a folder.
    pub fn new(
        max_memory: Option<&Bound<'_, PyAny>>,
        allow_read: Option<&Bound<'_, PyAny>>,
        library: Option<&Bound<'_, PyAny>>,
        out: Option<&Bound<'_, PyAny>>,
        prefix: &str,
    ) -> PyResult<Self> {
        Ok(Self {
            max_memory: max_memory
                .filter(|m| !m.is_none())
                .map(|m| parse_memory(m, &format!("{prefix}max_memory")))
                .transpose()?,
            allow_read: args::paths(allow_read, &format!("{prefix}allow_read"))?,
            library: library_with_env(args::paths(library, &format!("{prefix}library"))?),
            out: args::opt_path(out, &format!("{prefix}out"))?,
        })
    }

    /// The session of an evaluation: the budget of `max_memory` (clamped to half the process's
    /// hard limit with a Python `ResourceWarning` when it asks for more; else half the memory the
    /// process has), the folders to read, the library, the output folder (`out` in the working
    /// folder when unset).
    pub fn session(&self) -> Session {
        let session = Session::new()
            .with_max_memory(self.max_memory)
            .with_allow_read(self.allow_read.iter().cloned())
            .with_library(self.library.iter().cloned())
            .with_out_dir(self.out.clone());
        if let Some(w) = session.budget_warning() {
            Python::attach(|py| {
                let category = py.get_type::<pyo3::exceptions::PyResourceWarning>();
                // A warning filter set to "error" raises here; the budget still holds.
                let message = std::ffi::CString::new(w).unwrap_or_default();
                let _ = PyErr::warn(py, category.as_any(), &message, 1);
            });
        }
        session
    }

    /// The memory budget of an evaluation (see [`Settings::session`]).
    pub fn budget(&self) -> MemoryBudget {
        self.session().budget()
    }

    /// The node context of one evaluation; creates the output folder when the graph exports.
    pub fn context(&self, exports: bool, base: Option<PathBuf>) -> Result<NodeContext, String> {
        self.session()
            .export_context(base, exports)
            .map_err(|e| e.to_string())
    }
}

/// `CNETS_LIBRARY`'s folders, then `library`: the library of the Python door (and its Hops server).
pub fn library_with_env(library: Vec<PathBuf>) -> Vec<PathBuf> {
    cnets_host::library_from_env()
        .into_iter()
        .chain(library)
        .collect()
}

fn parse_memory(value: &Bound<'_, PyAny>, name: &str) -> PyResult<u64> {
    if value.is_instance_of::<PyInt>() && !value.is_instance_of::<PyBool>() {
        return match value.extract::<u64>() {
            Ok(bytes) if bytes > 0 => Ok(bytes),
            _ => Err(error(format!(
                "{name}: expected a positive number of bytes, got {}",
                args::describe(value)
            ))),
        };
    }
    if value.is_instance_of::<PyString>() {
        let text: String = value.extract()?;
        return cnets_engine::budget::parse_size(&text).map_err(|e| error(format!("{name}: {e}")));
    }
    Err(error(format!(
        "{name}: expected a number of bytes or a size such as \"512MB\" or \"2G\", got {}",
        args::describe(value)
    )))
}
