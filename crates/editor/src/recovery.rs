//! Crash recovery: the document is autosaved to a recovery file while it has unsaved changes;
//! a clean exit (or a save) removes it, so finding one at start means the last session ended
//! without saving, and the editor offers to restore it.
//!
//! When: every committed edit (a drag or handle release, a text field left, a wire, an added or
//! deleted node) is written in the frame it is committed (edits committed in quick succession at
//! most every [`AUTOSAVE_GAP`]); during a gesture (a slider being dragged) at most once per
//! [`AUTOSAVE_WITHIN`]; the app asks for a frame when a write is due, so the file is never more
//! than a second behind what the window shows.
//!
//! Files in the settings folder: `recovery.ron` (the graph's canonical text, written atomically)
//! and `recovery.path` (first line: the document's own path, if it had one; second line: the
//! example an untitled copy came from, if any). In the browser the same two texts are kept in the
//! page's local storage instead (a [`RecoveryStore`] of the web page, `crates/web`).

use std::path::{Path, PathBuf};
use std::sync::Arc;
use web_time::{Duration, Instant};

use cnets_engine::atomic::write_atomic;

use crate::document::GraphDocument;

mod background;

pub use background::TextJob;
use background::{Background, Finished};

/// During a gesture, the recovery file is rewritten at least this often.
pub const AUTOSAVE_WITHIN: Duration = Duration::from_secs(1);

/// Committed edits in quick succession (keys held on a value) are written at most this often.
pub const AUTOSAVE_GAP: Duration = Duration::from_millis(250);

/// After a failed write, autosave tries again after this long, twice as long after each further
/// failure, up to [`AUTOSAVE_RETRY_MAX`]: a store that refuses (a full disk, the page's local
/// storage over its quota) is not asked again every frame, nor the document written out for it.
pub const AUTOSAVE_RETRY: Duration = Duration::from_secs(5);

/// The longest wait between autosave attempts after failures.
pub const AUTOSAVE_RETRY_MAX: Duration = Duration::from_secs(300);

/// A recovery file found at start.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Recovered {
    /// The graph text.
    pub text: String,
    /// The path the document had.
    pub path: Option<PathBuf>,
    /// The example the document was an untitled copy of.
    pub origin: Option<PathBuf>,
}

/// What [`Recovery::tick`] did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Autosave {
    /// Nothing to write (clean document, or already written).
    Idle,
    /// Wrote the recovery file.
    Wrote,
    /// A write is due after this long (a gesture is in progress): ask for a frame then.
    Due(Duration),
    /// A write is in progress on autosave's thread ([`Recovery::in_background`]), which wakes
    /// the window when it ends.
    Writing,
    /// Writing failed ([`Recovery::last_error`] says why); the next try is after this long.
    Failed(Duration),
}

/// Where the recovery texts are kept, by name (`recovery.ron`, `recovery.path`).
pub trait RecoveryStore {
    /// The text stored under `name`, if any.
    fn read(&self, name: &str) -> Option<String>;
    /// Stores `text` under `name` (replacing it whole, or not at all).
    fn write(&mut self, name: &str, text: &str) -> std::io::Result<()>;
    /// Removes what is stored under `name`.
    fn remove(&mut self, name: &str);
    /// Why a text of at least `len` bytes would be refused, known before it is written out.
    fn refuses(&self, len: usize) -> Option<std::io::Error> {
        let _ = len;
        None
    }
    /// Where the texts go, as the status bar names it ("the recovery file", "local storage").
    fn place(&self) -> &str {
        "the recovery file"
    }
}

/// What autosave writes: the document's text, written out only when it is written, and a cheap
/// lower bound of its length (a store that cannot keep it refuses before it is written out).
pub trait DesignText {
    /// The document's text.
    fn text(&self) -> String;
    /// At most the text's length in bytes.
    fn len_at_least(&self) -> usize {
        0
    }
    /// The text to be written out elsewhere (autosave's thread), when it can be.
    fn snapshot(&self) -> Option<TextJob> {
        None
    }
}

impl<F: Fn() -> String> DesignText for F {
    fn text(&self) -> String {
        self()
    }
}

