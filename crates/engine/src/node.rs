//! Node type definitions: ports, documentation, the function that runs, and the context it runs in.

use std::borrow::Cow;
use std::fmt;
use std::path::{Component, Path, PathBuf};
use std::sync::Arc;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

use crate::budget::{MemoryBudget, bytes_of};
use crate::kinds::PortKind;
use crate::value::{Access, Value, ValueType};

/// The function that evaluates a node on fully prepared inputs (defaults filled in, converted to the
/// port types, one item per item port) and returns one value per output port.
pub type RunFn = Arc<dyn Fn(&NodeContext, &[Value]) -> Result<Vec<Value>, NodeError> + Send + Sync>;

/// A node failure with a message for the designer.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct NodeError {
    /// What went wrong and where.
    pub message: String,
}

impl NodeError {
    /// An error with the given message.
    pub fn new(message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
        }
    }
}

impl fmt::Display for NodeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for NodeError {}

impl From<String> for NodeError {
    fn from(message: String) -> Self {
        Self { message }
    }
}

impl From<&str> for NodeError {
    fn from(message: &str) -> Self {
        Self::new(message)
    }
}

impl From<cnets_geometry::GeometryError> for NodeError {
    fn from(e: cnets_geometry::GeometryError) -> Self {
        Self::new(e.to_string())
    }
}

impl From<std::io::Error> for NodeError {
    fn from(e: std::io::Error) -> Self {
        Self::new(e.to_string())
    }
}

/// One input or output port of a node type.
#[derive(Debug, Clone)]
pub struct PortDef {
    /// The port name (a contract: graph files and `cnets eval` use it).
    pub name: Cow<'static, str>,
    /// Item type.
    pub ty: ValueType,
    /// Item, list or tree access.
    pub access: Access,
    /// Value used when nothing is connected and no value is set.
    pub default: Option<Value>,
    /// An optional input may stay empty (the node sees `None`).
    pub optional: bool,
    /// One line for tooltips.
    pub doc: Cow<'static, str>,
}

impl PortDef {
    /// A port whose type, access and optionality come from the kind marker `K`.
    pub fn of<K: PortKind>(
        name: impl Into<Cow<'static, str>>,
        doc: impl Into<Cow<'static, str>>,
    ) -> Self {
        Self {
            name: name.into(),
            ty: K::item_type(),
            access: K::access(),
            default: None,
            optional: K::optional(),
            doc: doc.into(),
        }
    }

    /// A port with an explicit type and access.
    pub fn new(name: impl Into<Cow<'static, str>>, ty: ValueType, access: Access) -> Self {
        Self {
            name: name.into(),
            ty,
            access,
            default: None,
            optional: false,
            doc: Cow::Borrowed(""),
        }
    }

    /// Sets the default value (builder style).
    pub fn with_default(mut self, value: Value) -> Self {
        self.default = Some(value);
        self
    }

    /// Marks the port optional (builder style).
    pub fn optional(mut self) -> Self {
        self.optional = true;
        self
    }

    /// Sets the doc line (builder style).
    pub fn with_doc(mut self, doc: impl Into<Cow<'static, str>>) -> Self {
        self.doc = doc.into();
        self
    }

    /// True when the port must be connected or given a value.
    pub fn required(&self) -> bool {
        !self.optional && self.default.is_none()
    }

    /// The type as shown to users, e.g. `number` or `list<point>`.
    pub fn type_name(&self) -> String {
        self.ty.with_access(self.access)
    }
}

/// Special behaviour of a node type.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum NodeFlag {
    /// A designer-facing parameter (slider, toggle, …): the editor shows its inputs inline.
    Parameter,
    /// Writes files into the run's output directory; always demanded by `cnets run`.
    Export,
    /// Reads files from disk (relative to the graph file).
    Import,
}

/// A node type: id, documentation, ports and the function that runs it.
#[derive(Clone)]
pub struct NodeDef {
    /// Namespaced id, e.g. `curve.arc` (a contract).
    pub id: Cow<'static, str>,
    /// Palette category, e.g. `Curves`.
    pub category: Cow<'static, str>,
    /// One paragraph: the tooltip and the `cnets nodes` description.
    pub doc: Cow<'static, str>,
    /// Input ports in order.
    pub inputs: Vec<PortDef>,
    /// Output ports in order.
    pub outputs: Vec<PortDef>,
    /// Special behaviour.
    pub flags: Vec<NodeFlag>,
    /// The evaluation function.
    pub run: RunFn,
    /// Per-type data of dynamic node types (e.g. a cluster's subgraph), for introspection.
    pub extension: Option<Arc<dyn std::any::Any + Send + Sync>>,
}

impl fmt::Debug for NodeDef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("NodeDef")
            .field("id", &self.id)
            .field(
                "inputs",
                &self.inputs.iter().map(|p| &p.name).collect::<Vec<_>>(),
            )
            .field(
                "outputs",
                &self.outputs.iter().map(|p| &p.name).collect::<Vec<_>>(),
            )
            .finish()
    }
}

