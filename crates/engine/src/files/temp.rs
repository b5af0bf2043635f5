//! Temporary files of atomic writes: `.<name>.cnets-tmp-<random>.tmp` beside the target, created
//! exclusively and locked (`flock`) by the writing process for as long as it writes.
//!
//! A process killed mid-write (`kill -9`) leaves its temporary file behind. The next write into
//! that folder removes it ([`remove_stale`]) only when it is provably ours and abandoned: its name
//! carries the marker and a random part no user file has by chance, it is a regular file, nobody
//! holds its lock (a lock dies with its process, in every PID namespace: two containers sharing
//! a folder see each other's live writes as locked) and it is older than [`STALE_AFTER`] (the
//! instant between creating a file and locking it). Process ids are not used: a live writer in
//! another PID namespace has a pid this process cannot see. A process's own temporary files are
//! listed while they exist so a SIGINT/SIGTERM handler can remove them ([`remove_own`]).

use std::hash::{BuildHasher, Hasher};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;

/// What every temporary name carries between the target's name and the random part.
pub const MARKER: &str = ".cnets-tmp-";

/// How old an unlocked temporary file must be before it counts as abandoned.
pub const STALE_AFTER: Duration = Duration::from_secs(30);

/// The longest target name kept whole in a temporary name (a file name has at most 255 bytes).
const NAME_KEPT: usize = 200;

static COUNTER: AtomicU64 = AtomicU64::new(0);
static OWN: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn own() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    OWN.lock().unwrap_or_else(|p| p.into_inner())
}

/// 64 random bits: the OS-seeded hasher of the standard library over a counter, the pid and the
/// time (no random crate needed for a name that only has to be unique).
fn random() -> u64 {
    let mut h = std::collections::hash_map::RandomState::new().build_hasher();
    h.write_u64(COUNTER.fetch_add(1, Ordering::Relaxed));
    h.write_u32(std::process::id());
    if let Ok(t) = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH) {
        h.write_u128(t.as_nanos());
    }
    h.finish()
}

/// A fresh temporary name for writing `file`: `.<file>.cnets-tmp-<16 hex digits>.tmp` (a long
/// `file` is cut to its first 200 bytes).
pub fn temp_name(file: &str) -> String {
    let mut cut = file.len().min(NAME_KEPT);
    while !file.is_char_boundary(cut) {
        cut -= 1;
    }
    format!(".{}{MARKER}{:016x}.tmp", &file[..cut], random())
}

/// True when `name` has the shape of [`temp_name`]'s names.
pub fn is_temp_name(name: &str) -> bool {
    let Some(inner) = name.strip_prefix('.').and_then(|n| n.strip_suffix(".tmp")) else {
        return false;
    };
    inner.rsplit_once(MARKER).is_some_and(|(target, random)| {
        !target.is_empty() && random.len() == 16 && random.bytes().all(|b| b.is_ascii_hexdigit())
    })
}

/// A temporary file listed for [`remove_own`] while this lives.
#[derive(Debug)]
pub struct Listed(PathBuf);

/// Lists `path` as one of this process's temporary files until the returned guard drops.
pub fn list(path: PathBuf) -> Listed {
    own().push(path.clone());
    Listed(path)
}

impl Drop for Listed {
    fn drop(&mut self) {
        let mut own = own();
        if let Some(k) = own.iter().position(|p| *p == self.0) {
            own.swap_remove(k);
        }
    }
}

/// Removes this process's temporary files (for a SIGINT/SIGTERM handler); returns how many.
pub fn remove_own() -> usize {
    let own = own();
    own.iter()
        .filter(|p| std::fs::remove_file(p).is_ok())
        .count()
}

/// Removes, in `dir`, the abandoned temporary files of this scheme (see the module); returns how
/// many. Files of other shapes, live writers' files and anything that is not a regular file stay.
pub fn remove_stale(dir: &Path) -> usize {
    imp::remove_stale(dir)
}

#[cfg(unix)]
pub(crate) use imp::{create_locked, remove_stale_in};

#[cfg(unix)]
mod imp {
    use super::*;
    use rustix::fd::{AsFd, BorrowedFd, OwnedFd};
    use rustix::fs::{AtFlags, CWD, FileType, FlockOperation, Mode, OFlags};
    use rustix::io::Errno;