impl DesignText for &GraphDocument {
    fn text(&self) -> String {
        self.to_ron()
    }

    fn len_at_least(&self) -> usize {
        text_len_at_least(&self.graph)
    }

    fn snapshot(&self) -> Option<TextJob> {
        let (graph, meta) = self.text_parts();
        Some(Box::new(move || cnets_engine::file::to_ron(&graph, &meta)))
    }
}

/// At most the length of `graph`'s RON text: two bytes for each item of its literal values (a
/// digit and a separator at least). Large designs are large by their literals.
pub fn text_len_at_least(graph: &cnets_engine::Graph) -> usize {
    fn items(v: &cnets_engine::Value) -> usize {
        match v {
            cnets_engine::Value::List(list) => match list.as_packed() {
                Some(packed) => packed.len(),
                None => v.as_list().unwrap_or(&[]).iter().map(items).sum(),
            },
            cnets_engine::Value::Polyline(p) => p.points.len(),
            cnets_engine::Value::Text(t) => t.len() / 2,
            _ => 1,
        }
    }
    graph
        .nodes()
        .flat_map(|(_, n)| (0..n.def.inputs.len()).filter_map(|k| n.value(k)))
        .map(|v| 2 * items(v))
        .sum()
}

/// The desktop's store: files in a folder, written atomically.
#[derive(Debug)]
pub struct FolderStore(pub PathBuf);

impl RecoveryStore for FolderStore {
    fn read(&self, name: &str) -> Option<String> {
        std::fs::read_to_string(self.0.join(name)).ok()
    }

    fn write(&mut self, name: &str, text: &str) -> std::io::Result<()> {
        std::fs::create_dir_all(&self.0)?;
        write_atomic(&self.0.join(name), text.as_bytes())
    }

    fn remove(&mut self, name: &str) {
        let _ = std::fs::remove_file(self.0.join(name));
    }
}

/// A store that refuses graph texts over a size (the page's local storage holds 5–10 MB per
/// site): the refusal says how large the design is, and nothing is half written.
pub struct LimitedStore {
    /// The store written to.
    pub inner: Box<dyn RecoveryStore>,
    /// The longest text written, in bytes.
    pub max_bytes: usize,
}

impl RecoveryStore for LimitedStore {
    fn read(&self, name: &str) -> Option<String> {
        self.inner.read(name)
    }

    fn write(&mut self, name: &str, text: &str) -> std::io::Result<()> {
        if text.len() > self.max_bytes {
            return Err(self.too_large("", text.len()));
        }
        self.inner.write(name, text)
    }

    fn remove(&mut self, name: &str) {
        self.inner.remove(name);
    }

    fn refuses(&self, len: usize) -> Option<std::io::Error> {
        (len > self.max_bytes).then(|| self.too_large("at least ", len))
    }

    fn place(&self) -> &str {
        self.inner.place()
    }
}

impl LimitedStore {
    fn too_large(&self, at_least: &str, len: usize) -> std::io::Error {
        std::io::Error::other(format!(
            "the design is {at_least}{:.1} MB, more than the {:.1} MB autosave keeps here",
            len as f64 / 1e6,
            self.max_bytes as f64 / 1e6
        ))
    }
}

/// Autosaves into one folder (or another [`RecoveryStore`]).
pub struct Recovery {
    dir: PathBuf,
    store: Box<dyn RecoveryStore>,
    saved_version: Option<u64>,
    last_write: Option<Instant>,
    /// Failed writes in a row, the last one's time and error.
    failures: u32,
    failed_at: Option<Instant>,
    last_error: Option<String>,
    /// Autosave's thread, when writes go there ([`Recovery::in_background`]).
    background: Option<Background>,
}

impl std::fmt::Debug for Recovery {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Recovery")
            .field("dir", &self.dir)
            .field("saved_version", &self.saved_version)
            .finish_non_exhaustive()
    }
}

const TEXT: &str = "recovery.ron";
const PATHS: &str = "recovery.path";
/// The kept pair: another document's recovery, moved aside when the page was asked for a
/// different document ([`Recovery::hold`]).
const HELD_TEXT: &str = "held.ron";
const HELD_PATHS: &str = "held.path";

