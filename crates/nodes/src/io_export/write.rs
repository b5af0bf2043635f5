//! Writing an export: resolve the name inside the run's output directory, write atomically, record.

use std::path::Path;

use cnets_engine::atomic::write_atomic;
use cnets_engine::{NodeContext, NodeError};

/// `name` with `extension` appended when it has none (`model` → `model.glb`).
pub fn with_extension(name: &str, extension: &str) -> String {
    if Path::new(name.trim()).extension().is_some() {
        name.trim().to_string()
    } else {
        format!("{}.{extension}", name.trim())
    }
}

/// Writes `bytes` to `name` inside the output directory: the whole file is built in memory first and
/// written atomically (temporary file, sync, rename), so a failure never leaves a partial file. The
/// written path is recorded on the context and returned as text.
pub fn write_export(
    ctx: &NodeContext,
    name: &str,
    extension: &str,
    bytes: &[u8],
) -> Result<String, NodeError> {
    let path = ctx.output_path(&with_extension(name, extension))?;
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent).map_err(|e| {
            NodeError::new(format!(
                "cannot create the output folder {}: {e}",
                parent.display()
            ))
        })?;
    }
    write_atomic(&path, bytes)
        .map_err(|e| NodeError::new(format!("cannot write {}: {e}", path.display())))?;
    ctx.record_file(path.clone());
    Ok(path.display().to_string())
}
