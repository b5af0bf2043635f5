//! One module per `cnets` subcommand.

pub mod check;
pub mod drag;
pub mod eval;
pub mod nodes;
pub mod optimize;
pub mod render;
pub mod run;

use std::path::Path;

use crate::failure::Failure;

/// Creates the `--out` folder of exports (with its parents), saying what is in the way when a file
/// of that name is there.
pub fn create_out_dir(dir: &Path) -> Result<(), Failure> {
    std::fs::create_dir_all(dir).map_err(|e| {
        let why = match std::fs::symlink_metadata(dir) {
            Ok(m) if !m.is_dir() => {
                "a file of that name is in the way (--out names a folder for the exports)"
                    .to_string()
            }
            _ => e.to_string(),
        };
        Failure::usage(format!(
            "{}: cannot create the output directory: {why}",
            dir.display()
        ))
    })
}
