//! Reading files a graph names: only under allowed folders, only regular files, only up to a size.

use std::io::Read;
use std::path::{Path, PathBuf};

use super::FileError;

/// The default size limit of one read: 1 GB.
pub const DEFAULT_MAX_READ_BYTES: u64 = 1_000_000_000;

/// Where reads are allowed and how large a file may be.
#[derive(Debug, Clone)]
pub struct ReadAccess {
    /// Folders whose files (at any depth, after resolving links) may be read: the graph file's
    /// folder and the folders allowed with `--allow-read`.
    pub roots: Vec<PathBuf>,
    /// The largest file read, in bytes.
    pub max_bytes: u64,
}

impl ReadAccess {
    /// Reads allowed under `roots`, up to [`DEFAULT_MAX_READ_BYTES`].
    pub fn new(roots: Vec<PathBuf>) -> Self {
        Self {
            roots,
            max_bytes: DEFAULT_MAX_READ_BYTES,
        }
    }

    /// The file's real path (links resolved) when it lies under an allowed folder.
    pub fn check(&self, path: &Path) -> Result<PathBuf, FileError> {
        let real = path
            .canonicalize()
            .map_err(|e| FileError::Io(path.to_path_buf(), e))?;
        let inside = self
            .roots
            .iter()
            .filter_map(|r| r.canonicalize().ok())
            .any(|root| real.starts_with(root));
        if !inside {
            let allowed = if self.roots.is_empty() {
                "none".to_string()
            } else {
                self.roots
                    .iter()
                    .map(|r| r.display().to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            };
            return Err(FileError::NotAllowed {
                path: path.to_path_buf(),
                allowed,
            });
        }
        Ok(real)
    }

    /// The bytes of `path` after [`ReadAccess::check`]: opened without blocking (a FIFO does not
    /// hang the run), refused unless a regular file of at most `max_bytes`.
    pub fn read(&self, path: &Path) -> Result<Vec<u8>, FileError> {
        let real = self.check(path)?;
        let mut file = open_nonblocking(&real).map_err(|e| FileError::Io(path.to_path_buf(), e))?;
        let meta = file
            .metadata()
            .map_err(|e| FileError::Io(path.to_path_buf(), e))?;
        if !meta.is_file() {
            return Err(FileError::NotAFile(path.to_path_buf()));
        }
        if meta.len() > self.max_bytes {
            return Err(FileError::TooLarge {
                path: path.to_path_buf(),
                size: meta.len(),
                limit: self.max_bytes,
            });
        }
        let mut bytes = Vec::with_capacity(meta.len() as usize);
        (&mut file)
            .take(self.max_bytes.saturating_add(1))
            .read_to_end(&mut bytes)
            .map_err(|e| FileError::Io(path.to_path_buf(), e))?;
        if bytes.len() as u64 > self.max_bytes {
            return Err(FileError::TooLarge {
                path: path.to_path_buf(),
                size: bytes.len() as u64,
                limit: self.max_bytes,
            });
        }
        Ok(bytes)
    }

    /// [`ReadAccess::read`] as UTF-8 text.
    pub fn read_text(&self, path: &Path) -> Result<String, FileError> {
        String::from_utf8(self.read(path)?).map_err(|_| {
            FileError::Io(
                path.to_path_buf(),
                std::io::Error::new(
                    std::io::ErrorKind::InvalidData,
                    "the file is not UTF-8 text",
                ),
            )
        })
    }
}

#[cfg(unix)]
fn open_nonblocking(path: &Path) -> std::io::Result<std::fs::File> {
    use rustix::fs::{CWD, Mode, OFlags, openat};
    let fd = openat(
        CWD,
        path,
        OFlags::RDONLY | OFlags::NONBLOCK | OFlags::CLOEXEC,
        Mode::empty(),
    )?;
    let file = std::fs::File::from(fd);
    // Regular files ignore O_NONBLOCK; clearing it anyway keeps reads ordinary.
    let _ = rustix::fs::fcntl_setfl(&file, OFlags::empty());
    Ok(file)
}

#[cfg(not(unix))]
fn open_nonblocking(path: &Path) -> std::io::Result<std::fs::File> {
    std::fs::File::open(path)
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;

    #[test]
    fn reads_stay_under_their_folders_and_refuse_specials_and_size() {
        let base = std::env::temp_dir().join(format!("cnets-read-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&base);
        let (inside, outside) = (base.join("graph"), base.join("other"));
        std::fs::create_dir_all(&inside).unwrap();
        std::fs::create_dir_all(&outside).unwrap();
        std::fs::write(inside.join("a.csv"), b"0,0,0\n").unwrap();
        std::fs::write(outside.join("b.csv"), b"1,1,1\n").unwrap();
        std::os::unix::fs::symlink(outside.join("b.csv"), inside.join("link.csv")).unwrap();
        let mut access = ReadAccess::new(vec![inside.clone()]);

        assert_eq!(access.read(&inside.join("a.csv")).unwrap(), b"0,0,0\n");
        for refused in [
            outside.join("b.csv"),
            inside.join("link.csv"),
            inside.join("../other/b.csv"),
        ] {
            let e = access.read(&refused).unwrap_err();
            assert!(
                matches!(e, FileError::NotAllowed { .. }),
                "{refused:?}: {e}"
            );
        }
        assert!(matches!(
            ReadAccess::new(vec![inside.clone()]).read(Path::new("/etc/passwd")),
            Err(FileError::NotAllowed { .. })
        ));
        access.roots.push(PathBuf::from("/dev"));
        assert!(matches!(
            access.read(Path::new("/dev/zero")),
            Err(FileError::NotAFile(_))
        ));
        let fifo = inside.join("fifo");
        assert!(
            std::process::Command::new("mkfifo")
                .arg(&fifo)
                .status()
                .unwrap()
                .success()
        );
        assert!(matches!(access.read(&fifo), Err(FileError::NotAFile(_))));
        access.max_bytes = 3;
        assert!(matches!(
            access.read(&inside.join("a.csv")),
            Err(FileError::TooLarge { .. })
        ));
        std::fs::remove_dir_all(&base).unwrap();
    }
}