impl NodeDef {
    /// Starts a definition with no ports and a run function that fails; see the `node!` macro for
    /// the usual way to declare nodes.
    pub fn new(
        id: impl Into<Cow<'static, str>>,
        category: impl Into<Cow<'static, str>>,
        doc: impl Into<Cow<'static, str>>,
    ) -> Self {
        Self {
            id: id.into(),
            category: category.into(),
            doc: doc.into(),
            inputs: Vec::new(),
            outputs: Vec::new(),
            flags: Vec::new(),
            run: Arc::new(|_, _| Err(NodeError::new("node has no implementation"))),
            extension: None,
        }
    }

    /// Adds an input port.
    pub fn input(mut self, port: PortDef) -> Self {
        self.inputs.push(port);
        self
    }

    /// Adds an output port.
    pub fn output(mut self, port: PortDef) -> Self {
        self.outputs.push(port);
        self
    }

    /// Adds a flag.
    pub fn flag(mut self, flag: NodeFlag) -> Self {
        self.flags.push(flag);
        self
    }

    /// Sets the run function.
    pub fn run(
        mut self,
        f: impl Fn(&NodeContext, &[Value]) -> Result<Vec<Value>, NodeError> + Send + Sync + 'static,
    ) -> Self {
        self.run = Arc::new(f);
        self
    }

    /// True when the node has the flag.
    pub fn has_flag(&self, flag: NodeFlag) -> bool {
        self.flags.contains(&flag)
    }

    /// Index of the input port with this name.
    pub fn input_index(&self, name: &str) -> Option<usize> {
        self.inputs.iter().position(|p| p.name == name)
    }

    /// Index of the output port with this name.
    pub fn output_index(&self, name: &str) -> Option<usize> {
        self.outputs.iter().position(|p| p.name == name)
    }

    /// Comma-separated input names, for error messages.
    pub fn input_names(&self) -> String {
        self.inputs
            .iter()
            .map(|p| p.name.as_ref())
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// Comma-separated output names, for error messages.
    pub fn output_names(&self) -> String {
        self.outputs
            .iter()
            .map(|p| p.name.as_ref())
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The first line of the doc paragraph (a short summary).
    pub fn summary(&self) -> &str {
        self.doc.lines().next().unwrap_or("")
    }
}

/// A port name from a Rust identifier: raw identifiers (`r#type`) lose their `r#`.
pub fn port_name(ident: &'static str) -> &'static str {
    ident.strip_prefix("r#").unwrap_or(ident)
}

/// Joins doc-comment lines (as captured by the `node!` macro) into one trimmed text: lines are
/// trimmed, consecutive lines of a paragraph are joined by spaces, blank lines separate paragraphs.
pub fn doc_text(lines: &[&str]) -> String {
    let mut out = String::new();
    let mut blank = false;
    for line in lines.iter().map(|l| l.trim()) {
        if line.is_empty() {
            blank = !out.is_empty();
            continue;
        }
        if blank {
            out.push_str("\n\n");
            blank = false;
        } else if !out.is_empty() {
            out.push(' ');
        }
        out.push_str(line);
    }
    out
}

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
    /// How many clusters deep this context runs (0: the top graph); see [`MAX_CLUSTER_DEPTH`].
    pub depth: usize,
    in_use: AtomicU64,
    held: AtomicU64,
    warnings: Mutex<Vec<String>>,
    files: Mutex<Vec<PathBuf>>,
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
            depth: 0,
            in_use: AtomicU64::new(0),
            held: AtomicU64::new(0),
            warnings: Mutex::new(Vec::new()),
            files: Mutex::new(Vec::new()),
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
    pub fn reserve(&self, bytes: u64, what: &str) -> Result<(), NodeError> {
        self.budget
            .check(bytes, self.in_use(), what)
            .map_err(|e| NodeError::new(e.to_string()))
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

    /// Takes the warnings recorded so far.
    pub fn take_warnings(&self) -> Vec<String> {
        std::mem::take(&mut *lock(&self.warnings))
    }

    /// Takes the files recorded so far.
    pub fn take_files(&self) -> Vec<PathBuf> {
        std::mem::take(&mut *lock(&self.files))
    }

    /// Resolves a file name for writing inside the output directory. Absolute paths, `..` and an
    /// unset output directory are errors: exports never write outside `--out`.
    pub fn output_path(&self, name: &str) -> Result<PathBuf, NodeError> {
        let dir = self
            .out_dir
            .as_ref()
            .ok_or_else(|| NodeError::new("no output directory is set for exports"))?;
        let rel = Path::new(name);
        if name.trim().is_empty() {
            return Err(NodeError::new("the output file name is empty"));
        }
        let safe = rel
            .components()
            .all(|c| matches!(c, Component::Normal(_) | Component::CurDir));
        if !safe {
            return Err(NodeError::new(format!(
                "output name '{name}' must be a relative path inside the output directory (no '..', no root)"
            )));
        }
        Ok(dir.join(rel))
    }

    /// Resolves a path for reading: relative paths resolve against the graph's folder.
    pub fn input_path(&self, name: &str) -> PathBuf {
        let p = Path::new(name);
        match &self.base_dir {
            Some(base) if p.is_relative() => base.join(p),
            _ => p.to_path_buf(),
        }
    }
}

fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn doc_text_joins_lines_and_keeps_paragraphs() {
        assert_eq!(
            doc_text(&[" A circular", " arc.", "", " More."]),
            "A circular arc.\n\nMore."
        );
    }

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
}
