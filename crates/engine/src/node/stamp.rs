//! Files a node read, tracked as salsa tracks untracked reads: a node whose files changed since it
//! ran re-runs at the next evaluation, even when the graph itself was not edited.
//!
//! A file is recorded with its length, modification time and a content hash. It counts as changed
//! when its length or modification time differ, or when it disappeared or appeared. When both are
//! equal but the file was read within [`RACY_WINDOW`] of its modification time — so a rewrite in the
//! same clock tick would not show in the time stamp (git's "racy" files) — the content hash is
//! compared too.

use std::hash::Hasher;
use std::path::{Path, PathBuf};
use std::time::{Duration, SystemTime};

use rustc_hash::FxHasher;

/// How close to its modification time a read must be for the time stamp alone not to be trusted.
pub const RACY_WINDOW: Duration = Duration::from_secs(2);

/// What a node saw of one file it read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FileStamp {
    /// The file as the node named it (resolved against the graph's folder).
    pub path: PathBuf,
    /// Its length in bytes (`None`: it did not exist or could not be read).
    pub len: Option<u64>,
    /// Its modification time.
    pub modified: Option<SystemTime>,
    /// Hash of the bytes read.
    pub hash: u64,
    /// The read was close enough to the modification time that the hash must be compared too.
    pub racy: bool,
}

/// A content hash of file bytes.
pub fn content_hash(bytes: &[u8]) -> u64 {
    let mut h = FxHasher::default();
    h.write(bytes);
    h.write_usize(bytes.len());
    h.finish()
}

#[cfg(not(target_arch = "wasm32"))]
fn read_bytes(path: &Path) -> Option<Vec<u8>> {
    std::fs::read(path).ok()
}

// The web (wasm32): the files opened on the page (no modification times: always hashed).
#[cfg(target_arch = "wasm32")]
fn read_bytes(path: &Path) -> Option<Vec<u8>> {
    crate::files::memory::read(path).map(|b| b.to_vec())
}

#[cfg(target_arch = "wasm32")]
fn metadata(path: &Path) -> (Option<u64>, Option<SystemTime>) {
    (
        crate::files::memory::read(path).map(|b| b.len() as u64),
        None,
    )
}

#[cfg(not(target_arch = "wasm32"))]
fn metadata(path: &Path) -> (Option<u64>, Option<SystemTime>) {
    match std::fs::metadata(path) {
        Ok(m) => (Some(m.len()), m.modified().ok()),
        Err(_) => (None, None),
    }
}

impl FileStamp {
    /// The stamp of a file whose content (`None`: the read failed) was just read.
    pub fn of(path: &Path, bytes: Option<&[u8]>) -> Self {
        let (len, modified) = metadata(path);
        let racy = modified.is_none_or(|m| match SystemTime::now().duration_since(m) {
            Ok(age) => age < RACY_WINDOW,
            Err(_) => true,
        });
        Self {
            path: path.to_path_buf(),
            len,
            modified,
            hash: bytes.map_or(0, content_hash),
            racy,
        }
    }

    /// True when the file is no longer what the node read.
    pub fn changed(&self) -> bool {
        let (len, modified) = metadata(&self.path);
        if len != self.len || modified != self.modified {
            return true;
        }
        if self.len.is_none() || !self.racy {
            return false;
        }
        match read_bytes(&self.path) {
            Some(bytes) => content_hash(&bytes) != self.hash,
            None => true,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rewrite_of_the_same_length_in_the_same_second_is_seen() {
        let dir = std::env::temp_dir().join(format!("cnets-stamp-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("a.txt");
        let written = std::time::Instant::now();
        std::fs::write(&path, b"1 2 3").unwrap();
        let stamp = FileStamp::of(&path, Some(b"1 2 3"));
        // Racy while within the window of its write (a stalled thread may pass it).
        if written.elapsed() < std::time::Duration::from_secs(1) {
            assert!(stamp.racy, "just written");
        }
        assert!(!stamp.changed());
        std::fs::write(&path, b"1 2 4").unwrap();
        assert!(stamp.changed(), "same length, same second: the hash tells");
        std::fs::write(&path, b"1 2 3 4").unwrap();
        assert!(stamp.changed());
        std::fs::remove_file(&path).unwrap();
        assert!(stamp.changed(), "a removed file changed");
        let missing = FileStamp::of(&path, None);
        assert!(!missing.changed(), "still missing");
        std::fs::write(&path, b"x").unwrap();
        assert!(missing.changed(), "it appeared");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