    /// Creates the temporary file `name` in `dir` (exclusively, without following a link) and
    /// locks it for as long as the returned descriptor is open.
    pub(crate) fn create_locked(dir: BorrowedFd<'_>, name: &str) -> Result<OwnedFd, Errno> {
        let fd = rustix::fs::openat(
            dir,
            name,
            OFlags::WRONLY | OFlags::CREATE | OFlags::EXCL | OFlags::NOFOLLOW | OFlags::CLOEXEC,
            Mode::from_raw_mode(0o644),
        )?;
        // Nobody else can hold the lock of a file just created exclusively: this cannot block.
        if let Err(e) = rustix::fs::flock(&fd, FlockOperation::NonBlockingLockExclusive) {
            let _ = rustix::fs::unlinkat(dir, name, AtFlags::empty());
            return Err(e);
        }
        Ok(fd)
    }

    pub(super) fn remove_stale(dir: &Path) -> usize {
        match rustix::fs::openat(
            CWD,
            dir,
            OFlags::RDONLY | OFlags::DIRECTORY | OFlags::CLOEXEC,
            Mode::empty(),
        ) {
            Ok(fd) => remove_stale_in(fd.as_fd(), dir),
            Err(_) => 0,
        }
    }

    /// [`remove_stale`] in the open folder `dir` (whose path `shown` is for listing only).
    pub(crate) fn remove_stale_in(dir: BorrowedFd<'_>, shown: &Path) -> usize {
        let Ok(entries) = std::fs::read_dir(shown) else {
            return 0;
        };
        entries
            .flatten()
            .filter(|e| {
                let name = e.file_name();
                let Some(name) = name.to_str() else {
                    return false;
                };
                // The lock is held until the file is gone.
                is_temp_name(name)
                    && abandoned(dir, name).is_some_and(|_locked| {
                        rustix::fs::unlinkat(dir, name, AtFlags::empty()).is_ok()
                    })
            })
            .count()
    }

    /// The file `name` in `dir`, locked by this process, when it is a regular file older than
    /// [`STALE_AFTER`] whose lock nobody held.
    fn abandoned(dir: BorrowedFd<'_>, name: &str) -> Option<OwnedFd> {
        let fd = rustix::fs::openat(
            dir,
            name,
            OFlags::RDONLY | OFlags::NOFOLLOW | OFlags::NONBLOCK | OFlags::CLOEXEC,
            Mode::empty(),
        )
        .ok()?;
        let st = rustix::fs::fstat(&fd).ok()?;
        if FileType::from_raw_mode(st.st_mode) != FileType::RegularFile {
            return None;
        }
        let modified = std::time::UNIX_EPOCH + Duration::from_secs(st.st_mtime.max(0) as u64);
        let old = std::time::SystemTime::now()
            .duration_since(modified)
            .is_ok_and(|age| age > STALE_AFTER);
        if !old {
            return None;
        }
        rustix::fs::flock(&fd, FlockOperation::NonBlockingLockExclusive).ok()?;
        // Still the same file under that name (not replaced since it was opened).
        let now = rustix::fs::statat(dir, name, AtFlags::SYMLINK_NOFOLLOW).ok()?;
        (now.st_dev == st.st_dev && now.st_ino == st.st_ino).then_some(fd)
    }
}

#[cfg(not(unix))]
mod imp {
    use super::*;

    /// Without file locks nothing proves a temporary file abandoned: nothing is removed.
    pub(super) fn remove_stale(_dir: &Path) -> usize {
        0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn temporary_names_carry_the_marker_and_a_random_part() {
        let a = temp_name("mesh.obj");
        assert!(
            a.starts_with(".mesh.obj.cnets-tmp-") && a.ends_with(".tmp"),
            "{a}"
        );
        assert!(is_temp_name(&a));
        assert_ne!(a, temp_name("mesh.obj"));
        assert!(temp_name(&"é".repeat(300)).len() < 255);
        for other in [
            ".mesh.obj.1234.7.tmp",
            "mesh.obj.cnets-tmp-0123456789abcdef.tmp",
            ".mesh.obj.cnets-tmp-0123.tmp",
            ".cnets-tmp-0123456789abcdef.tmp",
            ".notes.tmp",
        ] {
            assert!(!is_temp_name(other), "{other}");
        }
    }
}