/// Reads a pair (text, paths) from `store`.
fn read_pair(store: &dyn RecoveryStore, text: &str, paths: &str) -> Option<Recovered> {
    let text = store.read(text)?;
    let paths = store.read(paths).unwrap_or_default();
    let mut lines = paths.lines().map(str::trim);
    let mut next = || lines.next().filter(|p| !p.is_empty()).map(PathBuf::from);
    let path = next();
    let origin = next();
    Some(Recovered { text, path, origin })
}

/// Moves the pair `from` to `to` in `store` (the text first; the source is removed only once
/// both are written).
fn move_pair(
    store: &mut dyn RecoveryStore,
    from: (&str, &str),
    to: (&str, &str),
) -> std::io::Result<()> {
    let Some(r) = read_pair(store, from.0, from.1) else {
        return Ok(());
    };
    store.write(to.0, &r.text)?;
    store.write(to.1, &paths_text(r.path.as_deref(), r.origin.as_deref()))?;
    store.remove(from.0);
    store.remove(from.1);
    Ok(())
}

/// The paths line of the recovery pair: the document's own path, then the example it copies.
fn paths_text(path: Option<&Path>, origin: Option<&Path>) -> String {
    let line = |p: Option<&Path>| p.map(|p| p.display().to_string()).unwrap_or_default();
    format!("{}\n{}\n", line(path), line(origin))
}

/// Writes the recovery pair: the text first, so a store that refuses it (too large, full) keeps
/// the last pair whole.
fn write_pair(store: &mut dyn RecoveryStore, text: &str, paths: &str) -> std::io::Result<()> {
    store.write(TEXT, text)?;
    store.write(PATHS, paths)
}

impl Recovery {
    /// Recovery files in `dir`.
    pub fn new(dir: &Path) -> Self {
        Self::with_store(dir, Box::new(FolderStore(dir.to_path_buf())))
    }

    /// Recovery texts kept in `store` (`dir` only names them in [`Recovery::file`]).
    pub fn with_store(dir: &Path, store: Box<dyn RecoveryStore>) -> Self {
        Self {
            dir: dir.to_path_buf(),
            store,
            saved_version: None,
            last_write: None,
            failures: 0,
            failed_at: None,
            last_error: None,
            background: None,
        }
    }

    /// Writes recovery files in `dir` on a thread of their own (the desktop editor): a document
    /// whose text takes long to write out does not stop the window. [`Recovery::tick`] hands the
    /// write over and reports it in a later call; the thread calls `wake` when a write ends (ask
    /// for a frame).
    pub fn in_background(mut self, wake: Arc<dyn Fn() + Send + Sync>) -> Self {
        self.background = Background::start(Box::new(FolderStore(self.dir.clone())), wake);
        self
    }

    /// The document version written last (by this session).
    pub fn saved_version(&self) -> Option<u64> {
        self.saved_version
    }

    /// Why the last autosave failed, while the writes fail.
    pub fn last_error(&self) -> Option<&str> {
        self.last_error.as_deref()
    }

    /// The wait before the next try after `failures` failed writes in a row.
    fn retry_after(failures: u32) -> Duration {
        let doublings = failures.saturating_sub(1).min(16);
        AUTOSAVE_RETRY
            .saturating_mul(1 << doublings)
            .min(AUTOSAVE_RETRY_MAX)
    }

    /// The recovery graph file.
    pub fn file(&self) -> PathBuf {
        self.dir.join(TEXT)
    }

    /// The recovery file left by a previous session, if any.
    pub fn find(&self) -> Option<Recovered> {
        read_pair(self.store.as_ref(), TEXT, PATHS)
    }

    /// Keeps the recovery pair aside (the page was asked for another document): it is neither
    /// offered over that document nor overwritten by its autosave; [`Recovery::held`] reads it
    /// and File ▸ Restore kept work opens it. One pair is kept: the latest replaces an older one.
    pub fn hold(&mut self) -> std::io::Result<()> {
        move_pair(self.store.as_mut(), (TEXT, PATHS), (HELD_TEXT, HELD_PATHS))?;
        self.saved_version = None;
        Ok(())
    }

