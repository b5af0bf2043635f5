//! Writing files atomically, replacing only what is ours to replace.
//!
//! Every write goes to a locked temporary file beside the target ([`temp`]), streamed through
//! [`AtomicFile`] (which stops at the first write after a cancel request), synced, then moved into
//! place — and only over **nothing or a regular file**: a FIFO, a device, a socket, a folder or a
//! symbolic link in the target's place is refused ([`FileError::NotReplaceable`]), so `--png
//! /dev/null` or a Save As onto a FIFO cannot turn them into regular files. On Linux the move is
//! race-free: `renameat2(RENAME_NOREPLACE)` when the name is free, else `RENAME_EXCHANGE` and a look
//! at what was swapped out (exchanged back, untouched, unless it is a regular file).
//!
//! - [`create_inside`] / [`write_inside`]: exports inside the output directory; every folder below
//!   it is opened relative to the one above with `O_NOFOLLOW` (`openat`, through `rustix`), so
//!   `out/link → /elsewhere` cannot take a write outside.
//! - [`create_file`] / [`write_file`]: a path a user named (`--png`, `optimize --out`, a graph
//!   saved by the editor): its folder is taken as named.
//! - [`check_replaceable`]: the same test up front, for a front end that asks before working.

use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use super::FileError;
#[cfg(not(target_arch = "wasm32"))]
use super::temp;

/// The message of a write stopped by a cancel request.
pub const CANCELLED: &str = "cancelled";

/// Writes `bytes` to the file named by `parts` (folders, then the file name, as
/// [`check_export_name`](super::check_export_name) returns them) inside `out_dir`, atomically (see
/// [`create_inside`]). Returns the written path.
pub fn write_inside(out_dir: &Path, parts: &[&str], bytes: &[u8]) -> Result<PathBuf, FileError> {
    let mut file = create_inside(out_dir, parts)?;
    file.write_all(bytes).map_err(|e| file.error(e))?;
    file.commit()
}

/// Opens an export named by `parts` inside `out_dir` for writing: missing folders are created;
/// every folder below `out_dir` is opened without following a symbolic link; the bytes go to a
/// locked temporary file in the final folder, moved over the target by [`AtomicFile::commit`]
/// (refused when the target is not a regular file). Stale temporary files in that folder are
/// removed first.
pub fn create_inside(out_dir: &Path, parts: &[&str]) -> Result<AtomicFile, FileError> {
    let Some((file, folders)) = parts.split_last() else {
        return Err(FileError::BadName(String::new(), "is empty"));
    };
    imp::create(out_dir, folders, file, true)
}

/// Writes `bytes` to `path` (a path a user named) atomically, replacing only a regular file or
/// nothing (see [`create_file`]).
pub fn write_file(path: &Path, bytes: &[u8]) -> Result<PathBuf, FileError> {
    let mut file = create_file(path)?;
    file.write_all(bytes).map_err(|e| file.error(e))?;
    file.commit()
}

/// Opens `path` (a path a user named: `--png`, `--out`, a Save As) for an atomic write into its
/// folder (which must exist). Refused at once when something other than a regular file is in the
/// way, and again at [`AtomicFile::commit`].
pub fn create_file(path: &Path) -> Result<AtomicFile, FileError> {
    let name = path.file_name().and_then(|n| n.to_str()).ok_or_else(|| {
        FileError::BadName(
            format!("{:?}", path.display().to_string()),
            "has no file name",
        )
    })?;
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    imp::create(dir, &[], name, false).map(|mut f| {
        f.path = path.to_path_buf();
        f
    })
}

/// Whether a write may replace what `path` names: nothing, or a regular file (a symbolic link is
/// not followed: it is refused, as is a folder, a FIFO, a device or a socket). For front ends that
/// ask before they work (the editor's Save As); every write checks again.
pub fn check_replaceable(path: &Path) -> Result<(), FileError> {
    match std::fs::symlink_metadata(path) {
        Err(e) if e.kind() == io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(FileError::Io(path.to_path_buf(), e)),
        Ok(m) => match kind_of(m.file_type()) {
            None => Ok(()),
            Some(kind) => Err(FileError::NotReplaceable(path.to_path_buf(), kind)),
        },
    }
}

