//! The messages between the page and its evaluation worker (docs/web.md, "The evaluation
//! worker"): the page sends graphs to evaluate (their RON text) and the files opened on the page;
//! the worker answers with what the desktop worker thread answers — node statuses, the preview
//! scene, its figures and picks.
//!
//! One message is one `ArrayBuffer` (transferred, not copied): a tag byte, then little-endian
//! numbers, length-prefixed texts and lists, and the scene's GPU buffers as they are uploaded.
//! Decoding checks every length against what is left, so a malformed message is an error, not a
//! panic or a huge allocation.

use std::collections::HashMap;
use std::sync::Arc;

use bytemuck::Pod;
use cnets_editor::preview::{
    ColorMode, Layer, LegendInfo, PickCurve, PickGeometry, PickMesh, Picks, PreviewOptions,
    PreviewStats,
};
use cnets_editor::worker::{EvalResponse, NodeStatus};
use cnets_engine::Value;
use cnets_geometry::fabrication::FaceClass;
use cnets_geometry::{DVec3, PolygonMesh, Polyline, QuadGrid};
use cnets_render::{Bounds, Color, Legend, Scene, SceneParts};

use crate::literals::LiteralRef;

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
}

/// A message from the page to the worker.
#[derive(Clone, Debug, PartialEq)]
pub enum ToWorker {
    /// Evaluate a graph (the newest one wins).
    Evaluate(Job),
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

type Res<T> = Result<T, WireError>;

const TO_EVALUATE: u8 = 1;
const TO_PROVIDE: u8 = 2;
const TO_LITERAL: u8 = 3;
const TO_PARSE: u8 = 4;
const FROM_READY: u8 = 10;
const FROM_ANSWER: u8 = 11;
const FROM_FAILED: u8 = 12;
const FROM_STOPPED: u8 = 13;
const FROM_PARSED: u8 = 14;

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
        }
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
        }),
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

// --- the parts -------------------------------------------------------------------------------

fn options(w: &mut Writer, o: &PreviewOptions) {
    w.u8(match o.color_mode {
        ColorMode::Configuration => 0,
        ColorMode::Planarity => 1,
        ColorMode::Plain => 2,
        ColorMode::Distance => 3,
    });
    w.opt(o.distance_to.as_ref(), |w, uid| w.u64(*uid));
    let layers = Layer::ALL
        .iter()
        .enumerate()
        .fold(0u32, |acc, (k, l)| acc | (u32::from(o.shows(*l)) << k));
    w.u32(layers);
    w.f64(o.planarity_limit());
}

fn read_options(r: &mut Reader) -> Res<PreviewOptions> {
    let mut o = PreviewOptions::default();
    o.color_mode = match r.u8()? {
        0 => ColorMode::Configuration,
        1 => ColorMode::Planarity,
        2 => ColorMode::Plain,
        3 => ColorMode::Distance,
        _ => return Err(WireError("unknown colour mode")),
    };
    o.distance_to = r.opt(Reader::u64)?;
    let layers = r.u32()?;
    for (k, l) in Layer::ALL.iter().enumerate() {
        o.set(*l, layers & (1 << k) != 0);
    }
    let limit = r.f64()?;
    if limit != o.planarity_limit() && !o.set_planarity_limit(limit) {
        return Err(WireError("planarity limit out of range"));
    }
    Ok(o)
}

const OK: u8 = 0;
const ERROR: u8 = 1;
const BLOCKED: u8 = 2;
const DISABLED: u8 = 3;
const IDLE: u8 = 4;
const RUNNING: u8 = 5;

fn status(w: &mut Writer, s: &NodeStatus) {
    match s {
        NodeStatus::Ok {
            warnings,
            outputs,
            time_ms,
            readout,
            ran_on,
        } => {
            w.u8(OK);
            w.strs(warnings);
            w.strs(outputs);
            w.f64(*time_ms);
            w.opt(readout.as_ref(), |w, t| w.str(t));
            w.opt(ran_on.as_ref(), |w, values| {
                w.len(values.len());
                for v in values {
                    value(w, v);
                }
            });
        }
        NodeStatus::Error(m) => {
            w.u8(ERROR);
            w.str(m);
        }
        NodeStatus::Blocked(m) => {
            w.u8(BLOCKED);
            w.str(m);
        }
        NodeStatus::Disabled => w.u8(DISABLED),
        NodeStatus::Idle => w.u8(IDLE),
        NodeStatus::Running { last_ms } => {
            w.u8(RUNNING);
            w.f64(*last_ms);
        }
    }
}

