//! What one evaluation may use, set up once by a door (the `cnets` command line, the Python
//! package and its Hops server, the editor): the memory budget, the folders nodes may read, the
//! library folders of cluster files, the folder exports write into and the cancel flag. A
//! [`Session`] makes every [`NodeContext`] of its evaluations ([`Session::context`],
//! [`Session::export_context`]), loads graph files and resolves node types with its library and
//! read permissions, and runs one node ([`Session::eval_node`]).
//!
//! The engine reads nothing from the environment: a door reads `CNETS_LIBRARY`
//! ([`library_from_env`]) and hands its folders to the session ([`Session::with_library`]).

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use cnets_engine::eval::evaluate_node;
use cnets_engine::file::Document;
use cnets_engine::{MemoryBudget, NodeContext, NodeDef, NodeError, NodeOutputs, Registry, Value};

use crate::{HostError, NodeType};

/// The environment variable that names library folders for cluster files (separated like `PATH`),
/// searched after a graph file's own folder and before the folders a door is given explicitly.
pub const LIBRARY_VAR: &str = "CNETS_LIBRARY";

/// The library folders named by `CNETS_LIBRARY` (separated like `PATH`; none when it is unset).
/// Doors call this and pass the folders to [`Session::with_library`]; the engine never reads the
/// environment.
pub fn library_from_env() -> Vec<PathBuf> {
    std::env::var_os(LIBRARY_VAR)
        .map(|v| std::env::split_paths(&v).collect())
        .unwrap_or_default()
}

/// Why a session could not set up or finish an evaluation.
#[derive(Debug, Clone, thiserror::Error)]
pub enum SessionError {
    /// Bad usage (an unknown node type or output) or a graph file that does not load.
    #[error(transparent)]
    Host(#[from] HostError),
    /// The folder exports write into could not be created.
    #[error("{}: cannot create the output directory: {}", .dir.display(), if *.in_the_way { "a file of that name is in the way" } else { .why.as_str() })]
    OutDir {
        /// The folder.
        dir: PathBuf,
        /// A file (not a folder) of that name is in the way.
        in_the_way: bool,
        /// What the file system said.
        why: String,
    },
    /// The evaluation was cancelled (the session's cancel flag was set).
    #[error("cancelled")]
    Cancelled,
    /// The node ran and failed: `<node type>: <its error>`.
    #[error("{node_type}: {error}")]
    Node {
        /// The node type's id.
        node_type: String,
        /// The node's error, typed (its kind, a file's line and column).
        error: NodeError,
    },
}

/// One node run by [`Session::eval_node`].
#[derive(Debug)]
pub struct NodeRun {
    /// The node's outputs (those not asked for may be empty placeholders), warnings and files, or
    /// its error.
    pub result: Result<NodeOutputs, NodeError>,
    /// How long the node took (the node alone: no conversion of inputs or outputs), also when it
    /// failed.
    pub elapsed: Duration,
    /// The node type's id.
    pub node_type: String,
}

impl NodeRun {
    /// The outputs, or the node's failure as [`SessionError::Node`].
    pub fn into_outputs(self) -> Result<NodeOutputs, SessionError> {
        self.result.map_err(|error| SessionError::Node {
            node_type: self.node_type,
            error,
        })
    }
}

/// What the evaluations of one door's request may use: one way to make a [`NodeContext`].
///
/// A new session has the default memory budget (half the memory the process has), no folders to
/// read besides an evaluation's own, no library, no output folder (writing is refused) and a
/// cancel flag of its own.
#[derive(Debug, Clone)]
pub struct Session {
    budget: MemoryBudget,
    budget_warning: Option<String>,
    allow_read: Vec<PathBuf>,
    library: Vec<PathBuf>,
    out_dir: Option<PathBuf>,
    cancel: Arc<AtomicBool>,
}

impl Default for Session {
    fn default() -> Self {
        Self::new()
    }
}

impl Session {
    /// A session with the defaults (see [`Session`]).
    pub fn new() -> Self {
        Self {
            budget: MemoryBudget::default(),
            budget_warning: None,
            allow_read: Vec::new(),
            library: Vec::new(),
            out_dir: None,
            cancel: Arc::new(AtomicBool::new(false)),
        }
    }

