//! Evaluation elsewhere: the web page's Web Worker (`crates/web`) evaluates the graph in another
//! instance of the wasm module, so the page answers input while a graph evaluates. The
//! [`Worker`](crate::worker::Worker) hands it its requests and polls it for responses; the
//! service keeps the worker's protocol (the newest request wins, the previewed nodes' response
//! first with `complete: false`, then the rest).

use crate::worker::{EvalRequest, EvalResponse};

/// An evaluation service outside this thread that is not a Rust thread (the page's Web Worker).
pub trait Remote {
    /// Hands over a request: the service answers the newest one it has and may drop older ones
    /// it has not finished (their cancel flags are set by the worker, as for a thread).
    fn send(&mut self, request: EvalRequest);

    /// The responses that arrived since the last call, oldest first.
    fn receive(&mut self) -> Vec<EvalResponse>;
}
