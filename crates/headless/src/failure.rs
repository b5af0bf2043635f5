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

/// Diagnostics printed for a graph that cannot load (a chain of 256 broken cluster files reports
/// one per file: the first ones say where, the rest is counted).
const MAX_DIAGNOSTICS: usize = 20;

impl From<LoadError> for Failure {
    fn from(e: LoadError) -> Self {
        let mut messages: Vec<String> = e
            .diagnostics
            .iter()
            .take(MAX_DIAGNOSTICS)
            .map(ToString::to_string)
            .collect();
        if e.diagnostics.len() > MAX_DIAGNOSTICS {
            messages.push(format!(
                "… and {} more problems",
                e.diagnostics.len() - MAX_DIAGNOSTICS
            ));
        }
        Self { code: 2, messages }
    }
}

impl From<cnets_host::HostError> for Failure {
    fn from(e: cnets_host::HostError) -> Self {
        match e {
            cnets_host::HostError::Usage(m) => Self::usage(m),
            e @ cnets_host::HostError::NoInterface { .. } => Self::usage(e.to_string()),
            cnets_host::HostError::Load(e) => e.into(),
        }
    }
}

impl From<std::io::Error> for Failure {
    /// Writing the output failed: a closed pipe (`| head`) ends quietly with success, anything
    /// else (a full disk) is one line and exit 2.
    fn from(e: std::io::Error) -> Self {
        if e.kind() == std::io::ErrorKind::BrokenPipe {
            return Self {
                code: 0,
                messages: Vec::new(),
            };
        }
        Self::usage(format!("cannot write the output: {e}"))
    }
}

/// The result of a command.
pub type CommandResult = Result<std::process::ExitCode, Failure>;