    /// The memory budget a user asked for (`--max-memory`, Python's `max_memory`; `None`: the
    /// default), clamped as [`MemoryBudget::requested`] clamps it; the warning of a clamp is kept
    /// for the door to show ([`Session::budget_warning`]).
    pub fn with_max_memory(mut self, limit: Option<u64>) -> Self {
        match limit {
            Some(limit) => {
                let granted = MemoryBudget::requested(limit);
                self.budget = granted.budget;
                self.budget_warning = granted.warning;
            }
            None => {
                self.budget = MemoryBudget::default();
                self.budget_warning = None;
            }
        }
        self
    }

    /// Sets the memory budget as it is (no clamping, no warning).
    pub fn with_budget(mut self, budget: MemoryBudget) -> Self {
        self.budget = budget;
        self.budget_warning = None;
        self
    }

    /// Adds folders nodes and cluster files may read from (`--allow-read DIR`), besides the
    /// folder of the graph evaluated.
    pub fn with_allow_read(mut self, dirs: impl IntoIterator<Item = PathBuf>) -> Self {
        self.allow_read.extend(dirs);
        self
    }

    /// Adds library folders searched for cluster files, after those added before: a door adds
    /// `CNETS_LIBRARY`'s ([`library_from_env`]) first, then its own (`--library DIR`).
    pub fn with_library(mut self, dirs: impl IntoIterator<Item = PathBuf>) -> Self {
        self.library.extend(dirs);
        self
    }

    /// Sets the folder export nodes write into (`None`: writing is refused).
    pub fn with_out_dir(mut self, dir: Option<PathBuf>) -> Self {
        self.out_dir = dir;
        self
    }

    /// Uses `flag` as the cancel flag (a door's Ctrl+C flag, an editor's stop button).
    pub fn with_cancel(mut self, flag: Arc<AtomicBool>) -> Self {
        self.cancel = flag;
        self
    }

    /// The memory budget of each evaluation.
    pub fn budget(&self) -> MemoryBudget {
        self.budget
    }

    /// Why the budget is less than asked for, when [`Session::with_max_memory`] clamped it.
    pub fn budget_warning(&self) -> Option<&str> {
        self.budget_warning.as_deref()
    }

    /// The folders nodes and cluster files may also read from.
    pub fn allow_read(&self) -> &[PathBuf] {
        &self.allow_read
    }

    /// The library folders, in the order they are searched.
    pub fn library(&self) -> &[PathBuf] {
        &self.library
    }

    /// The folder exports write into, if any.
    pub fn out_dir(&self) -> Option<&Path> {
        self.out_dir.as_deref()
    }

    /// The cancel flag every context of the session shares.
    pub fn cancel_flag(&self) -> &Arc<AtomicBool> {
        &self.cancel
    }

    /// Whether the session was cancelled.
    pub fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }

    /// A context for an evaluation that writes nothing: relative reads resolve against
    /// `base_dir` (the graph file's folder), with the session's budget, read permissions and
    /// cancel flag.
    pub fn context(&self, base_dir: Option<PathBuf>) -> NodeContext {
        let mut ctx = NodeContext::new(None, base_dir).with_budget(self.budget);
        ctx.allow_read = self.allow_read.clone();
        ctx.cancel = Arc::clone(&self.cancel);
        ctx
    }

    /// [`Session::context`] for an evaluation that writes files when `writes` (it has export
    /// nodes): the output folder is created (with its parents) and given to the context. A
    /// session without an output folder writes into `out` in the working folder.
    pub fn export_context(
        &self,
        base_dir: Option<PathBuf>,
        writes: bool,
    ) -> Result<NodeContext, SessionError> {
        let mut ctx = self.context(base_dir);
        if writes {
            let dir = self.out_dir.clone().unwrap_or_else(|| PathBuf::from("out"));
            create_out_dir(&dir)?;
            ctx.out_dir = Some(dir);
        }
        Ok(ctx)
    }

