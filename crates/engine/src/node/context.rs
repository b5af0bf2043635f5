//! What a running node may see and report besides its inputs: folders, files, the memory budget,
//! cancellation, warnings, the outputs asked of it.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

use std::borrow::Cow;

use super::mask::OutputMask;
use super::stamp::FileStamp;
use crate::budget::{MemoryBudget, bytes_of};
use crate::error::NodeError;
use crate::value::Value;

/// How many clusters deep a graph may nest (a chain of cluster files deeper than this is refused
/// when loading, and a deeper evaluation fails): deep enough for any design, shallow enough for the
/// stack of every thread that evaluates.
pub const MAX_CLUSTER_DEPTH: usize = 256;

/// What a running node may see and report besides its inputs.
pub struct NodeContext {
    /// Directory export nodes write into (`--out`); `None` forbids writing.
    pub out_dir: Option<PathBuf>,
    /// Directory relative paths of imports resolve against (the graph file's folder).
    pub base_dir: Option<PathBuf>,
    /// Set when the evaluation should stop as soon as possible.
    pub cancel: Arc<AtomicBool>,
    /// The memory the evaluation may use (default: half the machine's memory); nodes check what
    /// they are about to allocate with [`NodeContext::reserve`].
    pub budget: MemoryBudget,
    /// Folders besides `base_dir` whose files nodes may read (`--allow-read DIR`).
    pub allow_read: Vec<PathBuf>,
    /// The largest file a node may read, in bytes (default 1 GB).
    pub max_read_bytes: u64,
    /// The outputs the caller asked for (`cnets eval --outputs a,b`); `None`: all. A node may skip
    /// the work of outputs not asked for ([`NodeContext::wants`]) and leave them empty. In a graph
    /// the evaluator asks each node for the outputs that are wired, previewed or requested
    /// ([`NodeContext::ask_outputs`]); this field stays `None` there.
    pub requested: Option<Vec<String>>,
    /// How many clusters deep this context runs (0: the top graph); see [`MAX_CLUSTER_DEPTH`].
    pub depth: usize,
    in_use: AtomicU64,
    held: AtomicU64,
    warnings: Mutex<Vec<String>>,
    files: Mutex<Vec<PathBuf>>,
    reads: Mutex<Vec<FileStamp>>,
    asked: Mutex<Option<AskedOutputs>>,
    vouched: Mutex<Vec<String>>,
}

/// The outputs the running node was asked for, by name, and those it said it skipped.
struct AskedOutputs {
    names: Vec<Cow<'static, str>>,
    asked: OutputMask,
    skipped: OutputMask,
}

impl Default for NodeContext {
    fn default() -> Self {
        Self::new(None, None)
    }
}

impl NodeContext {
    /// A context with the given output and base directories.
    pub fn new(out_dir: Option<PathBuf>, base_dir: Option<PathBuf>) -> Self {
        Self {
            out_dir,
            base_dir,
            cancel: Arc::new(AtomicBool::new(false)),
            budget: MemoryBudget::default(),
            allow_read: Vec::new(),
            max_read_bytes: crate::files::DEFAULT_MAX_READ_BYTES,
            requested: None,
            depth: 0,
            in_use: AtomicU64::new(0),
            held: AtomicU64::new(0),
            warnings: Mutex::new(Vec::new()),
            files: Mutex::new(Vec::new()),
            reads: Mutex::new(Vec::new()),
            asked: Mutex::new(None),
            vouched: Mutex::new(Vec::new()),
        }
    }

    /// Sets the memory budget (builder style).
    pub fn with_budget(mut self, budget: MemoryBudget) -> Self {
        self.budget = budget;
        self
    }

