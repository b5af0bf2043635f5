//! Dragging the net itself: the design's free inputs solved so that one vertex of a quad mesh
//! reaches a target point, pinned vertices stay where they are and the faces stay (++)(++).
//!
//! The unknowns u are the free inputs (expanded into numbers, with bounds, as an optimization's
//! variables). The residual r stacks the grabbed vertex minus the target (3 rows) and every pinned
//! vertex minus where it started (3 rows each, weighted by [`PIN_WEIGHT`]). Its Jacobian
//! J = ∂r/∂u has few rows and many columns: one reverse pass per row gives it exactly (the
//! optimizer's reverse pass, seeded with one coordinate of one vertex). A step is the minimum-change Levenberg–Marquardt step
//!
//! `Δu = −D Jᵀ (J D Jᵀ + λ I)⁻¹ r`,
//!
//! D the squares of the inputs' scales (a bounded input's range, else the design's size), so a
//! ratio and a coordinate in metres weigh alike and the rest of the design stays close to where it
//! was; the step is clipped to the bounds and halved while it folds a face (when the start had
//! none) or does not reduce |r|; λ grows when no step helps and shrinks when one does. When the
//! target cannot be reached the iteration settles at the least-squares point, and `distance_left`
//! says how far the vertex stayed from the target (`shared/inverse-design-notes.md`).

use std::collections::HashMap;

use glam::DVec3;
use petgraph::stable_graph::NodeIndex;

use super::path::ValuePath;
use super::problem::{Problem, SetupMismatch};
use super::setup::{Method, Setup, Variable};
use crate::graph::Graph;
use crate::node::{NodeContext, Widget};
use crate::value::{Value, ValueType};

/// How much more a pinned vertex's distance weighs than the grabbed vertex's: a pin is all but
/// a hard constraint, so a target the inputs cannot reach moves the grabbed vertex only as far as
/// the pins let it (a pin gives way by about 1/PIN_WEIGHT² of the distance left).
pub const PIN_WEIGHT: f64 = 1e3;

/// What to drag, where to, and what may change.
#[derive(Debug, Clone)]
pub struct DragRequest {
    /// The node whose quad mesh output is dragged.
    pub node: String,
    /// The grabbed vertex: (row i along the generatrix, column j along the directrix).
    pub vertex: (usize, usize),
    /// Which net of a list of them (a construction over several generatrices, e.g. a
    /// non-manifold one): `None` for a node whose output is one quad mesh.
    pub item: Option<usize>,
    /// Where it should go.
    pub target: DVec3,
    /// Vertices that must stay where they are.
    pub pins: Vec<(usize, usize)>,
    /// Where the pins must stay (`None`: where they are in the graph given; a live drag solved
    /// again from its last answer keeps the positions of the grab).
    pub pinned_at: Option<Vec<DVec3>>,
    /// The free inputs (`None`: every parameter upstream of the node, [`default_free`]).
    pub free: Option<Vec<Variable>>,
    /// Steps at most.
    pub max_iter: usize,
}

impl DragRequest {
    /// A request with no pins, the default free inputs and 30 steps at most.
    pub fn new(node: impl Into<String>, vertex: (usize, usize), target: DVec3) -> Self {
        Self {
            node: node.into(),
            vertex,
            item: None,
            target,
            pins: Vec::new(),
            pinned_at: None,
            free: None,
            max_iter: 30,
        }
    }
}

/// One input number the drag changed.
#[derive(Debug, Clone, PartialEq)]
pub struct Change {
    /// Where it lives (`node.input[…]`).
    pub input: ValuePath,
    /// Its value before.
    pub old: f64,
    /// Its value after.
    pub new: f64,
}

/// What a drag reached.
#[derive(Debug, Clone)]
pub struct DragReport {
    /// Where the grabbed vertex ended.
    pub reached: DVec3,
    /// Its distance to the target.
    pub distance_left: f64,
    /// The largest distance a pinned vertex moved.
    pub pin_drift: f64,
    /// Faces that are not (++)(++), per construction on the path (`None`: it failed).
    pub not_convex: Vec<(String, Option<usize>)>,
    /// Every input number that changed.
    pub changes: Vec<Change>,
    /// Steps taken.
    pub iterations: usize,
    /// Graph evaluations.
    pub evaluations: u64,
    /// The graph with the new values.
    pub graph: Graph,
}

