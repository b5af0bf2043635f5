//! How commands fail: messages for stderr and the exit code (1: a node failed; 2: bad usage or an
//! unreadable or invalid file).

use cnets_engine::file::LoadError;

/// A command failure.
#[derive(Debug)]
pub struct Failure {
    /// Process exit code.
    pub code: u8,
    /// Lines printed as `error: <line>`.
    pub messages: Vec<String>,
}

impl Failure {
    /// Bad usage or an invalid file (exit 2).
    pub fn usage(message: impl Into<String>) -> Self {
        Self {
            code: 2,
            messages: vec![message.into()],
        }
    }

    /// A node ran and failed (exit 1).
    pub fn node(message: impl Into<String>) -> Self {
        Self {
            code: 1,
            messages: vec![message.into()],
        }
    }
}

impl From<LoadError> for Failure {
    fn from(e: LoadError) -> Self {
        Self {
            code: 2,
            messages: e.diagnostics.iter().map(ToString::to_string).collect(),
        }
    }
}

/// The result of a command.
pub type CommandResult = Result<std::process::ExitCode, Failure>;
