//! The headless crate's integration tests, one test binary: each module is what was a
//! `tests/<name>.rs` binary. Run one module's tests with
//! `cargo test -p <this crate> --test it <module>::`.

mod cli;
mod clusters_cli;
#[path = "../common/mod.rs"]
mod common;
mod drag_cli;
mod files_cli;
mod json_input;
mod limits;
mod messages_cli;
mod optimize_cli;
mod render;
mod three_doors;
mod writes_cli;