    /// Loads a graph file with the session's library folders and read permissions and applies the
    /// `node.input=value` overrides ([`crate::load_graph`]).
    pub fn load_graph(&self, path: &Path, sets: &[String]) -> Result<Document, HostError> {
        crate::load_graph(path, &self.library, sets, &self.allow_read)
    }

    /// A node type by registry id or `cluster:<path>`, the graph file found with the session's
    /// library folders and read permissions ([`crate::resolve`]).
    pub fn resolve(&self, id: &str, registry: &Arc<Registry>) -> Result<NodeType, HostError> {
        crate::resolve(id, registry, &self.library, &self.allow_read)
    }

    /// Runs one node on complete inputs (in port order) in a context of this session, relative
    /// reads resolving against `base_dir`; `outputs`: the outputs asked for by name (`None`: all),
    /// each checked ([`check_outputs`]). The output folder is created when the node writes files.
    /// A node that fails is an `Ok` run with its error ([`NodeRun::into_outputs`]); a cancelled
    /// one is [`SessionError::Cancelled`].
    pub fn eval_node(
        &self,
        def: &NodeDef,
        inputs: &[Value],
        outputs: Option<&[String]>,
        base_dir: Option<PathBuf>,
    ) -> Result<NodeRun, SessionError> {
        if let Some(names) = outputs {
            check_outputs(def, names)?;
        }
        let writes = def.has_flag(cnets_engine::NodeFlag::Export);
        let mut ctx = self.export_context(base_dir, writes)?;
        ctx.requested = outputs.map(<[String]>::to_vec);
        let start = Instant::now();
        let result = evaluate_node(def, &ctx, inputs);
        let elapsed = start.elapsed();
        if ctx.cancelled() {
            return Err(SessionError::Cancelled);
        }
        Ok(NodeRun {
            result,
            elapsed,
            node_type: def.id.to_string(),
        })
    }
}

/// Checks that every name of `names` is an output of `def`: the first that is not is a usage
/// error naming the valid outputs.
pub fn check_outputs(def: &NodeDef, names: &[String]) -> Result<(), HostError> {
    match names.iter().find(|n| def.output_index(n).is_none()) {
        Some(bad) => Err(HostError::usage(format!(
            "unknown output '{bad}' for {}; valid outputs: {}",
            def.id,
            def.output_names()
        ))),
        None => Ok(()),
    }
}