    /// The kept pair, if any.
    pub fn held(&self) -> Option<Recovered> {
        read_pair(self.store.as_ref(), HELD_TEXT, HELD_PATHS)
    }

    /// Moves the kept pair back as the recovery pair (its own document was asked for again).
    pub fn unhold(&mut self) -> std::io::Result<()> {
        move_pair(self.store.as_mut(), (HELD_TEXT, HELD_PATHS), (TEXT, PATHS))
    }

    /// Removes the kept pair (it was restored).
    pub fn clear_held(&mut self) {
        self.store.remove(HELD_TEXT);
        self.store.remove(HELD_PATHS);
    }

    /// Writes the recovery file now (atomically).
    pub fn write(
        &mut self,
        text: &str,
        path: Option<&Path>,
        origin: Option<&Path>,
        version: u64,
    ) -> std::io::Result<()> {
        write_pair(self.store.as_mut(), text, &paths_text(path, origin))?;
        self.saved_version = Some(version);
        self.last_write = Some(Instant::now());
        Ok(())
    }

    /// Autosaves a dirty document whose `version` was not written yet: at once when `committed`
    /// (no gesture in progress), else when the last write is [`AUTOSAVE_WITHIN`] old (otherwise
    /// it says when a write is due). `text` is only written out when writing, and not when the
    /// store refuses its lower bound.
    pub fn tick(
        &mut self,
        dirty: bool,
        version: u64,
        committed: bool,
        paths: (Option<&Path>, Option<&Path>),
        text: impl DesignText,
    ) -> Autosave {
        if let Some(finished) = self.background.as_mut().and_then(Background::poll) {
            return self.finished(finished);
        }
        if self.background.as_ref().is_some_and(Background::busy) {
            return Autosave::Writing;
        }
        if !dirty || self.saved_version == Some(version) {
            return Autosave::Idle;
        }
        let wait = if committed {
            AUTOSAVE_GAP
        } else {
            AUTOSAVE_WITHIN
        };
        if let Some(t) = self.last_write
            && t.elapsed() < wait
        {
            return Autosave::Due(wait.saturating_sub(t.elapsed()));
        }
        if let Some(t) = self.failed_at {
            let retry = Self::retry_after(self.failures);
            if t.elapsed() < retry {
                return Autosave::Due(retry.saturating_sub(t.elapsed()));
            }
        }
        if let Some(refusal) = self.store.refuses(text.len_at_least()) {
            return self.finished((version, Err(refusal.to_string())));
        }
        if let Some(background) = &mut self.background
            && let Some(job) = text.snapshot()
            && background.send(version, paths_text(paths.0, paths.1), job)
        {
            return Autosave::Writing;
        }
        let pair = (text.text(), paths_text(paths.0, paths.1));
        let written = write_pair(self.store.as_mut(), &pair.0, &pair.1);
        self.finished((version, written.map_err(|e| e.to_string())))
    }

    /// Records a write of `version` that finished (here or on autosave's thread).
    fn finished(&mut self, (version, written): Finished) -> Autosave {
        match written {
            Ok(()) => {
                self.saved_version = Some(version);
                self.last_write = Some(Instant::now());
                self.failures = 0;
                self.failed_at = None;
                self.last_error = None;
                Autosave::Wrote
            }
            Err(e) => {
                self.failures = self.failures.saturating_add(1);
                self.failed_at = Some(Instant::now());
                self.last_error = Some(e);
                Autosave::Failed(Self::retry_after(self.failures))
            }
        }
    }

    /// Where autosave writes, as the status bar names it.
    pub fn place(&self) -> &str {
        self.store.place()
    }

