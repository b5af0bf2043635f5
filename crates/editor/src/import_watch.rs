//! The watch on imported files: the files that importing nodes (`io.read_polylines`,
//! `io.read_mesh`, any node flagged `Import`) name in their `path` input, checked about once a
//! second like cluster files. When one changes (length or modification time), the editor submits
//! the graph again; the worker's evaluator then re-runs only the nodes whose read files changed
//! and what depends on them (the evaluator tracks every file a node read, docs/engine.md).

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::time::SystemTime;

use cnets_engine::{Graph, NodeFlag, Value, Widget};

/// The files the graph's importing nodes name (their literal file-path inputs, resolved against
/// `base`).
pub fn imported_files(graph: &Graph, base: Option<&Path>) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = graph
        .nodes()
        .filter(|(_, n)| n.def.flags.contains(&NodeFlag::Import))
        .filter_map(|(_, n)| {
            let k = n
                .def
                .inputs
                .iter()
                .position(|p| p.hint.widget == Widget::FilePath)?;
            match n.value(k) {
                Some(Value::Text(t)) if !t.trim().is_empty() => {
                    let p = Path::new(t.as_ref());
                    Some(match base {
                        Some(b) if p.is_relative() => b.join(p),
                        _ => p.to_path_buf(),
                    })
                }
                _ => None,
            }
        })
        .collect();
    files.sort();
    files.dedup();
    files
}

type Stamp = Option<(u64, Option<SystemTime>)>;

fn stamp(path: &Path) -> Stamp {
    std::fs::metadata(path)
        .ok()
        .map(|m| (m.len(), m.modified().ok()))
}

/// Remembers the length and modification time of imported files and tells when one changed.
#[derive(Debug, Default)]
pub struct ImportWatch {
    seen: HashMap<PathBuf, Stamp>,
}

impl ImportWatch {
    /// Forgets every file (a new document).
    pub fn clear(&mut self) {
        self.seen.clear();
    }

    /// Checks the imported files of `graph`; true when one changed since it was last seen (a file
    /// seen for the first time is only remembered).
    pub fn changed(&mut self, graph: &Graph, base: Option<&Path>) -> bool {
        let mut changed = false;
        for path in imported_files(graph, base) {
            let now = stamp(&path);
            if let Some(before) = self.seen.insert(path, now)
                && before != now
            {
                changed = true;
            }
        }
        changed
    }
}