fn read_status(r: &mut Reader) -> Res<NodeStatus> {
    Ok(match r.u8()? {
        OK => NodeStatus::Ok {
            warnings: r.strings()?,
            outputs: r.strings()?,
            time_ms: r.f64()?,
            readout: r.opt(Reader::string)?,
            ran_on: r.opt(|r| {
                let n = r.len(1)?;
                (0..n).map(|_| read_value(r, 0)).collect()
            })?,
        },
        ERROR => NodeStatus::Error(r.string()?),
        BLOCKED => NodeStatus::Blocked(r.string()?),
        DISABLED => NodeStatus::Disabled,
        IDLE => NodeStatus::Idle,
        RUNNING => NodeStatus::Running { last_ms: r.f64()? },
        _ => return Err(WireError("unknown node status")),
    })
}

/// The values a graph mapper ran on: what its widget reads (numbers, text, points, curves and
/// lists of them); anything else crosses as `Null`.
fn value(w: &mut Writer, v: &Value) {
    match v {
        Value::Number(x) => {
            w.u8(1);
            w.f64(*x);
        }
        Value::Integer(i) => {
            w.u8(2);
            w.u64(*i as u64);
        }
        Value::Boolean(b) => {
            w.u8(3);
            w.bool(*b);
        }
        Value::Text(t) => {
            w.u8(4);
            w.str(t);
        }
        Value::Point(p) => {
            w.u8(5);
            w.dvec3(*p);
        }
        Value::Vector(p) => {
            w.u8(6);
            w.dvec3(*p);
        }
        Value::Polyline(p) => {
            w.u8(7);
            w.dvec3s(&p.points);
            w.bool(p.closed);
        }
        Value::List(_) => {
            let items = v.as_list().unwrap_or(&[]);
            w.u8(8);
            w.len(items.len());
            for item in items {
                value(w, item);
            }
        }
        _ => w.u8(0),
    }
}

/// Lists nest at most this deep in a message (a mapper's inputs are flat or one level deep).
const MAX_DEPTH: usize = 32;

fn read_value(r: &mut Reader, depth: usize) -> Res<Value> {
    if depth > MAX_DEPTH {
        return Err(WireError("values nested too deep"));
    }
    Ok(match r.u8()? {
        0 => Value::Null,
        1 => Value::Number(r.f64()?),
        2 => Value::Integer(r.u64()? as i64),
        3 => Value::Boolean(r.bool()?),
        4 => Value::text(r.string()?),
        5 => Value::Point(r.dvec3()?),
        6 => Value::Vector(r.dvec3()?),
        7 => {
            let points = r.dvec3s()?;
            let closed = r.bool()?;
            Value::from(Polyline { points, closed })
        }
        8 => {
            let n = r.len(1)?;
            // Sized once: a list of millions of items is not grown by doubling.
            let mut items = Vec::with_capacity(n);
            for _ in 0..n {
                items.push(read_value(r, depth + 1)?);
            }
            Value::list(items)
        }
        _ => return Err(WireError("unknown value")),
    })
}

fn scene(w: &mut Writer, s: &Scene) {
    w.raw(&s.background.0);
    w.pods(s.face_vertices());
    w.pods(s.face_indices());
    w.pods(s.segments());
    w.pods(s.points());
    w.opt(s.bounds().as_ref(), |w, b| {
        w.pods(&[b.min.to_array(), b.max.to_array()]);
    });
    w.u64(s.skipped() as u64);
}

