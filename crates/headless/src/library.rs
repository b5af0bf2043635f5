//! Graph files used as node types: the graphs of a library folder (`cnets nodes --library`; the
//! logic lives in `cnets-host`, shared with the Python package).

use std::path::Path;
use std::sync::Arc;

use cnets_engine::{NodeDef, Registry};

use crate::failure::Failure;

/// Every graph of a folder that declares an interface, as node types (sorted by file name); their
/// cluster sources resolve next to them, in `CNETS_LIBRARY`'s folders, then in the folder. Files
/// that do not load are reported on stderr and skipped.
pub fn folder_defs(dir: &Path, registry: &Arc<Registry>) -> Result<Vec<NodeDef>, Failure> {
    let (defs, skipped) = cnets_host::folder_defs(dir, registry, &cnets_host::library_from_env())?;
    for m in skipped {
        crate::errln!("warning: skipped {m}");
    }
    Ok(defs)
}
