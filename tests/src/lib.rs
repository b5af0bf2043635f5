//! Helpers for the workspace-level tests: load a bundled graph, evaluate it, read outputs.

use std::path::PathBuf;
use std::sync::Arc;

use cnets_engine::file::{Document, load_file};
use cnets_engine::{Evaluator, NodeContext, Registry, Value};

/// The workspace root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The node registry shared by the tests.
pub fn registry() -> Arc<Registry> {
    Arc::new(cnets_nodes::registry())
}

/// Loads `graphs/<name>.ron`.
pub fn load(name: &str) -> Document {
    let path = root().join("graphs").join(format!("{name}.ron"));
    load_file(&path, &registry()).unwrap_or_else(|e| panic!("{e}"))
}

/// A document evaluated in full, with its evaluator.
pub struct Evaluated {
    /// The document.
    pub doc: Document,
    /// Its evaluator after one full evaluation.
    pub evaluator: Evaluator,
}

impl Evaluated {
    /// Evaluates every node of the document (exports go to a fresh temporary folder); panics on a
    /// failed node, naming it.
    pub fn new(doc: Document) -> Self {
        static COUNTER: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
        let k = COUNTER.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let dir = std::env::temp_dir().join(format!("cnets-tests-{}-{k}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("a temporary output folder");
        Self::with_output(doc, &dir)
    }

    /// Evaluates every node with exports written into `out_dir`.
    pub fn with_output(doc: Document, out_dir: &std::path::Path) -> Self {
        // Imports resolve against the graphs' folder, as `cnets run graphs/….ron` resolves them.
        let base = root().join("graphs");
        Self::with_context(
            doc,
            &NodeContext::new(Some(out_dir.to_path_buf()), Some(base)),
        )
    }

    fn with_context(doc: Document, ctx: &NodeContext) -> Self {
        let mut evaluator = Evaluator::new();
        evaluator.evaluate_all(&doc.graph, ctx);
        for (_, node) in doc.graph.nodes() {
            let result = evaluator.result(&doc.graph, &node.id);
            if let Some(r) = result.filter(|r| r.is_failure()) {
                panic!(
                    "node '{}' ({}) failed: {}",
                    node.id,
                    node.def.id,
                    r.error().as_deref().unwrap_or("")
                );
            }
        }
        Self { doc, evaluator }
    }

    /// An output value.
    pub fn output(&self, node: &str, output: &str) -> &Value {
        self.evaluator
            .output(&self.doc.graph, node, output)
            .unwrap_or_else(|| panic!("{node}.{output} has no value"))
    }

    /// A number output.
    pub fn number(&self, node: &str, output: &str) -> f64 {
        self.output(node, output)
            .as_f64()
            .unwrap_or_else(|| panic!("{node}.{output} is not a number"))
    }
}