fn read_scene(r: &mut Reader) -> Res<Scene> {
    let mut background = [0u8; 4];
    background.copy_from_slice(r.take(4)?);
    let parts = SceneParts {
        background: Color(background),
        face_vertices: r.pods()?,
        face_indices: r.pods()?,
        segments: r.pods()?,
        points: r.pods()?,
        bounds: r.opt(|r| {
            let corners: Vec<[f32; 3]> = r.pods()?;
            match corners[..] {
                [min, max] => Ok(Bounds::new(min.into(), max.into())),
                _ => Err(WireError("a box has two corners")),
            }
        })?,
        skipped: r.usize()?,
    };
    Scene::from_parts(parts).ok_or(WireError("a triangle index past the vertices"))
}

fn class_index(c: FaceClass) -> u8 {
    FaceClass::ALL.iter().position(|k| *k == c).unwrap_or(0) as u8
}

fn read_class(r: &mut Reader) -> Res<FaceClass> {
    FaceClass::ALL
        .get(usize::from(r.u8()?))
        .copied()
        .ok_or(WireError("unknown face class"))
}

fn stats(w: &mut Writer, s: &PreviewStats) {
    w.u64(s.vertices as u64);
    w.u64(s.faces as u64);
    w.opt(s.max_planarity.as_ref(), |w, p| w.f64(*p));
    w.opt(s.max_planarity_mesh.as_ref(), |w, m| w.str(m));
    match &s.legend {
        LegendInfo::None => w.u8(0),
        LegendInfo::Classes(classes) => {
            w.u8(1);
            w.len(classes.len());
            for (c, n) in classes {
                w.u8(class_index(*c));
                w.u64(*n as u64);
            }
        }
        LegendInfo::Planarity(l) | LegendInfo::Distance(l) => {
            w.u8(if matches!(s.legend, LegendInfo::Distance(_)) {
                3
            } else {
                2
            });
            w.str(&l.title);
            w.f64(l.min);
            w.f64(l.max);
            w.len(l.stops.len());
            for (x, c) in &l.stops {
                w.f64(*x);
                w.raw(&c.0);
            }
            w.strs(&l.labels);
        }
    }
    w.u64(s.apices as u64);
    w.opt(s.distance.as_ref(), |w, d| {
        w.str(&d.reference);
        w.f64(d.max);
        w.f64(d.rms);
        w.u64(d.vertices as u64);
    });
    w.f64(s.build_ms);
}

fn read_stats(r: &mut Reader) -> Res<PreviewStats> {
    let vertices = r.usize()?;
    let faces = r.usize()?;
    let max_planarity = r.opt(Reader::f64)?;
    let max_planarity_mesh = r.opt(Reader::string)?;
    let legend = match r.u8()? {
        0 => LegendInfo::None,
        1 => {
            let n = r.len(9)?;
            LegendInfo::Classes(
                (0..n)
                    .map(|_| Ok((read_class(r)?, r.usize()?)))
                    .collect::<Res<_>>()?,
            )
        }
        kind @ (2 | 3) => {
            let title = r.string()?;
            let min = r.f64()?;
            let max = r.f64()?;
            let n = r.len(12)?;
            let stops = (0..n)
                .map(|_| {
                    let x = r.f64()?;
                    let mut c = [0u8; 4];
                    c.copy_from_slice(r.take(4)?);
                    Ok((x, Color(c)))
                })
                .collect::<Res<_>>()?;
            let legend = Legend {
                title,
                min,
                max,
                stops,
                labels: r.strings()?,
            };
            if kind == 3 {
                LegendInfo::Distance(legend)
            } else {
                LegendInfo::Planarity(legend)
            }
        }
        _ => return Err(WireError("unknown legend")),
    };
    Ok(PreviewStats {
        vertices,
        faces,
        max_planarity,
        max_planarity_mesh,
        legend,
        apices: r.usize()?,
        distance: r.opt(|r| {
            Ok(cnets_editor::preview::DistanceFigures {
                reference: r.string()?,
                max: r.f64()?,
                rms: r.f64()?,
                vertices: r.usize()?,
            })
        })?,
        build_ms: r.f64()?,
    })
}