/// What a file type is when it is not a regular file.
fn kind_of(t: std::fs::FileType) -> Option<&'static str> {
    #[cfg(unix)]
    use std::os::unix::fs::FileTypeExt;
    if t.is_file() {
        return None;
    }
    Some(if t.is_dir() {
        "a folder"
    } else if t.is_symlink() {
        "a symbolic link"
    } else {
        #[cfg(unix)]
        {
            if t.is_fifo() {
                "a FIFO"
            } else if t.is_char_device() {
                "a character device"
            } else if t.is_block_device() {
                "a block device"
            } else if t.is_socket() {
                "a socket"
            } else {
                "not a regular file"
            }
        }
        #[cfg(not(unix))]
        "not a regular file"
    })
}

/// A file being written atomically: a locked temporary file until [`AtomicFile::commit`] moves it
/// into place. Dropped without a commit (an error, a cancel), the temporary file is removed and the
/// target is untouched. Writes fail with [`CANCELLED`] once the cancel flag is set
/// ([`AtomicFile::with_cancel`]); wrap it in a `BufWriter` and the flag is looked at every buffer.
pub struct AtomicFile {
    inner: imp::Inner,
    path: PathBuf,
    cancel: Option<Arc<AtomicBool>>,
}

impl AtomicFile {
    /// Stops writes (with [`CANCELLED`]) once `flag` is set.
    pub fn with_cancel(mut self, flag: Arc<AtomicBool>) -> Self {
        self.cancel = Some(flag);
        self
    }

    /// The path the file will have.
    pub fn path(&self) -> &Path {
        &self.path
    }

    fn cancelled(&self) -> bool {
        self.cancel
            .as_ref()
            .is_some_and(|c| c.load(Ordering::Relaxed))
    }

    /// An I/O error of this file as a [`FileError`] (a cancel as [`FileError::Cancelled`]).
    pub fn error(&self, e: io::Error) -> FileError {
        if e.to_string() == CANCELLED {
            FileError::Cancelled(self.path.clone())
        } else {
            FileError::Io(self.path.clone(), e)
        }
    }

    /// Syncs the file and moves it into place, over nothing or a regular file only. Returns the
    /// path.
    pub fn commit(mut self) -> Result<PathBuf, FileError> {
        if self.cancelled() {
            return Err(FileError::Cancelled(self.path.clone()));
        }
        let path = self.path.clone();
        self.inner.commit(&path)?;
        Ok(path)
    }
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        if self.cancelled() {
            return Err(io::Error::other(CANCELLED));
        }
        self.inner.write(buf)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.inner.flush()
    }
}

#[cfg(unix)]
mod imp {
    use super::*;
    use rustix::fd::{AsFd, OwnedFd};
    use rustix::fs::{
        AtFlags, CWD, FileType, Mode, OFlags, mkdirat, openat, renameat, statat, unlinkat,
    };
    use rustix::io::Errno;

    /// The open temporary file, its folder and names.
    pub(super) struct Inner {
        file: Option<std::fs::File>,
        dir: OwnedFd,
        tmp: String,
        target: String,
        /// True once the temporary name is gone (moved into place).
        done: bool,
        _listed: temp::Listed,
    }