/// Creates the folder exports write into, with its parents; says when a file is in the way.
fn create_out_dir(dir: &Path) -> Result<(), SessionError> {
    // The browser has no folders: its export nodes' files are kept in memory (the page offers
    // them as downloads).
    if cfg!(target_arch = "wasm32") {
        return Ok(());
    }
    std::fs::create_dir_all(dir).map_err(|e| SessionError::OutDir {
        dir: dir.to_path_buf(),
        in_the_way: std::fs::symlink_metadata(dir).is_ok_and(|m| !m.is_dir()),
        why: e.to_string(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn registry() -> Arc<Registry> {
        Arc::new(cnets_nodes::registry())
    }

    #[test]
    fn a_context_carries_the_sessions_budget_reads_and_cancel_flag() {
        let session = Session::new()
            .with_budget(MemoryBudget::new(64_000_000))
            .with_allow_read([PathBuf::from("/data")]);
        let ctx = session.context(Some(PathBuf::from("/graphs")));
        assert_eq!(ctx.budget, MemoryBudget::new(64_000_000));
        assert_eq!(ctx.allow_read, vec![PathBuf::from("/data")]);
        assert_eq!(ctx.base_dir, Some(PathBuf::from("/graphs")));
        assert_eq!(ctx.out_dir, None, "a plain context writes nothing");
        assert!(!ctx.cancelled());
        session.cancel_flag().store(true, Ordering::Relaxed);
        assert!(ctx.cancelled(), "the context shares the session's flag");
        assert!(session.cancelled());
    }

    #[test]
    fn a_requested_budget_over_the_hard_limit_is_clamped_with_a_warning() {
        let small = Session::new().with_max_memory(Some(64_000_000));
        // Unless the process's hard limit is below 128 MB, 64 MB is granted as asked.
        if small.budget_warning().is_none() {
            assert_eq!(small.budget(), MemoryBudget::new(64_000_000));
        }
        let huge = Session::new().with_max_memory(Some(u64::MAX));
        let granted = MemoryBudget::requested(u64::MAX);
        assert_eq!(huge.budget(), granted.budget);
        assert_eq!(huge.budget_warning(), granted.warning.as_deref());
        let default = Session::new().with_max_memory(None);
        assert_eq!(default.budget(), MemoryBudget::default());
        assert_eq!(default.budget_warning(), None);
    }

    #[test]
    fn library_folders_keep_their_order_and_the_env_list_splits_like_path() {
        let session = Session::new()
            .with_library([PathBuf::from("/env/a"), PathBuf::from("/env/b")])
            .with_library([PathBuf::from("/flag")]);
        assert_eq!(
            session.library(),
            [
                PathBuf::from("/env/a"),
                PathBuf::from("/env/b"),
                PathBuf::from("/flag")
            ]
        );
        // `library_from_env` reads the variable as `PATH` is read.
        let joined = std::env::join_paths(["/x", "/y"]).unwrap();
        let split: Vec<PathBuf> = std::env::split_paths(&joined).collect();
        assert_eq!(split, [PathBuf::from("/x"), PathBuf::from("/y")]);
    }

    /// `math.add` resolved by `session`, and its inputs `a = 1` and the default `b`.
    fn add(session: &Session) -> (Arc<NodeDef>, Vec<Value>) {
        let def = session
            .resolve("math.add", &registry())
            .unwrap()
            .def()
            .clone();
        let inputs = crate::complete_inputs(&def, vec![Some(Value::Number(1.0)), None]).unwrap();
        (def, inputs)
    }

    #[test]
    fn unknown_outputs_are_refused_once_with_the_valid_ones() {
        let session = Session::new();
        let (def, inputs) = add(&session);
        let err = session
            .eval_node(&def, &inputs, Some(&["nope".to_string()]), None)
            .unwrap_err()
            .to_string();
        assert!(
            err.starts_with("unknown output 'nope' for math.add; valid outputs: "),
            "{err}"
        );
        let run = session.eval_node(&def, &inputs, None, None).unwrap();
        assert_eq!(run.node_type, "math.add");
        let outputs = run.into_outputs().unwrap();
        assert_eq!(outputs.values.len(), def.outputs.len());
        let err = session
            .resolve("math.ad", &registry())
            .unwrap_err()
            .to_string();
        assert!(err.contains("did you mean"), "{err}");
    }

    #[test]
    fn a_cancelled_session_reports_it() {
        let session = Session::new();
        let (def, inputs) = add(&session);
        session.cancel_flag().store(true, Ordering::Relaxed);
        assert!(matches!(
            session.eval_node(&def, &inputs, None, None),
            Err(SessionError::Cancelled)
        ));
    }

    #[test]
    fn an_export_context_creates_the_output_folder_and_says_what_is_in_the_way() {
        let d = std::env::temp_dir().join(format!("cnets-host-session-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        let out = d.join("nested").join("out");
        let session = Session::new().with_out_dir(Some(out.clone()));
        let ctx = session.export_context(None, false).unwrap();
        assert_eq!(ctx.out_dir, None);
        assert!(!out.exists(), "nothing is created when nothing writes");
        let ctx = session.export_context(None, true).unwrap();
        assert_eq!(ctx.out_dir.as_deref(), Some(out.as_path()));
        assert!(out.is_dir());
        let file = d.join("file");
        std::fs::write(&file, "x").unwrap();
        let Err(err) = Session::new()
            .with_out_dir(Some(file.clone()))
            .export_context(None, true)
        else {
            panic!("a file is in the way");
        };
        assert!(matches!(
            err,
            SessionError::OutDir {
                in_the_way: true,
                ..
            }
        ));
        assert!(
            err.to_string()
                .ends_with("cannot create the output directory: a file of that name is in the way"),
            "{err}"
        );
        std::fs::remove_dir_all(&d).unwrap();
    }
}
