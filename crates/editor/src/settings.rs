//! Persistent settings: the editor's own folder, the recent-files list, the library folder and
//! per-document settings (the files and folders a document may read besides its own folder: a file
//! picked with Browse…, a folder allowed at a prompt — kept here, never in the graph file).
//!
//! The folder is `$CNETS_EDITOR_HOME` when set (tests use a temporary one), else
//! `$XDG_CONFIG_HOME/cnets-editor`, else `~/.config/cnets-editor`. Files in it are small text
//! files written atomically.

use std::path::{Path, PathBuf};

use cnets_engine::atomic::write_atomic;

/// Most recent files remembered.
pub const MAX_RECENT: usize = 10;

/// The editor's settings folder (see the module docs); not created here.
pub fn config_dir() -> PathBuf {
    if let Some(dir) = std::env::var_os("CNETS_EDITOR_HOME").filter(|d| !d.is_empty()) {
        return PathBuf::from(dir);
    }
    if let Some(dir) = std::env::var_os("XDG_CONFIG_HOME").filter(|d| !d.is_empty()) {
        return PathBuf::from(dir).join("cnets-editor");
    }
    let home = std::env::var_os("HOME").map_or_else(|| PathBuf::from("."), PathBuf::from);
    home.join(".config").join("cnets-editor")
}

/// Settings kept between sessions.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Settings {
    /// Where they are stored.
    pub dir: PathBuf,
    /// Recently opened or saved files, newest first.
    pub recent: Vec<PathBuf>,
    /// The user library folder chosen in the editor (`None`: the default,
    /// [`crate::library::default_library_dir`]).
    pub library: Option<PathBuf>,
    /// The top of the planarity colour scale set in the viewport (`viewport.txt`), as `f64`
    /// bits (see [`Settings::planarity_limit`]).
    planarity_limit: Option<u64>,
    /// Per document (its canonical path): files and folders its nodes may read besides its own
    /// folder (`allowed-reads.txt`, a `document<TAB>path` line each).
    allowed_reads: Vec<(PathBuf, PathBuf)>,
}

/// A document's key in the per-document settings: its canonical path (as given when it has none).
fn document_key(doc: &Path) -> PathBuf {
    std::fs::canonicalize(doc).unwrap_or_else(|_| doc.to_path_buf())
}

impl Settings {
    /// Loads the settings from `dir` (missing files: defaults).
    pub fn load(dir: &Path) -> Self {
        let recent = std::fs::read_to_string(dir.join("recent.txt"))
            .unwrap_or_default()
            .lines()
            .filter(|l| !l.trim().is_empty())
            .map(PathBuf::from)
            .take(MAX_RECENT)
            .collect();
        let library = std::fs::read_to_string(dir.join("library.txt"))
            .ok()
            .map(|t| t.trim().to_string())
            .filter(|t| !t.is_empty())
            .map(PathBuf::from);
        let planarity_limit = std::fs::read_to_string(dir.join("viewport.txt"))
            .unwrap_or_default()
            .lines()
            .find_map(|l| {
                let (key, value) = l.split_once('=')?;
                (key.trim() == "planarity_limit").then(|| value.trim().parse::<f64>().ok())?
            })
            .filter(|v| v.is_finite() && *v > 0.0)
            .map(f64::to_bits);
        let allowed_reads = std::fs::read_to_string(dir.join("allowed-reads.txt"))
            .unwrap_or_default()
            .lines()
            .filter_map(|l| {
                let (doc, path) = l.split_once('\t')?;
                (!doc.is_empty() && !path.is_empty())
                    .then(|| (PathBuf::from(doc), PathBuf::from(path)))
            })
            .collect();
        Self {
            dir: dir.to_path_buf(),
            recent,
            library,
            planarity_limit,
            allowed_reads,
        }
    }

    /// The files and folders the document saved at `doc` may read besides its own folder (in the
    /// order they were allowed).
    pub fn allowed_reads(&self, doc: &Path) -> Vec<PathBuf> {
        let key = document_key(doc);
        self.allowed_reads
            .iter()
            .filter(|(d, _)| *d == key)
            .map(|(_, p)| p.clone())
            .collect()
    }

    /// Lets the document saved at `doc` read `path` (a file or a folder) from now on, in this and
    /// later sessions, and saves the settings. Returns whether it was new.
    pub fn allow_read(&mut self, doc: &Path, path: &Path) -> bool {
        let entry = (document_key(doc), path.to_path_buf());
        if self.allowed_reads.contains(&entry) {
            return false;
        }
        self.allowed_reads.push(entry);
        let _ = self.save();
        true
    }