    pub(super) fn create(
        base: &Path,
        folders: &[&str],
        file: &str,
        inside: bool,
    ) -> Result<AtomicFile, FileError> {
        let io = |p: &Path, e: Errno| FileError::Io(p.to_path_buf(), e.into());
        let dir_flags = OFlags::RDONLY | OFlags::DIRECTORY | OFlags::CLOEXEC;
        let mut dir = openat(CWD, base, dir_flags, Mode::empty()).map_err(|e| io(base, e))?;
        let mut path = base.to_path_buf();
        let mut rel = PathBuf::new();
        for folder in folders {
            path.push(folder);
            rel.push(folder);
            match mkdirat(&dir, *folder, Mode::from_raw_mode(0o755)) {
                Ok(()) | Err(Errno::EXIST) => {}
                Err(e) => return Err(io(&path, e)),
            }
            dir = match openat(&dir, *folder, dir_flags | OFlags::NOFOLLOW, Mode::empty()) {
                Ok(d) => d,
                Err(Errno::LOOP | Errno::NOTDIR) => {
                    // Linux says ENOTDIR for a link opened with O_DIRECTORY | O_NOFOLLOW: look.
                    let link = statat(&dir, *folder, AtFlags::SYMLINK_NOFOLLOW)
                        .is_ok_and(|st| FileType::from_raw_mode(st.st_mode) == FileType::Symlink);
                    let rel = rel.display().to_string();
                    return Err(if link {
                        FileError::Link(rel)
                    } else {
                        FileError::NotAFolder(rel)
                    });
                }
                Err(e) => return Err(io(&path, e)),
            };
        }
        let target = path.join(file);
        check_at(&dir, file, &target)?;
        if inside {
            temp::remove_stale_in(dir.as_fd(), &path);
        }
        let tmp = temp::temp_name(file);
        let fd = temp::create_locked(dir.as_fd(), &tmp).map_err(|e| io(&target, e))?;
        let listed = temp::list(path.join(&tmp));
        Ok(AtomicFile {
            inner: Inner {
                file: Some(std::fs::File::from(fd)),
                dir,
                tmp,
                target: file.to_string(),
                done: false,
                _listed: listed,
            },
            path: target,
            cancel: None,
        })
    }

    /// Refuses what is in the target's place unless it is nothing or a regular file.
    fn check_at(dir: &OwnedFd, name: &str, shown: &Path) -> Result<(), FileError> {
        match statat(dir, name, AtFlags::SYMLINK_NOFOLLOW) {
            Err(Errno::NOENT) => Ok(()),
            Err(e) => Err(FileError::Io(shown.to_path_buf(), e.into())),
            Ok(st) => match kind(FileType::from_raw_mode(st.st_mode)) {
                None => Ok(()),
                Some(kind) => Err(FileError::NotReplaceable(shown.to_path_buf(), kind)),
            },
        }
    }

    fn kind(t: FileType) -> Option<&'static str> {
        match t {
            FileType::RegularFile => None,
            FileType::Directory => Some("a folder"),
            FileType::Symlink => Some("a symbolic link"),
            FileType::Fifo => Some("a FIFO"),
            FileType::CharacterDevice => Some("a character device"),
            FileType::BlockDevice => Some("a block device"),
            FileType::Socket => Some("a socket"),
            FileType::Unknown => Some("not a regular file"),
        }
    }

    impl Inner {
        pub(super) fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
            match self.file.as_mut() {
                Some(f) => f.write(buf),
                None => Err(io::Error::other("the file is closed")),
            }
        }

        pub(super) fn flush(&mut self) -> io::Result<()> {
            self.file.as_mut().map_or(Ok(()), |f| f.flush())
        }

        pub(super) fn commit(&mut self, shown: &Path) -> Result<(), FileError> {
            let io = |e: io::Error| FileError::Io(shown.to_path_buf(), e);
            if let Some(f) = self.file.take() {
                f.sync_all().map_err(io)?;
            }
            self.replace(shown)
        }

        /// Moves the temporary file over the target: only over nothing or a regular file.
        #[cfg(target_os = "linux")]
        fn replace(&mut self, shown: &Path) -> Result<(), FileError> {
            use rustix::fs::{RenameFlags, renameat_with};
            let (dir, tmp, target) = (&self.dir, self.tmp.as_str(), self.target.as_str());
            let io = |e: Errno| FileError::Io(shown.to_path_buf(), e.into());
            for _ in 0..8 {
                match renameat_with(dir, tmp, dir, target, RenameFlags::NOREPLACE) {
                    Ok(()) => {
                        self.done = true;
                        return Ok(());
                    }
                    Err(Errno::EXIST) => {}
                    Err(Errno::INVAL | Errno::NOSYS | Errno::OPNOTSUPP) => {
                        return self.replace_checked(shown);
                    }
                    Err(e) => return Err(io(e)),
                }
                match renameat_with(dir, tmp, dir, target, RenameFlags::EXCHANGE) {
                    Ok(()) => {}
                    // Gone in between: try to take the free name again.
                    Err(Errno::NOENT) => continue,
                    Err(Errno::INVAL | Errno::NOSYS | Errno::OPNOTSUPP) => {
                        return self.replace_checked(shown);
                    }
                    Err(e) => return Err(io(e)),
                }
                // The old entry now has the temporary name: a regular file is removed, anything
                // else goes back where it was.
                let old = statat(dir, tmp, AtFlags::SYMLINK_NOFOLLOW)
                    .map(|st| kind(FileType::from_raw_mode(st.st_mode)));
                return match old {
                    Ok(None) => {
                        self.done = true;
                        let _ = unlinkat(dir, tmp, AtFlags::empty());
                        Ok(())
                    }
                    other => {
                        let back = renameat_with(dir, tmp, dir, target, RenameFlags::EXCHANGE);
                        if back.is_err() {
                            // Both stay as they are: the user's entry under the temporary name.
                            self.done = true;
                        }
                        let kind = other.ok().flatten().unwrap_or("not a regular file");
                        Err(FileError::NotReplaceable(shown.to_path_buf(), kind))
                    }
                };
            }
            Err(io(Errno::BUSY))
        }

        #[cfg(not(target_os = "linux"))]
        fn replace(&mut self, shown: &Path) -> Result<(), FileError> {
            self.replace_checked(shown)
        }

        /// Without an exchange: look, then rename (a window where a swap goes unseen).
        fn replace_checked(&mut self, shown: &Path) -> Result<(), FileError> {
            check_at(&self.dir, &self.target, shown)?;
            renameat(
                &self.dir,
                self.tmp.as_str(),
                &self.dir,
                self.target.as_str(),
            )
            .map_err(|e| FileError::Io(shown.to_path_buf(), e.into()))?;
            self.done = true;
            Ok(())
        }
    }

    impl Drop for Inner {
        fn drop(&mut self) {
            drop(self.file.take());
            if !self.done {
                let _ = unlinkat(&self.dir, self.tmp.as_str(), AtFlags::empty());
            }
        }
    }
}

