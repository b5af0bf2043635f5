//! Writing an export inside the output directory without following links out of it.

#[cfg(unix)]
use std::io::Write;
use std::path::{Path, PathBuf};

use super::FileError;
#[cfg(not(target_arch = "wasm32"))]
use super::temp;

/// Writes `bytes` to the file named by `parts` (folders, then the file name, as
/// [`check_export_name`](super::check_export_name) returns them) inside `out_dir`, atomically:
/// missing folders are created; every folder below `out_dir` is opened relative to the one above
/// it without following a symbolic link (`openat` + `O_NOFOLLOW`), so `out/link → /elsewhere`
/// cannot take a write outside; the bytes go to a temporary file in the final folder, synced, then
/// renamed over the target (a link there is replaced, not followed). Stale temporary files of dead
/// processes in that folder are removed first. Returns the written path.
pub fn write_inside(out_dir: &Path, parts: &[&str], bytes: &[u8]) -> Result<PathBuf, FileError> {
    let Some((file, folders)) = parts.split_last() else {
        return Err(FileError::BadName(String::new(), "is empty"));
    };
    imp::write(out_dir, folders, file, bytes)
}

#[cfg(unix)]
mod imp {
    use super::*;
    use rustix::fs::{
        AtFlags, CWD, FileType, Mode, OFlags, mkdirat, openat, renameat, statat, unlinkat,
    };
    use rustix::io::Errno;

    pub(super) fn write(
        out_dir: &Path,
        folders: &[&str],
        file: &str,
        bytes: &[u8],
    ) -> Result<PathBuf, FileError> {
        let io = |p: &Path, e: Errno| FileError::Io(p.to_path_buf(), e.into());
        let dir_flags = OFlags::RDONLY | OFlags::DIRECTORY | OFlags::CLOEXEC;
        let mut dir = openat(CWD, out_dir, dir_flags, Mode::empty()).map_err(|e| io(out_dir, e))?;
        let mut path = out_dir.to_path_buf();
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
        temp::remove_stale(&path);
        let tmp = temp::temp_name(file);
        let target = path.join(file);
        let fd = openat(
            &dir,
            tmp.as_str(),
            OFlags::WRONLY | OFlags::CREATE | OFlags::EXCL | OFlags::NOFOLLOW | OFlags::CLOEXEC,
            Mode::from_raw_mode(0o644),
        )
        .map_err(|e| io(&target, e))?;
        let _listed = temp::list(path.join(&tmp));
        let written = (|| {
            let mut f = std::fs::File::from(fd);
            f.write_all(bytes)?;
            f.sync_all()?;
            drop(f);
            renameat(&dir, tmp.as_str(), &dir, file).map_err(std::io::Error::from)
        })();
        if let Err(e) = written {
            let _ = unlinkat(&dir, tmp.as_str(), AtFlags::empty());
            return Err(FileError::Io(target, e));
        }
        Ok(target)
    }
}

// The web (wasm32): no file system; the export is kept in memory for the page to download.
#[cfg(target_arch = "wasm32")]
mod imp {
    use super::*;

    pub(super) fn write(
        out_dir: &Path,
        folders: &[&str],
        file: &str,
        bytes: &[u8],
    ) -> Result<PathBuf, FileError> {
        Ok(crate::files::memory::write(out_dir, folders, file, bytes))
    }
}

#[cfg(not(any(unix, target_arch = "wasm32")))]
mod imp {
    use super::*;

    pub(super) fn write(
        out_dir: &Path,
        folders: &[&str],
        file: &str,
        bytes: &[u8],
    ) -> Result<PathBuf, FileError> {
        let mut path = out_dir.to_path_buf();
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
        temp::remove_stale(&path);
        let target = path.join(file);
        crate::atomic::write_atomic(&target, bytes)
            .map_err(|e| FileError::Io(target.clone(), e))?;
        Ok(target)
    }
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;

    #[test]
    fn writes_stay_inside_and_links_are_not_followed() {
        let base = std::env::temp_dir().join(format!("cnets-write-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&base);
        let (out, elsewhere) = (base.join("out"), base.join("elsewhere"));
        std::fs::create_dir_all(&out).unwrap();
        std::fs::create_dir_all(&elsewhere).unwrap();
        std::os::unix::fs::symlink(&elsewhere, out.join("link")).unwrap();

        let p = write_inside(&out, &["a", "b", "m.obj"], b"v 0 0 0\n").unwrap();
        assert_eq!(p, out.join("a/b/m.obj"));
        assert_eq!(std::fs::read(&p).unwrap(), b"v 0 0 0\n");

        let e = write_inside(&out, &["link", "escaped.obj"], b"x").unwrap_err();
        assert!(
            e.to_string()
                .contains("'link' inside the output directory is a symbolic link")
        );
        assert!(!elsewhere.join("escaped.obj").exists());

        // A link as the file itself is replaced, not written through.
        let victim = elsewhere.join("victim.txt");
        std::fs::write(&victim, b"keep").unwrap();
        std::os::unix::fs::symlink(&victim, out.join("f.obj")).unwrap();
        write_inside(&out, &["f.obj"], b"new").unwrap();
        assert_eq!(std::fs::read(&victim).unwrap(), b"keep");
        assert_eq!(std::fs::read(out.join("f.obj")).unwrap(), b"new");
        let leftovers: Vec<_> = std::fs::read_dir(&out)
            .unwrap()
            .flatten()
            .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
            .collect();
        assert!(leftovers.is_empty());
        std::fs::remove_dir_all(&base).unwrap();
    }
}
