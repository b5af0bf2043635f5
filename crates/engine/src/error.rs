//! The error a node reports ([`NodeError`]), in its own module so that the node definitions
//! (`node`) and the port kinds (`kinds`) both depend on it and not on each other.

use crate::budget::BudgetError;
use crate::convert::ConvertError;
use crate::value::json::JsonError;

/// A node failure with a message for the designer. Every variant displays as that message; node
/// code usually writes `NodeError::new(format!(..))`, `"…".into()` or `?` on a geometry, I/O,
/// conversion or JSON error.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum NodeError {
    /// What went wrong and where, in the node's words.
    #[error("{0}")]
    Message(String),
    /// The geometry kernel refused the inputs.
    #[error(transparent)]
    Geometry(#[from] cnets_geometry::GeometryError),
    /// A file could not be read or written (the I/O error's text).
    #[error("{0}")]
    Io(String),
    /// A value could not be converted to a port's type.
    #[error(transparent)]
    Convert(#[from] ConvertError),
    /// A JSON document did not decode into a value.
    #[error(transparent)]
    Json(#[from] JsonError),
    /// An allocation would not fit in the memory budget.
    #[error(transparent)]
    Budget(#[from] BudgetError),
    /// A problem at a place in a file a node read: the file, the line (1-based) and, when known,
    /// the column, as fields (a front end can show or jump to them), displayed as `file: line 3,
    /// column 7: message`.
    #[error("{file}: line {line}{}: {message}", column.map_or(String::new(), |c| format!(", column {c}")))]
    Located {
        /// The file, as the node named it.
        file: String,
        /// The line, from 1.
        line: usize,
        /// The column, from 1, when the reader knows it.
        column: Option<usize>,
        /// What is wrong there.
        message: String,
    },
    /// The node panicked (a bug: in the node or a library it calls); the panic's message.
    #[error("node panicked: {0}")]
    Panicked(String),
}

impl NodeError {
    /// An error with the given message.
    pub fn new(message: impl Into<String>) -> Self {
        Self::Message(message.into())
    }

    /// What kind of failure this is, as a word a front end can match instead of the message's
    /// text: `message`, `geometry`, `io`, `convert`, `json`, `memory`, `file` (a place in a
    /// file) or `panic`. The Python package's `CnetsError.kind`.
    pub fn kind(&self) -> &'static str {
        match self {
            NodeError::Message(_) => "message",
            NodeError::Geometry(_) => "geometry",
            NodeError::Io(_) => "io",
            NodeError::Convert(_) => "convert",
            NodeError::Json(_) => "json",
            NodeError::Budget(_) => "memory",
            NodeError::Located { .. } => "file",
            NodeError::Panicked(_) => "panic",
        }
    }
}

impl From<String> for NodeError {
    fn from(message: String) -> Self {
        Self::Message(message)
    }
}

impl From<&str> for NodeError {
    fn from(message: &str) -> Self {
        Self::new(message)
    }
}

impl From<std::io::Error> for NodeError {
    fn from(e: std::io::Error) -> Self {
        Self::Io(e.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_readers_place_displays_from_its_fields() {
        let e = NodeError::Located {
            file: "a.csv".into(),
            line: 3,
            column: None,
            message: "expected 2 or 3 numbers".into(),
        };
        assert_eq!(e.to_string(), "a.csv: line 3: expected 2 or 3 numbers");
        let e = NodeError::Located {
            file: "d.svg".into(),
            line: 1,
            column: Some(9),
            message: "undeclared namespace prefix 'x'".into(),
        };
        assert_eq!(
            e.to_string(),
            "d.svg: line 1, column 9: undeclared namespace prefix 'x'"
        );
    }

    #[test]
    fn every_kind_displays_as_its_message() {
        assert_eq!(NodeError::new("bad").to_string(), "bad");
        assert_eq!(NodeError::from("bad"), NodeError::Message("bad".into()));
        assert_eq!(NodeError::from(String::from("x")).to_string(), "x");
        let io = std::io::Error::new(std::io::ErrorKind::NotFound, "gone");
        assert_eq!(NodeError::from(io).to_string(), "gone");
        let g = cnets_geometry::GeometryError::ZeroNormal {
            row: None,
            column: 2,
        };
        assert_eq!(NodeError::from(g.clone()).to_string(), g.to_string());
    }
}
