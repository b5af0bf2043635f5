//! Faces kept convex: the `convex` constraint of a setup and the count of faces that are not
//! (++)(++) after a run.
//!
//! A construction reports its convexity margins in an output of role
//! [`Role::FaceMargins`](crate::node::Role::FaceMargins): four unit-free numbers per face, all
//! positive exactly when the face is (++)(++). For a construction named in `convex` the objective
//! gets a *barrier* on every margin below [`THRESHOLD`]:
//!
//! `μ · φ(m)`, `φ(m) = m/δ − 1 − ln(m/δ)` for `0 < m < δ`, `0` for `m ≥ δ`, `+∞` for `m ≤ 0`,
//!
//! with δ = [`THRESHOLD`]. φ and φ′ vanish at δ (the barrier is C¹ and leaves faces that are well
//! inside the convex region alone, so the fit is changed only near a fold), and it grows without
//! bound as a margin approaches 0: a step that would fold a face evaluates to +∞ and the line
//! search shortens it. μ is [`WEIGHT`] times the objective at the start (so the barrier is small
//! beside the fit wherever it is not needed). A start that is already folded is first made convex
//! by minimizing `Σ max(0, δ − m)²` alone (a feasibility phase), then the barrier run starts.

// The tests `!(m > 0.0)` are written so that NaN counts as folded.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use petgraph::stable_graph::NodeIndex;

use crate::graph::Graph;
use crate::node::Role;
use crate::value::Value;

/// δ: margins below it feel the barrier (unit-free: s over the directrix edge length).
pub const THRESHOLD: f64 = 0.02;

/// μ relative to the objective at the start.
pub const WEIGHT: f64 = 1e-3;

/// Numbers per face in a margins output.
pub const PER_FACE: usize = 4;

/// A construction whose margins a run reads.
#[derive(Debug, Clone)]
pub struct Watched {
    /// The node's id.
    pub node: String,
    /// Its index in the graph.
    pub index: NodeIndex,
    /// Its margins output.
    pub output: usize,
    /// Whether `convex` names it (its margins are kept positive); else only counted.
    pub kept: bool,
}

/// What the barrier adds, for the phase the run is in.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Phase {
    /// No construction is kept convex.
    Off,
    /// The start is folded: minimize `Σ max(0, δ − m)²` over the kept margins alone.
    Feasibility,
    /// Keep every kept margin positive with weight μ.
    Barrier(f64),
}

/// The margins output of `node_index` in `graph`, when its node declares one.
pub fn margins_output(graph: &Graph, index: NodeIndex) -> Option<usize> {
    graph
        .node_at(index)?
        .def
        .outputs
        .iter()
        .position(|p| p.hint.role == Role::FaceMargins)
}

/// The numbers of a margins output.
pub fn numbers(value: &Value) -> Vec<f64> {
    value
        .as_list()
        .map(|items| {
            items
                .iter()
                .map(|v| v.as_f64().unwrap_or(f64::NAN))
                .collect()
        })
        .unwrap_or_default()
}

/// Faces with a margin that is not positive (NaN counts as folded).
pub fn folded_faces(margins: &[f64]) -> usize {
    margins
        .chunks(PER_FACE)
        .filter(|face| face.iter().any(|m| !(*m > 0.0)))
        .count()
}

/// φ(m) (see the module's documentation).
pub fn barrier(m: f64) -> f64 {
    if !(m > 0.0) {
        return f64::INFINITY;
    }
    if m >= THRESHOLD {
        return 0.0;
    }
    let t = m / THRESHOLD;
    t - 1.0 - t.ln()
}

/// φ′(m), for 0 < m.
pub fn barrier_slope(m: f64) -> f64 {
    if m >= THRESHOLD || !(m > 0.0) {
        0.0
    } else {
        1.0 / THRESHOLD - 1.0 / m
    }
}

/// The feasibility phase's term for one margin: `max(0, δ − m)²`.
pub fn shortfall(m: f64) -> f64 {
    let d = (THRESHOLD - m).max(0.0);
    d * d
}

/// Its derivative.
pub fn shortfall_slope(m: f64) -> f64 {
    -2.0 * (THRESHOLD - m).max(0.0)
}

/// What `phase` adds to the objective for the margins `m`.
pub fn term(phase: Phase, m: &[f64]) -> f64 {
    match phase {
        Phase::Off => 0.0,
        Phase::Feasibility => m.iter().map(|&x| shortfall(x)).sum(),
        Phase::Barrier(weight) => weight * m.iter().map(|&x| barrier(x)).sum::<f64>(),
    }
}

/// Its derivative by each margin (the cotangent seeded into the margins output).
pub fn slopes(phase: Phase, m: &[f64]) -> Vec<f64> {
    match phase {
        Phase::Off => vec![0.0; m.len()],
        Phase::Feasibility => m.iter().map(|&x| shortfall_slope(x)).collect(),
        Phase::Barrier(weight) => m.iter().map(|&x| weight * barrier_slope(x)).collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_barrier_is_c1_at_the_threshold_and_infinite_at_zero() {
        assert_eq!(barrier(THRESHOLD), 0.0);
        assert_eq!(barrier(1.0), 0.0);
        assert!(barrier(THRESHOLD * (1.0 - 1e-9)).abs() < 1e-15);
        assert!(barrier_slope(THRESHOLD * (1.0 - 1e-9)).abs() < 1e-6);
        assert_eq!(barrier(0.0), f64::INFINITY);
        assert_eq!(barrier(-1.0), f64::INFINITY);
        assert_eq!(barrier(f64::NAN), f64::INFINITY);
        // The slope against central differences inside (0, δ).
        for m in [1e-4, 3e-3, 0.011, 0.019] {
            let h = 1e-9;
            let fd = (barrier(m + h) - barrier(m - h)) / (2.0 * h);
            assert!(
                (fd - barrier_slope(m)).abs() <= 1e-5 * fd.abs().max(1.0),
                "{m}"
            );
            let fd = (shortfall(m + h) - shortfall(m - h)) / (2.0 * h);
            assert!((fd - shortfall_slope(m)).abs() <= 1e-6, "{m}");
        }
        assert_eq!(
            folded_faces(&[
                1.0,
                1.0,
                1.0,
                1.0,
                1.0,
                0.0,
                1.0,
                1.0,
                f64::NAN,
                1.0,
                1.0,
                1.0
            ]),
            2
        );
    }
}
