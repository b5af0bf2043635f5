//! The messages between the page and its evaluation worker (docs/web.md, "The evaluation
//! worker"): the page sends graphs to evaluate (their RON text) and the files opened on the page;
//! the worker answers with what the desktop worker thread answers — node statuses, the preview
//! scene, its figures and picks.
//!
//! One message is one `ArrayBuffer` (transferred, not copied): a tag byte, then little-endian
//! numbers, length-prefixed texts and lists, and the scene's GPU buffers as they are uploaded.
//! Decoding checks every length against what is left, so a malformed message is an error, not a
//! panic or a huge allocation.

mod codec;
mod drag;
mod scene;
mod values;

pub use drag::DragJob;

use std::collections::HashMap;

use cnets_editor::net_drag::Solved;
use cnets_editor::preview::{Picks, PreviewOptions, PreviewStats};
use cnets_editor::worker::{EvalResponse, NodeStatus};
use cnets_engine::Value;
use cnets_render::Scene;

use crate::literals::LiteralRef;
use codec::{Reader, Res, Writer};
use scene::{options, picks, read_options, read_picks, read_scene, read_stats, scene, stats};
use values::{read_status, read_value, status, value};

/// A graph to evaluate: what an `EvalRequest` carries across, the graph as its RON text.
#[derive(Clone, Debug, PartialEq)]
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
#[derive(Clone, Debug, PartialEq)]
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
#[derive(Clone, Debug, PartialEq)]
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
#[derive(Clone, Debug, PartialEq)]
pub struct Parsed {
    /// The graph and its settings as RON, the large literals' inputs left unset.
    pub skeleton: String,
    /// Each large literal: where it goes and its value (the worker keeps it under the key).
    pub literals: Vec<(LiteralRef, Value)>,
}

/// An evaluation's answer as it arrives on the page.
pub struct Answer {
    /// The request's sequence number.
    pub seq: u64,
    /// The opened clusters the statuses belong to.
    pub view: Vec<String>,
    /// Status per node id.
    pub statuses: HashMap<String, NodeStatus>,
    /// The preview: `None` when it is the one the previous answer carried.
    pub preview: Option<(Scene, PreviewStats, Picks)>,
    /// Evaluation time in milliseconds.
    pub eval_ms: f64,
    /// Nodes that ran.
    pub ran: usize,
    /// Every node has its final status.
    pub complete: bool,
}