/// Why a drag cannot run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DragError {
    /// The request names something the graph does not have.
    #[error("{0}")]
    Request(String),
    /// The setup built from it does not fit the graph.
    #[error(transparent)]
    Setup(#[from] SetupMismatch),
    /// The net cannot be evaluated.
    #[error("the net cannot be evaluated: {0}")]
    Evaluation(String),
}

/// The free inputs a drag of `node` changes by default: every parameter upstream of it — a
/// slider's value within its range (the inputs its port declares as its range; not a slider
/// snapping to a step, which cannot move continuously), a point list's points, a graph mapper's
/// handles (their v, in the port's range), a list of numbers — numbers only (integers stay
/// integers), each with its bounds.
pub fn default_free(graph: &Graph, node: &str) -> Result<Vec<Variable>, DragError> {
    let start = graph
        .index(node)
        .map_err(|_| DragError::Request(format!("no node '{node}'")))?;
    let mut seen = vec![false; graph.index_bound()];
    let mut stack = vec![start];
    let mut upstream = Vec::new();
    while let Some(k) = stack.pop() {
        for s in graph.sources(k) {
            if !std::mem::replace(&mut seen[s.index()], true) {
                upstream.push(s);
                stack.push(s);
            }
        }
    }
    upstream.sort();
    let mut free = Vec::new();
    for k in upstream {
        let Some(n) = graph.node_at(k) else { continue };
        if !n.enabled {
            continue;
        }
        let wired: Vec<usize> = graph
            .wires_into(k)
            .iter()
            .map(|(_, w)| w.to_input)
            .collect();
        for (input, port) in n.def.inputs.iter().enumerate() {
            if wired.contains(&input) || port.ty == ValueType::Integer {
                continue;
            }
            let widget = port.widget();
            let numbers = matches!(port.ty, ValueType::Number | ValueType::Any)
                && n.def.has_flag(crate::node::NodeFlag::Parameter)
                && widget == Widget::Auto
                && port.access != crate::value::Access::Item;
            if !(matches!(
                widget,
                Widget::Slider | Widget::PointHandles | Widget::MapperHandles
            ) || numbers)
            {
                continue;
            }
            let value = n.value(input).or(port.default.as_ref());
            if value.is_none_or(|v| !holds_numbers(v)) {
                continue;
            }
            // A slider that snaps to a step moves in whole steps: its derivative is 0, so a
            // continuous solve cannot move it (set its step to 0 to let a drag move it).
            if port
                .hint
                .step_input
                .and_then(|s| sibling_number(graph, k, s))
                .is_some_and(|step| step > 0.0)
            {
                continue;
            }
            let (min, max) = match (
                port.hint.range_inputs,
                port.hint.hard_range,
                port.hint.soft_range,
            ) {
                (Some((lo, hi)), _, _) => (
                    sibling_number(graph, k, lo).unwrap_or(f64::NEG_INFINITY),
                    sibling_number(graph, k, hi).unwrap_or(f64::INFINITY),
                ),
                (None, Some(r), _) | (None, None, Some(r)) => r,
                (None, None, None) => (f64::NEG_INFINITY, f64::INFINITY),
            };
            free.push(Variable {
                input: ValuePath {
                    node: n.id.clone(),
                    port: port.name.to_string(),
                    indices: Vec::new(),
                },
                min,
                max,
            });
        }
    }
    Ok(free)
}

/// Whether a literal holds numbers a drag may move (no integers: they stay integers).
fn holds_numbers(v: &Value) -> bool {
    match v {
        Value::Number(_) | Value::Point(_) | Value::Vector(_) => true,
        Value::List(items) => !items.is_empty() && items.iter().all(holds_numbers),
        _ => false,
    }
}

/// The literal number of input `name` of node `k` (its default when it has none).
fn sibling_number(graph: &Graph, k: NodeIndex, name: &str) -> Option<f64> {
    let n = graph.node_at(k)?;
    let i = n.def.input_index(name)?;
    if graph.wires_into(k).iter().any(|(_, w)| w.to_input == i) {
        return None;
    }
    n.value(i).or(n.def.inputs[i].default.as_ref())?.as_f64()
}

/// The dragged net: its quad mesh output and size.
struct Net {
    index: NodeIndex,
    output: usize,
}