    /// The top of the planarity colour scale the designer set in the viewport, if any.
    pub fn planarity_limit(&self) -> Option<f64> {
        self.planarity_limit.map(f64::from_bits)
    }

    /// Remembers the top of the planarity colour scale and saves the settings.
    pub fn set_planarity_limit(&mut self, limit: f64) {
        self.planarity_limit = Some(limit.to_bits());
        let _ = self.save();
    }

    /// The user library folder: the chosen one, else the default.
    pub fn library_dir(&self) -> PathBuf {
        self.library
            .clone()
            .unwrap_or_else(crate::library::default_library_dir)
    }

    /// Chooses the user library folder and saves the choice.
    pub fn set_library(&mut self, dir: &Path) {
        self.library = Some(dir.to_path_buf());
        let _ = self.save();
    }

    /// Puts `path` first in the recent list and saves the list.
    pub fn add_recent(&mut self, path: &Path) {
        let path = std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf());
        self.recent.retain(|p| p != &path);
        self.recent.insert(0, path);
        self.recent.truncate(MAX_RECENT);
        let _ = self.save();
    }

    /// Writes the settings (creating the folder).
    pub fn save(&self) -> std::io::Result<()> {
        std::fs::create_dir_all(&self.dir)?;
        let text: String = self
            .recent
            .iter()
            .map(|p| format!("{}\n", p.display()))
            .collect();
        write_atomic(&self.dir.join("recent.txt"), text.as_bytes())?;
        if let Some(limit) = self.planarity_limit() {
            write_atomic(
                &self.dir.join("viewport.txt"),
                format!("planarity_limit = {limit:e}\n").as_bytes(),
            )?;
        }
        if !self.allowed_reads.is_empty() {
            let text: String = self
                .allowed_reads
                .iter()
                .map(|(d, p)| format!("{}\t{}\n", d.display(), p.display()))
                .collect();
            write_atomic(&self.dir.join("allowed-reads.txt"), text.as_bytes())?;
        }
        if let Some(lib) = &self.library {
            write_atomic(
                &self.dir.join("library.txt"),
                format!("{}\n", lib.display()).as_bytes(),
            )?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recent_files_persist_newest_first_without_duplicates() {
        let dir = std::env::temp_dir().join(format!("cnets-settings-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let mut s = Settings::load(&dir);
        assert!(s.recent.is_empty());
        for k in 0..12 {
            s.add_recent(Path::new(&format!("/tmp/g{k}.ron")));
        }
        s.add_recent(Path::new("/tmp/g5.ron"));
        let again = Settings::load(&dir);
        assert_eq!(again.recent.len(), MAX_RECENT);
        assert_eq!(again.recent[0], PathBuf::from("/tmp/g5.ron"));
        assert_eq!(again.recent[1], PathBuf::from("/tmp/g11.ron"));
        assert_eq!(
            again
                .recent
                .iter()
                .filter(|p| p.ends_with("g5.ron"))
                .count(),
            1
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn allowed_reads_are_kept_per_document_across_sessions() {
        let dir = std::env::temp_dir().join(format!("cnets-settings-ar-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let mut s = Settings::load(&dir);
        let (a, b) = (
            Path::new("/tmp/a/design.ron"),
            Path::new("/tmp/b/design.ron"),
        );
        assert!(s.allowed_reads(a).is_empty());
        assert!(s.allow_read(a, Path::new("/data/scans")));
        assert!(s.allow_read(a, Path::new("/data/site.svg")));
        assert!(
            !s.allow_read(a, Path::new("/data/scans")),
            "already allowed"
        );
        assert!(s.allow_read(b, Path::new("/elsewhere")));
        let again = Settings::load(&dir);
        assert_eq!(
            again.allowed_reads(a),
            vec![
                PathBuf::from("/data/scans"),
                PathBuf::from("/data/site.svg")
            ]
        );
        assert_eq!(again.allowed_reads(b), vec![PathBuf::from("/elsewhere")]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn the_planarity_limit_persists_and_bad_files_are_ignored() {
        let dir = std::env::temp_dir().join(format!("cnets-settings-pl-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let mut s = Settings::load(&dir);
        assert_eq!(s.planarity_limit(), None);
        s.set_planarity_limit(2.5e-5);
        assert_eq!(Settings::load(&dir).planarity_limit(), Some(2.5e-5));
        for junk in [
            "planarity_limit = nan\n",
            "planarity_limit = -1\n",
            "garbage",
        ] {
            std::fs::write(dir.join("viewport.txt"), junk).unwrap();
            assert_eq!(Settings::load(&dir).planarity_limit(), None, "{junk}");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
