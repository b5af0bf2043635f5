//! The evaluation session's state: the worker, what was sent to it last, the statuses it
//! answered and the change-to-picture figures (`worker.rs` is its handler).

use std::collections::HashMap;
use std::path::PathBuf;

use cnets_engine::Graph;
use web_time::Instant;

use crate::worker::{NodeStatus, Worker};

/// Change-to-picture latency figures: from a graph edit to the frame that hands the resulting
/// scene to the GPU.
#[derive(Clone, Debug, Default)]
pub struct Latency {
    /// The last measurement, in milliseconds.
    pub last_ms: f64,
    /// All measurements (capped at 10 000).
    pub samples: Vec<f64>,
    /// The last evaluation time (nodes only), in milliseconds.
    pub eval_ms: f64,
    /// The last scene build time, in milliseconds.
    pub scene_ms: f64,
    /// Nodes that ran in the last evaluation (the evaluation counter: an edit re-runs its
    /// downstream cone, a reopened file nothing).
    pub ran: usize,
    /// Pictures the 3D view took before the rest of the graph (nodes not previewed, or slow)
    /// had finished: how often a slow node did not hold the view back.
    pub early_pictures: usize,
}

/// The evaluation session of the editor.
pub(super) struct Evaluation {
    pub(super) worker: Worker,
    /// What was sent to the worker last: the document's generation and version, the display
    /// options and the nodes "Preview only the selected" draws (a hash; 0: all).
    pub(super) submitted: Option<(u64, u64, crate::preview::PreviewOptions, u64)>,
    /// The last graph sent to the worker, its generation and folder: a graph of a new
    /// generation takes over from it (the evaluator is kept).
    pub(super) last_evaluated: Option<(u64, Graph, Option<PathBuf>)>,
    /// When the document changed since the last request (the start of a latency measurement).
    pub(super) pending_change: Option<Instant>,
    /// The scene version that answers a change, and when the change was made.
    pub(super) awaiting_picture: Option<(u64, Instant)>,
    /// Status of every node after the last finished evaluation.
    pub(super) statuses: HashMap<String, NodeStatus>,
    /// The opened clusters `statuses` belong to.
    pub(super) statuses_view: Vec<String>,
    /// Latency figures.
    pub(super) latency: Latency,
}

impl Evaluation {
    /// A session on `worker`, with a change pending (the first evaluation).
    pub(super) fn new(worker: Worker) -> Self {
        Self {
            worker,
            submitted: None,
            last_evaluated: None,
            pending_change: Some(Instant::now()),
            awaiting_picture: None,
            statuses: HashMap::new(),
            statuses_view: Vec::new(),
            latency: Latency::default(),
        }
    }
}