/// A message from the worker to the page.
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
        result: Result<Parsed, String>,
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
pub struct WireError(&'static str);

const TO_EVALUATE: u8 = 1;
const TO_PROVIDE: u8 = 2;
const TO_LITERAL: u8 = 3;
const TO_PARSE: u8 = 4;
const TO_DRAG_START: u8 = 5;
const TO_DRAG_AIM: u8 = 6;
const TO_RELEASED: u8 = 7;
const FROM_READY: u8 = 10;
const FROM_ANSWER: u8 = 11;
const FROM_FAILED: u8 = 12;
const FROM_STOPPED: u8 = 13;
const FROM_PARSED: u8 = 14;
const FROM_DRAGGED: u8 = 15;

/// The bytes of a message to the worker.
pub fn encode_to_worker(message: &ToWorker) -> Vec<u8> {
    let mut w = Writer::default();
    match message {
        ToWorker::Evaluate(job) => {
            w.u8(TO_EVALUATE);
            w.u64(job.seq);
            w.str(&job.ron);
            w.opt(job.base_dir.as_ref(), |w, d| w.str(d));
            w.strs(&job.view);
            options(&mut w, &job.options);
            w.len(job.literals.len());
            for r in &job.literals {
                w.str(&r.node);
                w.str(&r.input);
                w.u64(r.key);
            }
            w.len(job.forget.len());
            job.forget.iter().for_each(|&k| w.u64(k));
            w.bool(job.held);
        }
        ToWorker::Released => w.u8(TO_RELEASED),
        ToWorker::Provide { name, bytes } => {
            w.u8(TO_PROVIDE);
            w.str(name);
            w.bytes(bytes);
        }
        ToWorker::Literal { key, value: v } => {
            w.u8(TO_LITERAL);
            w.u64(*key);
            value(&mut w, v);
        }
        ToWorker::Parse(job) => {
            w.u8(TO_PARSE);
            w.u64(job.token);
            w.str(&job.origin);
            w.strs(&job.library);
            w.bytes(&job.text);
        }
        ToWorker::DragStart(job) => {
            w.u8(TO_DRAG_START);
            drag::job(&mut w, job);
        }
        ToWorker::DragAim { target, steps } => {
            w.u8(TO_DRAG_AIM);
            target.iter().for_each(|x| w.f64(*x));
            w.u64(*steps);
        }
    }
    w.0
}

/// A message to the worker from its bytes.
pub fn decode_to_worker(bytes: &[u8]) -> Res<ToWorker> {
    let mut r = Reader::new(bytes);
    let message = match r.u8()? {
        TO_EVALUATE => ToWorker::Evaluate(Job {
            seq: r.u64()?,
            ron: r.string()?,
            base_dir: r.opt(Reader::string)?,
            view: r.strings()?,
            options: read_options(&mut r)?,
            literals: {
                let n = r.len(8 + 8 + 8)?;
                (0..n)
                    .map(|_| {
                        Ok(LiteralRef {
                            node: r.string()?,
                            input: r.string()?,
                            key: r.u64()?,
                        })
                    })
                    .collect::<Res<_>>()?
            },
            forget: {
                let n = r.len(8)?;
                (0..n).map(|_| r.u64()).collect::<Res<_>>()?
            },
            held: r.bool()?,
        }),
        TO_RELEASED => ToWorker::Released,
        TO_PROVIDE => ToWorker::Provide {
            name: r.string()?,
            bytes: r.bytes()?.to_vec(),
        },
        TO_LITERAL => ToWorker::Literal {
            key: r.u64()?,
            value: read_value(&mut r, 0)?,
        },
        TO_PARSE => ToWorker::Parse(ParseJob {
            token: r.u64()?,
            origin: r.string()?,
            library: r.strings()?,
            text: r.bytes()?.to_vec(),
        }),
        TO_DRAG_START => ToWorker::DragStart(Box::new(drag::read_job(&mut r)?)),
        TO_DRAG_AIM => ToWorker::DragAim {
            target: [r.f64()?, r.f64()?, r.f64()?],
            steps: r.u64()?,
        },
        _ => return Err(WireError("unknown message to the worker")),
    };
    r.end()?;
    Ok(message)
}

/// The worker's "ready" message.
pub fn encode_ready() -> Vec<u8> {
    vec![FROM_READY]
}

/// The message saying that the graph of request `seq` did not load.
pub fn encode_failed(seq: u64, message: &str) -> Vec<u8> {
    let mut w = Writer::default();
    w.u8(FROM_FAILED);
    w.u64(seq);
    w.str(message);
    w.0
}

/// The message answering the file read for `token`.
pub fn encode_parsed(token: u64, result: &Result<Parsed, String>) -> Vec<u8> {
    let mut w = Writer::default();
    w.u8(FROM_PARSED);
    w.u64(token);
    match result {
        Ok(parsed) => {
            w.bool(true);
            w.str(&parsed.skeleton);
            w.len(parsed.literals.len());
            for (r, v) in &parsed.literals {
                w.str(&r.node);
                w.str(&r.input);
                w.u64(r.key);
                value(&mut w, v);
            }
        }
        Err(e) => {
            w.bool(false);
            w.str(e);
        }
    }
    w.0
}

/// The message carrying a drag's answer.
pub fn encode_dragged(answer: &Result<Solved, String>) -> Vec<u8> {
    let mut w = Writer::default();
    w.u8(FROM_DRAGGED);
    drag::answer(&mut w, answer);
    w.0
}

/// The message saying that the worker stopped (its last words).
pub fn encode_stopped(message: &str) -> Vec<u8> {
    let mut w = Writer::default();
    w.u8(FROM_STOPPED);
    w.str(message);
    w.0
}

/// The message carrying `response`; with `same_preview` its scene, figures and picks are left
/// out (they are those of the previous answer).
pub fn encode_answer(response: &EvalResponse, same_preview: bool) -> Vec<u8> {
    let mut w = Writer::default();
    w.u8(FROM_ANSWER);
    w.u64(response.seq);
    w.strs(&response.view);
    let mut ids: Vec<&String> = response.statuses.keys().collect();
    ids.sort();
    w.len(ids.len());
    for id in ids {
        w.str(id);
        status(&mut w, &response.statuses[id]);
    }
    w.bool(!same_preview);
    if !same_preview {
        scene(&mut w, &response.scene);
        stats(&mut w, &response.stats);
        picks(&mut w, &response.picks);
    }
    w.f64(response.eval_ms);
    w.u64(response.ran as u64);
    w.bool(response.complete);
    w.0
}

/// A message from the worker from its bytes.
pub fn decode_from_worker(bytes: &[u8]) -> Res<FromWorker> {
    let mut r = Reader::new(bytes);
    let message = match r.u8()? {
        FROM_READY => FromWorker::Ready,
        FROM_FAILED => FromWorker::Failed {
            seq: r.u64()?,
            message: r.string()?,
        },
        FROM_STOPPED => FromWorker::Stopped {
            message: r.string()?,
        },
        FROM_DRAGGED => FromWorker::Dragged(drag::read_answer(&mut r)?),
        FROM_PARSED => FromWorker::Parsed {
            token: r.u64()?,
            result: if r.bool()? {
                let skeleton = r.string()?;
                let n = r.len(8 + 8 + 8 + 1)?;
                let literals = (0..n)
                    .map(|_| {
                        let at = LiteralRef {
                            node: r.string()?,
                            input: r.string()?,
                            key: r.u64()?,
                        };
                        Ok((at, read_value(&mut r, 0)?))
                    })
                    .collect::<Res<_>>()?;
                Ok(Parsed { skeleton, literals })
            } else {
                Err(r.string()?)
            },
        },
        FROM_ANSWER => {
            let seq = r.u64()?;
            let view = r.strings()?;
            let n = r.len(2)?;
            let mut statuses = HashMap::with_capacity(n);
            for _ in 0..n {
                let id = r.string()?;
                statuses.insert(id, read_status(&mut r)?);
            }
            let preview = if r.bool()? {
                Some((
                    read_scene(&mut r)?,
                    read_stats(&mut r)?,
                    read_picks(&mut r)?,
                ))
            } else {
                None
            };
            FromWorker::Answer(Box::new(Answer {
                seq,
                view,
                statuses,
                preview,
                eval_ms: r.f64()?,
                ran: r.usize()?,
                complete: r.bool()?,
            }))
        }
        _ => return Err(WireError("unknown message from the worker")),
    };
    r.end()?;
    Ok(message)
}

/// Whether two scenes draw the same (their buffers are equal).
pub fn same_scene(a: &Scene, b: &Scene) -> bool {
    a.background == b.background
        && a.face_vertices() == b.face_vertices()
        && a.face_indices() == b.face_indices()
        && a.segments() == b.segments()
        && a.points() == b.points()
        && a.skipped() == b.skipped()
}

#[cfg(test)]
mod tests;
