//! What loading a graph file reports: located problems and the error that gathers them.

use std::fmt;

use super::ron::Pos;

/// One problem found while loading, with its location when there is one.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Diagnostic {
    /// The file name as given (empty for a problem of no file, e.g. a cluster source not found
    /// by [`super::load_cluster_source`]; then it is shown as the message alone).
    pub file: String,
    /// Line and column.
    pub pos: Option<Pos>,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.pos {
            Some(p) => write!(f, "{}:{}:{}: {}", self.file, p.line, p.col, self.message),
            None if self.file.is_empty() => write!(f, "{}", self.message),
            None => write!(f, "{}: {}", self.file, self.message),
        }
    }
}

/// A graph file that could not be loaded: every problem found.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct LoadError {
    /// The problems, in file order.
    pub diagnostics: Vec<Diagnostic>,
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (k, d) in self.diagnostics.iter().enumerate() {
            if k > 0 {
                writeln!(f)?;
            }
            write!(f, "{d}")?;
        }
        Ok(())
    }
}

impl std::error::Error for LoadError {}

impl LoadError {
    /// A problem of no file and no place (a value that does not fit where a file put it, a link
    /// that does not decode): one diagnostic, the message alone.
    pub fn message(message: impl Into<String>) -> Self {
        Self {
            diagnostics: vec![Diagnostic {
                file: String::new(),
                pos: None,
                message: message.into(),
            }],
        }
    }

    /// The 1-based line of the first problem that has a place.
    pub fn first_line(&self) -> Option<usize> {
        self.diagnostics
            .iter()
            .find_map(|d| d.pos.map(|p| p.line as usize))
    }
}
