//! A drag's problem as the drag worker takes it (docs/web.md, "Dragging the net"): the graph at
//! the press as its RON text, the grabbed vertex, the pins and the free inputs.

use std::path::Path;

use cnets_editor::net_drag::DragProblem;
use cnets_engine::file::{GraphMeta, to_ron};
use cnets_engine::optimize::{ValuePath, Variable};

/// A drag's problem as it crosses to the worker: the graph as its RON text.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
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
