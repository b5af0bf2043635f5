//! The messages between the page and its evaluation worker (docs/web.md, "The evaluation
//! worker"): the page sends graphs to evaluate (their RON text) and the files opened on the page;
//! the worker answers with what the desktop worker thread answers — node statuses, the preview
//! scene, its figures and picks.
//!
//! One message is one `ArrayBuffer` (transferred, not copied): the message types derive serde and
//! cross in postcard's compact format (varint lengths, little-endian numbers), so a field added to
//! any of them — a figure, a status, a preview option — crosses without a line written here. The
//! scene's GPU buffers cross as their bytes (`cnets_render`'s `scene_bytes`: measured in
//! docs/web.md, a byte copy against element by element). Reading checks every length against what
//! is left, the meshes' invariants, the preview options' ranges, how deep values nest, and that
//! nothing is left over, so a malformed message is an error, not a panic or a huge allocation.

mod drag;

pub use drag::DragJob;

use std::collections::HashMap;
use std::sync::Arc;

use cnets_editor::net_drag::Solved;
use cnets_editor::preview::{Picks, PreviewOptions, PreviewStats};
use cnets_editor::worker::{EvalResponse, NodeStatus};
use cnets_engine::Value;
use cnets_engine::file::LoadError;
use cnets_render::Scene;
use serde::{Deserialize, Serialize};

use crate::literals::LiteralRef;

/// A graph to evaluate: what an `EvalRequest` carries across, the graph as its RON text.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Job {
    /// The request's sequence number.
    pub seq: u64,
    /// The graph (`cnets_engine::file::to_ron`).
    pub ron: String,
    /// The folder relative paths resolve in.
    pub base_dir: Option<String>,
    /// Opened clusters, outermost first.
    pub view: Vec<String>,
    /// Preview options.
    pub options: PreviewOptions,
    /// Inputs whose large literal values the worker holds: left unset in `ron`, put back there.
    pub literals: Vec<LiteralRef>,
    /// Large literals no request refers to any more (the worker drops them on receipt).
    pub forget: Vec<u64>,
    /// The pointer was held (a drag) when the request was made: the worker keeps the request's
    /// rest (the nodes not previewed) until a newer request comes or the page says the pointer
    /// was released ([`ToWorker::Released`]).
    pub held: bool,
}

/// A message from the page to the worker.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum ToWorker {
    /// Evaluate a graph (the newest one wins).
    Evaluate(Job),
    /// The pointer held during the last request was released: its rest may run.
    Released,
    /// A file opened on the page, readable by nodes under its name.
    Provide {
        /// The file's name.
        name: String,
        /// Its content.
        bytes: Vec<u8>,
    },
    /// A large literal value, kept by the worker under `key` for the requests that name it
    /// (`crate::literals`).
    Literal {
        /// The key requests name it by.
        key: u64,
        /// The value.
        value: Value,
    },
    /// A large graph file to read (parse) for the page, which keeps answering meanwhile.
    Parse(ParseJob),
    /// A drag of the net starts (the drag worker): its problem.
    DragStart(Box<DragJob>),
    /// The drag's vertex should be at `target`: solve in at most `steps` steps, from the last
    /// answer.
    DragAim {
        /// The target point.
        target: [f64; 3],
        /// Steps at most.
        steps: u64,
    },
}

/// A graph file the worker reads for the page (`crate::literals`, docs/web.md "Large files").
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ParseJob {
    /// Names the answer.
    pub token: u64,
    /// Where the file came from (its name: relative imports resolve against its folder).
    pub origin: String,
    /// The library folders cluster files are looked up in.
    pub library: Vec<String>,
    /// The file's content.
    pub text: Vec<u8>,
}

/// A graph file read by the worker: its RON text without its large literals, and those.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Parsed {
    /// The graph and its settings as RON, the large literals' inputs left unset.
    pub skeleton: String,
    /// Each large literal: where it goes and its value (the worker keeps it under the key).
    pub literals: Vec<(LiteralRef, Value)>,
}

/// An evaluation's answer as it arrives on the page.
#[derive(Serialize, Deserialize)]
pub struct Answer {
    /// The request's sequence number.
    pub seq: u64,
    /// The opened clusters the statuses belong to.
    pub view: Vec<String>,
    /// Status per node id.
    pub statuses: HashMap<String, NodeStatus>,
    /// The preview: `None` when it is the one the previous answer carried.
    pub preview: Option<(Arc<Scene>, PreviewStats, Arc<Picks>)>,
    /// Evaluation time in milliseconds.
    pub eval_ms: f64,
    /// Nodes that ran.
    pub ran: usize,
    /// Every node has its final status.
    pub complete: bool,
}

