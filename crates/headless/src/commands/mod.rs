//! One module per `cnets` subcommand.

pub mod check;
pub mod drag;
pub mod eval;
pub mod nodes;
pub mod optimize;
pub mod render;
pub mod run;
