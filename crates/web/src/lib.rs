//! The cnets editor as a web page (docs/web.md): the egui editor of `cnets-editor`, compiled to
//! `wasm32-unknown-unknown` and started by `index.html` (built by `scripts/web.sh`).
//!
//! - [`bundle`]: every file of `graphs/`, compiled in: the gallery graphs and the files they
//!   import, readable by nodes through the engine's in-memory files.
//! - [`link`]: share links, the graph in the URL fragment (`#graph=…`), and `?example=<name>`.
//! - [`opening`]: files read by the browser wait here; a large graph is read by the evaluation
//!   worker under a notice while the page keeps answering.
//! - [`wire`]: the messages between the page and its evaluation worker; [`service`]: the
//!   worker's side (the engine's evaluator answering the page's requests); [`literals`]: large
//!   literal values sent to the worker once and named by key afterwards; [`drag_service`]: the
//!   drag worker's side (the Drag net tool's solves).
//! - wasm32 only: `page` (the entry point, the WebGL2 set-up, and the browser's side of the
//!   editor: file picker, drag and drop, downloads, the clipboard, autosave in local storage),
//!   `remote` (the page's end of the evaluation worker), `drag_remote` (the page's end of the
//!   drag worker) and `worker_main` (the workers' entry point, in a Web Worker).
//!
//! The native build of this crate is its tests: the links of every gallery graph, the messages
//! and the worker's answers are checked here without a browser.

pub mod backing;
pub mod bundle;
pub mod drag_service;
pub mod link;
pub mod literals;
pub mod opening;
pub mod service;
pub mod wire;

#[cfg(target_arch = "wasm32")]
mod drag_remote;
#[cfg(target_arch = "wasm32")]
mod page;
#[cfg(target_arch = "wasm32")]
mod remote;
#[cfg(target_arch = "wasm32")]
mod worker_main;
