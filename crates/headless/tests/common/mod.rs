//! Helpers shared by the command-line tests.

use std::path::Path;

/// A fresh scratch folder for one test, removed when it goes out of scope (a failing test's
/// unwinding included), so the tests leave nothing behind in the system's temp folder.
pub struct Folder(tempfile::TempDir);

impl Folder {
    /// A new empty folder named `cnets-<name>-…` in the temp folder.
    pub fn new(name: &str) -> Self {
        let dir = tempfile::Builder::new()
            .prefix(&format!("cnets-{name}-"))
            .tempdir()
            .expect("a scratch folder");
        Folder(dir)
    }
}

impl std::ops::Deref for Folder {
    type Target = Path;

    fn deref(&self) -> &Path {
        self.0.path()
    }
}