impl Net {
    fn find(graph: &Graph, node: &str) -> Result<Self, DragError> {
        let index = graph
            .index(node)
            .map_err(|_| DragError::Request(format!("--node: no node '{node}'")))?;
        let def = &graph.node_at(index).expect("indexed").def;
        let output = def
            .outputs
            .iter()
            .position(|p| p.ty == ValueType::QuadMesh)
            .ok_or_else(|| {
                DragError::Request(format!(
                    "--node: node '{node}' ({}) has no quad mesh output",
                    def.id
                ))
            })?;
        Ok(Self { index, output })
    }
}

/// Solves a drag on a copy of `graph` (see the module's documentation).
pub fn drag(
    graph: &Graph,
    request: &DragRequest,
    ctx: &NodeContext,
) -> Result<DragReport, DragError> {
    if !request.target.is_finite() {
        return Err(DragError::Request(format!(
            "--to: the target ({}, {}, {}) is not finite",
            request.target.x, request.target.y, request.target.z
        )));
    }
    let net = Net::find(graph, &request.node)?;
    let free = match &request.free {
        Some(f) => f.clone(),
        None => default_free(graph, &request.node)?,
    };
    if free.is_empty() {
        return Err(DragError::Request(format!(
            "nothing upstream of '{}' can move: no slider, point list, mapper handle or list \
             of numbers (or every one is locked)",
            request.node
        )));
    }
    let keeps_convex = super::convexity::margins_output(graph, net.index).is_some();
    let setup = Setup {
        objective: ValuePath {
            node: request.node.clone(),
            port: graph.node_at(net.index).expect("indexed").def.outputs[net.output]
                .name
                .to_string(),
            indices: Vec::new(),
        },
        variables: free,
        penalties: Vec::new(),
        convex: if keeps_convex {
            vec![request.node.clone()]
        } else {
            Vec::new()
        },
        method: Method::Lbfgsb,
        max_iter: request.max_iter,
    };
    let mut problem = Problem::new(graph.clone(), setup, true)?;
    let (lo, hi) = problem.bounds();
    let mut x = problem.start();
    for ((v, l), h) in x.iter_mut().zip(&lo).zip(&hi) {
        *v = v.clamp(*l, *h);
    }
    let start = x.clone();
    problem.evaluate(&x, ctx).map_err(DragError::Evaluation)?;
    let mesh = mesh_of(&problem, &net, request.item)?;
    let (rows, cols) = (mesh.0, mesh.1);
    let mut grabbed = vec![request.vertex];
    grabbed.extend(request.pins.iter().copied());
    for &(i, j) in &grabbed {
        if i >= rows || j >= cols {
            return Err(DragError::Request(format!(
                "vertex ({i}, {j}) is out of range: '{}' has {rows} rows (i) and {cols} columns (j)",
                request.node
            )));
        }
    }
    let pinned_at: Vec<DVec3> = match &request.pinned_at {
        Some(at) if at.len() == request.pins.len() => at.clone(),
        Some(at) => {
            return Err(DragError::Request(format!(
                "{} pins but {} positions to hold them at",
                request.pins.len(),
                at.len()
            )));
        }
        None => request
            .pins
            .iter()
            .map(|&(i, j)| mesh.2[i * cols + j])
            .collect(),
    };
    let size = extent(&mesh.2);
    // The inputs' scales: a bounded input's range, else the design's size.
    let scale: Vec<f64> = lo
        .iter()
        .zip(&hi)
        .map(|(l, h)| {
            let w = h - l;
            if w.is_finite() && w > 0.0 { w } else { size }
        })
        .collect();
    let convex_start = keeps_convex && !problem.kept_folded();
    let residual = |mesh: &[DVec3]| -> Vec<f64> {
        let mut r = Vec::with_capacity(3 * grabbed.len());
        let (i, j) = request.vertex;
        r.extend((mesh[i * cols + j] - request.target).to_array());
        for (&(i, j), p) in request.pins.iter().zip(&pinned_at) {
            r.extend(((mesh[i * cols + j] - *p) * PIN_WEIGHT).to_array());
        }
        r
    };
    let norm = |r: &[f64]| r.iter().map(|v| v * v).sum::<f64>();
    let mut r = residual(&mesh.2);
    let mut merit = norm(&r);
    let tolerance = (1e-9 * size).powi(2);
    let mut lambda = 1e-6;
    let mut iterations = 0;
    while iterations < request.max_iter && merit > tolerance {
        iterations += 1;
        let mut jacobian = rows_of(&mut problem, &net, (cols, mesh.3), &grabbed, ctx)?;
        for row in jacobian.iter_mut().skip(3) {
            row.iter_mut().for_each(|v| *v *= PIN_WEIGHT);
        }
        let Some(step) = step(&jacobian, &r, &scale, lambda) else {
            break;
        };
        let mut accepted = false;
        let mut t = 1.0;
        for _ in 0..12 {
            let trial: Vec<f64> = x
                .iter()
                .zip(&step)
                .zip(lo.iter().zip(&hi))
                .map(|((v, s), (l, h))| (v + t * s).clamp(*l, *h))
                .collect();
            if trial == x {
                break;
            }
            if problem.evaluate(&trial, ctx).is_ok()
                && let Ok(m) = mesh_of(&problem, &net, request.item)
                && !(convex_start && problem.kept_folded())
            {
                let rt = residual(&m.2);
                let mt = norm(&rt);
                if mt < merit {
                    (x, r, merit) = (trial, rt, mt);
                    accepted = true;
                    break;
                }
            }
            t *= 0.5;
        }
        if accepted {
            lambda = (lambda / 3.0).max(1e-12);
        } else {
            lambda *= 10.0;
            if lambda > 1e6 {
                break;
            }
        }
    }
    problem.evaluate(&x, ctx).map_err(DragError::Evaluation)?;
    let mesh = mesh_of(&problem, &net, request.item)?;
    let (i, j) = request.vertex;
    let reached = mesh.2[i * cols + j];
    let pin_drift = request
        .pins
        .iter()
        .zip(&pinned_at)
        .map(|(&(i, j), p)| mesh.2[i * cols + j].distance(*p))
        .fold(0.0, f64::max);
    let variables = problem.setup().variables.clone();
    let changes = variables
        .iter()
        .zip(start.iter().zip(&x))
        .filter(|(_, (a, b))| a != b)
        .map(|(v, (a, b))| Change {
            input: v.input.clone(),
            old: *a,
            new: *b,
        })
        .collect();
    let not_convex = problem.not_convex();
    let evaluations = problem.evaluations;
    Ok(DragReport {
        reached,
        distance_left: reached.distance(request.target),
        pin_drift,
        not_convex,
        changes,
        iterations,
        evaluations,
        graph: problem.into_graph(),
    })
}

