//! The engine crate's integration tests, one test binary: each module is what was a
//! `tests/<name>.rs` binary. Run one module's tests with
//! `cargo test -p <this crate> --test it <module>::`.
//! Kept as binaries of their own (process-wide state: an allocator, a budget): `memory_budget.rs`.

mod clusters;
#[path = "../common/mod.rs"]
mod common;
mod cycles;
mod disconnect;
mod early_cutoff;
mod errors;
mod file_cplanes;
mod file_diagnostics;
mod file_fuzz;
mod file_round_trip;
mod incremental;
mod json_documents;
mod lazy_outputs;
mod mapping;
mod node_names;
mod optimizer;
mod packed_lists;
mod replace_def;
mod vouched_outputs;