    /// A context for the subgraph of a cluster run from this one: the same output directory,
    /// cancel flag, budget (with this evaluation's live values counted as in use) and read
    /// permissions, one level deeper; relative reads resolve against `base_dir`. Fails past
    /// [`MAX_CLUSTER_DEPTH`] levels.
    pub fn child(&self, base_dir: Option<PathBuf>) -> Result<NodeContext, NodeError> {
        if self.depth >= MAX_CLUSTER_DEPTH {
            return Err(NodeError::new(format!(
                "clusters nested more than {MAX_CLUSTER_DEPTH} deep"
            )));
        }
        let mut inner = NodeContext::new(self.out_dir.clone(), base_dir);
        inner.cancel = Arc::clone(&self.cancel);
        inner.budget = self.budget;
        inner.allow_read = self.allow_read.clone();
        inner.allow_read.extend(self.base_dir.clone());
        inner.max_read_bytes = self.max_read_bytes;
        inner.depth = self.depth + 1;
        inner.set_in_use(self.in_use());
        Ok(inner)
    }

    /// Bytes held by values of the evaluation outside the running node (the evaluator keeps this
    /// up to date before every node it runs).
    pub fn in_use(&self) -> u64 {
        self.in_use.load(Ordering::Relaxed)
    }

    /// Sets the bytes held by live values outside the running node (for evaluators and front ends
    /// that run nodes themselves).
    pub fn set_in_use(&self, bytes: u64) {
        self.in_use.store(bytes, Ordering::Relaxed);
    }

    /// Checks, before allocating, that `bytes` more fit in the memory budget beside the values
    /// already live; `what` names the allocation in the error ("a table of 10000000 × 10000000
    /// numbers needs 3200 TB, the limit is 12 GB").
    ///
    /// Where the process's allocations are counted ([`budget::allocated`](crate::budget::allocated))
    /// the check counts them when they are more than the values held (an input document, a
    /// reader's buffers).
    pub fn reserve(&self, bytes: u64, what: &str) -> Result<(), NodeError> {
        let live = self.in_use().max(crate::budget::allocated().unwrap_or(0));
        Ok(self.budget.check(bytes, live, what)?)
    }

    /// A [`Guard`](crate::budget::Guard) for work that grows step by step (a reader's records, a
    /// curve's segments): each step declares its bytes before allocating them.
    pub fn guard(&self, what: impl Into<String>) -> crate::budget::Guard {
        crate::budget::Guard::new(self.budget, self.in_use(), what)
    }

    /// Fails when the process has allocated more than the memory budget (where allocations are
    /// counted, [`budget::allocated`](crate::budget::allocated); else never). Readers, mapped
    /// nodes and writers call it where their work is split — every few thousand records, items or
    /// rows — so a file that expands far beyond its size stops at the budget with `what` named
    /// (`reading 'big.obj' took 1.1 GB, the limit is 1 GB`), not at the machine's end.
    pub fn check_memory(&self, what: &str) -> Result<(), NodeError> {
        match crate::budget::allocated() {
            Some(now) if now > self.budget.limit => Err(crate::budget::BudgetError::Exceeded {
                what: what.to_string(),
                allocated: now,
                limit: self.budget.limit,
            }
            .into()),
            _ => Ok(()),
        }
    }

    /// True when the output named `output` was asked for: by the evaluator (it is wired to a node
    /// that runs, previewed, exported or requested: [`NodeContext::ask_outputs`]) and by the
    /// caller (`requested`). A node that gets `false` may skip that output's work and return an
    /// empty placeholder; the evaluator records the output as not computed and runs the node again
    /// when it is asked for later. A node that never calls this computes every output.
    pub fn wants(&self, output: &str) -> bool {
        if !self
            .requested
            .as_ref()
            .is_none_or(|r| r.iter().any(|o| o == output))
        {
            return false;
        }
        let mut asked = lock(&self.asked);
        let Some(a) = asked.as_mut() else {
            return true;
        };
        match a.names.iter().position(|n| n == output) {
            Some(k) if !a.asked.contains(k) => {
                a.skipped.insert(k);
                false
            }
            _ => true,
        }
    }