    /// Removes the recovery files (after a save, a clean exit, or a declined restore).
    pub fn clear(&mut self) {
        if let Some(background) = &mut self.background {
            background.wait();
        }
        self.store.remove(TEXT);
        self.store.remove(PATHS);
        self.saved_version = None;
        // A saved document starts afresh: the next edit is autosaved without a failure's wait.
        self.failures = 0;
        self.failed_at = None;
        self.last_error = None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn committed_edits_are_written_at_once_gestures_within_a_second() {
        let dir = std::env::temp_dir().join(format!("cnets-recovery-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let mut r = Recovery::new(&dir);
        assert!(r.find().is_none());
        let none = (None, None);
        assert_eq!(
            r.tick(false, 1, true, none, || "x".into()),
            Autosave::Idle,
            "clean documents are not saved"
        );
        let a = Path::new("/tmp/a.ron");
        assert_eq!(
            r.tick(true, 1, false, (Some(a), None), || "one".into()),
            Autosave::Wrote,
            "the first step of a gesture is written"
        );
        assert_eq!(
            r.tick(true, 1, true, none, || "one".into()),
            Autosave::Idle,
            "same version: nothing to do"
        );
        match r.tick(true, 2, false, none, || "two".into()) {
            Autosave::Due(d) => assert!(d <= AUTOSAVE_WITHIN, "{d:?}"),
            other => panic!("mid-gesture, right after a write: due later, got {other:?}"),
        }
        assert_eq!(r.find().unwrap().text, "one");
        std::thread::sleep(AUTOSAVE_GAP);
        assert_eq!(
            r.tick(true, 3, true, (Some(a), None), || "three".into()),
            Autosave::Wrote,
            "the gesture's end is written at once"
        );
        let found = r.find().unwrap();
        assert_eq!(found.text, "three");
        assert_eq!(found.path, Some(PathBuf::from("/tmp/a.ron")));
        assert_eq!(found.origin, None);
        let example = Path::new("/x/graphs/bridge.ron");
        std::thread::sleep(AUTOSAVE_GAP);
        r.tick(true, 4, true, (None, Some(example)), || "four".into());
        let found = r.find().unwrap();
        assert_eq!((found.path, found.origin), (None, Some(example.into())));
        r.clear();
        assert!(r.find().is_none());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// A store in memory that refuses writes while `refuse` is set.
    struct FlakyStore {
        refuse: std::sync::Arc<std::sync::atomic::AtomicBool>,
        texts: std::collections::HashMap<String, String>,
    }

    impl RecoveryStore for FlakyStore {
        fn read(&self, name: &str) -> Option<String> {
            self.texts.get(name).cloned()
        }
        fn write(&mut self, name: &str, text: &str) -> std::io::Result<()> {
            if self.refuse.load(std::sync::atomic::Ordering::Relaxed) {
                return Err(std::io::Error::other("quota exceeded"));
            }
            self.texts.insert(name.into(), text.into());
            Ok(())
        }
        fn remove(&mut self, name: &str) {
            self.texts.remove(name);
        }
    }

    #[test]
    fn another_documents_recovery_is_kept_aside_and_brought_back() {
        let refuse = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
        let store = FlakyStore {
            refuse: refuse.clone(),
            texts: Default::default(),
        };
        let mut r = Recovery::with_store(Path::new("mem"), Box::new(store));
        let torus = Path::new("graphs/torus-monge.ron");
        r.write("torus text", None, Some(torus), 4).unwrap();
        r.hold().unwrap();
        assert!(r.find().is_none(), "not offered any more");
        let kept = r.held().unwrap();
        assert_eq!(
            (kept.text.as_str(), kept.origin.as_deref()),
            ("torus text", Some(torus))
        );
        // The other document's autosave does not touch the kept pair.
        r.write("facade text", None, Some(Path::new("graphs/facade.ron")), 1)
            .unwrap();
        assert_eq!(r.held().unwrap().text, "torus text");
        // A refused move keeps the pair where it was.
        refuse.store(true, std::sync::atomic::Ordering::Relaxed);
        assert!(r.unhold().is_err());
        assert_eq!(r.held().unwrap().text, "torus text");
        refuse.store(false, std::sync::atomic::Ordering::Relaxed);
        r.unhold().unwrap();
        assert_eq!(r.find().unwrap().text, "torus text");
        assert!(r.held().is_none());
        r.hold().unwrap();
        r.clear_held();
        assert!(r.held().is_none() && r.find().is_none());
    }

    #[test]
    fn a_refusing_store_is_tried_again_after_a_growing_wait_not_every_frame() {
        let refuse = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(true));
        let store = FlakyStore {
            refuse: refuse.clone(),
            texts: Default::default(),
        };
        let mut r = Recovery::with_store(Path::new("mem"), Box::new(store));
        let none = (None, None);
        let written = std::cell::Cell::new(0);
        let text = || {
            written.set(written.get() + 1);
            "graph".to_string()
        };
        assert_eq!(
            r.tick(true, 1, true, none, text),
            Autosave::Failed(AUTOSAVE_RETRY)
        );
        assert_eq!(r.last_error(), Some("quota exceeded"));
        // The frames after it (a new edit too) neither write the document out nor ask the store.
        for version in [1, 2, 3] {
            match r.tick(true, version, true, none, text) {
                Autosave::Due(d) => assert!(d <= AUTOSAVE_RETRY && d > Duration::ZERO, "{d:?}"),
                other => panic!("waiting to retry, got {other:?}"),
            }
        }
        assert_eq!(written.get(), 1, "the document was written out once");
        // The wait passed: tried again, refused again, the next wait twice as long.
        r.failed_at = Instant::now().checked_sub(AUTOSAVE_RETRY);
        assert_eq!(
            r.tick(true, 3, true, none, text),
            Autosave::Failed(AUTOSAVE_RETRY * 2)
        );
        assert_eq!(written.get(), 2);
        assert_eq!(Recovery::retry_after(7), AUTOSAVE_RETRY_MAX, "capped");
        // The store takes writes again: written, and the failures forgotten.
        refuse.store(false, std::sync::atomic::Ordering::Relaxed);
        r.failed_at = Instant::now().checked_sub(AUTOSAVE_RETRY * 2);
        assert_eq!(r.tick(true, 3, true, none, text), Autosave::Wrote);
        assert_eq!(r.last_error(), None);
        assert_eq!(r.find().map(|f| f.text).as_deref(), Some("graph"));
        assert_eq!((r.failures, r.failed_at), (0, None));
    }

    #[test]
    fn a_limited_store_refuses_large_designs_and_keeps_the_last_one() {
        let store = FlakyStore {
            refuse: Default::default(),
            texts: Default::default(),
        };
        let limited = LimitedStore {
            inner: Box::new(store),
            max_bytes: 1_000_000,
        };
        let mut r = Recovery::with_store(Path::new("mem"), Box::new(limited));
        let none = (None, None);
        assert_eq!(
            r.tick(true, 1, true, none, || "small".into()),
            Autosave::Wrote
        );
        std::thread::sleep(AUTOSAVE_GAP);
        let failed = r.tick(true, 2, true, none, || "x".repeat(2_500_000));
        assert_eq!(failed, Autosave::Failed(AUTOSAVE_RETRY));
        assert_eq!(
            r.last_error(),
            Some("the design is 2.5 MB, more than the 1.0 MB autosave keeps here")
        );
        assert_eq!(
            r.find().map(|f| f.text).as_deref(),
            Some("small"),
            "the last design that fitted is kept whole"
        );
        // Saved (the recovery pair cleared): the next edit is written without the failure's wait.
        r.clear();
        assert_eq!(
            r.tick(true, 3, true, none, || "again".into()),
            Autosave::Wrote
        );
        assert_eq!(r.find().map(|f| f.text).as_deref(), Some("again"));
    }

    /// A gate a document's text waits on while it is written out (closed until opened; a test
    /// that never opens it goes on after 30 s).
    #[derive(Clone, Default)]
    struct Gate(Arc<(std::sync::Mutex<bool>, std::sync::Condvar)>);

    impl Gate {
        fn open(&self) {
            *self.0.0.lock().unwrap() = true;
            self.0.1.notify_all();
        }

        fn pass(&self) {
            let (open, changed) = &*self.0;
            let guard = open.lock().unwrap();
            let _ = changed
                .wait_timeout_while(guard, Duration::from_secs(30), |open| !*open)
                .unwrap();
        }
    }

    /// A document whose text is written out only once its gate opens.
    struct Gated(&'static str, Gate);

    impl DesignText for Gated {
        fn text(&self) -> String {
            self.1.pass();
            self.0.to_string()
        }

        fn snapshot(&self) -> Option<TextJob> {
            let (text, gate) = (self.0, self.1.clone());
            Some(Box::new(move || {
                gate.pass();
                text.to_string()
            }))
        }
    }

    #[test]
    fn autosave_in_the_background_does_not_wait_for_the_text() {
        let dir = std::env::temp_dir().join(format!("cnets-recovery-bg-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let woken = Arc::new(std::sync::atomic::AtomicUsize::new(0));
        let wake = woken.clone();
        let mut r = Recovery::new(&dir).in_background(Arc::new(move || {
            wake.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        }));
        // The texts are held back until the gate opens: a tick that waited for one would take
        // the gate's 30 s.
        let gate = Gate::default();
        let start = Instant::now();
        assert_eq!(
            r.tick(true, 1, true, (None, None), Gated("one", gate.clone())),
            Autosave::Writing
        );
        // While it writes, later versions wait (not queued behind it).
        assert_eq!(
            r.tick(true, 2, true, (None, None), Gated("two", gate.clone())),
            Autosave::Writing
        );
        assert!(
            start.elapsed() < Duration::from_secs(15),
            "the ticks returned at once"
        );
        assert_eq!(woken.load(std::sync::atomic::Ordering::Relaxed), 0);
        gate.open();
        let wrote = loop {
            match r.tick(true, 2, true, (None, None), Gated("two", gate.clone())) {
                Autosave::Writing => std::thread::sleep(Duration::from_millis(20)),
                other => break other,
            }
            assert!(
                start.elapsed() < Duration::from_secs(60),
                "the write finished"
            );
        };
        assert_eq!(wrote, Autosave::Wrote);
        // (It wakes the window right after handing the result over.)
        let woke = || woken.load(std::sync::atomic::Ordering::Relaxed);
        while woke() == 0 && start.elapsed() < Duration::from_secs(60) {
            std::thread::sleep(Duration::from_millis(5));
        }
        assert_eq!(woke(), 1, "the thread woke the window when the write ended");
        assert_eq!(r.find().unwrap().text, "one");
        // Version 2 is written next (after the gap), held back a while, then nothing is left to
        // do.
        std::thread::sleep(AUTOSAVE_GAP);
        let second = Gate::default();
        assert_eq!(
            r.tick(true, 2, true, (None, None), Gated("two", second.clone())),
            Autosave::Writing
        );
        let opener = second.clone();
        std::thread::spawn(move || {
            std::thread::sleep(Duration::from_millis(300));
            opener.open();
        });
        // A save clears the pair, waiting for the write in flight so it cannot come back.
        r.clear();
        assert!(r.find().is_none(), "cleared after the write in flight");
        assert_eq!(
            r.tick(false, 2, true, (None, None), Gated("two", gate.clone())),
            Autosave::Idle
        );
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_design_known_to_be_too_large_is_refused_without_being_written_out() {
        let limited = LimitedStore {
            inner: Box::new(FlakyStore {
                refuse: Default::default(),
                texts: Default::default(),
            }),
            max_bytes: 1_000_000,
        };
        let mut r = Recovery::with_store(Path::new("mem"), Box::new(limited));
        let mut graph = cnets_engine::Graph::new(std::sync::Arc::new(cnets_nodes::registry()));
        graph.add_node("numbers", "param.list").unwrap();
        let numbers = (0..600_000).map(|k| cnets_engine::Value::Number(k as f64));
        graph
            .set_value(
                "numbers",
                "values",
                cnets_engine::Value::list(numbers.collect()),
            )
            .unwrap();
        assert_eq!(text_len_at_least(&graph), 1_200_000);
        let doc = GraphDocument::from_parts(graph.clone(), Default::default(), None);
        assert_eq!(
            r.tick(true, 1, true, (None, None), &doc),
            Autosave::Failed(AUTOSAVE_RETRY)
        );
        assert_eq!(r.place(), "the recovery file", "the inner store's place");
        // Refused by the bound ("at least"), before the text was written out.
        assert_eq!(
            r.last_error(),
            Some("the design is at least 1.2 MB, more than the 1.0 MB autosave keeps here")
        );
        // Its real text is longer than the bound.
        let real = cnets_engine::file::to_ron(&graph, &Default::default());
        assert!(real.len() >= text_len_at_least(&graph), "{}", real.len());
    }
}