fn picks(w: &mut Writer, p: &Picks) {
    w.len(p.meshes.len());
    for m in &p.meshes {
        w.str(&m.node);
        w.str(&m.output);
        w.opt(m.item.as_ref(), |w, i| w.u64(*i as u64));
        match &m.geometry {
            PickGeometry::Grid(g) => {
                w.u8(0);
                w.u64(g.rows as u64);
                w.u64(g.cols as u64);
                w.bool(g.wrap_rows);
                w.bool(g.wrap_cols);
                w.dvec3s(&g.vertices);
            }
            PickGeometry::Mesh(mesh) => {
                w.u8(1);
                w.dvec3s(&mesh.vertices);
                w.pods(&mesh.indices);
                w.pods(&mesh.face_starts);
            }
        }
        w.opt(m.classes.as_ref(), |w, classes| {
            let bytes: Vec<u8> = classes.iter().map(|c| class_index(*c)).collect();
            w.bytes(&bytes);
        });
        w.pods(&m.planarity);
    }
    w.len(p.curves.len());
    for c in &p.curves {
        w.str(&c.node);
        w.str(&c.output);
        w.dvec3s(&c.polyline.points);
        w.bool(c.polyline.closed);
    }
}

fn read_picks(r: &mut Reader) -> Res<Picks> {
    let n = r.len(8)?;
    let mut meshes = Vec::with_capacity(n);
    for _ in 0..n {
        let node = r.string()?;
        let output = r.string()?;
        let item = r.opt(Reader::usize)?;
        let geometry = match r.u8()? {
            0 => {
                let rows = r.usize()?;
                let cols = r.usize()?;
                let wrap_rows = r.bool()?;
                let wrap_cols = r.bool()?;
                let vertices = r.dvec3s()?;
                if rows.checked_mul(cols) != Some(vertices.len()) {
                    return Err(WireError("a grid's vertex count is not rows × columns"));
                }
                PickGeometry::Grid(Arc::new(QuadGrid {
                    rows,
                    cols,
                    wrap_rows,
                    wrap_cols,
                    vertices,
                }))
            }
            1 => {
                let vertices = r.dvec3s()?;
                let indices: Vec<u32> = r.pods()?;
                let face_starts: Vec<u32> = r.pods()?;
                let ordered = face_starts.windows(2).all(|w| w[0] <= w[1])
                    && face_starts
                        .last()
                        .is_none_or(|&s| s as usize <= indices.len());
                if !ordered || indices.iter().any(|&i| i as usize >= vertices.len()) {
                    return Err(WireError("a polygon mesh's indices are out of range"));
                }
                PickGeometry::Mesh(Arc::new(PolygonMesh {
                    vertices,
                    indices,
                    face_starts,
                }))
            }
            _ => return Err(WireError("unknown mesh kind")),
        };
        let classes = r.opt(|r| {
            r.bytes()?
                .iter()
                .map(|&k| {
                    FaceClass::ALL
                        .get(usize::from(k))
                        .copied()
                        .ok_or(WireError("unknown face class"))
                })
                .collect()
        })?;
        meshes.push(PickMesh {
            node,
            output,
            item,
            geometry,
            classes,
            planarity: r.pods()?,
        });
    }
    let n = r.len(8)?;
    let mut curves = Vec::with_capacity(n);
    for _ in 0..n {
        let node = r.string()?;
        let output = r.string()?;
        let points = r.dvec3s()?;
        let closed = r.bool()?;
        curves.push(PickCurve {
            node,
            output,
            polyline: Arc::new(Polyline { points, closed }),
        });
    }
    Ok(Picks { meshes, curves })
}

// --- the encoding ----------------------------------------------------------------------------

#[derive(Default)]
struct Writer(Vec<u8>);