    /// Asks the node about to run for the outputs in `mask` only (`outputs`: its output ports'
    /// names);
    /// evaluators call this before a node runs and [`NodeContext::skipped_outputs`] after. A mask
    /// covering every output asks for all (no bookkeeping).
    pub fn ask_outputs(
        &self,
        outputs: impl ExactSizeIterator<Item = Cow<'static, str>>,
        mask: OutputMask,
    ) {
        let all = OutputMask::first(outputs.len());
        *lock(&self.asked) = (!mask.covers(all)).then(|| AskedOutputs {
            names: outputs.collect(),
            asked: mask,
            skipped: OutputMask::NONE,
        });
    }

    /// Ends the request of [`NodeContext::ask_outputs`]: the outputs the node skipped (those it
    /// asked about with [`NodeContext::wants`] and was told no).
    pub fn skipped_outputs(&self) -> OutputMask {
        lock(&self.asked)
            .take()
            .map_or(OutputMask::NONE, |a| a.skipped)
    }

    /// Records that the running node keeps `bytes` alive besides its outputs (a cluster: its
    /// subgraph's results), so the evaluator counts them in the live memory.
    pub fn hold(&self, bytes: u64) {
        self.held.store(bytes, Ordering::Relaxed);
    }

    /// Takes the bytes recorded by [`NodeContext::hold`] (for evaluators).
    pub fn take_held(&self) -> u64 {
        self.held.swap(0, Ordering::Relaxed)
    }

    /// [`NodeContext::reserve`] for `count` values (list items: 32 bytes each).
    pub fn reserve_values(&self, count: u128, what: &str) -> Result<(), NodeError> {
        self.reserve(bytes_of(count, std::mem::size_of::<Value>()), what)
    }

    /// Records a warning shown on the node (it still produces outputs).
    pub fn warn(&self, message: impl Into<String>) {
        lock(&self.warnings).push(message.into());
    }

    /// Records a file the node wrote (listed in the run summary).
    pub fn record_file(&self, path: PathBuf) {
        lock(&self.files).push(path);
    }

