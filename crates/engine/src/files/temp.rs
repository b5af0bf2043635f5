//! Temporary files of atomic writes: `.<name>.<pid>.<n>.tmp` beside the target.
//!
//! A process killed mid-write (`kill -9`) leaves its temporary file behind; the next export into
//! that folder removes the ones whose process is gone ([`remove_stale`], Linux: a process is gone
//! when `/proc/<pid>` is). A process's own temporary files are listed while they exist so a
//! SIGINT/SIGTERM handler can remove them ([`remove_own`]).

use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};

static COUNTER: AtomicU64 = AtomicU64::new(0);
static OWN: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn own() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    OWN.lock().unwrap_or_else(|p| p.into_inner())
}

/// A fresh temporary name for writing `file` (`.<file>.<pid>.<n>.tmp`).
pub fn temp_name(file: &str) -> String {
    format!(
        ".{file}.{}.{}.tmp",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    )
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

/// The process id in a temporary name of this scheme (`.<name>.<pid>.<n>.tmp`).
pub fn temp_owner(name: &str) -> Option<u32> {
    let inner = name.strip_prefix('.')?.strip_suffix(".tmp")?;
    let mut parts = inner.rsplitn(3, '.');
    let n = parts.next()?;
    let pid = parts.next()?;
    let target = parts.next()?;
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    (digits(n) && !target.is_empty()).then_some(())?;
    digits(pid).then(|| pid.parse().ok()).flatten()
}

/// True when process `pid` is still running (Linux: `/proc/<pid>` exists). Where that cannot be
/// told, a process counts as alive, so nothing of a live process is removed.
pub fn alive(pid: u32) -> bool {
    if pid == std::process::id() {
        return true;
    }
    let proc = Path::new("/proc");
    if !proc.join("self").exists() {
        return true;
    }
    proc.join(pid.to_string()).exists()
}

/// Removes, in `dir`, temporary files of this scheme whose process is gone; returns how many.
pub fn remove_stale(dir: &Path) -> usize {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return 0;
    };
    entries
        .flatten()
        .filter(|e| {
            let name = e.file_name();
            let name = name.to_string_lossy();
            temp_owner(&name).is_some_and(|pid| !alive(pid))
                && e.file_type().is_ok_and(|t| t.is_file())
                && std::fs::remove_file(e.path()).is_ok()
        })
        .count()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn owners_are_read_from_temporary_names() {
        assert_eq!(temp_owner(".mesh.obj.1234.7.tmp"), Some(1234));
        assert_eq!(temp_owner(".a.b.c.99.0.tmp"), Some(99));
        assert_eq!(temp_owner("mesh.obj.1234.7.tmp"), None);
        assert_eq!(temp_owner(".mesh.obj.12x.7.tmp"), None);
        assert_eq!(temp_owner(".1234.7.tmp"), None);
        assert_eq!(temp_owner(".obj"), None);
    }

    #[test]
    fn stale_files_of_dead_processes_go_and_others_stay() {
        let dir = std::env::temp_dir().join(format!("cnets-temp-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        // No process has pid 4 000 000 000 (above Linux's pid_max).
        let dead = dir.join(".m.obj.4000000000.3.tmp");
        let mine = dir.join(format!(".m.obj.{}.3.tmp", std::process::id()));
        let other = dir.join(".notes.tmp");
        for p in [&dead, &mine, &other] {
            std::fs::write(p, b"x").unwrap();
        }
        assert_eq!(
            remove_stale(&dir),
            usize::from(Path::new("/proc/self").exists())
        );
        assert!(mine.exists() && other.exists());
        let listed = list(mine.clone());
        assert_eq!(remove_own(), 1);
        assert!(!mine.exists());
        drop(listed);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
