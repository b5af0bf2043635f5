//! Atomic file writes: a temporary file in the same directory, synced, then renamed over the target.
//! A crash leaves either the old file or the new one, never a half-written file. Only nothing or a
//! regular file is replaced (a FIFO, a device, a folder or a link in the way is an error): this is
//! [`files::write_file`](crate::files::write_file) with an `io::Error`.

use std::io;
use std::path::Path;

/// Writes `bytes` to `path` atomically, replacing only a regular file or nothing. Missing parent
/// directories are an error (not created).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> io::Result<()> {
    crate::files::write_file(path, bytes)
        .map(|_| ())
        .map_err(|e| match e {
            crate::files::FileError::Io(_, e) => e,
            other => io::Error::other(other.to_string()),
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs;

    #[test]
    fn writes_and_replaces_without_leftovers() {
        let dir = std::env::temp_dir().join(format!("cnets-atomic-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        let path = dir.join("g.ron");
        write_atomic(&path, b"one").unwrap();
        write_atomic(&path, b"two").unwrap();
        assert_eq!(fs::read_to_string(&path).unwrap(), "two");
        let entries: Vec<_> = fs::read_dir(&dir).unwrap().collect();
        assert_eq!(entries.len(), 1, "temporary files left behind");
        assert!(write_atomic(&dir.join("missing/x.ron"), b"x").is_err());
        fs::create_dir(dir.join("sub.ron")).unwrap();
        let e = write_atomic(&dir.join("sub.ron"), b"x").unwrap_err();
        assert!(e.to_string().contains("a folder"), "{e}");
        fs::remove_dir_all(&dir).unwrap();
    }
}
