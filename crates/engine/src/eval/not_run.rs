//! Why a node did not run, typed: blocked by what comes into it ([`Blocked`]), or unable to start
//! on its own inputs ([`InvalidInput`]). Each displays as the message the editor's badge and the
//! command line show; front ends match the variant, never the text.

/// A node did not run because of an upstream node: the input and the node it comes from.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum Blocked {
    /// The upstream node ran but was not asked for this output.
    #[error("input '{port}': '{upstream}' did not compute this output")]
    NotComputed {
        /// The blocked node's input.
        port: String,
        /// The node the wire comes from.
        upstream: String,
    },
    /// The wire names an output the upstream node does not have.
    #[error("input '{port}': '{upstream}' has no such output")]
    NoSuchOutput {
        /// The blocked node's input.
        port: String,
        /// The node the wire comes from.
        upstream: String,
    },
    /// The upstream node is disabled.
    #[error("input '{port}' comes from '{upstream}', which is disabled")]
    UpstreamDisabled {
        /// The blocked node's input.
        port: String,
        /// The node the wire comes from.
        upstream: String,
    },
    /// The upstream node failed, could not start, or is blocked itself.
    #[error("input '{port}' comes from '{upstream}', which failed")]
    UpstreamFailed {
        /// The blocked node's input.
        port: String,
        /// The node the wire comes from.
        upstream: String,
    },
    /// The upstream node has not been evaluated.
    #[error("input '{port}': '{upstream}' was not evaluated")]
    NotEvaluated {
        /// The blocked node's input.
        port: String,
        /// The node the wire comes from.
        upstream: String,
    },
}

impl Blocked {
    /// The node the blocking wire comes from.
    pub fn upstream(&self) -> &str {
        match self {
            Blocked::NotComputed { upstream, .. }
            | Blocked::NoSuchOutput { upstream, .. }
            | Blocked::UpstreamDisabled { upstream, .. }
            | Blocked::UpstreamFailed { upstream, .. }
            | Blocked::NotEvaluated { upstream, .. } => upstream,
        }
    }
}

/// A node could not start on its own inputs.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum InvalidInput {
    /// A required input is neither wired nor set.
    #[error("input '{port}' is required: connect it or set a value")]
    Required {
        /// The input.
        port: String,
    },
}