/// Rows, columns and vertices of the dragged net at the last evaluation, and the index of its
/// first coordinate among the output's numbers (the nets before it in a list).
fn mesh_of(
    problem: &Problem,
    net: &Net,
    item: Option<usize>,
) -> Result<(usize, usize, Vec<DVec3>, usize), DragError> {
    let value = problem
        .output_at(net.index, net.output)
        .map_err(DragError::Evaluation)?;
    let (mesh, offset) = match (value, item) {
        (Value::QuadMesh(g), None) => (g, 0),
        (Value::List(items), Some(k)) => match items.get(k) {
            Some(Value::QuadMesh(g)) => {
                (g, items[..k].iter().map(crate::value::leaves::count).sum())
            }
            _ => {
                return Err(DragError::Request(format!(
                    "the net has {} items; item {k} is not a quad mesh",
                    items.len()
                )));
            }
        },
        (Value::List(items), None) => {
            return Err(DragError::Request(format!(
                "the node's output is a list of {} nets: say which one (the item)",
                items.len()
            )));
        }
        (other, _) => {
            return Err(DragError::Evaluation(format!(
                "the net is {}, not a quad mesh",
                other.type_name()
            )));
        }
    };
    Ok((mesh.rows, mesh.cols, mesh.vertices.clone(), offset))
}

/// The largest coordinate extent of the vertices (1 when they have none).
fn extent(points: &[DVec3]) -> f64 {
    let (lo, hi) = points
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(*p), hi.max(*p))
        });
    let e = (hi - lo).max_element();
    if e.is_finite() && e > 0.0 { e } else { 1.0 }
}

