//! The session flags every subcommand that loads or evaluates a graph takes (`run`, `eval`,
//! `check`, `render`, `optimize`, `drag`): `--max-memory`, `--allow-read`, `--library`; they
//! become a [`cnets_host::Session`] with `CNETS_LIBRARY`'s folders before `--library`'s.

use std::path::PathBuf;

use cnets_host::{Session, SessionError};

use crate::failure::Failure;

/// The flags of an evaluation's session, shared by every subcommand (docs/cli.md, Session flags).
#[derive(Debug, Clone, clap::Args)]
#[command(next_help_heading = "Session")]
pub struct SessionArgs {
    /// The most memory the evaluation's values may take, e.g. `12G`, `512MB` (default: half the
    /// machine's memory); a node that would need more fails with what it needs.
    #[arg(long, value_name = "SIZE", value_parser = cnets_engine::budget::parse_size)]
    pub max_memory: Option<u64>,
    /// A folder nodes and cluster files may also read from (besides the graph file's folder);
    /// repeat for several.
    #[arg(long = "allow-read", value_name = "DIR")]
    pub allow_read: Vec<PathBuf>,
    /// Extra folders searched for cluster graph files (besides the graph's own folder and
    /// `CNETS_LIBRARY`).
    #[arg(long, value_name = "DIR")]
    pub library: Vec<PathBuf>,
}

impl SessionArgs {
    /// The session of these flags: `CNETS_LIBRARY`'s folders then `--library`'s, the folders of
    /// `--allow-read`, the budget of `--max-memory` (a clamped budget's warning printed), the
    /// process's Ctrl+C flag as its cancel flag.
    pub fn session(&self) -> Session {
        let session = Session::new()
            .with_max_memory(self.max_memory)
            .with_allow_read(self.allow_read.iter().cloned())
            .with_library(cnets_host::library_from_env())
            .with_library(self.library.iter().cloned())
            .with_cancel(crate::signals::cancel_flag());
        if let Some(w) = session.budget_warning() {
            crate::errln!("warning: {w}");
        }
        session
    }
}

impl From<SessionError> for Failure {
    fn from(e: SessionError) -> Self {
        match e {
            SessionError::Host(e) => e.into(),
            SessionError::OutDir {
                in_the_way: true, ..
            } => Failure::usage(format!("{e} (--out names a folder for the exports)")),
            SessionError::OutDir { .. } => Failure::usage(e.to_string()),
            SessionError::Cancelled => {
                cnets_engine::files::temp::remove_own();
                Failure {
                    code: crate::signals::CANCELLED,
                    messages: vec!["cancelled".to_string()],
                }
            }
            SessionError::Node { .. } => Failure::node(e.to_string()),
        }
    }
}
