//! Reading files a graph names: only under allowed folders, only regular files, only up to a size.
//!
//! The name is checked first, without touching the file system: a path outside every allowed
//! folder is refused whether or not it exists (a graph cannot probe which files are there). Then
//! the file is opened — on Linux as an `O_PATH` descriptor, which neither opens a device nor
//! blocks on a FIFO — and what was opened is checked: its real path (from the descriptor, so a
//! name swapped for a link in between reads nothing outside) must lie under an allowed folder,
//! and it must be a regular file of at most the size limit. The bytes are read from that same
//! descriptor.

use std::io::Read;
use std::path::{Component, Path, PathBuf};

use super::FileError;

/// The default size limit of one read: 1 GB.
pub const DEFAULT_MAX_READ_BYTES: u64 = 1_000_000_000;

/// Where reads are allowed and how large a file may be.
#[derive(Debug, Clone)]
pub struct ReadAccess {
    /// Folders whose files (at any depth, after resolving links) may be read: the graph file's
    /// folder and the folders allowed with `--allow-read`. An empty path is the current folder.
    pub roots: Vec<PathBuf>,
    /// The largest file read, in bytes.
    pub max_bytes: u64,
}

/// A file opened for reading after every check: a regular file under an allowed folder.
#[derive(Debug)]
pub struct Opened {
    /// The open file.
    pub file: std::fs::File,
    /// Its size in bytes when it was opened.
    pub len: u64,
    /// Its real path (links resolved).
    pub real: PathBuf,
}

/// `path` made absolute (against the current folder) with `.` and `..` resolved by name.
fn lexical(path: &Path) -> PathBuf {
    let absolute = if path.is_absolute() {
        path.to_path_buf()
    } else {
        std::env::current_dir().unwrap_or_default().join(path)
    };
    let mut out = PathBuf::new();
    for c in absolute.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                out.pop();
            }
            other => out.push(other),
        }
    }
    out
}

impl ReadAccess {
    /// Reads allowed under `roots`, up to [`DEFAULT_MAX_READ_BYTES`].
    pub fn new(roots: Vec<PathBuf>) -> Self {
        Self {
            roots,
            max_bytes: DEFAULT_MAX_READ_BYTES,
        }
    }

    /// Each allowed folder as written (made absolute) and with its links resolved.
    fn root_forms(&self) -> Vec<PathBuf> {
        self.roots
            .iter()
            .map(|r| {
                if r.as_os_str().is_empty() {
                    Path::new(".")
                } else {
                    r
                }
            })
            .flat_map(|r| [Some(lexical(r)), r.canonicalize().ok()])
            .flatten()
            .collect()
    }

    fn not_allowed(&self, path: &Path) -> FileError {
        let allowed = if self.roots.is_empty() {
            "none".to_string()
        } else {
            self.roots
                .iter()
                .map(|r| match r.display().to_string() {
                    s if s.is_empty() => ".".to_string(),
                    s => s,
                })
                .collect::<Vec<_>>()
                .join(", ")
        };
        FileError::NotAllowed {
            path: path.to_path_buf(),
            allowed,
        }
    }

    /// Refuses `path` when its name (made absolute, `..` resolved by name) lies outside every
    /// allowed folder. Touches nothing but the allowed folders themselves.
    pub fn check_name(&self, path: &Path) -> Result<(), FileError> {
        let name = lexical(path);
        if self.root_forms().iter().any(|root| name.starts_with(root)) {
            Ok(())
        } else {
            Err(self.not_allowed(path))
        }
    }

    /// The file's real path (links resolved) when it lies under an allowed folder: the name is
    /// checked, the file opened and what was opened checked (see the module).
    pub fn check(&self, path: &Path) -> Result<PathBuf, FileError> {
        self.open_checked(path, false).map(|o| o.real)
    }

    /// Opens `path` for reading after every check (see the module): the name, then what was
    /// opened — under an allowed folder, a regular file (a device, FIFO or socket is refused
    /// without blocking), at most `max_bytes`.
    pub fn open(&self, path: &Path) -> Result<Opened, FileError> {
        self.open_checked(path, true)
    }

    fn open_checked(&self, path: &Path, sized: bool) -> Result<Opened, FileError> {
        self.check_name(path)?;
        let io = |e: std::io::Error| FileError::Io(path.to_path_buf(), e);
        let (file, real) = imp::open(path).map_err(io)?;
        let roots = self.root_forms();
        if !roots.iter().any(|root| real.starts_with(root)) {
            return Err(self.not_allowed(path));
        }
        let meta = file.metadata().map_err(io)?;
        if !meta.is_file() {
            return Err(FileError::NotAFile(path.to_path_buf()));
        }
        if sized && meta.len() > self.max_bytes {
            return Err(FileError::TooLarge {
                path: path.to_path_buf(),
                size: meta.len(),
                limit: self.max_bytes,
            });
        }
        Ok(Opened {
            file: imp::reopen(file, &real).map_err(io)?,
            len: meta.len(),
            real,
        })
    }