/// A message from the worker to the page.
#[derive(Serialize, Deserialize)]
pub enum FromWorker {
    /// The worker has started and takes requests.
    Ready,
    /// An evaluation's answer.
    Answer(Box<Answer>),
    /// The graph of request `seq` did not load in the worker.
    Failed {
        /// The request.
        seq: u64,
        /// Why.
        message: String,
    },
    /// A graph file read for the page: its content, or why it does not load.
    Parsed {
        /// The request's token.
        token: u64,
        /// The graph, or the load error (as the page's own reading would have said it).
        result: Result<Parsed, LoadError>,
    },
    /// What a drag's solve reached, or why it failed.
    Dragged(Result<Solved, String>),
    /// The worker stopped (a panic: wasm cannot unwind); the page starts another.
    Stopped {
        /// The panic's message.
        message: String,
    },
}

/// A message that does not decode.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
#[error("a message between the page and its evaluation worker is malformed: {0}")]
pub struct WireError(String);

/// The bytes of a message. Writing to a growing buffer fails only for a sequence of unknown
/// length, which no message holds; should it ever, the bytes are empty, which the other side
/// reads as a malformed message and reports.
fn encode(message: &impl Serialize) -> Vec<u8> {
    postcard::to_allocvec(message).unwrap_or_default()
}

/// A message from its bytes: all of them, nothing left over.
fn decode<'a, T: Deserialize<'a>>(bytes: &'a [u8]) -> Result<T, WireError> {
    match postcard::take_from_bytes(bytes) {
        Ok((message, [])) => Ok(message),
        Ok((_, rest)) => Err(WireError(format!("{} bytes past its end", rest.len()))),
        Err(e) => Err(WireError(e.to_string())),
    }
}

/// The bytes of a message to the worker.
pub fn encode_to_worker(message: &ToWorker) -> Vec<u8> {
    encode(message)
}

/// A message to the worker from its bytes.
pub fn decode_to_worker(bytes: &[u8]) -> Result<ToWorker, WireError> {
    decode(bytes)
}

/// The worker's "ready" message.
pub fn encode_ready() -> Vec<u8> {
    encode(&FromWorker::Ready)
}

/// The message saying that the graph of request `seq` did not load.
pub fn encode_failed(seq: u64, message: &str) -> Vec<u8> {
    encode(&FromWorker::Failed {
        seq,
        message: message.to_string(),
    })
}

/// The message answering the file read for `token` (taken, not copied: a large file's text).
pub fn encode_parsed(token: u64, result: Result<Parsed, LoadError>) -> Vec<u8> {
    encode(&FromWorker::Parsed { token, result })
}

/// The message carrying a drag's answer (taken, not copied: it is sent once per solve).
pub fn encode_dragged(answer: Result<Solved, String>) -> Vec<u8> {
    encode(&FromWorker::Dragged(answer))
}

/// The message saying that the worker stopped (its last words).
pub fn encode_stopped(message: &str) -> Vec<u8> {
    encode(&FromWorker::Stopped {
        message: message.to_string(),
    })
}

/// The message carrying `response`; with `same_preview` its scene, figures and picks are left
/// out (they are those of the previous answer). The scene and picks are shared, not copied.
pub fn encode_answer(response: &EvalResponse, same_preview: bool) -> Vec<u8> {
    encode(&FromWorker::Answer(Box::new(Answer {
        seq: response.seq,
        view: response.view.clone(),
        statuses: response.statuses.clone(),
        preview: (!same_preview).then(|| {
            (
                response.scene.clone(),
                response.stats.clone(),
                response.picks.clone(),
            )
        }),
        eval_ms: response.eval_ms,
        ran: response.ran,
        complete: response.complete,
    })))
}

/// A message from the worker from its bytes.
pub fn decode_from_worker(bytes: &[u8]) -> Result<FromWorker, WireError> {
    decode(bytes)
}

/// Whether two scenes draw the same (their background and buffers are equal).
pub fn same_scene(a: &Scene, b: &Scene) -> bool {
    a.parts() == b.parts()
}

#[cfg(test)]
mod tests;