// The web (wasm32): no file system; the export is kept in memory for the page to download.
#[cfg(target_arch = "wasm32")]
mod imp {
    use super::*;

    pub(super) struct Inner {
        dir: PathBuf,
        folders: Vec<String>,
        file: String,
        bytes: Vec<u8>,
    }

    pub(super) fn create(
        base: &Path,
        folders: &[&str],
        file: &str,
        _inside: bool,
    ) -> Result<AtomicFile, FileError> {
        let path = folders
            .iter()
            .fold(base.to_path_buf(), |p, f| p.join(f))
            .join(file);
        Ok(AtomicFile {
            inner: Inner {
                dir: base.to_path_buf(),
                folders: folders.iter().map(|f| f.to_string()).collect(),
                file: file.to_string(),
                bytes: Vec::new(),
            },
            path,
            cancel: None,
        })
    }

    impl Inner {
        pub(super) fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
            self.bytes.extend_from_slice(buf);
            Ok(buf.len())
        }

        pub(super) fn flush(&mut self) -> io::Result<()> {
            Ok(())
        }

        pub(super) fn commit(&mut self, _shown: &Path) -> Result<(), FileError> {
            let folders: Vec<&str> = self.folders.iter().map(String::as_str).collect();
            crate::files::memory::write(&self.dir, &folders, &self.file, &self.bytes);
            Ok(())
        }
    }
}

#[cfg(not(any(unix, target_arch = "wasm32")))]
mod imp {
    use super::*;

    pub(super) struct Inner {
        file: Option<std::fs::File>,
        tmp: PathBuf,
        target: PathBuf,
        done: bool,
        _listed: temp::Listed,
    }

    pub(super) fn create(
        base: &Path,
        folders: &[&str],
        file: &str,
        _inside: bool,
    ) -> Result<AtomicFile, FileError> {
        let mut path = base.to_path_buf();
        let mut rel = PathBuf::new();
        for folder in folders {
            path.push(folder);
            rel.push(folder);
            match std::fs::symlink_metadata(&path) {
                Ok(m) if m.file_type().is_symlink() => {
                    return Err(FileError::Link(rel.display().to_string()));
                }
                Ok(m) if !m.is_dir() => {
                    return Err(FileError::NotAFolder(rel.display().to_string()));
                }
                Ok(_) => {}
                Err(_) => std::fs::create_dir(&path).map_err(|e| FileError::Io(path.clone(), e))?,
            }
        }
        let target = path.join(file);
        check_replaceable(&target)?;
        let tmp = path.join(temp::temp_name(file));
        let f = std::fs::File::create_new(&tmp).map_err(|e| FileError::Io(target.clone(), e))?;
        Ok(AtomicFile {
            inner: Inner {
                file: Some(f),
                tmp: tmp.clone(),
                target: target.clone(),
                done: false,
                _listed: temp::list(tmp),
            },
            path: target,
            cancel: None,
        })
    }