    /// True when cancellation was requested.
    pub fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }

    /// Says that every number of `output` is finite because the kernel that made it checked each
    /// one as it was computed (a construction's step fails on a non-finite vertex): the evaluator
    /// then skips its own scan of that output, a pass over all of its memory. Debug builds scan
    /// it anyway and panic if the promise is broken, so every test checks it.
    pub fn vouch_finite(&self, output: &str) {
        lock(&self.vouched).push(output.to_owned());
    }

    /// Takes the outputs vouched for by [`NodeContext::vouch_finite`] (for evaluators).
    pub fn take_vouched(&self) -> Vec<String> {
        std::mem::take(&mut *lock(&self.vouched))
    }

    /// Takes the warnings recorded so far.
    pub fn take_warnings(&self) -> Vec<String> {
        std::mem::take(&mut *lock(&self.warnings))
    }

    /// Takes the files recorded so far.
    pub fn take_files(&self) -> Vec<PathBuf> {
        std::mem::take(&mut *lock(&self.files))
    }

    /// Resolves an export name inside the output directory (no folder is created, no file
    /// written; see [`NodeContext::write_output`]). Names are checked by name
    /// ([`files::check_export_name`](crate::files::check_export_name): no control characters, no
    /// root, no `.`, `..` or empty components); an unset output directory is an error.
    pub fn output_path(&self, name: &str) -> Result<PathBuf, NodeError> {
        let dir = self
            .out_dir
            .as_ref()
            .ok_or_else(|| NodeError::new("no output directory is set for exports"))?;
        let parts =
            crate::files::check_export_name(name).map_err(|e| NodeError::new(e.to_string()))?;
        Ok(parts.iter().fold(dir.clone(), |p, c| p.join(c)))
    }

    /// Records reads made elsewhere on the node's behalf (a cluster's inner nodes).
    pub fn record_reads(&self, stamps: impl IntoIterator<Item = FileStamp>) {
        lock(&self.reads).extend(stamps);
    }

    /// Takes the file reads recorded so far.
    pub fn take_reads(&self) -> Vec<FileStamp> {
        std::mem::take(&mut *lock(&self.reads))
    }

    /// Writes an export named `name` (relative, checked as by [`NodeContext::output_path`]) inside
    /// the output directory, atomically and without following symbolic links out of it
    /// ([`files::write_inside`](crate::files::write_inside)); records and returns the path.
    pub fn write_output(&self, name: &str, bytes: &[u8]) -> Result<PathBuf, NodeError> {
        let mut file = self.create_output(name)?;
        file.write_all(bytes)
            .map_err(|e| NodeError::new(format!("cannot write '{name}': {}", file.error(e))))?;
        self.commit_output(name, file)
    }

    /// Opens an export named `name` for streaming (see [`NodeContext::write_output`]): write to
    /// it (through a `BufWriter`), then [`NodeContext::commit_output`]. Writes stop with
    /// "cancelled" once the evaluation is cancelled, and a file dropped without its commit leaves
    /// nothing behind, so an export never holds the whole file in memory and a Ctrl+C stops it
    /// mid-file.
    pub fn create_output(&self, name: &str) -> Result<crate::files::AtomicFile, NodeError> {
        let dir = self
            .out_dir
            .as_ref()
            .ok_or_else(|| NodeError::new("no output directory is set for exports"))?;
        let parts =
            crate::files::check_export_name(name).map_err(|e| NodeError::new(e.to_string()))?;
        let file = crate::files::create_inside(dir, &parts)
            .map_err(|e| NodeError::new(format!("cannot write '{name}': {e}")))?;
        Ok(file.with_cancel(self.cancel.clone()))
    }

    /// Moves an export opened by [`NodeContext::create_output`] into place; records and returns
    /// the path.
    pub fn commit_output(
        &self,
        name: &str,
        file: crate::files::AtomicFile,
    ) -> Result<PathBuf, NodeError> {
        let path = file
            .commit()
            .map_err(|e| NodeError::new(format!("cannot write '{name}': {e}")))?;
        self.record_file(path.clone());
        Ok(path)
    }

    /// Resolves a path for reading: relative paths resolve against the graph's folder. Reading
    /// goes through [`NodeContext::read_file`], which checks the permission.
    pub fn input_path(&self, name: &str) -> PathBuf {
        let p = Path::new(name);
        match &self.base_dir {
            Some(base) if p.is_relative() => base.join(p),
            _ => p.to_path_buf(),
        }
    }

    /// Where this context's nodes may read: the graph's folder and the `allow_read` folders, up
    /// to `max_read_bytes` per file.
    pub fn read_access(&self) -> crate::files::ReadAccess {
        let mut access = crate::files::ReadAccess::new(
            self.base_dir
                .iter()
                .chain(&self.allow_read)
                .cloned()
                .collect(),
        );
        access.max_bytes = self.max_read_bytes;
        access
    }

    /// Reads the file `name` (relative to the graph's folder, or absolute) for a node: allowed
    /// only under the graph's folder and the `allow_read` folders, only a regular file (no device,
    /// FIFO or socket), at most `max_read_bytes` and within the memory budget. Every node that
    /// reads a file calls this (or [`NodeContext::read_text`]). Returns the resolved path and the
    /// bytes.
    ///
    /// Every read is recorded (length, modification time, content hash; also a read that failed),
    /// so the evaluator re-runs the node when the file changes (`eval::reads`).
    ///
    /// A name outside the allowed folders is refused before anything touches the file system, and
    /// is not recorded either (its stamp would look at the file, there and at every later
    /// evaluation): a graph cannot tell a missing file from a present one outside.
    pub fn read_file(&self, name: &str) -> Result<(PathBuf, Vec<u8>), NodeError> {
        let path = self.input_path(name);
        #[cfg(not(target_arch = "wasm32"))]
        if let Err(e) = self.read_access().check_name(&path) {
            return Err(NodeError::new(format!("cannot read '{name}': {e}")));
        }
        let result = self.read_checked(name, &path);
        lock(&self.reads).push(FileStamp::of(&path, result.as_deref().ok()));
        result.map(|bytes| (path, bytes))
    }

    fn read_checked(&self, name: &str, path: &Path) -> Result<Vec<u8>, NodeError> {
        // The web (wasm32): no file system; the files the designer opened or dropped on the page.
        #[cfg(target_arch = "wasm32")]
        {
            let bytes = crate::files::memory::read(path).ok_or_else(|| {
                NodeError::new(format!(
                    "cannot read '{name}': in the browser a node reads only files opened on the page \
                     (File ▸ Open…, or drop the file on the page)"
                ))
            })?;
            self.reserve(bytes.len() as u64, &format!("reading '{name}'"))?;
            Ok(bytes.to_vec())
        }
        #[cfg(not(target_arch = "wasm32"))]
        self.read_checked_on_disk(name, path)
    }

    #[cfg(not(target_arch = "wasm32"))]
    fn read_checked_on_disk(&self, name: &str, path: &Path) -> Result<Vec<u8>, NodeError> {
        let access = self.read_access();
        let failed =
            |e: crate::files::FileError| NodeError::new(format!("cannot read '{name}': {e}"));
        // Checked, opened and checked again (what was opened), then read from that descriptor.
        let opened = access.open(path).map_err(failed)?;
        self.reserve(opened.len, &format!("reading '{name}'"))?;
        access.read_opened(path, opened).map_err(failed)
    }

    /// [`NodeContext::read_file`] as UTF-8 text.
    pub fn read_text(&self, name: &str) -> Result<(PathBuf, String), NodeError> {
        let (path, bytes) = self.read_file(name)?;
        let text = String::from_utf8(bytes).map_err(|_| {
            NodeError::new(format!("cannot read '{name}': the file is not UTF-8 text"))
        })?;
        Ok((path, text))
    }
}

fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn output_paths_stay_inside_the_output_directory() {
        let ctx = NodeContext::new(Some(PathBuf::from("/tmp/out")), None);
        assert_eq!(
            ctx.output_path("a/b.obj").unwrap(),
            PathBuf::from("/tmp/out/a/b.obj")
        );
        assert!(ctx.output_path("../x.obj").is_err());
        assert!(ctx.output_path("/etc/passwd").is_err());
        assert!(ctx.output_path("").is_err());
        assert!(NodeContext::default().output_path("a.obj").is_err());
    }

    /// Issue 27 §4: a name outside the allowed folders is refused by name, in the same words
    /// whether the file exists or not, and leaves no stamp (a stamp looks the file up, now and
    /// at every later evaluation: a probe of what exists outside).
    #[cfg(not(target_arch = "wasm32"))]
    #[test]
    fn reads_outside_are_refused_by_name_and_not_recorded() {
        let dir = std::env::temp_dir().join(format!("cnets-ctx-read-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("graph")).unwrap();
        std::fs::write(dir.join("there.csv"), "0,0\n").unwrap();
        std::fs::write(dir.join("graph/in.csv"), "0,0\n").unwrap();
        let ctx = NodeContext::new(None, Some(dir.join("graph")));
        let mut said = Vec::new();
        for name in ["../there.csv", "../missing.csv"] {
            let e = ctx.read_file(name).unwrap_err().to_string();
            assert!(
                e.contains("outside the folders reads are allowed in"),
                "{e}"
            );
            said.push(e.replace(name, "NAME").replace(&name[3..], "NAME"));
            assert!(ctx.take_reads().is_empty(), "{name} was recorded");
        }
        assert_eq!(said[0], said[1]);
        // A read inside is recorded, and so is a missing file inside.
        assert_eq!(ctx.read_file("in.csv").unwrap().1, b"0,0\n");
        assert!(ctx.read_file("missing.csv").is_err());
        assert_eq!(ctx.take_reads().len(), 2);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