    /// The bytes of `path` after the checks of [`ReadAccess::open`].
    pub fn read(&self, path: &Path) -> Result<Vec<u8>, FileError> {
        let opened = self.open(path)?;
        self.read_opened(path, opened)
    }

    /// The bytes of a file [`ReadAccess::open`] opened (never more than `max_bytes`).
    pub fn read_opened(&self, path: &Path, opened: Opened) -> Result<Vec<u8>, FileError> {
        let Opened { mut file, len, .. } = opened;
        let mut bytes = Vec::with_capacity(len.min(self.max_bytes) as usize);
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

/// Linux: an `O_PATH` descriptor (no device opened, no FIFO waited on), its real path read back
/// from `/proc/self/fd`, then reopened for reading through that descriptor — the same file.
#[cfg(target_os = "linux")]
mod imp {
    use std::fs::File;
    use std::io;
    use std::os::fd::AsRawFd;
    use std::path::{Path, PathBuf};

    use rustix::fs::{CWD, Mode, OFlags, openat};

    pub(super) fn open(path: &Path) -> io::Result<(File, PathBuf)> {
        let fd = openat(CWD, path, OFlags::PATH | OFlags::CLOEXEC, Mode::empty())?;
        let file = File::from(fd);
        let real = match std::fs::read_link(format!("/proc/self/fd/{}", file.as_raw_fd())) {
            Ok(real) => real,
            // No /proc: the name's real path, accepted only when it is the file opened.
            Err(_) => super::same_file(&file, path)?,
        };
        Ok((file, real))
    }

    pub(super) fn reopen(file: File, real: &Path) -> io::Result<File> {
        let magic = format!("/proc/self/fd/{}", file.as_raw_fd());
        let flags = OFlags::RDONLY | OFlags::NONBLOCK | OFlags::CLOEXEC;
        let opened = match openat(CWD, magic.as_str(), flags, Mode::empty()) {
            Ok(fd) => File::from(fd),
            Err(_) => File::from(openat(CWD, real, flags | OFlags::NOFOLLOW, Mode::empty())?),
        };
        super::identical(&file, &opened)?;
        // Regular files ignore O_NONBLOCK; clearing it keeps reads ordinary.
        let _ = rustix::fs::fcntl_setfl(&opened, OFlags::empty());
        Ok(opened)
    }
}

/// Other systems: opened without blocking, then accepted only when the name's real path is the
/// file that was opened.
#[cfg(all(unix, not(target_os = "linux")))]
mod imp {
    use std::fs::File;
    use std::io;
    use std::path::{Path, PathBuf};

    use rustix::fs::{CWD, Mode, OFlags, openat};

    pub(super) fn open(path: &Path) -> io::Result<(File, PathBuf)> {
        let flags = OFlags::RDONLY | OFlags::NONBLOCK | OFlags::NOCTTY | OFlags::CLOEXEC;
        let file = File::from(openat(CWD, path, flags, Mode::empty())?);
        let real = super::same_file(&file, path)?;
        let _ = rustix::fs::fcntl_setfl(&file, OFlags::empty());
        Ok((file, real))
    }

    pub(super) fn reopen(file: File, _real: &Path) -> io::Result<File> {
        Ok(file)
    }
}

#[cfg(not(unix))]
mod imp {
    use std::fs::File;
    use std::io;
    use std::path::{Path, PathBuf};

    pub(super) fn open(path: &Path) -> io::Result<(File, PathBuf)> {
        let file = File::open(path)?;
        Ok((file, path.canonicalize()?))
    }

    pub(super) fn reopen(file: File, _real: &Path) -> io::Result<File> {
        Ok(file)
    }
}

/// The real path of `path` when it is the very file `file` (else an error: it changed).
#[cfg(unix)]
fn same_file(file: &std::fs::File, path: &Path) -> std::io::Result<PathBuf> {
    use std::os::unix::fs::MetadataExt;
    let real = path.canonicalize()?;
    let (named, opened) = (std::fs::metadata(&real)?, file.metadata()?);
    if (named.dev(), named.ino()) == (opened.dev(), opened.ino()) {
        Ok(real)
    } else {
        Err(std::io::Error::other(
            "the file changed while it was being opened",
        ))
    }
}

/// An error unless both are the same file (device and inode).
#[cfg(unix)]
fn identical(a: &std::fs::File, b: &std::fs::File) -> std::io::Result<()> {
    let (x, y) = (rustix::fs::fstat(a)?, rustix::fs::fstat(b)?);
    if (x.st_dev, x.st_ino) == (y.st_dev, y.st_ino) {
        Ok(())
    } else {
        Err(std::io::Error::other(
            "the file changed while it was being opened",
        ))
    }
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

    #[test]
    fn outside_paths_are_refused_by_name_whether_or_not_they_exist() {
        let base = std::env::temp_dir().join(format!("cnets-probe-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&base);
        let (inside, outside) = (base.join("graph"), base.join("other"));
        std::fs::create_dir_all(&inside).unwrap();
        std::fs::create_dir_all(&outside).unwrap();
        std::fs::write(outside.join("there.csv"), b"1").unwrap();
        let access = ReadAccess::new(vec![inside.clone()]);
        let present = access.read(&outside.join("there.csv")).unwrap_err();
        let missing = access.read(&outside.join("not-there.csv")).unwrap_err();
        let dotted = access
            .read(&inside.join("../other/not-there.csv"))
            .unwrap_err();
        for e in [&present, &missing, &dotted] {
            assert!(matches!(e, FileError::NotAllowed { .. }), "{e}");
        }
        // The same words, whether the file exists or not.
        assert_eq!(
            present.to_string().replace("there.csv", "X"),
            missing.to_string().replace("not-there.csv", "X")
        );
        // Inside, a missing file is just missing.
        assert!(matches!(
            access.read(&inside.join("nope.csv")),
            Err(FileError::Io(..))
        ));
        std::fs::remove_dir_all(&base).unwrap();
    }

    #[test]
    fn an_empty_folder_is_the_current_folder() {
        // `cnets run g.ron` from the graph's own folder: its folder is "".
        let access = ReadAccess::new(vec![PathBuf::new()]);
        let here = std::env::current_dir().unwrap();
        let name = format!("cnets-empty-root-{}.csv", std::process::id());
        std::fs::write(here.join(&name), b"0,0,0\n").unwrap();
        let read = access.read(Path::new(&name));
        std::fs::remove_file(here.join(&name)).unwrap();
        assert_eq!(read.unwrap(), b"0,0,0\n");
        assert!(access.read(Path::new("/etc/hostname")).is_err());
    }

    #[test]
    fn a_name_swapped_for_a_link_never_reads_outside() {
        let base = std::env::temp_dir().join(format!("cnets-swap-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&base);
        let (inside, outside) = (base.join("graph"), base.join("other"));
        std::fs::create_dir_all(&inside).unwrap();
        std::fs::create_dir_all(&outside).unwrap();
        std::fs::write(outside.join("secret.csv"), b"SECRET").unwrap();
        let (file, link, staged) = (
            inside.join("in.csv"),
            inside.join("link.tmp"),
            inside.join("file.tmp"),
        );
        std::fs::write(&file, b"inside").unwrap();
        // The swapper counts its swaps; the reads go on until it has swapped often (a busy
        // machine may start it late), so the race is always run, never skipped by chance.
        use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};
        let stop = std::sync::Arc::new(AtomicBool::new(false));
        let swaps = std::sync::Arc::new(AtomicU32::new(0));
        let swapper = {
            let (file, link, staged, secret, stop, swaps) = (
                file.clone(),
                link.clone(),
                staged.clone(),
                outside.join("secret.csv"),
                stop.clone(),
                swaps.clone(),
            );
            std::thread::spawn(move || {
                while !stop.load(Ordering::Relaxed) {
                    let _ = std::fs::remove_file(&link);
                    let _ = std::os::unix::fs::symlink(&secret, &link);
                    let _ = std::fs::rename(&link, &file);
                    let _ = std::fs::write(&staged, b"inside");
                    let _ = std::fs::rename(&staged, &file);
                    swaps.fetch_add(1, Ordering::Relaxed);
                }
            })
        };
        let access = ReadAccess::new(vec![inside.clone()]);
        let (mut inside_reads, mut refusals) = (0u32, 0u32);
        let give_up = std::time::Instant::now() + std::time::Duration::from_secs(120);
        while inside_reads + refusals < 2000 || swaps.load(Ordering::Relaxed) < 200 {
            assert!(std::time::Instant::now() < give_up, "the swapper never ran");
            match access.read(&file) {
                Ok(bytes) => {
                    assert_eq!(bytes, b"inside", "read a file outside the allowed folder");
                    inside_reads += 1;
                }
                Err(e) => {
                    assert!(!e.to_string().contains("SECRET"), "{e}");
                    refusals += 1;
                }
            }
        }
        stop.store(true, Ordering::Relaxed);
        swapper.join().unwrap();
        std::fs::remove_dir_all(&base).unwrap();
    }
}
