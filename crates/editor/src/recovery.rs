//! Crash recovery: the document is autosaved to a recovery file while it has unsaved changes;
//! a clean exit (or a save) removes it, so finding one at start means the last session ended
//! without saving, and the editor offers to restore it.
//!
//! Files in the settings folder: `recovery.ron` (the graph's canonical text, written atomically)
//! and `recovery.path` (the document's own path, if it had one).

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use cnets_engine::atomic::write_atomic;

/// Seconds between autosaves of a changed document.
pub const AUTOSAVE_EVERY: Duration = Duration::from_secs(3);

/// A recovery file found at start.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Recovered {
    /// The graph text.
    pub text: String,
    /// The path the document had.
    pub path: Option<PathBuf>,
}

/// Autosaves into one folder.
#[derive(Debug)]
pub struct Recovery {
    dir: PathBuf,
    saved_version: Option<u64>,
    last_write: Option<Instant>,
}

impl Recovery {
    /// Recovery files in `dir`.
    pub fn new(dir: &Path) -> Self {
        Self {
            dir: dir.to_path_buf(),
            saved_version: None,
            last_write: None,
        }
    }

    /// The recovery graph file.
    pub fn file(&self) -> PathBuf {
        self.dir.join("recovery.ron")
    }

    fn path_file(&self) -> PathBuf {
        self.dir.join("recovery.path")
    }

    /// The recovery file left by a previous session, if any.
    pub fn find(&self) -> Option<Recovered> {
        let text = std::fs::read_to_string(self.file()).ok()?;
        let path = std::fs::read_to_string(self.path_file())
            .ok()
            .map(|p| p.trim().to_string())
            .filter(|p| !p.is_empty())
            .map(PathBuf::from);
        Some(Recovered { text, path })
    }

    /// Writes the recovery file now (atomically).
    pub fn write(&mut self, text: &str, path: Option<&Path>, version: u64) -> std::io::Result<()> {
        std::fs::create_dir_all(&self.dir)?;
        let p = path.map(|p| p.display().to_string()).unwrap_or_default();
        write_atomic(&self.path_file(), p.as_bytes())?;
        write_atomic(&self.file(), text.as_bytes())?;
        self.saved_version = Some(version);
        self.last_write = Some(Instant::now());
        Ok(())
    }

    /// Autosaves when the document is dirty, changed since the last autosave, and the last write
    /// is at least [`AUTOSAVE_EVERY`] old. `text` is only called when writing. Returns whether it
    /// wrote.
    pub fn tick(
        &mut self,
        dirty: bool,
        version: u64,
        path: Option<&Path>,
        text: impl FnOnce() -> String,
    ) -> bool {
        if !dirty || self.saved_version == Some(version) {
            return false;
        }
        if self
            .last_write
            .is_some_and(|t| t.elapsed() < AUTOSAVE_EVERY)
        {
            return false;
        }
        self.write(&text(), path, version).is_ok()
    }

    /// Removes the recovery files (after a save, a clean exit, or a declined restore).
    pub fn clear(&mut self) {
        let _ = std::fs::remove_file(self.file());
        let _ = std::fs::remove_file(self.path_file());
        self.saved_version = None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn autosave_find_and_clear() {
        let dir = std::env::temp_dir().join(format!("cnets-recovery-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let mut r = Recovery::new(&dir);
        assert!(r.find().is_none());
        assert!(
            !r.tick(false, 1, None, || "x".into()),
            "clean documents are not saved"
        );
        assert!(r.tick(true, 1, Some(Path::new("/tmp/a.ron")), || "one".into()));
        assert!(
            !r.tick(true, 1, None, || "one".into()),
            "same version: nothing to do"
        );
        assert!(
            !r.tick(true, 2, None, || "two".into()),
            "too soon after the last write"
        );
        let found = r.find().unwrap();
        assert_eq!(found.text, "one");
        assert_eq!(found.path, Some(PathBuf::from("/tmp/a.ron")));
        r.clear();
        assert!(r.find().is_none());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