impl Writer {
    fn raw(&mut self, b: &[u8]) {
        self.0.extend_from_slice(b);
    }
    fn u8(&mut self, x: u8) {
        self.0.push(x);
    }
    fn bool(&mut self, x: bool) {
        self.u8(u8::from(x));
    }
    fn u32(&mut self, x: u32) {
        self.raw(&x.to_le_bytes());
    }
    fn u64(&mut self, x: u64) {
        self.raw(&x.to_le_bytes());
    }
    fn f64(&mut self, x: f64) {
        self.raw(&x.to_le_bytes());
    }
    fn len(&mut self, n: usize) {
        self.u64(n as u64);
    }
    fn bytes(&mut self, b: &[u8]) {
        self.len(b.len());
        self.raw(b);
    }
    fn str(&mut self, s: &str) {
        self.bytes(s.as_bytes());
    }
    fn strs(&mut self, items: &[String]) {
        self.len(items.len());
        for s in items {
            self.str(s);
        }
    }
    fn opt<T>(&mut self, x: Option<&T>, f: impl FnOnce(&mut Self, &T)) {
        self.bool(x.is_some());
        if let Some(x) = x {
            f(self, x);
        }
    }
    /// A slice of plain data as its bytes (GPU buffers, indices, numbers), prefixed by its count.
    fn pods<T: Pod>(&mut self, items: &[T]) {
        self.len(items.len());
        self.raw(bytemuck::cast_slice(items));
    }
    fn dvec3(&mut self, p: DVec3) {
        for x in p.to_array() {
            self.f64(x);
        }
    }
    fn dvec3s(&mut self, points: &[DVec3]) {
        let flat: Vec<[f64; 3]> = points.iter().map(|p| p.to_array()).collect();
        self.pods(&flat);
    }
}

struct Reader<'a> {
    buf: &'a [u8],
}