    impl Inner {
        pub(super) fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
            match self.file.as_mut() {
                Some(f) => f.write(buf),
                None => Err(io::Error::other("the file is closed")),
            }
        }

        pub(super) fn flush(&mut self) -> io::Result<()> {
            self.file.as_mut().map_or(Ok(()), |f| f.flush())
        }

        pub(super) fn commit(&mut self, shown: &Path) -> Result<(), FileError> {
            let io = |e: io::Error| FileError::Io(shown.to_path_buf(), e);
            if let Some(f) = self.file.take() {
                f.sync_all().map_err(io)?;
            }
            check_replaceable(&self.target)?;
            std::fs::rename(&self.tmp, &self.target).map_err(io)?;
            self.done = true;
            Ok(())
        }
    }

    impl Drop for Inner {
        fn drop(&mut self) {
            drop(self.file.take());
            if !self.done {
                let _ = std::fs::remove_file(&self.tmp);
            }
        }
    }
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;

    /// A scratch folder removed at the end.
    struct Scratch(PathBuf);

    impl Scratch {
        fn new(name: &str) -> Self {
            let p = std::env::temp_dir().join(format!("cnets-{name}-{}", std::process::id()));
            let _ = std::fs::remove_dir_all(&p);
            std::fs::create_dir_all(&p).unwrap();
            Scratch(p)
        }
    }

    impl Drop for Scratch {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }

    fn leftovers(dir: &Path) -> Vec<String> {
        std::fs::read_dir(dir)
            .unwrap()
            .flatten()
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".tmp"))
            .collect()
    }

    fn mkfifo(path: &Path) {
        rustix::fs::mknodat(
            rustix::fs::CWD,
            path,
            rustix::fs::FileType::Fifo,
            rustix::fs::Mode::from_raw_mode(0o644),
            0,
        )
        .unwrap();
    }

    #[test]
    fn writes_stay_inside_and_links_are_not_followed() {
        let base = Scratch::new("write");
        let (out, elsewhere) = (base.0.join("out"), base.0.join("elsewhere"));
        std::fs::create_dir_all(&out).unwrap();
        std::fs::create_dir_all(&elsewhere).unwrap();
        std::os::unix::fs::symlink(&elsewhere, out.join("link")).unwrap();

        let p = write_inside(&out, &["a", "b", "m.obj"], b"v 0 0 0\n").unwrap();
        assert_eq!(p, out.join("a/b/m.obj"));
        assert_eq!(std::fs::read(&p).unwrap(), b"v 0 0 0\n");
        // A regular file is replaced.
        write_inside(&out, &["a", "b", "m.obj"], b"v 1 1 1\n").unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), b"v 1 1 1\n");

        let e = write_inside(&out, &["link", "escaped.obj"], b"x").unwrap_err();
        assert!(
            e.to_string()
                .contains("'link' inside the output directory is a symbolic link")
        );
        assert!(!elsewhere.join("escaped.obj").exists());

        // A link as the file itself is neither written through nor replaced.
        let victim = elsewhere.join("victim.txt");
        std::fs::write(&victim, b"keep").unwrap();
        std::os::unix::fs::symlink(&victim, out.join("f.obj")).unwrap();
        let e = write_inside(&out, &["f.obj"], b"new").unwrap_err();
        assert!(
            matches!(e, FileError::NotReplaceable(_, "a symbolic link")),
            "{e}"
        );
        assert_eq!(std::fs::read(&victim).unwrap(), b"keep");
        assert!(out.join("f.obj").is_symlink());
        assert!(leftovers(&out).is_empty());
    }

    #[test]
    fn only_nothing_or_a_regular_file_is_replaced() {
        let base = Scratch::new("replace");
        let dir = &base.0;
        let fifo = dir.join("fifo.png");
        mkfifo(&fifo);
        std::fs::create_dir(dir.join("folder.png")).unwrap();
        for (name, kind) in [("fifo.png", "a FIFO"), ("folder.png", "a folder")] {
            let path = dir.join(name);
            assert!(
                matches!(check_replaceable(&path), Err(FileError::NotReplaceable(_, k)) if k == kind)
            );
            let e = write_file(&path, b"png").unwrap_err();
            assert!(e.to_string().contains(kind), "{e}");
            assert!(e.to_string().contains("only a regular file"), "{e}");
        }
        use std::os::unix::fs::FileTypeExt;
        assert!(
            std::fs::symlink_metadata(&fifo)
                .unwrap()
                .file_type()
                .is_fifo()
        );
        assert!(matches!(
            check_replaceable(Path::new("/dev/null")),
            Err(FileError::NotReplaceable(_, "a character device"))
        ));
        assert!(matches!(
            write_file(Path::new("/dev/null"), b"x"),
            Err(FileError::NotReplaceable(..)) | Err(FileError::Io(..))
        ));
        // Nothing there, then a regular file: written, then replaced.
        let png = dir.join("a.png");
        check_replaceable(&png).unwrap();
        write_file(&png, b"one").unwrap();
        write_file(&png, b"two").unwrap();
        assert_eq!(std::fs::read(&png).unwrap(), b"two");
        assert!(leftovers(dir).is_empty());
    }

    #[test]
    fn a_cancelled_or_dropped_write_leaves_nothing() {
        let base = Scratch::new("cancel");
        let dir = &base.0;
        std::fs::write(dir.join("keep.obj"), b"old").unwrap();
        let flag = Arc::new(AtomicBool::new(false));
        let mut file = create_file(&dir.join("keep.obj"))
            .unwrap()
            .with_cancel(flag.clone());
        file.write_all(b"partial").unwrap();
        assert_eq!(leftovers(dir).len(), 1, "the temporary file while writing");
        flag.store(true, Ordering::Relaxed);
        let e = file.write_all(b"more").unwrap_err();
        assert_eq!(
            file.error(e).to_string(),
            format!("{}: cancelled", dir.join("keep.obj").display())
        );
        drop(file);
        assert!(leftovers(dir).is_empty());
        assert_eq!(std::fs::read(dir.join("keep.obj")).unwrap(), b"old");
    }

    #[test]
    fn stale_files_are_removed_only_when_ours_unlocked_and_old() {
        let base = Scratch::new("stale");
        let dir = &base.0;
        let old = std::time::SystemTime::now() - temp::STALE_AFTER * 2;
        let age = |p: &Path| {
            std::fs::File::options()
                .write(true)
                .open(p)
                .unwrap()
                .set_modified(old)
                .unwrap()
        };
        // Abandoned: our marker, nobody's lock, old.
        let abandoned = dir.join(temp::temp_name("m.obj"));
        std::fs::write(&abandoned, b"x").unwrap();
        age(&abandoned);
        // A live writer's (locked), even when old; a fresh one; a user's files of other shapes.
        let live = create_file(&dir.join("live.obj")).unwrap();
        let live_tmp = leftovers(dir)
            .into_iter()
            .find(|n| n.starts_with(".live.obj"))
            .unwrap();
        age(&dir.join(&live_tmp));
        let fresh = dir.join(temp::temp_name("n.obj"));
        std::fs::write(&fresh, b"x").unwrap();
        let user = [".m.obj.1234.7.tmp", ".m.obj.4000000000.3.tmp", ".notes.tmp"];
        for name in user {
            std::fs::write(dir.join(name), b"mine").unwrap();
            age(&dir.join(name));
        }
        let fifo = dir.join(temp::temp_name("p.obj"));
        mkfifo(&fifo);

        assert_eq!(temp::remove_stale(dir), 1);
        assert!(!abandoned.exists());
        assert!(dir.join(&live_tmp).exists() && fresh.exists() && fifo.exists());
        for name in user {
            assert!(dir.join(name).exists(), "{name}");
        }
        drop(live);
        assert!(!dir.join(&live_tmp).exists());
    }
}
