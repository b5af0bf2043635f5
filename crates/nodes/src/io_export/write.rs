//! Writing an export: resolve the name inside the run's output directory, write atomically, record.

use std::io::{BufWriter, Write};
use std::path::Path;

use cnets_engine::files::check_export_name;
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
/// written atomically (temporary file, sync, rename) without following links out of the directory
/// (`NodeContext::write_output`), so a failure never leaves a partial file. The name is checked
/// before the extension is added (`.`, `..` or an empty name are refused, not turned into `.obj`).
/// The written path is recorded on the context and returned as text.
pub fn write_export(
    ctx: &NodeContext,
    name: &str,
    extension: &str,
    bytes: &[u8],
) -> Result<String, NodeError> {
    check_export_name(name.trim()).map_err(|e| NodeError::new(e.to_string()))?;
    let path = ctx.write_output(&with_extension(name, extension), bytes)?;
    Ok(path.display().to_string())
}

/// Streams an export to `name` inside the output directory: `encode` writes into a 64 kB buffer
/// over the atomic file (`NodeContext::create_output`), so the file is never held in memory whole
/// and a cancel request stops the write at the next buffer; an error (or a cancel) leaves no
/// file. The name is checked as by [`write_export`]. The written path is recorded and returned.
pub fn stream_export(
    ctx: &NodeContext,
    name: &str,
    extension: &str,
    encode: impl FnOnce(&mut dyn Write) -> Result<(), String>,
) -> Result<String, NodeError> {
    check_export_name(name.trim()).map_err(|e| NodeError::new(e.to_string()))?;
    let full = with_extension(name, extension);
    let file = ctx.create_output(&full)?;
    let mut out = BufWriter::with_capacity(1 << 16, file);
    let written = encode(&mut out).and_then(|()| out.flush().map_err(|e| e.to_string()));
    if ctx.cancelled() {
        return Err(NodeError::new("cancelled"));
    }
    written.map_err(NodeError::new)?;
    let file = out
        .into_inner()
        .map_err(|e| NodeError::new(format!("cannot write '{full}': {}", e.error())))?;
    let path = ctx.commit_output(&full, file)?;
    Ok(path.display().to_string())
}