impl<'a> Reader<'a> {
    fn new(buf: &'a [u8]) -> Self {
        Self { buf }
    }
    fn take(&mut self, n: usize) -> Res<&'a [u8]> {
        if n > self.buf.len() {
            return Err(WireError("it ends early"));
        }
        let (head, tail) = self.buf.split_at(n);
        self.buf = tail;
        Ok(head)
    }
    fn end(&self) -> Res<()> {
        if self.buf.is_empty() {
            Ok(())
        } else {
            Err(WireError("bytes left over"))
        }
    }
    fn array<const N: usize>(&mut self) -> Res<[u8; N]> {
        let mut a = [0u8; N];
        a.copy_from_slice(self.take(N)?);
        Ok(a)
    }
    fn u8(&mut self) -> Res<u8> {
        Ok(self.take(1)?[0])
    }
    fn bool(&mut self) -> Res<bool> {
        match self.u8()? {
            0 => Ok(false),
            1 => Ok(true),
            _ => Err(WireError("a flag is neither 0 nor 1")),
        }
    }
    fn u32(&mut self) -> Res<u32> {
        Ok(u32::from_le_bytes(self.array()?))
    }
    fn u64(&mut self) -> Res<u64> {
        Ok(u64::from_le_bytes(self.array()?))
    }
    fn usize(&mut self) -> Res<usize> {
        usize::try_from(self.u64()?).map_err(|_| WireError("a count too large for this machine"))
    }
    fn f64(&mut self) -> Res<f64> {
        Ok(f64::from_le_bytes(self.array()?))
    }
    /// A count of items of at least `min_size` bytes each: never more than the bytes left allow.
    fn len(&mut self, min_size: usize) -> Res<usize> {
        let n = self.usize()?;
        if n.saturating_mul(min_size.max(1)) > self.buf.len() {
            return Err(WireError("a count larger than the message"));
        }
        Ok(n)
    }
    fn bytes(&mut self) -> Res<&'a [u8]> {
        let n = self.len(1)?;
        self.take(n)
    }
    fn string(&mut self) -> Res<String> {
        String::from_utf8(self.bytes()?.to_vec()).map_err(|_| WireError("a text is not UTF-8"))
    }
    fn strings(&mut self) -> Res<Vec<String>> {
        let n = self.len(8)?;
        (0..n).map(|_| self.string()).collect()
    }
    fn opt<T>(&mut self, f: impl FnOnce(&mut Self) -> Res<T>) -> Res<Option<T>> {
        if self.bool()? {
            f(self).map(Some)
        } else {
            Ok(None)
        }
    }
    fn pods<T: Pod>(&mut self) -> Res<Vec<T>> {
        let size = std::mem::size_of::<T>();
        let n = self.len(size)?;
        Ok(bytemuck::pod_collect_to_vec(self.take(n * size)?))
    }
    fn dvec3(&mut self) -> Res<DVec3> {
        Ok(DVec3::new(self.f64()?, self.f64()?, self.f64()?))
    }
    fn dvec3s(&mut self) -> Res<Vec<DVec3>> {
        let flat: Vec<[f64; 3]> = self.pods()?;
        Ok(flat.into_iter().map(DVec3::from_array).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn round_trip(message: &ToWorker) -> ToWorker {
        decode_to_worker(&encode_to_worker(message)).expect("decodes")
    }

    #[test]
    fn requests_round_trip() {
        let mut options = PreviewOptions::default();
        options.color_mode = ColorMode::Planarity;
        options.set(Layer::Apices, false);
        assert!(options.set_planarity_limit(1e-5));
        let job = ToWorker::Evaluate(Job {
            seq: 42,
            ron: "(nodes: {})".into(),
            base_dir: Some("graphs".into()),
            view: vec!["bay".into(), "inner".into()],
            options,
            literals: vec![LiteralRef {
                node: "big".into(),
                input: "values".into(),
                key: 7,
            }],
            forget: vec![3, 5],
        });
        assert_eq!(round_trip(&job), job);
        let literal = ToWorker::Literal {
            key: 7,
            value: Value::list(vec![
                Value::list(vec![Value::Number(-0.0), Value::Number(f64::MAX)]),
                Value::text("row"),
                Value::Point(DVec3::new(1.0, 2.0, 3.0)),
                Value::Integer(i64::MIN),
                Value::Null,
            ]),
        };
        assert_eq!(round_trip(&literal), literal);
        let parse = ToWorker::Parse(ParseJob {
            token: 3,
            origin: "big.ron".into(),
            library: vec!["graphs".into()],
            text: b"(nodes: {})".to_vec(),
        });
        assert_eq!(round_trip(&parse), parse);
        let file = ToWorker::Provide {
            name: "hull.obj".into(),
            bytes: vec![0, 1, 2, 255],
        };
        assert_eq!(round_trip(&file), file);
    }

    #[test]
    fn answers_round_trip_with_statuses_scene_and_picks() {
        let mut scene = Scene::new();
        let grid = QuadGrid::new(
            2,
            3,
            (0..6)
                .map(|k| DVec3::new(f64::from(k % 3), f64::from(k / 3), 0.5))
                .collect(),
        )
        .unwrap();
        scene
            .add_quad_grid(
                &grid,
                cnets_render::FaceColors::Uniform(Color([10, 20, 30, 255])),
            )
            .unwrap();
        let picks = Picks {
            meshes: vec![PickMesh {
                node: "net".into(),
                output: "mesh".into(),
                item: Some(1),
                geometry: PickGeometry::Grid(Arc::new(grid)),
                classes: Some(vec![FaceClass::Convex, FaceClass::NegativeApex]),
                planarity: vec![1e-15, 2e-3],
            }],
            curves: vec![PickCurve {
                node: "arc".into(),
                output: "curve".into(),
                polyline: Arc::new(Polyline {
                    points: vec![DVec3::X, DVec3::Y],
                    closed: true,
                }),
            }],
        };
        let statuses = HashMap::from([
            (
                "mapper".to_string(),
                NodeStatus::Ok {
                    warnings: vec!["careful".into()],
                    outputs: vec!["0.5".into()],
                    time_ms: 1.5,
                    readout: Some("text".into()),
                    ran_on: Some(vec![
                        Value::Number(0.25),
                        Value::text("bezier"),
                        Value::list(vec![Value::Integer(-3), Value::Point(DVec3::Z)]),
                    ]),
                },
            ),
            ("bad".to_string(), NodeStatus::Error("needs 320 GB".into())),
            ("slow".to_string(), NodeStatus::Running { last_ms: 900.0 }),
            ("off".to_string(), NodeStatus::Disabled),
        ]);
        let response = EvalResponse {
            seq: 9,
            view: vec![],
            statuses: statuses.clone(),
            scene: Arc::new(scene.clone()),
            stats: PreviewStats {
                vertices: 6,
                faces: 2,
                max_planarity: Some(2e-3),
                max_planarity_mesh: Some("net.mesh".into()),
                legend: LegendInfo::Classes(vec![(FaceClass::Convex, 1)]),
                apices: 0,
                distance: Some(cnets_editor::preview::DistanceFigures {
                    reference: "hull".into(),
                    max: 0.179,
                    rms: 0.025,
                    vertices: 560,
                }),
                build_ms: 0.5,
            },
            picks: Arc::new(picks),
            eval_ms: 3.0,
            ran: 4,
            changed_at: web_time::Instant::now(),
            finished_at: web_time::Instant::now(),
            complete: false,
        };
        let Ok(FromWorker::Answer(a)) = decode_from_worker(&encode_answer(&response, false)) else {
            panic!("an answer");
        };
        assert_eq!((a.seq, a.eval_ms, a.ran, a.complete), (9, 3.0, 4, false));
        assert_eq!(a.statuses, statuses);
        let (s, stats, p) = a.preview.expect("the preview");
        assert!(same_scene(&s, &scene) && s.bounds() == scene.bounds());
        assert_eq!(stats.legend, response.stats.legend);
        assert_eq!(p.meshes[0].classes, response.picks.meshes[0].classes);
        assert_eq!(p.meshes[0].planarity, response.picks.meshes[0].planarity);
        assert_eq!(p.meshes[0].geometry.vertices(), grid_vertices(&response));
        assert_eq!(p.curves[0].polyline, response.picks.curves[0].polyline);
        // Without the preview: the statuses only.
        let Ok(FromWorker::Answer(b)) = decode_from_worker(&encode_answer(&response, true)) else {
            panic!("an answer");
        };
        assert!(b.preview.is_none());
    }

    fn grid_vertices(r: &EvalResponse) -> &[DVec3] {
        r.picks.meshes[0].geometry.vertices()
    }

    #[test]
    fn read_files_round_trip_with_their_literals_or_their_error() {
        let parsed = Parsed {
            skeleton: "(nodes: {})".into(),
            literals: vec![(
                LiteralRef {
                    node: "numbers".into(),
                    input: "values".into(),
                    key: 1 << 63,
                },
                Value::list(vec![Value::Number(0.5), Value::Number(-2.0)]),
            )],
        };
        for result in [Ok(parsed), Err("big.ron:3:7: expected ')'".to_string())] {
            match decode_from_worker(&encode_parsed(9, &result)).expect("decodes") {
                FromWorker::Parsed {
                    token,
                    result: back,
                } => {
                    assert_eq!((token, back), (9, result));
                }
                _ => panic!("not a read file"),
            }
        }
    }

    #[test]
    fn malformed_messages_are_errors_not_panics() {
        let job = encode_to_worker(&ToWorker::Provide {
            name: "a.csv".into(),
            bytes: vec![1; 100],
        });
        for cut in 0..job.len() {
            assert!(decode_to_worker(&job[..cut]).is_err(), "cut at {cut}");
        }
        // A count far past the message is refused before anything is allocated.
        let mut huge = vec![TO_PROVIDE];
        huge.extend_from_slice(&u64::MAX.to_le_bytes());
        assert!(decode_to_worker(&huge).is_err());
        assert!(decode_from_worker(&[99]).is_err());
        assert!(decode_from_worker(&[]).is_err());
        // A triangle index past the vertices.
        let mut w = Writer::default();
        w.u8(FROM_ANSWER);
        w.u64(1);
        w.strs(&[]);
        w.len(0);
        w.bool(true);
        w.raw(&[0, 0, 0, 255]);
        w.pods::<cnets_render::FaceVertex>(&[]);
        w.pods(&[0u32, 1, 2]);
        assert!(decode_from_worker(&w.0).is_err());
    }
}
