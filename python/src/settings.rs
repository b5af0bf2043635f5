//! What an evaluation may use: the memory budget, the folders it may read, the library folders of
//! cluster files, and where exports go (docs/engine.md, Bounded resources and File access).

use std::path::PathBuf;

use cnets_engine::{MemoryBudget, NodeContext};
use pyo3::prelude::*;

use crate::error;

/// Resource settings of an evaluation, from Python keyword arguments.
#[derive(Debug, Clone, Default)]
pub struct Settings {
    /// The memory budget in bytes (`None`: half the machine's memory).
    pub max_memory: Option<u64>,
    /// Folders nodes and cluster files may also read from.
    pub allow_read: Vec<PathBuf>,
    /// Folders searched for cluster graph files.
    pub library: Vec<PathBuf>,
    /// Where export nodes write (`None`: `out` in the working folder, as `cnets run`).
    pub out: Option<PathBuf>,
}

impl Settings {
    /// Settings from keyword arguments; `max_memory` is a number of bytes or a size text such as
    /// `"512MB"` or `"2G"`.
    pub fn new(
        max_memory: Option<&Bound<'_, PyAny>>,
        allow_read: Option<Vec<PathBuf>>,
        library: Option<Vec<PathBuf>>,
        out: Option<PathBuf>,
    ) -> PyResult<Self> {
        Ok(Self {
            max_memory: max_memory.map(parse_memory).transpose()?,
            allow_read: allow_read.unwrap_or_default(),
            library: library.unwrap_or_default(),
            out,
        })
    }

    /// The node context of one evaluation; creates the output folder when the graph exports.
    pub fn context(&self, exports: bool, base: Option<PathBuf>) -> Result<NodeContext, String> {
        let out_dir = if exports {
            let dir = self.out.clone().unwrap_or_else(|| PathBuf::from("out"));
            std::fs::create_dir_all(&dir).map_err(|e| {
                format!("{}: cannot create the output directory: {e}", dir.display())
            })?;
            Some(dir)
        } else {
            None
        };
        let mut ctx = NodeContext::new(out_dir, base);
        if let Some(limit) = self.max_memory {
            ctx.budget = MemoryBudget::new(limit);
        }
        ctx.allow_read = self.allow_read.clone();
        Ok(ctx)
    }
}

fn parse_memory(value: &Bound<'_, PyAny>) -> PyResult<u64> {
    if let Ok(bytes) = value.extract::<u64>() {
        return Ok(bytes);
    }
    if let Ok(text) = value.extract::<String>() {
        return cnets_engine::budget::parse_size(&text)
            .map_err(|e| error(format!("max_memory: {e}")));
    }
    Err(error(
        "max_memory must be a number of bytes or a size such as \"512MB\" or \"2G\"",
    ))
}
