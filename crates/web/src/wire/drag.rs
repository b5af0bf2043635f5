//! The drag worker's messages (docs/web.md, "Dragging the net"): a drag's problem at the press,
//! its targets, and what each solve reached.

use std::path::Path;

use cnets_editor::net_drag::{DragProblem, Solved};
use cnets_engine::file::{GraphMeta, to_ron};
use cnets_engine::optimize::{ValuePath, Variable};

use super::WireError;
use super::codec::{Reader, Res, Writer};
use super::values::{read_value, value};

/// A drag's problem as it crosses to the worker: the graph as its RON text.
#[derive(Clone, Debug, PartialEq)]
pub struct DragJob {
    /// The graph (`cnets_engine::file::to_ron`), its clusters isolated.
    pub ron: String,
    /// The folder relative paths resolve in.
    pub base_dir: Option<String>,
    /// The dragged net's node.
    pub node: String,
    /// The grabbed vertex (i, j).
    pub vertex: (u64, u64),
    /// Which of the node's nets, if a list of them.
    pub item: Option<u64>,
    /// The pinned vertices and where each stays.
    pub pins: Vec<((u64, u64), [f64; 3])>,
    /// The free inputs: (`node.input[…]`, min, max).
    pub free: Vec<(String, f64, f64)>,
}

impl DragJob {
    /// The job of `problem` (its files read from `base_dir`).
    pub fn of(problem: &DragProblem, base_dir: Option<&Path>) -> Self {
        Self {
            ron: to_ron(&problem.graph, &GraphMeta::default()),
            base_dir: base_dir.map(|d| d.to_string_lossy().into_owned()),
            node: problem.node.clone(),
            vertex: (problem.vertex.0 as u64, problem.vertex.1 as u64),
            item: problem.item.map(|k| k as u64),
            pins: problem
                .pins
                .iter()
                .zip(&problem.pinned_at)
                .map(|(&(i, j), p)| ((i as u64, j as u64), p.to_array()))
                .collect(),
            free: problem
                .free
                .iter()
                .map(|v| (v.input.to_string(), v.min, v.max))
                .collect(),
        }
    }

    /// The free inputs as the solver takes them (a path that does not parse is an error).
    pub fn variables(&self) -> Result<Vec<Variable>, String> {
        self.free
            .iter()
            .map(|(path, min, max)| {
                Ok(Variable {
                    input: ValuePath::parse(path).map_err(|e| e.to_string())?,
                    min: *min,
                    max: *max,
                })
            })
            .collect()
    }
}

fn index(x: u64) -> usize {
    usize::try_from(x).unwrap_or(usize::MAX)
}

impl DragJob {
    /// The grabbed vertex as indices.
    pub fn vertex(&self) -> (usize, usize) {
        (index(self.vertex.0), index(self.vertex.1))
    }

    /// The pins as indices and points.
    pub fn pins(&self) -> (Vec<(usize, usize)>, Vec<cnets_geometry::DVec3>) {
        self.pins
            .iter()
            .map(|&((i, j), p)| ((index(i), index(j)), cnets_geometry::DVec3::from_array(p)))
            .unzip()
    }
}

pub(super) fn job(w: &mut Writer, job: &DragJob) {
    w.str(&job.ron);
    w.opt(job.base_dir.as_ref(), |w, d| w.str(d));
    w.str(&job.node);
    w.u64(job.vertex.0);
    w.u64(job.vertex.1);
    w.opt(job.item.as_ref(), |w, k| w.u64(*k));
    w.len(job.pins.len());
    for ((i, j), p) in &job.pins {
        w.u64(*i);
        w.u64(*j);
        p.iter().for_each(|x| w.f64(*x));
    }
    w.len(job.free.len());
    for (path, min, max) in &job.free {
        w.str(path);
        w.f64(*min);
        w.f64(*max);
    }
}

pub(super) fn read_job(r: &mut Reader) -> Res<DragJob> {
    Ok(DragJob {
        ron: r.string()?,
        base_dir: r.opt(Reader::string)?,
        node: r.string()?,
        vertex: (r.u64()?, r.u64()?),
        item: r.opt(Reader::u64)?,
        pins: {
            let n = r.len(5 * 8)?;
            (0..n)
                .map(|_| Ok(((r.u64()?, r.u64()?), [r.f64()?, r.f64()?, r.f64()?])))
                .collect::<Res<_>>()?
        },
        free: {
            let n = r.len(8 + 2 * 8)?;
            (0..n)
                .map(|_| Ok((r.string()?, r.f64()?, r.f64()?)))
                .collect::<Res<_>>()?
        },
    })
}

pub(super) fn answer(w: &mut Writer, answer: &Result<Solved, String>) {
    match answer {
        Ok(s) => {
            w.bool(true);
            w.len(s.values.len());
            for (node, input, v) in &s.values {
                w.str(node);
                w.str(input);
                value(w, v);
            }
            w.dvec3(s.reached);
            w.f64(s.distance_left);
            w.f64(s.pin_drift);
            w.u64(s.not_convex as u64);
            w.f64(s.solve_ms);
            w.bool(s.settled);
        }
        Err(e) => {
            w.bool(false);
            w.str(e);
        }
    }
}

pub(super) fn read_answer(r: &mut Reader) -> Res<Result<Solved, String>> {
    if !r.bool()? {
        return Ok(Err(r.string()?));
    }
    let n = r.len(8 + 8 + 1)?;
    let values = (0..n)
        .map(|_| Ok((r.string()?, r.string()?, read_value(r, 0)?)))
        .collect::<Res<_>>()?;
    Ok(Ok(Solved {
        values,
        reached: r.dvec3()?,
        distance_left: r.f64()?,
        pin_drift: r.f64()?,
        not_convex: usize::try_from(r.u64()?).map_err(|_| WireError("a count too large"))?,
        solve_ms: r.f64()?,
        settled: r.bool()?,
    }))
}