/// ∂(vertex coordinate)/∂u for x, y, z of every grabbed vertex: one reverse pass per row.
fn rows_of(
    problem: &mut Problem,
    net: &Net,
    (cols, offset): (usize, usize),
    vertices: &[(usize, usize)],
    ctx: &NodeContext,
) -> Result<Vec<Vec<f64>>, DragError> {
    let leaves = 3 * problem
        .output_at(net.index, net.output)
        .map(crate::value::leaves::count)
        .map_err(DragError::Evaluation)?
        / 3;
    let mut rows = Vec::with_capacity(3 * vertices.len());
    for &(i, j) in vertices {
        for c in 0..3 {
            let mut seed = vec![0.0; leaves];
            seed[offset + 3 * (i * cols + j) + c] = 1.0;
            let cot = HashMap::from([((net.index, net.output), seed)]);
            let pass = problem.reverse(cot, ctx).map_err(DragError::Evaluation)?;
            rows.push(pass.gradient);
        }
    }
    Ok(rows)
}

/// The damped minimum-change step `−D Jᵀ (J D Jᵀ + λ tr/m I)⁻¹ r` (`None` when it is not finite).
fn step(jacobian: &[Vec<f64>], r: &[f64], scale: &[f64], lambda: f64) -> Option<Vec<f64>> {
    let m = jacobian.len();
    let d: Vec<f64> = scale.iter().map(|s| s * s).collect();
    let mut a = vec![0.0; m * m];
    for p in 0..m {
        for q in 0..=p {
            let v: f64 = jacobian[p]
                .iter()
                .zip(&jacobian[q])
                .zip(&d)
                .map(|((x, y), w)| x * y * w)
                .sum();
            a[p * m + q] = v;
            a[q * m + p] = v;
        }
    }
    let trace: f64 = (0..m).map(|p| a[p * m + p]).sum::<f64>() / m.max(1) as f64;
    let damping = lambda * trace.max(f64::MIN_POSITIVE);
    for p in 0..m {
        a[p * m + p] += damping;
    }
    let y = solve(a, r.to_vec(), m)?;
    let n = scale.len();
    let step: Vec<f64> = (0..n)
        .map(|k| -d[k] * (0..m).map(|p| jacobian[p][k] * y[p]).sum::<f64>())
        .collect();
    step.iter().all(|v| v.is_finite()).then_some(step)
}

/// Solves the small symmetric system `a y = b` by Gaussian elimination with partial pivoting.
fn solve(mut a: Vec<f64>, mut b: Vec<f64>, m: usize) -> Option<Vec<f64>> {
    for col in 0..m {
        let pivot =
            (col..m).max_by(|&p, &q| a[p * m + col].abs().total_cmp(&a[q * m + col].abs()))?;
        if a[pivot * m + col].abs() <= f64::MIN_POSITIVE {
            return None;
        }
        if pivot != col {
            for k in 0..m {
                a.swap(col * m + k, pivot * m + k);
            }
            b.swap(col, pivot);
        }
        for row in col + 1..m {
            let f = a[row * m + col] / a[col * m + col];
            for k in col..m {
                a[row * m + k] -= f * a[col * m + k];
            }
            b[row] -= f * b[col];
        }
    }
    let mut y = vec![0.0; m];
    for row in (0..m).rev() {
        let s: f64 = (row + 1..m).map(|k| a[row * m + k] * y[k]).sum();
        y[row] = (b[row] - s) / a[row * m + row];
    }
    y.iter().all(|v| v.is_finite()).then_some(y)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_small_solve_is_exact() {
        // [[4, 1], [1, 3]] y = [1, 2] → y = (1/11, 7/11).
        let y = solve(vec![4.0, 1.0, 1.0, 3.0], vec![1.0, 2.0], 2).unwrap();
        assert!((y[0] - 1.0 / 11.0).abs() < 1e-15 && (y[1] - 7.0 / 11.0).abs() < 1e-15);
        assert!(solve(vec![0.0; 4], vec![1.0, 1.0], 2).is_none());
    }

    #[test]
    fn the_step_reaches_a_linear_target_in_one_go_when_undamped() {
        // r(u) = J u − t with J 1 × 3: the minimum-change step lands on J u = t.
        let j = vec![vec![1.0, 2.0, -1.0]];
        let r = vec![-3.0];
        let s = step(&j, &r, &[1.0, 1.0, 1.0], 0.0).unwrap();
        let reached: f64 = j[0].iter().zip(&s).map(|(a, b)| a * b).sum();
        assert!((reached - 3.0).abs() < 1e-12, "{reached}");
        // It is the least-norm such step: parallel to Jᵀ.
        assert!((s[1] - 2.0 * s[0]).abs() < 1e-12 && (s[2] + s[0]).abs() < 1e-12);
    }
}
